"""Meshing clearance evaluation (MCE) of a screw-rotor pair from discrete profile points.

After Wu & Chi, *A numerical method for the evaluation of the meshing clearance for twin screw
rotors with discrete tooth profile points* (Mech. Mach. Theory 70, 2013).

1. Each rotor's points are fitted with a cubic spline (sec. 2, eq. 1), so tangents are exact.
2. Each lobe gives its transverse rack by inverse generation (eqs. 2-6: the rack point of a
   profile point is where its normal passes the pitch point), and the normal rack is the
   transverse rack with lengths along the pitch line times cos(beta) (eq. 7), beta the helix
   angle at the pitch cylinder, the same for both rotors (h2 = h1 z2/z1).
3. The racks are positioned against each other (sec. 4: "an initial contact point"): the female
   rack slides along the pitch line until the two racks touch on the driving flank (or the
   sealing flank, or they are left as the points were given).
4. The normal clearance delta of each point of the datum rack (the female's) is its distance,
   along its own normal, to the compared rack (the male's): r_n2 + delta n_n2 = r_n1(u) (eq. 10).
   Positive is a gap, negative an interference. The male rack is evaluated between its samples
   by cubic Hermite interpolation with its exact tangents.
5. The clearance is distributed on the 3D contact line (sec. 3.2): every datum rack point whose
   contact lies inside both bores is a contact point (x, y) at male angle phi, z = h1 phi / 2 pi
   (Rinder eq. 1), cut at the rotor length as in :mod:`rotorcad.meshing`. The clearance band is
   the strip between the contact line and the line offset from it by max(delta, 0) along the
   helical surfaces' unit normal; its area and perimeter (the wetted perimeter) are those of the
   triangulated strip.

Means (both are in the paper, sec. 5.2): ``mean_clearance`` is delta averaged along the datum
normal rack (the paper's average over its contact points, which are spread along the rack), and
``equal_clearance`` is the band area over the contact line length.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
from scipy.spatial import cKDTree

from rotorcad.curves import Curve, Mapped
from rotorcad.errors import DesignError
from rotorcad.geometry import Array, cross, rotate
from rotorcad.inverse_rack import MEASURED_MIN_TURN, DerivedRack, contact_of_rack_points, rotor_rack
from rotorcad.roles import Side
from rotorcad.roots import bracket_root
from rotorcad.rotor_pair import RotorPair

CONTACT_SIDES = ("driving", "sealing", "as-given")


def _hermite(p0: Array, t0: Array, p1: Array, t1: Array, tau: Array) -> tuple[Array, Array]:
    """Evaluate the cubic Hermite point and derivative between samples with exact unit tangents.

    The tangents are scaled by the chord. ``p0``, ``t0``, ``p1``, ``t1`` are (n, 2), ``tau`` (n,) in
    [0, 1]; returns the points and the derivatives d/dtau, both (n, 2).
    """
    h = np.hypot(*(p1 - p0).T)[:, None]
    m0, m1 = t0 * h, t1 * h
    u = tau[:, None]
    p = (2 * u**3 - 3 * u**2 + 1) * p0 + (u**3 - 2 * u**2 + u) * m0 + (-2 * u**3 + 3 * u**2) * p1 + (u**3 - u**2) * m1
    d = (6 * u**2 - 6 * u) * p0 + (3 * u**2 - 4 * u + 1) * m0 + (-6 * u**2 + 6 * u) * p1 + (3 * u**2 - 2 * u) * m1
    return p, d


def normal_clearance(datum: Array, normals: Array, compared: Array, compared_tangents: Array, window: int = 8) -> Array:
    """Measure from each datum point along its unit normal to the compared polyline (Wu & Chi eq. 10).

    The crossing nearest the datum point is taken among the ``window`` segments either side of the
    nearest compared point, then refined on the Hermite cubic of that segment (Newton).

    Parameters
    ----------
    datum : (n, 2) float array, mm
        Points of the datum rack.
    normals : (n, 2) float array
        Their unit normals (positive clearance along them).
    compared : (m, 2) float array, mm
        The compared rack as a polyline.
    compared_tangents : (m, 2) float array
        Its exact unit tangents at the vertices.
    window : int
        Segments searched either side of the nearest compared vertex.

    Returns
    -------
    (n,) float array, mm
        Signed distance delta with datum + delta normal on the compared rack (positive a gap,
        negative an interference); NaN where the normal line does not cut it nearby.
    """
    k = cKDTree(compared).query(datum)[1]
    n_seg = len(compared) - 1
    offsets = np.arange(-window, window)
    seg = np.clip(k[:, None] + offsets[None, :], 0, n_seg - 1)  # segment i joins points i, i+1
    a, b = compared[seg], compared[seg + 1]
    g_a = cross(normals[:, None, :], a - datum[:, None, :])
    g_b = cross(normals[:, None, :], b - datum[:, None, :])
    with np.errstate(divide="ignore", invalid="ignore"):
        tau = g_a / (g_a - g_b)
    hit = (g_a * g_b <= 0) & np.isfinite(tau)
    cut = a + np.nan_to_num(tau)[..., None] * (b - a)
    delta = np.einsum("ijk,ik->ij", cut - datum[:, None, :], normals)
    delta = np.where(hit, delta, np.inf)
    j = np.argmin(np.abs(delta), axis=1)
    rows = np.arange(len(datum))
    found = np.isfinite(delta[rows, j])
    s = seg[rows, j]
    u = np.clip(np.nan_to_num(tau[rows, j]), 0.0, 1.0)
    p0, p1, t0, t1 = compared[s], compared[s + 1], compared_tangents[s], compared_tangents[s + 1]
    for _ in range(4):  # Newton on cross(n, H(u) - datum) = 0
        p, d = _hermite(p0, t0, p1, t1, u)
        f = cross(normals, p - datum)
        df = cross(normals, d)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(np.abs(df) > 1e-300, f / df, 0.0)
        u = np.clip(u - step, 0.0, 1.0)
    p, _ = _hermite(p0, t0, p1, t1, u)
    return np.where(found, np.einsum("ij,ij->i", p - datum, normals), np.nan)


@dataclass(frozen=True)
class ThermalState:
    """Rotors and housing at working temperature.

    After the Chinese paper in Wu & Chi's seed (sec. 1.2): a body grows by dL = L zeta (t_c - t0)
    (its eq. 1); the rotor's computation temperature is the arithmetic mean of suction and discharge
    temperature, and the centre distance follows the housing.

    Parameters
    ----------
    suction_temperature, discharge_temperature : float, degC
        Gas temperatures at suction and discharge.
    reference_temperature : float, degC
        Temperature at which the design's dimensions hold.
    rotor_expansion : float, 1/K
        Linear expansion coefficient of the rotors (default steel, 11.5e-6).
    housing_expansion : float, 1/K
        Linear expansion coefficient of the housing (default grey cast iron, 10.5e-6).
    housing_temperature : float, degC, optional
        Housing temperature; default the rotors' computation temperature.

    Raises
    ------
    DesignError
        A temperature at or below absolute zero, or an expansion coefficient outside [0, 0.001) 1/K.
    """

    suction_temperature: float
    discharge_temperature: float
    reference_temperature: float = 20.0
    rotor_expansion: float = 11.5e-6  # steel
    housing_expansion: float = 10.5e-6  # grey cast iron
    housing_temperature: float | None = None  # default: the rotors' computation temperature

    def __post_init__(self) -> None:
        for name in ("suction_temperature", "discharge_temperature", "reference_temperature"):
            v = getattr(self, name)
            if not (np.isfinite(v) and v > -273.15):
                raise DesignError(name, "a temperature above absolute zero in degC", v)
        for name in ("rotor_expansion", "housing_expansion"):
            v = getattr(self, name)
            if not (np.isfinite(v) and 0.0 <= v < 1e-3):
                raise DesignError(name, "a linear expansion coefficient from 0 to 0.001 per K", v)

    @property
    def rotor_temperature(self) -> float:
        """Rotor computation temperature, the mean of suction and discharge temperature, degC."""
        return 0.5 * (self.suction_temperature + self.discharge_temperature)

    @property
    def rotor_scale(self) -> float:
        """Growth factor of the rotors, 1 + zeta_rotor (t_rotor - t_ref)."""
        return 1.0 + self.rotor_expansion * (self.rotor_temperature - self.reference_temperature)

    @property
    def housing_scale(self) -> float:
        """Growth factor of the housing (and so of the centre distance), 1 + zeta_housing (t_housing - t_ref)."""
        t = self.rotor_temperature if self.housing_temperature is None else self.housing_temperature
        return 1.0 + self.housing_expansion * (t - self.reference_temperature)

    def apply(self, pair: RotorPair, male: Array, female: Array) -> tuple[RotorPair, Array, Array]:
        """Return the hot pair and the hot profile points.

        Each rotor grows about its own axis, the lead and the length with it; the centre distance grows
        with the housing.

        Parameters
        ----------
        pair : RotorPair
            The cold pair.
        male, female : (n, 2) float array or list of Curve, mm
            Profile points (or exact curves) of each rotor in its own frame.

        Returns
        -------
        tuple of (RotorPair, male, female)
            The hot pair and both profiles scaled by :attr:`rotor_scale`.
        """
        k = self.rotor_scale
        hot = replace(
            pair,
            center_distance=pair.center_distance * self.housing_scale,
            male_tip_radius=pair.male_tip_radius * k,
            male_root_radius=pair.male_root_radius * k,
            female_tip_radius=pair.female_tip_radius * k,
            female_root_radius=pair.female_root_radius * k,
            lead=pair.lead * k,
            length=pair.length * k,
        )
        return hot, _scaled(male, k), _scaled(female, k)


def _scaled(profile: Array | list[Curve], k: float) -> Array | list[Curve]:
    """Grow points (n, 2) or exact curves by the factor ``k`` about the rotor's centre."""
    if isinstance(profile, list | tuple):
        return [Mapped(c, ((k, 0.0), (0.0, k))) for c in profile]
    return np.asarray(profile) * k


