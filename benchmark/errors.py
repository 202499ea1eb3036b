"""Errors trackbench raises for bad plugins, parameters and data.

Each message names the input at fault (plugin, parameter, file and line), so
that a user can act on it without reading a traceback.
"""


class TrackbenchError(Exception):
    """Base of every error trackbench reports to its user."""


class PluginError(TrackbenchError):
    """A plugin failed to import, registered something invalid, or misspelt a hook.

    Parameters
    ----------
    message : str
        What went wrong, naming the plugin.
    plugin : str, optional
        The entry-point name of the one plugin at fault, when it is known;
        such a plugin can be left out and the others kept.
    """

    def __init__(self, message: str, plugin: str | None = None) -> None:
        super().__init__(message)
        self.plugin = plugin


class ParameterError(TrackbenchError):
    """A tracker parameter that the tracker does not declare or cannot take."""


class DataError(TrackbenchError):
    """A missing, unreadable or malformed input file, row or frame."""
