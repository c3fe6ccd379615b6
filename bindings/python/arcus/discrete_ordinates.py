"""Deterministic plane-parallel radiative transfer in water: the independent reference
the ocean engine's Monte Carlo irradiance profiles are compared with.

Pure numpy (scipy optional, used only for sparse solves of many-layer problems); of
arcus it imports only its phase functions (:mod:`arcus.legendre_phases`).  Run it
(``python3 -m arcus.discrete_ordinates``) for an example table.

Conventions
-----------
Geometry.  A horizontally infinite water column; depth ``z >= 0`` is measured downward
in metres and ``z = 0`` is *just below* the surface (0+).  The column is one
homogeneous layer (``solve_profile``) or a stack of homogeneous layers
(``solve_layers``), ending at ``bottom_depth`` (a Lambertian bottom of albedo
``bottom_albedo``, 0 = black) or going on for ever (``math.inf``: an exact
semi-infinite medium, see Method).

Optics.  Absorption ``a`` and scattering ``b`` in 1/m, ``c = a + b``, single-scattering
albedo ``omega = b / c``.  A phase function p(cos Theta) is normalised over the sphere,
``2 pi * int_{-1}^{1} p(mu) dmu = 1`` (isotropic: ``p = 1 / (4 pi)``).  Its Legendre
moments are ``chi_l = 2 pi int p(mu) P_l(mu) dmu`` (``chi_0 = 1``, ``chi_1 = g``), so
``p(mu) = sum_l (2l + 1) chi_l P_l(mu) / (4 pi)``.

Direction cosines.  ``mu`` is the cosine between the direction of *travel* and the
downward vertical: ``mu > 0`` travels down, ``mu < 0`` travels up.

Radiometry.  L(z, mu, phi) is radiance.  The solver works with the azimuthal mean
times 2 pi, ``u(z, mu) = int_0^{2 pi} L dphi``, so that
    E_d = int_0^1 mu u(mu) dmu          downward plane irradiance,
    E_u = int_0^1 mu u(-mu) dmu         upward plane irradiance (positive),
    E_0 = int_{-1}^1 u(mu) dmu          scalar irradiance,
and ``E_d``, ``E_0`` returned *include* the direct (unscattered) beam.  Only the m = 0
azimuthal Fourier component of the radiance enters these, so that is all that is solved.

Illumination.  ``fresnel=False`` (the "beam started just below the surface" set-up): a
collimated beam travels down at in-water direction cosine ``mu0`` with direct downward
plane irradiance 1 at z = 0+ (its flux normal to the beam is 1 / mu0).  There is no
interface: the top is a free, non-reflecting (vacuum) boundary, upwelling light leaves
through it, nothing comes back, and ``E_d(0) = 1`` exactly.
``fresnel=True``: a sun at ``sun_zenith_deg`` in air, with plane irradiance 1 on the
horizontal surface above the water, over a flat air-water interface (water index
``n_water``).  The beam is refracted by Snell's law (in-water ``mu0`` from it) and
transmitted with the unpolarised Fresnel transmittance T, so the direct beam's plane
irradiance at 0+ is T; upwelling light reaching the surface from below is reflected
back down with the unpolarised Fresnel reflectance (total internal reflection beyond
the critical angle), so ``E_d(0+) = T + (the reflected upwelling)``.  The internal
reflection can be switched on or off on its own with ``internal_reflection`` (default:
the value of ``fresnel``), e.g. a beam started just below a reflecting surface is
``fresnel=False, internal_reflection=True``.

Fluxes.  ``incident`` = T (fresnel) or 1: the direct flux entering the water at 0+.
``absorbed`` = sum over layers of ``a * int E_0 dz`` (integrated in closed form from the
solution), ``escaped`` = the upward flux leaving the water through the top (times the
Fresnel transmittance from below when the internal reflection is on), ``bottom`` =
the net downward flux into the bottom, ``E_d(H) - E_u(H)`` (for a black bottom all that
reaches it; 0 for a semi-infinite column).  Energy conservation reads
``incident = absorbed + escaped + bottom``; the three are computed independently of
one another, so their sum checks the solution.

Method
------
Discrete ordinates (Chandrasekhar; Stamnes & Swanson 1981, Stamnes et al. 1988 DISORT)
for the m = 0 component, with N quadrature points per hemisphere (``streams = N``):

* ``quadrature="double_gauss"`` (the default without internal reflection): N
  Gauss-Legendre points on (0, 1); Legendre order ``lmax = 2N - 1``.
* ``quadrature="split"`` (the default when upwelling light is Fresnel-reflected at the
  surface): Gauss points on (0, mu_c) and (mu_c, 1), mu_c the cosine of the critical
  angle; ``lmax = 2 (N // 2) - 1``.  The Fresnel reflectance from below has a
  square-root kink at mu_c (total internal reflection beyond), so the radiance
  reflected down has one; a single Gauss rule across it converges slowly (about 1.4 %
  error in the escaping flux at N = 32, 0.08 % at N = 128), the split rule fast
  (1e-4 at N = 32, 1e-5 at N = 64).

The azimuth-averaged phase-function matrix is the Legendre sum
``K(mu, mu') = sum_{l <= lmax} (2l + 1)/2 chi_l P_l(mu) P_l(mu')`` (2 pi times the
azimuthal mean of p, exactly, up to the truncation), a polynomial of degree lmax in
each argument, which the quadrature integrates exactly: ``sum_j w_j K(mu_i, mu_j) = 1``
and the discrete equations conserve energy to rounding.  Forward-peaked phase
functions use delta-M scaling (Wiscombe 1977; on by default): ``f = chi_{lmax+1}``,
``chi'_l = (chi_l - f) / (1 - f)``, ``b' = (1 - f) b``, the truncated peak being treated
as unscattered.  The irradiances (angular integrals) need no TMS/IMS radiance
corrections; their convergence in N is shown in the self-checks.

The direct beam is attenuated exactly (Beer-Lambert in the scaled optical depth) and
drives the diffuse field as a source ``omega' K'(mu, mu0) F0 exp(-tau / mu0)``.  The
homogeneous solutions of each layer come from the symmetric N x N eigenproblem for
``k^2`` (the DISORT reduction, here symmetrised by a Cholesky factor so the eigenvalues
are real), and are scaled so that every exponential in the boundary-value system is
``exp(-k * distance) <= 1`` (stable for any optical thickness).  A semi-infinite last
layer keeps only its decaying solutions (no black-bottom approximation).  The
boundary conditions (top: vacuum or Fresnel reflection; layer interfaces: continuity;
bottom: Lambertian) give one linear system for all layers.

Conservative scattering: omega is capped at ``1 - OMEGA_GAP`` (1e-12) inside the
eigen-solution, as DISORT does, since omega = 1 makes one eigenvalue 0.  The absorption
that cap adds is ~1e-12 * tau * E_0 of the flux (2e-9 at optical depth 1000).  If the
beam's 1/mu0 falls within 1e-8 (relative) of a homogeneous eigenvalue of a scattering
layer (a resonance of the particular solution) mu0 is moved by 2e-8 (relative), which
changes the irradiances by ~2e-8 tau.

Rounding.  Energy balances to ~1e-12 with absorption.  With a = 0 (omega capped as
above) it holds to ~1e-9 for a finite column; a conservative *semi-infinite* column
(all light returns, after arbitrarily long paths) keeps ~sqrt(OMEGA_GAP) ~ 1e-6 of it.
E_u at a black bottom is 0 to ~1e-11.
"""

