"""Errors trackbench raises for bad plugins, parameters and data.

Each message names the input at fault (plugin, parameter, file and line), so
that a user can act on it without reading a traceback.
"""


class TrackbenchError(Exception):
    """Base of every error trackbench reports to its user."""


class PluginError(TrackbenchError):
    """A plugin failed to import, registered something invalid, or misspelt a hook."""


class ParameterError(TrackbenchError):
    """A tracker parameter that the tracker does not declare or cannot take."""


class DataError(TrackbenchError):
    """A missing, unreadable or malformed input file, row or frame."""
