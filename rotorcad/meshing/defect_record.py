"""A defect of Rinder's kinematic rules (sec. 2.2.1) and the accuracy to which the rules are judged.

:class:`Defect` is one place where the meshline breaks a rule (cusp, jamming, slipping);
:func:`resolution` is the shortest meshline stretch the tests resolve at a profile's accuracy and
:data:`MESHLINE_GAIN` how much less accurate a given profile's meshline is than the profile. The rules
themselves are :mod:`rotorcad.meshing.defects` and :mod:`rotorcad.meshing.slipping`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.roles import Flank, Side


@dataclass(frozen=True)
class Defect:
    """A point (or stretch) of the meshline that breaks one of Rinder's rules (sec. 2.2.1).

    Parameters
    ----------
    kind : {"cusp", "jamming", "slipping"}
        Cusp: the meshline normal passes through O1 (male) or O2 (female); jamming: through the pitch
        point C; slipping: the meshline crosses O1O2 away from C.
    rotor : {"male", "female"}
        The rotor the rule names.
    x, y : float, mm
        Where it occurs, fixed frame.
    angle_deg : float, deg
        Male rotation angle at that contact.
    flank : str
        Name of the meshline piece (or, for slipping between pieces, which tip touches which root).
    point_generated : bool
        True when the whole piece has its normal through the centre (a point-generated flank).
    extent : float, mm
        Meshline length over which it holds (0: a single point).
    role : Flank, optional
        The lobe part where it occurs.
    """

    kind: str  # cusp, jamming, slipping
    rotor: Side  # male, female (text reads as the rotor)
    x: float
    y: float
    angle_deg: float
    flank: str
    point_generated: bool = False
    extent: float = 0.0  # meshline length over which it holds (0: a single point)
    role: Flank | None = None  # the lobe part where it occurs

    def __post_init__(self) -> None:
        """Read the rotor given as text ("male", "female") as a :class:`Side`."""
        object.__setattr__(self, "rotor", Side(self.rotor))

    def as_dict(self) -> dict[str, object]:
        """Return the defect as plain values (an entry of ``defects`` in :meth:`MeshingAnalysis.summary`).

        Returns
        -------
        dict
            The fields by name, ``role`` as ``flank_role`` (its text, or None).
        """
        return {
            "kind": self.kind,
            "rotor": str(self.rotor),
            "x": self.x,
            "y": self.y,
            "angle_deg": self.angle_deg,
            "flank": self.flank,
            "point_generated": self.point_generated,
            "extent": self.extent,
            "flank_role": None if self.role is None else str(self.role),
        }


MESHLINE_GAIN = 10.0
"""How many times less accurate the meshline generated from a given profile is than the profile:
the meshline's points lie where the profile's normal passes through C, and the normal's error moves
them along the meshline (1 µm of scatter on the samples' males: accuracy 2 µm, meshline 10-40 µm off
the design's at the median, its tangent 3-6 mrad off). The normals through O1, O2 and C of a given
profile's meshline are judged to this multiple of its accuracy (:func:`meshline_defects`)."""


def resolution(accuracy: float, scale: float) -> float:
    """Return the shortest meshline stretch (mm) that the defect tests resolve.

    A profile known to an accuracy e has its tangent direction resolved over a chord no shorter than
    the one along which a circle of the pair's size (the centre distance a) leaves its tangent by e,
    sqrt(8 a e), nor than 0.5 % of a. A stretch along which the normal passes through a centre within
    the accuracy is an arc about that centre only when it is longer than this; sign changes nearer
    each other than this cancel; defects of one kind nearer each other than this are one.

    Parameters
    ----------
    accuracy : float, mm
        Accuracy of the profile (:attr:`MeshingAnalysis.judged_accuracy`).
    scale : float, mm
        The centre distance.

    Returns
    -------
    float, mm
    """
    return max(5e-3 * scale, float(np.sqrt(8.0 * scale * accuracy)))
