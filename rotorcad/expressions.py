"""Safe arithmetic expressions: a parsed :mod:`ast` tree walked by hand, never given to ``eval``.

Two kinds of user text are small formulas: linked design values (``female_tip_radius = "0.61*a"``,
:mod:`rotorcad.linked_values`, on floats) and a sweep's objectives (``{min = "blow_hole_area /
male_flute_area"}``, :mod:`rotorcad.sweep.ranking`, on numpy columns). Both accept numbers, names,
``+ - * / **``, unary signs, parentheses and calls of the functions their caller allows; nothing
else (no attribute access but a dotted name where the caller asks for it, no subscripts, no
keywords, no comparisons).
"""

from __future__ import annotations

import ast
import operator
from collections.abc import Callable, Mapping
from typing import Any

ARITHMETIC: dict[type, Callable[..., Any]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.Pow: operator.pow,
    ast.USub: operator.neg,
    ast.UAdd: operator.pos,
}
"""The operators an expression may use."""


def evaluate(
    node: ast.AST,
    lookup: Callable[[str], Any],
    functions: Mapping[str, Callable[..., Any]],
    *,
    dotted: bool = False,
    max_exponent: float | None = None,
) -> Any:
    """Evaluate an expression tree of numbers, names, :data:`ARITHMETIC` and the given functions.

    Parameters
    ----------
    node : ast.AST
        The tree (``ast.parse(text, mode="eval")`` or its body).
    lookup : callable
        The value of a name (raises for an unknown one).
    functions : mapping of str to callable
        The functions a call may name, with 1 to 8 positional arguments.
    dotted : bool
        Accept ``table.key`` as one name (a sweep's varied value, ``pair.center_distance``).
    max_exponent : float, optional
        Refuse a scalar exponent larger than this in magnitude (``9**9**9`` on Python integers
        would not end).

    Returns
    -------
    float or numpy array
        The value (numbers are taken as floats).

    Raises
    ------
    ValueError
        A construct that is not allowed, named by its text.
    """
    if isinstance(node, ast.Expression):
        return evaluate(node.body, lookup, functions, dotted=dotted, max_exponent=max_exponent)
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool):
        return float(node.value)
    if isinstance(node, ast.Name):
        return lookup(node.id)
    if dotted and isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
        return lookup(f"{node.value.id}.{node.attr}")

    def inner(child: ast.AST) -> Any:
        return evaluate(child, lookup, functions, dotted=dotted, max_exponent=max_exponent)

    if isinstance(node, ast.BinOp) and type(node.op) in ARITHMETIC:
        left, right = inner(node.left), inner(node.right)
        if isinstance(node.op, ast.Pow) and max_exponent is not None and isinstance(right, float) and abs(right) > max_exponent:
            raise ValueError(f"an exponent above {max_exponent:g}")
        return ARITHMETIC[type(node.op)](left, right)
    if isinstance(node, ast.UnaryOp) and type(node.op) in ARITHMETIC:
        return ARITHMETIC[type(node.op)](inner(node.operand))
    if (
        isinstance(node, ast.Call)
        and isinstance(node.func, ast.Name)
        and node.func.id in functions
        and not node.keywords
        and 1 <= len(node.args) <= 8
    ):
        return functions[node.func.id](*(inner(a) for a in node.args))
    raise ValueError(f"'{ast.unparse(node)}' is not allowed")
