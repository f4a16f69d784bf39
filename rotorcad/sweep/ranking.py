"""Steering a sweep: constraints, objectives, the Pareto front and a ranking of the variants.

A sweep file may add::

    [constraints]                       # every one must hold for a variant to be feasible
    blow_hole_area_mm2 = "< 5"          # a result column with <, <=, >=, > or == and a number
    contact_line_length_mm = ["> 100", "<= 400"]   # several conditions on one column
    hobbable = true                     # a true/false column (hobbable, runs_without_timing_gears, ...)
    defects_jamming = "== 0"            # defects by kind: defects_cusp, defects_jamming, defects_slipping

    [objectives]                        # what is better: "min" or "max" of a column ...
    blow_hole_area_mm2 = "min"
    displacement_per_rev_mm3 = "max"
    specific_displacement = {max = "displacement_per_rev_mm3 / (male_volume_mm3 + female_volume_mm3)"}
    defects = "min"                     # defects count as the user states: an objective, a constraint, or not at all

A variant is *feasible* when it was built (``ok``) and meets every constraint. Among the feasible
ones, the *Pareto front* is the set no other feasible variant dominates (at least as good in every
objective and better in one; Deb, Multi-Objective Optimization using Evolutionary Algorithms,
2001, ch. 2). The *rank* orders the feasible variants: the front first, then the rest, each group
by the objectives in the order the file gives them (lexicographically); infeasible variants have
no rank. An objective's expression is parsed with
:mod:`ast` (numbers, result columns and varied values such as ``pair.center_distance``,
``+ - * / **``, parentheses and ``sqrt``, ``abs``, ``log``, ``exp``, ``minimum``, ``maximum``),
never given to ``eval``.
"""

from __future__ import annotations

import ast
import operator
import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from rotorcad.errors import DesignError
from rotorcad.expressions import evaluate

_COMPARISONS: dict[str, Callable[[Any, Any], Any]] = {
    "<=": operator.le,
    ">=": operator.ge,
    "==": operator.eq,
    "<": operator.lt,
    ">": operator.gt,
}
_CONDITION = re.compile(r"^\s*(<=|>=|==|<|>)\s*(\S+)\s*$")
_FUNCTIONS: dict[str, Callable[..., Any]] = {
    "sqrt": np.sqrt,
    "abs": np.abs,
    "log": np.log,
    "exp": np.exp,
    "minimum": np.minimum,
    "maximum": np.maximum,
}


@dataclass(frozen=True)
class Constraint:
    """One condition on a result column.

    Attributes
    ----------
    column : str
        The column.
    op : str
        One of ``<``, ``<=``, ``==``, ``>=``, ``>``.
    value : float or bool
        What the column is compared with.
    """

    column: str
    op: str
    value: float | bool

    def holds(self, table: pd.DataFrame) -> np.ndarray:
        """Return where the condition holds, (n,) bool (a missing value never meets it)."""
        values = table[self.column]
        if isinstance(self.value, bool):
            return (values.fillna(not self.value).astype(bool) == self.value).to_numpy()
        x = pd.to_numeric(values, errors="coerce").to_numpy(float)
        with np.errstate(invalid="ignore"):
            return np.asarray(_COMPARISONS[self.op](x, self.value)) & np.isfinite(x)


@dataclass(frozen=True)
class Objective:
    """What is better: the smallest or the largest value of a column or an expression of columns.

    Attributes
    ----------
    name : str
        The objective's name (the column's, or the key of ``[objectives]``).
    smaller : bool
        Whether smaller is better.
    expression : str
        The column or the expression of columns.
    """

    name: str
    smaller: bool
    expression: str

    def values(self, table: pd.DataFrame) -> np.ndarray:
        """Evaluate the objective for every row, (n,) float (NaN where it cannot be computed)."""
        tree = ast.parse(self.expression, mode="eval")
        with np.errstate(all="ignore"):
            out = _evaluate(tree.body, lambda c: pd.to_numeric(table[c], errors="coerce").to_numpy(float))
        return np.broadcast_to(np.asarray(out, dtype=float), (len(table),)).copy()


