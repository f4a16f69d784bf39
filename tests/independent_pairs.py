"""Screw-rotor pairs made without rotorcad: the reference inputs of the inverse-path tests.

Nothing here imports rotorcad. A rack is drawn in closed form (straight flanks, flats at the tip
and root lines, corners rounded by circular arcs) and each rotor is cut from it by brute force
(``cut_rotor``): the blank disc minus the rack at thousands of rolling positions (shapely polygon
booleans), which leaves scallops as a real cut does. Such a rotor has tip and root lands (the
images of the rack's flats), involute flanks (Litvin, *Gear Geometry and Applied Theory*, sec.
10: a straight rack flank of pressure angle alpha generates the involute of the circle
r_w cos(alpha)), fillets from the roundings, and a sharp corner at each tip where the rack's flat
cuts back what its flank and rounding would generate beyond the tip circle (a rack point at height
y touches at the radius sqrt((r_w + y)^2 + (y tan(alpha))^2) > r_w + y). ``resample`` and
``one_lobe`` turn the cut outline into what a CMM or a drawing gives.

Frames as in rotorcad's CONTRACT.md: the male centre at the origin, the female at (a, 0); rack
frame x along the pitch line (the rack moves +x as the male turns counter-clockwise), y = 0 on the
pitch line, y > 0 towards the female. The male's material is below the rack curve, the female's
above it.
"""

from __future__ import annotations

import functools
import hashlib
import inspect
import itertools
import os
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely


