"""The equivalent beam of a screw rotor and its deflection line (Rinder & Deix, sec. 2.3, 3.3).

Equation fixes (the OCR'd paper has misprints; each choice is checked by a limit or a derivation):

- eq. (2): J_red = pi J_ges J_F / (pi J_F + 2 (J_ges - J_F) arctan X),
  X = 0.5272 (d_F/d_K)^1.3161 (phi_L / l)^1.684. The printed "+" before J_F in the denominator
  would make J_red tend to J_ges J_F / (J_ges + 2 J_F) for large wraps, not to J_F as the text
  says; with "-" J_red runs from J_ges (X = 0, no twist) to J_F (X -> inf).
- phi_L / l: the fit is stated in degrees per millimetre (l in mm in the paper's legend) for rotors
  of one size, so read literally it depends on absolute size (a pair twice as large, same shape,
  would get another J_red / J_ges, and a design typed in inches another answer). The physics of
  the paper's spring-and-bar model (sec. 2.2: the teeth are helical springs wound on the core)
  depends on the wrap per length times a length of the section, e.g. the tip helix
  tan beta_K = (phi_L / l) d_K / 2 in rad: dimensionless. So the rotor's phi_L / l is converted to
  that of the pair of the same shape at the fit's size, centre distance
  ``FIT_CENTER_DISTANCE`` = 82 mm: (phi_L / l)_fit = (phi_L / l) a / 82 mm, in deg/mm, and put into
  eq. (2). The paper prints neither its example pair's dimensions nor the sizes of the FE study's
  rotors; 82 mm is the size of rotorcad's sample of the paper's 5/6 example
  (samples/rinder_deix_5_6.toml), at which this reading gives the paper's 0.002 mm (female) to
  4 % (README, "Rinder & Deix's example"); no other size fits both rotors (at 60 mm the female
  gives 2.26 um, the male 0.47 um; the male's 0.5 um would need about 45 mm). With the
  conversion every length of a pair scaled by k at the same pressures scales J_red by k^4, d_aeq
  and the deflection by k, exactly (the beam
  argument: q ~ p d, w ~ q l^4 / (E d^4)). In deg/mm X is near 1 for such a rotor, in the middle of
  the arctan, where the paper's Fig. 2 and 4 show the wrap to matter; in rad/mm J_red would stay
  within 0.1 % of J_ges for every practical rotor, in deg/m or rad/m it would be J_F for all of them.
- eq. (3) is the round bar whose midspan deflection under a central force equals that of the
  rotor beam (J_red, G A_ges / kappa): with F l^3/(48 E J) + kappa F l / (4 G A) and
  G = E / (2 (1 + mu)) the quadratic in d^2 has exactly the printed u and v (derived in the test).
- eq. (4): (EJ)_ers = E pi d^4 / 64 (printed d^2) and (GA/kappa)_ers = G pi d^2 / (4 kappa).
- eq. (7) prints a term 4 d cos(2 pi z / l), which is not 0 at z = 0; the ansatz that satisfies
  the boundary conditions of the simply supported helical part (w = 0, M = 0 at both ends) is the
  sine series w = sum_k a_k sin(k pi z / l). For the beam equation with shear,
  w'' = -M/(EJ) - kappa q/(GA), the Galerkin coefficients are exact per term:
  a_k = q_k (l / k pi)^4 [1/(EJ) + kappa (k pi / l)^2 / (GA)], q_k = 2/l int q sin(k pi z/l) dz.
  k = 1 reproduces eq. (9): c_xm = q_1 (l/pi)^4 and c_xq = q_1 (l/pi)^2 for the paper's load
  (checked in the test against the printed eq. 9). The paper used two terms; more are offered.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.errors import DesignError

KAPPA_ROUND = 10.0 / 9.0  # shear correction of a full circle (eq. 1): the paper's 1.111
FIT_CENTER_DISTANCE = 82.0  # mm: the pair size eq. (2)'s deg/mm fit is read at (module docstring)


def reduced_second_moment(
    j_total: float,
    j_core: float,
    root_diameter: float,
    tip_diameter: float,
    wrap_deg: float,
    length: float,
    center_distance: float = FIT_CENTER_DISTANCE,
) -> float:
    """J_red of the equivalent beam, eq. (2) with the sign fixed and made size-similar (module docstring).

    Parameters
    ----------
    j_total : float, mm^4
        J_ges of the whole transverse section.
    j_core : float, mm^4
        J_F of the root (core) circle.
    root_diameter, tip_diameter : float, mm
        d_F, d_K.
    wrap_deg : float, deg
        phi_L, the wrap of the rotor over ``length``.
    length : float, mm
        l, the helical length.
    center_distance : float, mm
        a of the pair the rotor belongs to: phi_L / l is put into eq. (2) as
        ``wrap_per_length_at_fit_size`` (that of the same-shaped pair at a = 82 mm).

    Returns
    -------
    float, mm^4
        J_red, from J_ges (no wrap) to J_F (large wrap per length).
    """
    x = (
        0.5272
        * (root_diameter / tip_diameter) ** 1.3161
        * wrap_per_length_at_fit_size(wrap_deg, length, center_distance) ** 1.684
    )
    return float(np.pi * j_total * j_core / (np.pi * j_core + 2.0 * (j_total - j_core) * np.arctan(x)))


def wrap_per_length_at_fit_size(wrap_deg: float, length: float, center_distance: float) -> float:
    """Return the wrap per length phi_L / l that eq. (2)'s fit is read with, deg/mm (module docstring).

    Parameters
    ----------
    wrap_deg : float, deg
        phi_L.
    length, center_distance : float, mm
        l and the pair's centre distance a.

    Returns
    -------
    float, deg/mm
        |phi_L| / l * a / ``FIT_CENTER_DISTANCE``: the phi_L / l of the same-shaped pair at the fit's
        size; a function of the shape alone (phi_L and l / a).
    """
    return abs(wrap_deg) / length * center_distance / FIT_CENTER_DISTANCE


def equivalent_diameter(area: float, j_red: float, length: float, poisson: float, kappa: float = KAPPA_ROUND) -> float:
    """d_aeq of the round bar that deflects as the rotor does, eq. (3).

    Parameters
    ----------
    area : float, mm^2
        A_ges.
    j_red : float, mm^4
        Eq. (2).
    length : float, mm
        l of the helical part.
    poisson : float
        mu.
    kappa : float
        Shear correction (the paper: 1.111).
    """
    den = np.pi * (area * length**2 + 24.0 * j_red * kappa * (1.0 + poisson))
    u = 48.0 * area * j_red * kappa * (1.0 + poisson) / den
    v = 64.0 * area * j_red * length**2 / den
    return float(np.sqrt(u + np.sqrt(u * u + v)))


@dataclass(frozen=True)
class Beam:
    """Bending and shear stiffness of a simply supported beam of length ``length``.

    Attributes
    ----------
    bending : float, N mm^2
        EJ.
    shear : float, N
        GA / kappa.
    length : float, mm
    """

    bending: float
    shear: float
    length: float

    @classmethod
    def round_bar(cls, diameter: float, length: float, young: float, poisson: float, kappa: float = KAPPA_ROUND) -> Beam:
        """Make the equivalent round bar of a diameter (Rinder & Deix eq. 4).

        Parameters
        ----------
        diameter : float, mm
            Diameter d of the bar.
        length : float, mm
            Its length.
        young : float, N/mm²
            Young's modulus E.
        poisson : float
            Poisson's ratio mu (G = E / (2 (1 + mu))).
        kappa : float
            Shear correction factor of the round section.

        Returns
        -------
        Beam
            EJ = E pi d^4 / 64 (N mm²), GA / kappa = G pi d^2 / (4 kappa) (N).
        """
        g = young / (2.0 * (1.0 + poisson))
        return cls(young * np.pi * diameter**4 / 64.0, g * np.pi * diameter**2 / (4.0 * kappa), float(length))

    def sine_coefficients(self, z: np.ndarray, load: np.ndarray, terms: int) -> np.ndarray:
        """q_k = 2/l int q(z) sin(k pi z / l) dz, k = 1..terms, by the midpoint rule.

        Parameters
        ----------
        z : (n,) float, mm
            Midpoints of n equal cells over [0, l].
        load : (n, d) float, N/mm
        terms : int

        Returns
        -------
        (terms, d) float, N/mm
        """
        k = np.arange(1, terms + 1)[:, None]
        basis = np.sin(k * np.pi * z[None, :] / self.length)
        return 2.0 / self.length * (basis @ load) * (self.length / len(z))

    def deflection(self, coefficients: np.ndarray, z: np.ndarray) -> np.ndarray:
        """w(z) from the load's sine coefficients (the Ritz-Galerkin solution, module docstring).

        Parameters
        ----------
        coefficients : (terms, d) float, N/mm
        z : (m,) float, mm

        Returns
        -------
        (m, d) float, mm
        """
        k = np.arange(1, len(coefficients) + 1)
        lam = k * np.pi / self.length
        gain = (1.0 / self.bending + lam**2 / self.shear) / lam**4  # (terms,)
        return np.sin(np.outer(z, lam)) @ (gain[:, None] * coefficients)


def step_load_coefficients(q: float, lead: float, length: float, reach: float, psi0: float, terms: int) -> np.ndarray:
    """Return the sine coefficients of the paper's flute load (Rinder & Deix eq. 6).

    q_x = -q cos(2 pi z / h + psi0) for 0 <= z <= r, 0 beyond, in closed form for every k (k = 1 is
    eq. 9's bracket).

    Parameters
    ----------
    q : float, N/mm
        l_s p (eq. 5).
    lead, length, reach : float, mm
        h, l, r.
    psi0 : float, rad
        Direction of the load's line of action at z = 0.
    terms : int
        Number of sine terms.

    Returns
    -------
    (terms, 2) float array, N/mm
        q_k for the x and y components (the y one is -q sin(...)).

    Raises
    ------
    DesignError
        A reach outside [0, length].
    """
    if not (0 <= reach <= length):
        raise DesignError("pressurised length r", f"from 0 to the rotor length {length:g} mm", reach)
    k = np.arange(1, terms + 1)
    a = k * np.pi / length  # sin(a z)
    b = 2 * np.pi / lead  # cos(b z + psi0)
    out = np.empty((terms, 2))
    for j, phase in enumerate((psi0, psi0 - np.pi / 2)):  # sin(x) = cos(x - pi/2)
        # int_0^r cos(b z + phase) sin(a z) dz = 1/2 int [sin((a+b) z + phase) + sin((a-b) z - phase)] dz
        plus = (np.cos(phase) - np.cos((a + b) * reach + phase)) / (a + b)
        minus = np.where(
            np.abs(a - b) > 1e-12,
            (np.cos(-phase) - np.cos((a - b) * reach - phase)) / np.where(np.abs(a - b) > 1e-12, a - b, 1.0),
            reach * np.sin(-phase),
        )
        out[:, j] = -q * (2.0 / length) * 0.5 * (plus + minus)
    return out


@dataclass(frozen=True)
class ShaftSegment:
    """A piece of a rotor shaft between the bearings, as a beam.

    Attributes
    ----------
    length : float, mm
    bending : float, N mm^2
        EJ.
    shear : float, N
        GA / kappa.
    """

    length: float
    bending: float
    shear: float


def stepped_deflection(
    segments: list[ShaftSegment], loaded: int, load: np.ndarray, cells: int = 2000
) -> tuple[np.ndarray, np.ndarray]:
    """Compute the deflection of a shaft of segments on bearings at its two ends (statically determinate).

    By integrating w'' = -M/(EJ) and the shear slope kappa V/(GA) along it (the classical beam
    theory with which Rinder & Deix superpose the journals; the helical part is one segment with
    its equivalent stiffnesses, eq. 4).

    Parameters
    ----------
    segments : list of ShaftSegment
        From the first bearing to the second.
    loaded : int
        Index of the segment that carries the load (the helical part).
    load : (n, d) float array, N/mm
        Line load at the midpoints of n equal cells over the loaded segment.
    cells : int
        Integration cells over the whole shaft (at least 20 per segment).

    Returns
    -------
    z : (m,) float array, mm
        Positions from the first bearing.
    w : (m, d) float array, mm
        Deflection, zero at both bearings.
    """
    ends = np.concatenate([[0.0], np.cumsum([s.length for s in segments])])
    total = ends[-1]
    pieces = [np.linspace(ends[i], ends[i + 1], max(20, int(cells * s.length / total)) + 1) for i, s in enumerate(segments)]
    nodes = np.unique(np.concatenate(pieces))
    load = np.asarray(load, dtype=float)
    n = len(load)
    z0, z1 = ends[loaded], ends[loaded + 1]
    mid = 0.5 * (nodes[1:] + nodes[:-1])
    cell = np.clip(np.floor((mid - z0) / (z1 - z0) * n).astype(int), 0, n - 1)
    q = np.where(((mid >= z0) & (mid < z1))[:, None], load[cell], 0.0)  # (m-1, d), constant per cell
    dz = np.diff(nodes)
    force = q * dz[:, None]
    reaction_b = (force * mid[:, None]).sum(axis=0) / total
    reaction_a = force.sum(axis=0) - reaction_b
    shear = reaction_a - np.concatenate([np.zeros((1, q.shape[1])), np.cumsum(force, axis=0)])  # V at nodes
    moment = np.concatenate([np.zeros((1, q.shape[1])), np.cumsum(0.5 * (shear[1:] + shear[:-1]) * dz[:, None], axis=0)])
    seg = np.clip(np.searchsorted(ends, mid, side="right") - 1, 0, len(segments) - 1)
    bending = np.array([s.bending for s in segments])[seg]
    shear_stiff = np.array([s.shear for s in segments])[seg]
    curvature = -0.5 * (moment[1:] + moment[:-1]) / bending[:, None]  # per cell
    slope = np.concatenate([np.zeros((1, q.shape[1])), np.cumsum(curvature * dz[:, None], axis=0)])
    w_bend = np.concatenate([np.zeros((1, q.shape[1])), np.cumsum(0.5 * (slope[1:] + slope[:-1]) * dz[:, None], axis=0)])
    w_shear = np.concatenate(
        [np.zeros((1, q.shape[1])), np.cumsum(0.5 * (shear[1:] + shear[:-1]) / shear_stiff[:, None] * dz[:, None], axis=0)]
    )
    w = w_bend + w_shear
    w -= np.outer(nodes / total, w[-1])  # a rigid turn puts the second bearing at 0
    return nodes, w
