"""Lubricant film of a cylinder on a plane: the contact-hydrodynamic (EHL) line-contact problem.

After Belkov, Maksimov & Shitikov, *Contact-hydrodynamic calculation of gear couplings of
high-speed turbomachines*, eqs. 1-6, solved numerically.

The paper's system, as reconstructed from the damaged OCR (every symbol in SI units):

* eqs. 1-2 (thin-film Navier-Stokes and continuity, one surface moving, the other at rest) give
  the Reynolds equation, printed as ``dp/dx = 6 mu V_Sigma (h - h0) / h^3``; ``V_Sigma`` is the
  sum of the surface speeds, so with the mean entraining speed u = V_Sigma / 2 it reads
  ``d/dx(h^3/(12 mu) dp/dx) = u dh/dx`` (integrated once with the flux constant h0 = h where
  dp/dx = 0). The OCR's boundary condition "dp/dx = 0 at h = h0" is the Reynolds (Swift-Stieber)
  outlet condition p = dp/dx = 0, kept here as p >= 0 with a free cavitation boundary;
* eq. 3: the undeformed gap of a cylinder of radius R on a plane, h(x) = h_0 + x^2/(2R);
* eq. 5: the elastic gap, h(x) = h_0 + x^2/(2R) - (2/(pi E_pr)) int p(s) ln|x - s| ds. The OCR's
  E_pr multiplies 2/pi; with Hamrock's reduced modulus E' (2/E' = sum (1 - nu^2)/E) the same
  kernel reads 4/(pi E'), which is what is used (it makes the Hertz pressure give a flat gap);
* eq. 6: Barus viscosity mu = mu_0 exp(alpha_0 p).

The paper does not solve eq. 5 itself: it replaces the deformed gap by a cylinder of twice the
radius (R_1 ~ 2 R, its Fig. 3) and integrates the Reynolds equation in closed form (its eq. 8,
the primitive of x^2/(a^2 + x^2)^3 with a^2 = 4 R h_0 inside and 2 R h_0 outside the Hertz
strip of half-width b_0 = 0.34e-5 sqrt(w R), which is the steel Hertz half-width, E = 2.0e11 Pa,
nu = 0.3). Here the coupled system 1-6 is solved as it stands, by Newton-Raphson on the
discretised Reynolds equation, the elastic gap and the load balance together (the method of
Houpert & Hamrock 1986), so the closed-form shortcut is not needed.

Discretisation. Lengths are scaled by ``ell`` (the larger of the Hertz half-width and the rigid
hydrodynamic length sqrt(8 R mu_0 u R / w')), pressures by w'/ell, gaps by ell^2/R. The grid is
uniform in a coordinate xi with X = xi from -1.5 to the outlet at X = 2 and X = -1.5 - sinh(-1.5 - xi)
further upstream (fine in the contact, coarse far upstream, so the inlet can sit far away: fully
flooded). In xi the Reynolds equation is d/dxi(eps/X' dP/dxi) = lambda dH/dxi with
eps = H^3 exp(-alpha_bar P): central second differences for the Poiseuille term, second-order upwind
differences for the wedge term. The elastic deflection uses piecewise-constant pressure on the
cells and the exact integral of ln|t|; the Jacobian's product with the dense influence matrix is
taken band by band. Cavitated nodes (P = 0 where the Reynolds equation would make P < 0) form an
active set that is updated every Newton step. A coarse first pass (inlet 30 scaled lengths
upstream) gives the central film h_c; the final grid puts the inlet 25 sqrt(2 R h_c) upstream of
the Hertz strip.

Checks (tests/test_coupling.py): Martin's rigid isoviscous film h_min = 4.9 mu_0 u R / w' to
better than 1 % with 401 nodes; the Hertz pressure under heavy loads; Dowson-Higginson and
Pan-Hamrock films within 0.7...1.4 in the elastic-piezoviscous regime.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

Array = np.ndarray

STEEL_E = 2.0e11  # Pa: the paper's b_0 = 0.34e-5 sqrt(w R) is the Hertz half-width of steel on steel with these
STEEL_NU = 0.3

_FINE = 1.5  # the grid is uniform from -_FINE to the outlet (scaled lengths)
_OUTLET = 2.0  # outlet end of the grid in scaled lengths (past the cavitation boundary)
_FAR_INLET = 30.0  # inlet of the first, coarse pass (scaled lengths)
_INLET_FILMS = 25.0  # the fine pass puts the inlet this many sqrt(2 R h_c) upstream of the Hertz strip


def reduced_modulus(e1: float = STEEL_E, nu1: float = STEEL_NU, e2: float = STEEL_E, nu2: float = STEEL_NU) -> float:
    """Return Hamrock's reduced modulus E', 2/E' = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.

    Parameters
    ----------
    e1, e2 : float, Pa
        Young's moduli of the two bodies (default steel, 2.0e11 Pa).
    nu1, nu2 : float
        Their Poisson's ratios (default 0.3).

    Returns
    -------
    float, Pa
    """
    return 2.0 / ((1.0 - nu1**2) / e1 + (1.0 - nu2**2) / e2)


@dataclass(frozen=True)
class LineContact:
    """A lubricated cylinder on a plane, per unit length of the line of contact (SI units).

    Parameters
    ----------
    radius : float
        Radius R of the cylinder [m] (for a coupling tooth, the flank crown radius R_b).
    load : float
        Load per unit length w' [N/m].
    speed : float
        Mean entraining speed u = (u_1 + u_2)/2 of the surfaces relative to the contact [m/s].
    viscosity : float
        Viscosity at ambient pressure mu_0 [Pa s].
    pressure_viscosity : float
        Barus coefficient alpha_0 [1/Pa] (eq. 6); 0 for an isoviscous lubricant.
    modulus : float
        Reduced modulus E' [Pa]; ``math.inf`` for rigid bodies (no elastic term in eq. 5).
    """

    radius: float
    load: float
    speed: float
    viscosity: float
    pressure_viscosity: float = 0.0
    modulus: float = reduced_modulus()

    @property
    def hertz_half_width(self) -> float:
        """Hertz half-width b = sqrt(8 w' R / (pi E')) [m] (0 for rigid bodies)."""
        return float(np.sqrt(8.0 * self.load * self.radius / (np.pi * self.modulus)))

    @property
    def hertz_pressure(self) -> float:
        """Hertz maximum pressure p_H = sqrt(w' E' / (2 pi R)) [Pa]."""
        return float(np.sqrt(self.load * self.modulus / (2.0 * np.pi * self.radius)))

    @property
    def film_scale(self) -> float:
        """mu_0 u R / w' [m]: the natural hydrodynamic film scale (Martin's film is 4.9 times it)."""
        return self.viscosity * self.speed * self.radius / self.load


@dataclass(frozen=True, eq=False)
class FilmSolution:
    """Pressure and film of a :class:`LineContact`.

    Attributes
    ----------
    x : ndarray, shape (n,)
        Grid along the rolling direction [m], inlet at x < 0.
    pressure : ndarray, shape (n,)
        Film pressure p(x) [Pa].
    film : ndarray, shape (n,)
        Film thickness h(x) [m] (elastic gap, eq. 5).
    converged : bool
        Whether Newton's method met its tolerance.
    """

    x: Array
    pressure: Array
    film: Array
    converged: bool

    @property
    def min_film(self) -> float:
        """Minimum film thickness h_min [m] (in the wetted part, up to the cavitation boundary)."""
        wet = self.pressure > 0
        last = np.flatnonzero(wet)[-1] + 1 if wet.any() else len(self.x)
        return float(self.film[: last + 1].min())

    @property
    def central_film(self) -> float:
        """Film thickness at x = 0 [m]."""
        return float(np.interp(0.0, self.x, self.film))

    @property
    def max_pressure(self) -> float:
        """Largest film pressure p_max [Pa]."""
        return float(self.pressure.max())

    @property
    def load_capacity(self) -> float:
        """Load capacity of the film per unit length, int p dx [N/m] (trapezoidal rule)."""
        return float(np.trapezoid(self.pressure, self.x))


@dataclass(frozen=True, eq=False)
class _Grid:
    """Mapped grid: nodes X (shape (n,)), the map's derivative dX/dxi, cell widths in X, step in xi."""

    x: Array
    dxdxi: Array
    width: Array
    step: float


