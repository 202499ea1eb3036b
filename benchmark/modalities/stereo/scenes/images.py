"""A rendered stereo sequence: the chase boat's image pairs (seeds/002, section 4.1).

:class:`StereoImageScene` turns a
:class:`~benchmark.modalities.stereo.scenes.image_spec.StereoImageSceneSpec` into
frames whose observation is what the field system's camera delivered: a
pair of images ``(left, right)``.  The boats move exactly as in the
simulated :class:`~benchmark.modalities.stereo.scenes.scene.StereoScene` of the same
spec, which the scene keeps inside for the trajectories, the truth and
CH's noisy GPS and compass: with the seed of a ``stereo`` sequence, an
image sequence has the same boats and the same navigation errors.  Only the
measurement differs: instead of projected pixel coordinates with Gaussian
noise (section 3), a front end has to find TG's yellow marker in the
images and its range in the disparity map (section 4.1, Fig. 10).

Randomness comes from the seed: besides the streams of the simulated scene,
a :class:`numpy.random.SeedSequence` of ``spec.seed`` spawns one stream for
the wave field and the shoreline and one per frame for the sensor noise, so
any frame can be rendered on its own and is identical to the one the full
iteration yields.

The object keeps only its spec; the simulated scene and the renderer (a
few MB of textures) are built on first use and dropped when the scene is
pickled (:class:`~benchmark.scenes.scene.SimulatedScene`).

Each frame carries

* ``observation``: ``(left, right)``, ``uint8`` BGR images of shape
  ``(H, W, 3)``;
* ``truth``: :class:`benchmark.modalities.stereo.model.StereoTruth`;
* ``navigation``: :class:`benchmark.modalities.stereo.model.ChaseNavigation`, CH's GPS
  position and compass heading.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from benchmark.modalities.stereo.model import ChaseNavigation, StereoTruth
from benchmark.modalities.stereo.scenes.image_spec import StereoImageSceneSpec
from benchmark.modalities.stereo.scenes.motion import BoatTrack, RelativeGeometry
from benchmark.modalities.stereo.scenes.render import StereoRenderer, StereoView
from benchmark.modalities.stereo.scenes.scene import StereoScene
from benchmark.model import SequenceInfo
from benchmark.scenes.scene import SimulatedScene

# Spawn keys of this scene's random streams; the simulated scene uses keys 0-3.
_WORLD, _FRAMES = 16, 17

ImagePair = tuple[np.ndarray, np.ndarray]
"""``(left, right)`` ``uint8`` BGR images."""


@dataclass
class _Cache:
    """What a scene builds on first use and keeps while it lives (never pickled)."""

    motion: StereoScene
    renderer: StereoRenderer | None = None


class StereoImageScene(SimulatedScene[StereoImageSceneSpec, _Cache]):
    """A chase-boat stereo sequence rendered as image pairs (seeds/002, section 4.1).

    Parameters
    ----------
    spec : StereoImageSceneSpec
        The definition, seed included.

    Examples
    --------
    >>> scene = StereoImageScene.from_dict({"name": "stereo-images/demo", "n_frames": 2})
    >>> left, right = scene.pair(0)
    >>> left.shape, right.dtype.name
    ((240, 320, 3), 'uint8')
    """

    spec_type = StereoImageSceneSpec

    @property
    def info(self) -> SequenceInfo:
        """The simulated scene's info, with the image size and ``"source": "rendered"``."""
        info = self.motion.info
        return dataclasses.replace(info, frame_size=self._spec.frame_size, extra={**info.extra, "source": "rendered"})

    def _build_cache(self) -> _Cache:
        return _Cache(motion=StereoScene(self._spec))

    @property
    def motion(self) -> StereoScene:
        """The simulated scene of the same spec: trajectories, truth and navigation."""
        return self._state().motion

    @property
    def renderer(self) -> StereoRenderer:
        """The renderer of this sequence, built on first use."""
        state = self._state()
        if state.renderer is None:
            spec = self._spec
            state.renderer = StereoRenderer(spec.render, spec.camera.calibration(), self._stream(_WORLD))
        return state.renderer

    def tracks(self) -> tuple[BoatTrack, BoatTrack]:
        """True tracks ``(chase, target)`` at the frame times."""
        return self.motion.tracks()

    def relative_geometry(self) -> RelativeGeometry:
        """True position of TG relative to CH at every frame."""
        return self.motion.relative_geometry()

    def truth(self, index: int) -> StereoTruth:
        """Ground truth of frame ``index``: TG's true position and velocity, CH's true pose."""
        return self.motion.truth(index)

    def navigation(self, index: int) -> ChaseNavigation:
        """CH's GPS position and compass heading at frame ``index``, with their errors."""
        return self.motion.navigation(index)

    def view(self, index: int) -> StereoView:
        """Where the boats are at frame ``index``, as the renderer needs it."""
        k = self._check(index)
        chase, _ = self.motion.tracks()
        geometry = self.motion.relative_geometry()
        return StereoView(
            chase_position_m=(float(chase.position_m[k, 0]), float(chase.position_m[k, 1])),
            chase_heading=float(chase.heading[k]),
            target_ahead_m=float(geometry.ahead_m[k]),
            target_starboard_m=float(geometry.starboard_m[k]),
            target_aspect=float(geometry.aspect[k]),
            time_s=k * self._spec.frame_interval_s,
        )

    def pair(self, index: int) -> ImagePair:
        """The left and right images of frame ``index``.

        Parameters
        ----------
        index : int
            Frame index, from 0.

        Returns
        -------
        left, right : numpy.ndarray
            ``uint8`` BGR images of shape ``(H, W, 3)``.

        References
        ----------
        seeds/002, section 4.1 and Fig. 10.
        """
        view = self.view(index)
        return self.renderer.render_pair(view, self._stream(_FRAMES, index))

    def observation(self, index: int) -> ImagePair:
        """The observation of frame ``index``: the image :meth:`pair`."""
        return self.pair(index)
