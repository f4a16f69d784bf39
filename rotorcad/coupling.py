"""Gear coupling with barrel-shaped (crowned) hub teeth: kinematics, tooth load and lubricant film.

After Belkov, Maksimov & Shitikov, *Contact-hydrodynamic calculation of gear couplings of
high-speed turbomachines*; the film itself is solved in :mod:`rotorcad.coupling_film`.

Geometry (paper, Fig. 1). Hub and sleeve have the same number of teeth z, module m, pressure angle
alpha and addendum factor h_a* (0.8); no profile shift (the paper's X only balances bending
strength and is not among its program's inputs), so the pitch radius is r = m z / 2. The hub
teeth are crowned: the hob centre travels on an arc of radius R0 (``barrel_radius``), by default
R0 = b sin(alpha) / (4 tan(gamma)) for face width b and misalignment gamma. A radial retraction
dr = x^2/(2 R0) of a rack flank at alpha moves the flank by dr sin(alpha) along its normal, so the
flank is crowned with R_b = R0 / sin(alpha) (the paper's "so-called barrel radius", section A-A).
The two involutes have the same base circle, so the flanks conform along the tooth height: the
contact is a cylinder of radius R_b on a plane, a line across the working depth 2 h_a* m, whose
length along the involute is exactly l = 2 h_a* m / cos(alpha) (involute arc length
(r_2^2 - r_1^2) / (2 r_b)).

Kinematics (paper, Fig. 2 and the formulas before eq. 1). A misalignment gamma tilts a hub tooth
at angle psi = omega t from the tilt plane by gamma cos(psi +- alpha) in the direction of its flank
normal (tilt axis components gamma cos psi, gamma sin psi projected on the flank normal at alpha);
the contact then sits at x_c = R_b tan(gamma cos(psi +- alpha)) on the barrel and rolls along the
face width at V_k = R_b omega sin(gamma) sin(omega t +- alpha) (paper). The teeth slide axially at
V_os = r omega sin(gamma) cos(psi) (paper: V_s = 0.5 omega d gamma cos(phi)) and radially at
V_r = (r omega sin^2(gamma) / 2) sin(2 psi) (derived: the radius of a point on the tilted pitch
circle is r sqrt(cos^2 psi + sin^2 psi cos^2 gamma)); V_r << V_os << V_k as the paper says.

Mean sliding speed. The paper averages V_s over a quarter turn,
V_cp = (2/pi) int_0^{pi/2} R omega sin(gamma) cos(phi) dphi = 2 R omega sin(gamma) / pi with
omega = 2 pi n / 60 and R = z m / 2, which is z m n sin(gamma) / 30 -- in the unit of m per
second: mm/s for m in mm, and m/s only with m in metres. The printed "z m n sin(gamma) / 300"
is therefore in cm/s (or off by 100 from m/s, m in mm: the m/s form is z m n sin(gamma) / 30000);
rotorcad uses the integral itself, in m/s.

Entraining speed, eq. 7 (OCR: "V_Sigma cp / 2 = 2 omega gamma / pi [R_b - r (1 + sin alpha)], m/s").
Read as the mean entraining speed u = V_Sigma / 2: its leading term (2/pi) R_b omega gamma is the
mean of |V_k| above, and the Reynolds equation is printed with 6 mu V_Sigma, which is 12 mu u. The
bracket's second term, the shift of the rolling speed by the tilt pivot (the coupling centre at
about a pitch radius from the flank), is kept as printed; sin(gamma) replaces gamma (identical to
1e-5 for gamma < 0.5 deg). When R_b <= r (1 + sin alpha) the formula gives no entrainment: the
paper's "error in the input data".

The OCR admits a second reading: the printed "V_Sigma" as the sum of the two surfaces' speeds, so
that the mean entraining speed is half of eq. 7 (``Eq7Reading.SUM``, ``coupling --method paper``; the
film then falls by 2^-0.7: Dowson-Higginson 3.08 against 5.00 um at a case where rotorcad's reading
gives 5.00). rotorcad keeps u = eq. 7 (``Eq7Reading.MEAN``, the default) because it is the kinematics of
the contact: a flank of crown radius R_b tilting at a rate Omega about a pivot at a distance d from
the contact moves the contact along the face at Omega (R_b - d); the surfaces then pass the contact
at Omega R_b (hub) and Omega (R_b - d) (sleeve), whose mean is Omega (R_b - d / 2) -- eq. 7's form,
with the quarter-turn mean (2 / pi) omega gamma of Omega. Reading it as the sum would make the
surfaces pass the contact at half the speed at which the contact itself travels.

Tooth load. Torque T = P / omega, tangential force F_t = T / r shared by the z_c teeth in contact
(z_c = z by default: the paper's program has no separate input for it, the load distribution
factor K_H carries the unequal sharing), normal tooth load F_n = K_H F_t / (z_c cos alpha), and
w' = F_n / l per unit length of the contact line.

Regime (one word from a stated rule, :attr:`CouplingResult.regime`), checked in this
order: ``no_solution`` when no film was found or the line-contact model does not hold (the Hertz
strip 2 b_H is wider than the contact line l is long: side leakage the model lacks);
``edge_contact`` when the strip runs off the face width; ``boundary`` / ``mixed`` when the film
parameter lambda = h_min / sigma (sigma the composite roughness of the two flanks, an input) is below
1 / below 3 (the usual limits, e.g. Hamrock, *Fundamentals of Fluid Film Lubrication*, ch. 1);
``starved`` when the inlet zone the film needs is longer than the face leaves beyond the
contact's farthest position (the film may then be thinner than the fully flooded one computed);
else ``full_film``. The inlet zone is rotorcad's rule of thumb, not a published starvation model:
where the crowned flank's gap x^2 / (2 R_b) stays within ten central films, x = sqrt(20 R_b h_c)
(the starved film itself is not computed). ``hydrodynamic`` is true for ``full_film`` and
``starved`` (lambda >= 3: the film separates the flanks; a starved inlet is said beside it).

Verdict (paper: "the coupling does not work: error in the input data, or edge contact" / "the
hydrodynamic regime is ensured"): the paper's verdict is hydrodynamic when eq. 7 gives entrainment, the
contact strip stays on the face width (x_c + b_H <= b/2 with x_c = R_b tan(gamma) and b_H the Hertz
half-width), the Reynolds-elastic problem has a film, and that film is thin (below a tenth of the
module; a thicker one means a load too small for the thin-film model: "error in the input data").
:attr:`CouplingResult.hydrodynamic` adds lambda >= 3 to it (the film separates the flanks).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace
from enum import Enum

import numpy as np

from rotorcad.coupling_film import FilmSolution, LineContact, reduced_modulus, solve_line_contact
from rotorcad.errors import DesignError
from rotorcad.roots import bracket_root

Array = np.ndarray

MPA = 1e6


DEFAULT_ROUGHNESS = 1.0e-3  # mm: composite Rq of two hobbed or shaped coupling flanks (0.7 um each, sqrt(2) 0.7)
STEEL_YOUNG = 2.0e5  # N/mm^2: the paper's steel (its b_0 = 0.34e-5 sqrt(w R))
STEEL_POISSON = 0.3
MIXED_LAMBDA = 3.0  # film parameter below which asperities carry part of the load
BOUNDARY_LAMBDA = 1.0  # and below which they carry most of it


class Eq7Reading(Enum):
    """How the speed of eq. 7 enters the film (module notes): ``coupling --method``."""

    MEAN = "rotorcad"  # eq. 7 is the mean entraining speed u = (u_1 + u_2) / 2
    SUM = "paper"  # eq. 7 is V_Sigma = u_1 + u_2 as printed, u = V_Sigma / 2


class Regime(Enum):
    """The lubrication regime of the coupling's most loaded tooth (module notes: the rule)."""

    FULL_FILM = "full_film"
    STARVED = "starved"
    MIXED = "mixed"
    BOUNDARY = "boundary"
    EDGE_CONTACT = "edge_contact"
    NO_SOLUTION = "no_solution"


