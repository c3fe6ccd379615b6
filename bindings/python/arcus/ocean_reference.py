"""The discrete-ordinates reference for an ocean scene's irradiance profiles.

The engine's own water (its coefficients from :meth:`arcus.ocean.Water.coefficients`,
its scatterers' phase functions) under the sun and a uniform sky, solved wavelength by
wavelength by :mod:`arcus.discrete_ordinates`, an independent plane-parallel method
(thesis §4.2 is the Monte Carlo side).  Elastic scattering only: Raman scattering and
fluorescence take light out of its wavelength as absorption does, and the light they
re-emit is left out, so where a Monte Carlo profile rises above this one is the
inelastic light (thesis §3.5, §5.3).

The uniform sky is a sum of suns: a sky of plane irradiance E on the surface sends
E · 2μ dμ from the zenith cosines in dμ (cosine-weighted, as the engine emits it), so
the sky's profile is ∫ 2μ E_sun(μ) dμ over (0, 1), taken by Gauss–Legendre in μ (the
Fresnel transmittance is smooth in μ, and vanishes linearly at the horizon)."""

import math

import numpy as np

from . import discrete_ordinates as do
from .ocean import _PHASES, EVENTS

#: Gauss nodes over the sky's zenith cosines: 12 and 24 agree within 1.3e-4 relative
#: for the presets' profiles to 30 m under the sun at 30° and a sky (north_sea: 9e-7).
SKY_NODES = 12
#: Gauss nodes across a tally layer for the layer-averaged E0.
LAYER_NODES = 8
#: The pure-water scatterer's phase function, 1 + 0.835 cos²θ (thesis eq. 3.26; the
#: engine's src/ocean/water.cpp uses the same).
WATER_PHASE = do.rayleigh_like(0.835)
_ELASTIC = ("scatter_water", "scatter_detritus", "scatter_phyto")


def _phase_of_tuple(phase):
    """A discrete-ordinates phase function from arcus.ocean's tuple form."""
    if phase is None or phase == "isotropic" or phase == ("isotropic",):
        return do.isotropic()
    kind, args = phase[0], phase[1:]
    if kind == "hg":
        return do.hg(*args)
    if kind == "two_term_hg":
        g_f, g_b, zeta = args
        return do.two_term_hg(zeta, g_f, g_b)
    if kind == "rayleigh_like":
        return do.rayleigh_like(*args)
    if kind == "table":
        return do.tabulated(*args)
    raise ValueError("unknown phase function %r" % (kind,))


def _phase_of_struct(p):
    """A discrete-ordinates phase function from an arcus_phase_function struct."""
    kind = {v: k for k, v in _PHASES.items()}[p.kind]
    if kind == "table":
        n = p.table_count
        return do.tabulated([p.table_cosines[i] for i in range(n)], [p.table_values[i] for i in range(n)])
    args = dict(hg=(p.g_forward,), two_term_hg=(p.g_forward, p.g_backward, p.forward_weight),
                rayleigh_like=(p.a,)).get(kind, ())
    return _phase_of_tuple((kind,) + args)


def scatterer_phases(water):
    """The phase functions of the water's three scatterers, in :data:`arcus.ocean.EVENTS`'
    scatter order (water, detritus, phytoplankton; the last isotropic, thesis §3.5.3)."""
    if water._iops is not None:  # one scatterer, the given phase function
        return [_phase_of_tuple(water._iops["phase"]), do.isotropic(), do.isotropic()]
    return [WATER_PHASE, _phase_of_struct(water._detritus_phase), do.isotropic()]


def _on_grid(spectrum, wl):
    """A light's spectrum (arcus.ocean's forms: a number, (nm, values), {"nm", "values"})
    at the wavelengths, as the engine reads it: linear between its samples, 0 beyond."""
    if isinstance(spectrum, dict):
        spectrum = (spectrum["nm"], spectrum["values"])
    if np.isscalar(spectrum):
        return np.full(wl.shape, float(spectrum))
    nm, values = (np.asarray(x, dtype=np.float64).ravel() for x in spectrum)
    return values[0] * np.ones(wl.shape) if nm.size == 1 else np.interp(wl, nm, values, left=0.0, right=0.0)


