"""Definitions of synthetic camera sequences, as plain data.

A camera sequence is a pure function of a :class:`CameraSceneSpec` (which
includes its seed).  The spec is a tree of frozen pydantic dataclasses
(:mod:`benchmark.scenes.spec`) whose fields declare their ranges, built from
a plain mapping, so suites can be written as TOML files
(:meth:`CameraSceneSpec.from_dict`); an unknown key, a value of the wrong
type or out of its range is a :class:`benchmark.errors.DataError` naming
the file, the key and the rule.

The tree mirrors the parts of the scene model of seeds/004, section II:

* :class:`MotionSpec`: the camera pose ``(Cx, Cy, Cz, theta, phi, xi)`` over
  time, each coordinate a :class:`Signal` (a mean, waves, events and
  smoothed noise), plus the forward speed that moves ``Cz``;
* :class:`SeabedSpec`: the appearance of the plane the pipe rests on (sand
  texture, :class:`Ripples`, :class:`Clutter` of rocks and algae);
* :class:`CableLook`: the pipe's surface (albedo, shine, marine growth);
* :class:`Burial`: stretches where sand covers the pipe (seeds/004, Fig. 14);
* :class:`Overgrowth`: algae and stones on the pipe and against its sides,
  which break its borders (seeds/000, section 5.2.3);
* :class:`Crossing`: a second cable lying across the followed one;
* :class:`OpticsSpec`: light, water and sensor; its optional
  :class:`WaterSpec` (``[optics.water]``) switches from the haze of the
  thesis suites to the image formation model of
  :mod:`~benchmark.modalities.camera.scenes.water`, lit by lamps (:class:`Lamp`)
  and daylight.

Fields added after the thesis suites were written carry
:data:`benchmark.identity.OMIT_AT_DEFAULT`, so that a spec that leaves them
at their defaults keeps its identity (and its frames) exactly.

Lengths are in metres, angles in degrees (converted to radians where the
scene is built), times in frames unless a name says otherwise.
"""

from __future__ import annotations

import math
from dataclasses import field
from typing import Annotated, Literal

import pydantic
from annotated_types import Ge, Gt, Interval, Lt

from benchmark.identity import OMIT_AT_DEFAULT
from benchmark.modalities.camera.scenes.water import JERLOV_KD
from benchmark.scenes.signal import Signal
from benchmark.scenes.spec import (
    SPEC_CONFIG,
    Finite,
    Flag,
    Integer,
    Name,
    NonNegative,
    Number,
    Positive,
    Share,
    TableSpec,
    Text,
    ordered,
    strictly_increasing,
)

ZRange = tuple[Number, Number]
"""A stretch ``(from, to)`` along the pipe axis ``Z``, in m."""

EVERYWHERE: ZRange = (-math.inf, math.inf)

DensityProfile = Annotated[tuple[tuple[Finite, NonNegative], ...], pydantic.AfterValidator(strictly_increasing)]
"""Points ``(Z in m, factor)`` of a density that varies along the pipe.

The factor is interpolated linearly between points and held constant
beyond the first and the last; an empty profile is 1 everywhere.
"""


TintFactor = Annotated[Finite, Interval(ge=0, le=1.5)]

Tint = tuple[TintFactor, TintFactor, TintFactor]
"""Relative reflectance of the R, G and B channels, each in ``[0, 1.5]``."""

WHITE: Tint = (1.0, 1.0, 1.0)

Albedo = Share
"""An albedo, in ``[0, 1]``."""

