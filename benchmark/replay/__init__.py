"""Replays: one cell played frame by frame into a self-contained page, as the thesis's Cable Tracking GUI.

:mod:`benchmark.replay.record` plays a cell exactly as the runner does and
keeps, per frame, the outcome, truth, estimate, step time, the tracker's
belief and a small JPEG of the frame; :mod:`benchmark.replay.page` writes
that recording as one HTML file that works from ``file://``.  What a frame
looks like is the business of its modality's view (:mod:`benchmark.replay.views`:
camera, sonar and stereo).  seeds/000, section 4.7.
"""