def _turned(points: Array, angles: Array) -> Array:
    """Turn points (n, 2) each by its own angle (n,) (rad, counter-clockwise) about the origin."""
    return rotate(points, angles)


@dataclass(frozen=True, eq=False)
class MeshingClearance:
    """Meshing clearance of a pair given by one lobe of each rotor (Wu & Chi).

    Parameters
    ----------
    pair : RotorPair
        Dimensions of the pair (use ``strict=False`` for measured or hot rotors).
    male_pieces, female_pieces : list of (str, Curve)
        One lobe of each rotor as named counter-clockwise pieces in the rotor's own frame (e.g.
        :func:`rotorcad.rotor_points.lobe_pieces`), mm.
    contact : {"driving", "sealing", "as-given"}
        Flank on which the racks are brought into contact, or "as-given" to leave them as the
        points lie.
    tolerance : float, mm
        Tolerance of the derived racks.
    contact_step : float, mm
        Largest step between the datum rack's contact points.

    Raises
    ------
    DesignError
        An unknown ``contact``.
    """

    pair: RotorPair
    male_pieces: list[tuple[str, Curve]]
    female_pieces: list[tuple[str, Curve]]
    contact: str = "driving"
    tolerance: float = 1e-4
    contact_step: float = 0.05  # mm between contact-line points

    def __post_init__(self) -> None:
        if self.contact not in CONTACT_SIDES:
            raise DesignError("contact", "one of " + ", ".join(CONTACT_SIDES), self.contact)

    @property
    def helix_angle(self) -> float:
        """Helix angle beta at the pitch cylinder, rad: tan(beta) = 2 pi r1w / h1 (the same for the female)."""
        return float(np.arctan(2 * np.pi * self.pair.male_pitch_radius / self.pair.lead))

    @cached_property
    def male_rack(self) -> DerivedRack:
        """The male's rack (:func:`rotorcad.inverse_rack.rotor_rack`) in the CONTRACT.md rack frame."""
        return self._rack(Side.MALE, 0.0)

    @cached_property
    def female_rack(self) -> DerivedRack:
        """The female's rack, the datum, in the CONTRACT.md rack frame (y > 0 towards the female).

        Sampled so that its contact points advance at most ``contact_step`` (mm).
        """
        return self._rack(Side.FEMALE, self.contact_step)

    def _rack(self, side: Side, contact_step: float) -> DerivedRack:
        pieces = side.pick(self.male_pieces, self.female_pieces)
        rack = rotor_rack(
            self.pair,
            side,
            pieces,
            tolerance=self.tolerance,
            samples=800,
            contact_step=contact_step,
            min_turn=MEASURED_MIN_TURN,
        )
        if len(rack.points) < 2:  # e.g. a drawing in metres or scaled x1e9: no normal meets the pitch circle
            raise DesignError(
                f"{side.value} points",
                "a profile whose every normal meets its pitch circle (it has a rack)",
                None,
                f"{100.0 * rack.lost_fraction:.1f} % of the lobe has no rack point",
            )
        return rack.in_contract_frame()

    @cached_property
    def _compared(self) -> tuple[Array, Array]:
        """The male normal rack over three periods (the racks need not start at the same phase).

        Points (3m, 2), mm, and unit tangents (3m, 2).
        """
        pts, tan = self.male_rack.normal_section(self.helix_angle)
        shift = np.array([self.pair.rack_period * np.cos(self.helix_angle), 0.0])
        return np.vstack([pts - shift, pts, pts + shift]), np.vstack([tan, tan, tan])

    @cached_property
    def _datum(self) -> tuple[Array, Array, Array]:
        """Female normal rack points (mm), unit tangents and unit normals towards the male side, each (n, 2)."""
        pts, tan = self.female_rack.normal_section(self.helix_angle)
        return pts, tan, np.stack([tan[:, 1], -tan[:, 0]], axis=1)

    def _in_both_bores(self, gap: Array | float = 0.0) -> Array:
        """Select the female rack points whose contact lies inside both tip circles.

        Inside the female's within the fit's tolerance (1 µm), and inside the male's by the local
        clearance ``gap`` (mm) more (a female root deeper than the male tip still seals against it,
        across that clearance). Returns an (n,) bool mask.
        """
        contact, _ = self._contacts(0.0)
        pair = self.pair
        slack = 1e-3 + np.maximum(np.nan_to_num(gap), 0.0)
        return (np.hypot(*contact.T) <= pair.male_tip_radius + slack) & (
            np.hypot(contact[:, 0] - pair.center_distance, contact[:, 1]) <= pair.female_tip_radius + 1e-3
        )

    def _contacts(self, shift: float) -> tuple[Array, Array]:
        """Return the contact point (n, 2), mm, and male angle (n,), rad, of each female (datum) rack point.

        The rack is moved by ``shift`` (mm) along the pitch line.
        """
        contact, angle = contact_of_rack_points(self.pair.male_pitch_radius, self.female_rack.points, self.female_rack.tangents)
        return contact, angle - shift / self.pair.male_pitch_radius

    def clearance_at(self, shift: float, mask: Array | None = None) -> Array:
        """Return the normal clearance of the datum (female) rack points with the female rack moved.

        Parameters
        ----------
        shift : float, mm
            Transverse shift of the female rack along the pitch line (applied as shift cos(beta) on
            the normal rack).
        mask : (n,) bool array, optional
            Datum points to evaluate; default all.

        Returns
        -------
        (k,) float array, mm
            Clearance of each selected point along its normal (Wu & Chi eq. 10), NaN where undefined.
        """
        pts, _, normals = self._datum
        if mask is not None:
            pts, normals = pts[mask], normals[mask]
        moved = pts + np.array([shift * np.cos(self.helix_angle), 0.0])
        compared, compared_tan = self._compared
        return normal_clearance(moved, normals, compared, compared_tan)

    @cached_property
    def shift(self) -> float:
        """Transverse shift of the female rack that makes the racks touch on the chosen flank, mm.

        The smallest clearance there is zero, found by stepping out from the given position (doubling,
        up to a quarter of the rack period) until it changes sign, then Brent's method. 0 for
        ``contact="as-given"``. Raises :class:`DesignError` when the flank has no contact inside both
        bores or the racks never touch there.
        """
        if self.contact == "as-given":
            return 0.0
        _, tan, _ = self._datum
        # the male lobe's trailing (rising) flank is the driving one. Only where a flank rises at more
        # than 30 degrees from the pitch line can sliding the rack bring it into contact: near the
        # lands a radial interference (hot rotors) would not go away by turning
        side = tan[:, 1] > 0.5 if self.contact == "driving" else tan[:, 1] < -0.5
        # the path of a sharp corner hangs on where the corner was found between the points: the
        # racks are brought into contact on the flank proper
        proper = ~self.female_rack.corner_path if self.female_rack.corner_path is not None else True
        inside = self._in_both_bores() & side & proper
        if not inside.any():
            raise DesignError(
                "contact", f"a flank that meets the mate inside both bores on the {self.contact} side", self.contact
            )
        # moving the female rack in +x closes the driving (rising) flanks and opens the sealing ones
        sign = 1.0 if self.contact == "driving" else -1.0

        @functools.cache
        def gap(g: float) -> float:
            d = self.clearance_at(sign * g, inside)
            return float(np.nanmin(d)) if np.isfinite(d).any() else np.nan

        g0 = gap(0.0)
        step = max(abs(g0), 1e-3) if np.isfinite(g0) else 1e-3
        direction = 1.0 if not np.isfinite(g0) or g0 >= 0 else -1.0
        # step out from the given position, doubling, up to a quarter of the rack period
        steps = [0.0]
        while step < self.pair.rack_period / 4:
            steps.append(direction * step)
            step *= 2
        root = bracket_root(gap, steps, xtol=1e-12)
        if root is not None:
            return sign * root
        raise DesignError(
            "female points",
            f"a female lobe that can be brought into contact with the male on the {self.contact} flank",
            None,
            "the racks never touch there within a quarter of the rack period",
        )

    @cached_property
    def clearance(self) -> Array:
        """Normal clearance of every datum rack point at the positioned racks, (n,) float, mm."""
        return self.clearance_at(self.shift)

    @cached_property
    def _band(self) -> dict[str, float]:
        """The clearance band on the 3D contact line (module docstring, step 5).

        Largest, smallest, mean and equal clearance (mm), band area (mm²), contact-line length and
        wetted perimeter (mm).
        """
        pair = self.pair
        contact, angle = self._contacts(self.shift)
        z = pair.lead * angle / (2 * np.pi)
        use = self._in_both_bores(self.clearance) & np.isfinite(self.clearance) & np.isfinite(z)
        z = z - z[use].min()
        pairs = use[:-1] & use[1:]
        reach = np.maximum(z[:-1], z[1:])[pairs]  # the rotor length that holds a segment of the contact line
        if reach.size and reach.min() > pair.length + 1e-9:  # not one segment within the length: no band
            longest = abs(pair.lead) * pair.length / float(reach.min())
            raise DesignError(
                "lead",
                f"at most {longest:.6g} mm for a rotor length of {pair.length:g} mm",
                pair.lead,
                "a longer lead leaves less than one segment of the contact line within the rotors",
            )
        use &= z <= pair.length + 1e-9
        delta = self.clearance
        line = np.column_stack([contact, z])
        # unit normal of the helical flank: transverse from the rack (axes swapped), axial part
        # from the helicoid (normal perpendicular to the screw motion (-y, x, h/2 pi))
        tan = self.female_rack.tangents
        n_t = np.stack([-tan[:, 0], tan[:, 1]], axis=1)  # rack normal (t_y, -t_x) in fixed axes
        n_z = 2 * np.pi * (contact[:, 1] * n_t[:, 0] - contact[:, 0] * n_t[:, 1]) / pair.lead
        normal = np.column_stack([n_t, n_z])
        normal /= np.linalg.norm(normal, axis=1, keepdims=True)
        offset = line + np.maximum(np.nan_to_num(delta), 0.0)[:, None] * normal
        seg = use[:-1] & use[1:]  # consecutive contact points (no bridging over gaps)
        dl = np.linalg.norm(np.diff(line, axis=0), axis=1)
        do = np.linalg.norm(np.diff(offset, axis=0), axis=1)
        tri1 = 0.5 * np.linalg.norm(np.cross(line[1:] - line[:-1], offset[:-1] - line[:-1]), axis=1)
        tri2 = 0.5 * np.linalg.norm(np.cross(offset[1:] - line[1:], offset[:-1] - line[1:]), axis=1)
        width = np.linalg.norm(offset - line, axis=1)
        starts = seg & ~np.concatenate([[False], seg[:-1]])  # first segment of each run
        ends = seg & ~np.concatenate([seg[1:], [False]])  # last segment of each run
        pts_n, _ = self.female_rack.normal_section(self.helix_angle)
        dr = np.hypot(*np.diff(pts_n, axis=0).T)
        mid = 0.5 * (np.nan_to_num(delta[:-1]) + np.nan_to_num(delta[1:]))
        length = float(dl[seg].sum())
        area = float((tri1 + tri2)[seg].sum())
        return {
            "max_normal_clearance": float(delta[use].max()),
            "min_normal_clearance": float(delta[use].min()),
            "mean_clearance": float((mid * dr)[seg].sum() / dr[seg].sum()),
            "equal_clearance": area / length if length > 0 else float("nan"),
            "band_area": area,
            "contact_line_length": length,
            "wetted_perimeter": float(dl[seg].sum() + do[seg].sum() + width[:-1][starts].sum() + width[1:][ends].sum()),
        }

    def distribution(self) -> dict[str, Array]:
        """Return the clearance on both rotors and over the rotation (Wu & Chi Fig. 9).

        Returns
        -------
        dict of (n,) float arrays
            One row per datum rack point: ``x``, ``y`` the positioned datum normal rack (mm);
            ``clearance`` along its normal (mm); ``male_angle_deg`` the male rotation angle at which the
            point is in contact (deg) and ``z`` its axial position on the contact line (mm, z = h1 phi /
            2 pi from the first contact inside both bores, so that 0 is the suction end and ``length``
            the discharge end); ``contact_x``, ``contact_y`` the contact point in the fixed transverse
            frame (mm); ``female_x``, ``female_y`` the female profile point there (own frame, mesh
            position, mm), ``male_x``, ``male_y`` the male point facing it across the transverse gap
            (own frame, mm); ``in_contact`` (0/1) whether the contact lies inside both bores and within
            the rotor length.
        """
        pair = self.pair
        contact, angle = self._contacts(self.shift)
        delta = self.clearance
        z = pair.lead * angle / (2 * np.pi)
        use = self._in_both_bores(delta) & np.isfinite(delta) & np.isfinite(z)
        z = z - (z[use].min() if use.any() else 0.0)
        use &= z <= pair.length + 1e-9
        tan = self.female_rack.tangents  # transverse rack tangent, CONTRACT frame (x along the pitch line)
        towards_male = np.stack([-tan[:, 0], tan[:, 1]], axis=1)  # the datum's normal in fixed axes (x = rack y)
        # the normal clearance in the transverse section (clearance_design: delta_t / delta_n)
        stretch = np.sqrt(tan[:, 1] ** 2 / np.cos(self.helix_angle) ** 2 + tan[:, 0] ** 2)
        gap_t = np.nan_to_num(delta) * stretch
        phi2 = -angle * pair.male_teeth / pair.female_teeth
        female = _turned(contact - np.array([pair.center_distance, 0.0]), -phi2)
        male = _turned(contact + gap_t[:, None] * towards_male, -angle)
        pts = self.datum_rack
        return {
            "x": pts[:, 0],
            "y": pts[:, 1],
            "clearance": delta,
            "male_angle_deg": np.degrees(angle),
            "z": z,
            "contact_x": contact[:, 0],
            "contact_y": contact[:, 1],
            "female_x": female[:, 0],
            "female_y": female[:, 1],
            "male_x": male[:, 0],
            "male_y": male[:, 1],
            "in_contact": use.astype(float),
        }

    def summary(self) -> dict[str, float]:
        """Return the figures of ``rotorcad clearance`` (CONTRACT.md).

        Returns
        -------
        dict of float
            ``max_normal_clearance``, ``min_normal_clearance`` (negative: interference),
            ``mean_clearance``, ``equal_clearance`` (mm), ``band_area`` (mm²),
            ``contact_line_length``, ``wetted_perimeter`` (mm), ``female_rack_shift`` (mm, the shift
            applied to position the racks) and ``helix_angle_deg`` (deg).
        """
        return {**self._band, "female_rack_shift": self.shift, "helix_angle_deg": float(np.degrees(self.helix_angle))}

    @property
    def datum_rack(self) -> Array:
        """The positioned female normal rack (the datum), (n, 2) float, mm, for plots."""
        pts, _, _ = self._datum
        return pts + np.array([self.shift * np.cos(self.helix_angle), 0.0])

    @property
    def datum_normals(self) -> Array:
        """Unit normals of the datum rack towards the male side, (n, 2) float."""
        return self._datum[2]


__all__ = [
    "CONTACT_SIDES",
    "MeshingClearance",
    "ThermalState",
    "normal_clearance",
]