class Hold(Enum):
    """What :func:`sweep_teeth` keeps while the number of teeth changes (paper, Fig. 4)."""

    MODULE = "module"  # m, b, R0, power: the tooth load falls as 1 / z^2
    DIAMETER = "diameter"  # m z, b, R0, power: the load per unit length of the contact line is kept
    TOOTH_LOAD = "tooth_load"  # m, b, R0 and the tooth load (power as z^2): only eq. 7's arm changes


class LoadedFlank(Enum):
    """Which flank of a coupling tooth carries the torque: the sign of alpha in V_k = R_b omega sin(gamma) sin(omega t +- alpha).

    The drive flank or the coast flank of an involute tooth (the side of contact when the torque
    reverses). Not :class:`rotorcad.roles.Flank`, which names the parts of a screw rotor's lobe.
    """

    DRIVING = 1
    COAST = -1


class Verdict(Enum):
    """The kinds of result the paper's program reports, each with its message."""

    HYDRODYNAMIC = "hydrodynamic regime: the oil film carries the tooth load"
    EDGE_CONTACT = "the coupling does not work: edge contact (the contact strip runs off the face width)"
    NO_ENTRAINMENT = (
        "the coupling does not work: error in the input data (no rolling of the contact, eq. 7 gives a mean entraining"
        " speed <= 0: barrel radius too small or no misalignment)"
    )
    NO_FILM = (
        "the coupling does not work: no lubricant film found for this load (the Reynolds-elastic solution did not converge;"
        " the load is far too heavy for the film)"
    )
    THICK_FILM = (
        "the coupling does not work: error in the input data (the film is thicker than a tenth of the module, so the"
        " load is too small for a thin-film contact)"
    )


