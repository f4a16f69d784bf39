"""Deflection of screw rotors under gas load (Rinder & Deix).

Section values from the real profile, the equivalent round bar, the load of the working chambers
and the deflection lines.

The helical part is the paper's equivalent beam, simply supported at its ends (w = 0, M = 0),
solved by Ritz-Galerkin with a sine series (:mod:`rotorcad.rotor_beam`). With shaft ends
(journals to the bearings, each a list of (length, diameter) from the rotor's end face to the
bearing) the whole shaft is integrated as a stepped beam on its bearings, which superposes the
journals as the paper does.

z runs from the discharge end face (see :mod:`rotorcad.working_chamber`); angles are the male's in
the rotors' frame (male at the origin, female at (a, 0)).
"""

from __future__ import annotations

import copy
import dataclasses
from dataclasses import dataclass, field
from enum import Enum

import numpy as np

from rotorcad.errors import DesignError
from rotorcad.gas_load import PressureCycle, line_loads, pressure_cycle
from rotorcad.roles import Side
from rotorcad.rotor_beam import (
    FIT_CENTER_DISTANCE,
    KAPPA_ROUND,
    Beam,
    ShaftSegment,
    equivalent_diameter,
    reduced_second_moment,
    stepped_deflection,
)
from rotorcad.section_properties import circle_values, section_values, shear_correction_over_turn
from rotorcad.working_chamber import ChamberTable, chamber_table, chord_table

STEEL = (210_000.0, 0.3)  # E in N/mm^2, Poisson's ratio
MAX_WRAP_DEG = 720.0  # screw rotors wrap 200-360 deg; beyond two turns the model is not meant
AIR_EXPONENT = 1.4  # the polytropic exponent taken when the design gives none: isentropic air


class LoadModel(Enum):
    """Which pressure load a flute puts on its rotor (``rotorcad deflect --method``).

    CHAMBER ("rotorcad"): the overpressure on the real chamber's boundary on the rotor, section by
    section (:func:`rotorcad.working_chamber.chamber_table`): the chord between the points where the
    chamber leaves the rotor, shorter than tip to tip where the contact line or the mate's lobe bounds it.
    CHORD ("paper"): Rinder & Deix eq. (5) as printed, the full tip-to-tip chord l_s = d_K sin(pi/z_L) in
    every section of the flute's cycle (:func:`rotorcad.working_chamber.chord_table`).
    """

    CHAMBER = "rotorcad"
    CHORD = "paper"


@dataclass(frozen=True)
class RotorBeam:
    """The equivalent beam of one rotor's helical part (Rinder & Deix sec. 2).

    Attributes
    ----------
    area : float, mm^2
        A_ges of the real section.
    j_total : float, mm^4
        J_ges (the same about every axis for z > 2).
    j_anisotropy : float
        |J_x - J_y| / J and |J_xy| / J of the real section, the larger (0 for z > 2 up to sampling).
    kappa_range : tuple[float, float]
        Shear correction eq. (1) of the real section over its turn gamma, min and max.
    root_diameter, tip_diameter : float, mm
        d_F, d_K.
    j_core : float, mm^4
        J_F of the root circle.
    j_reduced : float, mm^4
        J_red, eq. (2).
    diameter : float, mm
        d_aeq, eq. (3).
    beam : Beam
        (EJ)_ers, (GA/kappa)_ers of eq. (4) over the helical length.
    """

    area: float
    j_total: float
    j_anisotropy: float
    kappa_range: tuple[float, float]
    root_diameter: float
    tip_diameter: float
    j_core: float
    j_reduced: float
    diameter: float
    beam: Beam


