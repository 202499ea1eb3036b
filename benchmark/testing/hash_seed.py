"""The hash-seed check: a tracker's estimates do not depend on the interpreter's hash seed.

Python salts the hash of every string with a seed drawn when the
interpreter starts (``PYTHONHASHSEED``), so a set of strings, and whatever
is built by iterating one, comes out in another order in another process.
A tracker that lets that order decide something (the first of
``{"left", "right", "centre"}`` chooses an offset, a tie goes to whichever
candidate comes first) gives other estimates in every worker process of a
run, and no check that runs twice in one process can see it.

:func:`check_hash_seed` runs the tracker over the subject's frames here and
in a fresh interpreter whose ``PYTHONHASHSEED`` differs from this
process's (:mod:`benchmark.testing.fresh_run`), with the same frames,
parameters, model, generator and global random state, and compares the
estimates.  Both runs read the frames as records (:mod:`benchmark.storage`)
hand them over, so they see the same arrays.

A tracker that cannot run in another interpreter (its class is defined
inside a function, a fresh interpreter cannot import its module, a value
that records cannot hold) is not checked: the check is skipped with the
reason (:class:`~benchmark.testing.checks.NotApplicable`).  One that raises
there and not here fails.

The child is bounded by the check's own limits: it may use the CPU time the
check has left (``RLIMIT_CPU``), and it is killed when the check's wall-time
bound runs out (:data:`~benchmark.testing.time_limit.WAIT_FACTOR` times its
limit) or, where no timer runs, after ``WAIT_FACTOR`` times the kit's
default limit.

One other seed is one draw: an estimate that follows the first of ``k``
strings of a set agrees between two seeds by chance about once in ``k``
checks; one that follows the order of the whole set almost never.
"""

from __future__ import annotations

import dataclasses
import enum
import importlib
import os
import shutil
import signal
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING, Any

from benchmark import storage
from benchmark.testing.fresh_run import (
    FAILED,
    HASH_PROBE,
    INPUT,
    LOG,
    NOT_CHECKED,
    RESULT,
    Job,
    command,
    generator_record,
    native_threads,
)
from benchmark.shared_modules import seed_global_generators
from benchmark.testing.time_limit import WAIT_FACTOR, can_limit

if TYPE_CHECKING:
    from benchmark.testing.checks import Subject

kit = importlib.import_module("benchmark.testing.checks")
"""The kit's checks module, its names read when the check runs: it may register this check, so be half-imported now."""

OTHER_HASH_SEEDS = (1, 2)
"""The child's ``PYTHONHASHSEED``: the first that is not this process's."""

LOG_TAIL = 400
"""Characters of the child's output quoted when it ends without a result."""


class CannotRunElsewhere(Exception):
    """The tracker cannot run in a fresh interpreter, for the reason given; not a fault of its hashing."""


