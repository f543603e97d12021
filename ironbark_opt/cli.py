"""The ``ironbark`` command.

Sub-commands live in ``cli_<topic>.py`` modules and are registered here.
"""
from __future__ import annotations

import click

from ironbark_opt import __version__
from ironbark_opt.cli_common import OneLineErrorGroup


@click.group(cls=OneLineErrorGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="ironbark")
def main():
    """Ironbark-Opt: apogee prediction, ballast and motor choice for high-power rockets."""


def _register():
    import importlib
    for mod in ("cli_simulate", "cli_optimise", "cli_analysis", "cli_ork", "cli_motor", "cli_weather", "cli_aero"):
        try:
            module = importlib.import_module(f"ironbark_opt.{mod}")
        except ModuleNotFoundError as err:
            if err.name == f"ironbark_opt.{mod}":
                continue
            raise
        for cmd in module.COMMANDS:
            main.add_command(cmd)


_register()

if __name__ == "__main__":
    main()
