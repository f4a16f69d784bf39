"""Entry point of the ``rotorcad`` command: the command group and the error policy.

Every input problem ends as one sentence on stderr and exit status 2, without a traceback
(CONTRACT.md, common rules).
"""

from __future__ import annotations

import importlib
import sys

import click

from rotorcad import __version__
from rotorcad.errors import DesignError

# name -> (module:attribute, one-line summary): a command's module (and the heavy libraries it
# needs) is imported only when that command runs, so `rotorcad --help` starts at once
COMMANDS: dict[str, tuple[str, str]] = {
    "gear": ("rotorcad.cli.gear:gear", "One involute gear cut by the ISO 53 basic rack, optionally with its mate."),
    "rotor": ("rotorcad.cli.rotor:rotor", "A screw-rotor pair from a design or from points, with Rinder's analysis."),
    "hob": ("rotorcad.cli.hob_cmd:hob", "Rack and hob tooth of a gear or rotor pair, and the hobbability verdict."),
    "cut": ("rotorcad.cli.cut_cmd:cut", "Hob cutting simulation of a gear against the analytic envelope."),
    "pump": ("rotorcad.cli.pump_cmd:pump", "Delivery, irregularity and harmonics of an external gear pump."),
    "export": ("rotorcad.cli.export_cmd:export", "Solids of a rotor pair or gear design in every format (STL, STEP, DXF, ...)."),
    "interfere": (
        "rotorcad.cli.export_cmd:interfere",
        "Interference of the rotor pair and with the housing, as designed or assembled.",
    ),
    "clearance": ("rotorcad.cli.clearance_cmd:clearance", "Meshing clearance (Wu & Chi) of a pair from measured points."),
    "deflect": ("rotorcad.cli.deflect_cmd:deflect", "Deflection of the rotors under gas load (Rinder & Deix)."),
    "sweep": ("rotorcad.cli.sweep_cmd:sweep", "Thousands of rotor variants built and judged side by side, on Dask."),
    "coupling": ("rotorcad.cli.coupling_cmd:coupling", "Oil film of a gear coupling with barrel-shaped teeth (Belkov et al.)."),
}


class LazyGroup(click.Group):
    """A command group that imports a command's module when the command is used."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return list(COMMANDS)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name not in COMMANDS:
            return None
        module, _, attr = COMMANDS[cmd_name][0].partition(":")
        return getattr(importlib.import_module(module), attr)

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        with formatter.section("Commands"):
            formatter.write_dl([(name, summary) for name, (_, summary) in COMMANDS.items()])


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="rotorcad")
def cli() -> None:
    """rotorcad: conjugate profiles, gears and screw rotors to manufacturing files.

    Lengths in mm, angles in degrees on the command line. Run `rotorcad COMMAND --help`.
    """


def main(argv: list[str] | None = None) -> int:
    """Run the CLI; return the exit status (0 success, 2 bad input)."""
    try:
        cli.main(args=argv, prog_name="rotorcad", standalone_mode=False)
    except click.exceptions.Exit as exc:
        return int(exc.exit_code)
    except click.exceptions.Abort:
        click.echo("rotorcad: aborted.", err=True)
        return 130
    except click.ClickException as exc:
        message = " ".join(exc.format_message().split())
        if not message.endswith("."):
            message += "."
        click.echo(f"rotorcad: error: {message}", err=True)
        return 2 if exc.exit_code in (1, 2) else int(exc.exit_code)
    except DesignError as exc:
        click.echo(f"rotorcad: error: {exc}", err=True)
        return 2
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
