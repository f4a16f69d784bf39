"""Rotors and housing at working temperature: the hot pair and profiles the meshing clearance compares.

After Miao Huijun et al., *Calculation method of mesh clearance of screw steam compressor under
extreme condition*, sec. 1.2: a body grows by dL = L zeta (t_c - t0) (eq. 1). Used by
:class:`rotorcad.clearance.MeshingClearance` through ``rotorcad clearance``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from rotorcad.curves import Curve, Mapped
from rotorcad.errors import DesignError
from rotorcad.geometry import Array
from rotorcad.rotor_pair import RotorPair

REFERENCE_TEMPERATURE = 20.0
"""degC: the temperature at which the points (the design's dimensions) hold, by default (ISO 1)."""
STEEL_EXPANSION = 11.5e-6
"""1/K: linear expansion coefficient of the rotors by default (steel)."""
GREY_CAST_IRON_EXPANSION = 10.5e-6
"""1/K: linear expansion coefficient of the housing by default (grey cast iron)."""


@dataclass(frozen=True)
class ThermalState:
    """Rotors and housing at working temperature.

    After Miao Huijun et al. (sec. 1.2): a body grows by dL = L zeta (t_c - t0)
    (its eq. 1); the rotor's computation temperature is the arithmetic mean of suction and discharge
    temperature, and the centre distance follows the housing.

    Parameters
    ----------
    suction_temperature, discharge_temperature : float, degC
        Gas temperatures at suction and discharge.
    reference_temperature : float, degC
        Temperature at which the design's dimensions hold.
    rotor_expansion : float, 1/K
        Linear expansion coefficient of the rotors (default steel, 11.5e-6).
    housing_expansion : float, 1/K
        Linear expansion coefficient of the housing (default grey cast iron, 10.5e-6).
    housing_temperature : float, degC, optional
        Housing temperature; default the rotors' computation temperature.

    Raises
    ------
    DesignError
        A temperature at or below absolute zero, or an expansion coefficient outside [0, 0.001) 1/K.
    """

    suction_temperature: float
    discharge_temperature: float
    reference_temperature: float = REFERENCE_TEMPERATURE
    rotor_expansion: float = STEEL_EXPANSION
    housing_expansion: float = GREY_CAST_IRON_EXPANSION
    housing_temperature: float | None = None  # default: the rotors' computation temperature

    def __post_init__(self) -> None:
        for name in ("suction_temperature", "discharge_temperature", "reference_temperature"):
            v = getattr(self, name)
            if not (np.isfinite(v) and v > -273.15):
                raise DesignError(name, "a temperature above absolute zero in degC", v)
        for name in ("rotor_expansion", "housing_expansion"):
            v = getattr(self, name)
            if not (np.isfinite(v) and 0.0 <= v < 1e-3):
                raise DesignError(name, "a linear expansion coefficient from 0 to 0.001 per K", v)

    @property
    def rotor_temperature(self) -> float:
        """Rotor computation temperature, the mean of suction and discharge temperature, degC."""
        return 0.5 * (self.suction_temperature + self.discharge_temperature)

    @property
    def rotor_scale(self) -> float:
        """Growth factor of the rotors, 1 + zeta_rotor (t_rotor - t_ref)."""
        return 1.0 + self.rotor_expansion * (self.rotor_temperature - self.reference_temperature)

    @property
    def housing_temperature_used(self) -> float:
        """Housing temperature the centre distance follows, degC: the one given, else the rotors'."""
        return self.rotor_temperature if self.housing_temperature is None else self.housing_temperature

    @property
    def housing_scale(self) -> float:
        """Growth factor of the housing (and so of the centre distance), 1 + zeta_housing (t_housing - t_ref)."""
        return 1.0 + self.housing_expansion * (self.housing_temperature_used - self.reference_temperature)

    def keys(self, center_distance_cold: float) -> dict[str, float]:
        """Return the temperatures and coefficients of the hot pair, as ``rotorcad clearance`` reports them.

        Parameters
        ----------
        center_distance_cold : float, mm
            Centre distance of the pair at the reference temperature (the one given).

        Returns
        -------
        dict of str to float
            ``rotor_temperature``, ``housing_temperature``, ``reference_temperature`` (degC),
            ``rotor_expansion``, ``housing_expansion`` (1/K) and ``center_distance_cold`` (mm).
        """
        return {
            "rotor_temperature": self.rotor_temperature,
            "housing_temperature": self.housing_temperature_used,
            "reference_temperature": self.reference_temperature,
            "rotor_expansion": self.rotor_expansion,
            "housing_expansion": self.housing_expansion,
            "center_distance_cold": center_distance_cold,
        }

    def apply(self, pair: RotorPair, male: Array, female: Array) -> tuple[RotorPair, Array, Array]:
        """Return the hot pair and the hot profile points.

        Each rotor grows about its own axis, the lead and the length with it; the centre distance grows
        with the housing.

        Parameters
        ----------
        pair : RotorPair
            The cold pair.
        male, female : (n, 2) float array or list of Curve, mm
            Profile points (or exact curves) of each rotor in its own frame.

        Returns
        -------
        tuple of (RotorPair, male, female)
            The hot pair and both profiles scaled by :attr:`rotor_scale`.
        """
        k = self.rotor_scale
        hot = replace(
            pair,
            center_distance=pair.center_distance * self.housing_scale,
            male_tip_radius=pair.male_tip_radius * k,
            male_root_radius=pair.male_root_radius * k,
            female_tip_radius=pair.female_tip_radius * k,
            female_root_radius=pair.female_root_radius * k,
            lead=pair.lead * k,
            length=pair.length * k,
        )
        return hot, _scaled(male, k), _scaled(female, k)


def _scaled(profile: Array | list[Curve], k: float) -> Array | list[Curve]:
    """Grow points (n, 2) or exact curves by the factor ``k`` about the rotor's centre."""
    if isinstance(profile, list | tuple):
        return [Mapped(c, ((k, 0.0), (0.0, k))) for c in profile]
    return np.asarray(profile) * k


__all__ = ["GREY_CAST_IRON_EXPANSION", "REFERENCE_TEMPERATURE", "STEEL_EXPANSION", "ThermalState"]