def rotor_beam(
    outline: np.ndarray,
    root_radius: float,
    tip_radius: float,
    wrap_deg: float,
    length: float,
    young: float = STEEL[0],
    poisson: float = STEEL[1],
    center_distance: float = FIT_CENTER_DISTANCE,
) -> RotorBeam:
    """Make the equivalent beam of a rotor from its transverse outline (Rinder & Deix eqs. 1-4).

    Parameters
    ----------
    outline : (n, 2) float array, mm
        The closed transverse outline about the rotor's axis.
    root_radius, tip_radius : float, mm
        Root and tip radius of the rotor.
    wrap_deg : float, deg
        Wrap angle phi_L of the rotor over ``length``.
    length : float, mm
        Helical length l.
    young : float, N/mm²
        Young's modulus E.
    poisson : float
        Poisson's ratio mu.
    center_distance : float, mm
        Centre distance a of the rotor's pair: eq. (2)'s fit is read at the same-shaped pair's
        size a = 82 mm (``rotor_beam`` module docstring), so the beam scales with the rotor.

    Returns
    -------
    RotorBeam
        Section values, J_red (eq. 2), the equivalent diameter (eq. 3) and the round bar of that
        diameter over ``length``.

    Raises
    ------
    DesignError
        A modulus that is not positive or a Poisson's ratio outside [0, 0.5).
    """
    if not (np.isfinite(young) and young > 0):
        raise DesignError("young_modulus", "a positive modulus in N/mm^2", young)
    if not (np.isfinite(poisson) and 0 <= poisson < 0.5):
        raise DesignError("poisson_ratio", "from 0 to below 0.5", poisson)
    values = section_values(outline)
    j = values.j
    kappa = shear_correction_over_turn(outline, np.linspace(0.0, np.pi, 19))
    j_core = circle_values(2 * root_radius)[1]
    j_red = reduced_second_moment(j, j_core, 2 * root_radius, 2 * tip_radius, wrap_deg, length, center_distance)
    d = equivalent_diameter(values.area, j_red, length, poisson, KAPPA_ROUND)
    return RotorBeam(
        area=values.area,
        j_total=j,
        j_anisotropy=float(max(abs(values.j_x - values.j_y), abs(values.j_xy)) / j),
        kappa_range=(float(kappa.min()), float(kappa.max())),
        root_diameter=2 * root_radius,
        tip_diameter=2 * tip_radius,
        j_core=j_core,
        j_reduced=j_red,
        diameter=d,
        beam=Beam.round_bar(d, length, young, poisson),
    )


@dataclass(frozen=True)
class Shaft:
    """Journals of one rotor: (length, diameter) pieces from each end face to its bearing.

    Parameters
    ----------
    discharge, suction : tuple of (float, float), mm
        Pieces (length, diameter) from the discharge (suction) end face to the bearing, in that
        order; empty: the bearing sits at the end face.
    """

    discharge: tuple[tuple[float, float], ...] = ()
    suction: tuple[tuple[float, float], ...] = ()

    def segments(self, helical: Beam, young: float, poisson: float) -> tuple[list[ShaftSegment], int]:
        """Return the beam segments from the discharge bearing to the suction bearing.

        Parameters
        ----------
        helical : Beam
            The equivalent beam of the helical part.
        young : float, N/mm²
            Young's modulus of the journals.
        poisson : float
            Poisson's ratio of the journals.

        Returns
        -------
        segments : list of ShaftSegment
            Discharge journals (bearing first), the helical part, suction journals.
        index : int
            Index of the helical part in ``segments``.

        Raises
        ------
        DesignError
            A journal length or diameter that is not positive.
        """

        def piece(length: float, diameter: float) -> ShaftSegment:
            for name, value in (("journal length", length), ("journal diameter", diameter)):
                if not (np.isfinite(value) and value > 0):
                    raise DesignError(name, "a positive length in mm", value)
            bar = Beam.round_bar(diameter, length, young, poisson)
            return ShaftSegment(length, bar.bending, bar.shear)

        near = [piece(*p) for p in reversed(self.discharge)]  # bearing first
        far = [piece(*p) for p in self.suction]
        return [*near, ShaftSegment(helical.length, helical.bending, helical.shear), *far], len(near)

    @property
    def given(self) -> bool:
        """True when the rotor has journals at either end."""
        return bool(self.discharge or self.suction)


