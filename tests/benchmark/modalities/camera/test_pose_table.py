"""Tables III-IV of seeds/004 for any pose-reporting camera tracker."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pytest
from click.testing import CliRunner

from benchmark.cli import main
from benchmark.modalities.camera.model import CableState, CameraPose, CameraTruth, PosedCableState
from benchmark.modalities.camera.pose_table import COLUMNS, MeasuresBorders, pose_table
from benchmark.model import Frame, Sequence, SequenceInfo
from benchmark.report.markdown import titled_table

CABLE = CableState(1.0, 0.0, 30.0, 0.01)


@dataclass
class Poses(Sequence):
    """Frames whose true camera drifts 0.1 m right a frame."""

    count: int = 6

    @property
    def info(self) -> SequenceInfo:
        return SequenceInfo("poses", "camera", self.count, frame_size=(64, 48))

    def frames(self):
        for k in range(self.count):
            pose = CameraPose(0.1 * k, 2.0, 0.0, 0.0, math.radians(45.0), 0.0)
            yield Frame(k, np.zeros((48, 64), np.uint8), CameraTruth(CABLE, pose=pose))


class Lagging:
    """Reports the pose one frame late, measures on even frames; a variance that halves."""

    def __init__(self) -> None:
        self.measurement = None
        self.previous = None
        self.started_from_truth = None

    def reset(self, info, rng, init=None):
        self.started_from_truth = init is not None
        self.previous = CameraPose(0.0, 2.0, 0.0, 0.0, math.radians(45.0), 0.0)

    def step(self, frame):
        self.measurement = np.array([1.0, 2.0, 3.0, 4.0]) + frame.index if frame.index % 2 == 0 else None
        pose, self.previous = self.previous, frame.truth.pose
        variance = tuple(v / 2**frame.index for v in (1.0, 1.0, 0.3, 0.3))
        return PosedCableState(*CABLE.as_array(), pose=pose, pose_variance=variance)


def test_the_table_holds_measurement_state_error_and_variance_for_the_span():
    tracker = Lagging()
    assert isinstance(tracker, MeasuresBorders)
    table = pose_table(tracker, Poses(), first=2, frames=3)
    assert list(table.columns) == list(COLUMNS) and table["frame"].tolist() == [2, 3, 4]
    assert table["measured"].tolist() == ["Y", "N", "Y"] and not tracker.started_from_truth
    assert table.loc[0, ["i1_px", "i4_px"]].tolist() == [3.0, 6.0] and math.isnan(table.loc[1, "i1_px"])
    np.testing.assert_allclose(table["err_cx_m"], [-0.1, -0.1, -0.1])
    np.testing.assert_allclose(table["var_cx_m2"], [0.25, 0.125, 0.0625])
    assert table.loc[0, "phi_deg"] == pytest.approx(45.0)
    text = titled_table(table, "lagging on poses")
    assert text.startswith("# lagging on poses") and "2.50e-01" in text and "-0.10" in text



def test_progress_is_reported_frame_by_frame_up_to_the_span_s_end():
    reported = []
    pose_table(Lagging(), Poses(), first=2, frames=3, report=lambda done, total: reported.append((done, total)))
    assert reported == [(done, 5) for done in range(1, 6)]


def test_the_span_must_lie_in_the_sequence():
    with pytest.raises(ValueError, match="not a span"):
        pose_table(Lagging(), Poses(), first=0, frames=0)
    with pytest.raises(ValueError, match="no frames from 9"):
        pose_table(Lagging(), Poses(), first=9)
    pose_table(Lagging(), Poses(), init=True)


def test_the_command_runs_the_foresti_ekf_from_the_papers_prior(tmp_path):
    args = ["pose-table", "--tracker", "foresti_ekf", "--dataset", "camera/S3", "--frames", "3", "--out", str(tmp_path)]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    rows = [line for line in result.stdout.splitlines() if line.startswith("|")][2:]
    assert len(rows) == 3 and all(row.split("|")[2].strip() == "Y" for row in rows)
    assert (tmp_path / "pose_foresti_ekf.md").read_text().strip() == result.stdout.strip()
    missing = CliRunner().invoke(main, ["pose-table", "--tracker", "foresti_ekf", "--dataset", "camera/nope"])
    assert missing.exit_code == 2 and "nope" in missing.output
    no_pose = CliRunner().invoke(main, ["pose-table", "--tracker", "hough", "--dataset", "camera/S3", "--frames", "1"])
    assert no_pose.exit_code == 2 and "'hough' reported no camera pose" in no_pose.output
