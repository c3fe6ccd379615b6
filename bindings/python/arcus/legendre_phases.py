"""Phase functions as the discrete-ordinates solver (:mod:`arcus.discrete_ordinates`)
takes them: normalised over the sphere, evaluated and expanded in Legendre moments
χ_l = 2π ∫ p(μ) P_l(μ) dμ (exactly, for the tabulated one's linear pieces).  Pure numpy."""

import math

import numpy as np

__all__ = ["Phase", "hg", "two_term_hg", "rayleigh_like", "isotropic", "tabulated", "mixture", "legendre_table"]


def legendre_table(lmax, x):
    """P_l(x) for l = 0..lmax: array (lmax + 1, len(x)), by the Bonnet recurrence."""
    x = np.atleast_1d(np.asarray(x, dtype=float))
    table = np.empty((lmax + 1,) + x.shape)
    table[0] = 1.0
    if lmax >= 1:
        table[1] = x
    for l in range(1, lmax):
        table[l + 1] = ((2 * l + 1) * x * table[l] - l * table[l - 1]) / (l + 1)
    return table


# ----------------------------------------------------------------------- phase functions

class Phase:
    """A phase function normalised over the sphere: ``2 pi int p(mu) dmu = 1``.

    ``phase(mu)`` evaluates p; ``phase.moments(L)`` gives chi_0..chi_L with
    ``chi_l = 2 pi int p P_l dmu``; ``phase.g`` is the asymmetry parameter chi_1.
    """

    def __call__(self, mu):
        raise NotImplementedError

    def moments(self, lmax):
        raise NotImplementedError

    @property
    def g(self):
        return float(self.moments(1)[1])

    def azimuthal_kernel(self, mu, mu_prime, lmax):
        """K(mu, mu') = 2 pi <p>_phi = sum_{l <= lmax} (2l+1)/2 chi_l P_l(mu) P_l(mu')."""
        coef = (2 * np.arange(lmax + 1) + 1) / 2.0 * self.moments(lmax)
        return legendre_table(lmax, mu).T @ (coef[:, None] * legendre_table(lmax, mu_prime))


class _Isotropic(Phase):
    def __call__(self, mu):
        return np.full(np.shape(mu), 1.0 / (4.0 * math.pi))

    def moments(self, lmax):
        chi = np.zeros(lmax + 1)
        chi[0] = 1.0
        return chi

    def __repr__(self):
        return "isotropic()"


class _HG(Phase):
    def __init__(self, g):
        if not -1.0 < g < 1.0:
            raise ValueError(f"Henyey-Greenstein g must lie in (-1, 1), got {g}")
        self._g = float(g)

    def __call__(self, mu):
        g = self._g
        mu = np.asarray(mu, dtype=float)
        return (1.0 - g * g) / (4.0 * math.pi * (1.0 + g * g - 2.0 * g * mu) ** 1.5)

    def moments(self, lmax):
        return self._g ** np.arange(lmax + 1, dtype=float)

    def __repr__(self):
        return f"hg({self._g})"


class _RayleighLike(Phase):
    """p = (1 + A mu^2) / (4 pi (1 + A/3)); chi_2 = 2A / (15 + 5A)."""

    def __init__(self, A):
        if A <= -1.0:
            raise ValueError(f"rayleigh_like needs A > -1 (p >= 0), got {A}")
        self.A = float(A)

    def __call__(self, mu):
        mu = np.asarray(mu, dtype=float)
        return (1.0 + self.A * mu * mu) / (4.0 * math.pi * (1.0 + self.A / 3.0))

    def moments(self, lmax):
        chi = np.zeros(lmax + 1)
        chi[0] = 1.0
        if lmax >= 2:
            chi[2] = 2.0 * self.A / (15.0 + 5.0 * self.A)
        return chi

    def __repr__(self):
        return f"rayleigh_like({self.A})"


