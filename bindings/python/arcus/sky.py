"""Rainbow skies (thesis §4.1.4, §5.5.2): a box of rain (or ice crystals) lit by the sun,
rendered by single-scattering ray marching with the particles' phase tables.

A scene (a dict, or a JSON file: ``scenes/rainbow/*.json``) names the image and camera,
the sun (elevation, azimuth, disc, spectrum, reddening), the rain box with its drop
populations (one size, a mixture, or a size distribution: Marshall–Palmer or gamma;
drops above a size take the thesis' raindrop shape) and the background.  The drops'
phase tables come from :func:`arcus.sweep.phase_tables` (cached on disk, on Dask when
asked), are summed over the populations into a volume scattering function
β(λ, φ, θ) = Σ N·C_sca·p and an extinction σ_e(λ) = Σ N·C_ext, and the library renders
the sky (``arcus_rainbow_render``: the sun's disc, the march, CIE XYZ and sRGB).
"""

import dataclasses
import functools
import json
import math
import os
import time
from ctypes import byref, c_float, c_uint64
from dataclasses import dataclass

import numpy as np

from . import _lib, _scene_file, daylight, sweep
from ._args import to_path
from ._drop_sizes import cloud_droplets, gauss_bins, stratified_nodes
from ._errors import ArgumentError
from .context import _check_progress, _owned_context
from .image import read as read_image
from .image import write as write_image
from ._lib import lib

__all__ = ["SkyImage", "VolumeTable", "load_scene", "populations", "volume_table", "sky_parameters", "atmosphere_of",
           "daylight_sky_image", "render", "export",
           "light_frame", "upright_rotation"]

# Hansen & Travis (1974), eq. 2.30 with Bucholtz (1995): the Rayleigh optical depth of the
# whole atmosphere at sea level, λ in µm; a sun seen through `airmass` atmospheres is
# attenuated by exp(−airmass·τ_R(λ)).
def rayleigh_depth(wavelength_nm):
    lam = np.asarray(wavelength_nm, dtype=float) / 1000.0
    return 0.008569 * lam**-4 * (1 + 0.0113 * lam**-2 + 0.00013 * lam**-4)


def planck(wavelength_nm, temperature_k):
    """Black-body spectral radiance shape at ``wavelength_nm`` (arbitrary scale)."""
    lam = np.asarray(wavelength_nm, dtype=float) * 1e-9
    c2 = 1.438776877e-2  # h·c/k [m·K]
    return lam**-5 / np.expm1(c2 / (lam * temperature_k))


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


def _scene_dir(scene):
    """The folder a scene's relative file names start from: its file's, or the current one
    for a dict."""
    return "" if isinstance(scene, dict) else os.path.dirname(os.path.abspath(os.fspath(scene)))


def _sky_image(spec, base_dir):
    """A sky image, ``{"image": FILE, "scale": s}`` (FILE relative to the scene's folder):
    (absolute path, scale), or (None, 1.0) for a sky given as a spectrum."""
    if not isinstance(spec, dict) or "image" not in spec or "type" in spec:
        return None, 1.0
    unknown = set(spec) - {"image", "scale"}
    if unknown:
        raise ArgumentError("background.sky: an image sky takes 'image' and 'scale' only, got %s"
                            % ", ".join(sorted(unknown)))
    name = spec["image"]
    if not isinstance(name, str) or not name:
        raise ArgumentError("background.sky: 'image' must be a file name, got %r" % (name,))
    path = os.path.join(base_dir, name)
    if not os.path.isfile(path):
        raise ArgumentError("background.sky: the image %s does not exist" % path)
    return os.path.abspath(path), _number(spec, "scale", 1.0, low=0, where="background.sky")


def _daylight_kind(spec, where):
    """True for a background {"type": "daylight"} (the shared sky, arcus.daylight)."""
    if not isinstance(spec, dict) or "type" not in spec:
        return False
    if spec["type"] != "daylight":
        raise ArgumentError("%s: 'type' must be daylight, got %r" % (where, spec["type"]))
    allowed = {"type", "albedo"} if where == "background.ground" else {"type"}
    unknown = set(spec) - allowed
    if unknown:
        raise ArgumentError("%s: a daylight background takes %s only, got %s"
                            % (where, " and ".join(sorted(allowed)), ", ".join(sorted(unknown))))
    return True


