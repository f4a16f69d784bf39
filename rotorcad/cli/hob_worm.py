"""``rotorcad hob --hob-diameter``: the hob's basic worm of each rack, its figures and exact STEP."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import click

from hob.worm import MAX_STARTS, BasicWorm, basic_worm
from rotorcad.cli.common import InputError, Outputs
from rotorcad.errors import DesignError
from rotorcad.inverse_rack import DerivedRack

STEP_TOLERANCE = 1e-3
"""Largest distance (mm) of the worm's STEP faces from its helicoid: 1 um, as the rotors' STEP."""

OPTION_NAMES = {
    "starts": "--starts",
    "outside_diameter": "--hob-diameter",
    "length": "--hob-length",
    "gashes": "--gashes",
    "gash_depth": "--gash-depth",
    "rack": "the derived rack",
}
"""The worm's parameters (:func:`hob.worm.basic_worm`) as this command's options, for refusals."""

WORM_DECORATORS = [
    click.option(
        "--step",
        type=click.Path(path_type=Path, dir_okay=False),
        help="Exact STEP of the hob's basic worm (needs --hob-diameter); for a pair one file per rotor, "
        "the rotor's name added to the file name (hob_male.step, hob_female.step).",
    ),
    click.option("--starts", type=int, default=1, show_default=True, help=f"Thread starts of the hob, 1 to {MAX_STARTS}."),
    click.option("--hob-diameter", type=float, help="Outside diameter of the hob [mm]: gives the basic worm's figures."),
    click.option(
        "--hob-hand",
        type=click.Choice(["right", "left"]),
        help="Hand of the hob's thread. Default: the hand of the gear or rotor.",
    ),
    click.option("--hob-length", type=float, help="Length of the basic worm [mm]. Default: the hob diameter."),
    click.option("--gashes", type=int, default=0, show_default=True, help="Number of gashes (flutes), 2 to 40; 0 not stated."),
    click.option(
        "--gash-depth",
        type=float,
        help="Gash depth below the outside diameter [mm], more than the thread depth. Default: 1.25 x the thread depth.",
    ),
]


WORM_ONLY = [
    ("step", "--step", None),
    ("starts", "--starts", 1),
    ("hob_hand", "--hob-hand", None),
    ("hob_length", "--hob-length", None),
    ("gashes", "--gashes", 0),
    ("gash_depth", "--gash-depth", None),
]
"""The options that describe the worm, by key, flag and the value when not given: none without a diameter."""


def worm_options(fn):
    """Add the basic worm's options (:data:`WORM_DECORATORS`) to a command."""
    for deco in reversed(WORM_DECORATORS):
        fn = deco(fn)
    return fn


def worms_of(
    racks: dict[str, DerivedRack], hands: dict[str, bool], opts: dict[str, Any], datum: float = 0.0
) -> dict[str, BasicWorm]:
    """Make the basic worm of each rack from the options (none without ``--hob-diameter``).

    Parameters
    ----------
    racks : dict of DerivedRack
        By body name (``gear``, or ``male`` and ``female``).
    hands : dict of bool
        Whether each body is right-handed (the default hand of its hob).
    opts : dict
        The command's options.
    datum : float, mm
        The racks' datum line (a gear's profile shift x m_n from its pitch circle; 0 for rotors).

    Returns
    -------
    dict of BasicWorm

    Raises
    ------
    InputError
        A worm's option (:data:`WORM_ONLY`) without ``--hob-diameter``, or a figure out of range
        (naming its option).
    """
    if opts["hob_diameter"] is None:
        given = [flag for key, flag, unset in WORM_ONLY if opts[key] != unset]
        if given:
            raise InputError(f"--hob-diameter must be given with {given[0]}: the hob's outside diameter in mm.")
        return {}
    worms = {}
    for name, rack in racks.items():
        right = hands[name] if opts["hob_hand"] is None else opts["hob_hand"] == "right"
        try:
            worms[name] = basic_worm(
                rack, opts["starts"], opts["hob_diameter"], right, opts["hob_length"], opts["gashes"], opts["gash_depth"], datum
            )
            worms[name].section(STEP_TOLERANCE)  # a chain that does not close is refused before any file
        except DesignError as exc:
            label = OPTION_NAMES.get(exc.param, exc.param)
            if exc.param == "rack":
                raise InputError(f"the {name}'s derived rack cannot make a worm thread: {exc.sentence(label)}") from None
            raise InputError(exc.sentence(label)) from None
    return worms


def add_worm_steps(out: Outputs, worms: dict[str, BasicWorm], path: Path | None) -> dict[str, dict[str, float]]:
    """Add the worms' STEP files to ``out``; return the dict their writers fill with faces and deviation.

    Parameters
    ----------
    out : Outputs
        The command's files.
    worms : dict of BasicWorm
        By body name.
    path : Path or None
        ``--step`` (None: nothing added); a pair's files get ``_male``, ``_female`` before the suffix.

    Returns
    -------
    dict
        By body name, filled when the files are written: ``face_count``, ``step_deviation`` (mm).
    """
    info: dict[str, dict[str, float]] = {}
    if path is None:
        return info
    for name, worm in worms.items():
        target = path if len(worms) == 1 else path.with_name(f"{path.stem}_{name}{path.suffix}")
        out.add(target, lambda p, w=worm, n=name: info.update({n: _write(p, w)}), "--step")
    return info


def _write(path: Path, worm: BasicWorm) -> dict[str, float]:
    """Write one worm's STEP and return its face count and deviation from the helicoid (mm)."""
    from exports.step_exact import StepDeviationError
    from exports.step_worm import write_worm_step

    try:
        done = write_worm_step(
            path, worm.section(STEP_TOLERANCE), worm.section(STEP_TOLERANCE / 100).points, worm.signed_lead, worm.length
        )
    except StepDeviationError as exc:
        raise OSError(str(exc)) from None
    return {"face_count": int(done["faces"]), "step_deviation": float(done["deviation"])}


def worm_summaries(worms: dict[str, BasicWorm], info: dict[str, dict[str, float]]) -> dict[str, dict[str, Any]]:
    """Return the ``worms`` key of ``rotorcad hob --json``: each worm's figures and its STEP's check."""
    return {name: {**worm.summary(), **info.get(name, {})} for name, worm in worms.items()}


def rack_datum(body: Any) -> float:
    """Return the datum line of a body's rack, mm: a gear's profile shift x m_n, 0 for a pair's rotors."""
    return 0.0 if hasattr(body, "pair") else float(body.shift * body.module)


def body_hands(body: Any) -> dict[str, bool]:
    """Return whether each body of ``rotorcad hob`` is right-handed: a gear (spur: right) or a pair's rotors."""
    if hasattr(body, "pair"):
        right = body.pair.hand == "right"
        return {"male": right, "female": not right}  # the female's helix is of the other hand
    return {"gear": not (math.isfinite(body.helix_angle) and body.helix_angle < 0)}


__all__ = ["STEP_TOLERANCE", "add_worm_steps", "body_hands", "rack_datum", "worm_options", "worm_summaries", "worms_of"]