def check_hash_seed(subject: Subject) -> str:
    """The estimates here and in a fresh interpreter with another ``PYTHONHASHSEED`` are identical.

    Both runs start from the first frame's truth with the generator of seed
    :data:`~benchmark.testing.checks.SEED`, as :meth:`Subject.run` does.

    Parameters
    ----------
    subject : Subject
        The prepared tracker; its class must be importable as ``module:qualname``.

    Returns
    -------
    str
        The number of identical estimates and the two hash seeds.

    Raises
    ------
    AssertionError
        Naming the first frame where the estimates differ and the two hash
        seeds; or what the tracker raised in the fresh interpreter; or how
        that interpreter ended without a result.
    NotApplicable
        With the reason the run cannot happen in another interpreter.
    """
    _, frames = subject.ready()
    here = hash_seed_here()
    there = next(seed for seed in OTHER_HASH_SEEDS if str(seed) != here)
    try:
        location = importable_name(subject.entry.tracker_class)
        first = frames.frame_list[0]
        fields = (getattr(first, field.name) for field in dataclasses.fields(first))
        held = (subject.entry.params, subject.model, frames.info, frames.info.calibration, *fields)
        packages = _packages_of(subject, *held)
        stored = _stored(frames.frame_list, packages, "its frames")
        job_input = {
            "info": frames.info,
            "frames": stored,
            "params": subject.entry.params,
            "model": subject.model,
            "init": stored[0].truth,
            "generator": generator_record(subject.rng()),
            "global_seed": kit.SEED,
        }
        data = _dumps(job_input, packages, "its parameters or model")
        # As the fresh interpreter does: a tracker drawing from a global generator (which no_global_randomness
        # fails) must not pass for one whose output follows the hash seed.
        seed_global_generators([kit.SEED])
        estimates = subject.run(subject.create(), list(stored))
        packages = _packages_of(subject, *estimates) | packages
        estimates = _stored(estimates, packages, "its estimates")
    except CannotRunElsewhere as exc:
        raise subject.skip(f"not checked: {exc}") from None
    job = Job(location, tuple(sorted(packages)), native_threads(), _cpu_left_s())
    result = _run_elsewhere(subject, job, data, there)
    if result["outcome"] == NOT_CHECKED:
        raise subject.skip(f"not checked: {result['detail']}")
    if result["outcome"] == FAILED:
        raise subject.fail(f"in a fresh interpreter (PYTHONHASHSEED={there}), though not here: {result['detail']}")
    if result["hash_probe"] == hash(HASH_PROBE):
        raise subject.skip(f"not checked: a fresh interpreter with PYTHONHASHSEED={there} hashes strings as this one does")
    difference = kit.first_difference(frames, estimates, result["estimates"])
    if difference:
        raise subject.fail(
            f"its estimates depend on the hash seed: here (PYTHONHASHSEED={here}) and in a fresh interpreter "
            f"(PYTHONHASHSEED={there}) they differ {difference}; does an iteration over a set of strings, or "
            "hash(), decide something?"
        )
    seeds = f"here (PYTHONHASHSEED={here}) and in a fresh interpreter (PYTHONHASHSEED={there})"
    return f"{len(estimates)} identical estimates {seeds}"


def hash_seed_here() -> str:
    """This process's ``PYTHONHASHSEED`` as it was started: a number, or ``"random"``."""
    if not sys.flags.hash_randomization:
        return "0"
    value = os.environ.get("PYTHONHASHSEED", "")
    return value if value.isdigit() else "random"


def importable_name(cls: type) -> str:
    """``module:qualname`` of ``cls``, by which a fresh interpreter finds it.

    Raises
    ------
    CannotRunElsewhere
        If the class lives inside a function or in ``__main__``, or the name does not lead back to it here.
    """
    name = f"{cls.__module__}:{cls.__qualname__}"
    if "<locals>" in cls.__qualname__:
        raise CannotRunElsewhere(
            f"its class {cls.__qualname__} is defined inside a function, which another interpreter cannot import"
        )
    if cls.__module__ == "__main__":
        raise CannotRunElsewhere(
            f"its class {cls.__qualname__} is defined in __main__, which another interpreter does not run"
        )
    found: Any = sys.modules.get(cls.__module__)
    for part in cls.__qualname__.split("."):
        found = getattr(found, part, None)
    if found is not cls:
        raise CannotRunElsewhere(f"{name} does not name its class")
    top = cls.__module__.partition(".")[0]
    if not _findable(top):
        raise CannotRunElsewhere(
            f"its module {cls.__module__!r} cannot be imported in a fresh interpreter: no finder finds {top!r}"
        )
    return name


def _findable(top: str) -> bool:
    """Whether the import system finds module ``top`` afresh, as an interpreter with this ``sys.path`` would.

    It asks the finders of ``sys.meta_path`` (the path, and an editable
    install's own) and not ``sys.modules``: a module a test loaded from a
    file, or under a name only this process gave it, is not found.
    """
    for finder in sys.meta_path:
        try:
            if getattr(finder, "find_spec", None) and finder.find_spec(top, None) is not None:
                return True
        except Exception:  # a finder that cannot answer is no finder for it
            continue
    return False


def _packages_of(subject: Subject, *values: Any) -> storage.Packages:
    """The packages records of ``values`` (and of the tracker's own types) may name."""
    kinds = {type(value) for value in values if dataclasses.is_dataclass(value) or isinstance(value, enum.Enum)}
    return storage.packages_of(subject.entry.tracker_class, *kinds)