@dataclass(frozen=True)
class DeflectionLines:
    """The deflection of both rotors at one male angle.

    Attributes
    ----------
    angle : float, rad
        Male angle in the discharge-end section.
    z : (n,) float, mm
        Positions along the helical part from the discharge end.
    male, female : (n, 2) float, mm
        w_x, w_y of the helical parts (simply supported at their ends), eq. (8).
    male_shaft_z, female_shaft_z : (m,) float, mm
        Positions from the discharge bearing (empty without shaft ends).
    male_shaft, female_shaft : (m, 2) float, mm
        The whole shafts' deflection on their bearings.
    """

    angle: float
    z: np.ndarray
    male: np.ndarray
    female: np.ndarray
    male_shaft_z: np.ndarray = field(default_factory=lambda: np.zeros(0))
    male_shaft: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    female_shaft_z: np.ndarray = field(default_factory=lambda: np.zeros(0))
    female_shaft: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))

    def largest(self, rotor: Side | str, shaft: bool = False) -> tuple[float, float, float]:
        """Return the largest deflection of a rotor, where it occurs and its direction.

        Parameters
        ----------
        rotor : Side or {"male", "female"}
            Which rotor (the text is read as ``Side(rotor)``).
        shaft : bool
            True: along the whole shaft on its bearings (falls back to the helical part when there
            are no shaft ends).

        Returns
        -------
        tuple of float
            (|w| max in mm, its z in mm, its direction in deg from +x towards +y: tan phi = w_y / w_x).
        """
        side = Side(rotor)
        w = side.pick(self.male_shaft, self.female_shaft) if shaft else side.pick(self.male, self.female)
        z = side.pick(self.male_shaft_z, self.female_shaft_z) if shaft else self.z
        if len(w) == 0:
            return self.largest(side)
        mag = np.hypot(w[:, 0], w[:, 1])
        i = int(np.argmax(mag))
        return float(mag[i]), float(z[i]), float(np.degrees(np.arctan2(w[i, 1], w[i, 0])) % 360.0)


def _similar_chamber_table(rotors, pair, step_deg: float) -> ChamberTable:
    """Return the chamber table of the pair, cut at the size a = 82 mm and scaled back (size-similar).

    ``rotorcad.working_chamber`` cuts the gas space with tolerances in mm (``GAP``, ``SEAL``, the
    sections' 0.01 mm chords); cut at one size, the table of a pair k times as large is the same
    with areas times k^2 and forces per unit length and pressure times k, so its deflections scale as
    k exactly (tests/test_deflect_scaling.py). At a = 82 mm (the samples' size) nothing is rescaled.

    Parameters
    ----------
    rotors : ScrewRotors
        The pair's rotors (their sections in their own frames).
    pair : Pair
        Its dimensions, mm.
    step_deg : float, deg
        Phase step of the table.

    Returns
    -------
    ChamberTable
        In the pair's own size, mm.
    """
    import shapely.affinity

    size = pair.center_distance / FIT_CENTER_DISTANCE
    male = rotors.section(Side.MALE, 0.01 * size)
    female = rotors.section(Side.FEMALE, 0.01 * size)
    if size != 1.0:
        male, female = (shapely.affinity.scale(s, 1 / size, 1 / size, origin=(0.0, 0.0)) for s in (male, female))
    a, lead, length = pair.center_distance / size, pair.lead / size, pair.length / size
    table = chamber_table(male, female, pair.male_teeth, pair.female_teeth, a, lead, length, step_deg)
    if size == 1.0:
        return table
    return dataclasses.replace(
        table,
        area=table.area * size**2,
        male_force=table.male_force * size,
        female_force=table.female_force * size,
        male_flute_area=table.male_flute_area * size**2,
        female_flute_area=table.female_flute_area * size**2,
        lead=pair.lead,
        length=pair.length,
    )