def _grid(nodes: int, inlet: float) -> _Grid:
    """Nodes uniform in xi; X = xi on [-_FINE, _OUTLET], X = -_FINE - sinh(-_FINE - xi) upstream, down to -inlet."""
    far = np.arcsinh(max(inlet - _FINE, 0.0))
    xi = np.linspace(-_FINE - far, _OUTLET, nodes)
    step = float(xi[1] - xi[0])

    def x_of(t: Array) -> Array:
        return np.where(t < -_FINE, -_FINE - np.sinh(np.clip(-_FINE - t, 0.0, None)), t)

    edges = x_of(np.concatenate([[xi[0]], 0.5 * (xi[1:] + xi[:-1]), [xi[-1]]]))
    return _Grid(x_of(xi), np.cosh(np.clip(-_FINE - xi, 0.0, None)), np.diff(edges), step)


def _influence(grid: _Grid) -> Array:
    """K[i, j] = -int over cell j of ln|X_i - S| dS: the deflection at node i of unit pressure on cell j.

    Shape (n, n). Exact for piecewise-constant pressure (primitive t ln|t| - t of ln|t|).
    """
    edges = np.concatenate([[grid.x[0]], np.cumsum(grid.width) + grid.x[0]])

    def prim(t: Array) -> Array:
        a = np.abs(t)
        return np.where(a > 0, t * np.log(np.where(a > 0, a, 1.0)), 0.0) - t

    d = grid.x[:, None] - edges[None, :]
    f = prim(d)
    return f[:, 1:] - f[:, :-1]  # -int_{e_j}^{e_j+1} ln|x - s| ds = F(x - e_j+1) - F(x - e_j)