def _spectrum(spec, wl, where, default_radiance, daylight_sun=None):
    """A background spectrum: {"spectrum": "flat"|"rayleigh", "radiance": R} (rayleigh:
    λ^−4 scaled to mean R over the table's wavelengths), or the shared daylight
    ({"type": "daylight"}): the sky is then an image (0 here), the ground a Lambertian
    one of ``albedo`` (0.2) lit by the sun and the sky, ``daylight_sun`` =
    (zenith, atmosphere)."""
    if spec is None:
        return np.zeros_like(wl)
    if not isinstance(spec, dict):
        raise ArgumentError("%s must be an object, got %r" % (where, spec))
    if _daylight_kind(spec, where):
        if where == "background.sky":
            return np.zeros_like(wl)
        albedo = _number(spec, "albedo", 0.2, 0, 1, where)
        zenith, atmosphere = daylight_sun
        return albedo / math.pi * _daylight_ground(tuple(np.asarray(wl, dtype=float).ravel()), zenith, atmosphere)
    if "image" in spec:
        if where != "background.sky":
            raise ArgumentError("%s: only the sky may be an image" % where)
        return np.zeros_like(wl)
    value = _number(spec, "radiance", default_radiance, low=0, where=where)
    kind = spec.get("spectrum", "flat")
    if kind == "flat":
        return np.full_like(wl, value)
    if kind == "rayleigh":
        shape = rayleigh_depth(wl)
        return value * shape / shape.mean()
    raise ArgumentError("%s: 'spectrum' must be flat or rayleigh, got %r" % (where, kind))


def atmosphere_of(scene):
    """The scene's ``atmosphere`` (fields of :class:`arcus.daylight.Atmosphere`, each
    optional) over the library's clear day."""
    spec = load_scene(scene).get("atmosphere", {})
    if not isinstance(spec, dict):
        raise ArgumentError("scene: 'atmosphere' must be an object")
    try:
        return daylight._atmosphere(None, dict(spec))
    except ArgumentError as e:
        raise ArgumentError("atmosphere: %s" % e) from None


def ground_lit_atmosphere(scene):
    """:func:`atmosphere_of` over the scene's ground: a daylight ``background.ground``'s
    albedo (0.2) is the atmosphere's ``ground_albedo``, the ground that lights the sky
    back (one ground, given once: an ``atmosphere.ground_albedo`` beside it is refused)."""
    scene = load_scene(scene)
    atmosphere = atmosphere_of(scene)
    background = scene.get("background", {})
    ground = background.get("ground") if isinstance(background, dict) else None
    if not _daylight_kind(ground, "background.ground"):
        return atmosphere
    if "ground_albedo" in scene.get("atmosphere", {}):
        raise ArgumentError("atmosphere.ground_albedo: a daylight background.ground gives the ground's albedo "
                            "(background.ground.albedo); give it once")
    return dataclasses.replace(atmosphere, ground_albedo=_number(ground, "albedo", 0.2, 0, 1, "background.ground"))


def sun_spectrum(sun, wl, atmosphere=None):
    """The sun's irradiance at the rain [W/(m²·nm)]: the shared daylight (``"spectrum":
    "daylight"``: ASTM G173's sun through the refracted path at its elevation, in the
    scene's ``atmosphere``, as absolute W/(m²·nm)), or a black body (``temperature_k``,
    5778 K) or flat, scaled to mean ``irradiance`` over the wavelengths, then reddened by
    ``airmass`` atmospheres of Rayleigh scattering (Fig. 5.23(a)'s red sun)."""
    kind = sun.get("spectrum", "blackbody")
    if kind == "daylight":
        given = sorted({"temperature_k", "irradiance", "airmass"} & set(sun))
        if given:
            raise ArgumentError("sun: a daylight sun's spectrum and brightness are the atmosphere's; remove %s"
                                % ", ".join(given))
        elevation = _number(sun, "elevation_deg", 10.0, where="sun")
        band = float(np.median(np.diff(wl))) if wl.size > 1 else 0.0
        return daylight.solar_irradiance(wl, band=band) * daylight.sun_transmittance(
            wl, 90.0 - elevation, atmosphere if atmosphere is not None else daylight.default_atmosphere())
    if kind == "blackbody":
        shape = planck(wl, _number(sun, "temperature_k", 5778.0, where="sun", positive=True))
    elif kind == "flat":
        shape = np.ones_like(wl)
    else:
        raise ArgumentError("sun: 'spectrum' must be daylight, blackbody or flat, got %r" % (kind,))
    e = _number(sun, "irradiance", 1.0, low=0, where="sun") * shape / shape.mean()
    return e * np.exp(-_number(sun, "airmass", 0.0, low=0, where="sun") * rayleigh_depth(wl))


