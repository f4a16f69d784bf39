"""Profiles drawn in CAD: a DXF drawing read into exact curves, chained end to end.

:func:`read_profile_dxf` turns the modelspace entities of one layer into :mod:`rotorcad.curves`
curves without approximation: LINE and straight polyline segments into :class:`Line`, ARC and
bulged polyline segments (LWPOLYLINE, 2D POLYLINE) into :class:`Arc`, non-rational SPLINE into
:class:`Spline` with the drawing's own knots, control points and degree (a SPLINE given only by
fit points through ezdxf's construction tool). The curves are chained end to end (each entity
travelled either way) within :data:`GAP_TOLERANCE` and returned in one direction of travel:

- a closed chain counter-clockwise (positive enclosed area);
- an open chain that runs around the origin with its polar angle increasing: a lobe of a rotor,
  whose chord d from start to end is seen across from the chain's centroid c (|c x d| > |c . d|),
  with |c| >= 0.2 |d| and no point nearer the origin than 0.1 |d|;
- any other open chain (a rack period) with x growing.

:func:`sample_profile_dxf` samples that chain to a chord tolerance, and
:func:`read_profile_points` takes either a DXF drawing or a CSV points file, so a DXF can be used
wherever points are read. Coordinates are taken as millimetres ($INSUNITS is not applied: many
drawings carry a wrong one, ezdxf's own default is metres). Everything that cannot be read as one
profile is refused with one sentence naming the file's option (``label``).
"""

from __future__ import annotations

import re
from collections import Counter
from pathlib import Path

import numpy as np

from exports.csv_points import check_profile, looks_like_dxf, read_points
from exports.reading import check_regular_file
from rotorcad.curves import Arc, Curve, Line, Spline, sample_curve
from rotorcad.errors import DesignError

MAX_EXTENT = 1e5
"""Largest distance of a profile's point from the origin, mm (100 m: no rotor or gear is larger)."""

GAP_TOLERANCE = 1e-3
"""Largest gap between the ends of two entities that are joined, mm."""

CLOSING_GAP = 0.01
"""An open chain whose ends are nearer than this fraction of its extent is an outline that fails
to close (a gap), not a lobe or a rack."""

PROFILE_TYPES = ("LINE", "ARC", "LWPOLYLINE", "POLYLINE", "SPLINE", "CIRCLE", "ELLIPSE")
"""Entity types that count as profile geometry (CIRCLE and ELLIPSE only to be refused)."""

_READ_TYPES = "LINE, ARC, LWPOLYLINE, POLYLINE or SPLINE entities"
_VERTEX_SPLINE_FRAME = 16  # POLYLINE vertex flag: control point of a spline-fit polyline, not on it
_NOTED_GAP = 1e-6  # mm: a closing gap wider than this (not a rounding of the drawing) is closed with a note
_FLAT = 1e-6  # mm: an entity whose z varies more than this is not drawn in a plane z = const

Piece = list[Curve]  # the curves of one entity, already end to end


def _name(entity) -> str:
    return f"{entity.dxftype()} #{entity.dxf.handle}"


def _load(path: Path, label: str):
    """Read the ezdxf document of ``path``; a file ezdxf cannot read is refused with :class:`DesignError`."""
    import ezdxf  # here: commands that only may read a DXF do not pay its import (0.15 s)

    check_regular_file(path, label, "DXF drawing")
    try:
        return ezdxf.readfile(path)
    except PermissionError:
        raise DesignError(label, "a readable DXF drawing", str(path), "permission denied") from None
    except (StopIteration, EOFError):
        raise DesignError(label, "a DXF drawing", str(path), "it ends before the drawing is complete") from None
    except Exception as exc:  # any failure of the parser on foreign input (OSError, DXFStructureError, ValueError, ...)
        reason = (str(exc).strip().splitlines() or [""])[0].rstrip(".")
        reason = reason.replace(f"File '{path}' is", "it is").replace(str(path), "the file")
        reason = re.sub(r"\.\s+", "; ", reason)[:120].strip() or type(exc).__name__
        raise DesignError(label, "a DXF drawing", str(path), f"ezdxf cannot read it ({reason})") from None