def _evaluate(node: ast.AST, column: Callable[[str], np.ndarray]) -> Any:
    """Evaluate an objective's tree on the table's columns (a varied value by its dotted name)."""
    return evaluate(node, column, _FUNCTIONS, dotted=True)


def _names(node: ast.AST) -> list[str]:
    attributes = [n for n in ast.walk(node) if isinstance(n, ast.Attribute) and isinstance(n.value, ast.Name)]
    dotted = {id(n.value) for n in attributes}
    names = [n.id for n in ast.walk(node) if isinstance(n, ast.Name) and id(n) not in dotted and not _is_function(node, n)]
    return names + [f"{n.value.id}.{n.attr}" for n in attributes]


def _is_function(tree: ast.AST, name: ast.Name) -> bool:
    return any(isinstance(c, ast.Call) and c.func is name for c in ast.walk(tree))


@dataclass(frozen=True)
class Steering:
    """The constraints and objectives of a sweep file.

    Attributes
    ----------
    constraints : tuple of Constraint
    objectives : tuple of Objective
    """

    constraints: tuple[Constraint, ...] = ()
    objectives: tuple[Objective, ...] = ()

    def apply(self, table: pd.DataFrame) -> pd.DataFrame:
        """Add the columns ``feasible``, the objectives' values (``objective.NAME`` for an expression), ``pareto`` and ``rank``.

        Parameters
        ----------
        table : pandas.DataFrame
            The sweep's table.

        Returns
        -------
        pandas.DataFrame
            A copy with ``feasible`` (bool: built and every constraint met), ``pareto`` (bool: on
            the front of the feasible variants in the objectives; all feasible variants when there
            is no objective) and ``rank`` (1 = best; 0 for an infeasible variant).
        """
        table = table.copy()
        n = len(table)
        feasible = table["ok"].astype(bool).to_numpy() if n else np.zeros(0, bool)
        for c in self.constraints:
            feasible = feasible & c.holds(table)
        table["feasible"] = feasible
        scores = []
        for objective in self.objectives:
            values = objective.values(table)
            if objective.expression != objective.name:
                table[f"objective.{objective.name}"] = values
            scores.append(values if objective.smaller else -values)
        cost = np.column_stack(scores) if scores else np.zeros((n, 0))
        usable = feasible & np.all(np.isfinite(cost), axis=1)
        front = np.zeros(n, bool)
        front[usable] = pareto_front(cost[usable])
        table["pareto"] = front
        rank = np.zeros(n, dtype=np.int64)
        order = np.lexsort([*(cost[usable][:, k] for k in range(cost.shape[1] - 1, -1, -1)), ~front[usable]])
        rank[np.flatnonzero(usable)[order]] = np.arange(1, usable.sum() + 1)
        table["rank"] = rank
        return table


def pareto_front(cost: np.ndarray) -> np.ndarray:
    """Select the rows no other row dominates (smaller is better in every column).

    Row j dominates row i when ``cost[j] <= cost[i]`` in every column and ``<`` in one. The rows
    are taken in order of their sum (a dominating row has a smaller sum), each compared with the
    front found so far: O(n x front size), numpy-vectorised over the front.

    Parameters
    ----------
    cost : (n, k) float array
        Finite costs, smaller better.

    Returns
    -------
    (n,) bool array
    """
    n = len(cost)
    out = np.zeros(n, bool)
    if n == 0:
        return out
    if cost.shape[1] == 0:
        out[:] = True
        return out
    order = np.lexsort([*(cost[:, k] for k in range(cost.shape[1] - 1, -1, -1)), cost.sum(axis=1)])
    front: list[int] = []
    block = np.empty((0, cost.shape[1]))
    for i in order:
        c = cost[i]
        if len(front) and np.any(np.all(block <= c, axis=1) & np.any(block < c, axis=1)):
            continue
        front.append(i)
        block = cost[front]
    out[front] = True
    return out


