"""Rinder's narrow-tip ("Schmalkopf") profile (*Sonderverzahnungen für Schraubenverdichterrotoren*, Fig. 5).

Thin female teeth, deep wide flutes, a short driving meshline; 3 to 7 male lobes. Built as the
SRM-B construction with those proportions.
"""

from __future__ import annotations

from rotorcad.errors import DesignError
from rotorcad.families.parameters import FlankAngle, SealStop, TipLand
from rotorcad.families.srm_asymmetric import srm_asymmetric
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import ScrewRotors


def narrow_tip(
    pair: RotorPair, driving_foot_angle_deg: FlankAngle = 45.0, seal_stop: SealStop = 0.9, tip_land: TipLand = 0.0
) -> ScrewRotors:
    """Rinder's narrow-tip ("Schmalkopf") profile (Fig. 5), a development of the asymmetric SRM profile.

    The asymmetric SRM profile developed towards shorter contact lines and higher relative
    tightness. Rinder names its features, not its construction: very thin female teeth and wide, deeply cut
    flutes; a short meshline on the driving flank; still long point-generated parts on the sealing
    flank; good running on both flank parts; a small, unavoidable blow-hole; 3 to 7 male lobes. It
    is built here as the SRM-B construction (:func:`srm_asymmetric`) with those proportions: the
    driving arc's centre moved far off C (``driving_foot_angle_deg`` 45 by default, against SRM-B's
    30), which widens the male lobe at its foot and so thins the female tooth, and shortens the
    driving meshline; a deep male addendum (the design's tip radius) gives the deep female flutes.

    Parameters
    ----------
    pair : RotorPair
        Tooth counts, centre distance and radii (mm); 3 to 7 male lobes.
    driving_foot_angle_deg : float, deg
        Foot angle of the driving arc (see :func:`srm_asymmetric`).
    seal_stop : float
        Share of the male tip corner's sweep to the cusp along which it generates the female
        sealing flank.
    tip_land : float
        Male tip land along the rack, mm.

    Returns
    -------
    ScrewRotors
        The pair with its rack chain, family "narrow-tip".

    Raises
    ------
    DesignError
        ``male_teeth`` unless the male has 3 to 7 lobes.
    """
    if not 3 <= pair.male_teeth <= 7:
        raise DesignError("male_teeth", "from 3 to 7 for the narrow-tip profile (Rinder sec. 1.2)", pair.male_teeth)
    rotors = srm_asymmetric(pair, seal_stop=seal_stop, tip_land=tip_land, driving_foot_angle_deg=driving_foot_angle_deg)
    return ScrewRotors(pair, rotors.rack, "narrow-tip")