def _layer_entities(doc, label: str, value: str, layer: str | None) -> list:
    """Return the profile entities of modelspace on ``layer`` (layer names compared without case).

    Without a layer all profile entities, which must lie on one layer; refusals name the layers found.
    """
    by_layer: dict[str, list] = {}
    names: dict[str, str] = {}
    ignored: Counter[str] = Counter()
    for entity in doc.modelspace():
        kind = entity.dxftype()
        if kind not in PROFILE_TYPES:
            ignored[kind] += 1
            continue
        name = entity.dxf.layer
        names.setdefault(name.casefold(), name)
        by_layer.setdefault(name.casefold(), []).append(entity)
    found = ", ".join(sorted(names.values(), key=str.casefold))
    others = ""
    if ignored:
        others = " (only " + ", ".join(f"{n} {kind}" for kind, n in sorted(ignored.items())) + ")"
        if "INSERT" in ignored:
            others += "; explode blocks first"
    if layer is None:
        if not by_layer:
            raise DesignError(label, "a DXF drawing with a profile in modelspace", value, f"it holds no {_READ_TYPES}{others}")
        if len(by_layer) > 1:
            raise DesignError(
                label,
                "a DXF drawing whose profile entities all lie on one layer unless a layer is named",
                value,
                f"its entities lie on the layers {found}; name one of them as the layer",
            )
        return next(iter(by_layer.values()))
    if layer.casefold() in by_layer:
        return by_layer[layer.casefold()]
    if any(entry.dxf.name.casefold() == layer.casefold() for entry in doc.layers):
        where = f"; the layers with profile entities are {found}" if found else ""
        raise DesignError(
            label, f"a DXF drawing with a profile on the layer {layer!r}", value, f"that layer holds no {_READ_TYPES}{where}"
        )
    table = ", ".join(sorted((entry.dxf.name for entry in doc.layers), key=str.casefold))
    where = f"the layers with profile entities are {found}" if found else f"its layers are {table} and none holds a profile"
    raise DesignError(label, f"a DXF drawing with the layer {layer!r}", value, f"it has no such layer; {where}")


def _ocs_mirror(entity, label: str, value: str) -> bool:
    """Tell whether the entity's object coordinate system is the xy plane seen from below.

    That is extrusion (0, 0, -1): x mirrored. An entity in any other plane is refused.
    """
    n = np.asarray(entity.dxf.extrusion, dtype=float)
    n = n / np.linalg.norm(n)
    if abs(n[0]) > 1e-9 or abs(n[1]) > 1e-9:
        raise DesignError(
            label,
            "a profile drawn in the xy plane",
            value,
            f"{_name(entity)} lies in a plane of normal ({n[0]:.6g}, {n[1]:.6g}, {n[2]:.6g})",
        )
    return bool(n[2] < 0)


def _flat(entity, z: np.ndarray, label: str, value: str) -> None:
    if z.size and np.ptp(z) > _FLAT:
        raise DesignError(
            label,
            "a profile drawn in a plane z = constant",
            value,
            f"z runs from {z.min():.6g} to {z.max():.6g} mm along {_name(entity)}",
        )


def _mirrored(curve: Curve) -> Curve:
    """``curve`` under x -> -x (object coordinates of extrusion (0, 0, -1) to world)."""
    if isinstance(curve, Line):
        return Line((-curve.a[0], curve.a[1]), (-curve.b[0], curve.b[1]))
    if isinstance(curve, Arc):
        return Arc((-curve.center[0], curve.center[1]), curve.radius, np.pi - curve.s0, np.pi - curve.s1)
    raise TypeError(curve)  # pragma: no cover - splines are in world coordinates


