"""A rainbow scene read, and its rain (thesis §4.1.4, §5.5.2): the scene file checked by
the library, its table axes, the sun's light frame, the rain's drop populations (one
size, a mixture, a size distribution in bins or, for cloud droplets by Mie, in sizes
that move with the wavelength) and their phase tables summed into the rain's volume
scattering function (:func:`volume_table`).  :mod:`arcus.sky` renders it."""

import math
import time
from dataclasses import dataclass

import numpy as np

from . import _scene_file, sweep
from ._drop_sizes import cloud_droplets, gauss_bins, stratified_nodes
from ._errors import ArgumentError

__all__ = ["VolumeTable", "load_scene", "populations", "volume_table", "band_wavelengths", "wavelengths_of",
           "theta_of", "light_frame", "upright_rotation"]


# ---- scene --------------------------------------------------------------------------


def _number(d, key, default=None, low=None, high=None, where="scene", positive=False):
    v = d.get(key, default)
    if v is None:
        raise ArgumentError("%s: '%s' is missing" % (where, key))
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise ArgumentError("%s: '%s' must be a finite number, got %r" % (where, key, v))
    if positive and v <= 0:
        raise ArgumentError("%s: '%s' must be positive, got %r" % (where, key, v))
    if (low is not None and v < low) or (high is not None and v > high):
        raise ArgumentError("%s: '%s' must lie in [%s, %s], got %r" % (where, key, low, high, v))
    return float(v)


def _vector(d, key, default=None, where="scene"):
    v = d.get(key, default)
    if v is None or np.shape(v) != (3,) or not np.all(np.isfinite(np.asarray(v, dtype=float))):
        raise ArgumentError("%s: '%s' must be three finite numbers, got %r" % (where, key, v))
    return [float(x) for x in v]


def load_scene(scene):
    """A scene dict from a dict or a JSON file path (relative paths in it stay as given).

    A file is read and checked by the library (its schema: scenes/README.md, "Rainbow
    scenes"): an unknown or repeated key, a wrong type, a file that is not a regular
    file or is larger than ARCUS_MAX_SCENE_BYTES raise :class:`arcus.Error` naming the
    file and the key."""
    if isinstance(scene, dict):
        return scene
    return _scene_file.read(scene, ("rainbow",))[1]


def _axis(tables, key, default):
    """A table axis of a scene: a list, or {"linspace": [first, last, count]} or
    {"range": [first, last, step]} (as sweep specs write them)."""
    values = np.asarray(sweep.spec_axis(tables.get(key, default), "tables." + key), dtype=float).ravel()
    if values.size == 0 or not np.all(np.isfinite(values)) or np.any(np.diff(values) <= 0):
        raise ArgumentError("tables: '%s' must be finite and strictly increasing, got %r" % (key, tables.get(key)))
    return values


def wavelengths_of(tables):
    """The table wavelengths [nm] of a scene's ``tables``."""
    wl = _axis(tables, "wavelengths", {"linspace": [380, 700, 33]})
    if wl[0] <= 0:
        raise ArgumentError("tables: 'wavelengths' must be positive (nm), got %r" % (tables.get("wavelengths"),))
    return wl


def theta_of(tables):
    """The table's uniform θ samples [deg] within [0, 180] (the renderer interpolates
    them as a uniform grid)."""
    theta = _axis(tables, "theta", {"range": [100, 180, 0.05]})
    step = np.diff(theta)
    if theta.size < 2 or theta[0] < 0 or theta[-1] > 180 or np.ptp(step) > 1e-9 * (theta[-1] - theta[0]):
        raise ArgumentError("tables: 'theta' must be at least two uniform samples within [0, 180] degrees, got %r"
                            % (tables.get("theta"),))
    return theta


def light_frame(sun_elevation_deg, sun_azimuth_deg):
    """The light frame of the sun's centre as rows (x, y, z) in the world (y up, azimuth
    from +z toward +x): z along the light (−sun), y the world's up across the light,
    x = y × z.  Phase tables use it: φ = 0° along x, 90° along y (up)."""
    e, a = math.radians(sun_elevation_deg), math.radians(sun_azimuth_deg)
    sun = np.array([math.cos(e) * math.sin(a), math.sin(e), math.cos(e) * math.cos(a)])
    z = -sun
    up = np.array([0.0, 1.0, 0.0])
    y = up - up.dot(z) * z
    y = y / np.linalg.norm(y) if np.linalg.norm(y) > 1e-12 else np.array([0.0, 0.0, 1.0])
    return np.array([np.cross(y, z), y, z])


def upright_rotation(sun_elevation_deg, sun_azimuth_deg=180.0):
    """The particle → light-frame rotation of a particle standing upright (its own y along
    the world's up: a falling raindrop) under a sun at that elevation."""
    frame = light_frame(sun_elevation_deg, sun_azimuth_deg)
    px = frame[0]                     # horizontal, across the light
    py = np.array([0.0, 1.0, 0.0])
    pz = np.cross(px, py)
    return frame @ np.array([px, py, pz]).T  # R[r, c] = light_r · particle_c


