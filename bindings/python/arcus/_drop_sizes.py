"""Drop sizes for arcus.sky: Gauss–Legendre bins over a size range, the size
distributions of cloud and fog droplets, and their stratified nodes for Lorenz–Mie."""

import math

import numpy as np

from ._errors import ArgumentError


def gauss_bins(lo, hi, count):
    x, w = np.polynomial.legendre.leggauss(count)
    return (lo + hi) / 2 + (hi - lo) / 2 * x, (hi - lo) / 2 * w


#: The golden ratio's fractional part: successive wavelengths' strata offsets
#: frac(1/2 + j φ) fill (0, 1) as evenly as any sequence can (Weyl, Kronecker).
GOLDEN = (math.sqrt(5) - 1) / 2
#: Points of the cross-section's cumulative distribution, inverted by interpolation.
CDF_POINTS = 8193


def stratified_nodes(log_density, lo, hi, count, wavelengths):
    """Sizes for Lorenz–Mie that change with the wavelength: (radii, weights), each
    (wavelengths, count).  Row j takes one radius in each of ``count`` strata of equal
    cross-section (r² n(r): where the light is), at the offset frac(1/2 + j φ) within
    its stratum.  Any fixed set of sizes leaves the ripple of each one size (Mie's
    resonances, finer than any bins here) in every wavelength's table alike; moved from
    one wavelength to the next, the sizes' ripples fall at other angles and average out
    in the colour, for the same number of Mie calls (docs/benchmarks.md, "Fog bows").
    Weights: number fractions ⟨r²⟩/(count r²), so that every row holds the
    distribution's cross-section exactly and its number on average."""
    r = np.linspace(lo, hi, CDF_POINTS)
    log_n = log_density(r)
    n = np.exp(log_n - log_n.max())
    def integral(f):  # trapezoid along the grid, cumulative
        return np.concatenate([[0.0], np.cumsum((f[1:] + f[:-1]) / 2 * np.diff(r))])
    cdf = integral(r**2 * n)
    mean_r2 = cdf[-1] / integral(n)[-1]
    offsets = (0.5 + GOLDEN * np.arange(wavelengths)) % 1.0
    radii = np.interp((np.arange(count)[None, :] + offsets[:, None]) / count, cdf / cdf[-1], r)
    return radii, mean_r2 / (count * radii**2)


def cloud_droplets(p, dist, where):
    """A cloud's or fog's droplets: (ln n(r) up to a constant, the default radius
    range).  Either Hansen & Travis' (1974) forms by the effective radius a = <r³>/<r²>
    and effective variance b: "gamma", n(r) ∝ r^((1−3b)/b) exp(−r/(ab)) (b < 1/3), or
    "lognormal", n(r) ∝ exp(−(ln r − ln r_g)²/(2σ²))/r with σ² = ln(1 + b) and
    r_g = a/(1 + b)^(5/2); their range holds all but 10⁻⁴ of the drops' cross-section at
    either end (where the light comes from).  Or, as arcus 0.9 took it, a gamma by its
    mode: n(r) ∝ r^μ exp(−μ r / mode_radius), over [mode/4, 3·mode]."""
    from scipy import stats

    from .rain import _number  # the scene reader's checks (rain imports this module)
    if dist == "gamma" and "mode_radius" in p:
        if "effective_radius" in p or "effective_variance" in p:
            raise ArgumentError("%s: give a gamma distribution either mode_radius and mu or effective_radius and "
                                "effective_variance, not both" % where)
        mode = _number(p, "mode_radius", where=where, positive=True)
        mu = _number(p, "mu", 6.0, 0, 100, where)
        return (lambda r: mu * np.log(r) - mu * r / mode), (mode / 4, mode * 3)
    if "mu" in p:
        raise ArgumentError("%s: 'mu' goes with 'mode_radius' (a gamma by its mode)" % where)
    a = _number(p, "effective_radius", where=where, positive=True)
    if dist == "gamma":
        b = _number(p, "effective_variance", 0.1, where=where)
        if not 0 < b < 1 / 3:
            raise ArgumentError("%s: a gamma's effective_variance must lie in (0, 1/3), got %r" % (where, b))
        alpha = (1 - 3 * b) / b
        log_density = lambda r: alpha * np.log(r) - r / (a * b)  # noqa: E731
        cross_sections = stats.gamma(alpha + 3, scale=a * b)  # r² n(r)
    else:
        b = _number(p, "effective_variance", 0.1, where=where)
        if not b > 0:
            raise ArgumentError("%s: a lognormal's effective_variance must be positive, got %r" % (where, b))
        sigma2 = math.log1p(b)
        r_g = a / (1 + b) ** 2.5
        log_density = lambda r: -np.log(r / r_g) ** 2 / (2 * sigma2) - np.log(r)  # noqa: E731
        cross_sections = stats.lognorm(math.sqrt(sigma2), scale=r_g * math.exp(2 * sigma2))
    return log_density, (float(cross_sections.ppf(1e-4)), float(cross_sections.isf(1e-4)))
