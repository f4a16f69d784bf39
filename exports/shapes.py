"""Every solid of rotorcad as an OpenCASCADE solid (``TopoDS_Solid``), for CadQuery and build123d.

The solids are the exact STEP's (the same code writes the files): a rotor or gear swept along its
helix with one face per piece of its section, checked against the exact helicoid to the tolerance
(:mod:`exports.step_exact`); a gear as a part with its tip corners, bore, keyway, hub or
herringbone (:mod:`exports.gear_step`); the housing of box and cylinders; a gear rack of planes and
cylinders (:mod:`exports.step_rack`). Each comes placed as the export places it (the female and the
mate at the centre distance) as an ``OCP.TopoDS.TopoDS_Solid``, which a CAD library built on OCP
takes over in one line (README, "Python API")::

    import cadquery as cq
    part = cq.Workplane(obj=cq.Shape.cast(solid))      # CadQuery

    from build123d import Solid
    part = Solid(solid)                                # build123d
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from exports.gear_step import as_solid, gear_part_shape
from exports.step_exact import StepDeviationError, helical_solid, helicoid_deviation, housing_shape, section_segments
from rotorcad.geometry import rotate

if TYPE_CHECKING:
    from rotorcad.assembly import PlacedBody

STEP_TOLERANCE = 1e-3
"""mm: the faces' largest distance from the exact helicoid, unless a finer tolerance is asked."""


def _moved(shape: Any, offset: tuple[float, float]) -> Any:
    """Return ``shape`` moved by ``offset`` in x and y (a copy; the shape itself when not moved)."""
    if offset == (0.0, 0.0):
        return shape
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.gp import gp_Trsf, gp_Vec

    tr = gp_Trsf()
    tr.SetTranslation(gp_Vec(float(offset[0]), float(offset[1]), 0.0))
    return BRepBuilderAPI_Transform(shape, tr, True).Shape()


def body_shape(body: PlacedBody, tolerance: float = STEP_TOLERANCE) -> Any:
    """Return a placed body (:mod:`rotorcad.assembly`) as an exact OpenCASCADE solid.

    Parameters
    ----------
    body : PlacedBody
        A rotor, gear (as a part too) or housing body, placed in mesh.
    tolerance : float, mm
        Largest distance of a swept body's faces from the exact helicoid; its section's B-splines
        are sampled ever finer (the body's ``step_chords``) until it is met.

    Returns
    -------
    OCP.TopoDS.TopoDS_Solid

    Raises
    ------
    exports.step_exact.StepDeviationError
        When even the finest section's faces are farther from the helicoid than ``tolerance``.
    """
    if body.housing is not None:
        return as_solid(housing_shape(*body.housing, body.name))
    exact = rotate(body.outline(tolerance / 100).points, body.turn)
    for i, chord in enumerate(body.step_chords):
        segments = section_segments(body.outline(chord * tolerance), body.turn, tolerance)
        try:
            if body.features is not None:
                shape, _ = gear_part_shape(segments, body.lead, body.length, tolerance, body.features, exact)
            else:
                shape = helical_solid(segments, body.lead, body.length, tolerance)
                deviation = helicoid_deviation(shape, exact, body.lead, body.length)
                if deviation > tolerance:
                    raise StepDeviationError(f"the faces are {deviation * 1e3:.2f} um from the helicoid")
            return as_solid(_moved(shape, body.shift))
        except StepDeviationError:
            if i == len(body.step_chords) - 1:
                raise
    raise ValueError("the body has no section to sweep")


def gear_shapes(gear: Any, face_width: float, pair: Any = None, features: Any = None, tolerance: float = STEP_TOLERANCE) -> dict:
    """Return an involute gear (and its mate in mesh) as exact OpenCASCADE solids.

    Parameters
    ----------
    gear : InvoluteGear
        The gear.
    face_width : float, mm
        b, from z = 0.
    pair : GearPair, optional
        The gear with its mate: the mate too, at the working centre distance.
    features : GearFeatures or MadeFeatures, optional
        Tip chamfer or rounding, bore, keyway, hub, herringbone (:mod:`rotorcad.gears.features`).
    tolerance : float, mm
        Largest distance of the faces from the exact helicoid.

    Returns
    -------
    dict of str to OCP.TopoDS.TopoDS_Solid
        ``gear`` and, with a pair, ``mate``.

    Raises
    ------
    rotorcad.errors.DesignError
        Features the gear does not allow (naming the field).
    """
    from rotorcad.assembly import gear_bodies
    from rotorcad.gears.features import GearFeatures, made_features

    if isinstance(features, GearFeatures):
        features = made_features(gear, features)
    return {b.name: body_shape(b, tolerance) for b in gear_bodies(gear, pair, face_width, 4 * tolerance, features)}


def rotor_shapes(rotors: Any, tolerance: float = STEP_TOLERANCE, angle: float = 0.0, phase: float = 0.0) -> dict:
    """Return a screw-rotor pair as exact OpenCASCADE solids, placed in mesh.

    Parameters
    ----------
    rotors : ScrewRotors
        The rotors (``rotorcad.build_family(...)``).
    tolerance : float, mm
        Largest distance of the faces from the exact helicoid.
    angle : float, rad
        The male's turn; the female turned by -angle z1/z2 + ``phase``.
    phase : float, rad
        The female's extra turn.

    Returns
    -------
    dict of str to OCP.TopoDS.TopoDS_Solid
        ``male`` and ``female`` (about (a, 0)).
    """
    from rotorcad.assembly import rotor_bodies

    return {b.name: body_shape(b, tolerance) for b in rotor_bodies(rotors, rotors.pair, angle, phase, 2 * tolerance)}


def housing_shapes(pair: Any, clearance: float = 0.0) -> dict:
    """Return the housing (block minus the bores) and the bores as exact OpenCASCADE solids.

    Parameters
    ----------
    pair : RotorPair
        The pair (centre distance, tip radii, length).
    clearance : float, mm
        Radial clearance of the bores over the tip radii.

    Returns
    -------
    dict of str to OCP.TopoDS.TopoDS_Solid
        ``housing`` and ``bores``.
    """
    from rotorcad.solids import HOUSING_WALL

    r1, r2 = pair.male_tip_radius + clearance, pair.female_tip_radius + clearance
    dims = (float(pair.center_distance), float(r1), float(r2), float(pair.length), HOUSING_WALL)
    return {name: as_solid(housing_shape(*dims, name)) for name in ("housing", "bores")}


def rack_solid(rack: Any, face_width: float) -> Any:
    """Return a gear rack (:class:`rotorcad.gears.rack.GearRack`) as an exact OpenCASCADE solid (its own frame)."""
    from exports.step_rack import rack_shape

    return as_solid(rack_shape(rack, face_width))


__all__ = ["STEP_TOLERANCE", "body_shape", "gear_shapes", "housing_shapes", "rack_solid", "rotor_shapes"]