@dataclass(frozen=True)
class TrapezoidRack:
    """One period of a trapezoidal rack in the rack frame (mm, rad).

    ``flank_angle`` is each flank's angle to the normal of the pitch line (the pressure angle),
    ``height`` how far the rack reaches above and below the pitch line, ``corner_radius`` the
    rounding of the four corners, ``top_flat`` the width of the flat at y = +height (the male tip
    land's image), measured between the unrounded corners. ``flank_offset`` moves the trailing
    (x-decreasing) flank along its normal into the female side (+, the female thinner there) and
    ``offset_step`` applies that offset as a step only between the flank's end points (a ground
    correction), otherwise it is a smooth bump that fades out over the corner roundings.
    """

    period: float
    height: float = 8.0
    flank_angle: float = np.radians(30.0)
    corner_radius: float = 1.5
    top_flat: float | None = None
    flank_offset: float = 0.0

    @property
    def run(self) -> float:
        """Width of one straight flank across the full height (unrounded)."""
        return 2 * self.height * np.tan(self.flank_angle)

    @property
    def flat(self) -> float:
        return (self.period - 2 * self.run) / 2 if self.top_flat is None else self.top_flat

    def pieces(self) -> list[tuple[str, object]]:
        """The period as (kind, geometry) pieces from x = 0, travelled in +x: lines as
        ('line', (a, b)), arcs as ('arc', (centre, radius, psi0, psi1)), psi about the centre."""
        h, a, r = self.height, self.flank_angle, self.corner_radius
        top, bottom = self.flat, self.period - 2 * self.run - self.flat
        # unrounded corners: from the middle of the bottom flat, a rising flank, the top flat, a
        # falling flank, to the middle of the next bottom flat
        x1 = bottom / 2
        dx = self.flank_offset / np.cos(a)  # a parallel flank moved by the offset along its normal
        c = [(0.0, -h), (x1, -h), (x1 + self.run, h), (x1 + self.run + top + dx, h), (x1 + 2 * self.run + top + dx, -h)]
        # each corner rounded: the arc tangent to both neighbours; its set-back along each line
        turn = np.pi / 2 - a  # between a flat and a flank
        back = r * np.tan(turn / 2)
        up = np.array([np.sin(a), np.cos(a)])  # rising flank direction
        down = np.array([np.sin(a), -np.cos(a)])
        ex = np.array([1.0, 0.0])
        out: list[tuple[str, object]] = []

        def arc(corner, d_in, d_out, convex_up):
            p_in = np.asarray(corner) - back * d_in
            p_out = np.asarray(corner) + back * d_out
            n_in = np.array([-d_in[1], d_in[0]]) * (1 if convex_up else -1)  # towards the centre
            centre = p_in + r * n_in
            psi0 = np.arctan2(*(p_in - centre)[::-1])
            psi1 = np.arctan2(*(p_out - centre)[::-1])
            return p_in, p_out, ("arc", (tuple(centre), r, psi0, psi1))

        # corner 1 (bottom flat -> rising flank): concave seen from above, the arc turns left
        p1i, p1o, a1 = arc(c[1], ex, up, True)
        p2i, p2o, a2 = arc(c[2], up, ex, False)
        p3i, p3o, a3 = arc(c[3], ex, down, False)
        p4i, p4o, a4 = arc(c[4], down, ex, True)
        out.append(("line", ((0.0, -h), tuple(p1i))))
        out.append(a1)
        out.append(("line", (tuple(p1o), tuple(p2i))))
        out.append(a2)
        out.append(("line", (tuple(p2o), tuple(p3i))))
        out.append(a3)
        out.append(("line", (tuple(p3o), tuple(p4i))))
        out.append(a4)
        out.append(("line", (tuple(p4o), (self.period, -h))))
        return out

    def polygon_chain(self, tolerance: float = 1e-5) -> np.ndarray:
        """One period as a polyline (lines by their ends, arcs to the chord ``tolerance``), for
        cutting; the end point (x = period) is left out."""
        pts = []
        for kind, g in self.pieces():
            if kind == "line":
                pts.append(np.asarray([g[0]]))
            else:
                centre, r, psi0, psi1 = g
                n = max(int(np.ceil(abs(psi1 - psi0) / np.sqrt(8 * tolerance / r))), 1)
                psi = psi0 + (psi1 - psi0) * np.arange(n) / n
                pts.append(np.asarray(centre) + r * np.column_stack([np.cos(psi), np.sin(psi)]))
        return np.vstack(pts)

    def sample(self, step: float = 0.01) -> tuple[np.ndarray, np.ndarray]:
        """Points of one period (x from 0 to the period) and unit normals towards the female
        (+y side), exact for every piece, spaced about ``step`` mm."""
        pts, nrm = [], []
        for kind, g in self.pieces():
            if kind == "line":
                a, b = np.asarray(g[0]), np.asarray(g[1])
                n = max(int(np.ceil(np.hypot(*(b - a)) / step)), 1)
                u = np.arange(n) / n
                p = a + u[:, None] * (b - a)
                d = (b - a) / np.hypot(*(b - a))
                pts.append(p)
                nrm.append(np.broadcast_to([-d[1], d[0]], p.shape))
            else:
                centre, r, psi0, psi1 = g
                n = max(int(np.ceil(abs(psi1 - psi0) * r / step)), 1)
                psi = psi0 + (psi1 - psi0) * np.arange(n) / n
                p = np.asarray(centre) + r * np.column_stack([np.cos(psi), np.sin(psi)])
                radial = np.column_stack([np.cos(psi), np.sin(psi)])
                # the +y normal: outward on an arc turning right (convex up), inward otherwise
                nrm.append(radial if psi1 < psi0 else -radial)
                pts.append(p)
        return np.vstack(pts), np.vstack(nrm)


