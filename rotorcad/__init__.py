"""rotorcad: conjugate profiles, involute gears and screw-rotor pairs to manufacturing files.

The Python API in brief::

    from rotorcad import InvoluteGear, GearPair, DEG
    g = InvoluteGear(teeth=17, module=3.0, pressure_angle=20 * DEG, shift=0.3)
    pts = g.outline().points            # closed CCW polygon, mm
    pair = GearPair(g, InvoluteGear(29, 3.0, 20 * DEG, shift=-0.1))
    pair.working_pressure_angle, pair.contact_ratio

    from rotorcad import RotorPair, build_family, MeshingAnalysis
    rotors = build_family(RotorPair(5, 6, 116.0, 63.0, 45.0, 71.0, 53.0), "rack-involute", {})
    MeshingAnalysis(rotors).summary()   # Rinder's figures as plain numbers

Lengths are mm and angles radians throughout the Python API (degrees only in names ending in
``_deg``); arrays of points are ``(n, 2)`` float, mm. Rotor 1 is the male about O1 = (0, 0),
rotor 2 the female about O2 = (a, 0) (ARCHITECTURE.md, conventions). Every name below is imported on
first use (PEP 562), so ``import rotorcad`` stays light.

Design studies

* :func:`sweep` -- run a design sweep file on Dask, one table row per variant.
* :func:`design_summary` -- build and analyse the pair of a design mapping (``rotor --json``).
* :class:`GasDeflection` -- rotor deflection under gas load (Rinder & Deix eqs. 1-10).
* :class:`GearCoupling` -- crowned gear coupling and its lubricant film (Belkov et al.).
* :class:`ClearanceDistribution` -- a meshing clearance to design into the female.
* :class:`MeshingAnalysis` -- Rinder's meshline analysis: defects, blow-hole, sliding (eqs. 1-4).
* :class:`MeshingClearance` -- meshing clearance from profile points (Wu & Chi eqs. 1-10).

Screw rotors

* :class:`RotorPair` -- tooth counts, centre distance, radii, lead, length, hand (mm).
* :class:`ScrewRotors` -- a pair generated from its rack chain: lobes, outlines, sections.
* :func:`build_family`, :data:`FAMILIES` -- the profile families by name, with checked
  parameters; :func:`krigar`, :func:`lysholm`, :func:`srm_symmetric`, :func:`srm_asymmetric`,
  :func:`srm_b`, :func:`narrow_tip`, :func:`rack_involute` -- Rinder's Figs. 1-6;
  :func:`n_rack` -- Stosic's rack-generated N profile.
* :class:`SpatialBlowHole` -- the blow-hole triangle in 3D (Rinder sec. 2.2.2).
* :class:`Flank`, :class:`PieceRole`, :class:`Side` -- roles of lobe parts, rack pieces, rotors.
* :func:`helical_solid` -- a transverse section swept into a helical solid (manifold3d).
* :func:`lobe_pieces`, :func:`pair_from_rotor_points` -- a pair from measured points or a
  drawing of one rotor.

Gears, curves and the envelope engine

* :data:`DEG` -- one degree in radians.
* :class:`InvoluteGear`, :class:`GearPair`, :func:`mate_shift` -- involute gears after
  ISO 21771.
* :class:`Line`, :class:`Arc`, :class:`Involute`, :class:`PointPath`, :class:`Spline` -- exact
  plane curves with unit tangents.
* :class:`Segment`, :class:`Profile` -- named sampled curve pieces and chains of them.
* :class:`Rotation`, :class:`Translation`, :func:`pitch_point`, :func:`gear_mesh`,
  :func:`rotor_mesh` -- the plane motions of meshing bodies.
* :func:`conjugate`, :func:`contact_parameter`, :class:`Generated` -- the envelope engine:
  the meshing condition n · v_rel = 0.
* :class:`DesignError` -- the one exception for input that cannot describe a real part.

Examples
--------
An involute gear and a pair after ISO 21771: the base radius is m z cos(alpha) / 2, and the working
pressure angle solves inv(alpha_w) = inv(alpha) + 2 tan(alpha) (x1 + x2) / (z1 + z2):

>>> import math
>>> from rotorcad import DEG, GearPair, InvoluteGear
>>> g = InvoluteGear(teeth=17, module=3.0, pressure_angle=20 * DEG, shift=0.3)
>>> round(float(g.base_radius), 6), round(3.0 * 17 * math.cos(20 * DEG) / 2, 6)
(23.962162, 23.962162)
>>> pair = GearPair(g, InvoluteGear(29, 3.0, 20 * DEG, shift=-0.1))
>>> from rotorcad.gears.formulas import inv  # tan(a) - a, checked against published tables in the tests
>>> abs(inv(pair.working_pressure_angle) - (inv(20 * DEG) + 2 * math.tan(20 * DEG) * 0.2 / 46)) < 1e-12
True
>>> a = 3.0 * (17 + 29) / 2  # the reference centre distance m (z1 + z2) / 2, mm
>>> round(float(pair.working_center_distance), 4), round(a * math.cos(20 * DEG) / math.cos(pair.working_pressure_angle), 4)
(69.582, 69.582)

A screw-rotor pair: the pitch radius of the male is a / (1 + z2/z1), the wrap angle 2 pi L / h:

>>> from rotorcad import MeshingAnalysis, RotorPair, build_family
>>> pair = RotorPair(5, 6, 116.0, 63.0, 45.0, 71.0, 53.0, lead=300.0, length=190.0)
>>> round(pair.male_pitch_radius, 6), round(116.0 / (1 + 6 / 5), 6)
(52.727273, 52.727273)
>>> round(pair.wrap_angle, 6) == round(2 * math.pi * 190.0 / 300.0, 6)
True

Rinder's figures of the rack-involute family (the pair of ``samples/rack_involute_5_6.toml``) as plain
numbers (mm, mm², m/s); the displacement per male revolution is z1 (A1 + A2) L:

>>> pair = RotorPair(5, 6, 116.0, 69.51066515617151, 51.72727272727273, 64.27272727272728, 46.48933484382849,
...                  lead=300.0, length=190.0)
>>> profile = dict(driving_angle_deg=30.0, sealing_angle_deg=26.0, lobe_width=0.4, tip_rounding=0.0,
...                root_rounding=2.5, sealing_tip_rounding=2.5)
>>> summary = MeshingAnalysis(build_family(pair, "rack-involute", profile)).summary()
>>> summary["family"], summary["runs_without_timing_gears"], summary["running_reasons"]
('rack-involute', True, [])
>>> flutes = summary["male_flute_area"] + summary["female_flute_area"]
>>> abs(summary["displacement_per_rev"] - 5 * flutes * 190.0) < 1e-6 * summary["displacement_per_rev"]
True
>>> 0 < summary["blow_hole_area"] < 0.05 * flutes
True

Input that cannot describe a real part is refused in one sentence naming the parameter:

>>> from rotorcad import DesignError
>>> try:
...     RotorPair(5, 6, -116.0, 63.0, 45.0, 71.0, 53.0)
... except DesignError as error:
...     print(error)
center_distance must be a positive length up to 100000 mm (100 m) (got -116).
"""

