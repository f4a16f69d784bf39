"""The meshing analysis of a pair, everything Rinder reads off a toothing (:class:`MeshingAnalysis`).

Meshline (:mod:`rotorcad.meshing.meshline`), the rules of sec. 2.2.1 (:mod:`rotorcad.meshing.defects`),
the per-flank verdict (:mod:`rotorcad.meshing.contact_ratios`), the one angle convention
(:mod:`rotorcad.meshing.angles`), tightness and blow-hole (sec. 2.2.2), contact line (eq. 1), flute
areas and displacement, sliding velocity and slip (eqs. 2-4), and the summary ``rotor --json``
prints. The criteria are stated in :mod:`rotorcad.meshing`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import shapely

from rotorcad.blow_hole import SpatialBlowHole, apex_height
from rotorcad.envelope import Generated
from rotorcad.geometry import cross, dots, nearest_hypot, rotate, row_norms, shifted, wrap_angle
from rotorcad.meshing.angles import ANGLE_CONVENTION, tip_on_centre_line
from rotorcad.meshing.apex import arc_at, circle_meshline_apex
from rotorcad.meshing.blow_hole_accuracy import BLOW_HOLE_RESOLUTION, blow_hole_resolved, blow_hole_uncertainty
from rotorcad.meshing.contact_ratios import FlankReport, flank_reports, handover_length, running_reasons
from rotorcad.meshing.defects import MESHLINE_GAIN, Defect, is_tip_corner, meshline_defects, resolution
from rotorcad.meshing.line_points import given_of
from rotorcad.meshing.meshline import MeshlinePiece, meshline_pieces
from rotorcad.meshing.rounding_apex import area_bound, model_check, moved_crossings, rounding_apex
from rotorcad.meshing.slip import slip, slip_singularities
from rotorcad.meshing.tip_apex import tip_apex
from rotorcad.meshing.undecided import mark_decided, possible_rows, undecided_rows
from rotorcad.profile import DEFAULT_TOLERANCE
from rotorcad.rack_roles import point_generated_flanks
from rotorcad.roles import Flank, PieceRole, Side, tip_corner_name
from rotorcad.screw_rotors import ScrewRotors

EXACT_POINTS_AT_MOST = 20000
"""Most exact points (every lobe) :meth:`MeshingAnalysis._rounding_apex` fits a tip rounding's circles to: the N rack
male's outline at a 0.01 um chord (its spline within 1 % of the design's blow-hole) holds far more; 300 and 500 points
a lobe evenly spaced read +13.7 % and -59.5 % before, +0.9 % and 0.0 % with the circles."""

ROUNDING_STEP = 1e-4
"""mm: the step by which :attr:`MeshingAnalysis.apex_rounding_uncertainty` moves each of the rounding's circles' parameters."""


@dataclass(frozen=True, eq=False)
class MeshingAnalysis:
    """Everything Rinder reads off a toothing, for one pair at a design speed.

    Parameters
    ----------
    rotors : ScrewRotors
        The generated pair.
    speed_rpm : float, rpm
        Male speed, for the sliding velocities (m/s).
    samples : int
        Samples along each rack piece.
    tolerance : float, rad
        Relative tolerance of the cusp/jamming test: the uncertainty of the meshline's tangent
        direction (a whole piece within it is a point-generated flank).
    accuracy : float, mm, optional
        Accuracy of the profile to which the defects are judged; None: that of the rotors
        (:attr:`judged_accuracy`).
    """

    rotors: ScrewRotors
    speed_rpm: float = 3000.0
    samples: int = 600
    tolerance: float = 1e-3
    accuracy: float | None = None

    # ---- meshline ------------------------------------------------------------------------
    @cached_property
    def pieces(self) -> list[MeshlinePiece]:
        """The meshline, piece by piece: the contacts of every rack piece inside both bores.

        A list of :class:`MeshlinePiece`; pieces with fewer than two contacts are left out.
        """
        # inside both bores within 1 µm; a given profile's tip corner may lie outside its tip circle by its
        # accuracy (the rack-involute male's with 2 µm of scatter: 1 µm out, and its whole path was lost)
        corner_slack = 1e-3 + (4.0 * self.judged_accuracy if self.is_given else 0.0)
        return meshline_pieces(self.rotors.rack, self.rotors.pair, self.samples, corner_slack)  # one pass over all rack pieces

    @property
    def meshline(self) -> np.ndarray:
        """All contact points in the fixed frame, (n, 2) float, mm (piece after piece)."""
        return np.concatenate([p.points for p in self.pieces]) if self.pieces else np.zeros((0, 2))

    @property
    def contact_angles(self) -> np.ndarray:
        """Male rotation angle at every point of :attr:`meshline`, (n,) float, rad."""
        return np.concatenate([p.t for p in self.pieces]) if self.pieces else np.zeros(0)

    @property
    def is_given(self) -> bool:
        """True when the pair comes from points or a drawing (or an accuracy is imposed), not the design's exact curves."""
        return getattr(self.rotors, "accuracy", 0.0) > 0 or self.accuracy is not None

    # ---- the rules of sec. 2.2.1 -----------------------------------------------------------
    @property
    def judged_accuracy(self) -> float:
        """The accuracy (mm) to which the defects are judged (``defect_accuracy`` of the summary).

        :attr:`accuracy` when given, else that of one point of the profile the pair was generated
        from (:attr:`rotorcad.screw_rotors.ScrewRotors.point_accuracy`), at least the design's chord tolerance
        :data:`rotorcad.profile.DEFAULT_TOLERANCE`.
        """
        if self.accuracy is not None:
            return float(self.accuracy)
        point = getattr(self.rotors, "point_accuracy", None)
        given = float(getattr(self.rotors, "accuracy", 0.0) if point is None else point)
        return max(given, DEFAULT_TOLERANCE)

    @cached_property
    def defects(self) -> list[Defect]:
        """Cusps, jamming and slipping points on the meshline (Rinder sec. 2.2.1), a list of :class:`Defect`.

        :func:`rotorcad.meshing.defects.meshline_defects` of :attr:`pieces`, judged to
        :attr:`judged_accuracy`.
        """
        return self._defects[0]

    @cached_property
    def _defects(self) -> tuple[list[Defect], list[np.ndarray], list[Defect]]:
        """:attr:`defects`, point-generated samples per piece, the jamming the input can neither show nor rule out."""
        generated: list[np.ndarray] = []
        below: list[Defect] = []  # meshline_defects' ``below``
        pair, acc = self.rotors.pair, self.judged_accuracy
        return meshline_defects(self.pieces, pair, acc, self.tolerance, self.is_given, generated, below), generated, below

    @property
    def point_generated_flanks(self) -> list[dict[str, str]]:
        """Flanks traced by a single corner of the mate (punkterzeugt), each once, in one wording whatever the form.

        A list of dicts with ``rotor``, ``flank`` (the corner's name on its lobe part, as a defect there reads),
        ``flank_role`` and ``generated_by`` (:func:`rotorcad.rack_roles.point_generated_flanks`).
        """
        pair = self.rotors.pair
        return point_generated_flanks(self.rotors.rack, pair.male_pitch_radius, pair.male_addendum)

    # ---- running without timing gears (1.2, 2.2.1) -----------------------------------------
    @property
    def tip_corner_tolerance(self) -> float:
        """How near a tip circle a cusp must lie to be that tip's corner (:func:`is_tip_corner`), mm.

        1e-4 of the centre distance (12 µm at a = 116 mm): far below any flank's extent, far above
        the meshline's sampling error at a corner's end; for a profile given to a coarser accuracy
        (:attr:`judged_accuracy`, measured points) 20 times that accuracy, the distance by which a
        corner found from points may sit off its tip circle; of scattered points (whose tangents are
        known to a scatter, :attr:`rotorcad.screw_rotors.ScrewRotors.tangent_accuracy`) at least the
        resolution of the defect tests at that accuracy (:func:`rotorcad.meshing.defects.resolution`),
        along which their fit places a cusp no better: the narrow-tip male with 1-2 µm of scatter (80
        and 300 points a lobe, or 300 fitted with ``--smoothing`` 0.001-0.01 mm²) put the female tip
        corner's cusp 0.19-0.20 mm inside its tip circle (20 accuracies: 0.05-0.17 mm), and the
        sealing flank read "does not run". Not of exact points or drawings, whose fits place a cusp
        to their accuracy (the resolution, 0.58 mm and more, would take a flank's own cusp near a tip
        for the corner).
        """
        pair = self.rotors.pair
        scattered = float(getattr(self.rotors, "tangent_accuracy", 0.0)) > 0.0
        reach = resolution(self.judged_accuracy, pair.center_distance) if scattered else 0.0
        return max(1e-4 * pair.center_distance, 20.0 * self.judged_accuracy, reach)

    @cached_property
    def flanks(self) -> dict[Flank, FlankReport]:
        """Per flank (driving, sealing): working part, defects and contact ratios (Rinder sec. 1.2, 2.2.1).

        :func:`rotorcad.meshing.contact_ratios.flank_reports`; a dict Flank -> :class:`FlankReport`. A
        given profile's working part counts from its resolution (:func:`rotorcad.meshing.defects.resolution`),
        its contacts within the meshline's accuracy (:data:`MESHLINE_GAIN` times its own) of a tip corner or
        a land from none (:func:`rotorcad.meshing.contact_ratios.resolved_steps`), and a curve contact between the
        male tip corner's path and the female's shorter than the meshline's resolution is their hand-over
        (:func:`rotorcad.meshing.contact_ratios.is_corner_handover`). (Counting every working part from the
        meshline's resolution made Krigar's male at 300 exact points a lobe run as the design but dropped the
        short working parts of SRM-B's and the asymmetric SRM's sealing flanks from their CSVs; only the
        hand-over between two corners' paths is judged so.)
        """
        band = MESHLINE_GAIN * self.judged_accuracy if self.is_given else 0.0
        shortest = resolution(self.judged_accuracy, self.rotors.pair.center_distance) if self.is_given else 0.0
        handover = handover_length(self.judged_accuracy, self.rotors.pair.center_distance) if self.is_given else 0.0
        generated, tol = self._defects[1] if self.is_given else None, self.tip_corner_tolerance
        pair = self.rotors.pair
        return flank_reports(self.pieces, self.defects, pair, tol, shortest, band, handover, generated, self._defects[2])

    @property
    def running_reasons(self) -> list[str]:
        """Why the pair does not run without timing gears, one sentence per flank (empty: it runs)."""
        return running_reasons(self.flanks, self.defects, self.rotors.pair, self.tip_corner_tolerance, self._defects[2])

    # ---- one angle convention (Rinder Figs. 10-13) -------------------------------------------
    @cached_property
    def angle_reference(self) -> float:
        """Male rotation (rad) at which the middle of a male tip lies on O1O2, the zero of :meth:`rinder_angle`.

        Read off the male section (:func:`tip_on_centre_line`), so it does not depend on how the
        profile was given; of the passages one pitch apart, the one nearest the middle of the
        meshline's range of angles.
        """
        pair = self.rotors.pair
        ring = np.asarray(self.sections[0].exterior.coords)
        tolerance = 1e-4 * max(pair.male_addendum, 1e-3)
        return tip_on_centre_line(ring, pair.male_teeth, pair.male_tip_radius, tolerance, self.contact_angles)

    def rinder_angle(self, t: np.ndarray | float) -> np.ndarray | float:
        """Male rotation angle in the convention of every angle rotorcad shows (deg).

        phi = male rotation still to go until the middle of a male tip reaches the line of centres
        O1O2 (the lobe pointing at O2): positive before, negative after that instant. In this count
        the male tip reaches the housing cusp on the sealing side at a negative angle, as in
        Rinder's Figs. 10-13 and sec. 3.2 ("Drehwinkelstellung von ca. -25°").

        Parameters
        ----------
        t : float or (n,) float array, rad
            Male rotation angle of the meshing engine (:attr:`contact_angles`).

        Returns
        -------
        float or (n,) float array, deg
        """
        return np.degrees(self.angle_reference - np.asarray(t, dtype=float))

    def lobe_angle(self, t: float) -> float:
        """Return the :meth:`rinder_angle` of one contact, taken within half a male pitch of zero (deg).

        A point of the meshline is in contact once per male pitch; the count that names it (a
        defect's, an infinite slip's) is the one nearest the instant the male tip's middle passes O1O2,
        within +-180/z1 (every design's lies there). A rack derived from a female's points runs a
        period on from the design's, and the male tip's slipping read +72.1 deg for the design's +0.2.
        """
        half = 180.0 / self.rotors.pair.male_teeth
        return float((self.rinder_angle(t) + half) % (2.0 * half) - half)

    # ---- tightness (2.2.2) -----------------------------------------------------------------
    @cached_property
    def cusp(self) -> np.ndarray:
        """The housing cusp that the meshline comes nearest, (2,) float, mm.

        The intersection of the tip circles above O1O2, or its mirror image below (the upper one
        when the meshline comes as near both, for a given profile within its resolution).
        """
        k = self.rotors.pair.housing_cusp
        pts = self.meshline
        lower = k * np.array([1.0, -1.0])
        # of a given profile, a preference within its resolution is a tie, which goes to the upper cusp
        # as the design's does (the symmetric SRM's meshline comes as near both; 1 µm of scatter chose either)
        tie = resolution(self.judged_accuracy, self.rotors.pair.center_distance) if self.is_given else 0.0
        upper_gap = nearest_hypot(pts[:, 0] - k[0], pts[:, 1] - k[1])[1]  # np.hypot(*(pts - k).T).min()
        lower_gap = nearest_hypot(pts[:, 0] - lower[0], pts[:, 1] - lower[1])[1]
        return k if upper_gap <= lower_gap + tie else lower

    @cached_property
    def meshline_end(self) -> np.ndarray:
        """Meshline point nearest the housing cusp :attr:`cusp`, (2,) float, mm.

        The nearest sample, then the nearest contact between its neighbours along the rack piece
        (two rounds of 200 contacts): where the meshline turns sharply inside one piece (a rack
        fitted through points carries the design's piece ends inside it), the turn's point lies
        between samples. Of a given profile whose touching point there lies on a circular arc, the
        point of that arc's closed-form meshline (:meth:`_arc_apex`).
        """
        return self._apex[0]

    @cached_property
    def _apex(self) -> tuple[np.ndarray, tuple | None]:
        """The apex (:attr:`meshline_end`) and, where it comes from a male arc, the arguments of its search.

        The second item is None or (centre, radius, window, near, reach, bores) of
        :func:`rotorcad.meshing.apex.circle_meshline_apex` with the arc's fitted window
        (:func:`rotorcad.meshing.apex.arc_at`), for :attr:`blow_hole_uncertainty`.
        """
        pts = self.meshline
        k = self.cusp
        i = nearest_hypot(pts[:, 0] - k[0], pts[:, 1] - k[1])[0]  # np.argmin(np.hypot(*(pts - k).T))
        sizes = np.cumsum([len(p.points) for p in self.pieces])
        j = int(np.searchsorted(sizes, i, side="right"))
        piece, local = self.pieces[j], i - (int(sizes[j - 1]) if j else 0)
        if piece.rack_index < 0:
            return pts[i], None
        pair = self.rotors.pair
        gen = Generated(self.rotors.rack[piece.rack_index].curve, pair.mesh.rack, pair.mesh.female)
        o2 = np.array([pair.center_distance, 0.0])
        best, lo, hi = pts[i], piece.s[max(local - 1, 0)], piece.s[min(local + 1, len(piece.s) - 1)]
        best_t = float(piece.t[local])  # the male rotation at ``best``
        for _ in range(2):
            s = np.linspace(lo, hi, 201)
            t, x = gen.meshline_contact(s)[:2]  # the meshline alone (the full conjugate's numbers)
            ok = np.isfinite(t) & np.isfinite(x[:, 0]) & np.isfinite(x[:, 1])
            ok &= np.hypot(*x.T) <= pair.male_tip_radius + 1e-3
            ok &= np.hypot(x[:, 0] - o2[0], x[:, 1]) <= pair.female_tip_radius + 1e-3  # x - O2 by columns
            if not ok.any():
                break
            d = np.where(ok, np.hypot(*shifted(x, k, -1.0).T), np.inf)
            m = int(np.argmin(d))
            if d[m] < np.hypot(*(best - k)):
                best, best_t = x[m], float(t[m])
            lo, hi = s[max(m - 1, 0)], s[min(m + 1, len(s) - 1)]
        if self.is_given:
            tips = ((np.zeros(2), pair.male_tip_radius), (o2, pair.female_tip_radius))
            on_tip = self._tip_apex(j, local, tips)
            # a hand-over on the male tip circle (the male tip corner's path ends there) before a given male's lobe
            # arc; on the female's, the arc first: its closed-form meshline passes the cusp at a smooth nearest
            # approach that the female tip corner's path beside it took for a hand-over (the symmetric SRM's male
            # CSV with 1 um of scatter read -10.6 and -12.0 % at seeds 0-1 so; within 1 % from the arc), while an
            # arc fitted at the asymmetric SRM male's tip hand-over put the apex 0.5 mm inside (+72 %)
            # on the male tip circle to the profile's accuracy: a scattered tip corner lies off it by its scatter (the
            # asymmetric SRM male, 80 a lobe with 2 um: 1.3 um out, and a male arc's apex 1.4 mm inside read +197 %)
            on_male_tip = on_tip is not None and abs(float(np.hypot(*on_tip)) - pair.male_tip_radius) <= self.judged_accuracy
            if on_tip is not None and on_male_tip:
                return on_tip, None
            rounded = self._rounding_apex(best, best_t)
            if rounded is not None:
                self.__dict__["_tip_candidates"] = []  # the two circles place it, not the fitted profile's meshline
                return rounded, None
            on_arc = self._arc_apex(best, best_t, tips)
            if on_arc is not None:
                self.__dict__["_tip_candidates"] = []  # the arc's own bound holds (blow_hole_uncertainty)
                return on_arc
            if on_tip is not None:
                return on_tip, None
        return best, None

    def _tip_apex(self, j: int, local: int, tips: tuple) -> np.ndarray | None:
        """Return a given profile's apex where the meshline turns or a tip corner's path hands over, or None.

        :func:`rotorcad.meshing.tip_apex.tip_apex`; the places of it that hold are kept for
        :attr:`blow_hole_uncertainty` (``_tip_candidates``, :attr:`apex_candidates`).
        """
        rotors = self.rotors
        own = PieceRole.FEMALE_CORNER_PATH if rotors.family.startswith("female") else PieceRole.MALE_CORNER_PATH
        scattered = float(getattr(rotors, "tangent_accuracy", 0.0)) > 0.0
        smoothed = float(getattr(rotors, "accuracy", 0.0)) > float(getattr(rotors, "point_accuracy", None) or np.inf)
        args = (self.judged_accuracy, rotors.pair.center_distance, own, scattered, smoothed, rotors.pair, given_of(rotors))
        apex, found = tip_apex(self.pieces, j, local, tips, *args)
        self.__dict__["_tip_candidates"] = found  # read by blow_hole_uncertainty (cached, as a cached_property is)
        return apex

    def _touching_point(self, end: np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray] | None:
        """Return the given male's fitted lobe (dense samples) and its point touching at ``end`` at rotation ``t``, or None.

        The male point (fixed = R(t) male) turned by whole lobe pitches onto the lobe: which lobe touches there
        depends on the datum angle of the given points, the meshline does not. None where it lies off the lobe
        by more than the meshline's accuracy (a corner path's point off the fitted profile).
        """
        pair = self.rotors.pair
        lobe = np.vstack([seg.resampled(DEFAULT_TOLERANCE).points for seg in self.rotors.male_lobe().segments])
        line = shapely.LineString(lobe)
        pitch = 2.0 * np.pi / pair.male_teeth
        turns = [rotate(end, -t - k * pitch) for k in range(pair.male_teeth)]
        point = np.reshape(min(turns, key=lambda p: shapely.distance(shapely.Point(p), line)), 2)
        if shapely.distance(shapely.Point(point), line) > MESHLINE_GAIN * self.judged_accuracy:
            return None
        return lobe, point

    def _rounding_apex(self, end: np.ndarray, t: float) -> np.ndarray | None:
        """Return a given male's apex where its tip rounding meets a flank generated by a circle, or None.

        :func:`rotorcad.meshing.rounding_apex.rounding_apex`, from the given points themselves, within the
        meshline's resolution at :data:`MESHLINE_GAIN` times the accuracy of ``end`` (mm, fixed frame; ``t`` the
        male rotation, rad). Exact points are held to half their accuracy (the chords' sagitta, as 2 sigma), up to
        :data:`EXACT_POINTS_AT_MOST` of them (a denser outline's interpolating spline follows the rounding itself).
        """
        rotors = self.rotors
        given, sigma = getattr(rotors, "given_points", None), float(getattr(rotors, "point_scatter", 0.0))
        if given is not None and sigma <= 0.0 and len(given) <= EXACT_POINTS_AT_MOST:
            sigma = 0.5 * self.judged_accuracy  # exact points: their accuracy (the chords' sagitta) as 2 sigma
        if given is None or sigma <= 0.0 or not rotors.family.startswith("male"):
            return None
        touching = self._touching_point(end, t)
        if touching is None:
            return None
        reach = resolution(MESHLINE_GAIN * self.judged_accuracy, rotors.pair.center_distance)
        found = rounding_apex(given, sigma, *touching, end, t, self.meshline, self.contact_angles, reach, rotors.pair, self.cusp)
        if found is None:
            return None
        self.__dict__["_rounding_model"] = found[1]  # read by apex_rounding
        return found[0]

    def _arc_apex(self, end: np.ndarray, t: float, bores: tuple) -> tuple[np.ndarray, tuple] | None:
        """Return the apex from the closed-form meshline of a male arc (:mod:`rotorcad.meshing.apex`), or None.

        ``end`` (mm, fixed frame) is the meshline end found from the samples, ``t`` (rad) the male
        rotation at it. Where the male point that touches there lies on a circular arc of the fitted
        profile (all its samples within :attr:`judged_accuracy` of one circle over at least four
        resolutions, :func:`rotorcad.meshing.defects.resolution`), the apex is that circle's
        meshline point nearest the cusp, within the meshline's resolution of ``end``; with it the
        search's arguments (:attr:`_apex`). The apex is the meshline's point nearest the cusp, so a
        closed-form one of exact points or a drawing farther from the cusp than the sampled end, beyond
        the meshline's accuracy (:data:`MESHLINE_GAIN` times the profile's), is not that arc's contact
        (the narrow-tip male as exact points turned -41 deg: a circle fitted at the meshline's end put the
        apex 52 µm farther out, blow-hole 2.877 mm² for 2.773 at 0 deg); None then. Not of scattered
        points, whose nearest sample lies nearer the cusp than their meshline by the scatter's wander (the
        symmetric SRM's male with 1 µm of scatter: its arc's apex 29-93 µm beyond the nearest sample, and
        that sample's blow-hole -8 %).
        """
        pair = self.rotors.pair
        acc = self.judged_accuracy
        touching = self._touching_point(end, t)
        if touching is None:
            return None  # the contact is not on this lobe (a corner path's point off the fitted profile)
        lobe, point = touching
        arc = arc_at(lobe, point, acc, 4.0 * resolution(acc, pair.center_distance))
        if arc is None:
            return None
        c = np.array([pair.male_pitch_radius, 0.0])
        reach = resolution(MESHLINE_GAIN * acc, pair.center_distance)
        apex = circle_meshline_apex(arc[0], arc[1], c, self.cusp, end, reach, bores, arc[2])
        if apex is None:
            return None  # no contact within reach
        scattered = float(getattr(self.rotors, "tangent_accuracy", 0.0)) > 0.0
        if not scattered and np.hypot(*(apex - self.cusp)) > np.hypot(*(end - self.cusp)) + MESHLINE_GAIN * acc:
            return None  # farther from the cusp than the meshline's own end: not its arc
        return apex, (arc[0], arc[1], arc[2], end, reach, bores)

    @property
    def meshline_closed(self) -> bool:
        """The meshline runs into the housing cusp (Rinder 2.2.2), within 1 micrometre.

        Of a given profile also when its blow-hole area does not exceed the uncertainty it states
        (:attr:`blow_hole_uncertainty`) nor :data:`BLOW_HOLE_RESOLUTION` of the female flute's area
        (below the smallest open blow-hole Rinder ranks): the input cannot tell that meshline from a
        closed one. The Lysholm male with 1 µm of scatter (300 points a lobe) ended its meshline 22 µm
        from the cusp, 0.0001 ± 0.115 mm² of blow-hole, and read "open" (design: closed).
        """
        if np.hypot(*(self.meshline_end - self.cusp)) < 1e-3:
            return True
        small = min(self.blow_hole_uncertainty, BLOW_HOLE_RESOLUTION * self.female_flute_area)
        return bool(self.is_given and self.blow_hole_area <= small)

    @cached_property
    def blow_hole(self) -> shapely.Geometry:
        """Projected blow-hole polygon (see the module docstring)."""
        return self.blow_hole_at(self.meshline_end)

    def blow_hole_at(self, e: np.ndarray) -> shapely.Geometry:
        """Return the projected blow-hole polygon with its apex at ``e`` ((2,) float, mm, fixed frame)."""
        pair = self.rotors.pair
        k = self.cusp
        if np.hypot(*(e - k)) < 1e-3:
            return shapely.Polygon()
        o2 = np.array([pair.center_distance, 0.0])
        r1, r2 = pair.male_tip_radius, pair.female_tip_radius
        em = e / np.hypot(*e) * r1
        ef = o2 + (e - o2) / np.hypot(*(e - o2)) * r2

        def arc(center: np.ndarray, r: float, a: np.ndarray, b: np.ndarray) -> np.ndarray:
            t0 = np.arctan2(*(a - center)[::-1])
            t1 = np.arctan2(*(b - center)[::-1])
            t1 = wrap_angle(t1, t0)
            th = np.linspace(t0, t1, 200)
            return center + r * np.stack([np.cos(th), np.sin(th)], axis=1)

        ring = np.vstack([[e], arc(o2, r2, ef, k), arc(np.zeros(2), r1, k, em), [e]])
        return shapely.make_valid(shapely.Polygon(ring))

    @property
    def blow_hole_area(self) -> float:
        """Area of the projected blow-hole :attr:`blow_hole`, mm²."""
        return float(self.blow_hole.area)

    @cached_property
    def blow_hole_uncertainty(self) -> float:
        """How far the blow-hole area may lie from the true profile's, from the input's accuracy (mm²).

        :func:`rotorcad.meshing.blow_hole_accuracy.blow_hole_uncertainty`; 0 for a design.
        """
        return blow_hole_uncertainty(self)

    @property
    def blow_hole_resolved(self) -> bool:
        """Tell whether the input resolves the blow-hole (always for a design).

        :func:`rotorcad.meshing.blow_hole_accuracy.blow_hole_resolved`.
        """
        return blow_hole_resolved(self)

    @property
    def apex_arc(self) -> tuple | None:
        """Where the apex comes from a male arc's closed-form meshline, the arguments of its search, else None.

        (centre, radius, window, near, reach, bores) of :func:`rotorcad.meshing.apex.circle_meshline_apex`
        (:meth:`_arc_apex`).
        """
        return self._apex[1]

    @property
    def apex_rounding(self) -> tuple | None:
        """Where a male tip rounding's circles placed the apex (:meth:`_rounding_apex`), their model, else None.

        A :class:`rotorcad.meshing.rounding_apex.RoundingModel` (the rounding's centre and radius, the flank's body
        and its circle's centre and radius, mm; the points they were fitted to).
        """
        self._apex  # noqa: B018 (sets _rounding_model)
        return self.__dict__.get("_rounding_model")

    @cached_property
    def _rounding_moves(self) -> list:
        """:func:`rotorcad.meshing.rounding_apex.moved_crossings` of :attr:`apex_rounding` by :data:`ROUNDING_STEP`."""
        return moved_crossings(self.apex_rounding, ROUNDING_STEP, self.rotors.pair)

    @cached_property
    def apex_rounding_uncertainty(self) -> float:
        """Return how far the blow-hole area may be off where a male tip rounding's circles placed the apex (mm²), else inf.

        :func:`rotorcad.meshing.rounding_apex.area_bound` with every point within :attr:`judged_accuracy`, the
        circles' parameters moved by :data:`ROUNDING_STEP`; inf where a step loses the crossing or no rounding placed
        the apex. It holds where the model does (:attr:`apex_rounding_check`).
        """
        model = self.apex_rounding
        if model is None or any(m is None for m in self._rounding_moves):
            return float("inf")
        areas = [self.blow_hole_at(m[0]).area for m in self._rounding_moves]
        return area_bound(model, areas, self.blow_hole_area, ROUNDING_STEP, self.judged_accuracy, self.rotors.pair)

    @cached_property
    def apex_rounding_check(self) -> str | None:
        """Why the tip rounding's two circles do not hold as the points' model (one sentence), None where they do.

        :func:`rotorcad.meshing.rounding_apex.model_check`; "no rounding placed the apex" where none did.
        """
        if self.apex_rounding is None:
            return "no rounding placed the apex"
        pair, acc, scattered = self.rotors.pair, self.judged_accuracy, float(getattr(self.rotors, "point_scatter", 0.0)) > 0
        return model_check(self.apex_rounding, self.meshline_end, self._rounding_moves, ROUNDING_STEP, acc, pair, scattered)

    @property
    def apex_candidates(self) -> list[np.ndarray]:
        """The other places of a tip corner's hand-over apex that hold (:meth:`_tip_apex`), each (2,) float, mm."""
        self._apex  # noqa: B018 (sets _tip_candidates)
        return self.__dict__.get("_tip_candidates", [])

    @cached_property
    def spatial_blow_hole(self) -> SpatialBlowHole:
        """The blow-hole triangle in 3D (:mod:`rotorcad.blow_hole`).

        Its apex is the meshline end nearest the cusp (:attr:`meshline_end`, the apex of the projected
        blow-hole), at the height of the meshline sample nearest it (:func:`rotorcad.blow_hole.apex_height`:
        from the section where the nearest male tip's middle lies on O1O2, not from the contact line's
        start, which moves with where the lobe was cut).
        """
        pts, end = self.meshline, self.meshline_end
        i = int(np.argmin(np.hypot(*(pts - end).T)))
        pair = self.rotors.pair
        z = apex_height(float(self.contact_angles[i]), self.angle_reference, pair.lead, pair.male_teeth)
        return SpatialBlowHole(pair, end, z, self.cusp)

    # ---- contact line (eq. 1) ------------------------------------------------------------
    @cached_property
    def contact_line(self) -> np.ndarray:
        """3D contact (sealing) line, (n, 3) float, mm.

        Meshline points with z = h1 alpha / 2 pi (Rinder eq. 1, alpha the male rotation angle), shifted
        to start at z = 0 and cut at the rotor length.
        """
        pair = self.rotors.pair
        pts = self.meshline
        z = pair.lead * self.contact_angles / (2 * np.pi)
        line = np.column_stack([pts, z - z.min()])
        return line[line[:, 2] <= pair.length + 1e-9]

    @property
    def contact_line_length(self) -> float:
        """Length of the polyline :attr:`contact_line`, mm."""
        line = self.contact_line
        return float(row_norms(np.diff(line, axis=0)).sum())  # np.linalg.norm(..., axis=1), the same numbers

    # ---- areas and displacement ------------------------------------------------------------
    @cached_property
    def sections(self) -> tuple[shapely.Polygon, shapely.Polygon]:
        """Transverse sections of the male and the female, each in its own frame (shapely polygons, mm)."""
        return self.rotors.section("male"), self.rotors.section("female")

    @property
    def male_flute_area(self) -> float:
        """Male flute area A1 = (bore area - rotor section) / z1, mm² (bore = male tip circle)."""
        pair = self.rotors.pair
        return float((np.pi * pair.male_tip_radius**2 - self.sections[0].area) / pair.male_teeth)

    @property
    def female_flute_area(self) -> float:
        """Female flute area A2 = (bore area - rotor section) / z2, mm² (bore = female tip circle)."""
        pair = self.rotors.pair
        return float((np.pi * pair.female_tip_radius**2 - self.sections[1].area) / pair.female_teeth)

    @property
    def displacement_per_rev(self) -> float:
        """Displacement per male revolution V = z1 L (A1 + A2), mm³."""
        pair = self.rotors.pair
        return pair.male_teeth * pair.length * (self.male_flute_area + self.female_flute_area)

    @property
    def area_utilisation(self) -> float:
        """Share of the two bores' area that is flute: (z1 A1 + z2 A2) / (pi r1t^2 + pi r2t^2)."""
        pair = self.rotors.pair
        flutes = pair.male_teeth * self.male_flute_area + pair.female_teeth * self.female_flute_area
        return float(flutes / (np.pi * (pair.male_tip_radius**2 + pair.female_tip_radius**2)))

    # ---- sliding velocity and slip (eqs. 2-4) ----------------------------------------------
    @cached_property
    def kinematics(self) -> dict[str, np.ndarray]:
        """Velocities and slips at every contact of :attr:`meshline` (Rinder eqs. 2-4).

        A dict of (n,) float arrays: ``v1t`` and ``v2t``, the rotors' velocities along the common
        tangent (m/s, eq. 2); ``sliding``, the sliding velocity v_g = v1t - v2t (m/s, eq. 3); ``slip_male`` and
        ``slip_female``, the slips v_g / v1t and v_g / v2t (eq. 4; infinite where a tangential velocity
        vanishes); ``angle_deg``, the male angle in Rinder's count (deg, :meth:`rinder_angle`);
        ``normal_check``, the cross product of the tangent with the relative velocity (zero: the law
        of gearing holds).
        """
        v = self.velocities
        keys = ("v1t", "v2t", "sliding", "slip_male", "slip_female")
        return {**{k: v[k] for k in keys}, "angle_deg": self.rinder_angle(self.contact_angles), "normal_check": v["normal_check"]}

    @cached_property
    def velocities(self) -> dict[str, np.ndarray]:
        """:attr:`kinematics` without ``angle_deg`` (Rinder eqs. 2-4): no section needed (a sweep's figures)."""
        pair = self.rotors.pair
        w1 = self.speed_rpm * 2 * np.pi / 60.0
        w2 = -w1 * pair.male_teeth / pair.female_teeth
        pts = self.meshline
        tau = np.concatenate([p.tangents for p in self.pieces])
        o2 = np.array([pair.center_distance, 0.0])
        v1 = w1 * np.stack([-pts[:, 1], pts[:, 0]], axis=1)
        d2 = shifted(pts, o2, -1.0)
        v2 = w2 * np.stack([-d2[:, 1], d2[:, 0]], axis=1)
        v1t = dots(v1, tau) * 1e-3
        v2t = dots(v2, tau) * 1e-3
        vg = v1t - v2t
        z1, z2 = slip(vg, v1t), slip(vg, v2t)
        return {"v1t": v1t, "v2t": v2t, "sliding": vg, "slip_male": z1, "slip_female": z2, "normal_check": cross(tau, v1 - v2)}

    @cached_property
    def slip_singularities(self) -> list[dict[str, object]]:
        """Points of infinite slip: where a rotor's tangential velocity vanishes (Rinder eq. 4, sec. 3.2).

        :func:`rotorcad.meshing.slip.slip_singularities` of the meshline, a given profile's judged to its
        accuracy (the meshline's, :data:`MESHLINE_GAIN` times the profile's, and its resolution).

        Returns
        -------
        list of dict
            ``rotor`` (whose slip is infinite), ``x``, ``y`` (mm), ``angle_deg`` (:meth:`lobe_angle`),
            ``flank`` (lobe part), ``male_radius``, ``female_radius`` (mm).
        """
        v = self.velocities
        given = self.is_given
        band = MESHLINE_GAIN * self.judged_accuracy if given else 0.0
        reach = resolution(self.judged_accuracy, self.rotors.pair.center_distance) if given else 0.0
        found = slip_singularities(
            self.pieces, {"male": v["v1t"], "female": v["v2t"]}, self.rotors.pair, band, reach, self.judged_accuracy
        )
        return [
            {
                "rotor": f["rotor"],
                "x": f["x"],
                "y": f["y"],
                "angle_deg": self.lobe_angle(f["t"]),
                **{k: f[k] for k in ("flank", "male_radius", "female_radius")},
            }
            for f in found
        ]

    def _max(self, key: str) -> dict[str, float]:
        """Return the largest magnitude of a :attr:`kinematics` entry and where it occurs.

        A dict with ``value``, ``x``, ``y`` (mm), ``angle_deg`` (:meth:`lobe_angle`: a piece of a rack
        derived from points may hold contacts a male pitch on), ``flank`` and both radii (mm).
        """
        k = self.kinematics
        v = np.abs(k[key])
        v = np.where(np.isfinite(v) | np.isinf(v), v, -1.0)  # an infinite slip is the largest (nan: 0 / 0 left out)
        i = int(np.argmax(v))
        p = self.meshline[i]
        pair = self.rotors.pair
        roles = np.concatenate([piece.roles for piece in self.pieces])
        infinite = {"value_infinite": bool(np.isinf(v[i]))} if key.startswith("slip") else {}  # JSON null and this flag
        return {
            **infinite,
            "value": float(v[i]),
            "x": float(p[0]),
            "y": float(p[1]),
            "angle_deg": self.lobe_angle(float(self.contact_angles[i])),  # within +-180/z1, as the defects'
            "flank": str(roles[i]),
            "male_radius": float(np.hypot(*p)),
            "female_radius": float(np.hypot(p[0] - pair.center_distance, p[1])),
        }

    def defect_dicts(self) -> list[dict[str, object]]:
        """Return :attr:`defects` as plain values, angles in Rinder's count and each cusp's reading.

        Returns
        -------
        list of dict
            :meth:`Defect.as_dict` with ``angle_deg`` converted by :meth:`rinder_angle` and
            ``tip_corner`` (bool): the cusp is a rotor's tip corner or its point-generated path
            (:func:`is_tip_corner`), not a defect of a working flank.
        """
        out = []
        pair = self.rotors.pair
        spacing = self._corner_spacing
        for d in self.defects:
            row = d.as_dict()
            row["angle_deg"] = self.lobe_angle(np.radians(d.angle_deg))
            row["tip_corner"] = is_tip_corner(d, pair, self.tip_corner_tolerance)
            if row["tip_corner"]:  # one name of the corner whatever the input (a design's piece, a fit's)
                row["flank"] = tip_corner_name(d.role, self._corner_of(d))
            out.append(mark_decided(row, d, self.pieces, pair, spacing))
        return out

    def _corner_of(self, defect: Defect) -> Side:
        """Return the rotor whose tip corner a tip-corner cusp is.

        Its own for a corner's path (its normal through its centre all along), else the rotor on whose tip
        circle it lies (a hand-over to a mate's corner path), as the pictures label it.
        """
        if defect.point_generated:
            return Side(defect.rotor)
        pair = self.rotors.pair
        on_male_tip = abs(np.hypot(defect.x, defect.y) - pair.male_tip_radius) <= self.tip_corner_tolerance
        return Side.MALE if on_male_tip else Side.FEMALE

    @property
    def _corner_spacing(self) -> float:
        """The given points' spacing (mm) within which a tip corner is undecided (:mod:`rotorcad.meshing.undecided`), else 0."""
        return float(getattr(self.rotors, "point_spacing", None) or 0.0) if self.is_given else 0.0

    def undecided_defect_dicts(self) -> list[dict[str, object]]:
        """Return the tip corners the given points can neither show nor rule out (``undecided_defects`` of the summary).

        :func:`rotorcad.meshing.undecided.undecided_corners` of each rotor where no tip-corner cusp was
        found, as :meth:`defect_dicts` rows with ``decided`` false (none of a drawing), after the jamming the input
        can neither show nor rule out (:func:`rotorcad.meshing.undecided.possible_rows`). Empty for a design.

        Returns
        -------
        list of dict
        """
        spacing, rows = self._corner_spacing, possible_rows(self._defects[2])
        if not spacing:
            return rows
        pair = self.rotors.pair
        reach = resolution(MESHLINE_GAIN * self.judged_accuracy, pair.center_distance)
        near = max(self.tip_corner_tolerance, spacing)
        return rows + undecided_rows(self.pieces, pair, spacing, near, reach, self.defect_dicts())

    def summary(self) -> dict[str, object]:
        """Return the analysis as plain values (the figures of ``rotorcad rotor --json``).

        Returns
        -------
        dict
            Tooth counts, centre distance (mm), family, ``meshline_closed``, blow-hole areas (mm²),
            the blow-hole's uncertainty (mm²) and whether the input resolves it, the spatial blow-hole,
            contact-line length (mm), flute areas (mm²), displacement per
            revolution (mm³), area utilisation, the largest sliding velocity (m/s) and slips with where
            they occur, the points of infinite slip, speed (rpm), the angle convention, defects (with
            ``tip_corner``), point-generated flanks, per-flank reports (working part, transverse,
            overlap and total contact ratio), the pair's overlap ratio, whether the pair runs without
            timing gears and why not, wrap angle (deg). Angles in Rinder's count (:meth:`rinder_angle`).
        """
        pair = self.rotors.pair
        return {
            "male_teeth": pair.male_teeth,
            "female_teeth": pair.female_teeth,
            "center_distance": pair.center_distance,
            "family": self.rotors.family,
            "meshline_closed": self.meshline_closed,
            "blow_hole_area": self.blow_hole_area,
            "blow_hole_uncertainty": self.blow_hole_uncertainty,
            "blow_hole_resolved": self.blow_hole_resolved,
            "blow_hole_spatial": self.spatial_blow_hole.as_dict(),
            "contact_line_length": self.contact_line_length,
            "male_flute_area": self.male_flute_area,
            "female_flute_area": self.female_flute_area,
            "displacement_per_rev": self.displacement_per_rev,
            "area_utilisation": self.area_utilisation,
            "max_sliding_velocity": self._max("sliding")["value"],
            "max_sliding_at": self._max("sliding"),
            "max_slip_male": self._max("slip_male"),
            "max_slip_female": self._max("slip_female"),
            "slip_singularities": self.slip_singularities,
            "speed_rpm": self.speed_rpm,
            "angle_convention": ANGLE_CONVENTION,
            "defects": self.defect_dicts(),
            "undecided_defects": self.undecided_defect_dicts(),
            "defect_accuracy": self.judged_accuracy,
            # the meshline stretch the normals' tests resolve (rotorcad.meshing.defects.meshline_defects): not seen within it
            "defect_resolution": resolution((MESHLINE_GAIN if self.is_given else 1) * self.judged_accuracy, pair.center_distance),
            "point_generated_flanks": self.point_generated_flanks,
            "flanks": {str(f): r.as_dict() for f, r in self.flanks.items()},
            "overlap_contact_ratio": float(pair.wrap_angle * pair.male_teeth / (2 * np.pi)),
            "runs_without_timing_gears": all(r.runs_without_timing_gears for r in self.flanks.values()),
            "running_reasons": self.running_reasons,
            "wrap_angle_deg": float(np.degrees(pair.wrap_angle)),
        }