@dataclass(frozen=True)
class ArcFlankRack(TrapezoidRack):
    """A rack whose rising flank is straight (``flank_angle``) and whose falling flank is a circular
    arc of radius ``arc_radius`` crossing the pitch line at ``arc_angle`` from its normal, its centre
    on the male side (a convex flank whose pressure angle grows from the bottom to the top flat);
    the four corners rounded with ``corner_radius`` (the roundings at the arc tangent to it: their
    centres at R - r, or R + r, from the arc's centre). The flats cut the rotors' tips back to sharp
    corners as in :class:`TrapezoidRack`."""

    arc_radius: float = 40.0
    arc_angle: float = np.radians(30.0)

    def _arc(self) -> tuple[np.ndarray, float, float]:
        """The flank circle's centre relative to its pitch-line point, and its unrounded x extent
        relative to that point at the top and the bottom flat."""
        h, big, a = self.height, self.arc_radius, self.arc_angle
        c = big * np.array([-np.cos(a), -np.sin(a)])
        x_top = c[0] + np.sqrt(big**2 - (h - c[1]) ** 2)
        x_bottom = c[0] + np.sqrt(big**2 - (-h - c[1]) ** 2)
        return c, x_top, x_bottom

    @property
    def flat(self) -> float:
        _, x_top, x_bottom = self._arc()
        return (self.period - self.run - (x_bottom - x_top)) / 2 if self.top_flat is None else self.top_flat

    def pieces(self) -> list[tuple[str, object]]:
        h, a, r, big = self.height, self.flank_angle, self.corner_radius, self.arc_radius
        c_rel, x_top, x_bottom = self._arc()
        top = self.flat
        bottom = self.period - self.run - top - (x_bottom - x_top)
        x1 = bottom / 2
        x_t = x1 + self.run + top  # the unrounded top corner of the arc flank
        centre = np.array([x_t - x_top, 0.0]) + c_rel
        up = np.array([np.sin(a), np.cos(a)])
        ex = np.array([1.0, 0.0])
        back = r * np.tan((np.pi / 2 - a) / 2)

        def line_arc(corner, d_in, d_out, convex_up):  # the rounding between two lines
            p_in = np.asarray(corner) - back * d_in
            p_out = np.asarray(corner) + back * d_out
            n_in = np.array([-d_in[1], d_in[0]]) * (1 if convex_up else -1)
            cc = p_in + r * n_in
            return p_in, p_out, ("arc", (tuple(cc), r, np.arctan2(*(p_in - cc)[::-1]), np.arctan2(*(p_out - cc)[::-1])))

        p1i, p1o, a1 = line_arc((x1, -h), ex, up, True)
        p2i, p2o, a2 = line_arc((x1 + self.run, h), up, ex, False)
        # top rounding: centre on y = h - r, inside the flank circle (R - r from its centre)
        y = h - r
        fx = centre[0] + np.sqrt((big - r) ** 2 - (y - centre[1]) ** 2)
        f_top = np.array([fx, y])
        t_flat = np.array([fx, h])
        t_arc = centre + big * (f_top - centre) / np.hypot(*(f_top - centre))
        a3 = ("arc", (tuple(f_top), r, np.pi / 2, np.arctan2(*(t_arc - f_top)[::-1])))
        # bottom rounding: centre on y = -h + r, outside the flank circle (R + r from its centre)
        y = -h + r
        fx = centre[0] + np.sqrt((big + r) ** 2 - (y - centre[1]) ** 2)
        f_bot = np.array([fx, y])
        b_arc = centre + big * (f_bot - centre) / np.hypot(*(f_bot - centre))
        b_flat = np.array([fx, -h])
        a4 = ("arc", (tuple(f_bot), r, np.arctan2(*(b_arc - f_bot)[::-1]), -np.pi / 2))
        psi_top = np.arctan2(*(t_arc - centre)[::-1])
        psi_bottom = np.arctan2(*(b_arc - centre)[::-1])
        flank = ("arc", (tuple(centre), big, psi_top, psi_bottom))
        return [
            ("line", ((0.0, -h), tuple(p1i))),
            a1,
            ("line", (tuple(p1o), tuple(p2i))),
            a2,
            ("line", (tuple(p2o), tuple(t_flat))),
            a3,
            flank,
            a4,
            ("line", (tuple(b_flat), (self.period, -h))),
        ]


@dataclass(frozen=True)
class Pair:
    """Tooth counts, centre distance and the rack of an independent pair."""

    male_teeth: int
    female_teeth: int
    center_distance: float
    rack: TrapezoidRack

    @property
    def male_pitch_radius(self) -> float:
        return self.center_distance * self.male_teeth / (self.male_teeth + self.female_teeth)

    @property
    def female_pitch_radius(self) -> float:
        return self.center_distance - self.male_pitch_radius

    def radii(self) -> dict[str, float]:
        h = self.rack.height
        return {
            "male_tip_radius": self.male_pitch_radius + h,
            "male_root_radius": self.male_pitch_radius - h,
            "female_tip_radius": self.female_pitch_radius + h,
            "female_root_radius": self.female_pitch_radius - h,
        }