def derived_barrel_radius(face_width: float, pressure_angle: float, misalignment: float) -> float:
    """Crowning radius of the hub teeth R0 = b sin(alpha) / (4 tan(gamma)) (paper, geometry of Fig. 1).

    Parameters
    ----------
    face_width : float
        b [mm]; the paper recommends b = (6...10) m.
    pressure_angle : float
        alpha [rad].
    misalignment : float
        gamma [rad], > 0.

    Returns
    -------
    float
        R0 [mm]. The flank crown radius R_b = R0 / sin(alpha) = b / (4 tan(gamma)) puts the contact
        at most b/4 from the middle of the face width.
    """
    return face_width * math.sin(pressure_angle) / (4.0 * math.tan(misalignment))


def _check(name: str, value: float, lo: float, hi: float, allowed: str, *, open_lo: bool = True) -> None:
    """Refuse ``value`` unless it is finite and in (lo, hi] (or [lo, hi] with ``open_lo=False``)."""
    ok = math.isfinite(value) and (value > lo if open_lo else value >= lo) and value <= hi
    if not ok:
        raise DesignError(name, allowed, value)


@dataclass(frozen=True)
class GearCoupling:
    """A gear coupling of crowned hub teeth in a straight-toothed sleeve, and its operating point.

    The inputs of the paper's program (its list after eq. 8).

    Parameters
    ----------
    teeth : int
        Number of teeth z of hub and sleeve, 6 to 1000.
    module : float, mm
        Module m.
    face_width : float, mm
        Face width b (the paper recommends b = (6...10) m).
    speed_rpm : float, rpm
        Speed n.
    power_kw : float, kW
        Transmitted power P.
    viscosity : float, Pa s
        Lubricant viscosity at ambient pressure mu_0.
    pressure_viscosity : float, 1/Pa
        Barus coefficient alpha_0 (0 to 1e-6; 0 for an isoviscous lubricant).
    misalignment : float, rad
        Shaft misalignment angle gamma (0 to 10 degrees).
    pressure_angle : float, rad
        Pressure angle alpha (10 to 40 degrees).
    addendum : float
        Addendum factor h_a* (the working depth is 2 h_a* m).
    barrel_radius : float, mm, optional
        Crowning radius R0 of the hob centre's path; default b sin(alpha) / (4 tan(gamma)).
    load_factor : float
        Load distribution factor K_H, 1 to 10.
    teeth_in_contact : float, optional
        Teeth z_c sharing the load; default z.
    modulus : float, Pa
        Reduced modulus E' (default steel on steel, E = 200 GPa, nu = 0.3).
    roughness : float, mm
        Composite roughness sigma = sqrt(Rq1^2 + Rq2^2) of the two flanks, for the film parameter.
    reading : Eq7Reading
        How eq. 7's speed enters the film.

    Raises
    ------
    DesignError
        A value out of its range, or no misalignment without a barrel radius.
    """

    teeth: int
    module: float
    face_width: float
    speed_rpm: float
    power_kw: float
    viscosity: float
    pressure_viscosity: float
    misalignment: float
    pressure_angle: float = math.radians(20.0)
    addendum: float = 0.8
    barrel_radius: float | None = None
    load_factor: float = 1.0
    teeth_in_contact: float | None = None
    modulus: float = reduced_modulus()
    roughness: float = DEFAULT_ROUGHNESS
    reading: Eq7Reading = Eq7Reading.MEAN

    def __post_init__(self) -> None:
        if not (isinstance(self.teeth, (int, np.integer)) and 6 <= self.teeth <= 1000):
            raise DesignError("teeth", "a whole number from 6 to 1000", self.teeth)
        _check("module", self.module, 0.0, 100.0, "a positive number up to 100 mm")
        _check("face_width", self.face_width, 0.0, 2000.0, "a positive number up to 2000 mm")
        _check("speed_rpm", self.speed_rpm, 0.0, 1e6, "a positive number up to 1e6 rpm")
        _check("power_kw", self.power_kw, 0.0, 1e7, "a positive number up to 1e7 kW")
        _check("viscosity", self.viscosity, 0.0, 100.0, "a positive number up to 100 Pa s")
        _check("pressure_viscosity", self.pressure_viscosity, 0.0, 1e-6, "a number from 0 to 1e-6 1/Pa", open_lo=False)
        _check("misalignment", self.misalignment, 0.0, math.radians(10.0), "from 0 to 10 degrees", open_lo=False)
        _check(
            "pressure_angle", self.pressure_angle, math.radians(10.0), math.radians(40.0), "from 10 to 40 degrees", open_lo=False
        )
        _check("addendum", self.addendum, 0.0, 2.0, "a positive number up to 2")
        _check("load_factor", self.load_factor, 1.0, 10.0, "from 1 to 10", open_lo=False)
        if self.barrel_radius is None and self.misalignment == 0.0:
            raise DesignError("misalignment", "above 0 when no barrel radius is given (R0 = b sin(alpha) / (4 tan(gamma)))", 0.0)
        if self.barrel_radius is not None:
            _check("barrel_radius", self.barrel_radius, 0.0, 1e7, "a positive number (mm)")
        _check("roughness", self.roughness, 0.0, 1.0, "a positive composite roughness up to 1 mm")
        if not self.modulus > 0:  # math.inf: rigid bodies
            raise DesignError("modulus", "a positive reduced modulus in Pa", self.modulus)
        if self.teeth_in_contact is not None:
            _check("teeth_in_contact", self.teeth_in_contact, 0.0, float(self.teeth), f"above 0 and at most z = {self.teeth}")

    # geometry [mm]
    @property
    def pitch_radius(self) -> float:
        """Pitch radius r = m z / 2, mm (no profile shift)."""
        return self.module * self.teeth / 2.0

    @property
    def crown_radius(self) -> float:
        """R0 [mm]: given, or b sin(alpha) / (4 tan(gamma))."""
        if self.barrel_radius is not None:
            return self.barrel_radius
        return derived_barrel_radius(self.face_width, self.pressure_angle, self.misalignment)

    @property
    def flank_radius(self) -> float:
        """Flank crown radius R_b = R0 / sin(alpha) [mm] (paper, section A-A of Fig. 1): the cylinder of the contact."""
        return self.crown_radius / math.sin(self.pressure_angle)

    @property
    def crowning_depth(self) -> float:
        """Flank crowning at the tooth ends, b^2 / (8 R_b) [mm], normal to the flank."""
        return self.face_width**2 / (8.0 * self.flank_radius)

    @property
    def contact_length(self) -> float:
        """Length of the contact line across the working depth, l = 2 h_a* m / cos(alpha) [mm]."""
        return 2.0 * self.addendum * self.module / math.cos(self.pressure_angle)

    @property
    def contact_excursion(self) -> float:
        """Largest distance of the contact from the middle of the face width, R_b tan(gamma) [mm]."""
        return self.flank_radius * math.tan(self.misalignment)

    # kinematics [m/s]
    @property
    def omega(self) -> float:
        """Angular speed omega = 2 pi n / 60 [rad/s]."""
        return 2.0 * math.pi * self.speed_rpm / 60.0

    def speeds(self, samples: int = 361, flank: LoadedFlank = LoadedFlank.DRIVING) -> tuple[Array, Array, Array, Array]:
        """Speeds of the contact of one tooth over one revolution (paper, Fig. 2).

        Parameters
        ----------
        samples : int
            Number of angles n_s.
        flank : LoadedFlank
            The loaded flank (sign of alpha in V_k).

        Returns
        -------
        psi, rolling, axial, radial : ndarray, each shape (n_s,)
            Rotation angle psi = omega t [rad] from the tilt plane; rolling speed of the contact
            along the face width V_k = R_b omega sin(gamma) sin(psi +- alpha); axial sliding
            V_os = r omega sin(gamma) cos(psi); radial sliding V_r = r omega sin^2(gamma) sin(2 psi) / 2; all m/s.
        """
        psi = np.linspace(0.0, 2.0 * np.pi, samples)
        w, sg = self.omega, math.sin(self.misalignment)
        rolling = self.flank_radius * 1e-3 * w * sg * np.sin(psi + flank.value * self.pressure_angle)
        axial = self.pitch_radius * 1e-3 * w * sg * np.cos(psi)
        radial = 0.5 * self.pitch_radius * 1e-3 * w * sg**2 * np.sin(2.0 * psi)
        return psi, rolling, axial, radial

    @property
    def mean_sliding_speed(self) -> float:
        """V_cp = (2/pi) r omega sin(gamma) = z m n sin(gamma) / 30000 [m/s] for m in mm (see the module notes on "/300")."""
        return 2.0 / math.pi * self.pitch_radius * 1e-3 * self.omega * math.sin(self.misalignment)

    @property
    def eq7_speed(self) -> float:
        """Eq. 7 as printed, (2 omega sin(gamma) / pi) [R_b - r (1 + sin alpha)] [m/s]."""
        arm = self.flank_radius - self.pitch_radius * (1.0 + math.sin(self.pressure_angle))
        return 2.0 / math.pi * self.omega * math.sin(self.misalignment) * arm * 1e-3

    @property
    def entraining_speed(self) -> float:
        """Mean entraining speed u [m/s]: eq. 7 (:attr:`reading` MEAN) or half of it (SUM)."""
        return self.eq7_speed * (1.0 if self.reading is Eq7Reading.MEAN else 0.5)

    # load
    @property
    def tooth_load(self) -> float:
        """Normal load of the most loaded tooth, F_n = K_H T / (r z_c cos(alpha)) with T = P / omega [N]."""
        torque = self.power_kw * 1e3 / self.omega
        z_c = self.teeth if self.teeth_in_contact is None else self.teeth_in_contact
        return self.load_factor * torque / (self.pitch_radius * 1e-3 * z_c * math.cos(self.pressure_angle))

    @property
    def load_per_length(self) -> float:
        """Load per unit length of the contact line w' = F_n / l, N/m."""
        return self.tooth_load / (self.contact_length * 1e-3)

    def line_contact(self) -> LineContact:
        """Return the cylinder-on-plane problem of Belkov et al. eqs. 1-6 for this coupling.

        Returns
        -------
        LineContact
            In SI units: radius R_b (m), load w' (N/m), entraining speed u (m/s, eq. 7), mu_0 (Pa s),
            alpha_0 (1/Pa), E' (Pa).
        """
        return LineContact(
            radius=self.flank_radius * 1e-3,
            load=self.load_per_length,
            speed=self.entraining_speed,
            viscosity=self.viscosity,
            pressure_viscosity=self.pressure_viscosity,
            modulus=self.modulus,
        )


