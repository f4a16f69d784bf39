"""Roles are types in the core's signatures: a rotor is a ``Side``, text only at the public edge.

The core's functions take ``rotorcad.roles.Side`` where they take a rotor; the CLI and the top-level
API read "male" / "female" with ``Side(value)``. These tests read the signatures with ``inspect`` and
``typing.get_type_hints``, and check that the text a caller passes at the edge is the same rotor as
the enum.
"""

from __future__ import annotations

import enum
import importlib
import inspect
import math
import pkgutil
import typing

import numpy as np
import pytest
import shapely

import hob
import rotorcad
from rotorcad.coupling import GearCoupling, LoadedFlank
from rotorcad.deflection import DeflectionLines
from rotorcad.roles import Flank, Side
from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair

ROLE_PARAMETERS = {"rotor", "side", "body"}

NOT_SCANNED = ("rotorcad.cli",)  # the command line is the public edge: it reads the text users type

# The public edge: methods a user calls from the top-level API (``rotorcad.ScrewRotors``,
# ``rotorcad.GasDeflection`` and the ``DeflectionLines`` it returns) or from a script against
# ``rotorcad.inverse_rack``, which read "male" / "female" as ``Side(value)``.
PUBLIC_EDGE = {
    "rotorcad.screw_rotors.ScrewRotors.section",
    "rotorcad.deflection.DeflectionLines.largest",
    "rotorcad.deflection.GasDeflection.journal_length",
    "rotorcad.inverse_rack.rotor_rack",
    "rotorcad.measured.fit.lobe_pieces",  # rotorcad.lobe_pieces
    "rotorcad.measured.pairs.pair_from_rotor_points",  # rotorcad.pair_from_rotor_points
}


def _core_modules():
    for package in (rotorcad, hob):
        for info in pkgutil.walk_packages(package.__path__, package.__name__ + "."):
            if any(info.name == n or info.name.startswith(n + ".") for n in NOT_SCANNED):
                continue
            yield importlib.import_module(info.name)


def _callables(module):
    """Yield (qualified name, function) of the functions and methods defined in ``module``."""
    for name, obj in vars(module).items():
        if getattr(obj, "__module__", None) != module.__name__:
            continue
        if inspect.isfunction(obj):
            yield f"{module.__name__}.{name}", obj
        elif inspect.isclass(obj):
            for attr, member in vars(obj).items():
                fn = getattr(member, "__func__", member)  # staticmethod, classmethod
                if inspect.isfunction(fn):
                    yield f"{module.__name__}.{name}.{attr}", fn


def _annotation_parts(fn, parameter: str) -> set[str] | None:
    """The names in a parameter's annotation (``Side | str`` -> {"Side", "str"}); None when it has none."""
    try:
        hints = typing.get_type_hints(fn)
    except (NameError, TypeError):  # a name imported under TYPE_CHECKING: read the text of the annotation
        hints = dict(getattr(fn, "__annotations__", {}))
    if parameter not in hints:
        return None
    hint = hints[parameter]
    if isinstance(hint, str):
        return {part.strip() for part in hint.split("|")}
    return {getattr(arg, "__name__", str(arg)) for arg in (typing.get_args(hint) or (hint,))}


@pytest.fixture(scope="module")
def role_parameters() -> dict[tuple[str, str], set[str] | None]:
    """(function, parameter) -> the names in its annotation, over the core's modules."""
    found = {}
    for module in _core_modules():
        for qualname, fn in _callables(module):
            for parameter in inspect.signature(fn).parameters:
                if parameter in ROLE_PARAMETERS:
                    found[(qualname, parameter)] = _annotation_parts(fn, parameter)
    return found


def test_the_scan_reads_the_converted_signatures(role_parameters):
    # the scan must see the functions this change converted, else the checks below prove nothing
    for key in [
        ("rotorcad.working_chamber.ChamberTable.force_at", "rotor"),
        ("rotorcad.gas_load.line_loads", "rotor"),
        ("rotorcad.rotor_plotting.plot_point_deviation", "rotor"),
        ("rotorcad.screw_rotors.ScrewRotors.section", "rotor"),
        ("rotorcad.deflection.DeflectionLines.largest", "rotor"),
        ("rotorcad.deflection.GasDeflection.journal_length", "rotor"),
    ]:
        assert key in role_parameters, key
        assert "Side" in role_parameters[key], (key, role_parameters[key])


