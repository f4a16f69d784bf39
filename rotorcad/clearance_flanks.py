"""The meshing clearance per flank: which flank each datum rack point is on, and each flank's figures.

A per-flank designed clearance (``rotor --clearance driving=D,sealing=S,lands=L``,
:class:`rotorcad.clearance_design.ClearanceDistribution`) is read back per flank by the same split of
the datum (female) transverse rack: the driving flank where the rack rises (the male lobe's
trailing flank, Rinder sec. 1.2), the sealing flank where it falls, and the lands where the rack is
flatter than 30 degrees to the pitch line (|t_y| < :data:`rotorcad.clearance_design.LAND_SLOPE`,
t the rack's unit tangent travelled in +x): the male tip land on the female root (rack y > 0,
towards the female, CONTRACT.md rack frame) and the male root land under the female tip (y < 0).
Used by :class:`rotorcad.clearance.MeshingClearance`.
"""

from __future__ import annotations

import numpy as np

from rotorcad.clearance_design import LAND_SLOPE
from rotorcad.geometry import Array
from rotorcad.roles import Flank

FLANK_CODES: dict[Flank, int] = {Flank.DRIVING: 1, Flank.SEALING: 2, Flank.TIP: 3, Flank.ROOT: 4}
"""The ``flank`` column of ``rotorcad clearance --csv``: 1 driving, 2 sealing, 3 the male tip land
(on the female root), 4 the male root land (under the female tip); 0 where the rack has no tangent."""

FLANK_KEYS: dict[str, tuple[Flank, ...]] = {
    "driving": (Flank.DRIVING,),
    "sealing": (Flank.SEALING,),
    "lands": (Flank.TIP, Flank.ROOT),
}
"""The per-flank groups of the summary (``driving_...``, ``sealing_...``, ``lands_...`` keys), as
:class:`rotorcad.clearance_design.ClearanceDistribution` designs them."""


def flank_codes(points: Array, tangents: Array) -> Array:
    """Return the flank of each point of a transverse rack, as its :data:`FLANK_CODES` code.

    Parameters
    ----------
    points : (n, 2) float array, mm
        The rack points, CONTRACT.md rack frame (x along the pitch line, y > 0 towards the female).
    tangents : (n, 2) float array
        Their unit tangents, travelled in +x (the y part is the rise).

    Returns
    -------
    (n,) int array
        1 driving (rising), 2 sealing (falling), 3 tip land (flat, y > 0), 4 root land (flat, y <= 0),
        0 where the tangent is not finite.
    """
    rise = np.asarray(tangents, dtype=float)[:, 1]
    y = np.asarray(points, dtype=float)[:, 1]
    land = np.where(y > 0, FLANK_CODES[Flank.TIP], FLANK_CODES[Flank.ROOT])
    flank = np.where(rise > 0, FLANK_CODES[Flank.DRIVING], FLANK_CODES[Flank.SEALING])
    code = np.where(np.abs(rise) < LAND_SLOPE, land, flank)
    return np.where(np.isfinite(rise), code, 0).astype(int)


def flank_figures(clearance: Array, on: Array, codes: Array, weight: Array) -> dict[str, float | None]:
    """Return the contact zone's smallest, largest and mean normal clearance per flank.

    Parameters
    ----------
    clearance : (n,) float array, mm
        The normal clearance of the datum rack points (Wu & Chi eq. 10).
    on : (n,) bool array
        The points on the contact zone (:attr:`rotorcad.clearance.ClearanceZone.CONTACT`).
    codes : (n,) int array
        Their flanks (:func:`flank_codes`).
    weight : (n,) float array, mm
        Each point's share of the datum normal rack's length (half its two neighbouring steps), for the
        mean along the rack as ``mean_clearance`` takes it.

    Returns
    -------
    dict of float or None, mm
        ``{group}_min_normal_clearance``, ``{group}_max_normal_clearance`` and ``{group}_mean_clearance``
        for each group of :data:`FLANK_KEYS` (driving, sealing, lands); None where the group has no
        point on the contact zone.
    """
    out: dict[str, float | None] = {}
    for group, flanks in FLANK_KEYS.items():
        sel = on & np.isin(codes, [FLANK_CODES[f] for f in flanks]) & np.isfinite(clearance)
        values, w = clearance[sel], weight[sel]
        some = bool(sel.any())
        out[f"{group}_min_normal_clearance"] = float(values.min()) if some else None
        out[f"{group}_max_normal_clearance"] = float(values.max()) if some else None
        mean = float((values * w).sum() / w.sum()) if some and w.sum() > 0 else (float(values.mean()) if some else None)
        out[f"{group}_mean_clearance"] = mean
    return out


def point_weights(points: Array) -> Array:
    """Return each point's share of a polyline's length, (n,) float, mm: half of each step beside it.

    Parameters
    ----------
    points : (n, 2) float array, mm
        The polyline (the datum normal rack).

    Returns
    -------
    (n,) float array, mm
    """
    step = np.hypot(*np.diff(np.asarray(points, dtype=float), axis=0).T)
    return 0.5 * (np.concatenate([[0.0], step]) + np.concatenate([step, [0.0]]))


__all__ = ["FLANK_CODES", "FLANK_KEYS", "flank_codes", "flank_figures", "point_weights"]