def reduced_modulus_of(young: float, poisson: float) -> float:
    """Return E' [Pa] of two equal bodies from E [N/mm^2] and nu (Hamrock: E' = E / (1 - nu^2)).

    Parameters
    ----------
    young : float, N/mm^2
        Young's modulus E of hub and sleeve, above 0.
    poisson : float
        Poisson's ratio nu, 0 to below 0.5.

    Returns
    -------
    float, Pa

    Raises
    ------
    DesignError
        E or nu out of range.
    """
    _check("young_modulus", young, 0.0, 1e7, "a positive modulus up to 1e7 N/mm^2")
    _check("poisson_ratio", poisson, 0.0, 0.4999, "from 0 to below 0.5", open_lo=False)
    return reduced_modulus(young * 1e6, poisson, young * 1e6, poisson)


def dowson_higginson_film(contact: LineContact) -> float:
    """Return the minimum film of a line contact by Dowson & Higginson (1977), the independent check.

    H_min = 2.65 U^0.70 G^0.54 W^-0.13 with U = mu_0 u / (E' R), G = alpha_0 E', W = w' / (E' R),
    u the mean entraining speed; h_min = H_min R.

    Parameters
    ----------
    contact : LineContact
        The contact, SI units.

    Returns
    -------
    float, m
        h_min; NaN for an isoviscous lubricant (alpha_0 = 0) or rigid bodies, where the formula does
        not apply.
    """
    e, r = contact.modulus, contact.radius
    if contact.pressure_viscosity <= 0 or not math.isfinite(e):
        return math.nan
    u = contact.viscosity * contact.speed / (e * r)
    g = contact.pressure_viscosity * e
    w = contact.load / (e * r)
    return 2.65 * u**0.70 * g**0.54 * w**-0.13 * r