class _Tabulated(Phase):
    """Linear interpolation in mu of tabulated values, normalised; constant beyond the
    table's ends.  The moments are exact integrals of the interpolant."""

    def __init__(self, mu, values):
        mu = np.asarray(mu, dtype=float).ravel()
        values = np.asarray(values, dtype=float).ravel()
        if mu.shape != values.shape or mu.size < 2:
            raise ValueError("tabulated: mu and values must be 1-D, of equal length >= 2")
        if np.any(values < 0) or not np.all(np.isfinite(values)):
            raise ValueError("tabulated: values must be finite and >= 0")
        order = np.argsort(mu)
        mu, values = mu[order], values[order]
        if np.any(np.diff(mu) <= 0):
            raise ValueError("tabulated: the cosines must be distinct")
        if mu[0] < -1.0 - 1e-12 or mu[-1] > 1.0 + 1e-12:
            raise ValueError("tabulated: cosines must lie in [-1, 1]")
        inner = (mu > -1.0) & (mu < 1.0)
        grid = np.concatenate([[-1.0], mu[inner], [1.0]])
        vals = np.interp(grid, mu, values)
        total = 2.0 * math.pi * np.sum(0.5 * (vals[1:] + vals[:-1]) * np.diff(grid))
        if total <= 0:
            raise ValueError("tabulated: the phase function integrates to 0")
        self._grid = grid
        self._vals = vals / total
        self._cache = {}

    def __call__(self, mu):
        return np.interp(np.asarray(mu, dtype=float), self._grid, self._vals)

    def moments(self, lmax):
        if lmax not in self._cache:
            self._cache[lmax] = self._exact_moments(lmax)
        return self._cache[lmax].copy()

    def _exact_moments(self, lmax):
        # On a segment [x0, x1], p = f0 + s (x - x0).  With A_l = int P_l dx and
        # B_l = int x P_l dx over the segment, int p P_l = f0 A_l + s (B_l - x0 A_l).
        # int P_l = (P_{l+1} - P_{l-1}) / (2l+1) (l >= 1), and
        # x P_l = ((l+1) P_{l+1} + l P_{l-1}) / (2l+1) gives B_l from A_{l+1}, A_{l-1}.
        x0, x1 = self._grid[:-1], self._grid[1:]
        f0, f1 = self._vals[:-1], self._vals[1:]
        s = (f1 - f0) / (x1 - x0)
        L = lmax + 2
        P0, P1 = legendre_table(L + 1, x0), legendre_table(L + 1, x1)
        A = np.empty((L + 1, x0.size))
        A[0] = x1 - x0
        for l in range(1, L + 1):
            A[l] = ((P1[l + 1] - P0[l + 1]) - (P1[l - 1] - P0[l - 1])) / (2 * l + 1)
        B = np.empty((lmax + 1, x0.size))
        B[0] = 0.5 * (x1 * x1 - x0 * x0)
        for l in range(1, lmax + 1):
            B[l] = ((l + 1) * A[l + 1] + l * A[l - 1]) / (2 * l + 1)
        chi = 2.0 * math.pi * (A[:lmax + 1] @ f0 + (B - x0 * A[:lmax + 1]) @ s)
        return chi / chi[0]

    def __repr__(self):
        return f"tabulated(<{self._grid.size} points>)"


class _Mixture(Phase):
    def __init__(self, parts):
        parts = [(float(w), p) for w, p in parts]
        if not parts:
            raise ValueError("mixture: no components")
        weights = np.array([w for w, _ in parts])
        if np.any(weights < 0) or weights.sum() <= 0:
            raise ValueError("mixture: weights must be >= 0 with a positive sum")
        if abs(weights.sum() - 1.0) > 1e-9:
            raise ValueError(f"mixture: weights must sum to 1, got {weights.sum()!r}")
        self.parts = [(w, p) for w, (_, p) in zip(weights, parts)]

    def __call__(self, mu):
        return sum(w * p(mu) for w, p in self.parts)

    def moments(self, lmax):
        return sum(w * p.moments(lmax) for w, p in self.parts)

    def __repr__(self):
        return "mixture([" + ", ".join(f"({w}, {p!r})" for w, p in self.parts) + "])"


def isotropic():
    """p = 1 / (4 pi)."""
    return _Isotropic()


def hg(g):
    """Henyey-Greenstein: p = (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^{3/2}); chi_l = g^l."""
    return _HG(g)


def two_term_hg(zeta, g_f, g_b):
    """zeta HG(g_f) + (1 - zeta) HG(g_b)."""
    return _Mixture([(zeta, _HG(g_f)), (1.0 - zeta, _HG(g_b))])


def rayleigh_like(A):
    """p proportional to 1 + A mu^2, normalised (pure water: A = 0.835)."""
    return _RayleighLike(A)


def tabulated(mu, values):
    """p(mu_k) = values_k (any scale), linearly interpolated in mu and normalised."""
    return _Tabulated(mu, values)


def mixture(parts):
    """sum_j w_j p_j for parts = [(w_j, p_j), ...] with sum w_j = 1 (e.g. w_j = b_j / b)."""
    return _Mixture(parts)