def _condition(column: str, spec: Any, label: str) -> list[Constraint]:
    if isinstance(spec, bool):
        return [Constraint(column, "==", spec)]
    specs = spec if isinstance(spec, list) else [spec]
    out = []
    for text in specs:
        m = _CONDITION.match(text) if isinstance(text, str) else None
        try:
            value = float(m.group(2)) if m else None
        except ValueError:
            value = None
        if m is None or value is None or not np.isfinite(value):
            raise DesignError(label, 'true, false, or a condition such as "< 5", "<= 2.5", "== 0", ">= 100", "> 0"', repr(text))
        out.append(Constraint(column, m.group(1), value))
    return out


def steering(data: dict[str, Any], numeric: list[str], boolean: list[str]) -> Steering:
    """Read ``[constraints]`` and ``[objectives]`` of a sweep file, checked against the sweep's columns.

    Parameters
    ----------
    data : dict
        The sweep file as TOML holds it.
    numeric : list of str
        The number columns of the sweep's table (:func:`rotorcad.sweep.tasks.result_columns`, the
        defect counts by kind, the varied values).
    boolean : list of str
        Its true/false columns.

    Returns
    -------
    Steering

    Raises
    ------
    DesignError
        Naming ``[constraints] KEY`` or ``[objectives] KEY``: a column the sweep does not make, a
        malformed condition, a direction other than min/max, or an expression other than arithmetic
        of columns.
    """
    constraints: list[Constraint] = []
    for column, spec in _table(data, "constraints").items():
        label = f"[constraints] {column}"
        if column in boolean:
            if not isinstance(spec, bool):
                raise DesignError(label, f"true or false ({column} is a true/false column)", repr(spec))
            constraints.append(Constraint(column, "==", spec))
        elif column in numeric:
            if isinstance(spec, bool):
                raise DesignError(label, f'a condition such as "< 5" ({column} is a number)', repr(spec))
            constraints += _condition(column, spec, label)
        else:
            raise DesignError(label, "a column of this sweep: " + ", ".join([*numeric, *boolean]), None, "unknown column")
    objectives: list[Objective] = []
    for name, spec in _table(data, "objectives").items():
        label = f"[objectives] {name}"
        if isinstance(spec, str):
            direction, expression = spec, name
        elif isinstance(spec, dict) and len(spec) == 1:
            direction, expression = next(iter(spec.items()))
        else:
            direction, expression = None, None
        if direction not in ("min", "max") or not isinstance(expression, str):
            raise DesignError(label, '"min" or "max" of a column, or {min = "EXPRESSION"} / {max = "EXPRESSION"}', repr(spec))
        try:
            tree = ast.parse(expression, mode="eval")
            with np.errstate(all="ignore"):
                _evaluate(tree.body, lambda c: np.ones(1))
        except (SyntaxError, ValueError, TypeError) as exc:
            allowed = "a column or an expression of columns with numbers, + - * / ** ( ) and " + ", ".join(_FUNCTIONS)
            raise DesignError(label, allowed, repr(expression), str(exc)) from None
        unknown = [c for c in _names(tree) if c not in numeric]
        if unknown:
            raise DesignError(label, "of number columns of this sweep: " + ", ".join(numeric), repr(unknown[0]), "unknown column")
        objectives.append(Objective(name, direction == "min", expression))
    return Steering(tuple(constraints), tuple(objectives))


def _table(data: dict[str, Any], name: str) -> dict[str, Any]:
    table = data.get(name, {})
    if not isinstance(table, dict):
        raise DesignError(f"[{name}]", "a table of column = condition (or direction)", repr(table))
    return table


__all__ = ["Constraint", "Objective", "Steering", "pareto_front", "steering"]