import math
from typing import NamedTuple

import numpy as np

# The phase functions and their Legendre moments live in a module of their own; their
# names are this module's too.
from .legendre_phases import (Phase, hg, isotropic, legendre_table, mixture, rayleigh_like,  # noqa: F401
                              tabulated, two_term_hg)

__all__ = [
    "Phase", "hg", "two_term_hg", "rayleigh_like", "isotropic", "tabulated", "mixture",
    "Layer", "solve_profile", "solve_layers", "fresnel_reflectance", "snell_cosine",
    "kd_between", "legendre_table", "double_gauss", "hemisphere_quadrature", "OMEGA_GAP",
]

OMEGA_GAP = 1e-12         # omega <= 1 - OMEGA_GAP in the eigen-solution
RESONANCE_GAP = 1e-8      # minimum |k mu0 - 1| for the beam's particular solution


# ------------------------------------------------------------------------- quadrature

def double_gauss(n):
    """N-point Gauss-Legendre nodes and weights on (0, 1): the double-Gauss hemisphere."""
    return _gauss_on(n, 0.0, 1.0)


def _gauss_on(n, lo, hi):
    x, w = np.polynomial.legendre.leggauss(n)
    return lo + 0.5 * (hi - lo) * (x + 1.0), 0.5 * (hi - lo) * w