class GasDeflection:
    """Deflection of a rotor pair under the pressure of its working chambers (Rinder & Deix).

    Parameters
    ----------
    rotors : ScrewRotors
        The pair (its sections give the chamber and the beams).
    suction_bar, discharge_bar : float, bar absolute
        Suction and discharge pressure.
    exponent : float
        Polytropic exponent n of the compression p V^n = const.
    volume_ratio : float, optional
        Built-in volume ratio V_i fixing the discharge port's control edge.
    discharge_edge : float, rad, optional
        Or the control edge as a chamber angle (male rotation since the chamber opened).
    load : LoadModel
        The flute's load: the real chamber's boundary (default) or Rinder & Deix's eq. (5) chord.
    indicator : (k, 2) float array, optional
        Or an indicator diagram: rows (chamber angle in rad, absolute pressure in bar); see
        :func:`rotorcad.gas_load.pressure_cycle`.
    young, poisson : float
        E (N/mm²) and mu of the rotors.
    male_shaft, female_shaft : Shaft
        Journals (optional).
    terms : int
        Sine terms of the Ritz-Galerkin series, 1 to 400 (the paper used 2; 40 are converged to
        < 0.1 %).
    cells : int
        Cells along the length for the load.
    step_deg : float, deg
        Phase step of the chamber table.

    Raises
    ------
    DesignError
        Terms, modulus or Poisson's ratio out of range, a male wrap over 720 degrees, or a bad
        pressure model.
    """

    def __init__(
        self,
        rotors,
        suction_bar: float,
        discharge_bar: float,
        exponent: float = AIR_EXPONENT,
        volume_ratio: float | None = None,
        discharge_edge: float | None = None,
        indicator: np.ndarray | None = None,
        young: float = STEEL[0],
        poisson: float = STEEL[1],
        male_shaft: Shaft = Shaft(),
        female_shaft: Shaft = Shaft(),
        terms: int = 40,
        cells: int = 1000,
        step_deg: float = 1.0,
        load: LoadModel = LoadModel.CHAMBER,
    ) -> None:
        if not 1 <= int(terms) <= 400:
            raise DesignError("terms", "a whole number from 1 to 400", terms)
        if not (np.isfinite(young) and young > 0):
            raise DesignError("young_modulus", "a positive modulus in N/mm^2", young)
        if not (np.isfinite(poisson) and 0 <= poisson < 0.5):
            raise DesignError("poisson_ratio", "from 0 to below 0.5", poisson)
        pair = rotors.pair
        wrap = 360.0 * pair.length / pair.lead
        if not wrap <= MAX_WRAP_DEG:  # more chambers than a rotor has, and work that grows with them
            raise DesignError(
                "[pair] lead", f"one that gives a male wrap of at most {MAX_WRAP_DEG:g} degrees over the length", pair.lead
            )
        self.pair = pair
        self.terms = int(terms)
        self.table: ChamberTable = _similar_chamber_table(rotors, pair, step_deg)
        self.load = LoadModel.CHAMBER
        self.chamber_table = self.table
        self.cycle: PressureCycle = pressure_cycle(
            self.table, suction_bar, discharge_bar, exponent, volume_ratio, discharge_edge, indicator
        )
        wrap1 = np.degrees(self.table.wrap)
        wrap2 = wrap1 * pair.male_teeth / pair.female_teeth
        size = pair.center_distance / FIT_CENTER_DISTANCE  # the outline's chord tolerance in proportion to the pair
        fine1 = rotors.male_outline(1e-3 * size).points
        fine2 = rotors.female_outline(1e-3 * size).points
        a = pair.center_distance
        self.male = rotor_beam(fine1, pair.male_root_radius, pair.male_tip_radius, wrap1, pair.length, young, poisson, a)
        self.female = rotor_beam(fine2, pair.female_root_radius, pair.female_tip_radius, wrap2, pair.length, young, poisson, a)
        self.z = (np.arange(cells) + 0.5) * pair.length / cells
        self._young, self._poisson = young, poisson
        self._shafts = {
            Side.MALE: male_shaft.segments(self.male.beam, young, poisson) if male_shaft.given else None,
            Side.FEMALE: female_shaft.segments(self.female.beam, young, poisson) if female_shaft.given else None,
        }
        if load is not LoadModel.CHAMBER:
            self.table = self.with_load(load).table
            self.load = load

    def with_load(self, load: LoadModel) -> GasDeflection:
        """Return the same pair, pressures and beams with another flute load (no chamber recomputed).

        Parameters
        ----------
        load : LoadModel
            The load model of the copy.

        Returns
        -------
        GasDeflection
            A shallow copy whose line loads follow ``load``; the pressure cycle (from the real chamber's
            volume curve) is shared.
        """
        other = copy.copy(self)
        other.load = load
        if load is LoadModel.CHAMBER:
            other.table = self.chamber_table
        else:
            p = self.pair
            other.table = chord_table(self.chamber_table, p.male_teeth, p.female_teeth, p.male_tip_radius, p.female_tip_radius)
        return other

    def journal_length(self, rotor: Side | str) -> float:
        """Return the length from the discharge bearing to the discharge end face of a rotor.

        Parameters
        ----------
        rotor : Side or {"male", "female"}
            Which rotor (the text is read as ``Side(rotor)``).

        Returns
        -------
        float, mm
            0 without shaft ends.
        """
        shaft = self._shafts[Side(rotor)]
        return 0.0 if shaft is None else float(sum(seg.length for seg in shaft[0][: shaft[1]]))

    def chambers(self, angle: float) -> list[dict[str, float]]:
        """List the chambers alive at a male angle.

        Parameters
        ----------
        angle : float, rad
            Male angle in the discharge-end section.

        Returns
        -------
        list of dict
            One per chamber, by chamber angle: ``chamber_angle_deg`` (male rotation since it opened,
            deg), ``pressure_bar`` (bar absolute), ``from_z`` and ``to_z`` (mm from the discharge end:
            where along the rotors it holds gas, up to the contact line that seals it).
        """
        start, stop = self.table.cycle
        span = self.table.span
        pitch = 2 * np.pi / self.pair.male_teeth
        first = int(np.floor((start - angle) / pitch))
        out = []
        for k in range(first, int(np.ceil((stop - angle) / pitch)) + 1):
            psi0 = angle + k * pitch
            if not start <= psi0 < stop:
                continue
            theta = psi0 - start
            scale = self.table.lead / (2 * np.pi)
            out.append(
                {
                    "chamber_angle_deg": float(np.degrees(theta)),
                    "pressure_bar": float((self.cycle.overpressure(np.array([theta]))[0] + self.cycle.suction) * 10),
                    "from_z": float(np.clip((span[0] - psi0) * scale, 0.0, self.pair.length)),
                    "to_z": float(np.clip((span[1] - psi0) * scale, 0.0, self.pair.length)),
                }
            )
        return sorted(out, key=lambda c: c["chamber_angle_deg"])

    def bearing_loads(self, angle: float) -> dict[str, dict[str, float]]:
        """Return the gas force on each rotor and what it puts on the two bearings.

        Statics of the shaft on its bearings (at the end faces without shaft ends).

        Parameters
        ----------
        angle : float, rad
            Male angle in the discharge-end section.

        Returns
        -------
        dict
            Per rotor: ``force`` (N, magnitude of the radial resultant), ``direction_deg`` (of the
            resultant, from +x towards +y), ``discharge_bearing`` and ``suction_bearing`` (N).
        """
        out = {}
        cell = self.pair.length / len(self.z)
        for rotor, load in zip(Side, self.loads(angle), strict=True):
            near = self.journal_length(rotor)
            shaft = self._shafts[rotor]
            span = sum(seg.length for seg in shaft[0]) if shaft is not None else self.pair.length
            force = load.sum(axis=0) * cell  # (2,) N
            suction = (load * (near + self.z)[:, None]).sum(axis=0) * cell / span
            discharge = force - suction
            out[rotor.value] = {
                "force": float(np.hypot(*force)),
                "direction_deg": float(np.degrees(np.arctan2(force[1], force[0])) % 360.0),
                "discharge_bearing": float(np.hypot(*discharge)),
                "suction_bearing": float(np.hypot(*suction)),
            }
        return out

    def loads(self, angle: float) -> tuple[np.ndarray, np.ndarray]:
        """Return the line loads on the male and the female (:attr:`load`: the real chamber's or eq. 5's; eq. 6).

        Parameters
        ----------
        angle : float, rad
            Male angle in the discharge-end section.

        Returns
        -------
        tuple of two (cells, 2) float arrays, N/mm
            Load per unit length (x, y) at the cell centres :attr:`z` on the male and the female.
        """
        male = line_loads(self.table, self.cycle, self.pair.male_teeth, angle, self.z, Side.MALE)
        female = line_loads(self.table, self.cycle, self.pair.male_teeth, angle, self.z, Side.FEMALE)
        return male, female

    def at(self, angle: float, terms: int | None = None, points: int = 201) -> DeflectionLines:
        """Compute the deflection lines of both rotors at a male angle (Rinder & Deix eqs. 7-9).

        Parameters
        ----------
        angle : float, rad
            Male angle in the discharge-end section.
        terms : int, optional
            Sine terms; default the instance's.
        points : int
            Points along the helical part.

        Returns
        -------
        DeflectionLines
        """
        terms = self.terms if terms is None else terms
        z = np.linspace(0.0, self.pair.length, points)
        loads = dict(zip(Side, self.loads(angle), strict=True))
        lines = {}
        for rotor, model in ((Side.MALE, self.male), (Side.FEMALE, self.female)):
            coeff = model.beam.sine_coefficients(self.z, loads[rotor], terms)
            lines[rotor.value] = model.beam.deflection(coeff, z)
            shaft = self._shafts[rotor]
            if shaft is not None:
                lines[f"{rotor}_shaft_z"], lines[f"{rotor}_shaft"] = stepped_deflection(shaft[0], shaft[1], loads[rotor])
        return DeflectionLines(float(angle), z, **lines)

    def sweep(self, angles: np.ndarray, shaft: bool = False) -> np.ndarray:
        """Return the largest deflection of each rotor at each of a set of male angles.

        Parameters
        ----------
        angles : (k,) float array, rad
            Male angles.
        shaft : bool
            True: along the whole shafts on their bearings.

        Returns
        -------
        (k, 2) float array, mm
            Largest |w| of (male, female) at each angle.
        """
        out = np.empty((len(angles), 2))
        for i, a in enumerate(np.asarray(angles, dtype=float)):  # each angle is vectorised inside
            lines = self.at(a, points=101)
            out[i] = [lines.largest(Side.MALE, shaft)[0], lines.largest(Side.FEMALE, shaft)[0]]
        return out

    def refine_worst(self, angles: np.ndarray, largest: np.ndarray, shaft: bool = False, side: Side | None = None) -> float:
        """Find the male angle of the largest deflection of either rotor (or of ``side``).

        The best of a sweep, refined by a bounded scalar search between its neighbours.

        Parameters
        ----------
        angles : (k,) float array, rad
            The swept angles (equally spaced).
        largest : (k,) float array, mm
            The larger of the two rotors' deflections at each angle.
        shaft : bool
            True: along the whole shafts on their bearings.
        side : Side, optional
            The rotor whose deflection is maximised (then ``largest`` is its own); default: either.

        Returns
        -------
        float, rad
            The refined angle (the sweep's best when the search does not improve on it).
        """
        from scipy.optimize import minimize_scalar

        i = int(np.argmax(largest))
        step = float(angles[1] - angles[0]) if len(angles) > 1 else 0.01

        def minus(a: float) -> float:
            lines = self.at(a, points=101)
            return -max(lines.largest(rotor, shaft)[0] for rotor in ((side,) if side else (Side.MALE, Side.FEMALE)))

        best = minimize_scalar(minus, bounds=(angles[i] - step, angles[i] + step), method="bounded", options={"xatol": 1e-4})
        return float(best.x) if -best.fun >= largest[i] else float(angles[i])

    def worst_angle_eq10(self) -> float:
        """Return the male angle of Rinder & Deix eq. (10), in [0, 2 pi / z1).

        A chamber has just reached the discharge port's control edge, so the discharge pressure reaches
        farthest towards the suction end.

        Returns
        -------
        float, rad

        Raises
        ------
        DesignError
            With an indicator diagram (the built-in port model is needed).
        """
        if not np.isfinite(self.cycle.opening):
            raise DesignError("indicator diagram", "the built-in port model for eq. (10)", "an indicator diagram")
        start, _ = self.table.cycle
        return float((start + self.cycle.opening) % (2 * np.pi / self.pair.male_teeth))
