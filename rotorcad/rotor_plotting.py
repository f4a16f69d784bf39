"""Pictures of a screw-rotor pair in the manner of Rinder's figures.

The pair in mesh with its meshline, defects and blow-hole, and sliding velocity and slip over the
rotation angle in the manner of Rinder's Figs. 10-13, one labelled branch per pair of flanks in
contact. Style: :mod:`rotorcad.plot_style`.
"""

from __future__ import annotations

import textwrap

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from rotorcad import plot_style as ps
from rotorcad.meshing import MeshingAnalysis, is_tip_corner
from rotorcad.plot_style import styled
from rotorcad.roles import Flank, PieceRole, Side

MARKERS = {"cusp": ("v", ps.VERMILLION), "jamming": ("s", ps.PURPLE), "slipping": ("D", ps.YELLOW)}


def defect_label(analysis: MeshingAnalysis, defect) -> str:
    """Return the label a picture writes beside a defect: its kind, the rotor, its reading and flank.

    A cusp that is a tip corner (:func:`rotorcad.meshing.is_tip_corner`) is labelled as that corner,
    not as a defect of the flank (Rinder sec. 2.2.2).
    """
    role = "" if defect.role is None else f", {defect.role} flank"
    if defect.role in (Flank.TIP, Flank.ROOT) and defect.kind == "cusp":
        role = ", both flanks"  # a corner's path across O1O2: the corner of both flanks
    pair = analysis.rotors.pair
    if defect.kind == "cusp" and is_tip_corner(defect, pair, analysis.tip_corner_tolerance):
        if defect.point_generated:
            return f"{defect.rotor} tip corner{role}"
        on_male_tip = abs(np.hypot(defect.x, defect.y) - pair.male_tip_radius) <= analysis.tip_corner_tolerance
        return f"{defect.rotor} cusp at the {Side.MALE if on_male_tip else Side.FEMALE} tip corner{role}"
    if defect.kind == "slipping":
        return f"slipping ({defect.flank})"
    return f"{defect.kind} on the {defect.rotor}{role}"


def flank_verdict(analysis: MeshingAnalysis, flank: Flank) -> str:
    """Return one line of Rinder's verdict on a flank: runs or not, with its contact ratios."""
    r = analysis.flanks[flank]
    verdict = "runs without timing gears" if r.runs_without_timing_gears else "does not run without timing gears"
    if not r.running_decided:  # a given profile whose accuracy cannot decide it (ContactRatioReport.running_decided)
        verdict = f"undecided at the input's accuracy, {verdict} as read"
    return (
        f"{flank} flank: {verdict}; ε_α {r.transverse_contact_ratio:.2f} + ε_β {r.overlap_contact_ratio:.2f} "
        f"= {r.total_contact_ratio:.2f}"
    )


def _draw_defects(ax, analysis: MeshingAnalysis, where) -> None:
    """Mark every defect at ``where(defect)`` (x, y) with its marker and its label (kind, rotor, flank)."""
    for kind, (marker, colour) in MARKERS.items():
        found = [d for d in analysis.defects if d.kind == kind]
        if not found:
            continue
        pts = np.array([where(d) for d in found])
        corners = sum(is_tip_corner(d, analysis.rotors.pair, analysis.tip_corner_tolerance) for d in found)
        text = f"{kind} ({len(found)}" + (f", {corners} of them tip corners)" if corners else ")")
        ax.plot(*pts.T, marker, color=colour, mec=ps.BLACK, mew=0.6, ms=7, ls="none", label=text)
        for n, (d, p) in enumerate(zip(found, pts, strict=True)):
            ax.annotate(
                defect_label(analysis, d),
                p,
                textcoords="offset points",
                xytext=(8, 6 - 11 * (n % 3)) if kind != "slipping" else (8, -14 - 11 * (n % 2)),
                fontsize=6.5,
                color=ps.GREY,
                arrowprops={"arrowstyle": "-", "color": ps.LIGHT_GREY, "lw": 0.5},
            )