def _segment(p0: np.ndarray, p1: np.ndarray, bulge: float) -> Curve | None:
    """Make a polyline segment: straight, or the circular arc of ``bulge``.

    ``bulge`` = tan(included angle / 4), positive counter-clockwise (DXF reference, LWPOLYLINE group
    42). Returns None for a zero-length segment.
    """
    d = p1 - p0
    if not np.any(d):
        return None
    if abs(bulge) * float(np.hypot(*d)) < 2e-12:  # sagitta (bulge x chord / 2) below 1e-12 mm: straight
        return Line((float(p0[0]), float(p0[1])), (float(p1[0]), float(p1[1])))
    # centre on the chord's bisector at (1 - b^2)/(4 b) chord lengths, radius (1 + b^2)/(4|b|) chords
    c = 0.5 * (p0 + p1) + np.array([-d[1], d[0]]) * (1.0 - bulge * bulge) / (4.0 * bulge)
    radius = float(np.hypot(*d)) * (1.0 + bulge * bulge) / (4.0 * abs(bulge))
    s0 = float(np.arctan2(p0[1] - c[1], p0[0] - c[0]))
    return Arc((float(c[0]), float(c[1])), radius, s0, s0 + 4.0 * float(np.arctan(bulge)))


def _polyline(xy: np.ndarray, bulges: np.ndarray, closed: bool) -> Piece:
    n = len(xy)
    count = n if closed else n - 1
    curves = [_segment(xy[i], xy[(i + 1) % n], float(bulges[i])) for i in range(count)]
    return [c for c in curves if c is not None]


def _spline(entity, label: str, value: str) -> Curve:
    """Read a non-rational SPLINE as scipy's (knots, coefficients, degree), kept exact.

    A SPLINE given only by fit points is built by ezdxf's construction tool (degree 3); rational,
    malformed, non-planar or non-finite splines and degrees outside 1 to 5 are refused.
    """
    weights = np.asarray(entity.weights, dtype=float)
    if weights.size and np.ptp(weights) > 1e-12 * np.abs(weights).max():
        raise DesignError(
            label, "a profile of non-rational splines", value, f"{_name(entity)} is a rational spline (weights not all equal)"
        )
    if entity.control_point_count():
        degree = int(entity.dxf.degree)
        control = np.asarray(entity.control_points, dtype=float).reshape(-1, 3)
        knots = np.asarray(entity.knots, dtype=float)
        if knots.size == 0:
            knots = np.asarray(entity.construction_tool().knots(), dtype=float)
    elif entity.fit_point_count():
        tool = entity.construction_tool()  # ezdxf's global interpolation as AutoCAD does it (degree 3)
        degree = int(tool.degree)
        control = np.asarray(tool.control_points, dtype=float).reshape(-1, 3)
        knots = np.asarray(tool.knots(), dtype=float)
    else:
        raise DesignError(
            label, "a profile of complete entities", value, f"{_name(entity)} has neither control points nor fit points"
        )
    _flat(entity, control[:, 2], label, value)
    if not 1 <= degree <= 5:
        raise DesignError(label, "a profile of splines of degree 1 to 5", value, f"{_name(entity)} has degree {degree}")
    if len(knots) != len(control) + degree + 1 or np.any(np.diff(knots) < 0) or not knots[degree] < knots[-degree - 1]:
        raise DesignError(
            label,
            "a profile of well-formed splines",
            value,
            f"{_name(entity)} has {len(knots)} knots for {len(control)} control points of degree {degree}",
        )
    if not (np.isfinite(knots).all() and np.isfinite(control).all()):
        raise DesignError(label, "a profile of finite coordinates", value, f"{_name(entity)} has a NaN or infinite value")
    coefficients = (control[:, 0].copy(), control[:, 1].copy())
    return Spline(knots=(knots, coefficients, degree), s0=float(knots[degree]), s1=float(knots[-degree - 1]))


def _finite(entity, values: np.ndarray, label: str, value: str) -> None:
    """Refuse an entity with a NaN or infinite coordinate or bulge, before any curve is made of it."""
    if not np.isfinite(values).all():
        raise DesignError(label, "a profile of finite coordinates", value, f"{_name(entity)} has a NaN or infinite value")


