"""Linked design values: radii and lengths stated as expressions of the centre distance and tooth counts.

A design may give a [pair], [profile] or [housing] number as a short formula in a string, so that
a sweep over the centre distance or the tooth counts keeps the proportions::

    [pair]
    male_teeth = 5
    female_teeth = 6
    center_distance = 116.0
    male_tip_radius = "r1w + 0.487*m"
    male_root_radius = "r1w - 0.367*m"
    female_tip_radius = "a - male_root_radius"
    female_root_radius = "a - male_tip_radius"
    lead = "2.6*a"

The names an expression may use:

* ``a`` -- the centre distance (mm), ``z1`` and ``z2`` -- the male and female tooth counts;
* ``m = 2 a / (z1 + z2)`` -- the module-like scale of the pair (mm), ``r1w = a z1 / (z1 + z2)`` and
  ``r2w = a z2 / (z1 + z2)`` -- the pitch radii (mm; Rinder sec. 1.1, the rolling circles);
* every other number of [pair] by its key (``male_tip_radius``, ``lead``, ...), itself possibly an
  expression (a cycle is refused);
* ``pi``, and the functions ``sqrt``, ``sin``, ``cos``, ``tan`` (radians), ``radians``, ``degrees``,
  ``abs``, ``min``, ``max``.

Only numbers, these names, ``+ - * / **`` and parentheses are accepted: the text is parsed with
:mod:`ast` and the tree walked here, never given to ``eval``. The tooth counts and the centre
distance themselves are numbers (they are what the others follow).
"""

from __future__ import annotations

import ast
import math
from collections.abc import Callable
from typing import Any

import numpy as np

from rotorcad.errors import DesignError
from rotorcad.expressions import evaluate

LINKED_TABLES = ("pair", "profile", "housing")
"""Tables whose numbers may be expressions."""

FIXED_KEYS = ("male_teeth", "female_teeth", "center_distance", "hand")
"""[pair] keys that must be plain values: the quantities the others follow."""

FUNCTIONS: dict[str, Callable[..., float]] = {
    "sqrt": math.sqrt,
    "sin": math.sin,
    "cos": math.cos,
    "tan": math.tan,
    "radians": math.radians,
    "degrees": math.degrees,
    "abs": abs,
    "min": min,
    "max": max,
}
MAX_EXPRESSION_CHARS = 200
ALLOWED = (
    "a number or an expression of a, z1, z2, m, r1w, r2w and the [pair] lengths with numbers, + - * / ** ( ), pi, "
    + ", ".join(FUNCTIONS)
)


def base_quantities(pair: dict[str, Any]) -> dict[str, float]:
    """Return the named quantities an expression may use that follow from a, z1, z2.

    Parameters
    ----------
    pair : dict
        The [pair] table (``center_distance``, ``male_teeth``, ``female_teeth`` as numbers).

    Returns
    -------
    dict of str to float
        ``a``, ``z1``, ``z2`` and ``m = 2 a / (z1 + z2)``, ``r1w = a z1 / (z1 + z2)``,
        ``r2w = a z2 / (z1 + z2)`` (mm), ``pi``.

    Raises
    ------
    DesignError
        When a, z1 or z2 is not a plain positive number.
    """
    values = {}
    for key, name in (("center_distance", "a"), ("male_teeth", "z1"), ("female_teeth", "z2")):
        v = pair.get(key)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not (np.isfinite(v) and v > 0):
            raise DesignError(f"[pair] {key}", f"a positive number when other values are expressions of {name}", repr(v))
        values[name] = float(v)
    a, z1, z2 = values["a"], values["z1"], values["z2"]
    return {**values, "m": 2 * a / (z1 + z2), "r1w": a * z1 / (z1 + z2), "r2w": a * z2 / (z1 + z2), "pi": math.pi}


def _evaluate(node: ast.AST, lookup: Callable[[str], float]) -> float:
    """Walk an expression tree of numbers, names, the arithmetic operators and :data:`FUNCTIONS`."""
    return float(evaluate(node, lookup, FUNCTIONS, max_exponent=64))


