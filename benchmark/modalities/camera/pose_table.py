"""Tables III and IV of seeds/004: a pose tracker's measurement, state, error and covariance, frame by frame.

Foresti's Table III follows the EKF over its first twelve frames (it
converges: the errors and the covariance fall); Table IV over frames where
the pipe is buried (no measurement: the covariance grows frame by frame).
:func:`pose_table` runs a camera tracker that reports a pose
(:class:`~benchmark.modalities.camera.model.PosedCableState`) over a
sequence and lays out the same columns for a span of frames: whether a
measurement was taken and its abscissae ``i_1 .. i_4`` (when the tracker
exposes them, :class:`MeasuresBorders`), the estimated ``C_x``, ``C_y``,
``theta``, ``phi``, their errors against the true pose, and the diagonal of
the covariance.  The errors are estimate minus truth, like the board's
(the paper's columns ``X*(k) - x(k)`` print the opposite sign).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

import numpy as np
import pandas as pd

from benchmark.modalities.camera.model import PosedCableState
from benchmark.model import Sequence
from benchmark.selection import SelectionError

if TYPE_CHECKING:
    from benchmark.progress import Report

CAMERA = "camera"
"""The modality whose sequences carry the camera pose."""

COLUMNS = (
    "frame",
    "measured",
    "i1_px",
    "i2_px",
    "i3_px",
    "i4_px",
    "cx_m",
    "cy_m",
    "theta_deg",
    "phi_deg",
    "err_cx_m",
    "err_cy_m",
    "err_theta_deg",
    "err_phi_deg",
    "var_cx_m2",
    "var_cy_m2",
    "var_theta_rad2",
    "var_phi_rad2",
)
"""Columns of :func:`pose_table`, in the order of seeds/004's Tables III-IV."""


@runtime_checkable
class MeasuresBorders(Protocol):
    """A tracker that tells which border abscissae ``(i_1, i_2, i_3, i_4)`` its last step measured."""

    measurement: np.ndarray | None
    """The last frame's measurement, or None when it had none."""


def pose_table(
    tracker: Any,
    sequence: Sequence,
    first: int = 0,
    frames: int = 12,
    init: bool = False,
    report: Report | None = None,
) -> pd.DataFrame:
    """Run a pose-reporting camera tracker over a sequence and tabulate frames ``first .. first + frames - 1``.

    Parameters
    ----------
    tracker : Tracker
        A fresh camera tracker whose estimates are :class:`PosedCableState`.
    sequence : Sequence
        A camera sequence whose truth carries the camera pose.
    first, frames : int
        The span of frames tabulated; the tracker runs from frame 0.
    init : bool
        Hand the tracker the first frame's truth (``--init truth``) or not.
    report : callable, optional
        Told ``report(done, total)`` frames as the tracker steps through
        them (:class:`benchmark.progress.Meter`).

    Returns
    -------
    pandas.DataFrame
        Columns :data:`COLUMNS`; ``measured`` is ``"Y"`` or ``"N"`` (empty
        when the tracker does not say), abscissae empty without a
        measurement, errors empty where the truth has no pose, everything
        but the frame empty where the tracker reported no pose.

    Raises
    ------
    ValueError
        If the span is empty or lies beyond the sequence, naming it.
    SelectionError
        If the sequence is not a camera sequence, or the tracker reported no
        pose on any frame of the span.

    References
    ----------
    seeds/004, section VI-A, Tables III and IV.
    """
    name = getattr(tracker, "name", type(tracker).__name__)
    if sequence.info.modality != CAMERA:
        raise SelectionError(f"sequence {sequence.info.name!r} is a {sequence.info.modality} sequence, not camera")
    if first < 0 or frames < 1:
        raise ValueError(f"frames {first}..{first + frames - 1} of {sequence.info.name!r}: not a span of frames")
    iterator = iter(sequence.frames())
    start = next(iterator, None)
    if start is None:
        raise ValueError(f"sequence {sequence.info.name!r} has no frames")
    tracker.reset(sequence.info, np.random.default_rng(0), init=start.truth if init else None)
    rows: list[dict[str, Any]] = []
    for frame in (start, *iterator):
        if frame.index >= first + frames:
            break
        estimate = tracker.step(frame)
        if report is not None:
            report(frame.index + 1, first + frames)
        if frame.index >= first:
            rows.append(_row(frame.index, tracker, estimate, frame.truth))
    if not rows:
        raise ValueError(f"sequence {sequence.info.name!r} has no frames from {first} on")
    table = pd.DataFrame(rows, columns=list(COLUMNS))
    if table["cx_m"].isna().all():
        raise SelectionError(f"tracker {name!r} reported no camera pose on {sequence.info.name!r}")
    return table


def _row(index: int, tracker: Any, estimate: object, truth: Any) -> dict[str, Any]:
    row: dict[str, Any] = {"frame": index}
    if isinstance(tracker, MeasuresBorders):
        measured = tracker.measurement
        row["measured"] = "N" if measured is None else "Y"
        if measured is not None:
            row.update(zip(COLUMNS[2:6], (float(v) for v in measured)))
    pose = estimate.pose if isinstance(estimate, PosedCableState) else None
    if pose is None:
        return row
    row.update(cx_m=pose.cx, cy_m=pose.cy, theta_deg=math.degrees(pose.theta), phi_deg=math.degrees(pose.phi))
    true_pose = getattr(truth, "pose", None)
    if true_pose is not None:
        row.update(
            err_cx_m=pose.cx - true_pose.cx,
            err_cy_m=pose.cy - true_pose.cy,
            err_theta_deg=math.degrees(pose.theta - true_pose.theta),
            err_phi_deg=math.degrees(pose.phi - true_pose.phi),
        )
    if estimate.pose_variance is not None:  # type: ignore[union-attr]
        row.update(zip(COLUMNS[-4:], estimate.pose_variance))  # type: ignore[union-attr]
    return row


__all__ = ["COLUMNS", "MeasuresBorders", "pose_table"]