def hemisphere_quadrature(n, kind="double_gauss", n_water=1.34):
    """Nodes mu (ascending), weights w on (0, 1) and the Legendre order lmax it integrates
    exactly (so the phase-function kernel, of that degree, is normalised exactly).

    "double_gauss": N Gauss points on (0, 1), lmax = 2N - 1.  "split": Gauss on
    (0, mu_c) and (mu_c, 1) with N//2 and N - N//2 points, mu_c = sqrt(1 - 1/n_water^2)
    the cosine of the critical angle, lmax = 2 (N//2) - 1: the Fresnel reflectance from
    below has a square-root kink at mu_c that a single Gauss rule resolves poorly.
    """
    if kind == "double_gauss":
        mu, w = double_gauss(n)
        return mu, w, 2 * n - 1
    if kind == "split":
        if n < 4:
            raise ValueError("the split quadrature needs streams >= 4")
        mu_c = math.sqrt(1.0 - 1.0 / n_water ** 2)
        n1 = n // 2
        m1, w1 = _gauss_on(n1, 0.0, mu_c)
        m2, w2 = _gauss_on(n - n1, mu_c, 1.0)
        return np.concatenate([m1, m2]), np.concatenate([w1, w2]), 2 * n1 - 1
    raise ValueError(f"unknown quadrature {kind!r} (double_gauss or split)")


# -------------------------------------------------------------------------- interface

def snell_cosine(cos_i, n1, n2):
    """Cosine of the refraction angle, light going from index n1 into n2 (nan for TIR)."""
    cos_i = np.asarray(cos_i, dtype=float)
    sin_t2 = (n1 / n2) ** 2 * (1.0 - cos_i * cos_i)
    with np.errstate(invalid="ignore"):
        return np.where(sin_t2 <= 1.0, np.sqrt(np.maximum(0.0, 1.0 - sin_t2)), np.nan)


def fresnel_reflectance(cos_i, n1, n2):
    """Unpolarised Fresnel reflectance for light in index n1 meeting index n2 at incidence
    cosine cos_i (>= 0); 1 beyond the critical angle."""
    cos_i = np.clip(np.asarray(cos_i, dtype=float), 0.0, 1.0)
    sin_t2 = (n1 / n2) ** 2 * (1.0 - cos_i * cos_i)
    tir = sin_t2 >= 1.0
    cos_t = np.sqrt(np.maximum(0.0, 1.0 - sin_t2))
    with np.errstate(invalid="ignore", divide="ignore"):
        rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t)
        rp = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i)
        r = 0.5 * (rs * rs + rp * rp)
    return np.where(tir, 1.0, r)


# ------------------------------------------------------------------------------ solver

class Layer(NamedTuple):
    """A homogeneous layer: thickness [m] (math.inf for the last one only), a, b [1/m]."""
    thickness: float
    a: float
    b: float
    phase: Phase