def _entity_piece(entity, label: str, value: str) -> Piece:
    """Return the curves of one entity in its own order, in world coordinates."""
    kind = entity.dxftype()
    if kind == "CIRCLE":
        raise DesignError(
            label,
            "a profile of lines, arcs, polylines and splines, not a circle",
            value,
            f"{_name(entity)} is a circle of radius {entity.dxf.radius:.6g} mm",
        )
    if kind == "ELLIPSE":
        raise DesignError(label, f"a profile of {_READ_TYPES}", value, f"{_name(entity)} is an ELLIPSE; convert it to a spline")
    if kind == "SPLINE":
        return [_spline(entity, label, value)]
    if kind == "LINE":
        a, b = np.asarray(entity.dxf.start, dtype=float), np.asarray(entity.dxf.end, dtype=float)
        _flat(entity, np.array([a[2], b[2]]), label, value)
        _finite(entity, np.array([a, b]), label, value)
        segment = _segment(a[:2], b[:2], 0.0)
        piece = [] if segment is None else [segment]
    elif kind == "ARC":
        mirror = _ocs_mirror(entity, label, value)
        radius = float(entity.dxf.radius)
        s0, s1 = np.deg2rad(float(entity.dxf.start_angle)), np.deg2rad(float(entity.dxf.end_angle))
        s1 = s0 + (s1 - s0) % (2 * np.pi)  # counter-clockwise in its object coordinates
        if s1 - s0 == 0.0 or s1 - s0 >= 2 * np.pi - 1e-12:
            raise DesignError(
                label, "a profile of lines, arcs, polylines and splines, not a circle", value, f"{_name(entity)} is a full circle"
            )
        centre = np.asarray(entity.dxf.center, dtype=float)
        piece = [Arc((float(centre[0]), float(centre[1])), radius, float(s0), float(s1))] if radius > 0 else []
        if mirror:
            piece = [_mirrored(c) for c in piece]
    elif kind == "LWPOLYLINE":
        mirror = _ocs_mirror(entity, label, value)
        rows = np.asarray(list(entity.get_points("xyb")), dtype=float).reshape(-1, 3)
        _finite(entity, rows, label, value)
        piece = _polyline(rows[:, :2], rows[:, 2], bool(entity.closed))
        if mirror:
            piece = [_mirrored(c) for c in piece]
    else:  # POLYLINE
        if entity.is_poly_face_mesh or entity.is_polygon_mesh:
            raise DesignError(label, f"a profile of {_READ_TYPES}", value, f"{_name(entity)} is a mesh, not a profile")
        vertices = [v for v in entity.vertices if not v.dxf.flags & _VERTEX_SPLINE_FRAME]
        xyz = np.asarray([v.dxf.location for v in vertices], dtype=float).reshape(-1, 3)
        _finite(entity, np.c_[xyz, [v.dxf.bulge for v in vertices]], label, value)
        if entity.is_3d_polyline:  # world coordinates, straight segments
            _flat(entity, xyz[:, 2], label, value)
            piece = _polyline(xyz[:, :2], np.zeros(len(xyz)), bool(entity.is_closed))
        else:
            mirror = _ocs_mirror(entity, label, value)
            bulges = np.asarray([v.dxf.bulge for v in vertices], dtype=float)
            piece = _polyline(xyz[:, :2], bulges, bool(entity.is_closed))
            if mirror:
                piece = [_mirrored(c) for c in piece]
    for curve in piece:
        if not np.isfinite(np.concatenate([curve.start, curve.end])).all():
            raise DesignError(label, "a profile of finite coordinates", value, f"{_name(entity)} has a NaN or infinite value")
    return piece


def _reverse(piece: Piece) -> Piece:
    return [c.reversed() for c in reversed(piece)]


