"""Points files (CONTRACT.md, "Points files"): CSV with the header ``x,y`` in mm, one point per
line in order along the curve, comment lines starting with ``#``."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorcad.errors import DesignError


def write_points(path: Path, points: np.ndarray, comments: list[str] | None = None, header: str = "x,y") -> None:
    """Write ``points`` (n, 2), or rows with the columns ``header`` names, to ``path`` with full
    double precision."""
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        for line in comments or []:
            f.write(f"# {line}\n")
        f.write(f"{header}\n")
        np.savetxt(f, np.asarray(points, dtype=float), delimiter=",", fmt="%.12g")


def read_points(path: Path, label: str = "points file") -> np.ndarray:
    """Read a points file; a malformed file is refused with one sentence naming it."""
    path = Path(path)
    if not path.is_file():
        raise DesignError(label, "an existing CSV file", str(path))
    rows: list[tuple[float, float]] = []
    header_seen = False
    with open(path, encoding="utf-8") as f:
        for number, raw in enumerate(f, start=1):
            line = raw.strip()
            if not line or line.startswith("#"):
                continue
            if not header_seen:
                if [c.strip().lower() for c in line.split(",")] != ["x", "y"]:
                    raise DesignError(
                        label, "a CSV whose first line is the header x,y", str(path), f"line {number} reads {line!r}"
                    )
                header_seen = True
                continue
            parts = line.split(",")
            try:
                if len(parts) != 2:
                    raise ValueError
                rows.append((float(parts[0]), float(parts[1])))
            except ValueError:
                raise DesignError(label, "two numbers x,y on every line", str(path), f"line {number} reads {line!r}") from None
    pts = np.array(rows, dtype=float).reshape(-1, 2)
    if len(pts) < 4 or not np.all(np.isfinite(pts)):
        raise DesignError(label, "at least 4 finite points", str(path), f"{len(pts)} points read")
    return pts