@dataclass(frozen=True, eq=False)
class SkyImage:
    """A rendered sky: ``image`` (H, W, 3) linear sRGB, ``xyz`` (H, W, 3), ``theta``
    (H, W) the scattering angle from the sun's centre [deg], the :class:`VolumeTable`
    rendered, ``features`` compiled and ``seconds`` (table, render)."""

    image: np.ndarray
    xyz: np.ndarray
    theta: np.ndarray
    table: VolumeTable
    features: frozenset
    seconds: dict


def sky_parameters(scene, wavelengths, *, width=None, height=None, sun_samples=None, march_steps=None,
                   base_dir=None):
    """The members of ``arcus_rainbow_sky`` for a scene at the table's wavelengths, as a
    dict of numbers, 3-vectors and spectra (what :func:`render` passes the library and
    :func:`export` writes for arcus_view); a sky image as ``sky_image_file`` (an absolute
    path, or None) and ``sky_image_scale``, or the shared daylight sky as
    ``sky_image_daylight`` = (sun zenith, sun azimuth, Atmosphere), or None
    (:func:`daylight_sky_image` makes its image).  Relative file names start from ``base_dir``
    (default: the scene file's folder)."""
    if base_dir is None:
        base_dir = _scene_dir(scene)
    scene = load_scene(scene)
    img, cam, sun, rain = (scene.get(k, {}) for k in ("image", "camera", "sun", "rain"))
    for name, part in (("image", img), ("camera", cam), ("sun", sun), ("rain", rain)):
        if not isinstance(part, dict):
            raise ArgumentError("scene: '%s' must be an object" % name)
    look_a = math.radians(_number(cam, "look_azimuth_deg", 0.0, where="camera"))
    look_e = math.radians(_number(cam, "look_elevation_deg", 20.0, -89, 89, "camera"))
    background = scene.get("background", {})
    if not isinstance(background, dict):
        raise ArgumentError("scene: 'background' must be an object")
    sky_file, sky_scale = _sky_image(background.get("sky"), base_dir)
    atmosphere = ground_lit_atmosphere(scene)
    sun_zenith = 90.0 - _number(sun, "elevation_deg", 10.0, where="sun")
    daylight_sky = None
    if _daylight_kind(background.get("sky"), "background.sky"):
        daylight_sky = (sun_zenith, _number(sun, "azimuth_deg", 180.0, where="sun"), atmosphere)
    return dict(
        width=int(width or _number(img, "width", 800, 1, 16384, "image")),
        height=int(height or _number(img, "height", 600, 1, 16384, "image")),
        camera_position=_vector(cam, "position", [0.0, 1.7, 0.0], "camera"),
        camera_forward=[math.cos(look_e) * math.sin(look_a), math.sin(look_e), math.cos(look_e) * math.cos(look_a)],
        camera_up=[0.0, 1.0, 0.0],
        fov_deg=_number(img, "fov_deg", 90.0, where="image"),
        sun_elevation_deg=_number(sun, "elevation_deg", 10.0, where="sun"),
        sun_azimuth_deg=_number(sun, "azimuth_deg", 180.0, where="sun"),
        sun_diameter_deg=_number(sun, "diameter_deg", 0.53, where="sun"),
        sun_samples=int(sun_samples or _number(sun, "samples", 16, 1, 4096, "sun")),
        sun_irradiance=sun_spectrum(sun, wavelengths, atmosphere),
        sky_radiance=_spectrum(background.get("sky"), wavelengths, "background.sky", 0.0),
        ground_radiance=_spectrum(background.get("ground"), wavelengths, "background.ground", 0.0,
                                  (min(sun_zenith, 120.0), atmosphere)),
        sky_image_file=sky_file,
        sky_image_daylight=daylight_sky,
        sky_image_scale=sky_scale,
        rain_min=_vector(rain, "box_min", None, "rain"),
        rain_max=_vector(rain, "box_max", None, "rain"),
        march_steps=int(march_steps or _number(rain, "march_steps", 32, 1, 100000, "rain")),
        exposure=_number(img, "exposure", 0.0, low=0, where="image"))


