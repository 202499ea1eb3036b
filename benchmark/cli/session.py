"""What the commands of one ``trackbench`` invocation share: the plugin registry, the errors shown, the exit statuses.

A command, built in or added by a plugin, gets the :class:`Session` with
``click.pass_obj`` and reads the trackers, suites and modalities from
:attr:`Session.registry`.
"""

from __future__ import annotations

import dataclasses

import click

from benchmark import plugins
from benchmark.registry import Registry
from benchmark.text import one_line

EXIT_FAILED = 1
"""A cell failed or a plugin was left out; everything else was done."""
EXIT_INTERRUPTED = 130
"""The user's Ctrl-C (128 + SIGINT)."""


class ReportedError(click.ClickException):
    """A :class:`~benchmark.errors.TrackbenchError` shown as ``Error: ...``, exit status 2."""

    exit_code = 2


@dataclasses.dataclass
class Session:
    """State shared by the commands of one invocation: plugin options and the registry."""

    disable: tuple[str, ...] = ()
    strict_plugins: bool = False
    _registry: Registry | None = None

    @property
    def registry(self) -> Registry:
        """Trackers and suites of every plugin not disabled, loaded on first use.

        Plugins left out are reported on stderr when the registry is loaded.
        """
        if self._registry is None:
            self._registry = plugins.load_registry(disable=self.disable, strict=self.strict_plugins)
            for problem in self._registry.problems:
                click.echo(f"Warning: {one_line(problem)}", err=True)
        return self._registry

    @property
    def problems(self) -> list[str]:
        """Plugins left out, if the registry was loaded."""
        return self._registry.problems if self._registry is not None else []