def _dumps(value: Any, packages: storage.Packages, what: str) -> bytes:
    try:
        return storage.dumps(value, packages)
    except storage.StorageError as exc:
        raise CannotRunElsewhere(f"{what} cannot be stored for another interpreter: {exc}") from None


def _stored(value: Any, packages: storage.Packages, what: str) -> Any:
    """``value`` as another interpreter reads it: written as a record and read back."""
    return storage.loads(_dumps(value, packages, what), packages, what)


def _cpu_left_s() -> float | None:
    """CPU time left of the check's limit (:func:`~benchmark.testing.time_limit.time_limit`); None if no limit runs."""
    left = signal.getitimer(signal.ITIMER_PROF)[0] if can_limit() else 0.0
    return left or None


def _wall_left_s() -> float:
    """Wall time the child may take: what is left of the check's wall-time bound, or its bound for the default limit."""
    left = signal.getitimer(signal.ITIMER_REAL)[0] if can_limit() else 0.0
    if left:
        return left
    from benchmark.testing import DEFAULT_TIME_LIMIT_S  # not at the top: the package may import this module

    return DEFAULT_TIME_LIMIT_S * WAIT_FACTOR


def _run_elsewhere(subject: Subject, job: Job, data: bytes, hash_seed: int) -> dict[str, Any]:
    """Carry out ``job`` with input ``data`` in a fresh interpreter with ``PYTHONHASHSEED=hash_seed``: its result.

    The child finds modules where this process does (its ``sys.path`` as
    ``PYTHONPATH``) and starts a session of its own, so that killing it
    takes the processes it started too.

    Raises
    ------
    AssertionError
        If the child is still running when the check's time is up, or ends without a result.
    """
    folder = Path(tempfile.mkdtemp(prefix="trackbench-hash-seed-"))
    try:
        (folder / INPUT).write_bytes(data)
        job.write(folder)
        environment = {
            **os.environ,
            "PYTHONHASHSEED": str(hash_seed),
            "PYTHONPATH": os.pathsep.join(os.path.abspath(str(entry)) for entry in sys.path),
        }
        try:
            with open(folder / LOG, "wb") as log:
                process = subprocess.Popen(
                    command(folder),
                    env=environment,
                    stdin=subprocess.DEVNULL,
                    stdout=log,
                    stderr=subprocess.STDOUT,
                    start_new_session=True,
                )
        except OSError as exc:
            return {"outcome": NOT_CHECKED, "detail": f"no fresh interpreter could be started: {exc}"}
        waited = _wall_left_s()
        try:
            status = process.wait(timeout=waited)
        except subprocess.TimeoutExpired:
            _kill(process)
            raise subject.fail(
                f"a fresh interpreter running it was still busy after {waited:g} s of waiting and was killed: "
                "does it hang?"
            ) from None
        except BaseException:  # the check's own time, or the user's Ctrl-C
            _kill(process)
            raise
        try:
            result: dict[str, Any] = storage.loads((folder / RESULT).read_bytes(), frozenset(job.packages), RESULT)
        except (OSError, storage.StorageError):
            raise subject.fail(_ended_without_result(status, job, folder / LOG)) from None
        return result
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def _kill(process: subprocess.Popen[bytes]) -> None:
    """Kill the child and its session's processes, and reap it."""
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except (AttributeError, ProcessLookupError, PermissionError):  # no process groups here, or all gone
        process.kill()
    process.wait()


def _ended_without_result(status: int, job: Job, log: Path) -> str:
    """How the child ended, with the end of what it wrote."""
    if status < 0 and -status == getattr(signal, "SIGXCPU", None):
        left = f"the {job.cpu_limit_s:g} s of CPU time the check had left"
        return f"a fresh interpreter running it used up {left}: does it hang?"
    how = f"was killed by signal {_signal_name(-status)}" if status < 0 else f"ended with exit status {status}"
    tail = log.read_text(errors="replace")[-LOG_TAIL:].strip()
    return f"a fresh interpreter running it {how} without a result" + (f"; its output ends: {tail}" if tail else "")


def _signal_name(number: int) -> str:
    try:
        return signal.Signals(number).name
    except ValueError:
        return str(number)