def _check_sun(scene):
    # Checked before any table is computed (the library checks it again for C callers).
    sun = load_scene(scene).get("sun", {})
    if isinstance(sun, dict) and _number(sun, "elevation_deg", 10.0, where="sun") < 0:
        raise ArgumentError("sun: the sun is below the horizon (elevation_deg %g): it lights no rain in front "
                            "of the camera, so no rainbow forms; raise it to 0 or above" % sun["elevation_deg"])


# A process renders one scene's sky many times over (a sweep of settings, a test suite):
# the daylight's panorama (1.4 s on two cores) and the ground's light (0.4 s) are kept
# for the last few suns and atmospheres (Atmosphere is frozen, so hashable).
@functools.lru_cache(maxsize=4)
def _daylight_panorama(zenith, azimuth, atmosphere):
    return daylight.sky_image(512, 256, zenith, azimuth, atmosphere)


@functools.lru_cache(maxsize=8)
def _daylight_ground(wavelengths, zenith, atmosphere):
    direct, diffuse = daylight.ground_irradiance(np.array(wavelengths), zenith, atmosphere)
    return direct + diffuse


def daylight_sky_image(sky_image_daylight):
    """The daylight sky's panorama for ``sky_image_daylight`` (:func:`sky_parameters`):
    512 × 256 pixels of linear sRGB radiance [W/(m²·sr·nm)], scale 1 (a new array)."""
    zenith, azimuth, atmosphere = sky_image_daylight
    return _daylight_panorama(float(zenith), float(azimuth), atmosphere).copy()


def export(scene, path, *, table=None, width=None, height=None, sun_samples=None, march_steps=None, cache_dir=None,
           client="serial", workers=None, base_dir=None):
    """Writes a scene with its volume table for ``arcus_view`` (which has no Python to
    build tables): ``path`` (JSON: ``"arcus_rainbow_sky": 1``, the sky's members and the
    table's axes and extinction) and ``path + ".beta"`` (β as little-endian float64,
    wavelength × φ × θ).  ``width`` … ``march_steps`` override the scene's, as in
    :func:`render` (``base_dir`` too).  Returns the :class:`VolumeTable`."""
    base_dir = _scene_dir(scene) if base_dir is None else os.fspath(base_dir)
    scene = load_scene(scene)
    _check_sun(scene)
    if table is None:
        table = volume_table(scene, cache_dir=cache_dir, client=client, workers=workers)
    params = {k: (v.tolist() if isinstance(v, np.ndarray) else v)
              for k, v in sky_parameters(scene, table.wavelengths, width=width, height=height, sun_samples=sun_samples,
                                         march_steps=march_steps, base_dir=base_dir).items()}
    path = os.fspath(path)
    sunlit = params.pop("sky_image_daylight")
    if sunlit is not None:
        params["sky_image_file"] = os.path.abspath(path + ".sky.exr")
        write_image(params["sky_image_file"], daylight_sky_image(sunlit))
    beta_file = path + ".beta"
    np.ascontiguousarray(table.beta, dtype="<f8").tofile(beta_file)
    doc = {"arcus_rainbow_sky": 1, "description": scene.get("description", ""), "sky": params,
           "table": {"beta_file": os.path.basename(beta_file), "wavelengths_nm": table.wavelengths.tolist(),
                     "theta_first_deg": float(table.theta[0]), "theta_last_deg": float(table.theta[-1]),
                     "theta_count": int(table.theta.size), "phi_count": int(table.phi.size),
                     "extinction": np.asarray(table.extinction).tolist()}}
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
    return table


