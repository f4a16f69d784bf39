"""The dimensions of a screw-rotor pair and their validation.

Rotor 1 is the male (Hauptläufer), rotor 2 the female (Nebenläufer); O1 = (0, 0), O2 = (a, 0),
ratio i = z2/z1, pitch radii r1w = a/(1+i), r2w = a i/(1+i), pitch point C = (r1w, 0); male lead
h1, female lead h2 = h1 z2/z1, wrap angle 2 pi L / h1 (ARCHITECTURE.md, conventions).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.errors import ConflictError, DesignError, limit_text
from rotorcad.kinematics import Mesh, rotor_mesh
from rotorcad.roles import Side

MAX_LENGTH = 1e5
"""Largest centre distance, radius, lead or length of a design, mm (100 m: no rotor, gear or shaft is
larger; the same bound as a DXF profile's extent, :data:`exports.dxf_profile.MAX_EXTENT`)."""
LENGTH_RANGE = f"a positive length up to {MAX_LENGTH:.0f} mm (100 m)"
"""The allowed range of such a length, phrased to follow "must be"."""


def _centre_distance(relation: str, limit: float, a: float, why: str) -> DesignError:
    """Return the centre distance's side of a conflict with a radius (``must be <relation> <limit> mm (<why>)``)."""
    return DesignError("center_distance", f"{relation} {limit_text(limit, a)} mm ({why})", a)


@dataclass(frozen=True)
class RotorPair:
    """Tooth counts, centre distance, tip and root radii, lead, length and hand of a screw-rotor pair.

    The values are checked when the pair is made (ARCHITECTURE.md, conventions: rotor 1 the male about
    O1 = (0, 0), rotor 2 the female about O2 = (a, 0)).

    Parameters
    ----------
    male_teeth, female_teeth : int
        Lobe counts z1 and z2, whole numbers from 2 to 12.
    center_distance : float, mm
        Centre distance a.
    male_tip_radius, male_root_radius : float, mm
        Tip radius r1t and root radius r1f of the male.
    female_tip_radius, female_root_radius : float, mm
        Tip radius r2t and root radius r2f of the female.
    lead : float, mm
        Male lead h1 (axial advance per turn); the female's is h2 = h1 z2/z1.
    length : float, mm
        Rotor length L.
    hand : {"right", "left"}
        Hand of the male's helix.
    strict : bool
        True checks that each rotor's radii straddle its pitch circle and that each tip clears the
        mate's root; False (measured or hot rotors, assembled pairs) skips those checks, keeping
        only that the tip circles overlap.

    Raises
    ------
    DesignError
        A count, length or hand out of range, or radii that cannot make a pair (naming the field).
    """

    male_teeth: int
    female_teeth: int
    center_distance: float
    male_tip_radius: float
    male_root_radius: float
    female_tip_radius: float
    female_root_radius: float
    lead: float = 300.0
    length: float = 190.0
    hand: str = "right"
    # False for measured or hot rotors, whose tips may reach past the mate's root (that is then
    # what the clearance evaluation reports): the tip/root checks below are skipped
    strict: bool = True

    def __post_init__(self) -> None:
        for name in ("male_teeth", "female_teeth"):
            z = getattr(self, name)
            if isinstance(z, bool) or not isinstance(z, (int, np.integer)) or not 2 <= z <= 12:
                raise DesignError(name, "a whole number from 2 to 12", z)
        a = self.center_distance
        if not (np.isfinite(a) and 0 < a <= MAX_LENGTH):
            raise DesignError("center_distance", LENGTH_RANGE, a)
        for name in ("male_tip_radius", "male_root_radius", "female_tip_radius", "female_root_radius", "lead", "length"):
            v = getattr(self, name)
            if not (np.isfinite(v) and 0 < v <= MAX_LENGTH):
                raise DesignError(name, LENGTH_RANGE, v)
        if self.hand not in ("right", "left"):
            raise DesignError("hand", "'right' or 'left'", self.hand)
        for rotor, pitch in ((Side.MALE, self.male_pitch_radius), (Side.FEMALE, self.female_pitch_radius)):
            if not self.strict:
                break  # an assembled or measured pair: its radii need not straddle these pitch circles
            tip, root = getattr(self, f"{rotor}_tip_radius"), getattr(self, f"{rotor}_root_radius")
            per_a = pitch / a  # the pitch radius a z / (z1 + z2) per mm of centre distance
            if not root < pitch + 1e-9:
                why = f"so that the {rotor} pitch circle lies outside its root circle of {root:.6g} mm"
                raise ConflictError(
                    f"{rotor}_root_radius",
                    f"at most the {rotor} pitch radius {limit_text(pitch, root)} mm",
                    root,
                    alternatives=(_centre_distance("at least", root / per_a, a, why),),
                )
            if not tip > pitch - 1e-9:
                why = f"so that the {rotor} pitch circle lies inside its tip circle of {tip:.6g} mm"
                raise ConflictError(
                    f"{rotor}_tip_radius",
                    f"at least the {rotor} pitch radius {limit_text(pitch, tip)} mm",
                    tip,
                    alternatives=(_centre_distance("at most", tip / per_a, a, why),),
                )
            if not tip < a:
                raise ConflictError(
                    f"{rotor}_tip_radius",
                    f"less than the centre distance {limit_text(a, tip)} mm",
                    tip,
                    alternatives=(_centre_distance("greater than", tip, a, f"the {rotor} tip radius"),),
                )
        mt, ft, mr, fr = self.male_tip_radius, self.female_tip_radius, self.male_root_radius, self.female_root_radius
        overlap = "so that the tip circles overlap"
        if not mt + ft > a:
            raise ConflictError(
                "female_tip_radius",
                f"greater than {limit_text(a - mt, ft)} mm {overlap}",
                ft,
                alternatives=(
                    DesignError("male_tip_radius", f"greater than {limit_text(a - ft, mt)} mm {overlap}", mt),
                    DesignError("center_distance", f"less than {limit_text(mt + ft, a)} mm {overlap}", a),
                ),
            )
        for tip, root, tip_name, root_name in (
            (mt, fr, "male tip radius", "female root radius"),
            (ft, mr, "female tip radius", "male root radius"),
        ):
            if self.strict and tip + root > a + 1e-9:
                tip_limit = f"at most {limit_text(a - root, tip)} mm (centre distance minus {root_name})"
                a_limit = f"at least {limit_text(tip + root, a)} mm ({tip_name} plus {root_name})"
                raise ConflictError(
                    root_name.replace(" ", "_"),
                    f"at most {limit_text(a - tip, root)} mm (centre distance minus {tip_name})",
                    root,
                    alternatives=(
                        DesignError(tip_name.replace(" ", "_"), tip_limit, tip),
                        DesignError("center_distance", a_limit, a),
                    ),
                )

    @property
    def ratio(self) -> float:
        """Ratio i = z2/z1 (dimensionless)."""
        return self.female_teeth / self.male_teeth

    @property
    def male_pitch_radius(self) -> float:
        """Male pitch radius r1w = a/(1+i), mm."""
        return self.center_distance / (1.0 + self.ratio)

    @property
    def female_pitch_radius(self) -> float:
        """Female pitch radius r2w = a i/(1+i), mm."""
        return self.center_distance * self.ratio / (1.0 + self.ratio)

    @property
    def female_lead(self) -> float:
        """Female lead h2 = h1 z2/z1, mm."""
        return self.lead * self.female_teeth / self.male_teeth

    @property
    def wrap_angle(self) -> float:
        """Male wrap angle 2 pi L / h1 (rad)."""
        return 2.0 * np.pi * self.length / self.lead

    @property
    def rack_period(self) -> float:
        """Rack period p = 2 pi r1w / z1 (= 2 pi r2w / z2), mm."""
        return 2.0 * np.pi * self.male_pitch_radius / self.male_teeth

    @property
    def male_addendum(self) -> float:
        """Male addendum h1 = r1t - r1w, mm: how far the rack reaches into the female side."""
        return self.male_tip_radius - self.male_pitch_radius

    @property
    def male_dedendum(self) -> float:
        """Male dedendum d1 = r1w - r1f, mm: how far the rack reaches into the male side."""
        return self.male_pitch_radius - self.male_root_radius

    @property
    def mesh(self) -> Mesh:
        """The male, female and rack motions of this pair (:func:`rotorcad.kinematics.rotor_mesh`)."""
        return rotor_mesh(self.male_teeth, self.female_teeth, self.center_distance)

    @property
    def housing_cusp(self) -> np.ndarray:
        """Upper intersection K of the two tip circles (the housing cusp, y > 0): (2,) float, mm."""
        a, r1, r2 = self.center_distance, self.male_tip_radius, self.female_tip_radius
        x = (a * a + r1 * r1 - r2 * r2) / (2.0 * a)
        return np.array([x, np.sqrt(max(r1 * r1 - x * x, 0.0))])