def _wedge_bands(n: int, step: float) -> dict[int, Array]:
    """Return the diagonals of the wedge term dH/dxi by offset, each of shape (n,).

    dH/dxi at node i is the sum over offsets o of c_o[i] H[i + o]: second-order upwind differences
    (first order at the first interior node).
    """
    c = {0: np.zeros(n), -1: np.zeros(n), -2: np.zeros(n)}
    c[0][2 : n - 1], c[-1][2 : n - 1], c[-2][2 : n - 1] = 1.5 / step, -2.0 / step, 0.5 / step
    c[0][1], c[-1][1] = 1.0 / step, -1.0 / step
    return c


def _band_apply(bands: dict[int, Array], v: Array) -> Array:
    """(B v) for a banded B given by its diagonals (offset -> shape (n,)); v of shape (n,) or (n, m)."""
    out = np.zeros_like(v)
    n = len(v)
    for o, c in bands.items():
        lo, hi = max(0, -o), min(n, n - o)
        out[lo:hi] += (c[lo:hi] * v[lo + o : hi + o].T).T
    return out


def _band_dense(bands: dict[int, Array], n: int) -> Array:
    """Return the banded matrix given by its diagonals as a dense (n, n) array."""
    m = np.zeros((n, n))
    for o, c in bands.items():
        i = np.arange(max(0, -o), min(n, n - o))
        m[i, i + o] = c[i]
    return m


@dataclass(frozen=True, eq=False)
class _Scaled:
    """The dimensionless problem: lambda (Reynolds), alpha_bar (Barus), kappa (elasticity)."""

    lam: float
    alpha: float
    kappa: float
    ell: float
    p_scale: float
    h_scale: float


def _scaled(c: LineContact) -> _Scaled:
    b = c.hertz_half_width
    ell = max(b, np.sqrt(8.0 * c.radius * c.film_scale))
    p_scale = c.load / ell
    return _Scaled(
        lam=12.0 * c.viscosity * c.speed * c.radius**2 / (ell**2 * c.load),
        alpha=c.pressure_viscosity * p_scale,
        kappa=b**2 / (2.0 * ell**2),
        ell=float(ell),
        p_scale=float(p_scale),
        h_scale=float(ell**2 / c.radius),
    )


