"""The Examples in the docstrings run, so that what a newcomer copies from them works.

The top-level API's examples (``rotorcad/__init__.py``) check themselves against closed forms
written beside them: ISO 21771's base radius m z cos(alpha) / 2 and the working pressure angle from
inv(alpha_w) = inv(alpha) + 2 tan(alpha) (x1 + x2) / (z1 + z2); the pitch radius a / (1 + z2/z1)
and wrap angle 2 pi L / h of a screw-rotor pair; the displacement z1 (A1 + A2) L; the one-sentence
refusal of CONTRACT.md. Every other module whose docstrings hold an example is run as well.
"""

from __future__ import annotations

import doctest
import importlib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def modules_with_examples() -> list[str]:
    """Return the dotted names of the modules of the three packages with a ``>>>`` in their source."""
    names = []
    for package in ("rotorcad", "hob", "exports"):
        for path in sorted((ROOT / package).rglob("*.py")):
            if ">>> " in path.read_text():
                parts = path.relative_to(ROOT).with_suffix("").parts
                names.append(".".join(parts[:-1] if parts[-1] == "__init__" else parts))
    return names


def test_the_top_level_api_has_examples():
    """The package docstring shows the API at work (gears, rotors, Rinder's analysis, a refusal)."""
    import rotorcad

    examples = doctest.DocTestParser().get_examples(rotorcad.__doc__)
    assert len(examples) >= 10
    used = " ".join(e.source for e in examples)
    for name in ("InvoluteGear", "GearPair", "RotorPair", "build_family", "MeshingAnalysis", "DesignError"):
        assert name in used


@pytest.mark.parametrize("name", modules_with_examples())
def test_examples_run(name: str):
    """Each module's examples give what they print."""
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE, verbose=False)
    assert result.attempted > 0, f"{name}: no example found by doctest"
    assert result.failed == 0, f"{name}: {result.failed} of {result.attempted} examples failed (run python -m doctest -v)"