def trapezoid_4_6(**rack: float) -> Pair:
    """The issue's pair: 4/6, a = 100 mm, 30 deg flanks, 8 mm above and below the pitch line,
    corners rounded with 1.5 mm, tip radii 48 / 68, root radii 32 / 52."""
    period = 2 * np.pi * 40.0 / 4
    return Pair(4, 6, 100.0, TrapezoidRack(period, **rack))


def arc_flank_5_6() -> Pair:
    """Another rack and other lobe counts: 5/6, a = 100 mm, the rising flank straight at 25 deg,
    the falling flank a circular arc of radius 40 mm crossing the pitch line at 30 deg (44 deg at
    the top flat, 17 deg at the bottom), 7 mm above and below the pitch line, corners rounded with
    1.2 mm; both rotors' tips cut back to sharp corners by the flats."""
    period = 2 * np.pi * (100.0 * 5 / 11) / 5
    rack = ArcFlankRack(period, height=7.0, flank_angle=np.radians(25.0), corner_radius=1.2)
    return Pair(5, 6, 100.0, rack)


def rounded_male(ring: np.ndarray, radius: float) -> np.ndarray:
    """The male outline with its convex (tip) corners rounded by ``radius`` (a morphological opening
    with shapely: shrunk by the radius and grown back), counter-clockwise, without a repeated end."""
    poly = shapely.Polygon(ring).buffer(-radius, quad_segs=256).buffer(radius, quad_segs=256)
    out = np.asarray(poly.exterior.coords)[:-1]
    return out if shapely.LinearRing(out).is_ccw else out[::-1]


def _rot(p: np.ndarray, angle: np.ndarray) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.column_stack([c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1]])


def arc_flank_male_envelope(k: float = 1.0) -> np.ndarray:
    """The 5/6 male's true conjugate of :func:`arc_flank_5_6`'s rack, one lobe in the male's own frame, mm.

    Closed form (Wu & Chi eq. 4): each rack point is cut where its normal passes through the pitch point, at the
    rack shift ``off`` and male turn (off - x) / r1; the rack sampled at 2 um chords, its flats (no such normal)
    left out; every length scaled by ``k``.
    """
    rp = arc_flank_5_6()
    pts, nrm = rp.rack.sample(0.002)
    r1 = rp.male_pitch_radius
    steep = np.abs(nrm[:, 1]) > 1e-6
    pts, nrm = pts[steep], nrm[steep]
    off = pts[:, 1] * nrm[:, 0] / nrm[:, 1]
    return k * _rot(np.column_stack([r1 + pts[:, 1], off]), -(off - pts[:, 0]) / r1)


REFERENCE_DATA = Path(__file__).resolve().parent / "reference_data"


def stored(kind: str, key: str, compute: Callable[[], np.ndarray]) -> np.ndarray:
    """The brute-force result named by ``kind`` and ``key`` (the repr of every input), from its
    file in tests/reference_data when there is one, else computed. With the environment variable
    ROTORCAD_WRITE_REFERENCES=1 (tests/make_reference_data.py sets it) a computed result is
    written there. The files hold what the functions below compute (a test regenerates one and
    compares); they save seconds to minutes of shapely booleans per run of the suite."""
    path = REFERENCE_DATA / f"{kind}_{hashlib.sha256(key.encode()).hexdigest()[:16]}.npy"
    writing = os.environ.get("ROTORCAD_WRITE_REFERENCES") == "1"
    if path.exists():
        if writing:
            _note_used(path)
        return np.load(path)
    if not writing:
        warnings.warn(
            f"tests/reference_data has no {path.name} ({kind}): computed here; python tests/make_reference_data.py stores it",
            stacklevel=2,
        )
    result = compute()
    if writing:
        REFERENCE_DATA.mkdir(exist_ok=True)
        np.save(path, result)
        _note_used(path)
    return result


def _note_used(path: Path) -> None:
    """Add a stored file's name to tests/reference_data/.used (tests/make_reference_data.py --prune keeps those)."""
    with open(REFERENCE_DATA / ".used", "a") as used:
        used.write(path.name + "\n")


def _digest(value: object) -> str:
    """The text of one input in a stored result's key: an array by its shape and its bytes' SHA-256."""
    if isinstance(value, np.ndarray):
        data = np.ascontiguousarray(value, dtype=float)
        return f"array{data.shape}:{hashlib.sha256(data.tobytes()).hexdigest()}"
    return repr(value)