def _chain(pieces: list[Piece], names: list[str], label: str, value: str) -> tuple[Piece, bool]:
    """Join the pieces end to end into one chain, starting from the first; return it and whether it closes.

    Refused with :class:`DesignError`: a branch (two pieces continuing at one joint), pieces left
    out of a closed chain, a gap wider than :data:`GAP_TOLERANCE`, or an open chain whose ends are
    nearly met (:data:`CLOSING_GAP`).
    """
    starts = np.array([p[0].start for p in pieces])
    ends = np.array([p[-1].end for p in pieces])
    free = np.ones(len(pieces), dtype=bool)
    free[0] = False
    chain = list(pieces[0])
    head, tail = starts[0], ends[0]

    def nearest(point: np.ndarray) -> tuple[int, bool, float]:
        ds = np.where(free, np.hypot(*(starts - point).T), np.inf)
        de = np.where(free, np.hypot(*(ends - point).T), np.inf)
        near = (ds <= GAP_TOLERANCE) | (de <= GAP_TOLERANCE)
        if np.count_nonzero(near) > 1:
            which = ", ".join(names[i] for i in np.flatnonzero(near)[:4])
            raise DesignError(
                label,
                "a profile whose entities meet end to end, two at each joint",
                value,
                f"{which} continue the chain at ({point[0]:.6f}, {point[1]:.6f}) mm (a branch or a duplicate entity)",
            )
        i, j = int(np.argmin(ds)), int(np.argmin(de))
        return (i, False, float(ds[i])) if ds[i] <= de[j] else (j, True, float(de[j]))

    closed = bool(np.hypot(*(tail - head)) <= GAP_TOLERANCE)
    joints: list[tuple[float, np.ndarray]] = []  # the gaps joined, and where
    while not closed and free.any():  # forward from the tail
        i, at_end, gap = nearest(tail)
        if gap > GAP_TOLERANCE:
            break
        joints.append((gap, tail))
        free[i] = False
        chain += _reverse(pieces[i]) if at_end else pieces[i]
        tail = starts[i] if at_end else ends[i]
        closed = bool(np.hypot(*(tail - head)) <= GAP_TOLERANCE)
    while not closed and free.any():  # backward from the head
        i, at_end, gap = nearest(head)
        if gap > GAP_TOLERANCE:
            break
        joints.append((gap, head))
        free[i] = False
        chain = (pieces[i] if at_end else _reverse(pieces[i])) + chain
        head = starts[i] if at_end else ends[i]
        closed = bool(np.hypot(*(tail - head)) <= GAP_TOLERANCE)
    if free.any():
        k = int(np.argmax(free))
        if closed:
            raise DesignError(
                label,
                "a DXF drawing with one profile on the layer",
                value,
                f"the closed outline through ({head[0]:.6f}, {head[1]:.6f}) mm leaves {np.count_nonzero(free)} more "
                f"entities out, such as {names[k]} from ({starts[k][0]:.6f}, {starts[k][1]:.6f}) mm",
            )
        gaps = [(*nearest(point), point) for point in (head, tail)]
        i, at_end, gap, point = min(gaps, key=lambda g: g[2])
        other = ends[i] if at_end else starts[i]
        raise DesignError(
            label,
            f"a profile whose entities meet within {GAP_TOLERANCE:g} mm",
            value,
            f"there is a gap of {gap:.6g} mm between ({point[0]:.6f}, {point[1]:.6f}) mm and "
            f"({other[0]:.6f}, {other[1]:.6f}) mm ({names[i]})",
        )
    ends_of_curves = np.array([p for c in chain for p in (c.start, c.end)])
    span = np.hypot(*np.ptp(ends_of_curves, axis=0))  # the chain's extent (one polyline has two ends only)
    gap = float(np.hypot(*(tail - head)))
    if closed:
        joints.append((gap, tail))
    widest, where = max(joints, key=lambda j: j[0], default=(0.0, tail))
    if widest > _NOTED_GAP:
        import warnings

        from rotorcad.errors import InputNote

        warnings.warn(
            f"{label} {value}: the outline was joined across a gap of {widest:.3g} mm at ({where[0]:.6f}, {where[1]:.6f}) mm, "
            f"within the joining accuracy of {GAP_TOLERANCE:g} mm",
            InputNote,
            stacklevel=2,
        )
    if not closed and gap < CLOSING_GAP * span:
        raise DesignError(
            label,
            f"a profile whose entities meet within {GAP_TOLERANCE:g} mm",
            value,
            f"the outline does not close, with a gap of {gap:.6g} mm between ({tail[0]:.6f}, {tail[1]:.6f}) mm "
            f"and ({head[0]:.6f}, {head[1]:.6f}) mm",
        )
    return chain, closed