import importlib

__version__ = "0.1.0"

# the public names and the modules that define them, imported on first use (PEP 562), so that
# `import rotorcad` (and the command line's start) does not load numpy, scipy and shapely up front
_API = {
    "Arc": "rotorcad.curves",
    "Involute": "rotorcad.curves",
    "Line": "rotorcad.curves",
    "PointPath": "rotorcad.curves",
    "Spline": "rotorcad.curves",
    "Generated": "rotorcad.envelope",
    "conjugate": "rotorcad.envelope",
    "contact_parameter": "rotorcad.envelope",
    "DesignError": "rotorcad.errors",
    "DEG": "rotorcad.gear",
    "GearPair": "rotorcad.gear",
    "InvoluteGear": "rotorcad.gear",
    "mate_shift": "rotorcad.gear",
    "Rotation": "rotorcad.kinematics",
    "Translation": "rotorcad.kinematics",
    "gear_mesh": "rotorcad.kinematics",
    "pitch_point": "rotorcad.kinematics",
    "rotor_mesh": "rotorcad.kinematics",
    "Profile": "rotorcad.profile",
    "Segment": "rotorcad.profile",
    "RotorPair": "rotorcad.rotor_pair",
    "ScrewRotors": "rotorcad.screw_rotors",
    "build_family": "rotorcad.rotor_families",
    "FAMILIES": "rotorcad.rotor_families",
    "krigar": "rotorcad.rotor_families",
    "lysholm": "rotorcad.rotor_families",
    "srm_symmetric": "rotorcad.rotor_families",
    "srm_asymmetric": "rotorcad.rotor_families",
    "srm_b": "rotorcad.rotor_families",
    "narrow_tip": "rotorcad.rotor_families",
    "rack_involute": "rotorcad.rotor_families",
    "n_rack": "rotorcad.families.n_rack",
    "SpatialBlowHole": "rotorcad.blow_hole",
    "Flank": "rotorcad.roles",
    "PieceRole": "rotorcad.roles",
    "Side": "rotorcad.roles",
    "MeshingAnalysis": "rotorcad.meshing",
    "MeshingClearance": "rotorcad.clearance",
    "ClearanceDistribution": "rotorcad.clearance_design",
    "helical_solid": "rotorcad.solids",
    "lobe_pieces": "rotorcad.rotor_points",
    "pair_from_rotor_points": "rotorcad.rotor_points",
    "design_summary": "rotorcad.design.rotors",
    "GasDeflection": "rotorcad.deflection",
    "GearCoupling": "rotorcad.coupling",
    "sweep": "rotorcad.sweep",
}


def __getattr__(name: str) -> object:
    """Import a public name from its module on first use (PEP 562) and keep it here.

    Parameters
    ----------
    name : str
        An attribute of the package.

    Returns
    -------
    object
        The class, function or constant of that name.

    Raises
    ------
    AttributeError
        A name that is not part of the API.
    """
    if name in _API:
        module = importlib.import_module(_API[name])
        value = module if module.__name__ == f"{__name__}.{name}" else getattr(module, name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'rotorcad' has no attribute {name!r}")


def __dir__() -> list[str]:
    """List the package's names, the lazily imported API included."""
    return sorted([*globals(), *_API])


__all__ = [  # noqa: RUF022 - grouped as the docstring reads
    "sweep",
    "design_summary",
    "GasDeflection",
    "GearCoupling",
    "ClearanceDistribution",
    "MeshingAnalysis",
    "MeshingClearance",
    "RotorPair",
    "ScrewRotors",
    "build_family",
    "FAMILIES",
    "krigar",
    "lysholm",
    "srm_symmetric",
    "srm_asymmetric",
    "srm_b",
    "narrow_tip",
    "rack_involute",
    "n_rack",
    "SpatialBlowHole",
    "Flank",
    "PieceRole",
    "Side",
    "helical_solid",
    "lobe_pieces",
    "pair_from_rotor_points",
    "DEG",
    "Arc",
    "DesignError",
    "GearPair",
    "Generated",
    "Involute",
    "InvoluteGear",
    "Line",
    "PointPath",
    "Profile",
    "Rotation",
    "Segment",
    "Spline",
    "Translation",
    "__version__",
    "conjugate",
    "contact_parameter",
    "gear_mesh",
    "mate_shift",
    "pitch_point",
    "rotor_mesh",
]