def render(scene, *, exr=None, png=None, table=None, width=None, height=None, sun_samples=None, march_steps=None,
           cache_dir=None, client="serial", workers=None, progress=None, context=None, base_dir=None):
    """Renders a rainbow scene (dict or JSON path): a :class:`SkyImage`; writes ``exr``
    (R, G, B linear, X, Y, Z, theta) and ``png`` (sRGB) if given.  ``table`` reuses a
    :class:`VolumeTable`; ``width``, ``height``, ``sun_samples`` and ``march_steps``
    override the scene's.  Phase tables come from the sweep cache (``cache_dir``),
    computed where missing, here (``client="serial"``) or on a Dask client/address.
    ``base_dir``: where a dict's relative file names start (default: the current folder)."""
    base_dir = _scene_dir(scene) if base_dir is None else os.fspath(base_dir)
    scene = load_scene(scene)
    _check_sun(scene)
    sky_parameters(scene, np.array([550.0]), base_dir=base_dir)  # the scene's errors before any table is computed
    if table is None:
        table = volume_table(scene, cache_dir=cache_dir, client=client, workers=workers,
                             progress=progress is not None)
    wl = table.wavelengths
    params = sky_parameters(scene, wl, width=width, height=height, sun_samples=sun_samples, march_steps=march_steps,
                            base_dir=base_dir)
    sky = _lib.RainbowSkyStruct()
    _lib.check(lib.arcus_rainbow_sky_init(byref(sky)))
    spectra = {k: np.ascontiguousarray(params.pop(k), dtype=float)
               for k in ("sun_irradiance", "sky_radiance", "ground_radiance")}
    sky_image = params.pop("sky_image_file")
    sunlit = params.pop("sky_image_daylight")
    if sunlit is not None:
        sky_image = daylight_sky_image(sunlit)
    elif sky_image is not None:
        sky_image = read_image(sky_image)
    if sky_image is not None:
        sky_image = np.ascontiguousarray(sky_image, dtype=np.float32)
        sky.sky_image = _lib.ptr(sky_image, c_float)
        sky.sky_image_height, sky.sky_image_width = sky_image.shape[:2]
    sky.sky_image_scale = params.pop("sky_image_scale")
    for key, value in params.items():
        if isinstance(value, list):
            getattr(sky, key)[:] = value
        else:
            setattr(sky, key, value)
    for key, value in spectra.items():
        setattr(sky, key, _lib.ptr(value))
    _check_progress(progress)

    beta = np.ascontiguousarray(table.beta, dtype=float)
    ext = np.ascontiguousarray(table.extinction, dtype=float)
    wl_c = np.ascontiguousarray(wl, dtype=float)
    t = _lib.RainbowTableStruct(len(wl_c), _lib.ptr(wl_c), len(table.theta), float(table.theta[0]),
                                float(table.theta[-1]), len(table.phi), _lib.ptr(beta), _lib.ptr(ext))
    with _owned_context(context) as ctx:
        t0 = time.perf_counter()

        def start(callback, job_out):
            sky.progress = callback
            return lib.arcus_rainbow_render(ctx._handle, byref(t), byref(sky), job_out)

        def read(job):
            w, h = sky.width, sky.height
            xyz, rgb = np.empty((h, w, 3), np.float32), np.empty((h, w, 3), np.float32)
            th = np.empty((h, w), np.float32)
            ctx._check(lib.arcus_job_get_rainbow_image(job, None, None, _lib.ptr(xyz, c_float),
                                                       _lib.ptr(rgb, c_float), _lib.ptr(th, c_float)))
            if exr is not None or png is not None:
                ctx._check(lib.arcus_job_write_rainbow_image(job, None if exr is None else to_path(exr, "exr"),
                                                             None if png is None else to_path(png, "png")))
            bits = c_uint64()
            ctx._check(lib.arcus_job_get_features(job, byref(bits)))
            return xyz, rgb, th, _lib.feature_names(bits.value)

        xyz, rgb, th, features = ctx._run_job(start, progress, False, "arcus_rainbow_render", reader=read)
        seconds = {"table": table.seconds, "render": time.perf_counter() - t0}
    return SkyImage(image=rgb, xyz=xyz, theta=th, table=table, features=features, seconds=seconds)