@dataclass(frozen=True, eq=False)
class CouplingResult:
    """The paper's program output for one coupling: verdict, film, pressures.

    SI inside (the film solution); the properties give mm, N and MPa.

    Parameters
    ----------
    coupling : GearCoupling
        Geometry and operating point.
    verdict : Verdict
        The kind of result.
    film : FilmSolution, optional
        The film solution (None when there is none).
    """

    coupling: GearCoupling
    verdict: Verdict
    film: FilmSolution | None

    @property
    def hydrodynamic(self) -> bool:
        """True when the oil film separates the flanks: a film on the face with lambda = h_min / sigma >= 3.

        The regime is then ``full_film`` or ``starved``: a short inlet (``starved``, :attr:`inlet_off_face`)
        is reported beside the verdict, not against it (the paper's "hydrodynamic regime is ensured" is
        the film separating the surfaces; its program, like this one, takes the oil as supplied far
        upstream). False for ``mixed``, ``boundary``, ``edge_contact`` and ``no_solution``.
        """
        return self.verdict is Verdict.HYDRODYNAMIC and self.regime in (Regime.FULL_FILM, Regime.STARVED)

    @property
    def edge_contact(self) -> bool:
        """x_c + b_H > b / 2: the Hertz strip at the contact's farthest position leaves the face width."""
        c = self.coupling
        return c.contact_excursion + self.hertz_half_width > c.face_width / 2.0

    @property
    def inlet_length(self) -> float:
        """Length of the film's inlet zone, mm (NaN without a film).

        Where the gap of the crowned flank, x^2 / (2 R_b), is within ten central films:
        x = sqrt(20 R_b h_c); most of the film pressure builds there.
        """
        if self.film is None:
            return math.nan
        return math.sqrt(20.0 * self.coupling.flank_radius * self.central_film_thickness)

    @property
    def inlet_room(self) -> float:
        """Room for the inlet zone on the face, mm: b / 2 - x_c.

        From the contact at its farthest position to the face's edge.
        """
        c = self.coupling
        return c.face_width / 2.0 - c.contact_excursion

    @property
    def inlet_off_face(self) -> bool:
        """Whether the inlet zone (:attr:`inlet_length`) runs off the face at the contact's farthest position.

        The film may then be starved and thinner than computed (the paper's model, like this one, takes
        the oil as supplied far upstream). Reported, not a verdict.
        """
        return bool(self.inlet_length > self.inlet_room)

    @property
    def min_film_thickness(self) -> float:
        """h_min [mm] (NaN without a film)."""
        return self.film.min_film * 1e3 if self.film is not None else math.nan

    @property
    def central_film_thickness(self) -> float:
        """Film at the middle of the contact [mm]."""
        return self.film.central_film * 1e3 if self.film is not None else math.nan

    @property
    def load_capacity(self) -> float:
        """Load capacity of the film of one tooth, l int p dx [N] (equals the tooth load at the solution)."""
        if self.film is None:
            return math.nan
        return self.film.load_capacity * self.coupling.contact_length * 1e-3

    @property
    def max_pressure(self) -> float:
        """Largest film pressure p_max [MPa]."""
        return self.film.max_pressure / MPA if self.film is not None else math.nan

    @property
    def hertz_stress(self) -> float:
        """Hertz contact stress of the dry line contact, sqrt(w' E' / (2 pi R_b)) [MPa]."""
        return self.coupling.line_contact().hertz_pressure / MPA

    @property
    def hertz_half_width(self) -> float:
        """Hertz half-width b_H = sqrt(8 w' R_b / (pi E')) [mm] (the paper's b_0 = 0.34e-5 sqrt(w R) for steel)."""
        return self.coupling.line_contact().hertz_half_width * 1e3

    @property
    def ehl_film_thickness(self) -> float:
        """Dowson-Higginson minimum film for the same contact [mm]."""
        c = self.coupling
        if c.entraining_speed <= 0:
            return math.nan
        return dowson_higginson_film(c.line_contact()) * 1e3

    @property
    def ehl_ratio(self) -> float:
        """h_min of the Reynolds-elastic solution / Dowson-Higginson h_min."""
        return self.min_film_thickness / self.ehl_film_thickness

    @property
    def film_parameter(self) -> float:
        """Film parameter lambda = h_min / sigma, the film over the composite roughness (NaN without a film)."""
        return self.min_film_thickness / self.coupling.roughness

    @property
    def line_contact_holds(self) -> bool:
        """True when the Hertz strip 2 b_H is no wider than the contact line l is long (the model's premise)."""
        return 2.0 * self.hertz_half_width <= self.coupling.contact_length

    @property
    def regime(self) -> Regime:
        """The regime word by the rule of the module notes."""
        return self._regime()[0]

    @property
    def regime_reason(self) -> str:
        """The rule's reason for :attr:`regime`, with its numbers (mm shown in um)."""
        return self._regime()[1]

    def _regime(self) -> tuple[Regime, str]:
        c = self.coupling
        um = 1e3
        if self.film is None or not self.film.converged:
            return Regime.NO_SOLUTION, (
                "no film: the Reynolds-elastic problem has no converged solution for this load"
                if c.entraining_speed > 0
                else "no film: eq. 7 gives no entrainment"
            )
        if not self.line_contact_holds:
            return Regime.NO_SOLUTION, (
                f"the line-contact model does not hold: the Hertz strip 2 b_H = {2 * self.hertz_half_width:.3g} mm is wider "
                f"than the contact line l = {c.contact_length:.3g} mm is long (side leakage the model lacks)"
            )
        if self.edge_contact:
            return Regime.EDGE_CONTACT, (
                f"the Hertz strip runs off the face: x_c + b_H = {c.contact_excursion + self.hertz_half_width:.3g} mm "
                f"> b / 2 = {c.face_width / 2:.3g} mm"
            )
        lam = self.film_parameter
        film = f"h_min = {self.min_film_thickness * um:.3g} um is {lam:.3g} times the composite roughness "
        film += f"{c.roughness * um:.3g} um"
        if lam < BOUNDARY_LAMBDA:
            return Regime.BOUNDARY, f"{film} (< {BOUNDARY_LAMBDA:g}: the asperities carry most of the load)"
        if lam < MIXED_LAMBDA:
            return Regime.MIXED, f"{film} (< {MIXED_LAMBDA:g}: the asperities carry part of the load)"
        if self.inlet_off_face:
            return Regime.STARVED, (
                f"{film} (>= {MIXED_LAMBDA:g}: the film separates the flanks), but the inlet limits it: the inlet zone "
                f"needs {self.inlet_length:.3g} mm, the face leaves {self.inlet_room:.3g} mm beyond the contact's farthest "
                f"position, so near there the film may be thinner than the fully flooded {self.min_film_thickness * um:.3g} um "
                "(a rule of thumb, the starved film is not computed)"
            )
        return Regime.FULL_FILM, (
            f"{film} (>= {MIXED_LAMBDA:g}); the inlet zone {self.inlet_length:.3g} mm fits the face room "
            f"{self.inlet_room:.3g} mm; the strip stays on the face"
        )

    @property
    def message(self) -> str:
        """The verdict's message, one sentence: the regime and its reason for a film the paper calls hydrodynamic."""
        if self.verdict is not Verdict.HYDRODYNAMIC:
            return self.verdict.value
        regime, reason = self._regime()
        if regime is Regime.FULL_FILM:
            return f"{self.verdict.value} ({reason})"
        if regime is Regime.STARVED:
            return f"{self.verdict.value}; starved inlet: {reason}"
        return f"{regime.value.replace('_', ' ')}: {reason}"


