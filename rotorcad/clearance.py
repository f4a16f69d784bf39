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
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from rotorcad.clearance_accuracy import ACCURACY_FLOOR, estimated_accuracy, pair_quality, points_quality, trends
from rotorcad.clearance_flanks import flank_codes, flank_figures, point_weights
from rotorcad.clearance_normals import normal_clearance, normal_crossing, trim_folds
from rotorcad.clearance_phase import alignment_curve, complementary_shift, search_steps
from rotorcad.clearance_thermal import ThermalState
from rotorcad.clearance_zones import CORNER_CORE, SHARP_FAN, ClearanceZone, holes_as_gaps
from rotorcad.curves import Curve, sample_curve
from rotorcad.errors import DesignError
from rotorcad.geometry import Array, distance_to_polyline, polyline_distance, rotate
from rotorcad.inverse_rack import (
    MEASURED_JOIN_GAP,
    MEASURED_MIN_TURN,
    SMOOTHED_STALL_FACTOR,
    DerivedRack,
    contact_of_rack_points,
    rotor_rack,
    stalls,
)
from rotorcad.measured.pairs import CONFIDENCE, max_factor
from rotorcad.roles import Side
from rotorcad.roots import bracket_root
from rotorcad.rotor_pair import RotorPair

CONTACT_SIDES = ("driving", "sealing", "as-given")

ALIGNMENT_WINDOW_MAX = 5.0
"""mm: the contact alignment's window where the flank's clearance trends (:func:`trends`): twenty
spacings of 300 points a lobe of the N-rack (5.3 mm); its 80 a lobe with 2 um scatter at 82.2 mm for 82
read -35 um (a false interference) with twenty spacings (20 mm), -1.3 um with 5 mm."""


