"""``trackbench check``: the conformance kit of :mod:`benchmark.testing` on installed trackers."""

from __future__ import annotations

import click

from benchmark.cli.options import Seconds
from benchmark.cli.session import EXIT_FAILED, Session


@click.command("check")
@click.argument("names", nargs=-1, metavar="[NAME]...")
@click.option(
    "--frames", type=click.IntRange(min=1), default=60, show_default=True, help="Frames each run of a check reads."
)
@click.option(
    "--random-frames",
    type=click.IntRange(min=1),
    default=5,
    show_default=True,
    help="Frames of each random sequence the random_sequences check draws.",
)
@click.option(
    "--time-limit",
    "time_limit_s",
    type=Seconds(),
    default=60.0,
    show_default=True,
    help="Seconds of CPU time one check may use (and ten times as long of waiting) before it fails as a hang.",
)
@click.option(
    "--in-process",
    is_flag=True,
    help="Run the checks in this process (for a debugger); a tracker that ends the process ends the command.",
)
@click.pass_context
def check_command(
    ctx: click.Context,
    names: tuple[str, ...],
    frames: int,
    random_frames: int,
    time_limit_s: float,
    in_process: bool,
) -> None:
    """Run the conformance kit (benchmark.testing) on installed trackers: all of them, or those NAMEd.

    Each check runs in a worker process, so a tracker that crashes or hangs
    fails that check only. Prints one row per tracker and check, a tracker's
    failures first and those that follow from an earlier one marked so;
    `skip` for a check about a capability the tracker declares it lacks,
    `xfail` for one it lists in expected_failed_checks. Exit status 1 if any
    check failed (or passed while listed as expected to fail).
    """
    from benchmark.selection import select_trackers
    from benchmark.testing import check_tracker, checks
    from benchmark.testing.isolated import check_in_workers

    session: Session = ctx.obj
    registry = session.registry
    entries = select_trackers(registry, names)
    if in_process:
        results = (
            result
            for entry in entries
            for result in check_tracker(
                entry, registry=registry, n_frames=frames, random_frames=random_frames, time_limit_s=time_limit_s
            )
        )
    else:
        results = check_in_workers([entry.name for entry in entries], registry, frames, time_limit_s, random_frames)
    header = ("tracker", "check", "result")
    widths = [
        max(len(header[0]), *(len(entry.name) for entry in entries)),
        max(len(header[1]), *(len(check.name) for check in checks())),
        len("xpass "),
    ]

    def row(*cells: str) -> str:
        return "  ".join(cell.ljust(width) for cell, width in zip(cells, widths)) + "  " + cells[-1]

    click.echo(row(*header, "message"))
    counts = dict.fromkeys(CHECK_VERDICTS, 0)
    for result in results:
        counts[result.outcome] += 1
        verdict = CHECK_VERDICTS[result.outcome]
        click.echo(row(result.tracker, result.check, verdict, result.message or result.detail))
    summary = ", ".join(f"{count} {outcome}" for outcome, count in counts.items() if count or outcome == "failed")
    click.echo(f"{summary} ({len(entries)} trackers)")
    if counts["failed"] or counts["xpassed"]:
        ctx.exit(EXIT_FAILED)


CHECK_VERDICTS = {"passed": "ok", "failed": "FAIL", "skipped": "skip", "xfailed": "xfail", "xpassed": "XPASS"}
"""How ``trackbench check`` shows each outcome of a check."""