def evaluate_expression(text: str, names: dict[str, float], label: str) -> float:
    """Evaluate one expression with the given names (no ``eval``: an :mod:`ast` walk).

    Parameters
    ----------
    text : str
        The expression, e.g. ``"0.61*a"``.
    names : dict of str to float
        The quantities it may use.
    label : str
        ``[table] key``, for the refusal.

    Returns
    -------
    float
        A finite number.

    Raises
    ------
    DesignError
        Text that is not such an expression, an unknown name, or a result that is not finite.
    """
    return _Resolver({}, names).value_of(text, label)


class _Resolver:
    """Resolve the expressions of [pair] (which may refer to each other) and of the other tables."""

    def __init__(self, pair: dict[str, Any], names: dict[str, float]) -> None:
        self.pair = pair
        self.names = names
        self.done: dict[str, float] = {}
        self.busy: list[str] = []

    def lookup(self, name: str) -> float:
        if name in self.names:
            return self.names[name]
        if name in self.done:
            return self.done[name]
        if name in self.pair and name not in FIXED_KEYS:
            if name in self.busy:
                raise ValueError("a cycle: " + " -> ".join([*self.busy, name]))
            value = self.pair[name]
            if isinstance(value, str):
                self.busy.append(name)
                try:
                    value = self.value_of(value, f"[pair] {name}")
                finally:
                    self.busy.pop()
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise ValueError(f"{name} is not a number")
            self.done[name] = float(value)
            return self.done[name]
        raise ValueError(f"unknown name '{name}'")

    def value_of(self, text: str, label: str) -> float:
        if len(text) > MAX_EXPRESSION_CHARS:
            raise DesignError(label, ALLOWED + f" of at most {MAX_EXPRESSION_CHARS} characters", None)
        try:
            tree = ast.parse(text.strip(), mode="eval")
            value = _evaluate(tree, self.lookup)
        except DesignError:
            raise
        except SyntaxError:
            raise DesignError(label, ALLOWED, repr(text), "not an expression") from None
        except (ValueError, ZeroDivisionError, OverflowError, TypeError) as exc:
            raise DesignError(label, ALLOWED, repr(text), str(exc) or type(exc).__name__) from None
        if not np.isfinite(value):
            raise DesignError(label, ALLOWED + " with a finite value", repr(text), f"it gives {value}")
        return value


def has_expressions(data: dict[str, Any]) -> bool:
    """Tell whether a design mapping states any value as an expression (a string in a numeric place).

    Parameters
    ----------
    data : dict
        The design as a TOML file holds it.

    Returns
    -------
    bool
    """
    for table in LINKED_TABLES:
        section = data.get(table)
        if isinstance(section, dict):
            for key, value in section.items():
                if isinstance(value, str) and key not in ("hand", "family", "points"):
                    return True
    return False


def resolve_expressions(data: dict[str, Any]) -> dict[str, Any]:
    """Replace every expression of a design mapping by its value.

    Parameters
    ----------
    data : dict
        The design as a TOML file holds it ([pair] with a, z1, z2 as numbers).

    Returns
    -------
    dict
        The same mapping when it has no expression; else a copy with numbers in their place
        (tables copied, the input kept as it is).

    Raises
    ------
    DesignError
        Naming ``[table] key`` of an expression that cannot be evaluated (unknown name, a cycle,
        a construct other than arithmetic, a value that is not finite) or a fixed key
        (:data:`FIXED_KEYS`) given as an expression.
    """
    if not has_expressions(data):
        return data
    pair = data.get("pair", {})
    if not isinstance(pair, dict):
        return data  # the design check names a [pair] that is not a table
    for key in FIXED_KEYS[:3]:
        if isinstance(pair.get(key), str):
            allowed = "a number (the other values follow it; it cannot be an expression)"
            raise DesignError(f"[pair] {key}", allowed, repr(pair[key]))
    resolver = _Resolver(pair, base_quantities(pair))
    out = {table: dict(content) if isinstance(content, dict) else content for table, content in data.items()}
    for table in LINKED_TABLES:
        section = out.get(table)
        if not isinstance(section, dict):
            continue
        for key, value in section.items():
            if not isinstance(value, str) or key in ("hand", "family", "points"):
                continue
            if table == "pair":
                resolver.busy = [key]
                section[key] = resolver.value_of(value, f"[pair] {key}")
                resolver.done[key] = section[key]
                resolver.busy = []
            else:
                section[key] = resolver.value_of(value, f"[{table}] {key}")
    return out


__all__ = ["FUNCTIONS", "base_quantities", "evaluate_expression", "has_expressions", "resolve_expressions"]