def populations(rain, sun_elevation_deg, wavelengths=1):
    """The rain's populations as (particle spec, number density [1/m³]) pairs: one size,
    or a size distribution in Gauss–Legendre bins (``bins``).  Cloud and fog droplets by
    Lorenz–Mie take, instead of fixed bins, ``bins`` sizes that move with the wavelength
    (:func:`arcus._drop_sizes.stratified_nodes`): their specs' radius and their density
    are then one per wavelength, of ``wavelengths``.  Specs are those of
    :func:`arcus.sweep.phase_tables`."""
    pops = rain.get("populations")
    if not isinstance(pops, list) or not pops:
        raise ArgumentError("rain: 'populations' must be a non-empty list of drop populations")
    out = []
    for i, p in enumerate(pops):
        where = "rain.populations[%d]" % i
        if not isinstance(p, dict):
            raise ArgumentError("%s must be an object, got %r" % (where, p))
        shape = p.get("shape", "sphere")
        if shape == "crystal":
            spec = {"kind": "crystal", "shape": p.get("crystal", "column"),
                    "size": _number(p, "size", where=where, positive=True),
                    "orientation": p.get("orientation", "random"), "tilt_deg": _number(p, "tilt_deg", 1.0, 0, 90, where),
                    "sun_elevation_deg": sun_elevation_deg,
                    "orientations": int(_number(p, "orientations", 2000, 1, 1e7, where)),
                    "seed": int(_number(p, "seed", 1, 0, 2**31, where))}
            out.append((spec, _number(p, "density", where=where, low=0)))
            continue
        dist = p.get("distribution")
        if dist is None:
            if shape == "sphere":
                radius = _number(p, "radius", where=where, positive=True)
                sizes = [(2 * radius, _number(p, "density", where=where, low=0))]
            elif shape == "raindrop":
                sizes = [(_number(p, "diameter", where=where, positive=True), _number(p, "density", where=where, low=0))]
            else:
                raise ArgumentError("%s: 'shape' must be sphere, raindrop or crystal, got %r" % (where, shape))
        else:
            bins = int(_number(p, "bins", 6, 1, 200, where))
            if dist == "marshall_palmer":
                # Marshall & Palmer (1948): N(D) = 8000 exp(−Λ D) per m³ per mm,
                # Λ = 4.1 R^−0.21 per mm for a rain rate R in mm/h.
                rate = _number(p, "rain_rate_mm_h", where=where, positive=True)
                lo, hi = p.get("diameter_range_mm", [0.5, 3.0])
                lam = 4.1 * rate**-0.21
                d_mm, w = gauss_bins(float(lo), float(hi), bins)
                dens = 8000.0 * np.exp(-lam * d_mm) * w
                sizes = list(zip(d_mm * 1e-3, dens))
            elif dist in ("gamma", "lognormal"):
                log_density, (lo, hi) = cloud_droplets(p, dist, where)
                lo, hi = p.get("radius_range", [lo, hi])
                total = _number(p, "total_density", where=where, low=0)
                above = p.get("nonspherical_above_mm", 1.0)
                if p.get("method") == "mie" and shape == "sphere" and 0 < float(lo) < float(hi) \
                        and 2 * float(hi) * 1e3 < float(above):
                    radii, weights = stratified_nodes(log_density, float(lo), float(hi), bins, wavelengths)
                    out += [({"kind": "sphere", "radius": radii[:, i].tolist(), "method": "mie"},
                             total * weights[:, i]) for i in range(bins)]
                    continue
                r, w = gauss_bins(float(lo), float(hi), bins)
                log_n = log_density(r)
                n = np.exp(log_n - log_n.max()) * w  # narrow distributions: r^α beyond a double's range
                sizes = list(zip(2 * r, total * n / n.sum()))
            else:
                raise ArgumentError("%s: 'distribution' must be marshall_palmer, gamma or lognormal, got %r"
                                    % (where, dist))
            if not sizes or float(lo) >= float(hi) or float(lo) <= 0:
                raise ArgumentError("%s: the size range must be positive and increasing, got %r" % (where, [lo, hi]))
        above = p.get("nonspherical_above_mm", 1.0 if shape == "sphere" and dist else None)
        for diameter, density in sizes:
            if density < 0 or not math.isfinite(density):
                raise ArgumentError("%s: number density must be finite and >= 0, got %r" % (where, density))
            raindrop = shape == "raindrop" or (above is not None and diameter * 1e3 >= float(above))
            if raindrop:
                spec = {"kind": "raindrop", "diameter": float(diameter),
                        "rotation": upright_rotation(sun_elevation_deg).tolist()}
            else:
                spec = {"kind": "sphere", "radius": float(diameter / 2), "method": p.get("method", "rays")}
            out.append((spec, float(density)))
    if sum(float(np.sum(d)) for _, d in out) <= 0:
        raise ArgumentError("rain: the populations hold no drops (every number density is 0)")
    return out


