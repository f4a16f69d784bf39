"""Design files (TOML, CONTRACT.md "Design files"): reading and checking them.

Unknown keys are an error naming the key, so a typo never passes silently. Angles are given in
degrees in keys ending in ``_deg``.
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

from rotorcad.errors import DesignError

NUMBER = (int, float)

GEAR_KEYS: dict[str, type | tuple[type, ...]] = {
    "teeth": int,
    "module": NUMBER,
    "pressure_angle_deg": NUMBER,
    "helix_angle_deg": NUMBER,
    "shift": NUMBER,
    "addendum": NUMBER,
    "dedendum": NUMBER,
    "tip_radius": NUMBER,
}
MATE_KEYS: dict[str, type | tuple[type, ...]] = {"teeth": int, "shift": NUMBER, "center_distance": NUMBER}


def load_toml(path: Path) -> dict[str, Any]:
    """Read a TOML design file; a missing or malformed file is refused in one sentence."""
    path = Path(path)
    if not path.is_file():
        raise DesignError("design file", "an existing TOML file", str(path))
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except tomllib.TOMLDecodeError as exc:
        raise DesignError("design file", "valid TOML", str(path), str(exc)) from None


def check_table(
    data: dict[str, Any], table: str, keys: dict[str, type | tuple[type, ...]], required: tuple[str, ...] = ()
) -> dict[str, Any]:
    """Validate one table of a design: known keys, right types, required keys present."""
    section = data.get(table, {})
    if not isinstance(section, dict):
        raise DesignError(f"[{table}]", "a table of keys", type(section).__name__)
    for key, value in section.items():
        if key not in keys:
            raise DesignError(f"key '{key}' in [{table}]", "one of " + ", ".join(sorted(keys)), None, "unknown key")
        expected = keys[key]
        if isinstance(value, bool) or not isinstance(value, expected):
            kind = "a whole number" if expected is int else "a number"
            raise DesignError(f"[{table}] {key}", kind, repr(value))
    for key in required:
        if key not in section:
            raise DesignError(f"[{table}] {key}", "given", None, "missing key")
    return dict(section)


def load_gear_design(path: Path) -> dict[str, dict[str, Any]]:
    """A gear design: ``[gear]`` (required: teeth, module) and optional ``[mate]``."""
    data = load_toml(path)
    for table in data:
        if table not in ("gear", "mate"):
            raise DesignError(f"table [{table}]", "one of [gear], [mate] in a gear design", None, "unknown table")
    gear = check_table(data, "gear", GEAR_KEYS, required=("teeth", "module"))
    mate = check_table(data, "mate", MATE_KEYS) if "mate" in data else {}
    return {"gear": gear, "mate": mate}