JerlovType = Literal[tuple(JERLOV_KD)]  # type: ignore[valid-type]
"""A Jerlov water type of :data:`~benchmark.modalities.camera.scenes.water.JERLOV_KD`."""


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class MotionSpec:
    """The camera trajectory, seeds/004 section II and Fig. 2.

    Attributes
    ----------
    cx_m : Signal
        Lateral offset ``Cx`` of the camera from the pipe axis.
    cy_m : Signal
        Height ``Cy`` of the camera above the pipe axis (the seabed is at
        ``Y = -r``).
    theta_deg, phi_deg, xi_deg : Signal
        Pan, tilt (90 looks straight down) and roll.
    speed_mps : Signal
        Forward speed along ``Z``; ``Cz`` starts at 0 and integrates it.
    speed_noise_mps : float
        Standard deviation of the inertial sensor's error on each reported
        speed.
    """

    cx_m: Signal = Signal()
    cy_m: Signal = Signal(mean=2.0)
    theta_deg: Signal = Signal()
    phi_deg: Signal = Signal(mean=60.0)
    xi_deg: Signal = Signal()
    speed_mps: Signal = Signal(mean=0.45)
    speed_noise_mps: NonNegative = 0.02


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Ripples:
    """Sand ripples: parallel crests with a sharp edge, a trap for line detectors.

    Attributes
    ----------
    amplitude : float
        Relative albedo modulation (0.2 changes the albedo by +-20 %).
    wavelength_m : float
        Distance between crests.
    angle_deg : float
        Angle between the crests and the pipe axis.
    sharpness : float
        0 gives a sine profile, 1 a sawtooth with a sharp crest.
    waviness_m : float
        How far the crests wander from straight lines.
    z_m : tuple of float
        The stretch of seabed that has them, with soft ends of ``fade_m``.
    """

    amplitude: Number = 0.2
    wavelength_m: Positive = 0.12
    angle_deg: Number = 15.0
    sharpness: Share = 0.85
    waviness_m: Number = 0.008
    z_m: ZRange = EVERYWHERE
    fade_m: Number = 0.5


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Clutter:
    """Rocks and tufts of algae scattered over a stretch of seabed.

    Attributes
    ----------
    z_m : tuple of float
        Stretch along the pipe; it is clipped to the seabed the camera sees.
    x_m : float
        Half width of the cluttered band around the pipe.
    rocks_per_m2, algae_per_m2 : float
        Mean densities (Poisson).
    rock_size_m, algae_size_m : float
        Typical diameter of a rock and length of an algae tuft.
    rock_albedo, algae_albedo : float
        Their mean albedos.
    density : DensityProfile
        Factor on both densities along ``Z``; empty for a constant density.
    """

    z_m: ZRange = EVERYWHERE
    x_m: Number = 2.5
    rocks_per_m2: NonNegative = 0.0
    rock_size_m: Positive = 0.1
    rock_albedo: Number = 0.35
    algae_per_m2: NonNegative = 0.0
    algae_size_m: Positive = 0.25
    algae_albedo: Number = 0.18
    density: DensityProfile = ()


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class SeabedSpec:
    """Appearance of the seabed plane ``Y = -r``.

    Attributes
    ----------
    albedo : float
        Mean albedo of the sand, in [0, 1].
    patchiness, patch_scale_m : float
        Relative strength and size of large darker and lighter patches.
    detail : float
        Relative strength of centimetre-to-decimetre texture.
    grain : float
        Relative strength of the finest, per-centimetre grain.
    ripples : tuple of Ripples
    clutter : tuple of Clutter
    tint : tuple of float
        Reflectance of R, G and B relative to ``albedo`` (the grey map is
        multiplied by it per channel); used by the water model only.  The
        clutter and the overgrowth share it.
    """

    albedo: Albedo = 0.5
    patchiness: Number = 0.15
    patch_scale_m: Number = 0.6
    detail: Number = 0.08
    grain: Number = 0.06
    ripples: tuple[Ripples, ...] = ()
    clutter: tuple[Clutter, ...] = ()
    tint: Tint = field(default=WHITE, metadata=OMIT_AT_DEFAULT)


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class CableLook:
    """Appearance of the pipe's surface.

    Attributes
    ----------
    albedo : float
        Mean albedo of the bare pipe.
    texture : float
        Relative strength of its surface texture.
    specular : float
        Strength of the highlight along the middle (the light is on the
        vehicle, so the middle faces it).
    growth_coverage : float
        Share in [0, 1] of the flanks covered by marine growth.
    growth_albedo : float
        Albedo of the growth.
    growth_angle_deg, growth_spread_deg : float
        Where the growth sits, as the angle around the pipe from its top
        (90 is the flank the camera sees as a border), and how wide.
    tint : tuple of float
        Reflectance of R, G and B relative to ``albedo`` (a yellow paint is
        about ``(1, 0.85, 0.15)``); used by the water model only.
    """

    albedo: Albedo = 0.22
    texture: Number = 0.06
    specular: Number = 0.15
    growth_coverage: Share = 0.0
    growth_albedo: Albedo = 0.4
    growth_angle_deg: Number = 80.0
    growth_spread_deg: Number = 30.0
    tint: Tint = field(default=WHITE, metadata=OMIT_AT_DEFAULT)


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Burial:
    """A stretch where sand covers the pipe (seeds/004, Fig. 14).

    Attributes
    ----------
    z_m : tuple of float
        Where the sand is at its full ``level``.
    level : float
        Sand height as a share of the pipe diameter above the seabed: 0 is
        the seabed, 1 the top of the pipe; above 1 the pipe is hidden.
    ramp_m : float
        Length over which the sand rises before and falls after the
        stretch: the pipe is partly buried there.
    roughness : float
        Irregularity of the sand line, as a share of the diameter.
    """

    z_m: Annotated[tuple[Finite, Finite], pydantic.AfterValidator(ordered)]
    level: Number = 1.15
    ramp_m: NonNegative = 0.6
    roughness: NonNegative = 0.05


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Overgrowth:
    """Algae and stones on the pipe and against its sides (seeds/000, section 5.2.3).

    Unlike :class:`Clutter`, which lies on the seabed beside the pipe, this
    layer is drawn over the pipe as well: algae mats and fronds drape over
    it and across its borders, stones lean against its flanks or lie on top,
    so stretches of the borders disappear and the fronds add short straight
    edges of every orientation, some nearly parallel to the pipe.

    Attributes
    ----------
    z_m : tuple of float
        Stretch along the pipe; it is clipped to the seabed the camera sees.
    density : DensityProfile
        Factor along ``Z`` on the mat cover and on the numbers of fronds and
        stones; empty for a constant density.
    x_m : float
        Half width of the band around the pipe axis where mats lie and
        fronds are rooted.
    mat_cover : float
        Share in [0, 1) of the band that algae mats cover where the factor
        is 1.
    mat_scale_m : float
        Typical size of a mat.
    mat_albedo : float
        Mean albedo of the mats.
    fronds_per_m : float
        Tufts of fronds (seaweed, seagrass) per metre of pipe (Poisson).
    frond_length_m, frond_width_m : float
        Typical length and width of one frond.
    frond_albedo : float
        Mean albedo of the fronds.
    parallel_share : float
        Share in [0, 1] of the tufts that lie along the pipe (within about
        10 deg); the others point anywhere.
    side_stones_per_m : float
        Stones per metre of pipe that lie against its sides, either side.
    top_stones_per_m : float
        Stones per metre of pipe that lie on top of it.
    stone_size_m : float
        Typical diameter of a stone.
    stone_height : float
        Height of a stone as a share of its diameter.
    stone_albedo : float
        Mean albedo of the stones.
    """

    z_m: ZRange = EVERYWHERE
    density: DensityProfile = ()
    x_m: Annotated[Number, Gt(0)] = 0.5
    mat_cover: Annotated[Finite, Interval(ge=0, lt=1)] = 0.0
    mat_scale_m: Annotated[Number, Gt(0)] = 0.08
    mat_albedo: Albedo = 0.22
    fronds_per_m: Annotated[Number, Ge(0)] = 0.0
    frond_length_m: Annotated[Number, Gt(0)] = 0.3
    frond_width_m: Annotated[Number, Gt(0)] = 0.02
    frond_albedo: Albedo = 0.2
    parallel_share: Share = 0.3
    side_stones_per_m: Annotated[Number, Ge(0)] = 0.0
    top_stones_per_m: Annotated[Number, Ge(0)] = 0.0
    stone_size_m: Annotated[Number, Gt(0)] = 0.15
    stone_height: Annotated[Number, Gt(0)] = 0.6
    stone_albedo: Albedo = 0.35


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Crossing:
    """A second cable lying straight on the seabed across the followed one.

    It is drawn (:mod:`~benchmark.modalities.camera.scenes.crossing`), never
    tracked: the ground truth stays the followed cable.

    Attributes
    ----------
    at_m : float
        ``Z`` where its axis passes over the followed cable's axis.
    angle_deg : float
        Angle from the followed cable's ``+Z`` to its own direction, turning
        towards ``+X``, in ``(0, 180)``: 90 crosses at right angles, 45
        runs ahead and to the right.
    diameter_m : float or None
        Its diameter; None takes the followed cable's.
    look : CableLook or None
        Its surface; None takes the followed cable's (its texture drawn
        anew).  The water model tints it as the followed cable, whatever
        its own ``tint``.
    """

    at_m: Finite
    angle_deg: Annotated[Finite, Interval(gt=0, lt=180)]
    diameter_m: Positive | None = None
    look: CableLook | None = None


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Lamp:
    """A lamp on the vehicle, aimed at the point the camera looks at.

    Attributes
    ----------
    offset_m : tuple of float
        Position relative to the camera in the camera's frame: right, down,
        forward (``(0, -0.4, 0)`` is 40 cm above it).
    intensity : float
        Radiant intensity on the beam's axis, in the units where a white
        surface facing the lamp 1 m away receives ``intensity``.
    cone_deg : float
        Half angle of the beam, to the middle of its soft edge.
    edge_deg : float
        Half width of the soft edge (smoothstep from full to no light).
    hotspot : float
        Extra light on the axis, as a share of the beam's (0 for an even beam).
    hotspot_deg : float
        Angular radius of the hot spot (``1/e`` of its extra light).
    """

    offset_m: tuple[Finite, Finite, Finite] = (0.0, -0.4, 0.0)
    intensity: Annotated[Number, Ge(0)] = 1.0
    cone_deg: Number = 35.0
    edge_deg: Annotated[Number, Ge(0)] = 8.0
    hotspot: Annotated[Number, Ge(0)] = 0.5
    hotspot_deg: Annotated[Number, Gt(0)] = 10.0

    def __post_init__(self) -> None:
        if not (0 < self.cone_deg - self.edge_deg and self.cone_deg + self.edge_deg < 90):
            raise ValueError(f"need 0 < cone_deg - edge_deg and cone_deg + edge_deg < 90, got {self.cone_deg}, {self.edge_deg}")


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class WaterSpec:
    """Water, light and camera exposure of the image formation model (:mod:`~benchmark.modalities.camera.scenes.water`).

    Attributes
    ----------
    jerlov : str
        Jerlov water type: ``I``, ``IA``, ``IB``, ``II``, ``III`` (oceanic)
        or ``1C``, ``3C``, ``5C``, ``7C``, ``9C`` (coastal, turbid).
    depth_m : float
        Depth of the camera below the surface: it filters the daylight.
    sun : float
        White daylight on a horizontal surface just below the surface, in the
        lamp's units (:attr:`Lamp.intensity`); 0 for none (deep water, night).
    sky_ambient : float
        Share of the daylight that comes from all directions rather than
        from above.
    caustics : float
        Relative depth of the sun flicker (the light focused by surface waves
        into moving bright lines on the seabed), just below the surface; it
        fades with depth over :data:`~benchmark.modalities.camera.scenes.lighting.CAUSTIC_FADE_M`.
    caustic_scale_m, caustic_speed_mps : float
        Size of the flicker's cells and the speed at which they move.
    lamps : tuple of Lamp
    mean_grey : float
        Grey level the camera's automatic exposure brings the mean of each
        frame to.
    snow_per_m3 : float
        Marine snow: particles per cubic metre large enough to see.
    snow_size_mm : float
        Their median diameter.
    defocus_px : float
        Blur (standard deviation, px) of a particle at half the focus
        distance; the focus is at the distance the lamps are aimed at.
    """

    jerlov: JerlovType = "II"
    depth_m: NonNegative = 50.0
    sun: NonNegative = 0.0
    sky_ambient: Share = 0.3
    caustics: NonNegative = 0.0
    caustic_scale_m: Annotated[Number, Gt(0)] = 0.5
    caustic_speed_mps: Annotated[Number, Ge(0)] = 0.3
    lamps: tuple[Lamp, ...] = (Lamp(),)
    mean_grey: Annotated[Number, Gt(0), Lt(255)] = 110.0
    snow_per_m3: NonNegative = 0.0
    snow_size_mm: Annotated[Number, Gt(0)] = 1.5
    defocus_px: NonNegative = 2.0

    def __post_init__(self) -> None:
        if self.sun == 0 and not any(lamp.intensity > 0 for lamp in self.lamps):
            raise ValueError("the scene needs light: a lamp with intensity > 0 or sun > 0")


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class OpticsSpec:
    """Light, water and sensor.

    Attributes
    ----------
    exposure : float
        Grey level of a white surface facing the lamp at the reference distance.
    ambient : float
        Share of light that does not depend on the surface's orientation.
    light_falloff : bool
        Whether the lamp's light falls off with the distance squared.
    daylight : float
        Share in [0, 1] of the light that does not fall off (daylight from
        above); the lamp gives the rest.
    reference_distance_m : float or None
        Distance at which the lamp's fall-off factor is 1; None takes the
        distance from the camera to the seabed along the optical axis at
        the mean pose of the sequence.
    auto_gain : float
        How much of the change of light at the image centre (the lamp's
        fall-off as the vehicle moves) the camera's gain control undoes: 0
        for a fixed gain, 1 for all of it.
    water_grey : float
        Grey level of the water far away (the haze colour).
    attenuation_per_m : float
        Haze coefficient: a surface at distance ``s`` keeps
        ``exp(-attenuation_per_m s)`` of its light.
    vignetting : float
        Darkening of the image corners, 0 for none.
    blur_px : float
        Standard deviation of the Gaussian blur, 0 for none.
    noise_grey : float
        Standard deviation of the sensor noise in grey levels.
    snow_per_frame : float
        Mean number of bright suspended particles per frame (haze model only).
    shot_noise : float
        Signal-dependent (shot) noise: the noise variance grows by this many
        grey levels squared per grey level, on top of ``noise_grey ** 2``
        (the read noise); 0 for none.
    jpeg_quality : int
        Quality (1-100) of the JPEG compression a video link applies to
        every frame; 0 for none.
    water : WaterSpec or None
        The water, light and camera of the image formation model; None keeps
        the haze model above (``water_grey``, ``attenuation_per_m``,
        ``exposure``, ``ambient``, ``light_falloff``, ``daylight``,
        ``auto_gain`` and ``snow_per_frame`` serve it only).
    """

    exposure: Number = 430.0
    ambient: Number = 0.15
    light_falloff: Flag = True
    daylight: Share = 0.4
    reference_distance_m: Annotated[Number, Gt(0)] | None = None
    auto_gain: Share = 0.85
    water_grey: Number = 38.0
    attenuation_per_m: Annotated[Number, Ge(0)] = 0.1
    vignetting: Annotated[Number, Ge(0)] = 0.35
    blur_px: Annotated[Number, Ge(0)] = 0.8
    noise_grey: Annotated[Number, Ge(0)] = 3.5
    snow_per_frame: Annotated[Number, Ge(0)] = 0.0
    shot_noise: NonNegative = field(default=0.0, metadata=OMIT_AT_DEFAULT)
    jpeg_quality: Annotated[Integer, Interval(ge=0, le=100)] = field(default=0, metadata=OMIT_AT_DEFAULT)
    water: WaterSpec | None = field(default=None, metadata=OMIT_AT_DEFAULT)


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class CameraSceneSpec(TableSpec):
    """Everything that defines one synthetic camera sequence.

    Attributes
    ----------
    name : str
        Sequence name in results, e.g. ``"camera/S1"``.
    n_frames : int
        Number of frames.
    seed : int
        Seed of every random choice (texture, trajectory noise, sensor noise).
    description : str
        What the sequence is meant to test.
    frame_size : tuple of int
        Image ``(W, H)`` in px.
    frame_interval_s : float
        Time between frames, ``tau`` of seeds/004 eq. (7).
    focal_px : float
        ``f / dx`` in px (seeds/004 eq. (3)).
    pipe_diameter_m : float
        Diameter of the cylinder.
    nominal_tilt_deg : float or None
        Tilt at which the camera is mounted (``phi_0`` of seeds/004 eq. (12));
        None takes the mean of ``motion.phi_deg``.
    crossing : tuple of Crossing
        Other cables lying across the pipe.
    """

    name: Name
    n_frames: Annotated[Integer, Ge(1)]
    seed: Integer = 0
    description: Text = ""
    frame_size: tuple[Annotated[Integer, Ge(8)], Annotated[Integer, Ge(8)]] = (320, 240)
    frame_interval_s: Annotated[Number, Gt(0)] = 0.04
    focal_px: Annotated[Number, Gt(0)] = 380.0
    pipe_diameter_m: Annotated[Number, Gt(0)] = 0.2
    nominal_tilt_deg: Number | None = None
    motion: MotionSpec = field(default_factory=MotionSpec)
    seabed: SeabedSpec = field(default_factory=SeabedSpec)
    cable: CableLook = field(default_factory=CableLook)
    burial: tuple[Burial, ...] = ()
    overgrowth: tuple[Overgrowth, ...] = ()
    optics: OpticsSpec = field(default_factory=OpticsSpec)
    crossing: tuple[Crossing, ...] = field(default=(), metadata=OMIT_AT_DEFAULT)

    @property
    def radius(self) -> float:
        """Pipe radius ``r`` in m."""
        return self.pipe_diameter_m / 2.0

    @property
    def nominal_tilt(self) -> float:
        """The mounting tilt ``phi_0`` in rad."""
        tilt = self.motion.phi_deg.mean if self.nominal_tilt_deg is None else self.nominal_tilt_deg
        return math.radians(tilt)
