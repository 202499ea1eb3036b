"""A closed-loop camera sequence: each frame rendered from where the tracker's last estimate steered the vehicle.

A :class:`ClosedLoopScene` is a :class:`benchmark.model.Sequence` whose
frames depend on the tracker: the runner hands it every estimate through
:meth:`~benchmark.model.Sequence.steer` after the frame is scored, the
:class:`~benchmark.closedloop.loop.Loop` turns it into a command and moves
the vehicle, and the next frame is rendered from the new pose.  So its
frames never go to the frame cache (``cache_frames`` is False), and each
cell renders its own.  Steering answers with the vehicle's
:class:`~benchmark.results.LoopValues` at the frame just seen, which the
runner keeps in the frame's score for the following metrics
(:mod:`benchmark.metrics.closed_loop`).

Its spec, :class:`ClosedLoopSpec`, declares the route, the vehicle, the
camera's mount and the controller's gains beside the look of a camera
scene (seabed, cable, burial, overgrowth, optics, as in
:class:`~benchmark.modalities.camera.scenes.spec.CameraSceneSpec`).  The
look is rendered by a :class:`~benchmark.modalities.camera.scenes.scene.CameraScene`
whose own trajectory is the corridor the vehicle may use: along the route
at the surge speed, swaying ``corridor_m`` either side, so that its
seabed is textured wherever the vehicle may look.  Stretches of burial and
overgrowth, and the cables that cross the route
(:mod:`~benchmark.modalities.camera.scenes.crossing`), are placed along the
route's arc length, the pipe frame's ``Z`` (:mod:`benchmark.closedloop.loop`):
a crossing at ``at_m`` crosses the route's tangent there at its angle, and
is drawn straight in that frame.

The run ends when the vehicle passes the route's end, or after
:attr:`ClosedLoopSpec.max_frames` frames.  In real-time mode
(:mod:`benchmark.closedloop.real_time`) the frames a busy tracker skips
are neither rendered nor yielded; the frames it sees keep their own index
and time.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterator, Mapping
from dataclasses import field
from functools import cached_property
from typing import Annotated, Any, ClassVar

import pydantic
from annotated_types import Ge, Gt

from benchmark.closedloop.controller import CableFollower, FollowerGains
from benchmark.closedloop.loop import CameraMount, Loop, Track
from benchmark.closedloop.real_time import intervals_until_next
from benchmark.closedloop.route import Leg, Route, RouteSpec
from benchmark.closedloop.vehicle import Kinematics, VehicleState
from benchmark.identity import OMIT_AT_DEFAULT, DatasetIdentity, digest, generator_source
from benchmark.modalities.camera.model import CableState, VehicleSpeeds
from benchmark.modalities.camera.geometry import Line
from benchmark.modalities.camera.scenes.burial import image_chord
from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.modalities.camera.scenes.spec import (
    Burial,
    CableLook,
    CameraSceneSpec,
    Crossing,
    MotionSpec,
    OpticsSpec,
    Overgrowth,
    SeabedSpec,
)
from benchmark.model import Frame, Sequence, SequenceInfo
from benchmark.results import LoopValues
from benchmark.scenes.draws import Conditions, resolve_draws
from benchmark.scenes.signal import Signal, Wave
from benchmark.scenes.spec import SPEC_CONFIG, Finite, Integer, Name, Number, Positive, TableSpec, Text

FRAME_MARGIN = 1.5
""":attr:`ClosedLoopSpec.max_frames` allows this many times the frames the route takes at the surge speed."""


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class ClosedLoopSpec(TableSpec):
    """A closed-loop route as data.

    Attributes
    ----------
    name, seed, description
        As a camera scene's.
    legs : tuple of Leg
        The route (:class:`~benchmark.closedloop.route.RouteSpec`).
    kinematics : Kinematics
        The vehicle.
    mount : CameraMount
        The camera on it.
    gains : FollowerGains
        The controller, the same for every tracker on the route.
    corridor_m : float
        How far either side of the cable the seabed is textured.
    start_offset_m, start_heading_deg : float
        Where the vehicle starts against the cable's start.
    frame_size, frame_interval_s, focal_px, pipe_diameter_m, seabed, cable, burial, overgrowth, optics
        The look, as :class:`~benchmark.modalities.camera.scenes.spec.CameraSceneSpec` declares it.
    crossing : tuple of Crossing
        Cables lying across the route, each at an arc length ``at_m`` on it.
    """

    name: Name
    legs: tuple[Leg, ...]
    seed: Integer = 0
    description: Text = ""
    kinematics: Kinematics = field(default_factory=Kinematics)
    mount: CameraMount = field(default_factory=CameraMount)
    gains: FollowerGains = field(default_factory=FollowerGains)
    corridor_m: Positive = 1.5
    start_offset_m: Finite = 0.0
    start_heading_deg: Finite = 0.0
    frame_size: tuple[Annotated[Integer, Ge(8)], Annotated[Integer, Ge(8)]] = (320, 240)
    frame_interval_s: Annotated[Number, Gt(0)] = 0.04
    focal_px: Annotated[Number, Gt(0)] = 380.0
    pipe_diameter_m: Annotated[Number, Gt(0)] = 0.2
    seabed: SeabedSpec = field(default_factory=SeabedSpec)
    cable: CableLook = field(default_factory=CableLook)
    burial: tuple[Burial, ...] = ()
    overgrowth: tuple[Overgrowth, ...] = ()
    optics: OpticsSpec = field(default_factory=OpticsSpec)
    crossing: tuple[Crossing, ...] = field(default=(), metadata=OMIT_AT_DEFAULT)

    def __post_init__(self) -> None:
        length = self.route.length_m
        for crossing in self.crossing:
            if not 0.0 <= crossing.at_m <= length:
                raise ValueError(f"crossing at_m = {crossing.at_m} is not on the route (0 to {length:g} m)")

    @property
    def route(self) -> Route:
        """The cable's route."""
        return Route(RouteSpec(self.legs))

    @property
    def max_frames(self) -> int:
        """The most frames a run may take: :data:`FRAME_MARGIN` times the route at the surge speed."""
        nominal = self.route.length_m / (self.kinematics.surge_mps * self.frame_interval_s)
        return int(math.ceil(FRAME_MARGIN * nominal)) + 1

    def loop(self) -> Loop:
        """A new run's vehicle at the route's start, steered by the route's controller."""
        follower = CableFollower(self.gains, self.frame_interval_s, self.frame_size[0])
        start = VehicleState(self.start_offset_m, 0.0, math.radians(self.start_heading_deg))
        return Loop(self.route, self.kinematics, self.mount, follower, self.frame_interval_s, start)

    def look(self) -> CameraSceneSpec:
        """The camera scene that renders the route: the look, and the corridor as its trajectory."""
        frames = self.max_frames
        sway = Wave(amplitude=self.corridor_m, period_frames=max(2.0, frames / 4.0))
        motion = MotionSpec(
            cx_m=Signal(waves=(sway,)),
            cy_m=Signal(mean=self.mount.height_m),
            phi_deg=Signal(mean=self.mount.tilt_deg),
            speed_mps=Signal(mean=self.kinematics.surge_mps),
            speed_noise_mps=0.0,
        )
        return CameraSceneSpec(
            name=self.name,
            n_frames=frames,
            seed=self.seed,
            description=self.description,
            frame_size=self.frame_size,
            frame_interval_s=self.frame_interval_s,
            focal_px=self.focal_px,
            pipe_diameter_m=self.pipe_diameter_m,
            nominal_tilt_deg=self.mount.tilt_deg,
            motion=motion,
            seabed=self.seabed,
            cable=self.cable,
            burial=self.burial,
            overgrowth=self.overgrowth,
            optics=self.optics,
            crossing=self.crossing,
        )