class _Newton:
    """Newton-Raphson on (P, H0) for one scaled problem on one grid; all operations are arrays."""

    def __init__(self, s: _Scaled, grid: _Grid, kernel: Array) -> None:
        self.s, self.g = s, grid
        self.n = len(grid.x)
        self.ek = s.kappa * kernel  # elastic influence, shape (n, n)
        self.wedge = _wedge_bands(self.n, grid.step)
        self.base = 0.5 * grid.x**2

    def film(self, p: Array, h0: float) -> Array:
        """H = H0 + X^2/2 + kappa K P (eq. 5, scaled), shape (n,)."""
        return h0 + self.base + self.ek @ p

    def _coefficients(self, p: Array, h: Array) -> tuple[Array, Array]:
        """Return G = eps / X' = H^3 exp(-alpha P) / X' at the nodes and its face means, shapes (n,), (n-1,)."""
        g = h**3 * np.exp(-self.s.alpha * p) / self.g.dxdxi
        return g, 0.5 * (g[1:] + g[:-1])

    def residual(self, p: Array, h: Array) -> Array:
        """Reynolds residual at the interior nodes (zero at the two ends), shape (n,)."""
        _, face = self._coefficients(p, h)
        flux = face * np.diff(p)
        res = np.zeros(self.n)
        res[1:-1] = (flux[1:] - flux[:-1]) / self.g.step**2
        return res - self.s.lam * _band_apply(self.wedge, h)

    def system(self, p: Array, h0: float, fixed: Array) -> tuple[Array, Array]:
        """Assemble the residual (shape (n+1,)) and the Jacobian (shape (n+1, n+1)).

        Reynolds rows, rows P = 0 at the ends and at cavitated nodes (``fixed``), and the load row
        sum(P width) = 1.
        """
        n, d2 = self.n, self.g.step**2
        h = self.film(p, h0)
        g, face = self._coefficients(p, h)
        dp = np.diff(p)
        zero = np.zeros(n)
        q = {-1: zero.copy(), 0: zero.copy(), 1: zero.copy()}  # d res / d g by offset
        q[-1][1:-1], q[0][1:-1], q[1][1:-1] = -0.5 * dp[:-1] / d2, 0.5 * (dp[1:] - dp[:-1]) / d2, 0.5 * dp[1:] / d2
        direct = {-1: zero.copy(), 0: zero.copy(), 1: zero.copy()}  # d res / d P through the differences
        direct[-1][1:-1], direct[1][1:-1] = face[:-1] / d2, face[1:] / d2
        direct[0][1:-1] = -(face[1:] + face[:-1]) / d2
        dh = {o: q[o] * np.roll(3.0 * g / h, -o) for o in q}  # d res / d H = Q diag(3 g / H) - lambda W
        for o, c in self.wedge.items():
            dh[o] = dh.get(o, 0.0) - self.s.lam * c
        bands = {o: direct[o] + q[o] * np.roll(-self.s.alpha * g, -o) for o in direct}
        jac = np.zeros((n + 1, n + 1))
        jac[:n, :n] = _band_dense(bands, n) + _band_apply(dh, self.ek)
        jac[:n, n] = _band_apply(dh, np.ones(n))
        res = np.zeros(n + 1)
        res[:n] = self.residual(p, h)
        rows = np.flatnonzero(fixed)
        jac[rows] = 0.0
        jac[rows, rows] = 1.0
        res[rows] = p[rows]
        jac[n, :n] = self.g.width
        res[n] = p @ self.g.width - 1.0
        return res, jac

    def cavitated(self, p: Array, h0: float) -> Array:
        """Return the nodes held at P = 0, a bool mask of shape (n,).

        The two ends, and nodes downstream of the pressure peak where P = 0 and the Reynolds equation
        solved for that node alone (neighbours fixed) would not give P > 0.
        """
        h = self.film(p, h0)
        _, face = self._coefficients(p, h)
        num = np.zeros(self.n)
        num[1:-1] = (face[1:] * p[2:] + face[:-1] * p[:-2]) / self.g.step**2
        num -= self.s.lam * _band_apply(self.wedge, h)
        out = (p <= 0.0) & (self.g.x > self.g.x[np.argmax(p)]) & (num <= 0.0)
        out[[0, -1]] = True
        return out

    def solve(self, p: Array, h0: float, iterations: int = 60) -> tuple[Array, float, bool]:
        """Newton iterations from (p, h0), damped to keep the film positive; returns (P, H0, converged)."""
        fixed = self.cavitated(p, h0)
        for _ in range(iterations):
            res, jac = self.system(p, h0, fixed)
            try:
                step = np.linalg.solve(jac, -res)
            except np.linalg.LinAlgError:
                return p, h0, False
            factor = 1.0
            while factor > 1e-6:
                p_new = np.maximum(p + factor * step[: self.n], 0.0)
                h0_new = h0 + factor * step[self.n]
                if self.film(p_new, h0_new).min() > 0:
                    break
                factor *= 0.5
            else:
                return p, h0, False
            change = np.abs(p_new - p).max() / p_new.max() + abs(h0_new - h0) / max(abs(h0_new), 1e-3)
            new_fixed = self.cavitated(p_new, h0_new)
            settled = np.array_equal(new_fixed, fixed)
            p, h0, fixed = p_new, h0_new, new_fixed
            if change < 1e-9 and settled and factor == 1.0:
                return p, h0, True
        return p, h0, False


