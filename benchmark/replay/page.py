"""The replay page: a recording as one self-contained HTML file that works from ``file://``.

Everything the page needs is inside it: the recording as JSON in a
``<script type="application/json">`` element, each frame's JPEG as a
``data:`` URI, the player in plain JavaScript, no CDN.  The player (the
thesis's Cable Tracking GUI, seeds/000, section 4.7) has play, pause,
step back and forward, a speed, a frame slider and the outcome strip
(coloured as the site's :data:`~benchmark.site.figures.OUTCOME_COLOURS`;
a click jumps to the frame).  The frame is drawn on a canvas with the
marks its modality's view (:mod:`benchmark.replay.views`) gives it, each
drawn by one routine in its role's colour: the truth's in green, the
estimate's in red, the frame's measurement in amber, particles in blue and
an estimate's covariance as a dashed red ellipse; beside it the belief
panel: for a particle belief, per state dimension, each particle a
horizontal line whose length is its weight at its value, with truth and
estimate marked (Figs. 4.11 and 4.14); for a Gaussian belief, the mean and
its 2-sigma band per dimension over the frames.  Below: the estimate and
the truth as numbers, and the step time.
"""

from __future__ import annotations

import base64
import json
import math
from pathlib import Path
from typing import Any

import jinja2
import numpy as np
from markupsafe import Markup

from benchmark.files import write_text_atomically
from benchmark.replay.record import Belief, FrameRecord, Recording
from benchmark.results import LOOP_PREFIX
from benchmark.replay.views import Mark, ReplayView, view_of
from benchmark.site.figures import OUTCOME_COLOURS

SIGNIFICANT_DIGITS = 5
"""Significant digits of the numbers in the page's data."""

_templates = jinja2.Environment(
    loader=jinja2.FileSystemLoader(Path(__file__).with_name("templates")),
    autoescape=True,
    undefined=jinja2.StrictUndefined,
)


def _number(value: float) -> float | None:
    """``value`` to :data:`SIGNIFICANT_DIGITS` digits; None (JSON null) when not finite."""
    value = float(value)
    return float(f"{value:.{SIGNIFICANT_DIGITS}g}") if math.isfinite(value) else None


def _numbers(values: Any) -> list[Any]:
    return [_numbers(v) if hasattr(v, "__len__") else _number(v) for v in values]


LEVELS = 65534
"""Levels of a particle coordinate between its dimension's ends, and of a weight up to its frame's heaviest."""

NOT_FINITE = 65535
"""The level of a coordinate that is not finite."""


def dimension_ranges(recording: Recording) -> list[tuple[float, float]]:
    """Per state dimension, the ends of every value the page draws: particles, 2-sigma bands, truths, estimates.

    The belief panel keeps these ends for the whole recording, so that it does not jump from frame to frame.
    """
    columns: list[list[np.ndarray]] = [[] for _ in recording.dimensions]
    for frame in recording.frames:
        for state in (frame.truth, frame.estimate):
            if state is not None:
                for d, value in enumerate(state[: len(columns)]):
                    columns[d].append(np.array([value]))
        belief = frame.belief
        if belief is not None and belief.particles is not None:
            for d in range(min(len(columns), belief.particles.shape[1])):
                columns[d].append(belief.particles[:, d])
        if belief is not None and belief.mean is not None and belief.variance is not None:
            spread = 2.0 * np.sqrt(np.maximum(belief.variance, 0.0))
            for d in range(min(len(columns), belief.mean.size)):
                columns[d].append(np.array([belief.mean[d] - spread[d], belief.mean[d] + spread[d]]))
    ranges = []
    for column in columns:
        values = np.concatenate(column) if column else np.empty(0)
        values = values[np.isfinite(values)]
        low, high = (float(values.min()), float(values.max())) if values.size else (-1.0, 1.0)
        pad = 0.05 * (high - low) or 0.05 * abs(high) or 1.0
        ranges.append((low - pad, high + pad))
    return ranges


def _levels(values: np.ndarray, low: float, high: float) -> np.ndarray:
    """``values`` as ``uint16`` levels from ``low`` (0) to ``high`` (:data:`LEVELS`); :data:`NOT_FINITE` if not finite."""
    with np.errstate(invalid="ignore", over="ignore"):
        scaled = np.clip(np.round((values - low) / (high - low) * LEVELS), 0, LEVELS)
    return np.where(np.isfinite(values), scaled, NOT_FINITE).astype("<u2")


def _packed(levels: np.ndarray) -> str:
    return base64.b64encode(np.ascontiguousarray(levels, dtype="<u2").tobytes()).decode("ascii")