class ClosedLoopScene(Sequence):
    """A route driven by the estimates of the tracker that runs on it (module docstring).

    Parameters
    ----------
    spec : ClosedLoopSpec
        The definition, seed included.
    conditions : Mapping, optional
        The conditions it was drawn under.
    """

    spec_type: ClassVar[type[ClosedLoopSpec]] = ClosedLoopSpec
    cache_frames = False
    closed_loop = True

    def __init__(self, spec: ClosedLoopSpec, conditions: Mapping[str, Any] | None = None) -> None:
        self._spec = spec
        self._conditions: Conditions = dict(conditions or {})
        self._loop: Loop | None = None
        self._seen: Frame | None = None
        self._intervals = 1

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], source: str = "<dict>") -> ClosedLoopScene:
        """A closed-loop scene from a suite file's table, its draws drawn."""
        table, conditions = resolve_draws(data, source)
        return cls(cls.spec_type.from_dict(table, source), conditions)

    def __getstate__(self) -> dict[str, Any]:
        return {"_spec": self._spec, "_conditions": self._conditions}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__init__(state["_spec"], state["_conditions"])  # type: ignore[misc]

    @property
    def spec(self) -> ClosedLoopSpec:
        """The definition of this route."""
        return self._spec

    @cached_property
    def _look(self) -> CameraScene:
        return CameraScene(self._spec.look())

    @property
    def info(self) -> SequenceInfo:
        """As the camera scene's that renders it (at most :attr:`ClosedLoopSpec.max_frames` frames), with the route's length."""
        info = self._look.info
        extra = {**info.extra, "source": "rendered, closed loop", "route_m": self._spec.route.length_m}
        return dataclasses.replace(info, extra={**extra, "conditions": dict(self._conditions)})

    @cached_property
    def identity(self) -> DatasetIdentity:
        """Its generator and version as source, its spec's digest as fingerprint."""
        return DatasetIdentity(
            self._spec.name, "camera", source=generator_source(type(self)), fingerprint=digest(self._spec)
        )

    def conditions(self) -> Conditions:
        """The conditions it was drawn under."""
        return dict(self._conditions)

    @property
    def track(self) -> Track | None:
        """Where the vehicle of the latest run went, frame by frame; None before a run."""
        return None if self._loop is None else self._loop.track

    def frames(self) -> Iterator[Frame]:
        """Render each frame from the vehicle's pose, which the estimates handed to :meth:`steer` move."""
        spec, look = self._spec, self._look
        loop = self._loop = spec.loop()
        index = 0
        while index < spec.max_frames and not loop.ended:
            pose = loop.pose()
            state = loop.state
            self._seen = Frame(
                index=index,
                observation=look.render_from(pose, index),
                truth=look.truth_from(pose),
                navigation=VehicleSpeeds(lateral=state.sway_mps, vertical=0.0, frontal=spec.kinematics.surge_mps),
                time_s=index * spec.frame_interval_s,
            )
            self._intervals = 1
            yield self._seen
            index += self._intervals

    def steer(self, estimate: Any, busy_s: float = 0.0) -> LoopValues:
        """Take the estimate of the frame just yielded; the next frame is seen from where it steers the vehicle.

        ``busy_s`` is how long the tracker was busy with the frame, 0 but in
        real-time mode (:mod:`benchmark.closedloop.real_time`): the frames
        that arrive meanwhile are skipped, the vehicle moving on under the
        previous command, and :meth:`frames` yields the first frame after.

        Returns
        -------
        LoopValues
            The vehicle when it took that frame: its offset and heading
            error against the cable, how far along the route, the frame's
            time, and whether the cable's centreline crossed the image.
        """
        loop, seen = self._loop, self._seen
        if loop is None or seen is None:
            raise RuntimeError(f"{self._spec.name}: steered before its first frame")
        place, cable = loop.place, seen.truth.cable
        centreline = Line.from_normal(cable.d, cable.alpha) if cable.is_known else None
        in_view = centreline is not None and image_chord(centreline, self._spec.frame_size) is not None
        self._intervals = intervals_until_next(busy_s, self._spec.frame_interval_s)
        loop.steer(estimate if isinstance(estimate, CableState) else None, self._intervals)
        return LoopValues(
            offset_m=place.offset_m,
            heading_error_deg=math.degrees(place.heading_error),
            along_m=place.s_m,
            time_s=seen.time_s,
            in_view=in_view,
            route_m=loop.route.length_m,
        )