def _needs_azimuth(spec):
    return spec["kind"] in ("raindrop", "mesh") or (spec["kind"] == "crystal" and spec["orientation"] != "random")


@dataclass(frozen=True, eq=False)
class VolumeTable:
    """The rain's volume scattering function: ``beta`` (L, F, T) [1/(m·sr)] at
    ``wavelengths`` (L,), ``phi`` (F,) = 360°·j/F and ``theta`` (T,) [deg], its
    ``extinction`` (L,) [1/m], and the sweep's task counts (``computed``, ``cached``)."""

    wavelengths: np.ndarray
    theta: np.ndarray
    phi: np.ndarray
    beta: np.ndarray
    extinction: np.ndarray
    computed: int
    cached: int
    seconds: float


def band_wavelengths(wavelengths, samples):
    """(L, samples): the midpoints of ``samples`` equal parts of each wavelength's band,
    which runs halfway to its neighbours (the ends' bands are as wide on both sides), so
    that a table averaged over them integrates the band: interference fringes finer than
    the wavelength step (single drop sizes: fringes a few nm apart at 0.3 mm) average
    out instead of aliasing (docs/sky.md, "Wavelengths").  One sample: the wavelengths."""
    wl = np.asarray(wavelengths, dtype=float)
    if samples == 1 or wl.size < 2:
        return wl[:, None]
    mid = (wl[1:] + wl[:-1]) / 2
    lo = np.concatenate([[wl[0] - (mid[0] - wl[0])], mid])
    hi = np.concatenate([mid, [wl[-1] + (wl[-1] - mid[-1])]])
    return lo[:, None] + (hi - lo)[:, None] * (np.arange(samples) + 0.5) / samples


def volume_table(scene, *, cache_dir=None, client="serial", workers=None, progress=False):
    """Sums the populations' phase tables (from :func:`arcus.sweep.phase_tables`) into the
    rain's :class:`VolumeTable`; with ``tables.band_samples`` K > 1, each wavelength's
    table is the mean over K points across its band (:func:`band_wavelengths`)."""
    scene = load_scene(scene)
    tables = scene.get("tables", {})
    sun = scene.get("sun", {})
    elevation = _number(sun, "elevation_deg", 10.0, where="sun")
    wl, theta = wavelengths_of(tables), theta_of(tables)
    sub = band_wavelengths(wl, int(_number(tables, "band_samples", 1, 1, 64, "tables")))
    pops = populations(scene.get("rain", {}), elevation, sub.size)
    azimuth = any(_needs_azimuth(s) for s, _ in pops)
    phi = None
    if azimuth:
        step = _number(tables, "phi_step_deg", 5.0, where="tables", positive=True)
        phi = np.arange(0.0, 360.0 - 1e-9, step)
    t0 = time.perf_counter()
    options = dict(grid=int(_number(tables, "grid", 1000, 4, 8192, "tables")),
                   max_bounces=int(_number(tables, "max_bounces", 3, 0, 15, "tables")),
                   cache_dir=cache_dir, client=client, workers=workers, progress=progress)
    # Particles that look the same from every azimuth (spheres, random orientations) get
    # 1-D tables, far cheaper than the 2-D ones of the rest; both are summed over φ × θ.
    beta = np.zeros((sub.size, 1 if phi is None else phi.size, theta.size))
    extinction = np.zeros(sub.size)
    computed = cached = 0
    for two_d in (False, True):
        group = [(s, d) for s, d in pops if _needs_azimuth(s) == two_d]
        if not group:
            continue
        pt = sweep.phase_tables([s for s, _ in group], sub.ravel(), theta, phi if two_d else None, **options)
        # (N, L): a number density per particle, or per particle and wavelength
        density = np.array([np.broadcast_to(d, (sub.size,)) for _, d in group])
        phase = np.asarray(pt.phase, dtype=float)
        if phase.ndim == 3:  # (N, L, T): the same at every φ
            phase = phase[:, :, None, :]
        beta += np.einsum("nl,nl,nlft->lft", density, np.asarray(pt.cross_section), phase)
        extinction += np.sum(density * np.asarray(pt.extinction), axis=0)
        computed += pt.computed
        cached += pt.cached
    # each wavelength's band: the mean of its sub-wavelengths' tables
    beta = beta.reshape(sub.shape + beta.shape[1:]).mean(axis=1)
    extinction = extinction.reshape(sub.shape).mean(axis=1)
    return VolumeTable(wavelengths=wl, theta=theta, phi=np.array([0.0]) if phi is None else phi,
                       beta=np.ascontiguousarray(beta), extinction=extinction, computed=computed, cached=cached,
                       seconds=time.perf_counter() - t0)