def _as_suns(lights, wl, sky_nodes):
    """The lights as suns: [(zenith in degrees, plane irradiance per wavelength)]."""
    mu, wmu = np.polynomial.legendre.leggauss(sky_nodes)
    mu, wmu = 0.5 * (mu + 1.0), 0.5 * wmu
    suns = []
    for i, light in enumerate(lights):
        e = _on_grid(light.spectrum, wl)
        if light.kind == "sky":
            suns += [(math.degrees(math.acos(m)), e * 2.0 * m * wm) for m, wm in zip(mu, wmu)]
            continue
        d = np.asarray(light.direction, dtype=np.float64)
        if light.kind != "directional" or light.radius > 0 or not d[2] < 0:
            raise ValueError("lights[%d]: a plane-parallel column takes the sun (a directional light going down, "
                             "radius 0) and a uniform sky, not %s" % (i, light))
        suns.append((math.degrees(math.acos(-d[2] / np.linalg.norm(d))), e))
    if not suns:
        raise ValueError("lights: neither a sun nor a sky")
    return suns


def elastic_profile(water, lights, depths, *, grid=(380.0, 780.0, 5.0), surface=True, n_water=1.34,
                    bottom_depth=math.inf, bottom_albedo=0.0, layer=0.0, streams=32, sky_nodes=SKY_NODES,
                    context=None):
    """Ed, Eu, E0 [W/m²/nm] (depth × wavelength) of the water under ``lights``
    (:class:`arcus.ocean.Light`: the sun, :meth:`~arcus.ocean.Light.sun`, and a uniform
    sky, :meth:`~arcus.ocean.Light.sky`) over a flat Fresnel surface (``surface=False``:
    a free top, the light starting in the water at those angles), with the arguments of
    :func:`arcus.ocean.trace_photons`.  With ``layer`` > 0, E0 is averaged over
    [z − layer/2, z + layer/2] ∩ water, as the engine tallies it.  Returns a dict with
    ``wavelengths``, ``depths``, ``Ed``, ``Eu``, ``E0``."""
    depths = np.asarray(depths, dtype=np.float64).ravel()
    if depths.size == 0 or np.any(depths < 0) or not np.all(np.isfinite(depths)):
        raise ValueError("depths: finite and >= 0, got %r" % (depths,))
    c = water.coefficients(grid, context=context)
    wl = c["wavelengths"]
    suns = _as_suns(lights, wl, sky_nodes)
    rows = [EVENTS.index(e) for e in _ELASTIC]
    b_j = c["events"][rows]
    a = c["extinction"] - b_j.sum(axis=0)  # absorption, Raman and fluorescence alike
    phases = scatterer_phases(water)

    # the E0 tally's layer: Gauss nodes over each clipped interval, solved with the depths
    x, w = np.polynomial.legendre.leggauss(LAYER_NODES)
    lo = np.maximum(depths - 0.5 * layer, 0.0)
    hi = np.minimum(depths + 0.5 * layer, bottom_depth)
    nodes = (lo[:, None] + 0.5 * (hi - lo)[:, None] * (x[None, :] + 1.0)).ravel()
    z = np.concatenate([depths, nodes])

    out = {q: np.zeros((depths.size, wl.size)) for q in ("Ed", "Eu", "E0")}
    for k in range(wl.size):
        b = float(b_j[:, k].sum())
        phase = do.mixture([(b_j[j, k] / b, phases[j]) for j in range(3)]) if b > 0 else do.isotropic()
        for zenith, e in suns:
            if e[k] == 0:
                continue
            if surface:
                kw = dict(fresnel=True, sun_zenith_deg=zenith, n_water=n_water)
            else:
                kw = dict(mu0=math.cos(math.radians(zenith)), internal_reflection=False)
            r = do.solve_profile(float(a[k]), b, phase, z, bottom_depth=bottom_depth, bottom_albedo=bottom_albedo,
                                 streams=streams, **kw)
            e0 = r["E0"][depths.size:].reshape(depths.size, LAYER_NODES) @ w * 0.5 if layer > 0 else r["E0"][:depths.size]
            out["Ed"][:, k] += e[k] * r["Ed"][:depths.size]
            out["Eu"][:, k] += e[k] * r["Eu"][:depths.size]
            out["E0"][:, k] += e[k] * e0
    return dict(wavelengths=wl, depths=depths, **out)