_STORING: list[str] = []  # the stored brute forces being computed now (one inside another is not stored apart)


def stored_by_inputs(kind: str, *uses: Callable) -> Callable[[Callable[..., np.ndarray]], Callable[..., np.ndarray]]:
    """Decorator: the brute force's result through :func:`stored`, keyed by every argument (arrays by
    their bytes) and by the source text of the function and of the functions it ``uses``: a stored
    result is read only for the very inputs and code that computed it (an edited brute force or
    other points compute anew). The undecorated function is the wrapper's ``brute_force``."""

    def wrap(func: Callable[..., np.ndarray]) -> Callable[..., np.ndarray]:
        signature = inspect.signature(func)
        code = hashlib.sha256("".join(inspect.getsource(f) for f in (func, *uses)).encode()).hexdigest()

        @functools.wraps(func)
        def read_or_compute(*args: object, **kwargs: object) -> np.ndarray:
            if _STORING:  # inside another stored brute force: that one's result is stored
                return func(*args, **kwargs)
            bound = signature.bind(*args, **kwargs)
            bound.apply_defaults()
            key = repr((code, [(name, _digest(value)) for name, value in bound.arguments.items()]))
            _STORING.append(kind)
            try:
                return stored(kind, key, lambda: func(*args, **kwargs))
            finally:
                _STORING.pop()

        read_or_compute.brute_force = func  # type: ignore[attr-defined]
        return read_or_compute

    return wrap


@functools.lru_cache(maxsize=8)
def cut_rotor(pair: Pair, rotor: str, positions: int = 3000) -> np.ndarray:
    """:func:`cut_rotor_brute_force`, read from tests/reference_data when stored there."""
    return stored("cut_rotor", repr((pair, rotor, positions)), lambda: cut_rotor_brute_force(pair, rotor, positions))


def cut_rotor_brute_force(pair: Pair, rotor: str, positions: int = 3000) -> np.ndarray:
    """The rotor cut by brute force: its tip disc minus the rack (the other rotor's side of the
    rack curve) at ``positions`` rolling positions over one full turn (shapely union, then
    difference). Returns the outer ring, counter-clockwise, without a repeated end point."""
    r1, r2, a = pair.male_pitch_radius, pair.female_pitch_radius, pair.center_distance
    rk = pair.rack
    pts = rk.polygon_chain()
    tip = (r1 if rotor == "male" else r2) + rk.height
    reach = tip + rk.period  # the rack beyond this never reaches the blank
    periods = int(np.ceil(reach / rk.period))
    strip = np.vstack([pts + np.array([k * rk.period, 0.0]) for k in range(-periods, periods + 1)])
    strip = strip[np.abs(strip[:, 0]) <= reach]
    far = 2 * rk.height
    if rotor == "male":
        tool = np.vstack([strip, [[strip[-1, 0], far], [strip[0, 0], far]]])  # the female side
        pitch = r1
    else:
        tool = np.vstack([strip, [[strip[-1, 0], -far], [strip[0, 0], -far]]])  # the male side
        pitch = r2
    # one full turn of the rotor; the rack is periodic, so only its shift modulo the period matters
    shift = np.linspace(0.0, 2 * np.pi * pitch, positions, endpoint=False)  # rack travel s
    polys = []
    for s in shift:
        fixed = np.column_stack([r1 + tool[:, 1], tool[:, 0] + np.mod(s, rk.period)])
        if rotor == "male":  # the male turned counter-clockwise by s / r1
            polys.append(_rot(fixed, np.full(len(fixed), -s / r1)))
        else:  # the female turned clockwise by s / r2
            polys.append(_rot(fixed - np.array([a, 0.0]), np.full(len(fixed), s / r2)))
    tools = shapely.polygons(polys)
    cut = shapely.Point(0, 0).buffer(tip, quad_segs=2048).difference(shapely.unary_union(tools))
    if isinstance(cut, shapely.MultiPolygon):
        cut = max(cut.geoms, key=lambda g: g.area)
    ring = np.asarray(cut.exterior.coords)[:-1]
    if shapely.LinearRing(ring).is_ccw is False:
        ring = ring[::-1]
    return ring


