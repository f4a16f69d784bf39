"""The one safe expression walker (rotorcad.expressions) of linked design values and sweep objectives.

Reference: Python's own arithmetic on the same text (``eval`` of a literal-only string in the test,
never in rotorcad), and numpy's on columns.
"""

from __future__ import annotations

import ast
import math

import numpy as np
import pytest

from rotorcad.expressions import evaluate

TEXTS = ["1 + 2 * 3", "-(4.5 - 1) ** 2 / 3", "2 ** 0.5 * +3", "sqrt(16) + max(1, 7, 3)"]


@pytest.mark.parametrize("text", TEXTS)
def test_arithmetic_is_pythons(text):
    functions = {"sqrt": math.sqrt, "max": max}
    expected = eval(text, {"__builtins__": {}}, functions)  # the test's reference: literals only
    assert evaluate(ast.parse(text, mode="eval"), lambda n: 0.0, functions) == pytest.approx(expected, rel=1e-15)


def test_columns_and_dotted_names():
    cols = {"a": np.array([1.0, 2.0]), "pair.lead": np.array([3.0, 4.0])}
    got = evaluate(ast.parse("a * pair.lead + 1", mode="eval"), cols.__getitem__, {}, dotted=True)
    np.testing.assert_array_equal(got, cols["a"] * cols["pair.lead"] + 1)


@pytest.mark.parametrize(
    "text", ["a.b", "x[0]", "(lambda: 1)()", "__import__('os')", "f(x=1)", "1 if a else 2", "a < 2", "'s' * 3"]
)
def test_anything_else_is_refused(text):
    with pytest.raises(ValueError, match="is not allowed"):
        evaluate(ast.parse(text, mode="eval"), lambda n: 1.0, {"f": abs})


def test_a_huge_exponent_is_refused_before_it_runs():
    with pytest.raises(ValueError, match="exponent above 64"):
        evaluate(ast.parse("9 ** 9 ** 9", mode="eval"), lambda n: 1.0, {}, max_exponent=64)
