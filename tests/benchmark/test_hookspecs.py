"""Tests of benchmark.hookspecs: the register hooks, the commands hook, the speed bounds hook, and the marker plugins use."""

import pluggy

import benchmark
from benchmark import hookspecs
from benchmark.cli.discovery import COMMAND_PLUGINS
from benchmark.plugins import REGISTER_HOOKS
from benchmark.speed.bounds import SPEED_PLUGINS


def test_the_register_hooks_are_specified_in_the_order_they_are_called():
    manager = pluggy.PluginManager(hookspecs.PROJECT_NAME)
    manager.add_hookspecs(hookspecs)
    specified = [name for name in dir(manager.hook) if name.startswith("trackbench_")]
    assert sorted(specified) == sorted(REGISTER_HOOKS + COMMAND_PLUGINS.hooks + SPEED_PLUGINS.hooks)
    assert REGISTER_HOOKS[0] == "trackbench_register_modalities"
    assert COMMAND_PLUGINS.hooks == ("trackbench_register_commands",)
    assert SPEED_PLUGINS.hooks == ("trackbench_register_speed_bounds",)
    for name in specified:
        assert getattr(manager.hook, name).spec.argnames == ("registry",)


def test_plugins_mark_their_hooks_with_the_project_s_hookimpl():
    assert benchmark.hookimpl is hookspecs.hookimpl
    assert hookspecs.hookimpl.project_name == hookspecs.PROJECT_NAME == "trackbench"

    @hookspecs.hookimpl(tryfirst=True)
    def trackbench_register_trackers(registry):
        pass

    assert trackbench_register_trackers.trackbench_impl["tryfirst"] is True