def scan(ring: np.ndarray, count: int, phase: float = 0.0, noise: float = 0.0, seed: int = 0) -> np.ndarray:
    """``count`` points evenly spaced along the closed ring (linear interpolation on it, whose chords
    are fine enough for this), the first ``phase`` of a spacing past the ring's first point: as a
    CMM scans, so that sharp corners fall between the points unless ``phase`` puts one on them; with
    Gaussian noise of standard deviation ``noise`` mm along the points' normals (their central chords'),
    drawn from ``seed`` (a CMM's scatter)."""
    closed = np.vstack([ring, ring[:1]])
    u = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(closed, axis=0).T))])
    v = (np.arange(count) + phase) * u[-1] / count
    pts = np.column_stack([np.interp(v, u, closed[:, 0]), np.interp(v, u, closed[:, 1])])
    if noise:
        d = np.roll(pts, -1, axis=0) - np.roll(pts, 1, axis=0)
        normal = np.column_stack([d[:, 1], -d[:, 0]]) / np.hypot(*d.T)[:, None]
        pts = pts + np.random.default_rng(seed).normal(0.0, noise, count)[:, None] * normal
    return pts


def patterned(lobe: np.ndarray, teeth: int) -> np.ndarray:
    """The whole outline of one lobe (root to root, its last point the next lobe's first) turned
    round the rotor ``teeth`` times."""
    turns = 2 * np.pi * np.arange(teeth) / teeth
    c, s = np.cos(turns), np.sin(turns)
    x, y = lobe[:-1, 0], lobe[:-1, 1]
    return np.column_stack([(np.outer(c, x) - np.outer(s, y)).ravel(), (np.outer(s, x) + np.outer(c, y)).ravel()])


def resample(ring: np.ndarray, spacing: float, noise: float = 0.0, seed: int = 0) -> np.ndarray:
    """The closed ring resampled at about ``spacing`` mm along its length (:func:`scan`), with
    Gaussian noise of standard deviation ``noise`` mm along the ring's normals (a CMM's scatter)."""
    closed = np.vstack([ring, ring[:1]])
    n = round(float(np.cumsum(np.hypot(*np.diff(closed, axis=0).T))[-1]) / spacing)
    return scan(ring, n, 0.0, noise, seed)


def one_lobe(ring: np.ndarray, teeth: int, start_deg: float = 0.0) -> np.ndarray:
    """The points of the ring whose polar angle lies within one lobe pitch from ``start_deg``, in
    the ring's order (starting anywhere inside that window)."""
    ang = np.mod(np.degrees(np.arctan2(ring[:, 1], ring[:, 0])) - start_deg, 360.0)
    keep = ang < 360.0 / teeth
    idx = np.flatnonzero(keep)
    # the window's points are one run of the ring, perhaps wrapped past its start
    gap = np.flatnonzero(np.diff(idx) > 1)
    if len(gap):
        idx = np.concatenate([idx[gap[0] + 1 :], idx[: gap[0] + 1]])
    return ring[idx]


def female_cut_by_male(pair: Pair, male: np.ndarray, positions: int = 6000) -> np.ndarray:
    """:func:`female_cut_by_male_brute_force`, read from tests/reference_data when stored there."""
    key = repr((pair, positions, hashlib.sha256(np.ascontiguousarray(male, dtype=float).tobytes()).hexdigest()))
    return stored("female_cut_by_male", key, lambda: female_cut_by_male_brute_force(pair, male, positions))