def _start(s: _Scaled, c: LineContact, grid: _Grid) -> tuple[Array, float]:
    """Return the initial pressure (a half ellipse over the Hertz strip, or over the rigid pressure zone) and H0."""
    half = max(c.hertz_half_width / s.ell, 0.5)
    p = np.sqrt(np.clip(1.0 - (grid.x / half) ** 2, 0.0, None))
    p /= p @ grid.width
    return p, 0.5 * c.film_scale / s.h_scale + 1e-3


def _partial(s: _Scaled, t: float) -> _Scaled:
    """Return the problem at continuation parameter t in [0, 1]: elasticity grows on [0, 1/2], then pressure-viscosity."""
    return _Scaled(s.lam, s.alpha * max(0.0, 2.0 * t - 1.0), s.kappa * min(1.0, 2.0 * t), s.ell, s.p_scale, s.h_scale)


def _newton(s: _Scaled, c: LineContact, grid: _Grid, start: tuple[Array, float] | None) -> tuple[Array, float, bool]:
    """Run Newton from ``start`` (or the half-ellipse start), with continuation if that fails.

    The continuation starts from the rigid isoviscous problem (linear but for the load balance):
    elasticity first, then alpha_0, with steps that double after a success and halve after a failure
    (down to 1/256). Returns (P, H0, converged).
    """
    kernel = _influence(grid)
    p, h0 = start or _start(s, c, grid)
    p, h0, ok = _Newton(s, grid, kernel).solve(p, h0)
    if ok:
        return p, h0, ok
    p, h0 = _start(s, c, grid)
    p, h0, ok = _Newton(_partial(s, 0.0), grid, kernel).solve(p, h0)
    t, dt = 0.0, 0.125
    while ok and t < 1.0:
        t_next = min(1.0, t + dt)
        p_next, h0_next, step_ok = _Newton(_partial(s, t_next), grid, kernel).solve(p, h0)
        if step_ok:
            p, h0, t, dt = p_next, h0_next, t_next, 2.0 * dt
        elif dt > 1.0 / 256.0:
            dt *= 0.5
        else:
            ok = False
    return p, h0, ok


def solve_line_contact(contact: LineContact, nodes: int = 401) -> FilmSolution:
    """Solve the Reynolds equation with Barus viscosity and the elastic gap (Belkov et al. eqs. 1-6).

    The load per unit length of ``contact`` is carried by the film. Two passes: a coarse grid with
    the inlet 30 scaled lengths upstream gives the central film h_c; the fine grid then puts the
    inlet 25 sqrt(2 R h_c) upstream of the Hertz strip (fully flooded) and starts Newton from the
    coarse solution. Newton-Raphson runs on pressure, H0 and the load balance together, with
    continuation (elasticity, then the pressure-viscosity coefficient) when a start fails.

    Parameters
    ----------
    contact : LineContact
        Radius, load, entraining speed, viscosity, Barus coefficient and reduced modulus (SI).
    nodes : int
        Number of nodes n of the fine grid.

    Returns
    -------
    FilmSolution
        Grid x (shape (n,), m), pressure (Pa) and film (m); ``converged`` is False when Newton's
        method found no film (the lubricant cannot carry the load under these conditions).

    Raises
    ------
    ValueError
        A radius, load, speed or viscosity that is not positive.
    """
    if not (contact.radius > 0 and contact.load > 0 and contact.speed > 0 and contact.viscosity > 0):
        raise ValueError("radius, load, speed and viscosity must be positive")
    s = _scaled(contact)
    coarse = _grid(max(nodes // 2, 61), _FAR_INLET)
    p, h0, ok = _newton(s, contact, coarse, None)
    if ok:
        k = _Newton(s, coarse, _influence(coarse))
        h_c = float(np.interp(0.0, coarse.x, k.film(p, h0)))
        inlet = min(_FAR_INLET, max(4.0, contact.hertz_half_width / s.ell + _INLET_FILMS * np.sqrt(2.0 * h_c)))
    else:
        inlet = _FAR_INLET
    grid = _grid(nodes, inlet)
    start = None
    if ok:
        p_fine = np.interp(grid.x, coarse.x, p)
        start = (p_fine / (p_fine @ grid.width), h0)
    p, h0, ok = _newton(s, contact, grid, start)
    newton = _Newton(s, grid, _influence(grid))
    return FilmSolution(
        x=grid.x * s.ell,
        pressure=p * s.p_scale,
        film=newton.film(p, h0) * s.h_scale,
        converged=bool(ok),
    )
