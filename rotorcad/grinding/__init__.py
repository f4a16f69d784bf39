"""Form grinding of helical rotors and gears: the wheel from the rotor, the rotor from the wheel.

:mod:`~rotorcad.grinding.setting` (where the wheel sits), :mod:`~rotorcad.grinding.wheel_profile`
(the wheel's axial profile from the rotor), :mod:`~rotorcad.grinding.ground_rotor` (the rotor a
wheel grinds, the stock it leaves: secondary cutting and unreached flank parts),
:mod:`~rotorcad.grinding.sensitivity` (the rotor's deviation per unit setting error),
:mod:`~rotorcad.grinding.job` (one wheel made and checked, as numbers).
"""

from rotorcad.grinding.ground_rotor import GrindingCheck, WheelEnvelope, check_grinding, rotor_from_wheel, stock
from rotorcad.grinding.job import GrindingJob, grind
from rotorcad.grinding.sensitivity import ERRORS, Sensitivity, sensitivities
from rotorcad.grinding.setting import GrindingSetting, default_setting, helix_crossing_angle
from rotorcad.grinding.wheel_profile import Flute, WheelProfile, flute_of, wheel_profile

__all__ = [
    "ERRORS",
    "Flute",
    "GrindingCheck",
    "GrindingJob",
    "GrindingSetting",
    "Sensitivity",
    "WheelEnvelope",
    "WheelProfile",
    "check_grinding",
    "default_setting",
    "flute_of",
    "grind",
    "helix_crossing_angle",
    "rotor_from_wheel",
    "sensitivities",
    "stock",
    "wheel_profile",
]