class _LayerSolution:
    """Scaled optics, eigen-solution and particular solution of one layer."""

    def __init__(self, layer, mu, w, table, delta_m):
        n = mu.size
        nl = table.shape[0]            # Legendre terms kept: l = 0 .. nl - 1
        self.layer = layer
        self._table = table            # P_l(mu_i), l < nl, over the N positive nodes
        chi = np.asarray(layer.phase.moments(nl), dtype=float)
        if abs(chi[0] - 1.0) > 1e-9:
            raise ValueError(f"phase function {layer.phase!r} is not normalised (chi_0 = {chi[0]})")
        f = min(max(chi[nl], 0.0), 1.0 - 1e-12) if delta_m else 0.0
        self.f = f
        self.chi = (chi[:nl] - f) / (1.0 - f)
        self.b_s = layer.b * (1.0 - f)
        self.c_s = layer.a + self.b_s
        if not self.c_s > 0:
            raise ValueError("a layer needs a + b > 0")
        self.omega = min(self.b_s / self.c_s, 1.0 - OMEGA_GAP)
        self.dtau = layer.thickness * self.c_s  # inf for a semi-infinite layer
        self.coef = (2 * np.arange(nl) + 1) / 2.0 * self.chi
        self.sign = (-1.0) ** np.arange(nl)
        # Kernel between the 2N signed directions [mu_1..mu_N, -mu_1..-mu_N].
        kpp = table.T @ (self.coef[:, None] * table)                  # K(mu_i, mu_j)
        kpm = table.T @ ((self.coef * self.sign)[:, None] * table)    # K(mu_i, -mu_j)
        self.kpp, self.kpm = kpp, kpm
        om = self.omega
        sw = np.sqrt(w)
        smu = np.sqrt(mu)
        eye = np.eye(n)
        # alpha = M^-1 (om K+ W - I), beta = M^-1 om K- W; (alpha - beta)(alpha + beta) S = k^2 S.
        b1 = om * sw[:, None] * (kpp - kpm) * sw[None, :] - eye   # negative definite
        b2 = om * sw[:, None] * (kpp + kpm) * sw[None, :] - eye   # negative semidefinite
        s1 = -b1 / smu[:, None] / smu[None, :]
        s2 = -b2 / smu[:, None] / smu[None, :]
        chol = np.linalg.cholesky(0.5 * (s1 + s1.T))
        y = chol.T @ s2 @ chol
        lam, vec = np.linalg.eigh(0.5 * (y + y.T))
        lam = np.maximum(lam, 0.0)
        k = np.sqrt(lam)
        svec = (chol @ vec) / (sw * smu)[:, None]                    # eigenvectors S of P
        alpha_minus_beta = (om * (kpp - kpm) * w[None, :] - eye) / mu[:, None]
        dvec = -np.linalg.solve(alpha_minus_beta, svec) * k[None, :]
        gp, gm = 0.5 * (svec + dvec), 0.5 * (svec - dvec)            # G+ (down), G- (up)
        scale = np.max(np.abs(np.vstack([gp, gm])), axis=0)
        gp, gm = gp / scale, gm / scale
        self.k = k
        self.g_decay = np.vstack([gp, gm])    # solution ~ exp(-k tau)
        self.g_grow = np.vstack([gm, gp])     # solution ~ exp(+k tau)

    def particular(self, mu, w, mu0, f0, table_mu0):
        """Z with u_p = Z exp(-tau / mu0), tau the cumulative (scaled) optical depth."""
        if self.layer.b == 0:
            return np.zeros(2 * mu.size)
        kbeam_down = (self.coef * table_mu0) @ self._table             # K(mu_i, mu0)
        kbeam_up = (self.coef * self.sign * table_mu0) @ self._table   # K(-mu_i, mu0)
        ksig = np.block([[self.kpp, self.kpm], [self.kpm, self.kpp]])
        musig = np.concatenate([mu, -mu])
        wsig = np.concatenate([w, w])
        lhs = np.diag(1.0 - musig / mu0) - self.omega * ksig * wsig[None, :]
        rhs = self.omega * f0 * np.concatenate([kbeam_down, kbeam_up])
        return np.linalg.solve(lhs, rhs)


def _solve_dense_or_sparse(matrix, rhs):
    if matrix.shape[0] > 4000:
        try:
            import scipy.sparse
            import scipy.sparse.linalg
            return scipy.sparse.linalg.spsolve(scipy.sparse.csc_matrix(matrix), rhs)
        except ImportError:
            pass
    return np.linalg.solve(matrix, rhs)