@dataclass(frozen=True, eq=False)
class MeshingClearance:
    """Meshing clearance of a pair given by one lobe of each rotor (Wu & Chi).

    Parameters
    ----------
    pair : RotorPair
        Dimensions of the pair (use ``strict=False`` for measured or hot rotors).
    male_pieces, female_pieces : list of (str, Curve)
        One lobe of each rotor as named counter-clockwise pieces in the rotor's own frame (e.g.
        :func:`rotorcad.measured.fit.lobe_pieces`), mm.
    contact : {"driving", "sealing", "as-given"}
        Flank on which the racks are brought into contact, or "as-given" to leave them as the
        points lie.
    tolerance : float, mm
        Tolerance of the derived racks.
    contact_step : float, mm
        Largest step between the datum rack's contact points.
    scatter, spacing : float, mm
        The points' scatter and spacing (:func:`points_quality`, the larger of the two rotors'),
        for the stated :attr:`accuracy`; 0 for exact curves.
    sagitta : float, mm
        The sagittas of the polygons the two rotors' points lie on, added
        (:func:`rotorcad.measured.pattern.pattern_deviation`), for the stated :attr:`accuracy`.
    corner_error : float, mm
        How far a sharp corner found between sparse points may lie from its fits' crossing
        (:func:`rotorcad.measured.fit.corner_uncertainty`), for the stated :attr:`gap_accuracy`;
    curvature_jump : float, 1/mm, optional
        The larger of the two rotors' largest curvature jumps between neighbouring points
        (:func:`rotorcad.measured.fit.curvature_jump`), for the stated :attr:`accuracy`; None: the
        default of :func:`estimated_accuracy`. :func:`rotorcad.clearance_accuracy.pair_quality` gives
        all five.

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
    scatter: float = 0.0  # mm: the points' scatter (points_quality), for the stated accuracy
    spacing: float = 0.0  # mm: the points' spacing (points_quality), for the stated accuracy
    sagitta: float = 0.0  # mm: the two rotors' polygon sagittas (pattern_deviation), for the stated accuracy
    corner_error: float = 0.0  # mm: a corner's uncertainty between sparse points (corner_uncertainty), for gap_accuracy
    curvature_jump: float | None = None  # 1/mm: the points' largest curvature jump (curvature_jump), for the stated accuracy

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
            join_gap=MEASURED_JOIN_GAP,
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

        Points (k, 2), mm, and unit tangents (k, 2), each fold cut back to its envelope
        (:func:`rotorcad.clearance_normals.trim_folds`: a swallowtail where the fit's curvature folds the
        rack at a stalled generation, whose tail a normal met inside the male).
        """
        pts, tan = self.male_rack.normal_section(self.helix_angle)
        shift = np.array([self.pair.rack_period * np.cos(self.helix_angle), 0.0])
        pts, tan, _ = trim_folds(np.vstack([pts - shift, pts, pts + shift]), np.vstack([tan, tan, tan]))
        return pts, tan

    @cached_property
    def _transverse_compared(self) -> tuple[Array, Array, Array, Array]:
        """The male transverse rack over three periods: points (k, 2), mm, unit tangents, corner and unresolved flags (k,).

        Each fold cut back to its envelope as in :attr:`_compared`.

        A corner flag marks a sharp male corner's path (:meth:`_near_corner`) and a stall of the male's
        generation below its tip (:func:`rotorcad.inverse_rack.stalls`); an unresolved flag the rest of
        such a stall's reach (:attr:`corner_reach`), where the fit rounds the corner over the spacing.
        """
        rack = self.male_rack
        shift = np.array([self.pair.rack_period, 0.0])
        pts = np.vstack([rack.points - shift, rack.points, rack.points + shift])
        corner = self._near_corner(rack, CORNER_CORE)
        # the flank within the corner's reach: a contact the fit's corner moves (not judged)
        unresolved = self._near_corner(rack) & ~corner
        # a sharp male corner below its tip that the fit smoothed over (the crossing of an undercut
        # flank's two generated parts): the male's points stall there as at a corner's fan (a turn of
        # 3 deg is enough here: a slow generation taken for a corner only moves the female facing it
        # to the gaps, measured there by the closest approach). Sparse points round the corner over
        # their spacing and lift its stall: up to SMOOTHED_STALL_FACTOR with a turn of STALL_TURN, but
        # less than the 30 deg of a corner the fit keeps (a tip rounding turns by 150 deg)
        found = stalls(rack, measured=True, min_turn=np.radians(3.0))
        if self.spacing > 0:
            found += stalls(rack, measured=True, factor=SMOOTHED_STALL_FACTOR, max_turn=np.radians(30.0))
        for a, b, _ in found:
            at = rack.profile[a:b]
            near = distance_to_polyline(rack.profile, at) if len(at) > 1 else np.hypot(*(rack.profile - at[0]).T)
            core = near <= 0.02  # the stall itself: the female passes over the corner's notch
            corner |= core
            unresolved |= (near <= self.unresolved_reach) & ~core  # the flank beside it, as far as the fit rounds it
        unresolved &= ~corner
        pts, tan, (corner, unresolved) = trim_folds(
            pts, np.vstack([rack.tangents] * 3), (np.tile(corner, 3), np.tile(unresolved, 3))
        )
        return pts, tan, corner, unresolved

    @property
    def corner_reach(self) -> float:
        """Reach of a sharp corner's neighbourhood along the profile, mm: 0.02 mm and two point spacings.

        A fit through points h apart cannot place a corner closer than about h, and the flank's
        last points before it generate the rack of a tiny rounding: the neighbourhood gets the
        corner's treatment.
        """
        return 0.02 + 2.0 * self.spacing

    @property
    def unresolved_reach(self) -> float:
        """Reach along the profile beside a male corner below its tip that the fit rounds, mm: 0.02 mm and four point spacings.

        The fitted cubic rings beside a corner it rounds (the 5/6 arc-flank male of the tests, 300 points
        a lobe, 2 µm scatter: 12 µm at its undercut's crossing, 5.5 µm 1.5-2 spacings beside it).
        """
        return 0.02 + 4.0 * self.spacing

    def _near_corner(self, rack: DerivedRack, reach: float | None = None) -> Array:
        """(n,) bool: the rack point is on a sharp corner's path or made within ``reach`` (mm; :attr:`corner_reach`) of it."""
        fan = rack.corner_path
        if not fan.any() or rack.profile is None:
            return fan
        corners = np.unique(np.round(rack.profile[fan], 9), axis=0)
        # a fan whose normals turn by less than SHARP_FAN is a kink the fits leave where a land meets a
        # flank's spline (scattered points: 0.4-6 deg), not a corner: its normals are the flank's
        at = np.round(rack.profile, 9)
        sharp = np.zeros(len(fan), dtype=bool)
        for c in corners:
            own = fan & np.all(at == c, axis=1)
            heading = np.unwrap(np.arctan2(rack.tangents[own, 1], rack.tangents[own, 0]))
            if np.ptp(heading) >= SHARP_FAN:
                sharp |= own
        fan = sharp
        if not fan.any():
            return fan
        corners = np.unique(at[fan], axis=0)
        d = np.min(np.hypot(*(rack.profile[:, None, :] - corners[None, :, :]).transpose(2, 0, 1)), axis=1)
        return fan | (d <= (self.corner_reach if reach is None else reach))

    def _faces_male_corner(self, shift: float) -> tuple[Array, Array]:
        """Return where the datum points' normals meet the male rack, with the female rack moved by ``shift`` (mm).

        (n,) bool each: on the path of a sharp male corner (or a stall's core), where the female is not
        touched by a male flank (the male's tip corner passes it at a gap: the root below a sharp tip);
        and beside a male corner the fit rounds (:attr:`ClearanceZone.UNRESOLVED`). Judged in the
        transverse section, where the racks are generated (the normal section turns the normals).
        """
        rack = self.female_rack
        moved = rack.points + np.array([shift, 0.0])
        normals = np.stack([rack.tangents[:, 1], -rack.tangents[:, 0]], axis=1)
        compared, compared_tan, corner, unresolved = self._transverse_compared
        _, seg = normal_crossing(moved, normals, compared, compared_tan)
        ok = seg >= 0
        s = np.where(ok, seg, 0)
        return ok & (corner[s] | corner[s + 1]), ok & (unresolved[s] | unresolved[s + 1])

    @cached_property
    def _datum(self) -> tuple[Array, Array, Array]:
        """Female normal rack points (mm), unit tangents and unit normals towards the male side, each (n, 2)."""
        pts, tan = self.female_rack.normal_section(self.helix_angle)
        return pts, tan, np.stack([tan[:, 1], -tan[:, 0]], axis=1)

    def _in_both_bores(self, gap: Array | float = 0.0) -> Array:
        """Select the female rack points whose contact lies inside both tip circles.

        Inside the female's within the fit's tolerance (1 µm, and three scatters: a sharp tip corner
        fitted where scattered flanks cross lies beyond the tip radius by that much, 1.35 µm for the 5/6
        independent female with 1 µm, and its path fell out of every zone), and inside the male's by the
        local clearance ``gap`` (mm) more (a female root deeper than the male tip still seals against it,
        across that clearance). Returns an (n,) bool mask.
        """
        contact, _ = self._contacts(0.0)
        pair = self.pair
        fit = 1e-3 + 3.0 * self.scatter
        slack = fit + np.maximum(np.nan_to_num(gap), 0.0)
        return (np.hypot(*contact.T) <= pair.male_tip_radius + slack) & (
            np.hypot(contact[:, 0] - pair.center_distance, contact[:, 1]) <= pair.female_tip_radius + fit
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

        The smallest clearance there is zero, found by stepping out from the racks' complementary phase
        (:mod:`rotorcad.clearance_phase`, doubling, up to a quarter period) to a sign change, then Brent's. 0 for
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
        proper = ~self._near_corner(self.female_rack)
        # nor where the female faces the path of a sharp male corner (its root below the male tip)
        start = complementary_shift(self.male_rack, self.female_rack)  # any input phase: over the whole period
        inside = self._in_both_bores() & side & proper & ~np.logical_or(*self._faces_male_corner(start))
        if not inside.any():
            raise DesignError(
                "contact", f"a flank that meets the mate inside both bores on the {self.contact} side", self.contact
            )
        # moving the female rack in +x closes the driving (rising) flanks and opens the sealing ones
        sign = 1.0 if self.contact == "driving" else -1.0

        pts_n, _, _ = self._datum
        arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts_n, axis=0).T))])
        width = self.alignment_window

        @functools.cache
        def gap(g: float) -> float:
            d = self.clearance_at(sign * g, inside)
            ok = np.isfinite(d)
            if not ok.any():
                return np.nan
            return float(np.min(alignment_curve(d[ok], arc[inside][ok], width, self.scatter)))

        root = bracket_root(gap, search_steps(sign * start, gap(sign * start), self.pair.rack_period), xtol=1e-12)
        quality = (self.scatter, self.spacing, self.sagitta, self.curvature_jump)
        if root is not None and width > ALIGNMENT_WINDOW_MAX and trends(self.clearance_at(sign * root, inside), *quality):
            width = ALIGNMENT_WINDOW_MAX  # sparse points' window spans the flank, whose clearance trends
            gap.cache_clear()
            root = bracket_root(gap, search_steps(sign * root, gap(sign * root), self.pair.rack_period), xtol=1e-12)
        if root is not None:
            # the flank proper at the contact found: what faces the male corner there is left out
            again = inside & ~np.logical_or(*self._faces_male_corner(sign * root))
            if again.any() and not np.array_equal(again, inside):
                inside = again
                gap.cache_clear()
                refined = bracket_root(gap, [root, root - 1e-3, root + 1e-3, root - 4e-3, root + 4e-3], xtol=1e-12)
                root = root if refined is None else refined
            return sign * root
        raise DesignError(
            "female points",
            f"a female lobe that can be brought into contact with the male on the {self.contact} flank",
            None,
            "the racks never touch there within a quarter of the rack period",
        )

    @property
    def alignment_window(self) -> float:
        """Width of the running mean (mm along the datum rack) whose smallest value the contact alignment zeroes.

        Twenty point spacings (none for exact curves): the scatter left by the fits is averaged out
        of the alignment, a designed clearance's minimum is not (it varies over millimetres). Where
        the clearance along the flank trends by more than the window can average (:meth:`shift`),
        at most :data:`ALIGNMENT_WINDOW_MAX`.
        """
        return 20.0 * self.spacing

    @cached_property
    def clearance(self) -> Array:
        """Normal clearance of every datum rack point at the positioned racks, (n,) float, mm."""
        return self.clearance_at(self.shift)

    @cached_property
    def _use(self) -> Array:
        """(n,) bool: the datum point's contact lies inside both bores and within the rotor length."""
        pair = self.pair
        _, angle = self._contacts(self.shift)
        z = pair.lead * angle / (2 * np.pi)
        # a point whose normal meets no male rack nearby is inside the rotors too: :meth:`_zones_where` makes
        # it a gap, measured by the closest approach (:func:`rotorcad.clearance_zones.holes_as_gaps`)
        measured = np.isfinite(self.clearance)
        use = self._in_both_bores(self.clearance) & np.isfinite(z)
        if not (use & measured).any():
            return use & measured
        z = z - z[use & measured].min()
        return use & (z <= pair.length + 1e-9)  # a lead that leaves no contact run within: _band refuses it

    @cached_property
    def zones(self) -> Array:
        """The :class:`ClearanceZone` code of every datum rack point at the positioned racks, (n,) int."""
        return self._zones_where(self._use)

    def _zones_where(self, use: Array) -> Array:
        """Return the zones of :attr:`zones` with ``use`` ((n,) bool) as the points inside the rotors."""
        corner = self._near_corner(self.female_rack, CORNER_CORE)
        faces, unresolved = self._faces_male_corner(self.shift)
        unresolved |= self._near_corner(self.female_rack) & ~corner  # the flank the corner's place moves
        zone = np.where(unresolved, ClearanceZone.UNRESOLVED, ClearanceZone.CONTACT)
        zone = np.where(corner, ClearanceZone.CORNER, np.where(faces, ClearanceZone.GAP, zone))
        zone = np.where(use, zone, ClearanceZone.OUTSIDE)
        zone = holes_as_gaps(zone, use & ~np.isfinite(self.clearance))
        # the last point of a contact run beside a corner's zone is judged with that zone
        for other in (ClearanceZone.UNRESOLVED, ClearanceZone.GAP, ClearanceZone.CORNER):
            edge = (zone == ClearanceZone.CONTACT) & ((np.roll(zone, 1) == other) | (np.roll(zone, -1) == other))
            zone = np.where(edge, other if other == ClearanceZone.UNRESOLVED else ClearanceZone.GAP, zone)
        # a contact run of a few points between gaps is the racks' junction, not a flank
        on = np.concatenate([[0], (zone == ClearanceZone.CONTACT).astype(int), [0]])
        starts, ends = np.flatnonzero(np.diff(on) == 1), np.flatnonzero(np.diff(on) == -1)
        short = np.zeros(len(zone) + 1, dtype=int)
        few = ends - starts < 5
        np.add.at(short, starts[few], 1)
        np.add.at(short, ends[few], -1)
        zone = np.where(np.cumsum(short)[:-1] > 0, ClearanceZone.GAP, zone)
        return zone.astype(int)

    @property
    def flanks(self) -> Array:
        """(n,) int: the flank of each datum point (1 driving, 2 sealing, 3, 4 lands: :func:`flank_codes`)."""
        return flank_codes(self.female_rack.points, self.female_rack.tangents)

    @property
    def contact_zone(self) -> Array:
        """(n,) bool: the datum points on the conjugate contact zone (:attr:`ClearanceZone.CONTACT`)."""
        return self.zones == ClearanceZone.CONTACT

    @cached_property
    def _male_outline(self) -> Array:
        """The whole male outline in its own frame as a closed polyline (m, 2), mm (0.1 µm chords)."""
        lobe = np.vstack([sample_curve(c, 1e-4)[1] for _, c in self.male_pieces])
        z1 = self.pair.male_teeth
        ring = np.vstack([rotate(lobe, 2 * np.pi * k / z1) for k in range(z1)])
        return np.vstack([ring, ring[:1]])

    def _female_in_male_frame(self, female: Array, angle: Array) -> Array:
        """Female points (own frame, (..., 2)) in the male's own frame at male angles ``angle`` (...), rad."""
        pair = self.pair
        phi2 = -angle * pair.male_teeth / pair.female_teeth
        fixed = rotate(female.reshape(-1, 2), np.broadcast_to(phi2, female.shape[:-1]).ravel())
        fixed = fixed + np.array([pair.center_distance, 0.0])
        return rotate(fixed, -np.broadcast_to(angle, female.shape[:-1]).ravel()).reshape(female.shape)

    def _approach(self, female: Array, angle: Array, window: float) -> Array:
        """Closest approach of female points to the male over the mesh, (n,) float, mm.

        The smallest distance of each point (female's own frame, (n, 2)) from the male outline over
        the male angles ``angle`` +- ``window`` (rad): a grid of 65 positions, then two finer grids of
        17 about the best, then the parabola through the best three (the transverse section, as two
        rotors' outlines are compared by the brute force of the tests).
        """
        male = polyline_distance(self._male_outline)  # distance_to_polyline's numbers, the R-tree built once
        centre, width = np.asarray(angle, dtype=float), window
        # every grid holds its centre (odd counts), whose distance bounds the smallest: positions
        # farther than the largest such bound are not searched (they return inf)
        bound = male(self._female_in_male_frame(female, centre))
        reach = float(np.max(bound)) * (1 + 1e-9) + 1e-9 if len(bound) else None
        for n in (65, 17, 17):
            grid = centre[:, None] + np.linspace(-width, width, n)[None, :]
            pts = self._female_in_male_frame(np.repeat(female[:, None, :], n, axis=1), grid)
            d = male(pts.reshape(-1, 2), reach).reshape(len(female), n)
            j = np.clip(np.argmin(d, axis=1), 1, n - 2)
            centre = grid[np.arange(len(female)), j]
            width = 2 * width / (n - 1)
        rows = np.arange(len(female))
        d0, d1, d2 = d[rows, j - 1], d[rows, j], d[rows, j + 1]
        curv = d0 - 2 * d1 + d2
        with np.errstate(divide="ignore", invalid="ignore"):
            vertex = np.where((curv > 0) & np.isfinite(curv), d1 - (d2 - d0) ** 2 / (8 * curv), d1)
        return np.minimum(np.clip(vertex, 0.0, None), d.min(axis=1))

    @cached_property
    def gap(self) -> Array:
        """The transverse gap of the datum points that are not on the contact zone, (n,) float, mm.

        For :attr:`ClearanceZone.GAP` points (the female never touched there) the closest approach of
        the male over the mesh; for :attr:`ClearanceZone.CORNER` points (the path of a sharp female
        corner) the distance of the corner from the male at that point of its path, whose smallest
        value is the corner's closest approach (the corner path against the mate, not a normal
        through the corner). NaN on the contact zone and outside.
        """
        zone = self.zones
        out = np.full(len(zone), np.nan)
        contact, angle = self._contacts(self.shift)
        pair = self.pair
        phi2 = -angle * pair.male_teeth / pair.female_teeth
        female = rotate(contact - np.array([pair.center_distance, 0.0]), -phi2)
        corner = (zone == ClearanceZone.CORNER) & self.female_rack.corner_path
        if corner.any():
            at = self._female_in_male_frame(female[corner], angle[corner])
            out[corner] = distance_to_polyline(at, self._male_outline)
        # the parts that never touch and a female corner's neighbourhood: the closest approach
        gap = ((zone == ClearanceZone.GAP) | (zone == ClearanceZone.CORNER)) & ~corner
        if gap.any():
            out[gap] = self._approach(female[gap], angle[gap], np.pi / pair.male_teeth)
        return out

    @property
    def accuracy(self) -> float:
        """The stated accuracy of the contact-zone clearance, mm (:func:`estimated_accuracy`).

        A bound on the largest error over the contact zone with 95 % confidence, for as many
        independent points as the contact zone's length on the female rack over the point spacing.
        """
        if self.scatter <= 0 or self.spacing <= 0:
            return estimated_accuracy(self.scatter, self.spacing, sagitta=self.sagitta, curvature_jump=self.curvature_jump)
        pts = self.female_rack.points
        on = self.contact_zone
        step = np.hypot(*np.diff(pts, axis=0).T)
        length = float(step[on[:-1] & on[1:]].sum())
        count = max(length / self.spacing, 1.0)
        return estimated_accuracy(self.scatter, self.spacing, count, self.sagitta, self.curvature_jump)

    @property
    def gap_accuracy(self) -> float:
        """The stated accuracy of the gaps of the parts that never touch and of a corner's path, mm.

        :attr:`accuracy` plus :attr:`corner_error`: a sharp corner between sparse points (or a
        rounding shorter than their spacing, which looks the same) lies somewhere in the triangle of
        its edge and its fits' crossing, and its path, and the mate's closest approach to it, move by
        as much (:func:`rotorcad.measured.fit.corner_uncertainty`).
        """
        return float(self.accuracy + self.corner_error)

    def _refuse_a_lead_past_the_contact_zone(self) -> None:
        """Refuse a lead so long that the contact zone of the bores falls outside the rotor length.

        The contact zone is judged as :attr:`zones` does, over the whole contact line in the bores;
        the lead named is the longest that keeps one contact run (five points, the shortest that
        counts as a flank) within the length.
        """
        pair = self.pair
        _, angle = self._contacts(self.shift)
        z = pair.lead * angle / (2 * np.pi)
        inside = self._in_both_bores(self.clearance) & np.isfinite(self.clearance) & np.isfinite(z)
        if not inside.any():
            return
        z = np.abs(z - z[inside].min())
        on = self._zones_where(inside) == ClearanceZone.CONTACT
        if not on.any():
            return  # no contact anywhere in the bores: the contact itself is refused
        runs = np.lib.stride_tricks.sliding_window_view(on, 5).all(axis=1)
        reach = np.lib.stride_tricks.sliding_window_view(z, 5).max(axis=1)[runs]
        if not reach.size or reach.min() <= pair.length + 1e-9:
            return
        longest = abs(pair.lead) * pair.length / float(reach.min())
        raise DesignError(
            "lead",
            f"at most {longest:.6g} mm for a rotor length of {pair.length:g} mm",
            pair.lead,
            "a longer lead leaves the contact zone of the flanks outside the rotors",
        )

    @cached_property
    def _band(self) -> dict[str, float | None]:
        """The clearance band on the 3D contact line (module docstring, step 5), and the zones' figures.

        Largest, smallest and mean normal clearance over the contact zone (mm); equal clearance and
        band area (mm, mm²) over the whole contact line, the band as wide as the normal clearance on
        the contact zone and where it is unresolved and as the gap elsewhere; contact-line length and
        wetted perimeter (mm); largest and smallest gap of the parts that never touch and smallest
        gap of a sharp corner's path (mm, None where there are none); largest and smallest normal
        clearance where the points cannot resolve the contact (mm, None where there is none) and its
        share of the contact line's length.
        """
        pair = self.pair
        contact, angle = self._contacts(self.shift)
        z = pair.lead * angle / (2 * np.pi)
        use = self._use
        z = z - (z[use].min() if use.any() else 0.0)
        zone = self.zones
        on = zone == ClearanceZone.CONTACT
        unresolved = zone == ClearanceZone.UNRESOLVED
        delta = np.where(on | unresolved, self.clearance, self.gap)
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
        c = self.clearance
        mid = 0.5 * (np.nan_to_num(c[:-1]) + np.nan_to_num(c[1:]))
        run = on[:-1] & on[1:]
        length = float(dl[seg].sum())
        area = float((tri1 + tri2)[seg].sum())
        if not on.any():
            self._refuse_a_lead_past_the_contact_zone()
            raise DesignError("contact", "a pair whose flanks touch somewhere inside both bores", self.contact)
        gap = zone == ClearanceZone.GAP
        corner = (zone == ClearanceZone.CORNER) & self.female_rack.corner_path  # the corners' own paths

        def figure(values: Array, sel: Array, pick) -> float | None:
            return float(pick(values[sel])) if sel.any() else None

        def share(sel: Array) -> float:  # of the contact line's length (its points crowd a corner's fan)
            return float(dl[seg & sel[:-1] & sel[1:]].sum() / length) if length > 0 else float(sel.sum() / use.sum())

        return {
            "max_normal_clearance": float(c[on].max()),
            "min_normal_clearance": float(c[on].min()),
            "mean_clearance": float((mid * dr)[run].sum() / dr[run].sum()) if run.any() else float(c[on].mean()),
            "equal_clearance": area / length if length > 0 else float("nan"),
            "band_area": area,
            "contact_line_length": length,
            "wetted_perimeter": float(dl[seg].sum() + do[seg].sum() + width[:-1][starts].sum() + width[1:][ends].sum()),
            "max_gap": figure(self.gap, gap, np.max),
            "min_gap": figure(self.gap, gap, np.min),
            "min_corner_gap": figure(self.gap, corner, np.min),
            "contact_zone_share": share(on | unresolved),
            "max_unresolved_clearance": figure(c, unresolved, np.max),
            "min_unresolved_clearance": figure(c, unresolved, np.min),
            "unresolved_share": share(unresolved),
        }

    def rinder_angle(self, angle: Array) -> Array:
        """Male rotation angles of contacts in the one angle convention (deg, :data:`rotorcad.meshing.ANGLE_CONVENTION`).

        The rotation still to go until the middle of the nearest male tip (the given male's points
        within the larger of 1e-4 of the addendum and :attr:`accuracy` of its outermost radius)
        reaches O1O2, as :meth:`rotorcad.meshing.MeshingAnalysis.rinder_angle` counts it: within
        +-180/z1 deg, the window of one lobe from root to root in which ``rotor`` gives its angles.

        Parameters
        ----------
        angle : (n,) float array, rad
            Male rotation angles of the contacts (the count of :meth:`distribution`'s ``z``).

        Returns
        -------
        (n,) float array, deg
        """
        from rotorcad.meshing import tip_on_centre_line  # meshing imports the engine, not this module

        ring, pair = self._male_outline, self.pair
        tol = max(1e-4 * pair.male_addendum, self.accuracy)
        zero = tip_on_centre_line(ring, pair.male_teeth, float(np.hypot(*ring.T).max()), tol, angle[self._use])
        half = 180.0 / pair.male_teeth
        return (np.degrees(zero - angle) + half) % (2 * half) - half

    def distribution(self) -> dict[str, Array]:
        """Return the clearance on both rotors and over the rotation (Wu & Chi Fig. 9).

        Returns
        -------
        dict of (n,) float arrays
            One row per datum rack point: ``x``, ``y`` the positioned datum normal rack (mm);
            ``clearance`` along its normal (mm); ``male_angle_deg`` the male angle at which the
            point is in contact (deg, the one angle convention, :meth:`rinder_angle`) and ``z`` its
            axial position on the contact line (mm, z = h1 phi / 2 pi with phi the male rotation,
            from the first contact inside both bores, so that 0 is the suction end and ``length``
            the discharge end); ``contact_x``, ``contact_y`` the contact point in the fixed transverse
            frame (mm); ``female_x``, ``female_y`` the female profile point there (own frame, mesh
            position, mm), ``male_x``, ``male_y`` the male point facing it across the transverse gap
            (own frame, mm); ``in_contact`` (0/1) whether the contact lies inside both bores and within
            the rotor length; ``zone`` the :class:`ClearanceZone` code (1 contact zone, 2 a part that
            never touches, 3 a sharp female corner's path, 4 a contact the points cannot resolve, 0
            outside); ``gap`` the transverse gap
            there (mm, :attr:`gap`; NaN on the contact zone).
        """
        pair = self.pair
        contact, angle = self._contacts(self.shift)
        delta = self.clearance
        z = pair.lead * angle / (2 * np.pi)
        use = self._use
        z = z - (z[use].min() if use.any() else 0.0)
        tan = self.female_rack.tangents  # transverse rack tangent, CONTRACT frame (x along the pitch line)
        towards_male = np.stack([-tan[:, 0], tan[:, 1]], axis=1)  # the datum's normal in fixed axes (x = rack y)
        # the normal clearance in the transverse section (clearance_design: delta_t / delta_n)
        stretch = np.sqrt(tan[:, 1] ** 2 / np.cos(self.helix_angle) ** 2 + tan[:, 0] ** 2)
        gap_t = np.nan_to_num(delta) * stretch
        phi2 = -angle * pair.male_teeth / pair.female_teeth
        female = rotate(contact - np.array([pair.center_distance, 0.0]), -phi2)
        male = rotate(contact + gap_t[:, None] * towards_male, -angle)
        pts = self.datum_rack
        return {
            "x": pts[:, 0],
            "y": pts[:, 1],
            "clearance": delta,
            "male_angle_deg": self.rinder_angle(angle),
            "z": z,
            "contact_x": contact[:, 0],
            "contact_y": contact[:, 1],
            "female_x": female[:, 0],
            "female_y": female[:, 1],
            "male_x": male[:, 0],
            "male_y": male[:, 1],
            "in_contact": use.astype(float),
            "zone": self.zones.astype(float),
            "gap": self.gap,
            "flank": self.flanks.astype(float),
        }

    def summary(self) -> dict[str, float]:
        """Return the figures of ``rotorcad clearance`` (CONTRACT.md).

        Returns
        -------
        dict of float (None where a zone is empty)
            ``max_normal_clearance``, ``min_normal_clearance`` (negative: interference) and
            ``mean_clearance`` over the contact zone, ``equal_clearance`` (mm) and ``band_area``
            (mm²) over the whole contact line, ``contact_line_length``, ``wetted_perimeter`` (mm),
            ``max_gap``, ``min_gap`` (mm, the parts that never touch), ``min_corner_gap`` (mm, the
            closest approach of a sharp female corner's path), ``contact_zone_share`` (of the
            contact line's length), ``max_unresolved_clearance``, ``min_unresolved_clearance`` (mm,
            the normal clearance where the points cannot resolve the contact,
            :attr:`ClearanceZone.UNRESOLVED`, not judged), ``unresolved_share`` (of the contact line's
            length), ``accuracy`` (mm, :attr:`accuracy`), ``gap_accuracy`` (mm, :attr:`gap_accuracy`: of
            ``max_gap``, ``min_gap``, ``min_corner_gap``), ``female_rack_shift`` (mm,
            the shift applied to position the racks) and ``helix_angle_deg`` (deg).
        """
        pts_n, _, _ = self._datum
        per_flank = flank_figures(self.clearance, self.contact_zone, self.flanks, point_weights(pts_n))
        return {
            **self._band,
            **per_flank,
            "accuracy": self.accuracy,
            "gap_accuracy": self.gap_accuracy,
            "female_rack_shift": self.shift,
            "helix_angle_deg": float(np.degrees(self.helix_angle)),
        }

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
    "ACCURACY_FLOOR",
    "CONFIDENCE",
    "CONTACT_SIDES",
    "ClearanceZone",
    "MeshingClearance",
    "ThermalState",
    "estimated_accuracy",
    "max_factor",
    "normal_clearance",
    "normal_crossing",
    "pair_quality",
    "points_quality",
]
