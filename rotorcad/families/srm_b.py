"""Rinder's asymmetric SRM-B profile: the SRM profile with the driving arc's centre moved off the pitch point.

After Rinder, *Sonderverzahnungen für Schraubenverdichterrotoren*, sec. 1.2: a shorter meshline
and a transverse contact ratio above zero (:func:`rotorcad.families.srm_asymmetric.srm_asymmetric`).
"""

from __future__ import annotations

from rotorcad.families.parameters import SealStop, TipLand
from rotorcad.families.srm_asymmetric import DrivingRounding, OptionalCenterDepth, OptionalFlankAngle, srm_asymmetric
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import ScrewRotors


def srm_b(
    pair: RotorPair,
    seal_stop: SealStop = 0.9,
    driving_center_depth: OptionalCenterDepth = None,
    driving_rounding: DrivingRounding = 0.0,
    tip_land: TipLand = 0.0,
    driving_foot_angle_deg: OptionalFlankAngle = None,
) -> ScrewRotors:
    """Rinder's asymmetric SRM-B profile: :func:`~rotorcad.families.srm_asymmetric.srm_asymmetric`, driving arc off C.

    The centre is given by the arc's foot angle (30 deg unless ``driving_center_depth`` is given
    instead).

    Parameters
    ----------
    pair : RotorPair
        Tooth counts, centre distance and radii (mm).
    seal_stop, driving_rounding, tip_land : float
        As for :func:`~rotorcad.families.srm_asymmetric.srm_asymmetric`.
    driving_center_depth : float or None, mm
        Depth of the driving arc's centre below the pitch line; None: placed by the foot angle.
    driving_foot_angle_deg : float or None, deg
        Foot angle of the driving arc; None: 30 unless ``driving_center_depth`` is given.

    Returns
    -------
    ScrewRotors
        The pair with its rack chain, family "srm-b".
    """
    if driving_foot_angle_deg is None and driving_center_depth is None:
        driving_foot_angle_deg = 30.0
    return srm_asymmetric(
        pair,
        seal_stop=seal_stop,
        driving_center_depth=0.0 if driving_center_depth is None else driving_center_depth,
        driving_rounding=driving_rounding,
        tip_land=tip_land,
        driving_foot_angle_deg=driving_foot_angle_deg,
    )
