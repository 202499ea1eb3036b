"""A tracker's run in a fresh interpreter: the job a check writes, and the program that carries it out.

Some faults show only in another process: an estimate that follows the
iteration order of a set of strings changes with the interpreter's hash
seed (:mod:`benchmark.testing.hash_seed`).  A check hands such a run to a
fresh interpreter through a private folder:

``job.json``
    Plain JSON: the tracker class as ``module:qualname``, the packages
    whose types the records may hold, the thread count of every native
    pool of the checking process, and the CPU time the run may use.
``input.rec``
    One record (:mod:`benchmark.storage`, never pickle) of a dict: the
    sequence's info, the frames, the parameters, the fitted model (None
    for a tracker that does not learn), ``init`` for ``reset``, the
    generator (its bit generator's kind, seed sequence and state, so the
    child draws exactly the numbers the checking process would) and the
    seed of the global generators.
``result.rec``
    Written by the child: a record of a dict whose ``outcome`` is
    ``"estimates"`` (with ``estimates``), ``"not checked"`` (the run cannot
    happen there: ``detail`` says why) or ``"failed"`` (the tracker raised,
    ``detail`` names where); and ``hash_probe``, the child's hash of
    :data:`HASH_PROBE`, which tells whether its string hashes differ from
    the checking process's.
``log.txt``
    The child's standard output and error.

The program is this file run as a script (:func:`command`), not as a
module of :mod:`benchmark.testing`, whose package imports pytest and
pandas: the child imports only NumPy, :mod:`benchmark.storage` and
:mod:`benchmark.faults` (with :mod:`benchmark`'s package), the tracker's
module and what the records name.  Apart from the environment it is started with, the child is set up
as the checking process is: the same native thread counts (threadpoolctl's
pools, OpenCV's, numba's), the same seed in NumPy's, Python's and OpenCV's
global generators, the same generator handed to ``reset``.
"""

from __future__ import annotations

import dataclasses
import importlib
import json
import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

from benchmark import storage
from benchmark.faults import Call, Fault
from benchmark.shared_modules import seed_global_generators

JOB = "job.json"
INPUT = "input.rec"
RESULT = "result.rec"
LOG = "log.txt"

HASH_PROBE = "trackbench hash probe"
"""A string both processes hash: equal hashes mean equal hash seeds."""

ESTIMATES, NOT_CHECKED, FAILED = "estimates", "not checked", "failed"
"""The outcomes of a run in the child."""


@dataclasses.dataclass(frozen=True)
class Job:
    """What the child needs besides the records: where the tracker is and how to set the process up.

    Attributes
    ----------
    tracker : str
        The tracker class as ``module:qualname``.
    packages : tuple of str
        Top-level packages whose types the records may hold.
    threads : dict
        Thread count of each native pool of the checking process, by
        library file name (threadpoolctl), ``"opencv"`` and ``"numba"``.
    cpu_limit_s : float or None
        CPU time the child may use (``RLIMIT_CPU``, whole seconds rounded up); None for no limit.
    """

    tracker: str
    packages: tuple[str, ...]
    threads: dict[str, int]
    cpu_limit_s: float | None

    def write(self, folder: Path) -> None:
        """Write ``job.json`` into ``folder``."""
        (folder / JOB).write_text(json.dumps(dataclasses.asdict(self)))

    @classmethod
    def read(cls, folder: Path) -> Job:
        """The job of ``folder``."""
        fields = json.loads((folder / JOB).read_text())
        return cls(fields["tracker"], tuple(fields["packages"]), dict(fields["threads"]), fields["cpu_limit_s"])


def command(folder: Path) -> list[str]:
    """The command line that runs the job of ``folder`` in a fresh interpreter.

    ``-P`` keeps this file's own folder off the child's ``sys.path``, where
    ``checks.py`` and its neighbours would shadow top-level modules.
    """
    return [sys.executable, "-P", __file__, str(folder)]


def generator_record(rng: np.random.Generator) -> dict[str, Any]:
    """What rebuilds ``rng`` in another process: its bit generator's kind, seed sequence and state.

    The seed sequence matters to a tracker that spawns child generators
    (``rng.spawn``), the state to one that draws.
    """
    bits = rng.bit_generator
    sequence = bits.seed_seq
    seed_sequence = (
        {
            "entropy": sequence.entropy,
            "spawn_key": tuple(sequence.spawn_key),
            "pool_size": sequence.pool_size,
            "n_children_spawned": sequence.n_children_spawned,
        }
        if isinstance(sequence, np.random.SeedSequence)
        else None
    )
    return {"kind": type(bits).__name__, "seed_sequence": seed_sequence, "state": bits.state}


def rebuild_generator(record: dict[str, Any]) -> np.random.Generator:
    """The generator :func:`generator_record` described.

    Raises
    ------
    ValueError
        If the record names no bit generator of :mod:`numpy.random`.
    """
    kind = getattr(np.random, str(record["kind"]), None)
    if not (isinstance(kind, type) and issubclass(kind, np.random.BitGenerator)):
        raise ValueError(f"{record['kind']!r} is not a bit generator of numpy.random")
    described = record["seed_sequence"]
    seed = None if described is None else np.random.SeedSequence(**described)
    bits = kind(seed)
    bits.state = record["state"]
    return np.random.Generator(bits)


