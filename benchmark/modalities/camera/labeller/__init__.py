"""``trackbench label``: the thesis' GroundTruthEditor as a page in the browser.

The thesis labelled its video sequences by hand with its own tool, the
GroundTruthEditor (seeds/000, appendix B): import a set of images, move the
two green border lines onto the cable with spin boxes, copy the values to
the next frame, and save the whole as an image sequence file (section
4.7.3; ``conventions.md`` section 2).  This package is that tool, served on
``127.0.0.1`` to a page in the browser:

* :mod:`~benchmark.modalities.camera.labeller.document`: the frames being
  labelled, their cable states, and saving them as a sequence file with a
  backup of the previous one;
* :mod:`~benchmark.modalities.camera.labeller.app`: the Starlette app the
  page talks to, which also converts between cable states and border lines
  with :mod:`benchmark.modalities.camera.geometry`, so the page holds no
  cable geometry of its own;
* :mod:`~benchmark.modalities.camera.labeller.command`: the command;
* ``static/``: the page.
"""
