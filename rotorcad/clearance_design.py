"""Designed meshing clearance: a pair's female thinned by a clearance distribution.

The corrected rotors measure that clearance back (Wu & Chi, *Meshing clearance evaluation*,
eqs. 7 and 10: the clearance is the distance along the normal of the datum normal rack).

A clearance delta_n given in the normal section at a rack point of transverse flank angle alpha
(angle of the rack flank to the normal of the pitch line) is, in the transverse section, the
offset delta_t = delta_n sqrt(cos^2(alpha) / cos^2(beta) + sin^2(alpha)) of the female along its
transverse normal, beta the helix angle at the pitch cylinder: the normal rack is the transverse
rack with lengths along the pitch line times cos(beta), so its unit normal (cos alpha / cos beta,
sin alpha) / norm is the transverse one (cos alpha, sin alpha) stretched, and a transverse offset
delta_t moves the normal rack by delta_t / norm along its own normal.

The distribution is uniform, per flank (the driving flank where the rack rises, the sealing flank
where it falls, and the lands where the rack is flatter than 30 degrees to the pitch line, each
with its own value: a step where they meet, as a ground correction leaves it), or a table of
clearance over the datum rack's x (one rack period, interpolated periodically).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.envelope import conjugate, rack_frame
from rotorcad.errors import DesignError
from rotorcad.geometry import perp_cw
from rotorcad.screw_rotors import ScrewRotors

LAND_SLOPE = 0.5  # |sin| of the rack tangent's angle to the pitch line below which a point is a land's image


@dataclass(frozen=True)
class ClearanceDistribution:
    """Normal clearance to design, per flank or as a table over the rack.

    Parameters
    ----------
    driving, sealing, lands : float, mm
        Clearance (0 to 1 mm) on the driving flank (rack rising), the sealing flank (rack falling)
        and the lands (rack flatter than 30 degrees to the pitch line).
    table : tuple of (float, float), optional
        Rows (x, clearance), mm: x along the pitch line of the transverse rack in the rack frame of
        CONTRACT.md, over one rack period (interpolated periodically). When given, it replaces the
        per-flank values.

    Raises
    ------
    DesignError
        A clearance outside [0, 1] mm, or a table with fewer than two finite rows.
    """

    driving: float = 0.0
    sealing: float = 0.0
    lands: float = 0.0
    table: tuple[tuple[float, float], ...] | None = None

    def __post_init__(self) -> None:
        for name in ("driving", "sealing", "lands"):
            v = getattr(self, name)
            if not (np.isfinite(v) and 0.0 <= v <= 1.0):
                raise DesignError(f"clearance {name}", "a clearance from 0 to 1 mm", v)
        if self.table is not None:
            rows = np.asarray(self.table, dtype=float)
            if rows.ndim != 2 or rows.shape[1] != 2 or len(rows) < 2 or not np.all(np.isfinite(rows)):
                raise DesignError("clearance table", "at least two finite rows x,clearance", None)
            if np.any(rows[:, 1] < 0) or np.any(rows[:, 1] > 1.0):
                raise DesignError("clearance table", "clearances from 0 to 1 mm", None)

    @staticmethod
    def uniform(value: float) -> ClearanceDistribution:
        """Make a distribution with the same clearance everywhere.

        Parameters
        ----------
        value : float, mm
            The clearance on both flanks and the lands.

        Returns
        -------
        ClearanceDistribution
        """
        return ClearanceDistribution(value, value, value)

    @staticmethod
    def parse(text: str) -> ClearanceDistribution:
        """Read a distribution from its command-line text.

        Parameters
        ----------
        text : str
            ``0.05`` (uniform) or ``driving=0.03,sealing=0.05,lands=0.04`` (missing flanks 0), mm.

        Returns
        -------
        ClearanceDistribution

        Raises
        ------
        DesignError
            Text that is neither form, or a value out of range.
        """
        text = text.strip()
        try:
            if "=" not in text:
                return ClearanceDistribution.uniform(float(text))
            values = {}
            for part in text.split(","):
                key, _, value = part.partition("=")
                key = key.strip()
                if key not in ("driving", "sealing", "lands"):
                    raise DesignError("clearance", "a value or driving=, sealing=, lands= values in mm", text)
                values[key] = float(value)
            return ClearanceDistribution(**values)
        except ValueError:
            raise DesignError("clearance", "a value or driving=, sealing=, lands= values in mm", text) from None

    def at(self, x: np.ndarray, tangents: np.ndarray, period: float) -> np.ndarray:
        """Return the normal clearance at datum rack points.

        Parameters
        ----------
        x : (n,) float array, mm
            Positions along the pitch line, rack frame of CONTRACT.md.
        tangents : (n, 2) float array
            Unit tangents of the rack there, travelled in +x (their y part is the rise).
        period : float, mm
            Rack period p, for the table's periodic interpolation.

        Returns
        -------
        (n,) float array, mm
            The designed normal clearance delta_n.
        """
        if self.table is not None:
            rows = np.asarray(self.table, dtype=float)
            order = np.argsort(rows[:, 0])
            return np.interp(np.mod(x, period), rows[order, 0], rows[order, 1], period=period)
        rising = tangents[:, 1]
        return np.where(np.abs(rising) < LAND_SLOPE, self.lands, np.where(rising > 0, self.driving, self.sealing))


def corrected_female(rotors: ScrewRotors, clearance: ClearanceDistribution, tolerance: float = 1e-3) -> np.ndarray:
    """Thin the female outline by the designed normal clearance (module docstring).

    Each outline point's rack point (inverse generation by the envelope engine) gives its flank, its
    transverse flank angle alpha and its x on the datum rack; the point moves into the female by
    delta_t along its exact normal. Points without a rack point are left as they are.

    Parameters
    ----------
    rotors : ScrewRotors
        The pair as designed (without clearance).
    clearance : ClearanceDistribution
        The normal clearance to give.
    tolerance : float, mm
        Chord tolerance of the female outline.

    Returns
    -------
    (n, 2) float array, mm
        The thinned female outline, own frame at the mesh position, closed counter-clockwise.
    """
    pair = rotors.pair
    outline = rotors.female_outline(tolerance)
    pts, tan = outline.points, outline.tangents
    mesh = pair.mesh
    shift = np.array([pair.center_distance, 0.0])
    contact = conjugate(pts + shift, tan, mesh.female, mesh.rack, limits=(-pair.male_dedendum - 1e-6, pair.male_addendum + 1e-6))
    rack_pts = rack_frame(contact.points, pair.male_pitch_radius)
    rack_tan = np.stack([contact.tangents[:, 1], contact.tangents[:, 0]], axis=1)  # (y, x) of the fixed frame
    flip = np.where(rack_tan[:, 0] < 0, -1.0, 1.0)[:, None]  # travelled in +x
    rack_tan = rack_tan * flip
    beta = np.arctan(2 * np.pi * pair.male_pitch_radius / pair.lead)
    sin_a = np.abs(rack_tan[:, 0])  # the flank's angle to the normal of the pitch line: sin = |t_x|
    cos_a = np.abs(rack_tan[:, 1])
    delta_n = clearance.at(rack_pts[:, 0], rack_tan, pair.rack_period)
    delta_t = delta_n * np.sqrt(cos_a**2 / np.cos(beta) ** 2 + sin_a**2)
    delta_t = np.where(np.isfinite(delta_t), delta_t, 0.0)  # no rack point: left as it is
    return pts - delta_t[:, None] * perp_cw(tan)


__all__ = ["ClearanceDistribution", "corrected_female"]
