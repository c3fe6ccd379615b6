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

from . import _lib, daylight
from ._args import to_path
from ._errors import ArgumentError
from .context import _check_progress, _owned_context
from .image import read as read_image
from .image import write as write_image
from ._lib import lib
# the scene and its rain, read and tabulated there; named here too, as arcus.sky's since 0.9
from .rain import (VolumeTable, _number, _vector, band_wavelengths, light_frame, load_scene, populations,  # noqa: F401
                   theta_of, upright_rotation, volume_table, wavelengths_of)

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