def solve_layers(layers, depths, *, mu0=1.0, sun_zenith_deg=None, n_water=1.34, fresnel=False,
                 internal_reflection=None, bottom_albedo=0.0, streams=32, delta_m=True,
                 quadrature=None):
    """Irradiance profile of a stack of homogeneous layers (top first).

    layers: sequence of ``Layer(thickness, a, b, phase)`` (or tuples in that order); only
    the last may have ``thickness = math.inf`` (semi-infinite).  Other arguments and the
    returned dict as for :func:`solve_profile`, plus ``absorbed_layers``.
    """
    layers = [Layer(*lay) for lay in layers]
    if not layers:
        raise ValueError("no layers")
    for i, lay in enumerate(layers):
        if not lay.thickness > 0:
            raise ValueError(f"layer {i}: thickness must be > 0")
        if math.isinf(lay.thickness) and i != len(layers) - 1:
            raise ValueError("only the last layer may be semi-infinite")
        if lay.a < 0 or lay.b < 0:
            raise ValueError(f"layer {i}: a and b must be >= 0")
        if not isinstance(lay.phase, Phase):
            raise TypeError(f"layer {i}: phase must come from hg(), isotropic(), ... ")
    n = int(streams)
    if n < 2:
        raise ValueError("streams (points per hemisphere) must be >= 2")
    if internal_reflection is None:
        internal_reflection = bool(fresnel)
    if not 0.0 <= bottom_albedo <= 1.0:
        raise ValueError("bottom_albedo must lie in [0, 1]")
    if bottom_albedo > 0 and math.isinf(layers[-1].thickness):
        raise ValueError("a semi-infinite column has no bottom: bottom_albedo must be 0")

    # Incident beam just below the surface.
    if fresnel:
        if mu0 != 1.0:
            raise ValueError("with fresnel=True the beam's direction comes from sun_zenith_deg, not mu0")
        if sun_zenith_deg is None:
            raise ValueError("fresnel=True needs sun_zenith_deg (the sun's zenith angle in air)")
        if not 0.0 <= sun_zenith_deg < 90.0:
            raise ValueError("sun_zenith_deg must lie in [0, 90)")
        cos_s = math.cos(math.radians(sun_zenith_deg))
        mu_beam = float(snell_cosine(cos_s, 1.0, n_water))
        surface_r = float(fresnel_reflectance(cos_s, 1.0, n_water))
        incident = 1.0 - surface_r
    else:
        if sun_zenith_deg is not None:
            raise ValueError("sun_zenith_deg is used only with fresnel=True; give mu0 (in water)")
        if not 0.0 < mu0 <= 1.0:
            raise ValueError("mu0 must lie in (0, 1]")
        mu_beam = float(mu0)
        surface_r = 0.0
        incident = 1.0

    if quadrature is None:
        quadrature = "split" if internal_reflection else "double_gauss"
    mu, w, lmax = hemisphere_quadrature(n, quadrature, n_water)
    table = legendre_table(lmax, mu)
    sols = []
    for lay in layers:
        sols.append(_LayerSolution(lay, mu, w, table, delta_m))

    # Keep 1/mu0 away from the homogeneous eigenvalues (the particular solution's resonance).
    mu0_s = mu_beam
    for _ in range(10):
        gaps = [np.min(np.abs(s.k * mu0_s - 1.0)) for s in sols if s.layer.b > 0]
        if min(gaps, default=1.0) >= RESONANCE_GAP:
            break
        mu0_s = mu0_s * (1.0 - 2.0 * RESONANCE_GAP) if mu0_s >= 0.5 else mu0_s * (1.0 + 2.0 * RESONANCE_GAP)
    f0 = incident / mu0_s                    # beam flux normal to itself
    table0 = legendre_table(lmax, [mu0_s])[:, 0]
    zs = [s.particular(mu, w, mu0_s, f0, table0) for s in sols]

    nl = len(layers)
    semi = math.isinf(layers[-1].thickness)
    tau_top = np.concatenate([[0.0], np.cumsum([s.dtau for s in sols])])[:nl]
    z_top = np.concatenate([[0.0], np.cumsum([lay.thickness for lay in layers])])[:nl]
    bottom_z = z_top[-1] + layers[-1].thickness
    bottom_tau = tau_top[-1] + sols[-1].dtau

    # Unknowns: for each layer C+ (N) then C- (N); a semi-infinite last layer has only C+.
    offs = [2 * n * i for i in range(nl)]
    size = 2 * n * nl - (n if semi else 0)
    mat = np.zeros((size, size))
    rhs = np.zeros(size)
    r_top = fresnel_reflectance(mu, n_water, 1.0) if internal_reflection else np.zeros(n)

    def edge(i):
        """Decay factors exp(-k dtau) of layer i (0 for a semi-infinite layer)."""
        s = sols[i]
        return np.exp(-s.k * s.dtau) if np.isfinite(s.dtau) else np.zeros(n)

    # Top: u+(0) - R u-(0) = 0.
    s0 = sols[0]
    top_op = np.hstack([np.eye(n), -np.diag(r_top)])
    mat[:n, 0:n] = top_op @ s0.g_decay
    if not (semi and nl == 1):
        mat[:n, n:2 * n] = (top_op @ s0.g_grow) * edge(0)[None, :]
    rhs[:n] = -top_op @ zs[0]
    # Interfaces: u_i(bottom of i) = u_{i+1}(top of i+1).
    for i in range(nl - 1):
        r = n + 2 * n * i
        e_i, e_next = edge(i), edge(i + 1)
        mat[r:r + 2 * n, offs[i]:offs[i] + n] = sols[i].g_decay * e_i[None, :]
        mat[r:r + 2 * n, offs[i] + n:offs[i] + 2 * n] = sols[i].g_grow
        mat[r:r + 2 * n, offs[i + 1]:offs[i + 1] + n] = -sols[i + 1].g_decay
        if not (semi and i + 1 == nl - 1):
            mat[r:r + 2 * n, offs[i + 1] + n:offs[i + 1] + 2 * n] = -sols[i + 1].g_grow * e_next[None, :]
        rhs[r:r + 2 * n] = (zs[i + 1] - zs[i]) * math.exp(-tau_top[i + 1] / mu0_s)
    # Bottom: u-(H) - 2 R_b (sum_j w_j mu_j u+_j(H) + direct) = 0.
    if not semi:
        r = size - n
        sl = sols[-1]
        bot_op = np.hstack([-2.0 * bottom_albedo * np.tile(w * mu, (n, 1)), np.eye(n)])
        e_l = edge(nl - 1)
        mat[r:, offs[-1]:offs[-1] + n] = (bot_op @ sl.g_decay) * e_l[None, :]
        mat[r:, offs[-1] + n:offs[-1] + 2 * n] = bot_op @ sl.g_grow
        beam_h = math.exp(-bottom_tau / mu0_s)
        rhs[r:] = (2.0 * bottom_albedo * mu0_s * f0 - bot_op @ zs[-1]) * beam_h
    coeffs = _solve_dense_or_sparse(mat, rhs)

    def layer_coeffs(i):
        cp = coeffs[offs[i]:offs[i] + n]
        cm = coeffs[offs[i] + n:offs[i] + 2 * n] if not (semi and i == nl - 1) else np.zeros(n)
        return cp, cm

    def field(i, t):
        """u (2N x len(t)) and du/dtau at local scaled optical depth t in layer i, plus
        the direct beam's u-equivalent factor exp(-tau/mu0)."""
        s = sols[i]
        cp, cm = layer_coeffs(i)
        t = np.asarray(t, dtype=float)
        ed = np.exp(-np.outer(s.k, t))                                   # (N, m)
        if np.isfinite(s.dtau):
            eg = np.exp(-np.outer(s.k, s.dtau - t))
        else:
            eg = np.zeros_like(ed)
        beam = np.exp(-(tau_top[i] + t) / mu0_s)
        u = s.g_decay @ (cp[:, None] * ed) + s.g_grow @ (cm[:, None] * eg) + np.outer(zs[i], beam)
        du = (s.g_decay @ (-(s.k * cp)[:, None] * ed) + s.g_grow @ ((s.k * cm)[:, None] * eg)
              - np.outer(zs[i], beam) / mu0_s)
        return u, du, beam

    depths = np.atleast_1d(np.asarray(depths, dtype=float))
    if np.any(depths < 0) or np.any(depths > bottom_z * (1 + 1e-12)):
        raise ValueError(f"depths must lie in [0, {bottom_z}]")
    which = np.clip(np.searchsorted(z_top, depths, side="right") - 1, 0, nl - 1)
    ed = np.empty(depths.size)
    eu = np.empty(depths.size)
    e0 = np.empty(depths.size)
    ded, deu, de0 = np.empty(depths.size), np.empty(depths.size), np.empty(depths.size)
    wmu = w * mu
    for i in range(nl):
        sel = which == i
        if not np.any(sel):
            continue
        t = np.minimum((depths[sel] - z_top[i]) * sols[i].c_s, sols[i].dtau)
        u, du, beam = field(i, t)
        c = sols[i].c_s
        ed[sel] = wmu @ u[:n] + mu0_s * f0 * beam
        eu[sel] = wmu @ u[n:]
        e0[sel] = w @ (u[:n] + u[n:]) + f0 * beam
        ded[sel] = c * (wmu @ du[:n] - f0 * beam)
        deu[sel] = c * (wmu @ du[n:])
        de0[sel] = c * (w @ (du[:n] + du[n:]) - f0 * beam / mu0_s)

    # Absorption: a_i int E0 dz = (a_i / c_i) int E0 dtau, in closed form per layer.
    absorbed_layers = np.zeros(nl)
    for i, s in enumerate(sols):
        if s.layer.a == 0:
            continue
        cp, cm = layer_coeffs(i)
        if np.isfinite(s.dtau):
            kd = s.k * s.dtau
            with np.errstate(divide="ignore", invalid="ignore"):
                integ = np.where(s.k > 0, -np.expm1(-kd) / s.k, s.dtau)
            beam_int = mu0_s * (math.exp(-tau_top[i] / mu0_s) - math.exp(-(tau_top[i] + s.dtau) / mu0_s))
            int_u = s.g_decay @ (cp * integ) + s.g_grow @ (cm * integ) + zs[i] * beam_int
        else:
            int_u = s.g_decay @ (cp / s.k)
            beam_int = mu0_s * math.exp(-tau_top[i] / mu0_s)
            int_u = int_u + zs[i] * beam_int
        int_e0 = w @ (int_u[:n] + int_u[n:]) + f0 * beam_int
        absorbed_layers[i] = s.layer.a / s.c_s * int_e0

    u_top, _, _ = field(0, np.array([0.0]))
    escaped = float(np.sum(wmu * (1.0 - r_top) * u_top[n:, 0]))
    if semi:
        bottom = 0.0
    else:
        u_bot, _, beam_b = field(nl - 1, np.array([sols[-1].dtau]))
        ed_b = wmu @ u_bot[:n, 0] + mu0_s * f0 * beam_b[0]
        eu_b = wmu @ u_bot[n:, 0]
        bottom = float(ed_b - eu_b)

    # The exact unscattered beam (unscaled attenuation), for reference.
    tau_true_top = np.concatenate([[0.0], np.cumsum([lay.thickness * (lay.a + lay.b) for lay in layers])])[:nl]
    ed_direct = incident * np.exp(-(tau_true_top[which] + (depths - z_top[which])
                                    * np.array([lay.a + lay.b for lay in layers])[which]) / mu_beam)

    with np.errstate(divide="ignore", invalid="ignore"):
        kd_loc = -ded / ed
        ku_loc = -deu / eu
        k0_loc = -de0 / e0
    return dict(depth=depths, Ed=ed, Eu=eu, E0=e0, Kd=kd_loc, Ku=ku_loc, K0=k0_loc,
                Ed_direct=ed_direct, Ed_diffuse=ed - ed_direct,
                absorbed=float(absorbed_layers.sum()), absorbed_layers=absorbed_layers,
                escaped=escaped, bottom=bottom, incident=incident, surface_reflectance=surface_r,
                mu0=mu_beam, streams=n, delta_m_f=[s.f for s in sols])


