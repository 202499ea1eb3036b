"""Stereo data on disk: a folder of left and right images with a sidecar, and the exporter that writes one.

:class:`~benchmark.modalities.stereo.io.folder.StereoFolder` opens the
folder (``--dataset DIR``); :func:`~benchmark.modalities.stereo.io.export.export_stereo_sequence`
writes any stereo sequence of image pairs in that form (``trackbench make-dataset``).
"""