def _spans(curve: Curve) -> int:
    """Count the polynomial pieces of a spline (knot spans in use); 1 for other curves."""
    if not isinstance(curve, Spline):
        return 1
    lo, hi = sorted((curve.s0, curve.s1))
    knots = np.unique(curve.knots[0])
    return max(1, int(np.count_nonzero((knots > lo) & (knots < hi))) + 1)


def _samples(curve: Curve, tolerance: float) -> np.ndarray:
    """Sample points along ``curve`` to the chord tolerance (mm).

    The ends of a line; on a spline :func:`rotorcad.curves.sample_curve` starts from at least two
    intervals per polynomial piece, so that no piece (an inflection, a small wiggle) lies unseen
    between two first samples.
    """
    if isinstance(curve, Line):
        return np.array([curve.start, curve.end])
    return sample_curve(curve, tolerance, minimum=2 * _spans(curve) + 1)[1]


def _coarse(chain: Piece) -> np.ndarray:
    """Sample points along the chain for its orientation.

    Line ends, and at least 17 points on other curves (two per polynomial piece of a spline).
    """
    parts = []
    for c in chain:
        if isinstance(c, Line):
            parts.append(np.array([c.start, c.end]))
        else:
            parts.append(c.evaluate(np.linspace(c.s0, c.s1, max(17, 2 * _spans(c) + 1)))[0])
    return np.vstack(parts)


def _orient(chain: Piece, closed: bool) -> Piece:
    """Turn the chain into its direction of travel (module docstring).

    Counter-clockwise when closed or running around the origin, else with x growing.
    """
    p = _coarse(chain)
    if closed:
        area = 0.5 * np.sum(p[:-1, 0] * p[1:, 1] - p[1:, 0] * p[:-1, 1])
        return chain if area >= 0 else _reverse(chain)
    length = np.hypot(*np.diff(p, axis=0).T)
    centroid = ((p[:-1] + p[1:]) * 0.5 * length[:, None]).sum(axis=0) / max(length.sum(), 1e-300)
    d = p[-1] - p[0]
    across = abs(centroid[0] * d[1] - centroid[1] * d[0])
    along = abs(centroid @ d)
    chord = np.hypot(*d)
    clear = np.hypot(*p.T).min() >= 0.1 * chord  # a chain through the origin has no polar angle there
    if across > along and np.hypot(*centroid) >= 0.2 * chord and clear:  # a lobe, seen across from the origin
        polar = np.unwrap(np.arctan2(p[:, 1], p[:, 0]))
        turn = polar[-1] - polar[0]
        forward = turn > 0 if turn != 0 else centroid[0] * d[1] - centroid[1] * d[0] > 0
    else:
        forward = d[0] > 0 if d[0] != 0 else d[1] > 0
    return chain if forward else _reverse(chain)


def _shorter_than_a_joint(piece: Piece) -> bool:
    """Tell whether a piece of straight lines is shorter in all than :data:`GAP_TOLERANCE`.

    Such an entity (a LINE between two points of an outline under 1 um apart) would be taken for a
    branch at the joint it lies in; left out, its neighbours are joined across it as across a gap.
    """
    if not all(isinstance(c, Line) for c in piece):
        return False
    return sum(float(np.hypot(*(c.end - c.start))) for c in piece) < GAP_TOLERANCE


