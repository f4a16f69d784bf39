"""A gear rack part: teeth of the ISO 53 basic rack profile along a given length, outline and solid.

The rack's teeth are the basic rack profile itself (ISO 53: straight flanks at the normal pressure
angle alpha_n, tooth thickness p_n / 2 on the datum line, addendum h_aP* m, dedendum h_fP* m and
the root fillet of radius rho_fP* m tangent to flank and root line), in the normal section. A
helical rack's teeth lie at the helix angle beta across the face: its section along the length (the
transverse section of the gears it meshes with) is the normal one stretched by 1 / cos(beta) along
the length (pitch p_t = pi m / cos(beta), tan(alpha_t) = tan(alpha_n) / cos(beta)), and the solid is
that section extruded across the face with a shear of tan(beta) along the length, exact for the
planar flanks and the fillets' oblique cylinders alike.

Frame: x along the rack's length from 0 to L, y up towards the tips with the datum (pitch) line at
y = 0, the back at y = -height; z across the face from 0 to the face width, the section at z
shifted by z tan(beta) along x. Tooth centres at x = (j + 1/2) p_t, space centres at x = j p_t, so
that a length of whole pitches ends at space centres.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import shapely

from rotorcad.errors import DesignError
from rotorcad.gears.formulas import tool_tip_radius_limit, transverse_pressure_angle
from rotorcad.gears.involute_gear import DEG, MODULE_RANGE
from rotorcad.gears.sampling import arc_intervals, span
from rotorcad.geometry import Array
from rotorcad.profile import DEFAULT_TOLERANCE
from rotorcad.triangle_mesh import TriangleMesh

MAX_RACK_PITCHES = 20_000
"""Most pitches along a rack: its outline (some 60 points a tooth at 0.1 um) stays within a second."""


@dataclass(frozen=True, eq=False)
class GearRack:
    """A straight or helical gear rack of the ISO 53 basic rack profile.

    Parameters
    ----------
    length : float, mm
        Length L along the pitch line, above 0 and at most :data:`MAX_RACK_PITCHES` pitches.
    module : float, mm
        Normal module m, within :data:`~rotorcad.gears.involute_gear.MODULE_RANGE`.
    pressure_angle : float, rad
        Normal pressure angle alpha_n, from 1 to below 45 degrees.
    helix_angle : float, rad
        Helix angle beta of the teeth across the face, between -60 and 60 degrees (exclusive).
    addendum, dedendum : float
        h_aP*, h_fP*, factors of the module, from 0.1 to 3.
    root_radius_factor : float
        rho_fP*: root fillet radius / m, from 0 to the full-radius fillet
        (:func:`~rotorcad.gears.formulas.tool_tip_radius_limit`).
    height : float or None, mm
        From the back to the datum line (None: h_fP* m + 2 m); above h_fP* m.
    tolerance : float, mm
        Chord error of the sampled fillets.

    Raises
    ------
    DesignError
        A value out of its range, naming it (``rack_length``, ``rack_height``, ``module``, ...).
    """

    length: float
    module: float
    pressure_angle: float = 20.0 * DEG
    helix_angle: float = 0.0
    addendum: float = 1.0
    dedendum: float = 1.25
    root_radius_factor: float = 0.38
    height: float | None = None
    tolerance: float = DEFAULT_TOLERANCE

    def __post_init__(self) -> None:
        m = self.module
        if not (np.isfinite(m) and MODULE_RANGE[0] <= m <= MODULE_RANGE[1]):
            raise DesignError("module", f"a length from {MODULE_RANGE[0]:g} to {MODULE_RANGE[1]:g} mm", m)
        if not (1.0 * DEG <= self.pressure_angle < 45.0 * DEG):
            raise DesignError("pressure_angle", "from 1 to below 45 degrees", float(self.pressure_angle / DEG))
        if not (-60.0 * DEG < self.helix_angle < 60.0 * DEG):
            raise DesignError("helix_angle", "between -60 and 60 degrees (exclusive)", round(self.helix_angle / DEG, 6))
        for name, value in (("addendum", self.addendum), ("dedendum", self.dedendum)):
            if not (0.1 <= value <= 3.0):
                raise DesignError(name, "from 0.1 to 3 (factor of the module)", value)
        longest = MAX_RACK_PITCHES * self.pitch
        if not (np.isfinite(self.length) and 0.0 < self.length <= longest):
            raise DesignError(
                "rack_length", f"a length above 0 and at most {longest:.6g} mm ({MAX_RACK_PITCHES} pitches)", self.length
            )
        rho_max = tool_tip_radius_limit(self.pressure_angle, self.dedendum)
        if not (0.0 <= self.root_radius_factor <= rho_max + 1e-12):
            raise DesignError(
                "tip_radius_factor", f"between 0 and {rho_max:.4f} for this pressure angle and dedendum", self.root_radius_factor
            )
        if self.tip_half_width <= 0.0:
            top = np.pi / (4.0 * np.tan(self.pressure_angle))
            raise DesignError("addendum", f"below {top:.4f} so that the rack's tooth has a tip land", self.addendum)
        if self.height is not None and not (np.isfinite(self.height) and self.dedendum * m < self.height <= 1e4):
            raise DesignError("rack_height", f"above the dedendum {self.dedendum * m:.6g} mm and at most 10000 mm", self.height)
        lo, hi = 1e-7 * m, 0.1 * m
        if not (np.isfinite(self.tolerance) and lo <= self.tolerance <= hi):
            raise DesignError("tolerance", f"from {lo:.3g} to {hi:.3g} mm for a module of {m:g} mm", self.tolerance)

    # ----- closed forms (ISO 53, ISO 21771) ------------------------------------------------------
    @property
    def stretch(self) -> float:
        """1 / cos(beta): the transverse section is the normal one stretched along the length by it."""
        return float(1.0 / np.cos(self.helix_angle))

    @property
    def pitch(self) -> float:
        """Transverse pitch p_t = pi m / cos(beta), mm (along the length)."""
        return float(np.pi * self.module * self.stretch)

    @property
    def normal_pitch(self) -> float:
        """Normal pitch p_n = pi m, mm."""
        return float(np.pi * self.module)

    @property
    def transverse_pressure_angle(self) -> float:
        """alpha_t = atan(tan(alpha_n) / cos(beta)), rad: the flank angle of the section along the length."""
        return transverse_pressure_angle(self.pressure_angle, self.helix_angle)

    @property
    def tip_half_width(self) -> float:
        """Half the tip land in the normal section, p_n / 4 - h_aP* m tan(alpha_n), mm."""
        return float(np.pi * self.module / 4.0 - self.addendum * self.module * np.tan(self.pressure_angle))

    @property
    def back_height(self) -> float:
        """Height from the back to the datum line, mm (``height``, or h_fP* m + 2 m)."""
        return float(self.height if self.height is not None else (self.dedendum + 2.0) * self.module)

    @property
    def tooth_count(self) -> int:
        """Whole teeth along the length: those whose tip land lies within 0 <= x <= L."""
        tip = self.tip_half_width * self.stretch
        centres = (np.arange(int(np.ceil(self.length / self.pitch)) + 1) + 0.5) * self.pitch
        return int(np.count_nonzero((centres - tip >= -1e-12) & (centres + tip <= self.length + 1e-12)))

    # ----- the profile ---------------------------------------------------------------------------
    def _half_period(self, tolerance: float) -> Array:
        """From the tooth centre (x = 0) to the space centre (x = p_n / 2), normal section: (n, 2) mm.

        Tip line, flank, root fillet (tangent to the flank and the root line), root line.
        """
        m, a = self.module, self.pressure_angle
        pn = np.pi * m
        rho = self.root_radius_factor * m
        h_a, h_f = self.addendum * m, self.dedendum * m
        yc = -h_f + rho
        xc = pn / 4.0 + (rho - yc * np.sin(a)) / np.cos(a)  # the fillet centre, rho from the flank
        pts = [(0.0, h_a), (pn / 4.0 - h_a * np.tan(a), h_a)]
        if rho > 0.0:
            # the arc from the flank's tangency (direction pi + alpha from the centre) down to the root line
            n = arc_intervals(0.5 * np.pi - a, rho, tolerance * np.cos(self.helix_angle))
            t = span(np.pi + a, 1.5 * np.pi, n + 1)
            pts += list(zip(xc + rho * np.cos(t), yc + rho * np.sin(t), strict=True))
        else:
            pts.append((pn / 4.0 + h_f * np.tan(a), -h_f))
        if pn / 2.0 - xc > 1e-12 * m:
            pts.append((pn / 2.0, -h_f))
        return np.asarray(pts, dtype=float)

    def pieces(self) -> list[tuple]:
        """Return the exact pieces of the section's top along the periods that cover 0 <= x <= L.

        From the space centre at x = -p_t (one period before the rack) to x = (count + 1) p_t, in the
        transverse section (the normal one stretched by k = 1 / cos(beta) along x): straight
        ``("line", (x0, y0), (x1, y1))`` and root fillets ``("ellipse", (cx, cy), k rho, rho, t0,
        t1)``, the points (cx + k rho cos t, cy + rho sin t) from t0 to t1 (a circle for beta = 0).

        Returns
        -------
        list of tuple
            The pieces end to end, mm and rad.
        """
        m, a, k = self.module, self.pressure_angle, self.stretch
        pn = np.pi * m
        rho = self.root_radius_factor * m
        h_a, h_f = self.addendum * m, self.dedendum * m
        yc = -h_f + rho
        xc = pn / 4.0 + (rho - yc * np.sin(a)) / np.cos(a)
        tip = pn / 4.0 - h_a * np.tan(a)
        flank_low = (xc - rho * np.cos(a), yc - rho * np.sin(a)) if rho > 0.0 else (pn / 4.0 + h_f * np.tan(a), -h_f)
        has_root = pn / 2.0 - xc > 1e-12 * m
        out: list[tuple] = []
        count = int(np.ceil(self.length / self.pitch)) + 1
        for j in range(-1, count + 1):
            c = pn / 2.0 + j * pn  # the tooth centre, normal section (the space centres at j pn)

            def pt(x: float, y: float, c: float = c) -> tuple[float, float]:
                return (float((c + x) * k), float(y))

            if has_root:
                out.append(("line", pt(-pn / 2.0, -h_f), pt(-xc, -h_f)))
            if rho > 0.0:  # the left flank's fillet, from the root line up to the flank (mirror of the right one)
                out.append(("ellipse", pt(-xc, yc), k * rho, rho, 1.5 * np.pi, 2.0 * np.pi - a))
            out.append(("line", pt(-flank_low[0], flank_low[1]), pt(-tip, h_a)))
            out.append(("line", pt(-tip, h_a), pt(tip, h_a)))
            out.append(("line", pt(tip, h_a), pt(*flank_low)))
            if rho > 0.0:
                out.append(("ellipse", pt(xc, yc), k * rho, rho, np.pi + a, 1.5 * np.pi))
            if has_root:
                out.append(("line", pt(xc, -h_f), pt(pn / 2.0, -h_f)))
        return out

    def period(self, tolerance: float | None = None) -> Array:
        """One pitch of the section along the length, from space centre to space centre: (n, 2) mm.

        The normal section's period (:meth:`_half_period` and its mirror image) stretched by
        1 / cos(beta) along the length, tooth centre at x = p_t / 2; no repeated end point.

        Parameters
        ----------
        tolerance : float, optional
            Chord error of the fillets, mm (default the rack's ``tolerance``).
        """
        half = self._half_period(self.tolerance if tolerance is None else tolerance)
        right = half[1:] if half[0, 0] == 0.0 else half
        left = half[::-1] * np.array([-1.0, 1.0])
        one = np.concatenate([left[:-1], half[:1], right])  # from -p_n/2 to p_n/2 through the tip centre
        one = one[:-1]  # the next period starts where this one ends
        one[:, 0] = (one[:, 0] + np.pi * self.module / 2.0) * self.stretch
        return one

    def outline(self, tolerance: float | None = None) -> Array:
        """Return the rack's section at z = 0 as a closed counter-clockwise outline, (n, 2) mm.

        The periods along 0 <= x <= L, cut at both ends by the end faces x = 0 and x = L, and the
        back at y = -height; no repeated end point.
        """
        one = self.period(tolerance)
        count = int(np.ceil(self.length / self.pitch)) + 1
        teeth = (one[None, :, :] + np.stack([np.arange(count) * self.pitch, np.zeros(count)], axis=1)[:, None, :]).reshape(-1, 2)
        top = np.concatenate([teeth, [[count * self.pitch, one[0, 1]]]])
        back = -self.back_height
        ring = np.concatenate([top, [[top[-1, 0], back - 1.0], [top[0, 0], back - 1.0]]])
        part = shapely.Polygon(ring).intersection(shapely.box(0.0, back, self.length, self.addendum * self.module + 1.0))
        part = shapely.geometry.polygon.orient(part, 1.0)
        return np.asarray(part.exterior.coords)[:-1]

    @cached_property
    def section(self) -> shapely.Polygon:
        """:meth:`outline` at the rack's tolerance as a polygon."""
        return shapely.Polygon(self.outline())

    def summary(self) -> dict[str, object]:
        """Return the CONTRACT.md keys of the rack (``rack`` of ``rotorcad gear``).

        Returns
        -------
        dict
            ``length``, ``height`` (back to datum line), ``pitch`` (transverse, along the length),
            ``normal_pitch``, ``tooth_thickness`` (on the datum line along the length, p_t / 2),
            ``addendum``, ``dedendum`` (mm), ``pressure_angle_deg`` and ``transverse_pressure_angle_deg``
            (the flank angles, degrees), ``teeth`` (whole teeth), ``area`` (of the section, mm²).
        """
        return {
            "length": float(self.length),
            "height": self.back_height,
            "pitch": self.pitch,
            "normal_pitch": self.normal_pitch,
            "tooth_thickness": self.pitch / 2.0,
            "addendum": self.addendum * self.module,
            "dedendum": self.dedendum * self.module,
            "pressure_angle_deg": float(self.pressure_angle / DEG),
            "transverse_pressure_angle_deg": float(self.transverse_pressure_angle / DEG),
            "teeth": self.tooth_count,
            "area": float(self.section.area),
        }


def rack_solid_mesh(rack: GearRack, face_width: float, tolerance: float | None = None) -> TriangleMesh:
    """Return the rack's solid as a triangle mesh: the section extruded across the face with the helix's shear.

    The straight extrusion of :func:`rotorcad.solids.twisted_extrusion` (one layer, no twist) sheared
    by x += z tan(beta): a linear map of determinant 1 (volumes and the faces' orientation kept), exact
    for a helical rack, whose flanks are planes and fillets oblique cylinders.

    Parameters
    ----------
    rack : GearRack
        The rack.
    face_width : float, mm
        Across the face, above 0 and at most 10000 mm.
    tolerance : float, optional
        Chord error of the section, mm.

    Returns
    -------
    rotorcad.triangle_mesh.TriangleMesh
        Vertices (n, 3) and faces, mm; the volume is the section's area times the face width.
    """
    import manifold3d as m3

    from rotorcad.solids import twisted_extrusion

    if not (np.isfinite(face_width) and 0.0 < face_width <= 1e4):
        raise DesignError("face_width", "a length above 0 and at most 10000 mm", face_width)
    pts = rack.outline(tolerance)
    contours = tuple(np.asarray(c, dtype=float) for c in m3.CrossSection([pts], m3.FillRule.Positive).to_polygons())
    mesh = twisted_extrusion(contours, float(face_width), 1, 0.0)
    vertices = mesh.vertices.copy()
    vertices[:, 0] += vertices[:, 2] * np.tan(rack.helix_angle)
    return TriangleMesh(vertices, mesh.faces)


__all__ = ["MAX_RACK_PITCHES", "GearRack", "rack_solid_mesh"]