def solve_profile(a, b, phase, depths, *, mu0=1.0, sun_zenith_deg=None, n_water=1.34, fresnel=False,
                  bottom_depth=math.inf, bottom_albedo=0.0, streams=32, delta_m=True,
                  internal_reflection=None, quadrature=None):
    """Irradiance profile of a homogeneous water column.

    a, b: absorption and scattering coefficients [1/m]; phase: a :class:`Phase`;
    depths: depths [m] below the surface (0 = just below).  mu0: in-water direction
    cosine of the beam when ``fresnel=False`` (direct E_d(0+) = 1, vacuum top); with
    ``fresnel=True`` the sun's zenith angle in air ``sun_zenith_deg`` is refracted and
    the beam's E_d(0+) is the Fresnel transmittance T (unit irradiance above the
    surface), and upwelling light is Fresnel-reflected back down.  bottom_depth: depth
    of a Lambertian bottom of albedo bottom_albedo (math.inf: semi-infinite, albedo
    must be 0).  streams: quadrature points per hemisphere (N).  delta_m: delta-M
    scaling of the phase function.  internal_reflection: Fresnel reflection of
    upwelling light at the surface (default = fresnel).  quadrature: "double_gauss"
    or "split" (at the critical angle); default split when internal_reflection is on.

    Returns a dict of arrays over ``depth``: ``Ed`` (incl. direct), ``Eu``, ``E0`` (incl.
    direct), the local diffuse attenuations ``Kd = -dln Ed/dz``, ``Ku``, ``K0`` [1/m],
    ``Ed_direct`` (the exact unscattered beam, exp(-c z / mu0) times its E_d(0+)) and
    ``Ed_diffuse = Ed - Ed_direct``; and the fluxes ``incident``, ``absorbed``,
    ``escaped``, ``bottom`` (incident = absorbed + escaped + bottom), plus ``mu0`` (in
    water) and ``surface_reflectance`` (Fresnel R of the sun's beam, 0 without fresnel).
    """
    return solve_layers([Layer(bottom_depth, a, b, phase)], depths, mu0=mu0,
                        sun_zenith_deg=sun_zenith_deg, n_water=n_water, fresnel=fresnel,
                        internal_reflection=internal_reflection, bottom_albedo=bottom_albedo,
                        streams=streams, delta_m=delta_m, quadrature=quadrature)


