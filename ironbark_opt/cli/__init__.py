"""The ``ironbark`` command.

Sub-commands live in the modules ``ironbark_opt/cli/<topic>.py`` (shared options in ``common.py``) and are registered here
*lazily*: ``ironbark simulate`` imports ``cli/simulate.py`` only, so a command
never pays for the imports of the others (``requests``/``ssl`` for
``motor``/``weather``, the panel solver for ``aero``, IPOPT set-up for
``ballast``).  ``ironbark --help`` lists every command and therefore imports
them all.
"""
from __future__ import annotations

import importlib

import click

from ironbark_opt import __version__
from ironbark_opt.cli.common import OneLineErrorGroup

#: every module that contributes commands (its ``COMMANDS`` list)
_MODULES = ("simulate", "optimise", "analysis", "ork", "motor", "weather", "aero",
            "flight", "window")
#: the module that defines a command, so one command imports one module; a command
#: not listed here is still found (every module in ``_MODULES`` is then imported)
_HOME = {"simulate": "simulate", "ballast": "optimise", "sensitivity": "analysis",
         "montecarlo": "analysis", "ork": "ork", "motor": "motor", "weather": "weather",
         "aero": "aero", "flight": "flight", "calibrate": "flight",
         "window": "window"}


class LazyGroup(OneLineErrorGroup):
    """A click group that imports a sub-command's module on first use (and reports
    usage errors in one line, :class:`~ironbark_opt.cli.common.OneLineErrorGroup`)."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._loaded = set()

    def list_commands(self, ctx):
        for module in _MODULES:
            self._load(module)
        return super().list_commands(ctx)

    def get_command(self, ctx, cmd_name):
        if cmd_name not in self.commands and cmd_name in _HOME:
            self._load(_HOME[cmd_name])
        if cmd_name not in self.commands:
            for module in _MODULES:
                self._load(module)
        return super().get_command(ctx, cmd_name)

    def _load(self, module_name):
        if module_name in self._loaded:
            return
        self._loaded.add(module_name)
        try:
            module = importlib.import_module(f"ironbark_opt.cli.{module_name}")
        except ModuleNotFoundError as err:
            if err.name == f"ironbark_opt.cli.{module_name}":
                return                   # an optional command module not in this checkout
            raise
        for cmd in module.COMMANDS:
            self.add_command(cmd)


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="ironbark")
def main():
    """Ironbark-Opt: apogee prediction, ballast and motor choice for high-power rockets."""
