"""The reliability parameters of a straight line, seeds/004 eqs. (5a)-(6d).

For a line ``r`` with domain ``dom_r`` of ``h`` entries, ``d1`` and ``d2``
are the indices of its first and last True entries (eqs. 5a-5b) and ``n_r``
the number of True entries.  Then

* ``PL = (d2 - d1) / h``, the length (eq. 6a).  The paper prints
  ``l_r = (d2 - d1) tan(alpha_r)`` and ``L_r = h tan(theta_r)`` and states
  that their ratio is ``(d2 - d1) / h``; we implement the ratio it states.
  ``h`` is the length of the domain: the image height for a row domain,
  its width for a column domain ("rows (or columns)").
* ``PR = n / (d2 - d1)``, the robustness (eq. 6b).  A complete domain from
  ``d1`` to ``d2`` holds ``d2 - d1 + 1`` entries, one more than the
  denominator, so ``PR`` is clipped to 1 to stay in the ``[0, 1]`` the paper
  gives it (Tables I-II list ``PR = 1.00``).  A domain with ``d2 == d1``
  (one entry or none) has ``PR = 0``: it is no evidence of a line.
* ``PF = M / max M`` over the candidate set ``R`` (eq. 6c).
* ``Lambda = gPL PL + gPR PR + gPF PF`` with ``gPL + gPR + gPF = 1``
  (eq. 6d); Tables I-II use ``(0.5, 0.35, 0.15)``, our defaults.

Lines are kept when ``PL > 0.5`` and ``PR > 0.65``, the thresholds of
Fig. 8(c)-(f).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

DEFAULT_WEIGHTS = (0.5, 0.35, 0.15)
"""``(gamma_PL, gamma_PR, gamma_PF)`` of Tables I-II."""


def extent(domain: np.ndarray) -> tuple[int, int, int] | None:
    """``(d1, d2, n)`` of a domain, eqs. (5a)-(5b); None when it has no True entry.

    References
    ----------
    seeds/004, eqs. (5a)-(5b).
    """
    domain = _check_domain(domain)
    ones = np.flatnonzero(domain)
    if ones.size == 0:
        return None
    return int(ones[0]), int(ones[-1]), int(ones.size)


def _check_domain(domain: np.ndarray) -> np.ndarray:
    domain = np.asarray(domain)
    if domain.ndim != 1 or domain.dtype != bool or domain.size == 0:
        raise ValueError(f"domain must be a non-empty 1-D bool array, got {domain.dtype} of shape {domain.shape}")
    return domain


def length_and_robustness(domain: np.ndarray) -> tuple[float, float]:
    """``(PL, PR)`` of a domain, eqs. (6a)-(6b).

    Parameters
    ----------
    domain : numpy.ndarray
        1-D ``bool`` domain of ``h`` entries.

    Returns
    -------
    PL, PR : float
        ``(d2 - d1) / h`` and ``min(1, n / (d2 - d1))``; both 0 when
        ``d2 == d1`` or the domain is empty.

    References
    ----------
    seeds/004, eqs. (6a)-(6b).
    """
    found = extent(domain)
    if found is None:
        return 0.0, 0.0
    d1, d2, n = found
    if d2 == d1:
        return 0.0, 0.0
    return (d2 - d1) / domain.size, min(1.0, n / (d2 - d1))


def strength(moduli: Sequence[float] | np.ndarray) -> np.ndarray:
    """``PF`` of each line of a candidate set, eq. (6c): its modulus over the set's largest.

    Returns zeros when every modulus is 0, and an empty array for an empty set.

    References
    ----------
    seeds/004, eq. (6c).
    """
    moduli = np.asarray(moduli, dtype=np.float64).reshape(-1)
    if not np.all(np.isfinite(moduli)) or np.any(moduli < 0):
        raise ValueError(f"moduli must be finite and >= 0, got {moduli}")
    largest = moduli.max(initial=0.0)
    return moduli / largest if largest > 0 else np.zeros_like(moduli)


def check_weights(weights: tuple[float, float, float]) -> None:
    """Raise ValueError unless the three weights are >= 0 and sum to 1 (seeds/004, after eq. 6d)."""
    if len(weights) != 3 or not all(math.isfinite(g) and g >= 0 for g in weights):
        raise ValueError(f"weights must be three finite numbers >= 0, got {weights}")
    if not math.isclose(sum(weights), 1.0, abs_tol=1e-9):
        raise ValueError(f"weights must sum to 1 (gPL + gPR + gPF = 1), got {weights} summing to {sum(weights)}")


def reliability(pl: float, pr: float, pf: float, weights: tuple[float, float, float] = DEFAULT_WEIGHTS) -> float:
    """``Lambda = gPL PL + gPR PR + gPF PF``, eq. (6d).

    Parameters
    ----------
    pl, pr, pf : float
        Length, robustness and strength, each in ``[0, 1]``.
    weights : tuple of float
        ``(gPL, gPR, gPF)``, non-negative and summing to 1.

    Returns
    -------
    float
        ``Lambda`` in ``[0, 1]``.

    References
    ----------
    seeds/004, eq. (6d) and Table I (``0.96, 0.70, 0.51`` gives ``0.80``).
    """
    check_weights(weights)
    for name, value in (("pl", pl), ("pr", pr), ("pf", pf)):
        if not 0.0 <= value <= 1.0:
            raise ValueError(f"{name} must be in [0, 1], got {value}")
    return min(1.0, weights[0] * pl + weights[1] * pr + weights[2] * pf)


def is_reliable(pl: float, pr: float, min_pl: float = 0.5, min_pr: float = 0.65) -> bool:
    """True when a line survives the filtering of Fig. 8(e)-(f): ``PL > min_pl`` and ``PR > min_pr``.

    References
    ----------
    seeds/004, section IV and Fig. 8(c)-(f).
    """
    return pl > min_pl and pr > min_pr
