"""``trackbench check``: the conformance kit from the command line, on the fake registry."""

from __future__ import annotations

from collections.abc import Callable

from click.testing import Result


def test_check_prints_a_row_per_tracker_and_check_and_fails_on_a_failure(invoke: Callable[..., Result]) -> None:
    result = invoke("check", "perfect", "blind")
    assert result.exit_code == 1, result.output
    lines = result.output.splitlines()
    assert lines[0].split() == ["tracker", "check", "result", "message"]
    rows = [line.split()[:3] for line in lines[1:-1]]
    assert len(rows) == 28
    assert rows[:2] == [["perfect", "frames_without_truth", "FAIL"], ["perfect", "starts_without_truth", "FAIL"]]
    assert ["blind", "frames_without_truth", "ok"] in rows
    assert ["blind", "belief_invariants", "skip"] in rows
    assert ["blind", "hash_seed", "skip"] in rows  # the test's own fakes cannot be imported afresh
    assert "22 passed, 2 failed, 4 skipped (2 trackers)" in lines[-1]


def test_check_passes_with_exit_status_0(invoke: Callable[..., Result]) -> None:
    result = invoke("check", "blind", "--frames", "4")
    assert result.exit_code == 0, result.output
    assert "12 passed, 0 failed, 2 skipped (1 trackers)" in result.output


def test_a_hanging_tracker_fails_runs_at_the_time_limit_and_the_checks_after_it_unrun(invoke: Callable[..., Result]) -> None:
    result = invoke("check", "sleepy", "--frames", "3", "--time-limit", "0.2")
    assert result.exit_code == 1, result.output
    rows = {line.split()[1]: line for line in result.output.splitlines()[1:-1]}
    assert " ok " in rows["metadata"]
    assert "FAIL" in rows["runs"] and "did not finish within 2 s of waiting (0.2 s of CPU time allowed) (step, frame 1)" in rows["runs"]
    assert "does it hang?" in rows["runs"]
    after_runs = [check for check, line in rows.items() if "follows from 'runs': not run: 'runs' ran out of time" in line]
    assert len(after_runs) == 12 and all("FAIL" in rows[check] for check in after_runs)  # not waited out again


def test_check_of_an_unknown_tracker_is_a_usage_error(invoke: Callable[..., Result]) -> None:
    result = invoke("check", "nope")
    assert result.exit_code == 2
    assert "unknown tracker 'nope'" in result.output


def test_in_process_gives_the_same_rows_as_the_workers(invoke: Callable[..., Result]) -> None:
    isolated = invoke("check", "perfect", "--frames", "4")
    here = invoke("check", "perfect", "--frames", "4", "--in-process")
    assert isolated.exit_code == here.exit_code == 1

    def verdicts(output: str) -> list[list[str]]:
        return [line.split()[:3] for line in output.splitlines()]

    assert verdicts(isolated.output) == verdicts(here.output)
    assert "10 passed, 2 failed, 2 skipped (1 trackers)" in here.output


def test_the_command_s_defaults_are_the_kit_s(invoke: Callable[..., Result]) -> None:
    """The command line does not import the kit (and pytest with it) to show its help, so it repeats its defaults."""
    from benchmark.cli import main
    from benchmark.testing import DEFAULT_TIME_LIMIT_S, RANDOM_FRAMES
    from benchmark.testing.checks import DEFAULT_FRAMES

    assert f"[default: {RANDOM_FRAMES}" in invoke("check", "--help").output
    defaults = {option.name: option.default for option in main.commands["check"].params}
    assert (defaults["frames"], defaults["random_frames"], defaults["time_limit_s"]) == (
        DEFAULT_FRAMES,
        RANDOM_FRAMES,
        DEFAULT_TIME_LIMIT_S,
    )
