"""trackbench: a benchmark for subsea cable and pipeline trackers.

Modalities, trackers and datasets arrive as pluggy plugins (entry-point
group ``trackbench``).  A plugin module marks its hook implementations with
:data:`hookimpl`::

    from benchmark import Tracker, hookimpl

    class MyTracker(Tracker):
        name, version, modality = "mine", "1.0", "camera"
        ...

    @hookimpl
    def trackbench_register_trackers(registry):
        registry.add_tracker(MyTracker)

The camera's data model is re-exported here for the plugins that were
written against it; every modality's own types live in
:mod:`benchmark.modalities`.
"""

from benchmark.errors import DataError, ParameterError, PluginError, TrackbenchError
from benchmark.hookspecs import hookimpl
from benchmark.identity import DatasetIdentity
from benchmark.modalities.camera.model import (
    CableState,
    CameraCalibration,
    CameraFrame,
    CameraPose,
    CameraTruth,
    VehicleSpeeds,
)
from benchmark.modality import Modality, Reader
from benchmark.model import Frame, Outcome, Sequence, SequenceInfo
from benchmark.registry import Registry
from benchmark.tracker import NoParams, Tracker

__version__ = "0.1.0"

__all__ = [
    "CableState",
    "CameraCalibration",
    "CameraFrame",
    "CameraPose",
    "CameraTruth",
    "DataError",
    "DatasetIdentity",
    "Frame",
    "Modality",
    "NoParams",
    "Outcome",
    "ParameterError",
    "PluginError",
    "Reader",
    "Registry",
    "Sequence",
    "SequenceInfo",
    "Tracker",
    "TrackbenchError",
    "VehicleSpeeds",
    "hookimpl",
    "__version__",
]
