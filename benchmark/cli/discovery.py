"""Commands that plugins add to the command line, through the ``trackbench_register_commands`` hook.

Such plugins are modules named in the entry-point group
``trackbench.commands`` (trackbench's own camera modality adds ``diagnose``,
``pose-table`` and ``import`` this way).  They are a group of their own so that
listing the commands imports those modules only, not every tracker of the
``trackbench`` group with its dependencies.  Loading goes through
:func:`benchmark.plugins.load_plugins`, so a command plugin is disabled,
left out or made strict exactly like a tracker plugin, and every error
names it.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable

import click

from benchmark.plugins import PluginGroup, load_plugins
from benchmark.registry import Origin, PluginRecords

COMMAND_PLUGINS = PluginGroup("trackbench.commands", ("trackbench_register_commands",), "its commands are unavailable")
"""The entry-point group of the plugins that add commands, and their one hook."""


class CommandRegistry(PluginRecords):
    """The commands plugins add, each under a name no built-in command or other plugin has."""

    def __init__(self, taken: Collection[str] = ()) -> None:
        super().__init__()
        self.taken = frozenset(taken)
        self.commands: dict[str, click.Command] = {}
        self.origins: dict[str, Origin] = {}

    def add_command(self, command: click.Command) -> click.Command:
        """Add ``command`` under its name.

        Raises
        ------
        PluginError
            If ``command`` is not a :class:`click.Command` or its name is
            taken by a built-in command or another plugin's.
        """
        if not isinstance(command, click.Command) or not command.name:
            raise self._fail(f"{command!r} is not a named click.Command")
        if command.name in self.taken:
            raise self._fail(f"command {command.name!r} is a built-in command of trackbench")
        if command.name in self.commands:
            raise self._fail(f"command {command.name!r} is already added by plugin {self.origins[command.name].plugin!r}")
        self.commands[command.name] = command
        self.origins[command.name] = self.origin
        return command


def load_commands(taken: Collection[str], disable: Iterable[str] = (), *, strict: bool = False) -> CommandRegistry:
    """The commands of every plugin of :data:`COMMAND_PLUGINS` not disabled, beside the built-in ones in ``taken``.

    Raises
    ------
    PluginError
        With ``strict``, for any plugin left out; see :func:`benchmark.plugins.load_plugins`.
    """
    return load_plugins(lambda: CommandRegistry(taken), COMMAND_PLUGINS, disable, strict=strict)
