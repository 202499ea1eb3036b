"""Commands plugins add through ``trackbench_register_commands``: found, listed, run, and refused when they clash."""

from __future__ import annotations

import os
import subprocess
import sys
import types
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

from benchmark import hookimpl
from benchmark.cli import main
from benchmark.cli.discovery import COMMAND_PLUGINS, load_commands
from benchmark.errors import DataError, PluginError

from ..conftest import Install

HELLO = '''
import click

from benchmark import hookimpl


@click.command("hello")
@click.option("--name", default="world", show_default=True, help="Whom to greet.")
@click.pass_obj
def hello(session, name):
    """Greet NAME and name the plugins this session disables."""
    click.echo(f"hello {name}, disabled: {', '.join(session.disable)}")


@hookimpl
def trackbench_register_commands(registry):
    registry.add_command(hello)
'''

LISTED_MODULES = """
import sys

from benchmark.cli import main

try:
    main(sys.argv[1:], prog_name="trackbench")
finally:
    print(sorted(name for name in sys.modules if name.startswith("trackbench_") or name == "acme_hello"))
"""


def trackbench(site: Path, *arguments: str) -> subprocess.CompletedProcess[str]:
    environment = {**os.environ, "PYTHONPATH": str(site)}
    return subprocess.run(
        [sys.executable, "-c", LISTED_MODULES, *arguments], capture_output=True, text=True, env=environment, check=False
    )


def test_a_third_party_distribution_adds_a_command_that_help_lists_without_importing_any_tracker(
    tmp_path: Path,
) -> None:
    site = tmp_path / "site"
    info = site / "acme_hello-1.0.dist-info"
    info.mkdir(parents=True)
    (site / "acme_hello.py").write_text(HELLO)
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: acme-hello\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text(f"[{COMMAND_PLUGINS.name}]\nhello = acme_hello\n")

    listed = trackbench(site, "--help")
    assert listed.returncode == 0, listed.stderr
    assert "  hello  " in listed.stdout and "Greet NAME" in listed.stdout and "  diagnose  " in listed.stdout
    assert listed.stdout.splitlines()[-1] == "['acme_hello']"  # no tracker plugin was imported to list them

    ran = trackbench(site, "--disable", "nothing", "hello", "--name", "sea")
    assert ran.returncode == 0, ran.stderr
    assert ran.stdout.splitlines()[0] == "hello sea, disabled: nothing"


def plugin_commands(monkeypatch: pytest.MonkeyPatch, installed: Install, name: str, *commands: click.Command) -> None:
    """Install a distribution ``NAME-dist`` whose plugin ``NAME`` adds ``commands``."""

    @hookimpl
    def trackbench_register_commands(registry) -> None:  # noqa: ANN001
        for command in commands:
            registry.add_command(command)

    module = types.ModuleType(f"acme_{name}")
    module.trackbench_register_commands = trackbench_register_commands  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, module.__name__, module)
    installed(f"{name}-dist", [(name, module.__name__)], group=COMMAND_PLUGINS.name)


@click.command("tide")
def tide() -> None:
    """Print the tide."""
    click.echo("high")


@click.command("sink")
def sink() -> None:
    """Fail with a data error."""
    raise DataError("sink.dat: no such file")


def test_a_command_whose_name_is_taken_is_left_out_with_a_warning_and_exit_status_1(
    monkeypatch: pytest.MonkeyPatch, installed: Install
) -> None:
    plugin_commands(monkeypatch, installed, "first", tide)
    plugin_commands(monkeypatch, installed, "second", tide)
    plugin_commands(monkeypatch, installed, "shadow", click.Command("run"))
    result = CliRunner().invoke(main, ["tide"])
    assert result.exit_code == 1, result.output
    assert result.stdout == "high\n"
    assert "Warning: plugin 'shadow' (shadow-dist 0.3): command 'run' is a built-in command of trackbench " \
        "(left out: its commands are unavailable)" in result.stderr
    clash = [line for line in result.stderr.splitlines() if "command 'tide' is already added" in line]
    assert clash in (  # pluggy calls the plugin registered last first
        ["Warning: plugin 'first' (first-dist 0.3): command 'tide' is already added by plugin 'second' "
         "(left out: its commands are unavailable)"],
        ["Warning: plugin 'second' (second-dist 0.3): command 'tide' is already added by plugin 'first' "
         "(left out: its commands are unavailable)"],
    )
    assert main.get_command(click.Context(main), "run").help.startswith("Run trackers on datasets")


def test_strict_plugins_makes_a_command_left_out_an_error(monkeypatch: pytest.MonkeyPatch, installed: Install) -> None:
    plugin_commands(monkeypatch, installed, "shadow", tide, click.Command("list"))
    result = CliRunner().invoke(main, ["--strict-plugins", "tide"])
    assert result.exit_code == 2
    assert result.stderr.startswith("Error: plugin 'shadow' (shadow-dist 0.3): command 'list' is a built-in")
    with pytest.raises(PluginError, match="command 'list' is a built-in"):
        load_commands(main.commands, strict=True)


def test_a_plugin_command_s_data_error_is_one_line_and_exit_status_2(
    monkeypatch: pytest.MonkeyPatch, installed: Install
) -> None:
    plugin_commands(monkeypatch, installed, "sinking", sink)
    result = CliRunner().invoke(main, ["sink"])
    assert result.exit_code == 2
    assert result.stderr == "Error: sink.dat: no such file\n"


def test_a_disabled_command_plugin_adds_nothing(monkeypatch: pytest.MonkeyPatch, installed: Install) -> None:
    plugin_commands(monkeypatch, installed, "tides", tide)
    assert CliRunner().invoke(main, ["tide"]).exit_code == 0
    result = CliRunner().invoke(main, ["--disable", "tides", "tide"])
    assert result.exit_code == 2 and "No such command 'tide'" in result.stderr
    assert "tides" in load_commands(main.commands).origins["tide"].plugin
    assert "tide" not in load_commands(main.commands, disable=["tides"]).commands