def _crossing(chain: Piece, closed: bool) -> np.ndarray | None:
    """Where the chain crosses or runs along itself, mm (2,); None for a simple outline.

    The curves are followed by chords within :data:`GAP_TOLERANCE` of them (lines by their ends),
    so a crossing shallower than that may go unseen; GEOS tells whether the chords are simple
    (:func:`shapely.is_simple`) and an R-tree of the chords finds the first pair that crosses or
    overlaps (chords that only share an end are a joint).
    """
    import shapely

    parts = [_samples(c, GAP_TOLERANCE) for c in chain]
    points = np.vstack([parts[0], *(q[1:] for q in parts[1:])])
    if closed:
        points[-1] = points[0]
    if shapely.is_simple(shapely.linestrings(points)):
        return None
    chords = shapely.linestrings(np.stack([points[:-1], points[1:]], axis=1))
    tree = shapely.STRtree(chords)
    for predicate in ("crosses", "overlaps"):
        pairs = tree.query(chords, predicate=predicate)
        if pairs.shape[1]:
            where = shapely.intersection(chords[pairs[0, 0]], chords[pairs[1, 0]])
            return np.asarray(shapely.get_coordinates(shapely.centroid(where))[0])
    # a chord touching the interior of a chord two or more away (a vertex on the outline)
    near = tree.query(chords, predicate="touches")
    apart = np.abs(near[0] - near[1]) > 1
    if closed:
        apart &= np.abs(near[0] - near[1]) < len(chords) - 1
    if apart.any():
        k = int(np.argmax(apart))
        where = shapely.intersection(chords[near[0, k]], chords[near[1, k]])
        return np.asarray(shapely.get_coordinates(shapely.centroid(where))[0])
    return None


def _read_chain(path: Path, label: str, layer: str | None) -> tuple[Piece, bool]:
    path = Path(path)
    value = str(path)
    doc = _load(path, label)
    entities = _layer_entities(doc, label, value, layer)
    pieces, names = [], []
    for entity in entities:
        piece = _entity_piece(entity, label, value)
        if piece:
            pieces.append(piece)
            names.append(_name(entity))
    if len(pieces) > 1:  # a straight entity shorter than the joining accuracy is a joint, not a piece (nor a branch)
        keep = [not _shorter_than_a_joint(p) for p in pieces]
        if any(keep):
            names = [n for n, k in zip(names, keep, strict=True) if k]
            pieces = [p for p, k in zip(pieces, keep, strict=True) if k]
    if not pieces:
        where = "in modelspace" if layer is None else f"on the layer {layer!r}"
        raise DesignError(label, f"a DXF drawing with a profile {where}", value, "its entities all have zero length")
    chain, closed = _chain(pieces, names, label, value)
    far = max(float(np.hypot(*point)) for c in chain for point in (c.start, c.end))
    if far > MAX_EXTENT:  # e.g. a drawing scaled x1e9: its arcs would be sampled to 0.1 um for hours
        raise DesignError(
            label, f"a profile within {MAX_EXTENT:g} mm of the origin", value, f"a point lies {far:.3g} mm from it (other units?)"
        )
    crossing = _crossing(chain, closed)
    if crossing is not None:  # taken as drawn, such an outline would reach the contact search and fail there
        x, y = crossing
        raise DesignError(label, "an outline that does not cross itself", value, f"it crosses itself at ({x:.6f}, {y:.6f}) mm")
    return _orient(chain, closed), closed


def read_profile_dxf(path: Path, label: str, layer: str | None = None) -> list[Curve]:
    """Read the profile drawn in a DXF file as exact curves, end to end, in one direction of travel.

    Parameters
    ----------
    path : Path
        DXF drawing (ASCII or binary, any version ezdxf reads), coordinates in mm.
    label : str
        The option or key that named the file; it leads the error sentence.
    layer : str or None
        Layer of the profile (case-insensitive). None: all profile entities of modelspace, which
        must then lie on one layer.

    Returns
    -------
    list of Curve
        :class:`~rotorcad.curves.Line`, :class:`~rotorcad.curves.Arc` (``s`` the polar angle in
        rad about its centre) and :class:`~rotorcad.curves.Spline` (``s`` the B-spline
        parameter), each ending within :data:`GAP_TOLERANCE` (mm) of where the next starts. A
        closed chain runs counter-clockwise and ends where it starts; an open chain that runs
        around the origin has its polar angle increasing; any other open chain (a rack) runs
        with x growing.

    Raises
    ------
    DesignError
        With one sentence naming ``label``: not a regular file or over 64 MiB, not a DXF
        drawing, no profile entities, entities on several layers and no ``layer`` (naming
        them), an unknown or empty layer (naming the layers found), a CIRCLE or full ARC, an
        ELLIPSE, a rational SPLINE, an entity out of the xy plane, a gap wider than
        :data:`GAP_TOLERANCE` (naming where), a branch, more than one profile, or an outline that
        crosses or runs along itself (naming where).
    """
    return _read_chain(path, label, layer)[0]