def kd_between(depth, ed):
    """Mean diffuse attenuation between successive depths: -Delta ln E_d / Delta z."""
    depth = np.asarray(depth, dtype=float)
    ed = np.asarray(ed, dtype=float)
    return -np.diff(np.log(ed)) / np.diff(depth)


# ----------------------------------------------------------------------------- example

def _print_profile(out, dt):
    print(f"{'z [m]':>7} {'Ed':>12} {'Eu':>12} {'E0':>12} {'Kd [1/m]':>10} {'Eu/Ed':>9}")
    for i, z in enumerate(out["depth"]):
        print(f"{z:7.2f} {out['Ed'][i]:12.6e} {out['Eu'][i]:12.6e} {out['E0'][i]:12.6e}"
              f" {out['Kd'][i]:10.6f} {out['Eu'][i] / out['Ed'][i]:9.5f}")
    print(f"incident {out['incident']:.6f} = absorbed {out['absorbed']:.6f} + escaped "
          f"{out['escaped']:.6f} + bottom {out['bottom']:.6f}"
          f" (residual {out['incident'] - out['absorbed'] - out['escaped'] - out['bottom']:.1e});"
          f" {dt * 1e3:.1f} ms")


def _example():
    import time
    water = mixture([(0.2, rayleigh_like(0.835)), (0.8, hg(0.92))])
    print("Water: a = 0.05 /m, b = 0.25 /m, phase 0.2 rayleigh_like(0.835) + 0.8 HG(0.92); N = 32.\n")
    depths = np.array([0.0, 1.0, 2.0, 5.0, 10.0, 20.0, 39.0, 40.0])
    t0 = time.perf_counter()
    out = solve_profile(0.05, 0.25, water, depths, mu0=1.0, bottom_depth=40.0)
    dt = time.perf_counter() - t0
    print("Beam started just below the surface, straight down (mu0 = 1), no interface, black")
    print("bottom at 40 m:")
    _print_profile(out, dt)
    depths = np.array([0.0, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0])
    t0 = time.perf_counter()
    out = solve_profile(0.05, 0.25, water, depths, fresnel=True, sun_zenith_deg=30.0)
    dt = time.perf_counter() - t0
    print(f"\nSun at 30 deg over a flat Fresnel surface (n = 1.34): mu0 in water = {out['mu0']:.5f},"
          f" T = {out['incident']:.5f};\nsemi-infinite:")
    _print_profile(out, dt)


if __name__ == "__main__":
    _example()
