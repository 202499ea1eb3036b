"""Worker processes run one native thread each, however many the process that started them had."""

from __future__ import annotations

import os

import cv2
import numpy as np
import pytest
import threadpoolctl

from benchmark.executors.local import LocalExecutor
from benchmark.workers import cell_isolation, native_threads


def threads_after_loading_every_plugin() -> dict[str, int]:
    """In a worker: import every plugin (scikit-learn's OpenMP runtime included), then report the pools."""
    from benchmark.plugins import load_registry

    load_registry()
    import sklearn.ensemble  # noqa: F401  (loads its OpenMP runtime if no plugin did)

    return native_threads()


def test_a_worker_runs_one_blas_openmp_opencv_and_numba_thread(monkeypatch: pytest.MonkeyPatch) -> None:
    cv2.setNumThreads(2)
    image = np.random.default_rng(0).random((480, 640)).astype(np.float32)
    cv2.GaussianBlur(image, (31, 31), 5.0)  # this process's OpenCV pool is up before the worker is forked
    for name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):  # the suite's conftest limits them
        monkeypatch.setenv(name, "2")
    with threadpoolctl.threadpool_limits(2):  # the BLAS and OpenMP pools this process has loaded: two threads
        counts = LocalExecutor(1).call(threads_after_loading_every_plugin, (), 120.0)
    assert any("openblas" in name for name in counts)
    assert any("gomp" in name or "omp" in name for name in counts)
    assert {"opencv", "numba"} <= set(counts)
    assert all(count == 1 for count in counts.values()), counts


def test_a_cell_s_folder_and_environment_are_undone_when_it_ends(tmp_path, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("KEPT", "before")
    with pytest.raises(RuntimeError), cell_isolation():
        os.chdir("/")
        os.environ["KEPT"] = "changed"
        os.environ["ADDED"] = "1"
        raise RuntimeError("a tracker's fault")
    assert os.getcwd() == str(tmp_path)
    assert os.environ["KEPT"] == "before" and "ADDED" not in os.environ


def test_what_a_cell_replaces_in_numpy_or_its_error_handling_is_put_back() -> None:
    mean, errors = np.mean, np.geterr()
    with pytest.raises(FloatingPointError), cell_isolation():
        np.mean = lambda *args, **kwargs: 0.0
        np.seterr(all="raise")
        np.float64(1.0) / np.float64(0.0)
    assert np.mean is mean and np.geterr() == errors