def analyse(coupling: GearCoupling, nodes: int = 401) -> CouplingResult:
    """Solve the paper's contact-hydrodynamic problem for one coupling (Belkov et al. eqs. 1-7).

    Parameters
    ----------
    coupling : GearCoupling
        Geometry and operating point.
    nodes : int
        Grid nodes of the film solution.

    Returns
    -------
    CouplingResult
        Verdict with the film (None when eq. 7 gives no entrainment or no film was found).
    """
    if coupling.entraining_speed <= 0.0:
        return CouplingResult(coupling, Verdict.NO_ENTRAINMENT, None)
    film = solve_line_contact(coupling.line_contact(), nodes)
    result = CouplingResult(coupling, Verdict.HYDRODYNAMIC, film)
    if not film.converged:
        return CouplingResult(coupling, Verdict.NO_FILM, None)
    if result.edge_contact:
        return CouplingResult(coupling, Verdict.EDGE_CONTACT, film)
    if result.min_film_thickness > 0.1 * coupling.module:
        return CouplingResult(coupling, Verdict.THICK_FILM, film)
    return result


def load_capacity_at(contact: LineContact, min_film: float, nodes: int = 201) -> float:
    """Return the paper's load capacity W(h_min) at a given minimum film thickness.

    An outer root-find on log w' over the film solution. The bracket grows from the contact's own
    load by factors of 4 (at most 4^15 either way).

    Parameters
    ----------
    contact : LineContact
        The contact, SI units (its load is the starting guess).
    min_film : float, m
        The minimum film thickness h_min.
    nodes : int
        Grid nodes of each film solution.

    Returns
    -------
    float, N/m
        The load per unit length the film carries at ``min_film``; NaN when no load in the bracket
        gives that film.
    """

    def gap(log_w: float) -> float:
        s = solve_line_contact(replace(contact, load=math.exp(log_w)), nodes)
        return math.log(s.min_film / min_film) if s.converged else math.nan

    gap = functools.cache(gap)  # the start is evaluated for the direction, then as the first trial
    start = math.log(contact.load)
    direction = 1.0 if gap(start) > 0 else -1.0  # film too thick: raise the load
    trials = (start + k * direction * math.log(4.0) for k in range(16))
    root = bracket_root(gap, trials, xtol=1e-6, stop_at_nan=True)
    return math.nan if root is None else math.exp(root)