def sample_profile_dxf(path: Path, label: str, layer: str | None = None, tolerance: float = 1e-4) -> np.ndarray:
    """Points along the DXF profile of :func:`read_profile_dxf` to a chord tolerance.

    Parameters
    ----------
    path, label, layer
        As for :func:`read_profile_dxf`.
    tolerance : float
        Largest distance from the chords to the curves, mm (:func:`rotorcad.curves.sample_curve`).
        Straight segments are given by their two ends (exact at any tolerance).

    Returns
    -------
    numpy.ndarray
        Points (n, 2) in mm in the chain's direction of travel, each joint once; a closed profile
        without its repeated end point.

    Raises
    ------
    DesignError
        As :func:`read_profile_dxf`, and for fewer than 4 distinct points, more than 2 000 000
        points, or points all on one straight line (:func:`exports.csv_points.check_profile`).
    """
    if not (np.isfinite(tolerance) and tolerance > 0):
        raise DesignError("tolerance", "a positive length in mm", tolerance)
    chain, closed = _read_chain(path, label, layer)
    parts = []
    for i, curve in enumerate(chain):
        p = _samples(curve, tolerance)
        parts.append(p if i == 0 else p[1:])
    points = np.vstack(parts)
    if closed:
        points = points[:-1]
    return check_profile(points, label, str(path))


def read_profile_points(path: Path, label: str, layer: str | None = None) -> np.ndarray:
    """Profile points from a DXF drawing or a CSV points file, whichever ``path`` is.

    A file whose name ends in ``.dxf`` or whose first bytes are those of a DXF drawing
    (:func:`exports.csv_points.looks_like_dxf`) is sampled by :func:`sample_profile_dxf` at its
    default tolerance; any other file is read by :func:`exports.csv_points.read_points`, and
    ``layer`` is not used.

    Parameters
    ----------
    path : Path
        The file.
    label : str
        The option or key that named the file; it leads the error sentence.
    layer : str or None
        Layer of the profile in a DXF drawing.

    Returns
    -------
    numpy.ndarray
        Points (n, 2) in mm.
    """
    if _is_drawing(path, label):
        return sample_profile_dxf(path, label, layer)
    return read_points(path, label)


def _is_drawing(path: Path, label: str) -> bool:
    """Tell whether ``path`` is a DXF drawing (by its name or its first bytes).

    A path that is not a regular file is refused first (:class:`DesignError`).
    """
    path = Path(path)
    check_regular_file(path, label, "CSV points file or DXF drawing")
    with open(path, "rb") as f:
        head = f.read(512)
    return path.suffix.lower() == ".dxf" or looks_like_dxf(head)


def read_profile(path: Path, label: str, layer: str | None = None) -> np.ndarray | list[Curve]:
    """Read a rotor profile as the user gave it: the exact curves of a DXF drawing or the points of a CSV file.

    Whichever ``path`` is (see :func:`read_profile_points`): a drawing is read by
    :func:`read_profile_dxf` (arcs stay arcs, splines the drawing's splines), a CSV file by
    :func:`exports.csv_points.read_points`.

    Parameters
    ----------
    path : Path
        The file.
    label : str
        The option or key that named the file; it leads the error sentence.
    layer : str or None
        Layer of the profile in a DXF drawing.

    Returns
    -------
    list of Curve or (n, 2) float array, mm
        The curves of a drawing, or the points of a CSV file.

    Raises
    ------
    DesignError
        As :func:`read_profile_dxf` or :func:`exports.csv_points.read_points`.
    """
    if _is_drawing(path, label):
        return read_profile_dxf(path, label, layer)
    return read_points(path, label)