def _draw_undecided(ax, analysis: MeshingAnalysis, where=None) -> None:
    """Mark, hollow, the defects the given points can neither show nor rule out (``undecided_defects``).

    Each at ``where(row)`` (default its meshline point (x, y)), labelled with its kind, rotor and flank; none for a
    design.
    """
    rows = analysis.undecided_defect_dicts()
    for kind, (marker, colour) in MARKERS.items():
        found = [r for r in rows if r["kind"] == kind]
        if not found:
            continue
        pts = np.array([where(r) if where else (r["x"], r["y"]) for r in found], dtype=float)
        text = f"undecided {kind} ({len(found)}): the points can neither show nor rule it out"
        ax.plot(*pts.T, marker, color="none", mec=colour, mew=1.2, ms=9, ls="none", label=text)
        for r, p in zip(found, pts, strict=True):
            role = f", {r['flank_role']} flank" if r.get("flank_role") else ""
            ax.annotate(
                f"undecided {kind} on the {r['rotor']}{role}",
                p,
                textcoords="offset points",
                xytext=(8, -16),
                fontsize=6.5,
                color=ps.GREY,
                arrowprops={"arrowstyle": "-", "color": ps.LIGHT_GREY, "lw": 0.5},
            )


def _draw_singularities(ax, analysis: MeshingAnalysis, where) -> None:
    """Mark the points of infinite slip (:attr:`MeshingAnalysis.slip_singularities`) with their rotor and flank."""
    found = analysis.slip_singularities
    if not found:
        return
    pts = np.array([where(f) for f in found])
    ax.plot(*pts.T, "o", mfc="none", mec=ps.VERMILLION, mew=1.4, ms=9, ls="none", label=f"infinite slip ({len(found)})")
    for f, p in zip(found, pts, strict=True):
        ax.annotate(
            f"infinite {f['rotor']} slip, {f['flank']} flank",
            p,
            textcoords="offset points",
            xytext=(8, 10),
            fontsize=6.5,
            color=ps.VERMILLION,
        )


def pair_case(analysis: MeshingAnalysis) -> str:
    """Return ``family z1/z2`` of the analysed pair, as the titles name it."""
    pair = analysis.rotors.pair
    return f"{analysis.rotors.family} {pair.male_teeth}/{pair.female_teeth}"


def pair_settings(analysis: MeshingAnalysis) -> str:
    """Return the pair's dimensions (mm) for a title line."""
    p = analysis.rotors.pair
    return (
        f"a = {p.center_distance:g} mm, r1a = {p.male_tip_radius:g} mm, r1f = {p.male_root_radius:g} mm, "
        f"r2a = {p.female_tip_radius:g} mm, r2f = {p.female_root_radius:g} mm, h1 = {p.lead:g} mm, L = {p.length:g} mm"
    )


