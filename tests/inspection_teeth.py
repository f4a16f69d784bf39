"""Gear teeth with known deviations, made for the inspection tests without rotorcad.inspection.

Each flank is an involute written from its definition (a string unwound from the base circle,
ISO 21771 eq. 2.21): tooth k's left flank leaves the base circle at the polar angle
phi_k + psi_b, psi_b = (pi / 2 + 2 x tan(alpha_n)) / z + inv(alpha_t); the point of roll length
xi is T + xi t, T the base-circle point at phi_k + psi_b - xi / r_b and t its unit tangent
(counter-clockwise), which is also the flank's outward normal. The right flank is the mirror
image about the tooth's centre line. A deviation d(xi) moves the point by d along that normal
(+ more material), so the flank's normal deviation at roll length xi is d(xi) by construction.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np


def inv(a: float | np.ndarray) -> float | np.ndarray:
    """The involute function tan(a) - a."""
    return np.tan(a) - a


def transverse(alpha_n: float, beta: float) -> float:
    """alpha_t = atan(tan(alpha_n) / cos(beta))."""
    return math.atan(math.tan(alpha_n) / math.cos(beta))


def teeth_points(
    z: int,
    m: float,
    alpha_n: float,
    teeth: list[int],
    roll: np.ndarray,
    *,
    beta: float = 0.0,
    shift: float = 0.0,
    deviation: Callable[[np.ndarray], np.ndarray] | None = None,
    rotation: float = 0.0,
    tooth_turns: dict[int, float] | None = None,
    alpha_actual: float | None = None,
    scatter: float = 0.0,
    seed: int = 1,
) -> np.ndarray:
    """Points of both flanks of ``teeth`` (mm), in a frame turned by ``rotation`` (rad).

    ``alpha_actual`` makes the teeth with another normal pressure angle (base radius
    r cos(alpha_t')) and the nominal arc thickness on the reference circle; ``tooth_turns`` turns
    chosen teeth by an angle (rad, counter-clockwise); ``scatter`` adds a uniform normal error in
    [-scatter, scatter] mm to every point.
    """
    rng = np.random.default_rng(seed)
    r = z * m / math.cos(beta) / 2.0
    at = transverse(alpha_n if alpha_actual is None else alpha_actual, beta)
    rb = r * math.cos(at)
    psi_b = (math.pi / 2 + 2 * shift * math.tan(alpha_n)) / z + inv(at)
    out = []
    for k in teeth:
        phi = 2 * math.pi * k / z + rotation + (tooth_turns or {}).get(k, 0.0)
        for s in (1, -1):
            t_angle = phi + s * (psi_b - roll / rb)
            normal = s * np.column_stack([-np.sin(t_angle), np.cos(t_angle)])
            p = rb * np.column_stack([np.cos(t_angle), np.sin(t_angle)]) + roll[:, None] * normal
            d = np.zeros_like(roll) if deviation is None else deviation(roll)
            if scatter:
                d = d + rng.uniform(-scatter, scatter, len(roll))
            out.append(p + d[:, None] * normal)
    return np.vstack(out)


__all__ = ["inv", "teeth_points", "transverse"]