def native_threads() -> dict[str, int]:
    """The thread count of every native pool of this process: threadpoolctl's by library file, OpenCV's, numba's.

    OpenCV's is read where the process has loaded it, numba's where its
    threads run: asking numba would start them, and a process that forks
    workers later must not have.
    """
    import threadpoolctl

    pools = threadpoolctl.ThreadpoolController().lib_controllers
    counts = {Path(pool.filepath).name: pool.num_threads for pool in pools}
    if "cv2" in sys.modules:
        counts["opencv"] = sys.modules["cv2"].getNumThreads()
    parallel = sys.modules.get("numba.np.ufunc.parallel")
    if getattr(parallel, "_is_initialized", False):
        counts["numba"] = sys.modules["numba"].get_num_threads()
    return counts


def use_native_threads(counts: dict[str, int]) -> None:
    """Give this process's native pools the thread counts of :func:`native_threads` in another.

    A pool the other process has and this one has not loaded is left
    alone; one it loads later reads the environment, which it inherited.
    """
    import threadpoolctl

    for pool in threadpoolctl.ThreadpoolController().lib_controllers:
        wanted = counts.get(Path(pool.filepath).name)
        if wanted is not None and pool.num_threads != wanted:
            pool.set_num_threads(wanted)
    if "cv2" in sys.modules and "opencv" in counts and sys.modules["cv2"].getNumThreads() != counts["opencv"]:
        sys.modules["cv2"].setNumThreads(counts["opencv"])
    if "numba" in sys.modules and "numba" in counts and sys.modules["numba"].get_num_threads() != counts["numba"]:
        sys.modules["numba"].set_num_threads(counts["numba"])


def _limit_cpu(seconds: float | None) -> None:
    """Let the process use ``seconds`` of CPU time (rounded up), after which the kernel ends it with ``SIGXCPU``."""
    if seconds is None:
        return
    try:
        import resource
    except ImportError:  # not POSIX: the checking process's wall-time bound remains
        return
    _, hard = resource.getrlimit(resource.RLIMIT_CPU)
    soft = max(1, math.ceil(seconds))
    if hard != resource.RLIM_INFINITY:
        soft = min(soft, hard)
    resource.setrlimit(resource.RLIMIT_CPU, (soft, hard))


def _tracker_class(name: str) -> type | dict[str, Any]:
    """The class ``module:qualname``, imported afresh, or the outcome that says why there is none."""
    module, _, qualname = name.partition(":")
    imported = Call.of(lambda: importlib.import_module(module), f"importing {module!r}")
    if imported.fault is not None and imported.fault.is_a(ImportError):
        reason = f"its module {module!r} cannot be imported in a fresh interpreter: {imported.summary}"
        return _outcome(NOT_CHECKED, reason)
    if not imported.ok:
        return _outcome(FAILED, f"importing its module {module!r} in a fresh interpreter raised {imported.summary}")
    found: Any = imported.value()
    try:
        for part in qualname.split("."):
            found = getattr(found, part)
    except AttributeError:
        return _outcome(NOT_CHECKED, f"a fresh import of {module!r} defines no {qualname!r}")
    return found


def _outcome(outcome: str, detail: str = "", estimates: list[Any] | None = None) -> dict[str, Any]:
    return {"outcome": outcome, "detail": detail, "estimates": estimates, "hash_probe": hash(HASH_PROBE)}


def run(folder: Path, job: Job) -> dict[str, Any]:
    """Carry out ``job``, whose input is in ``folder``: the result to store in ``result.rec``.

    Parameters
    ----------
    folder : Path
        Holding ``input.rec``.
    job : Job
        Read from the folder's ``job.json``.

    Returns
    -------
    dict
        See the module's description of ``result.rec``.
    """
    _limit_cpu(job.cpu_limit_s)
    packages = frozenset(job.packages)
    tracker_class = _tracker_class(job.tracker)
    if isinstance(tracker_class, dict):
        return tracker_class
    threads = Call.of(lambda: use_native_threads(job.threads), "setting the thread counts")
    if not threads.ok:
        reason = f"the fresh interpreter cannot take the checking process's thread counts: {threads.summary}"
        return _outcome(NOT_CHECKED, reason)
    try:
        inputs = storage.loads((folder / INPUT).read_bytes(), packages, "the check's input")
        rng = rebuild_generator(inputs["generator"])
    except (storage.StorageError, ValueError, TypeError, KeyError) as exc:
        reason = f"the fresh interpreter cannot read its frames, parameters or model: {Fault.of(exc).text}"
        return _outcome(NOT_CHECKED, reason)
    seed_global_generators([inputs["global_seed"]])
    frames = inputs["frames"]

    def played() -> list[Any]:
        tracker = Call.of(lambda: tracker_class(inputs["params"]), "creating an instance").value()
        if inputs["model"] is not None:
            Call.of(lambda: tracker.use_model(inputs["model"]), "use_model").value()
        Call.of(lambda: tracker.reset(inputs["info"], rng, init=inputs["init"]), "reset").value()
        return [
            Call.of(lambda: tracker.step(frame), f"step, frame {frame.index}", frame.index).value() for frame in frames
        ]

    ran = Call.of(played, "creating an instance")
    if not ran.ok:
        return _outcome(FAILED, ran.message)
    estimates = ran.value()
    for frame, estimate in zip(frames, estimates):
        try:
            storage.dumps(estimate, packages)
        except storage.StorageError as exc:
            return _outcome(FAILED, f"its estimate at frame {frame.index} cannot be stored: {exc}")
    return _outcome(ESTIMATES, estimates=estimates)


def main(folder: Path) -> None:
    """Run the job of ``folder`` and write ``result.rec``."""
    job = Job.read(folder)
    (folder / RESULT).write_bytes(storage.dumps(run(folder, job), frozenset(job.packages)))


if __name__ == "__main__":
    main(Path(sys.argv[1]))
