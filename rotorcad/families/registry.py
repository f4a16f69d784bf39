"""The profile families by name: one line each, and the builder that checks a design's parameters.

A family is a builder ``build(pair, **params) -> ScrewRotors`` whose keywords are its ``[profile]``
parameters, each with its default and allowed range (:mod:`rotorcad.families.parameters`).
Adding a family is one module with its builder and one :func:`register` line below.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

from rotorcad.errors import DesignError
from rotorcad.families.checks import check_tips
from rotorcad.families.krigar import krigar
from rotorcad.families.lysholm import lysholm
from rotorcad.families.n_rack import n_rack
from rotorcad.families.narrow_tip import narrow_tip
from rotorcad.families.parameters import Param, parameters_of
from rotorcad.families.rack_involute import rack_involute
from rotorcad.families.srm_asymmetric import srm_asymmetric
from rotorcad.families.srm_b import srm_b
from rotorcad.families.srm_symmetric import srm_symmetric
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import ScrewRotors


class Family(NamedTuple):
    """A registered family: its builder and its ``[profile]`` parameters (read from the builder).

    A pair ``(build, params)``, so ``FAMILIES[name][1]`` is the parameters' schema.

    Parameters
    ----------
    build : callable
        ``build(pair, **params) -> ScrewRotors``.
    params : dict of str to Param
        :func:`~rotorcad.families.parameters.parameters_of` the builder.
    """

    build: Callable[..., ScrewRotors]
    params: dict[str, Param]


FAMILIES: dict[str, Family] = {}
"""The families by the name a design's ``[profile] family`` gives."""


def register(name: str, build: Callable[..., ScrewRotors]) -> Family:
    """Add a family under ``name``, its parameters read from the builder's signature.

    Parameters
    ----------
    name : str
        The name a design gives as ``[profile] family`` (lower case, words joined by "-").
    build : callable
        ``build(pair, **params) -> ScrewRotors``, defined at module level; every keyword has a
        default and an ``Annotated[float, Allowed(...)]`` range (:mod:`rotorcad.families.parameters`).

    Returns
    -------
    Family
        The entry added to :data:`FAMILIES`.

    Raises
    ------
    ValueError
        ``name`` already registered.
    """
    if name in FAMILIES:
        raise ValueError(f"a profile family {name!r} is registered already")
    FAMILIES[name] = family = Family(build, parameters_of(build))
    return family


register("krigar", krigar)
register("srm-symmetric", srm_symmetric)
register("lysholm", lysholm)
register("srm-asymmetric", srm_asymmetric)
register("srm-b", srm_b)
register("narrow-tip", narrow_tip)
register("rack-involute", rack_involute)
register("n-rack", n_rack)


def build_family(pair: RotorPair, family: str, params: dict[str, float]) -> ScrewRotors:
    """Construct a named family with checked parameters.

    The pair is refused when a rotor does not reach its tip radius
    (:func:`~rotorcad.families.checks.check_tips`).

    Parameters
    ----------
    pair : RotorPair
        Tooth counts, centre distance, radii, lead and length (mm).
    family : str
        A key of :data:`FAMILIES`.
    params : dict of str to float
        The family's ``[profile]`` parameters (each checked against its stated range).

    Returns
    -------
    ScrewRotors

    Raises
    ------
    DesignError
        An unknown family or key, a value out of its range, a rack the family cannot build, or a
        rotor short of its tip radius.
    """
    if family not in FAMILIES:
        raise DesignError("family", "one of " + ", ".join(sorted(FAMILIES)), family)
    fn, schema = FAMILIES[family]
    kwargs = {}
    for key, value in params.items():
        if key not in schema:
            allowed = ", ".join(sorted(schema)) or "none"
            raise DesignError(f"key '{key}' in [profile]", f"one of: {allowed} for the {family} family", None, "unknown key")
        if not schema[key].check(float(value)):
            raise DesignError(f"[profile] {key}", schema[key].allowed, value)
        kwargs[key] = float(value)
    rotors = fn(pair, **kwargs)
    check_tips(rotors)
    return rotors


__all__ = ["FAMILIES", "Family", "build_family", "register"]
