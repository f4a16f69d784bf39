"""The symmetric circular SRM profile (Nilsson 1952; Rinder, *Sonderverzahnungen für Schraubenverdichterrotoren*, Fig. 3).

The rack is a semicircle of radius h1 centred on the pitch line, so both rotors get circular
flanks centred on their pitch circles; male root = pitch circle. Large blow-hole. No parameters.
"""

from __future__ import annotations

import numpy as np

from rotorcad.errors import DesignError
from rotorcad.families.corners import flank_to_female_tip
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import RackPiece, ScrewRotors, rack_arc, rack_line


def srm_symmetric(pair: RotorPair) -> ScrewRotors:
    """Symmetric circular SRM profile (Rinder Fig. 3)."""
    p, h1, d1 = pair.rack_period, pair.male_addendum, pair.male_dedendum
    if abs(d1) > 1e-6:
        raise DesignError(
            "male_root_radius",
            f"equal to the male pitch radius {pair.male_pitch_radius:.6g} mm for the symmetric circular profile",
            pair.male_root_radius,
        )
    if not 2 * h1 < p:
        raise DesignError(
            "male_tip_radius",
            f"less than {pair.male_pitch_radius + p / 2:.6g} mm so that the lobe circle fits the pitch",
            pair.male_tip_radius,
        )
    xc = p / 2
    # the female tip circle is its pitch circle and cuts the flute circle short of the rack's feet:
    # both female tip corners are sharp, and their paths close the rack down to the pitch line
    lobe = rack_arc(pair, (xc, 0.0), h1, np.pi, 0.0)
    leading, x_start = flank_to_female_tip(pair, lobe, False, ("lobe arc", "flute arc"), "trailing")
    lobe = leading[1].curve
    trailing, x_foot = flank_to_female_tip(pair, lobe, True, ("lobe arc", "flute arc"), "leading")
    rack = (
        RackPiece(rack_line(pair, (0.0, 0.0), (x_start, 0.0)), "root arc", "tip arc"),
        leading[0],
        *trailing,
        RackPiece(rack_line(pair, (x_foot, 0.0), (p, 0.0)), "root arc", "tip arc"),
    )
    return ScrewRotors(pair, rack, "srm-symmetric")
