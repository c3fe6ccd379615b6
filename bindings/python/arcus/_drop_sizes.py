"""Drop sizes for arcus.sky: Gauss–Legendre bins over a size range, and the size
distributions of cloud and fog droplets."""

import math

import numpy as np

from ._errors import ArgumentError


def gauss_bins(lo, hi, count):
    x, w = np.polynomial.legendre.leggauss(count)
    return (lo + hi) / 2 + (hi - lo) / 2 * x, (hi - lo) / 2 * w


def cloud_droplets(p, dist, where):
    """A cloud's or fog's droplets: (ln n(r) up to a constant, the default radius
    range).  Either Hansen & Travis' (1974) forms by the effective radius a = <r³>/<r²>
    and effective variance b: "gamma", n(r) ∝ r^((1−3b)/b) exp(−r/(ab)) (b < 1/3), or
    "lognormal", n(r) ∝ exp(−(ln r − ln r_g)²/(2σ²))/r with σ² = ln(1 + b) and
    r_g = a/(1 + b)^(5/2); their range holds all but 10⁻⁴ of the drops' cross-section at
    either end (where the light comes from).  Or, as arcus 0.9 took it, a gamma by its
    mode: n(r) ∝ r^μ exp(−μ r / mode_radius), over [mode/4, 3·mode]."""
    from scipy import stats

    from .sky import _number  # the scene reader's checks (sky imports this module)
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
