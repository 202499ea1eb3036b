"""trackbench: a benchmark for subsea cable and pipeline trackers.

Trackers and datasets arrive as pluggy plugins (entry-point group
``trackbench``).  A plugin module marks its hook implementations with
:data:`hookimpl`::

    from benchmark import Tracker, hookimpl

    class MyTracker(Tracker):
        name, version, modality = "mine", "1.0", "camera"
        ...

    @hookimpl
    def trackbench_register_trackers(registry):
        registry.add_tracker(MyTracker)
"""

import pluggy

from benchmark.errors import DataError, ParameterError, PluginError, TrackbenchError
from benchmark.hookspecs import PROJECT_NAME
from benchmark.model import (
    CableState,
    CameraCalibration,
    CameraPose,
    CameraTruth,
    Frame,
    Outcome,
    Sequence,
    SequenceInfo,
    VehicleSpeeds,
)
from benchmark.registry import Registry
from benchmark.tracker import NoParams, Tracker

__version__ = "0.1.0"

hookimpl = pluggy.HookimplMarker(PROJECT_NAME)
"""Marker for hook implementations in trackbench plugins."""

__all__ = [
    "CableState",
    "CameraCalibration",
    "CameraPose",
    "CameraTruth",
    "DataError",
    "Frame",
    "NoParams",
    "Outcome",
    "ParameterError",
    "PluginError",
    "Registry",
    "Sequence",
    "SequenceInfo",
    "Tracker",
    "TrackbenchError",
    "VehicleSpeeds",
    "hookimpl",
    "__version__",
]