def test_no_rotor_parameter_is_annotated_as_text(role_parameters):
    as_text = sorted(
        f"{fn}({p})" for (fn, p), parts in role_parameters.items() if parts is not None and "str" in parts and "Side" not in parts
    )
    assert not as_text, f"a rotor passed as str in the core (take rotorcad.roles.Side): {as_text}"


def test_text_is_read_only_at_the_public_edge(role_parameters):
    either = {fn for (fn, _), parts in role_parameters.items() if parts is not None and {"Side", "str"} <= parts}
    assert either <= PUBLIC_EDGE, f"Side | str inside the core (take Side, convert at the edge): {sorted(either - PUBLIC_EDGE)}"


def test_one_flank_enum():
    # rotorcad.roles.Flank names the parts of a lobe; the coupling's loaded tooth flank has its own name
    flanks = {
        obj
        for module in _core_modules()
        for obj in vars(module).values()
        if inspect.isclass(obj) and issubclass(obj, enum.Enum) and obj.__name__ == "Flank"
    }
    assert flanks == {Flank}, [f"{f.__module__}.{f.__qualname__}" for f in flanks]
    assert Flank.DRIVING.value == "driving" and set(LoadedFlank) == {LoadedFlank.DRIVING, LoadedFlank.COAST}


def test_loaded_flank_is_the_sign_of_alpha_in_the_rolling_speed():
    # Belkov et al., Fig. 2: V_k = R_b omega sin(gamma) sin(omega t +- alpha), + on the driving flank
    c = GearCoupling(
        teeth=40,
        module=4.0,
        face_width=32.0,
        speed_rpm=8000.0,
        power_kw=4000.0,
        viscosity=0.02,
        pressure_viscosity=2e-8,
        misalignment=math.radians(0.3),
    )
    omega = 2 * math.pi * 8000.0 / 60.0
    amplitude = c.flank_radius * 1e-3 * omega * math.sin(math.radians(0.3))
    for flank, sign in ((LoadedFlank.DRIVING, 1.0), (LoadedFlank.COAST, -1.0)):
        psi, rolling, _, _ = c.speeds(73, flank)
        np.testing.assert_allclose(rolling, amplitude * np.sin(psi + sign * c.pressure_angle), rtol=1e-12, atol=1e-15)


@pytest.fixture(scope="module")
def rotors():
    return build_family(RotorPair(5, 6, 116.0, 63.0, 45.0, 71.0, 53.0), "rack-involute", {})


def test_section_reads_text_as_the_same_rotor(rotors):
    pair = rotors.pair
    for side, tip in ((Side.MALE, pair.male_tip_radius), (Side.FEMALE, pair.female_tip_radius)):
        by_enum, by_text = rotors.section(side, 0.01), rotors.section(side.value, 0.01)
        assert by_enum.is_valid and shapely.symmetric_difference(by_enum, by_text).area == 0.0
        assert by_text.area == pytest.approx(by_enum.area, rel=1e-15)
        # and it is that rotor: the section is clipped to its own tip circle (a closed form), and reaches it
        reach = np.hypot(*np.asarray(by_text.exterior.coords).T).max()
        assert tip - 0.05 < reach <= tip + 1e-6


def test_deflection_lines_read_text_as_the_same_rotor():
    # brute force on made-up lines: the largest |w| of each rotor's array, where and in which direction
    z = np.linspace(0.0, 100.0, 11)
    male = np.column_stack([np.sin(z / 30.0), np.zeros_like(z)])
    female = np.column_stack([np.zeros_like(z), -2.0 * np.cos(z / 40.0)])
    lines = DeflectionLines(0.0, z, male, female)
    i_m, i_f = np.argmax(np.hypot(*male.T)), np.argmax(np.hypot(*female.T))
    assert lines.largest("male") == lines.largest(Side.MALE) == pytest.approx((np.hypot(*male[i_m]), z[i_m], 0.0))
    assert lines.largest("female") == lines.largest(Side.FEMALE) == pytest.approx((2.0, z[i_f], 270.0))
    # without shaft ends the whole-shaft reading falls back to the helical part
    assert lines.largest(Side.FEMALE, shaft=True) == lines.largest(Side.FEMALE)


def test_an_unknown_rotor_is_refused_at_the_edge(rotors):
    with pytest.raises(ValueError, match="'left' is not a valid Side"):
        rotors.section("left")