def female_cut_by_male_brute_force(pair: Pair, male: np.ndarray, positions: int = 6000) -> np.ndarray:
    """The female cut by brute force with the given male outline as the tool (the envelope of the
    male, as a rotor-rotor generating cut makes it): the female's tip disc minus the male at
    ``positions`` mesh positions over one female turn. Returns the outer ring, counter-clockwise,
    without a repeated end point."""
    a, z1, z2 = pair.center_distance, pair.male_teeth, pair.female_teeth
    tip = pair.female_pitch_radius + pair.rack.height
    disc = shapely.Point(a, 0.0).buffer(tip + 0.5, quad_segs=256)
    phi = np.linspace(0.0, 2 * np.pi * z2 / z1, positions, endpoint=False)  # male angle: one female turn
    # the male is periodic by a lobe pitch: turning it by phi is the same as by phi mod pitch
    pitch = 2 * np.pi / z1
    tools = []
    for p1 in phi:
        turned = _rot(male, np.full(len(male), np.mod(p1, pitch)))
        near = shapely.Polygon(turned).intersection(disc)  # only what reaches into the female's disc
        ring = np.asarray(shapely.get_coordinates(near))
        if len(ring) < 3:
            continue
        tools.append(shapely.transform(near, lambda q, p1=p1: _rot(q - np.array([a, 0.0]), np.full(len(q), p1 * z1 / z2))))
    cut = shapely.Point(0.0, 0.0).buffer(tip, quad_segs=2048).difference(shapely.unary_union(tools))
    if isinstance(cut, shapely.MultiPolygon):
        cut = max(cut.geoms, key=lambda g: g.area)
    ring = np.asarray(cut.exterior.coords)[:-1]
    return ring if shapely.LinearRing(ring).is_ccw else ring[::-1]


def write_drawing(path: str, ring: np.ndarray, radii: tuple[float, float], flank: tuple[float, float]) -> None:
    """The closed outline as a CAD drawing would have it (ezdxf, layer PROFILE): the lands (points
    on the tip or root circle of ``radii`` within 0.01 um, the cut's chords) as ARCs about the centre, the flanks
    (points with a radius inside ``flank``) as SPLINEs through their points, everything else (the
    roundings' images, the tip corners) as LWPOLYLINEs."""
    import ezdxf

    r = np.hypot(*ring.T)
    on_circle = np.min(np.abs(r[:, None] - np.asarray(radii)[None, :]), axis=1) < 1e-5
    kind = np.where(on_circle, 0, np.where((r > flank[0]) & (r < flank[1]), 1, 2))
    for _ in range(2):  # runs of fewer than 5 points are drawn with their neighbours as polylines
        edges = np.flatnonzero(np.diff(np.concatenate([[-1], kind, [-1]])) != 0)
        for a, b in itertools.pairwise(edges):
            if b - a < 5:
                kind[a:b] = 2
    start = int(np.flatnonzero(np.diff(kind) != 0)[0]) + 1  # begin at a change of kind
    ring, kind = np.roll(ring, -start, axis=0), np.roll(kind, -start)
    closed = np.vstack([ring, ring[:1]])
    bounds = [*(np.flatnonzero(np.diff(kind) != 0) + 1).tolist(), len(ring)]
    doc = ezdxf.new("R2000")
    msp = doc.modelspace()
    lo = 0
    for hi in bounds:
        pts = closed[lo : hi + 1]  # each run shares its last point with the next run
        if kind[lo] == 0 and len(pts) > 3:  # the arc over the land's own points, a line on to the next run
            radius = float(np.median(np.hypot(*pts[:-1].T)))
            a0, a1 = (float(np.degrees(np.arctan2(p[1], p[0]))) for p in (pts[0], pts[-2]))
            msp.add_arc((0.0, 0.0), radius, a0, a1, dxfattribs={"layer": "PROFILE"})
            end = radius * np.array([np.cos(np.radians(a1)), np.sin(np.radians(a1))])
            msp.add_lwpolyline([tuple(end), tuple(pts[-1])], dxfattribs={"layer": "PROFILE"})
        elif kind[lo] == 1 and len(pts) > 3:
            msp.add_spline(fit_points=[(float(x), float(y), 0.0) for x, y in pts], dxfattribs={"layer": "PROFILE"})
        else:
            msp.add_lwpolyline([(float(x), float(y)) for x, y in pts], dxfattribs={"layer": "PROFILE"})
        lo = hi
    doc.saveas(path)


def ring_distance(ring: np.ndarray, tree, p: np.ndarray) -> np.ndarray:
    """Exact distance (mm) of each point ``p`` ((m, 2)) to a closed ring densified finely enough that the
    nearest segment is one of the two at the nearest vertex (``tree``: a cKDTree of ``ring``'s vertices)."""
    _, k = tree.query(p)
    best = np.full(len(p), np.inf)
    for j in (k - 1, k):  # the segments before and after the nearest vertex
        s0, s1 = ring[np.mod(j, len(ring))], ring[np.mod(j + 1, len(ring))]
        d = s1 - s0
        t = np.clip(np.einsum("ij,ij->i", p - s0, d) / np.einsum("ij,ij->i", d, d), 0.0, 1.0)
        best = np.minimum(best, np.hypot(*(s0 + t[:, None] * d - p).T))
    return best