def _belief(belief: Belief | None, ranges: list[tuple[float, float]]) -> dict[str, Any] | None:
    """A belief for the page; particles packed as base64 ``uint16`` levels of each dimension's range, row by row."""
    if belief is None:
        return None
    if belief.particles is not None and belief.weights is not None:
        states = belief.particles[:, : len(ranges)]
        levels = np.stack([_levels(states[:, d], *ranges[d]) for d in range(states.shape[1])], axis=1)
        heaviest = float(belief.weights.max())
        return {
            "kind": "particles",
            "count": int(states.shape[0]),
            "dims": int(states.shape[1]),
            "particles": _packed(levels),
            "weights": _packed(_levels(belief.weights, 0.0, heaviest if heaviest > 0 else 1.0)),
        }
    return {"kind": "gaussian", "mean": _numbers(belief.mean), "variance": _numbers(belief.variance)}


def frame_marks(frame: FrameRecord, view: ReplayView) -> list[tuple[str, Mark]]:
    """The marks of ``frame`` with their roles, in the order the page draws them (later on top).

    The searched region's marks first, then the belief's, the frame's own
    (its measurement), the truth's and last the estimate's; marks with a
    number that is not finite are left out.
    """
    region = [] if frame.region is None else view.region_marks(frame.region, frame.picture)
    belief = [] if frame.belief is None else view.belief_marks(frame.belief, frame.picture)
    roled = [(mark.role or "", mark) for mark in (*region, *belief, *frame.picture.marks)]
    roled += [(mark.role or "truth", mark) for mark in frame.truth_marks]
    roled += [(mark.role or "estimate", mark) for mark in frame.estimate_marks]
    return [(role, mark) for role, mark in roled if mark.finite]


def _frame(frame: FrameRecord, ranges: list[tuple[float, float]], view: ReplayView) -> dict[str, Any]:
    plane = frame.picture.plane
    return {
        "index": frame.index,
        "outcome": frame.outcome,
        "errors": {name: _number(value) for name, value in frame.errors.items()},
        "loop": {name.removeprefix(LOOP_PREFIX): _number(value) for name, value in frame.loop.items()},
        "step_s": _number(frame.step_s),
        "truth": None if frame.truth is None else _numbers(frame.truth),
        "estimate": None if frame.estimate is None else _numbers(frame.estimate),
        "marks": [[role, mark.shape, _numbers(mark.points)] for role, mark in frame_marks(frame, view)],
        "clip": None if plane is None else _numbers(plane.box),
        "belief": _belief(frame.belief, ranges),
        "image": "data:image/jpeg;base64," + base64.b64encode(frame.picture.jpeg).decode("ascii"),
        "width": frame.picture.width,
        "height": frame.picture.height,
    }


def page_data(recording: Recording, view: ReplayView | None = None) -> dict[str, Any]:
    """The recording as the JSON the page's player reads; ``view`` by default its modality's."""
    view = view or view_of(recording.modality)
    ranges = dimension_ranges(recording)
    return {
        "tracker": recording.tracker,
        "dataset": recording.dataset,
        "modality": recording.modality,
        "seed": recording.seed,
        "dimensions": list(recording.dimensions),
        "ended": recording.ended,
        "ranges": ranges,
        "levels": LEVELS,
        "colours": OUTCOME_COLOURS,
        "frames": [_frame(frame, ranges, view) for frame in recording.frames],
    }


def _script_json(data: Any) -> str:
    """JSON that cannot end the ``<script>`` element holding it."""
    text = json.dumps(data, separators=(",", ":"), allow_nan=False)
    return text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


def replay_html(
    recording: Recording, view: ReplayView | None = None, back: tuple[str, str] | None = None, start: int | None = None
) -> str:
    """The page of ``recording`` as one HTML document.

    ``view`` draws its frames, by default its modality's; ``back``, an
    address and its label, is linked above it; the page opens at frame
    ``start`` (by default its first) unless its address names one (``#frame=N``).
    """
    title = f"{recording.tracker} on {recording.dataset}, seed {recording.seed}"
    data = Markup(_script_json({**page_data(recording, view), "start": start}))
    return _templates.get_template("replay.html").render(title=title, data=data, colours=OUTCOME_COLOURS, back=back)


def write_replay(
    recording: Recording, path: Path, view: ReplayView | None = None, back: tuple[str, str] | None = None
) -> Path:
    """Write the page of ``recording`` to ``path`` (atomically) and return it; ``view`` and ``back`` as :func:`replay_html`'s."""
    return write_text_atomically(path, replay_html(recording, view, back), "replay page")
