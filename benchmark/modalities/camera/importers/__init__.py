"""Bringing outside camera data in: labels made in other tools and ROS recordings.

Each importer writes what the camera readers already read, an image
sequence file in the thesis' format (seeds/000, section 4.7.3;
``conventions.md`` section 2), with a sidecar beside it for what the format
cannot hold (:mod:`~benchmark.modalities.camera.io.sidecar`):

* :mod:`~benchmark.modalities.camera.importers.labels`: border or
  cable-state labels from a CSV file or a CVAT 1.1 XML export;
* :mod:`~benchmark.modalities.camera.importers.rosbag`: the images of a ROS 1
  or ROS 2 bag, with the vehicle speeds of a navigation topic.

The commands ``trackbench import labels`` and ``trackbench import rosbag``
(:mod:`benchmark.modalities.camera.commands`) call them.
"""
