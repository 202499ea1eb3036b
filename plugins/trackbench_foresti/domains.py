"""Restoration of a line's domain (seeds/004, section IV).

"After having extracted all straight lines from the input image, it is
possible to reinforce the desired line instances by means of 'restorations'
of the domains as filling up of small holes, removal of some isolated
points or segments, and so on."

Our reading, in this order:

1. every hole (a run of False entries with True entries on both sides) of
   at most ``max_gap`` entries is filled, since a short break of a border
   is more likely a Canny or sampling gap than a real end of the line;
2. every run of True entries shorter than ``min_run`` left after filling is
   removed: an isolated point or short segment is more likely an accidental
   alignment than a piece of the line.

Filling first lets a dashed but dense border survive the removal, which
the paper's purpose ("reinforce the desired line instances") suggests.
"""

from __future__ import annotations

import numba
import numpy as np


def runs(domain: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Start and stop indices (stop exclusive) of the runs of True in a 1-D boolean array."""
    padded = np.concatenate(([False], np.asarray(domain, dtype=bool), [False]))
    change = np.flatnonzero(padded[1:] != padded[:-1])
    return change[0::2], change[1::2]


def restore_domain(domain: np.ndarray, max_gap: int, min_run: int) -> np.ndarray:
    """Fill small holes of a domain, then remove its short isolated runs.

    Parameters
    ----------
    domain : numpy.ndarray
        1-D ``bool`` array ``dom[i]``; it is not modified.
    max_gap : int
        Holes of up to this many entries between two True entries are
        filled (0 fills nothing).
    min_run : int
        Runs of True shorter than this, after filling, are cleared (0 or 1
        clears nothing).

    Returns
    -------
    numpy.ndarray
        The restored ``bool`` domain, same length.

    References
    ----------
    seeds/004, section IV ("filling up of small holes, removal of some
    isolated points or segments").
    """
    domain = np.asarray(domain)
    if domain.ndim != 1 or domain.dtype != bool:
        raise ValueError(f"domain must be a 1-D bool array, got {domain.dtype} of shape {domain.shape}")
    if max_gap < 0 or min_run < 0:
        raise ValueError(f"max_gap and min_run must be >= 0, got max_gap={max_gap}, min_run={min_run}")
    return _restore(domain, int(max_gap), int(min_run))


@numba.njit(cache=True, nogil=True)
def _restore(domain: np.ndarray, max_gap: int, min_run: int) -> np.ndarray:
    """:func:`restore_domain` in one pass: runs grow across holes of at most ``max_gap`` and are kept when long."""
    restored = np.zeros(domain.size, np.bool_)
    start = last = -1  # the first and last True entries of the run being grown; -1 before the first
    for i in range(domain.size):
        if not domain[i]:
            continue
        if start < 0 or i - last - 1 > max_gap:
            if start >= 0 and last + 1 - start >= min_run:
                restored[start : last + 1] = True
            start = i
        last = i
    if start >= 0 and last + 1 - start >= min_run:
        restored[start : last + 1] = True
    return restored


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the restoration kernel now."""
    _restore(np.zeros(1, np.bool_), 1, 1)