@styled
def plot_pair(analysis: MeshingAnalysis, clearance: float = 0.0) -> Figure:
    """Draw the male and the female in mesh at male angle 0 with the meshline and the blow-hole.

    Pitch circles, housing bores, meshline with the flagged points (cusp, jamming, slipping), the
    housing cusp and the (projected) blow-hole; the legend beside the pair.

    Parameters
    ----------
    analysis : MeshingAnalysis
        The analysed pair.
    clearance : float, mm
        Radial clearance of the housing bores over the tip circles.

    Returns
    -------
    matplotlib.figure.Figure
    """
    rotors = analysis.rotors
    pair = rotors.pair
    a = pair.center_distance
    r1, r2 = pair.male_tip_radius + clearance, pair.female_tip_radius + clearance
    aspect = (r1 + a + r2) / (2 * max(r1, r2))
    fig = ps.new_figure(min(3.2 + 4.6 * aspect, 13.0), 5.2)
    ax = fig.add_subplot()
    male, female = analysis.sections
    ax.fill(*male.exterior.xy, facecolor=ps.MALE_FILL, edgecolor=ps.MALE_EDGE, lw=0.7, label=f"male rotor z1 = {pair.male_teeth}")
    fx, fy = female.exterior.xy
    ax.fill(
        np.asarray(fx) + a,
        fy,
        facecolor=ps.FEMALE_FILL,
        edgecolor=ps.FEMALE_EDGE,
        lw=0.7,
        label=f"female rotor z2 = {pair.female_teeth}",
    )
    for centre, r in (((0.0, 0.0), pair.male_pitch_radius), ((a, 0.0), pair.female_pitch_radius)):
        ax.plot(*ps.circle_points(centre, r).T, "--", color=ps.PITCH, lw=0.8)
    bores = [ps.circle_points((0.0, 0.0), r1), ps.circle_points((a, 0.0), r2)]
    for pts in bores:
        ax.plot(*pts.T, "-", color=ps.BORE, lw=1.0)
    ax.plot([], [], "--", color=ps.PITCH, lw=0.8, label="pitch circles")
    ax.plot([], [], "-", color=ps.BORE, lw=1.0, label=f"housing bores (tip + {clearance:g} mm)")
    labelled: set[bool] = set()
    for piece in analysis.pieces:
        working = piece.kind is PieceRole.CURVE
        text = "meshline, working part (common tangent)" if working else "meshline, point-generated part (tip corner)"
        ax.plot(*piece.points.T, "-" if working else ":", color=ps.BLACK, lw=1.6, label=None if working in labelled else text)
        labelled.add(working)
    _draw_defects(ax, analysis, lambda d: (d.x, d.y))
    _draw_undecided(ax, analysis)
    _draw_singularities(ax, analysis, lambda f: (f["x"], f["y"]))
    for flank in (Flank.DRIVING, Flank.SEALING):  # Rinder's verdict written at the flank's meshline
        pts = [p.points[p.roles == flank] for p in analysis.pieces if p.kind is PieceRole.CURVE]
        pts = [q for q in pts if len(q)]
        if not pts:
            pts = [p.points[p.roles == flank] for p in analysis.pieces if (p.roles == flank).any()]
        if pts:
            longest = max(pts, key=len)
            ax.annotate(
                flank_verdict(analysis, flank).replace("; ", "\n"),
                longest[len(longest) // 2],
                textcoords="offset points",
                xytext=(-150, 10 if flank is Flank.SEALING else -24),
                fontsize=6.5,
                arrowprops={"arrowstyle": "-", "color": ps.GREY, "lw": 0.5},
            )
    bh = analysis.blow_hole
    first = True
    for g in getattr(bh, "geoms", [bh]):
        if hasattr(g, "exterior") and not g.is_empty:
            ax.fill(*g.exterior.xy, color=ps.VERMILLION, alpha=0.8, label="blow-hole" if first else None)
            first = False
    ax.plot(
        *analysis.cusp, "*", color=ps.BLACK, ms=10, ls="none", label=f"housing cusp; blow-hole {analysis.blow_hole_area:.3g} mm²"
    )
    ax.plot(pair.male_pitch_radius, 0.0, "o", color=ps.BLACK, ms=3.5)
    ax.annotate("C", (pair.male_pitch_radius, 0.0), textcoords="offset points", xytext=(4, -10), fontsize=8)
    ps.frame(ax, bores, margin=0.02)
    ax.set_xlabel(ps.label("x", "mm"))
    ax.set_ylabel(ps.label("y", "mm"))
    ps.legend_outside(ax)
    closed = "closed" if analysis.meshline_closed else "open"
    runs = "runs" if all(r.runs_without_timing_gears for r in analysis.flanks.values()) else "needs timing gears"
    ps.title(
        fig,
        f"screw-rotor pair {pair_case(analysis)} in mesh: meshline {closed}, {runs} (Rinder 2.2.1)",
        pair_settings(analysis),
    )
    return fig


def branches(analysis: MeshingAnalysis) -> list[tuple[str, slice, str]]:
    """Return the meshline's branches as (label, slice of the kinematics arrays, colour).

    One per rack piece, labelled by the male and the female flank in contact; the same pair of
    flanks keeps one colour.

    Parameters
    ----------
    analysis : MeshingAnalysis
        The analysed pair.

    Returns
    -------
    list of (str, slice, str)
    """
    colours: dict[str, str] = {}
    out = []
    start = 0
    for piece in analysis.pieces:
        n = len(piece.t)
        text = f"male {piece.male_name} ↔ female {piece.female_name}"
        if text not in colours:
            colours[text] = ps.CYCLE[len(colours) % len(ps.CYCLE)]
        out.append((text, slice(start, start + n), colours[text]))
        start += n
    return out


@styled
def plot_sliding(analysis: MeshingAnalysis) -> Figure:
    """Draw sliding velocity and slip over the male rotation angle (Rinder eqs. 3-4, Figs. 10-13).

    Sliding velocity |v_g| (eq. 3) and slip of male and female (eq. 4) over the male rotation angle
    at contact, one line per branch of the meshline (labelled by its flanks). Slip is drawn on a
    symmetric logarithmic scale, so that its run to infinity where a tangential velocity vanishes
    stays visible; a slip that is infinite is marked at the frame's edge.

    Parameters
    ----------
    analysis : MeshingAnalysis
        The analysed pair (its speed sets the velocities, m/s).

    Returns
    -------
    matplotlib.figure.Figure
    """
    k = analysis.kinematics
    ang = k["angle_deg"]
    fig = ps.new_figure(11.0, 7.2)
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    handles = []
    seen: set[str] = set()
    infinite = False
    for text, sl, colour in branches(analysis):
        wrapped = "\n".join(textwrap.wrap(text, 44))
        line = ax1.plot(ang[sl], np.abs(k["sliding"][sl]), "-", color=colour, lw=1.4, label=wrapped)[0]
        if text not in seen:
            handles.append(line)
            seen.add(text)
        for key, style in (("slip_male", "-"), ("slip_female", "--")):
            z = k[key][sl]
            ax2.plot(ang[sl], np.where(np.isfinite(z), z, np.nan), style, color=colour, lw=1.2)
            bad = ~np.isfinite(z) & np.isfinite(ang[sl])
            if bad.any():
                infinite = True
                ax2.plot(ang[sl][bad], np.full(bad.sum(), 1e4), "^", color=colour, ms=5, clip_on=False)
    mags = np.abs(k["sliding"])
    where_vg = {}
    for d in analysis.defects:  # the defect's angle, at the sliding velocity of the nearest contact
        phi = float(analysis.rinder_angle(np.radians(d.angle_deg)))
        i = int(np.argmin(np.hypot(*(analysis.meshline - (d.x, d.y)).T)))
        where_vg[id(d)] = (phi, float(mags[i]) if np.isfinite(mags[i]) else 0.0)
    _draw_defects(ax1, analysis, lambda d: where_vg[id(d)])

    def nearest_contact(row: dict) -> tuple[float, float]:  # an undecided defect at its nearest contact's angle and |v_g|
        i = int(np.argmin(np.hypot(*(analysis.meshline - (row["x"], row["y"])).T)))
        return float(ang[i]), float(mags[i]) if np.isfinite(mags[i]) else 0.0

    _draw_undecided(ax1, analysis, nearest_contact)
    for flank, y in ((Flank.DRIVING, 0.97), (Flank.SEALING, 0.90)):
        ax1.text(0.01, y, flank_verdict(analysis, flank), transform=ax1.transAxes, fontsize=7, va="top")
    ax1.set_ylabel(ps.label("sliding velocity |v_g|", "m/s"))
    ax1.set_title("sliding velocity along each branch of the meshline (Rinder eq. 3)")
    ps.legend_outside(ax1, handles, title="branch: flanks in contact", alignment="left")
    ax2.set_yscale("symlog", linthresh=1.0, linscale=1.0)
    _draw_singularities(ax2, analysis, lambda f: (f["angle_deg"], 1e3))
    ax2.axhline(0.0, color=ps.GREY, lw=0.6)
    finite = np.abs(np.concatenate([k["slip_male"], k["slip_female"]]))
    finite = finite[np.isfinite(finite)]
    top = max(10.0, 10 ** np.ceil(np.log10(max(float(finite.max()) if len(finite) else 1.0, 1.0))))
    ax2.set_ylim(-top, top)
    ax2.set_ylabel(ps.label("slip ζ (symmetric log scale)", "1"))
    ax2.set_xlabel(ps.label("male angle φ1 to go until a male tip's middle is on O1O2", "°"))
    ax2.set_title("slip ζ1 = v_g / v1t and ζ2 = v_g / v2t (Rinder eq. 4), colours as above")
    styles = [
        Line2D([], [], color=ps.GREY, ls="-", label="male slip ζ1"),
        Line2D([], [], color=ps.GREY, ls="--", label="female slip ζ2"),
    ]
    if infinite:
        styles.append(Line2D([], [], color=ps.GREY, marker="^", ls="none", label="|ζ| infinite (v_t = 0)"))
    if analysis.slip_singularities:
        styles.append(
            Line2D([], [], marker="o", mfc="none", mec=ps.VERMILLION, ls="none", label="point of infinite slip (v_t → 0)")
        )
    ps.legend_outside(ax2, styles)
    pair = analysis.rotors.pair
    n2 = analysis.speed_rpm * pair.male_teeth / pair.female_teeth
    peak = analysis.summary()["max_sliding_velocity"] if analysis.pieces else float("nan")
    ps.title(
        fig,
        f"sliding velocity and slip, screw-rotor pair {pair_case(analysis)}",
        f"male {analysis.speed_rpm:g} rpm, female {n2:.4g} rpm, a = {pair.center_distance:g} mm; largest |v_g| = {peak:.3g} m/s",
    )
    return fig


def point_deviation(section, points: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Deviation of measured points from a rotor's section (the profile the pair is built on).

    Parameters
    ----------
    section : shapely.Polygon
        The rotor's transverse section in its own frame (mm).
    points : (n, 2) float, mm
        The measured points, same frame.

    Returns
    -------
    foot : (n, 2) float, mm
        The nearest point of the section's outline to each measured point.
    normal : (n, 2) float
        Unit outward normal of the outline there (the direction of excess material).
    deviation : (n,) float, mm
        Signed normal distance: positive outside the section (material beyond the profile).
    """
    import shapely

    ring = section.exterior
    pts = np.asarray(points, dtype=float)
    geoms = shapely.points(pts)
    foot = shapely.get_coordinates(shapely.line_interpolate_point(ring, shapely.line_locate_point(ring, geoms)))
    dist = np.hypot(*(pts - foot).T)
    sign = np.where(shapely.contains(section, geoms), -1.0, 1.0)
    # the outward normal from the outline's tangent at the foot (a short chord of the exact outline)
    s = shapely.line_locate_point(ring, geoms)
    step = 1e-3
    ahead = shapely.get_coordinates(shapely.line_interpolate_point(ring, (s + step) % ring.length))
    behind = shapely.get_coordinates(shapely.line_interpolate_point(ring, (s - step) % ring.length))
    tangent = ahead - behind
    tangent /= np.linalg.norm(tangent, axis=1, keepdims=True)
    ccw = 1.0 if ring.is_ccw else -1.0
    normal = ccw * np.stack([tangent[:, 1], -tangent[:, 0]], axis=1)
    return foot, normal, sign * dist


@styled
def plot_point_deviation(analysis: MeshingAnalysis, rotor: Side, points: np.ndarray, source: str) -> Figure:
    """Draw measured points against the profile the pair is built on (the smoothed fit of those points).

    The deviation of every point along the profile's normal, magnified with the factor stated, and
    the deviation over the point number with its spread.

    Parameters
    ----------
    analysis : MeshingAnalysis
        The pair built from the points.
    rotor : Side
        Which rotor the points measure.
    points : (n, 2) float array, mm
        The measured points in the rotor's own frame.
    source : str
        The file named in the title.

    Returns
    -------
    matplotlib.figure.Figure
    """
    section = analysis.sections[rotor.pick(0, 1)]
    foot, normal, dev = point_deviation(section, points)
    fig = ps.new_figure(11.0, 5.6)
    ax1, ax2 = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.2, 1.0]})
    ring = np.asarray(section.exterior.coords)
    ax1.plot(*ring.T, "-", color=ps.REFERENCE, lw=0.8, label=f"{rotor} profile built from the points")
    largest = float(np.max(np.abs(dev))) if len(dev) else 0.0
    extent = float(np.ptp(ring, axis=0).max())
    scale = ps.magnification(largest, extent)
    handles = ps.draw_deviation(ax1, foot, normal, dev, scale, what="measured − profile", every=max(1, len(dev) // 400))
    ps.scale_bar(ax1, scale, largest)
    ax1.set_xlabel(ps.label("x", "mm"))
    ax1.set_ylabel(ps.label("y", "mm"))
    ax1.set_title(f"deviation along the normal, ×{scale:g}")
    ps.frame(ax1, [ring])
    ps.legend_below(ax1, ncol=1, handles=[ax1.lines[0], *handles])
    ax2.plot(np.arange(len(dev)), dev * 1e3, ".", color=ps.BLUE, ms=2)
    sigma = float(np.std(dev)) if len(dev) else 0.0
    for k, style in ((1, "--"), (-1, "--")):
        ax2.axhline(k * 2 * sigma * 1e3, color=ps.GREY, ls=style, lw=0.7)
    ax2.axhline(0.0, color=ps.BLACK, lw=0.6)
    ax2.set_xlabel(ps.label("measured point number", "1"))
    ax2.set_ylabel(ps.label("deviation from the profile, outward", "µm"))
    ax2.set_title(f"spread: σ = {sigma * 1e3:.3g} µm (±2σ dashed), largest {largest * 1e3:.3g} µm")
    ps.title(
        fig,
        f"measured {rotor} points ({source}) against the profile of {pair_case(analysis)}",
        f"{len(dev)} points; positive: material outside the profile; {pair_settings(analysis)}",
    )
    return fig
