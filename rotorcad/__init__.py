"""rotorcad: conjugate profiles, involute gears and screw-rotor pairs to manufacturing files.

The Python API in brief::

    from rotorcad import InvoluteGear, GearPair, DEG
    g = InvoluteGear(teeth=17, module=3.0, pressure_angle=20 * DEG, shift=0.3)
    pts = g.outline().points            # closed CCW polygon, mm
    pair = GearPair(g, InvoluteGear(29, 3.0, 20 * DEG, shift=-0.1))
    pair.working_pressure_angle, pair.contact_ratio
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
    "design_summary": "rotorcad.rotor_build",
    "GasDeflection": "rotorcad.deflection",
    "GearCoupling": "rotorcad.coupling",
    "sweep": "rotorcad.cli.sweep_run",
}


def __getattr__(name: str) -> object:
    if name in _API:
        value = getattr(importlib.import_module(_API[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'rotorcad' has no attribute {name!r}")


def __dir__() -> list[str]:
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