def sweep_teeth(
    coupling: GearCoupling, teeth: Array, *, keep_diameter: bool = False, nodes: int = 201, hold: Hold | None = None
) -> Array:
    """Return h_min over the number of teeth, everything else as given (paper, Fig. 4).

    The paper (text under Fig. 4): "with the number of teeth z growing, the other operating conditions
    and the geometry kept, h_min falls slightly". It does so when the tooth load is among what is kept
    (:attr:`Hold.TOOTH_LOAD`: only the arm R_b - r (1 + sin alpha) of eq. 7 changes with r = m z / 2);
    with the power kept instead it rises (module kept) or stays (diameter kept). README, "Belkov's Fig. 4".

    Parameters
    ----------
    coupling : GearCoupling
        The base case.
    teeth : (k,) int array
        Numbers of teeth.
    keep_diameter : bool
        Keep the pitch diameter m z (the module changes as m z / z_i) instead of the module.
    nodes : int
        Grid nodes of each film solution.
    hold : Hold, optional
        What is kept (overrides ``keep_diameter``); the crowning radius R0 is always kept.

    Returns
    -------
    (k,) float array, mm
        h_min; NaN where no film was found (no entrainment, or no converged film). Cases judged
        edge contact or too thick a film keep their h_min.
    """
    hold = hold if hold is not None else (Hold.DIAMETER if keep_diameter else Hold.MODULE)
    diameter = coupling.module * coupling.teeth
    out = np.full(len(teeth), np.nan)
    for k, z in enumerate(np.asarray(teeth, dtype=int)):
        m = diameter / z if hold is Hold.DIAMETER else coupling.module
        # the tooth load K_H T / (r z cos alpha) with T = P / omega and r = m z / 2 is kept when P grows as z^2
        power = coupling.power_kw * (z / coupling.teeth) ** 2 if hold is Hold.TOOTH_LOAD else coupling.power_kw
        case = replace(coupling, teeth=int(z), module=m, power_kw=power, barrel_radius=coupling.crown_radius)
        r = analyse(case, nodes)
        if r.film is not None:
            out[k] = r.min_film_thickness
    return out
