"""Entry point of the ``rotorcad`` command: the command group and the error policy.

Every input problem ends as one sentence on stderr and exit status 2, without a traceback
(CONTRACT.md, common rules).
"""

from __future__ import annotations

import sys

import click

from rotorcad import __version__
from rotorcad.cli.clearance_cmd import clearance
from rotorcad.cli.cut_cmd import cut
from rotorcad.cli.export_cmd import export, interfere
from rotorcad.cli.gear import gear
from rotorcad.cli.hob_cmd import hob
from rotorcad.cli.pump_cmd import pump
from rotorcad.cli.rotor import rotor
from rotorcad.errors import DesignError


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="rotorcad")
def cli() -> None:
    """rotorcad: conjugate profiles, gears and screw rotors to manufacturing files.

    Lengths in mm, angles in degrees on the command line. Run `rotorcad COMMAND --help`.
    """


cli.add_command(gear)
cli.add_command(rotor)
cli.add_command(hob)
cli.add_command(cut)
cli.add_command(pump)
cli.add_command(export)
cli.add_command(interfere)
cli.add_command(clearance)


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
