"""A family's ``[profile]`` parameters, declared once: in its builder's signature.

Each parameter of a family is a keyword of its builder, with its default and, in its annotation,
the range a design may give (:class:`Allowed`)::

    def krigar(pair: RotorPair, tip_land: TipLand = 0.0) -> ScrewRotors: ...

:func:`parameters_of` reads them back as the family's schema (:class:`Param`: default, the
sentence a message names, the check), which the design files, the sweep and the report use.
Declare the builder at module level: its annotations are evaluated in the module's namespace.
"""

from __future__ import annotations

import inspect
import math
import typing
from collections.abc import Callable
from dataclasses import dataclass
from typing import Annotated


@dataclass(frozen=True)
class Allowed:
    """The range a ``[profile]`` value may take: the words a refusal names and the test.

    Parameters
    ----------
    text : str
        What the value must be, phrased to follow "must be" (e.g. "between 5 and 60 degrees").
    check : callable
        ``check(value) -> bool`` for one float value.
    """

    text: str
    check: Callable[[float], bool]


def between(low: float, high: float, text: str) -> Allowed:
    """Return the range low <= value <= high (finite), worded as ``text``.

    Parameters
    ----------
    low, high : float
        The ends, both allowed.
    text : str
        The words of a refusal (see :class:`Allowed`).

    Returns
    -------
    Allowed
    """
    return Allowed(text, lambda v: bool(math.isfinite(v) and low <= v <= high))


def at_least(low: float, text: str) -> Allowed:
    """Return the range value >= low (finite), worded as ``text``.

    Parameters
    ----------
    low : float
        The least value, allowed.
    text : str
        The words of a refusal (see :class:`Allowed`).

    Returns
    -------
    Allowed
    """
    return Allowed(text, lambda v: bool(math.isfinite(v) and v >= low))


# ranges shared by several families
TipLand = Annotated[float, at_least(0.0, "a finite length of at least 0 mm")]
"""The male tip land along the rack, mm."""
FLANK_ANGLE = between(5.0, 60.0, "between 5 and 60 degrees")
FlankAngle = Annotated[float, FLANK_ANGLE]
"""An angle of a rack flank or of a driving arc's foot, degrees."""
SealStop = Annotated[float, between(0.1, 0.99, "between 0.1 and 0.99 (share of the tip corner's sweep to the cusp)")]
"""The share of the male tip corner's sweep to the housing cusp that generates the female sealing flank."""


@dataclass(frozen=True)
class Param:
    """One ``[profile]`` parameter of a family, as :func:`parameters_of` reads it.

    Parameters
    ----------
    default : float or None
        The builder's default (None: not given unless the design gives it).
    allowed : str
        What the value must be, for a refusal (:attr:`Allowed.text`).
    check : callable
        ``check(value) -> bool``.
    """

    default: float | None
    allowed: str
    check: Callable[[float], bool]


def parameters_of(build: Callable[..., object]) -> dict[str, Param]:
    """Return the ``[profile]`` parameters a family's builder declares in its signature.

    Every parameter after the first (the :class:`~rotorcad.rotor_pair.RotorPair`) is one: a
    keyword with a default, annotated ``Annotated[float, Allowed(...)]`` (or ``float | None``).

    Parameters
    ----------
    build : callable
        The builder, ``build(pair, **params) -> ScrewRotors``, defined at module level.

    Returns
    -------
    dict of str to Param
        In the signature's order.

    Raises
    ------
    TypeError
        A parameter without a default or without an :class:`Allowed` range (a programming error
        in the family's module, not a design's).
    """
    hints = typing.get_type_hints(build, include_extras=True)
    out: dict[str, Param] = {}
    for name, p in list(inspect.signature(build).parameters.items())[1:]:
        allowed = [m for m in getattr(hints.get(name), "__metadata__", ()) if isinstance(m, Allowed)]
        if p.default is inspect.Parameter.empty or len(allowed) != 1:
            raise TypeError(f"{build.__qualname__}: parameter {name!r} needs a default and one Allowed range in its annotation")
        out[name] = Param(p.default, allowed[0].text, allowed[0].check)
    return out


__all__ = ["FLANK_ANGLE", "Allowed", "FlankAngle", "Param", "SealStop", "TipLand", "at_least", "between", "parameters_of"]