@stored_by_inputs("closest_approach", _rot, ring_distance)
def closest_approach(
    pair: Pair, female: np.ndarray, male: np.ndarray, positions: int = 2000, window_deg: float = 40.0
) -> np.ndarray:
    """Brute force: for each female point (own frame, (n, 2)), the smallest distance to the male
    outline (closed ring, own frame) over ``positions`` mesh positions, those where the female has
    turned the point to within ``window_deg`` of the line of centres (the mesh; male turned
    counter-clockwise by phi1, female clockwise by phi1 z1 / z2 as in ``cut_rotor``). The distance
    to the ring is exact: the nearest vertex of the ring densified to 5 um (cKDTree), then the two
    segments at it."""
    from scipy.spatial import cKDTree

    a, z1, z2 = pair.center_distance, pair.male_teeth, pair.female_teeth
    ring = np.asarray(shapely.segmentize(shapely.LinearRing(male), 0.005).coords)[:-1]
    tree = cKDTree(ring)
    theta = np.arctan2(female[:, 1], female[:, 0])
    u = np.linspace(-1.0, 1.0, positions)
    out = np.full(len(female), np.inf)
    for chunk in np.array_split(np.arange(len(female)), max(1, len(female) // 64)):
        # the female turned clockwise by phi2 brings the point's polar angle to pi +- window
        phi2 = (theta[chunk] - np.pi)[:, None] + np.radians(window_deg) * u[None, :]
        phi1 = phi2 * z2 / z1
        f = np.repeat(female[chunk], positions, axis=0)
        fixed = _rot(f, -phi2.ravel()) + np.array([a, 0.0])
        p = _rot(fixed, -phi1.ravel())
        out[chunk] = ring_distance(ring, tree, p).reshape(len(chunk), positions).min(axis=1)
    return out


def segment_tree(line: shapely.LineString | shapely.LinearRing) -> shapely.STRtree:
    """The STRtree of a line's segments that :func:`distance_to_line` searches, to be kept by a caller that
    measures against the same line many times (180 000 segments: 0.3 s to build)."""
    coords = np.asarray(line.coords)
    return shapely.STRtree(shapely.linestrings(np.stack([coords[:-1], coords[1:]], axis=1)))


def distance_to_line(points: np.ndarray, line: shapely.LineString | shapely.LinearRing | shapely.STRtree) -> np.ndarray:
    """``shapely.distance(shapely.points(points), line)`` (the exact distance of each point (n, 2)
    to the line's segments, mm), found per point through an STRtree of the segments: the same
    numbers as shapely's, without its scan of every segment for every point (10 s for 50000 points
    against a 20000-vertex ring, 0.2 s this way). ``line`` may be its :func:`segment_tree`."""
    tree = line if isinstance(line, shapely.STRtree) else segment_tree(line)
    (which, _), dist = tree.query_nearest(shapely.points(points), return_distance=True, all_matches=False)
    out = np.full(len(points), np.inf)
    np.minimum.at(out, which, dist)
    return out


@stored_by_inputs("true_gap", _rot, closest_approach.brute_force)
def true_gap(
    pair: Pair, female_ring: np.ndarray, male_ring: np.ndarray, female_points: np.ndarray, positions: int = 1500
) -> np.ndarray:
    """Brute force: the true transverse gap at fitted female points (n, 2) (own frame): each point
    moved onto the true female outline (its nearest point on ``female_ring``, shapely), then its
    closest approach to the true male outline ``male_ring`` over the mesh (``closest_approach``).
    What a clearance read from scattered points of these rotors should give there."""
    ring = shapely.LinearRing(female_ring)
    on = shapely.line_interpolate_point(ring, shapely.line_locate_point(ring, shapely.points(female_points)))
    return closest_approach(pair, shapely.get_coordinates(on), male_ring, positions=positions)
