"""trackbench_segmentation: the segmentation tracker of Ortiz et al., seeds/000, section 2.3.

Ortiz et al. find the cable bottom-up.  The image is divided into a pyramid
of cells; each cell is segmented by the hills of its grey level x gradient
modulus histogram (Panda and Rosenfeld, Fig. 2.4); the segments' contours
are followed up from the bottom of the image in the direction a Kalman
filter predicts, fitted with straight segments, grouped and filtered; nearly
parallel pairs of long lines are chosen by the expected width, their
parallelism and their length, and the best pairs of all cells are fused
into one (Fig. 2.5).  While tracking, the Kalman filter on the cable's
position, orientation and width limits the search to a region of interest.

The plugin registers one tracker, ``segmentation``
(:class:`SegmentationTracker`), through the ``trackbench`` entry-point group
every third-party tracker uses::

    [project.entry-points.trackbench]
    segmentation = "trackbench_segmentation"

Published and measured figures, side by side.  Ortiz et al. [AO03] report
89.8 % success on 1367 real 320 x 240 images at 24 ms a frame on an 800 MHz
Pentium III (seeds/000, section 2.3).  This implementation, on the rendered
320 x 240 camera suite and clutter family, initialised from the first
frame's truth (``trackbench run --tracker segmentation --tracker hough
--suite camera --suite camera-clutter --jobs 1``, version 1.0), is 82.5 %
correct, 5.5 % false and 12.0 % missed over all frames, at about 210 frames
a second (4.8 ms a frame) in one process; ``hough`` in the same run is
66.8 / 2.3 / 31.0 % at about 860 frames a second.  Per sequence, % correct
/ false / missed and frames a second:

==============  ===================  ==================
sequence        segmentation         hough
==============  ===================  ==================
camera/S1       66.1 / 16.1 / 17.7   58.9 / 0.8 / 40.3
camera/S1b      75.0 / 1.6 / 23.4    60.9 / 0.8 / 38.3
camera/S1c      80.2 / 4.8 / 14.9    64.9 / 0.8 / 34.3
camera/S2       99.8 / 0.2 / 0.0     100.0 / 0.0 / 0.0
camera/S3       100.0 / 0.0 / 0.0    100.0 / 0.0 / 0.0
camera/S4       95.3 / 2.9 / 1.7     97.1 / 0.0 / 2.9
camera/S5       91.2 / 4.1 / 4.7     31.6 / 0.0 / 68.4
camera/S6       94.6 / 0.0 / 5.4     98.4 / 0.0 / 1.6
camera/S7       59.3 / 37.3 / 3.3    43.3 / 46.7 / 10.0
clutter family  78.0 / 5.5 / 16.5    56.2 / 1.3 / 42.5
==============  ===================  ==================

The clutter family's row is the mean of its ten draws (59.3 to 99.6 %
correct).  The weak spots: while sand hides S7's pipeline the region of
interest holds on to sand ripples of about the expected width, so the
tracker reports them instead of losing the cable (37.3 % false).  S1's
overgrowth of rocks and algae gives most of the other false frames (16.1 %
on S1): the tracker has no test of whether a pair is still the cable, only
the region of interest and the expected width, so a pair of clutter edges
of the right width is taken like the cable's borders.
"""

from benchmark import Registry, hookimpl
from trackbench_segmentation.params import PAPER, SegmentationParams
from trackbench_segmentation.tracker import SegmentationTracker

__all__ = ["PAPER", "SegmentationParams", "SegmentationTracker", "trackbench_register_trackers"]


@hookimpl
def trackbench_register_trackers(registry: Registry) -> None:
    """Register the segmentation tracker and its paper variant, ``segmentation-paper``."""
    registry.add_tracker(SegmentationTracker)
    registry.add_tracker(SegmentationTracker, name="segmentation-paper", params=PAPER)
