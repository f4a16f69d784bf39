"""rotorcad: conjugate profiles, involute gears and screw-rotor pairs to manufacturing files.

The Python API in brief::

    from rotorcad import InvoluteGear, GearPair, DEG
    g = InvoluteGear(teeth=17, module=3.0, pressure_angle=20 * DEG, shift=0.3)
    pts = g.outline().points            # closed CCW polygon, mm
    pair = GearPair(g, InvoluteGear(29, 3.0, 20 * DEG, shift=-0.1))
    pair.working_pressure_angle, pair.contact_ratio
"""

from rotorcad.curves import Arc, Involute, Line, PointPath, Spline
from rotorcad.envelope import Generated, conjugate, contact_parameter
from rotorcad.errors import DesignError
from rotorcad.gear import DEG, GearPair, InvoluteGear, mate_shift
from rotorcad.kinematics import Rotation, Translation, gear_mesh, pitch_point, rotor_mesh
from rotorcad.profile import Profile, Segment

__version__ = "0.1.0"

__all__ = [
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
