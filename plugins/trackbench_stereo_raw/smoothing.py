"""Velocity from raw positions, smoothed by a moving average.

seeds/002 computes the raw speed "as the magnitude of changes in the N-E
position between consecutive time steps, using the raw stereovision
measurements (after being smoothed with a moving average filter)"
(section 3.3), the raw heading likewise (section 3.4), with a 15-element
moving average (section 4, Figs. 14-15).

:class:`VelocitySmoother` keeps the last ``window`` finite differences
``(p_i - p_(i-1)) / (t_i - t_(i-1))`` of consecutive measured positions and
reports their mean.  Without gaps this is exactly the change between
consecutive steps of the ``window``-sample moving average of the positions:
the mean of the last ``n`` differences telescopes to
``(p_k - p_(k-n)) / (n T)``, and so does the difference of two consecutive
moving averages divided by ``T``.  Dividing each difference by the actual
time between its two measurements keeps the estimate right across frames
where the target was lost.  Until ``window`` differences exist the mean is
over those available.
"""

from __future__ import annotations

from collections import deque

import numpy as np


class VelocitySmoother:
    """Moving average of the velocities between consecutive measured positions.

    Parameters
    ----------
    window : int
        Number of differences averaged (seeds/002, section 4: 15).

    References
    ----------
    seeds/002, sections 3.3-3.4 and 4 (Figs. 14-15).
    """

    def __init__(self, window: int) -> None:
        if window < 1:
            raise ValueError(f"window must be at least 1, not {window}")
        self._differences: deque[np.ndarray] = deque(maxlen=window)
        self._last: tuple[float, np.ndarray] | None = None

    def add(self, time_s: float, position_m: np.ndarray) -> np.ndarray | None:
        """Add a measured position and return the smoothed velocity, None before the second one.

        Parameters
        ----------
        time_s : float
            Time of the measurement; must increase from call to call.
        position_m : array_like
            North-East position ``[X, Y]``, m.

        Returns
        -------
        numpy.ndarray or None
            ``[X_dot, Y_dot]``, m/s: the mean of the last ``window``
            differences.
        """
        position = np.asarray(position_m, dtype=float)
        if self._last is not None:
            last_time, last_position = self._last
            if not time_s > last_time:
                raise ValueError(f"measurement at {time_s} s does not follow the one at {last_time} s")
            self._differences.append((position - last_position) / (time_s - last_time))
        self._last = (time_s, position)
        if not self._differences:
            return None
        return np.mean(self._differences, axis=0)
