"""Translucent materials: the dipole model of subsurface light (thesis §3.1.4, with eq.
3.7 corrected; Jensen et al. 2001), the measured materials, and the inversion from what a
photograph shows to coefficients (Jensen & Buhler 2002).  docs/translucency.md.

Units are the C API's (arcus_translucency.h): coefficients in mm⁻¹, distances in mm,
R_d per mm², three channels R, G, B.

>>> marble = Dipole.from_material("marble")
>>> marble.total_reflectance          # (3,) closed form, = ∫ 2πr R_d(r) dr
>>> marble.Rd([0.5, 1.0, 2.0])        # (3, 3): distances × channels
>>> Dipole.from_reflectance(marble.total_reflectance, marble.diffuse_length, eta=1.5)
>>> est = estimate_bssrdf("photo.exr", "bunny.ply", [((0, 1, 1), 1.0)], camera, mm_per_unit=20)
>>> est.dipole, est.profile, est.condition, est.timings            # thesis §3.3.1
>>> img = render(marble, "bunny.ply", [((0, 1, 1), 1.0)], {"position": (0, 0, 5), "look_at": (0, 0, 0)},
...              mm_per_unit=20, out="bunny.exr")   # eq. 3.6–3.8; img.image is (height, width, 3)
"""

import os
import time
import warnings
from ctypes import byref, c_char_p, c_double, c_float, c_uint8, c_uint64
from dataclasses import dataclass, field

import numpy as np

from . import _lib
from . import image
from ._advance import _check_progress
from ._args import to_choice, to_float, to_int, to_path, to_real_array, to_vec3
from ._errors import ArgumentError
from ._lib import lib
from .context import _owned_context
from ._photos import read_matte as _matte, read_photo as _photo
from ._meshes import handle_of as _mesh_handle, read_mesh  # noqa: F401  (read_mesh is public here)
from ._single_image import (DetectedLight, LightDetection, PhotoShape, automatic_outputs,  # noqa: F401  (public here)
                            detect_lights, estimate_shape, shape_params_into)

__all__ = ["Dipole", "Profile", "materials", "henyey_greenstein", "fresnel_reflectance", "render", "Rendered",
           "read_mesh", "estimate_bssrdf", "Estimate", "detect_lights", "LightDetection", "DetectedLight",
           "estimate_shape", "PhotoShape"]


def _check(code):
    _lib.check(code)


def _rgb(value, name):
    """``value`` as three floats (one number stands for all three channels)."""
    array = to_real_array(value, name)
    if array.shape == ():
        array = np.repeat(array, 3)
    if array.shape != (3,):
        raise ArgumentError("%s must be one number or three (R, G, B), got shape %s" % (name, array.shape))
    return array


def materials():
    """The names of Jensen et al. 2001's measured materials, for :meth:`Dipole.from_material`."""
    names, name, i = [], c_char_p(), 0
    while lib.arcus_translucency_material_name(i, byref(name)) == 0:
        names.append(_lib.decode(name.value))
        i += 1
    return names


class Dipole:
    """A homogeneous translucent medium for the dipole: absorption ``sigma_a`` and
    reduced scattering ``sigma_s_prime`` = (1 − g)σ_s (mm⁻¹; one number or R, G, B)
    and the relative refractive index ``eta`` (1 to 3).  Give ``sigma_s`` and ``g``
    instead of ``sigma_s_prime`` if you have them: multiple scattering sees only their
    product (1 − g)σ_s, so the dipole keeps that.

    The derived terms are attributes, each (3,) unless scalar: ``albedo`` (α′),
    ``sigma_t_prime``, ``sigma_tr``, ``diffuse_length`` (ℓ_d = 1/σ_tr, mm),
    ``z_r``/``z_v`` (source depths, mm), ``total_reflectance``, ``diffusive`` (α′ >= 0.5),
    ``f_dr``, ``a``, ``exit_transmittance`` (what eq. 3.6's exit term lets out, 1 − 2·FM1).
    A channel outside diffusion (α′ < 0.5, e.g. ketchup's green and blue) warns.  Bad
    values raise :class:`arcus.ArgumentError` naming them.
    """

    def __init__(self, sigma_a, sigma_s_prime=None, eta=1.3, *, sigma_s=None, g=None):
        if sigma_s_prime is None:
            if sigma_s is None:
                raise ArgumentError("give sigma_s_prime, or sigma_s and g")
            g = 0.0 if g is None else to_float(g, "g")
            if not -1 < g < 1:
                raise ArgumentError("g = %r is not between -1 and 1" % g)
            sigma_s_prime = (1 - g) * _rgb(sigma_s, "sigma_s")
        elif sigma_s is not None or g is not None:
            raise ArgumentError("give sigma_s_prime, or sigma_s and g, not both")
        self._struct = _lib.DipoleStruct()
        self._struct.sigma_a[:] = list(_rgb(sigma_a, "sigma_a"))
        self._struct.sigma_s_prime[:] = list(_rgb(sigma_s_prime, "sigma_s_prime"))
        self._struct.eta = to_float(eta, "eta")
        terms = _lib.DipoleTermsStruct()
        _check(lib.arcus_translucency_dipole_get_terms(byref(self._struct), byref(terms)))
        for name in ("albedo", "sigma_t_prime", "sigma_tr", "diffuse_length", "z_r", "z_v", "total_reflectance"):
            setattr(self, name, np.array(getattr(terms, name)[:]))
        self.diffusive = np.array(terms.diffusive[:], dtype=bool)
        self.f_dr, self.a, self.exit_transmittance = terms.f_dr, terms.a, terms.exit_transmittance
        if not self.diffusive.all():
            channels = ", ".join("RGB"[c] for c in range(3) if not self.diffusive[c])
            warnings.warn("reduced albedo below 0.5 in %s (%s): diffusion describes such a medium poorly"
                          % (channels, np.array2string(self.albedo, precision=3)), stacklevel=2)

    @property
    def sigma_a(self):
        return np.array(self._struct.sigma_a[:])

    @property
    def sigma_s_prime(self):
        return np.array(self._struct.sigma_s_prime[:])

    @property
    def eta(self):
        return self._struct.eta

    @classmethod
    def from_material(cls, name):
        """One of :func:`materials` (Jensen et al. 2001; η = 1.3, marble 1.5)."""
        if not isinstance(name, str):
            raise ArgumentError("name must be a str, got %r" % (name,))
        d = _lib.DipoleStruct()
        _check(lib.arcus_translucency_dipole_from_material(name.encode(), byref(d)))
        return cls(d.sigma_a[:], d.sigma_s_prime[:], d.eta)

    @classmethod
    def from_reflectance(cls, total_reflectance, diffuse_length, eta=1.3):
        """The dipole with total diffuse reflectance 0 < R_total < 1 and diffuse mean free
        path ℓ_d > 0 mm (one number or R, G, B each), at ``eta`` (Jensen & Buhler 2002)."""
        total = np.ascontiguousarray(_rgb(total_reflectance, "total_reflectance"))
        length = np.ascontiguousarray(_rgb(diffuse_length, "diffuse_length"))
        d = _lib.DipoleStruct()
        _check(lib.arcus_translucency_dipole_from_reflectance(_lib.ptr(total), _lib.ptr(length),
                                                              to_float(eta, "eta"), byref(d)))
        return cls(d.sigma_a[:], d.sigma_s_prime[:], d.eta)

    def Rd(self, r, scale=1.0, scaling="energy"):
        """R_d per mm² at distances ``r`` mm (any shape): an array of r's shape + (3,).
        ``scale`` stretches the profile (thesis §5.2): "energy" R_d(r/s)/s² keeps the
        total reflectance, "thesis" R_d(r/s) multiplies it by s²."""
        distances = to_real_array(r, "r")
        flat = np.ascontiguousarray(distances.reshape(-1))
        out = np.empty((flat.size, 3))
        _check(lib.arcus_translucency_dipole_profile(byref(self._struct), to_float(scale, "scale"),
                                                     to_choice(scaling, "scaling", _SCALINGS),
                                                     flat.size, _lib.ptr(flat), _lib.ptr(out)))
        return out.reshape(distances.shape + (3,))

    def __repr__(self):
        return "Dipole(sigma_a=%s, sigma_s_prime=%s, eta=%r)" % (
            np.array2string(self.sigma_a, separator=", "), np.array2string(self.sigma_s_prime, separator=", "),
            self.eta)


class Profile:
    """A tabulated diffuse reflectance profile R(r) per channel (arcus_profile_table):
    ``values`` (count, 3) per mm² at r_k = ``reach_mm`` (k / (count − 1))² (dense near 0,
    where profiles peak), linear in √r between samples, 0 beyond the reach; ``eta`` for
    the boundary.  For §5.2's blends, §3.4's fitted profiles (:attr:`Estimate.hermite`)
    and measured data; :func:`render` takes one wherever it takes a :class:`Dipole`.
    """

    def __init__(self, reach_mm, values, eta=1.3):
        self.reach_mm = to_float(reach_mm, "reach_mm")
        self.values = np.ascontiguousarray(to_real_array(values, "values"), dtype=float)
        self.eta = to_float(eta, "eta")
        if self.values.ndim != 2 or self.values.shape[1] != 3 or not 2 <= len(self.values) <= 65536:
            raise ArgumentError("values must be (count, 3) with count 2..65536, got shape %s" % (self.values.shape,))
        if not (self.reach_mm > 0 and np.isfinite(self.reach_mm)):
            raise ArgumentError("reach_mm = %r is not a finite distance > 0" % self.reach_mm)
        if not (np.isfinite(self.values).all() and (self.values >= 0).all()):
            raise ArgumentError("values must be finite and >= 0")

    @property
    def radii(self):
        """The samples' distances, mm: reach (k / (count − 1))²."""
        return self.reach_mm * np.linspace(0, 1, len(self.values)) ** 2

    @classmethod
    def from_dipole(cls, dipole, reach_mm=None, count=4096):
        """``dipole`` sampled (exactly, at the table's radii) up to ``reach_mm`` (default:
        25 diffusion lengths of its longest channel, where R_d has fallen by e^-25, at
        most 1000 mm)."""
        if reach_mm is None:
            longest = np.max(np.where(np.isfinite(dipole.diffuse_length), dipole.diffuse_length, np.inf))
            reach_mm = float(min(1000.0, 25 * longest))
        r = to_float(reach_mm, "reach_mm") * np.linspace(0, 1, to_int(count, "count", 2, 65536)) ** 2
        return cls(reach_mm, dipole.Rd(r), dipole.eta)

    @classmethod
    def from_samples(cls, radii, values, eta=1.3, count=4096):
        """Measured or computed samples: ``radii`` (n,) increasing from 0 mm, ``values``
        (n, 3), linearly interpolated onto the table's radii."""
        r = to_real_array(radii, "radii")
        v = to_real_array(values, "values")
        if r.ndim != 1 or len(r) < 2 or r[0] != 0 or np.any(np.diff(r) <= 0):
            raise ArgumentError("radii must be increasing from 0 (at least two), got %r" % (r,))
        if v.shape != (len(r), 3):
            raise ArgumentError("values must be (len(radii), 3), got shape %s" % (v.shape,))
        grid = r[-1] * np.linspace(0, 1, to_int(count, "count", 2, 65536)) ** 2
        return cls(r[-1], np.stack([np.interp(grid, r, v[:, c]) for c in range(3)], axis=1), eta)

    @classmethod
    def blend(cls, profiles, weights, count=4096):
        """Σ w_i R_i (thesis §5.2's linear blends): ``profiles`` Dipoles or Profiles of
        one η, ``weights`` one number each (or R, G, B each); the reach is the largest."""
        items = [p if isinstance(p, Profile) else cls.from_dipole(p, count=count) for p in profiles]
        if len(items) != len(weights) or not items:
            raise ArgumentError("give one weight per profile (%d profiles, %d weights)" % (len(items), len(weights)))
        if len({p.eta for p in items}) != 1:
            raise ArgumentError("blended profiles must share one eta, got %s" % sorted({p.eta for p in items}))
        reach = max(p.reach_mm for p in items)
        grid = reach * np.linspace(0, 1, to_int(count, "count", 2, 65536)) ** 2
        total = sum(_rgb(w, "weights[%d]" % i) * p.Rd(grid) for i, (w, p) in enumerate(zip(weights, items)))
        return cls(reach, total, items[0].eta)

    def Rd(self, r):
        """R per mm² at distances ``r`` mm (any shape), as the renderer reads the table:
        an array of r's shape + (3,)."""
        distances = to_real_array(r, "r")
        u = np.sqrt(np.abs(distances) / self.reach_mm) * (len(self.values) - 1)
        k = np.minimum(u.astype(int), len(self.values) - 2)
        f = (u - k)[..., None]
        out = (1 - f) * self.values[k] + f * self.values[k + 1]
        return np.where((u < len(self.values) - 1)[..., None], out, 0.0)

    @property
    def total_reflectance(self):
        """∫ 2πr R(r) dr per channel, by the trapezoid rule over the samples."""
        r = self.radii
        y = 2 * np.pi * r[:, None] * self.values
        return 0.5 * ((y[1:] + y[:-1]) * np.diff(r)[:, None]).sum(axis=0)

    def _table(self):
        t = _lib.ProfileTableStruct()
        t.count, t.reach_mm, t.eta = len(self.values), self.reach_mm, self.eta
        t.values = _lib.ptr(self.values)
        return t

    def __repr__(self):
        return "Profile(reach_mm=%r, %d samples, eta=%r, total_reflectance=%s)" % (
            self.reach_mm, len(self.values), self.eta, np.array2string(self.total_reflectance, precision=4))


def henyey_greenstein(cos_theta, g):
    """The Henyey–Greenstein phase function (per steradian, normalised; thesis eq. 3.5
    corrected) at cosines ``cos_theta`` (any shape, in [-1, 1]), asymmetry -1 < g < 1."""
    mu = to_real_array(cos_theta, "cos_theta")
    flat = np.ascontiguousarray(mu.reshape(-1))
    out = np.empty_like(flat)
    _check(lib.arcus_translucency_henyey_greenstein(to_float(g, "g"), flat.size, _lib.ptr(flat), _lib.ptr(out)))
    return out.reshape(mu.shape)


def fresnel_reflectance(cos_i, n1, n2):
    """The exact unpolarised Fresnel reflectance for light arriving at cos θ = ``cos_i``
    from a medium of index ``n1`` on one of ``n2`` (1 under total internal reflection)."""
    out = c_double()
    _check(lib.arcus_translucency_fresnel_reflectance(to_float(cos_i, "cos_i"), to_float(n1, "n1"),
                                                      to_float(n2, "n2"), byref(out)))
    return out.value


# ---- rendering ------------------------------------------------------------------------

_EXITS = {"thesis": 0, "normalized": 1}
_SCALINGS = {"energy": 0, "thesis": 1}
_GATHERS = {"hierarchical": 0, "brute_force": 1}
_CAMERA_KEYS = ("position", "look_at", "up", "vfov_deg", "width", "height")


@dataclass(eq=False)  # element-wise array comparison has no single truth value
class Rendered:
    """A render of :func:`render`: ``image`` (height, width, 3) float32 linear RGB
    radiance (0 where the mesh is not seen), ``subsurface`` its eq. 3.6 part alone,
    ``covered`` (height, width) bool, ``stats`` (samples, their spacing in mm, the
    surface's area, covered pixels, tree nodes, nodes visited per pixel, seconds per
    stage), ``features`` (the kernel features compiled) and ``seconds``."""
    image: np.ndarray
    subsurface: np.ndarray
    covered: np.ndarray
    stats: dict = field(default_factory=dict)
    features: frozenset = frozenset()
    seconds: float = 0.0


def _lights(lights):
    """``lights`` as a ctypes array: a list of (direction, irradiance) pairs or dicts with
    those keys; irradiance is one number or R, G, B."""
    if isinstance(lights, (tuple, dict)) and not (isinstance(lights, tuple) and lights and
                                                  isinstance(lights[0], (tuple, list, dict, np.ndarray))):
        lights = [lights]
    if not isinstance(lights, (list, tuple)) or not lights:
        raise ArgumentError("lights must be a non-empty list of (direction, irradiance) pairs, got %r" % (lights,))
    array = (_lib.DirectionalLightStruct * len(lights))()
    for i, light in enumerate(lights):
        if isinstance(light, dict):
            unknown = set(light) - {"direction", "irradiance"}
            if unknown or "direction" not in light:
                raise ArgumentError("lights[%d] takes 'direction' and 'irradiance', got %s" % (i, sorted(light)))
            direction, irradiance = light["direction"], light.get("irradiance", 1.0)
        elif isinstance(light, (tuple, list)) and len(light) == 2:
            direction, irradiance = light
        else:
            raise ArgumentError("lights[%d] must be a (direction, irradiance) pair or a dict, got %r" % (i, light))
        array[i].direction[:] = list(to_vec3(direction, "lights[%d].direction" % i))
        array[i].irradiance[:] = list(_rgb(irradiance, "lights[%d].irradiance" % i))
    return array


def _camera(params, camera):
    """The camera dict (any of position, look_at, up, vfov_deg, width, height) over the
    defaults of ``arcus_translucency_render_params_init``."""
    if camera is None:
        return
    if not isinstance(camera, dict):
        raise ArgumentError("camera must be a dict with keys among %s, got %r" % (", ".join(_CAMERA_KEYS), camera))
    unknown = sorted(set(camera) - set(_CAMERA_KEYS))
    if unknown:
        raise ArgumentError("camera: unknown key(s) %s (known: %s)" % (", ".join(unknown), ", ".join(_CAMERA_KEYS)))
    for key in ("position", "look_at", "up"):
        if key in camera:
            getattr(params.camera, key)[:] = list(to_vec3(camera[key], "camera['%s']" % key))
    if "vfov_deg" in camera:
        params.camera.vfov_deg = to_float(camera["vfov_deg"], "camera['vfov_deg']")
    for key in ("width", "height"):
        if key in camera:
            setattr(params.camera, key, to_int(camera[key], "camera['%s']" % key, 1, 16384))


def render(dipole, mesh, lights, camera=None, *, ortho_height=0.0, mm_per_unit=1.0, exit="thesis",
           profile_scale=1.0, profile_scaling="energy", sample_spacing_mm=0.0, gather="hierarchical",
           max_solid_angle=None, highlight_deg=10.0, out=None, exposure=None, progress=None, context=None):
    """Renders ``mesh`` (a file path, or ``(vertices, triangles)``), made of ``dipole``
    (a :class:`Dipole`, or a tabulated :class:`Profile`), under directional ``lights`` ([(direction toward the light,
    irradiance (one number or R, G, B)), ...]) seen by ``camera`` (a dict of position,
    look_at, up, vfov_deg, width, height in mesh units; defaults: 256², from (0, 0, 5)):
    thesis eq. 3.6–3.8, a :class:`Rendered`.

    ``ortho_height`` > 0 makes the view orthographic, that tall; ``mm_per_unit`` says how
    long a mesh unit is.  ``exit``: "thesis" (eq. 3.6 as written) or "normalized"
    (divided by 1 − 2·FM1, energy-conserving); ``profile_scale``/``profile_scaling``
    stretch the profile (§5.2); ``sample_spacing_mm`` (0: 1/σ′_t) spaces the irradiance
    samples; ``gather``: "hierarchical" (Jensen & Buhler 2002, nodes under
    ``max_solid_angle`` sr taken whole; default 0.1 for a dipole, 0.005 for a table)
    or "brute_force" (the reference);
    ``highlight_deg``: the Phong highlight's angle b (0: none).  ``out``: a path or
    paths to write the image to, in the format each extension names: .exr and .hdr keep
    the radiance, .png and .jpg are scaled by ``exposure`` (default: the 99.5th
    percentile of the object's pixels to 0.9) and sRGB-encoded.
    """
    if not isinstance(dipole, (Dipole, Profile)):
        raise ArgumentError("dipole must be an arcus.translucency.Dipole or Profile, got %r" % (dipole,))
    table = dipole._table() if isinstance(dipole, Profile) else None
    _check_progress(progress)
    light_array = _lights(lights)
    params = _lib.TranslucencyRenderParamsStruct()
    _check(lib.arcus_translucency_render_params_init(byref(params)))
    _camera(params, camera)
    params.ortho_height = to_float(ortho_height, "ortho_height")
    params.mm_per_unit = to_float(mm_per_unit, "mm_per_unit")
    params.exit = to_choice(exit, "exit", _EXITS)
    params.profile_scale = to_float(profile_scale, "profile_scale")
    params.profile_scaling = to_choice(profile_scaling, "profile_scaling", _SCALINGS)
    params.sample_spacing_mm = to_float(sample_spacing_mm, "sample_spacing_mm")
    params.gather = to_choice(gather, "gather", _GATHERS)
    if max_solid_angle is not None:
        params.max_solid_angle = to_float(max_solid_angle, "max_solid_angle")
    params.highlight_deg = to_float(highlight_deg, "highlight_deg")
    outputs = [] if out is None else [out] if isinstance(out, (str, os.PathLike)) else list(out)
    for i, path in enumerate(outputs):
        to_path(path, "out[%d]" % i)
    with _owned_context(context) as ctx:
        mesh_handle = _mesh_handle(ctx, mesh)
        t0 = time.perf_counter()
        try:
            def start(callback, job_out):
                params.progress = callback
                if table is not None:
                    return lib.arcus_translucency_render_table(ctx._handle, mesh_handle, byref(table),
                                                               len(light_array), light_array, byref(params), job_out)
                return lib.arcus_translucency_render(ctx._handle, mesh_handle, byref(dipole._struct),
                                                     len(light_array), light_array, byref(params), job_out)

            def read(job):
                stats = _lib.TranslucencyRenderStatsStruct()
                ctx._check(lib.arcus_job_get_translucency_stats(job, byref(stats)))
                h, w = stats.height, stats.width
                rgb, sub = np.empty((h, w, 3), np.float32), np.empty((h, w, 3), np.float32)
                covered = np.empty((h, w), np.uint8)
                ctx._check(lib.arcus_job_get_translucency_image(job, _lib.ptr(rgb, c_float), _lib.ptr(sub, c_float),
                                                                _lib.ptr(covered, c_uint8)))
                bits = c_uint64()
                ctx._check(lib.arcus_job_get_features(job, byref(bits)))
                named = {name: getattr(stats, name) for name, _ in stats._fields_ if name not in ("width", "height")}
                return rgb, sub, covered.astype(bool), named, _lib.feature_names(bits.value)

            rgb, sub, covered, stats, features = ctx._run_job(start, progress, False, "arcus_translucency_render",
                                                              reader=read)
        finally:
            lib.arcus_mesh_release(mesh_handle)
    if exposure is None:
        seen = rgb[covered].max(axis=1) if covered.any() else np.zeros(1)
        top = float(np.percentile(seen, 99.5))
        exposure = 0.9 / top if top > 0 else 1.0
    exposure = to_float(exposure, "exposure")
    for path in outputs:
        eight_bit = os.fspath(path).lower().endswith((".png", ".jpg", ".jpeg"))
        image.write(path, rgb * exposure if eight_bit else rgb)
    return Rendered(image=rgb, subsurface=sub, covered=covered, stats=stats, features=features,
                    seconds=time.perf_counter() - t0)


# ---- estimation from a photograph -------------------------------------------------------

_FIT_TO = {"image": 0, "profile": 1}
_HERMITE_SAMPLES = 4096
#: Table 3.2's families of basis functions (arcus_profile_basis).
BASIS_FAMILIES = {"piecewise_constant": 0, "haar": 1, "gaussian": 2, "hermite": 3, "legendre": 4}


@dataclass(eq=False)
class Estimate:
    """A BSSRDF estimated from one photograph (:func:`estimate_bssrdf`, thesis §3.3.1):
    ``dipole`` (a :class:`Dipole` fitted per channel), ``profile`` (``edges`` (m + 1,)
    mm and ``weights`` (m, 3) per mm²: the piecewise-constant R_d), ``condition``
    ({"A": (3,), "AtA": (3,)} condition numbers), ``solve`` (QMR iterations, residuals,
    dropped columns, the fit's relative error, per channel), ``pixels`` (the downscaled
    size, |𝕆| and |𝕀|), ``highlight_cut``, ``minimum_subtracted`` and ``timings``
    (seconds per stage); ``hermite``, §3.4's plausible profile (a :class:`Profile`:
    monotone, differentiable, through the bins, keeping their energy); ``fitted``, the
    one ``fit`` named; ``system``, when asked for with ``keep_system=True``: per
    channel the assembled ``A`` (3, n, m) per mm², ``b`` (3, n), the weights ``x`` (3, m),
    and what A is made of, in mm: ``rows`` (n, 3), ``sources`` (s, 3),
    ``source_weights`` (s, 3), ``near_irradiance`` (n, 3), ``near_radius_mm``, and the
    front sources' sub-pixel points ``sub_sources`` and ``sub_source_weights`` (k, 3),
    which stand for them from ``near_radius_mm`` to ``refined_radius_mm``."""
    dipole: "Dipole"
    profile: tuple
    condition: dict
    solve: dict
    pixels: dict
    highlight_cut: float
    minimum_subtracted: np.ndarray
    timings: dict
    features: frozenset = frozenset()
    system: dict = None
    hermite: "Profile" = None
    fit: str = "dipole"
    lights: "LightDetection" = None
    shape: "PhotoShape" = None
    relief: tuple = None

    @property
    def fitted(self):
        """The model asked for with ``fit``: :attr:`dipole` or :attr:`hermite`."""
        return self.hermite if self.fit == "hermite" else self.dipole


def _system(ctx, job, r):
    """The estimate's linear system and what it is assembled from (Estimate.system)."""
    n, m, s = r.equation_pixels, r.basis_count, 2 * r.object_pixels
    a, b, x = np.empty((3, n, m)), np.empty((3, n)), np.empty((3, m))
    for c in range(3):
        ctx._check(lib.arcus_job_get_translucency_system(job, c, _lib.ptr(a[c]), _lib.ptr(b[c]), _lib.ptr(x[c])))
    rows, sources, weights, near = np.empty((n, 3)), np.empty((s, 3)), np.empty((s, 3)), np.empty((n, 3))
    ctx._check(lib.arcus_job_get_translucency_sources(job, _lib.ptr(rows), _lib.ptr(sources), _lib.ptr(weights),
                                                      _lib.ptr(near)))
    sub, sub_weights = np.empty((r.sub_source_count, 3)), np.empty((r.sub_source_count, 3))
    ctx._check(lib.arcus_job_get_translucency_sub_sources(job, _lib.ptr(sub), _lib.ptr(sub_weights)))
    return {"A": a, "b": b, "x": x, "rows": rows, "sources": sources, "source_weights": weights,
            "near_irradiance": near, "near_radius_mm": r.near_radius_mm, "sub_sources": sub,
            "sub_source_weights": sub_weights, "refined_radius_mm": r.refined_radius_mm}


def estimate_bssrdf(photo, mesh=None, lights=None, camera=None, *, basis=24, family="piecewise_constant",
                    fit="dipole", fit_to="image", ortho_height=0.0, mm_per_unit=1.0, eta=1.3, exit="thesis",
                    r_max_mm=0.0, max_side=200, matte=None, remove_highlights=None, subtract_minimum=True,
                    tikhonov=0.0, nonnegative=None, keep_system=False, mm_per_pixel=1.0, irradiance=1.0, shape=None,
                    progress=None, context=None):
    """Estimates the BSSRDF of the object in ``photo`` (an HDR file or an (h, w, 3)
    array of linear radiance) from its ``mesh`` (a path or ``(vertices, triangles)``),
    its directional ``lights`` and ``camera`` (as :func:`render`; the camera's size is
    the photo's): an :class:`Estimate`.  ``basis`` functions of ``family`` (one of
    :data:`BASIS_FAMILIES`, Table 3.2) up to ``r_max_mm`` (0: the object's diameter);
    ``tikhonov`` (λ: λ × the mean diagonal of AᵀA added to it) and ``nonnegative``
    (weights >= 0), both off as in the thesis (``nonnegative`` is on for the photo
    alone); ``fit``: "dipole" or "hermite" (§3.4's
    monotone cubic Hermite profile; both are computed, ``fit`` picks ``.fitted``);
    ``fit_to``: "image" (the pixels the dipole predicts) or "profile" (the bins, as the
    thesis); ``matte``: an (h, w) array, non-zero on the object (default: the mesh's
    projection).

    With neither ``mesh`` nor ``lights`` (thesis §3.4, an uncontrolled photograph) both
    come from the photo: :func:`detect_lights`, :func:`estimate_shape` (``shape``: a
    dict of its keyword arguments) and a closed mesh from the depth, seen
    orthographically at ``mm_per_pixel``; ``irradiance`` (one number or R, G, B) is the
    lights' summed irradiance, which a photo cannot give.  The result's ``lights``,
    ``shape`` and ``relief`` (the mesh, in pixels) say what the photo gave; its dipole is
    approximate there and ``fit`` defaults to the Hermite profile."""
    automatic = mesh is None and lights is None
    if not automatic and (mesh is None or lights is None):
        raise ArgumentError("give both mesh and lights, or neither (the photo alone, thesis §3.4)")
    if automatic and fit == "dipole":
        fit = "hermite"
    if fit not in ("dipole", "hermite"):
        raise ArgumentError("fit must be 'dipole' or 'hermite' (§3.4's monotone cubic Hermite), got %r" % (fit,))
    _check_progress(progress)
    pixels = _photo(photo, eight_bit="warn" if automatic else "refuse")
    height, width = pixels.shape[:2]
    whole = _lib.TranslucencyAutoParamsStruct()
    _check(lib.arcus_translucency_auto_params_init(byref(whole)))
    if not automatic:  # §3.3.1's defaults, not the photo-alone ones
        _check(lib.arcus_translucency_estimate_params_init(byref(whole.estimate)))
    params = whole.estimate
    if automatic:
        whole.mm_per_pixel = to_float(mm_per_pixel, "mm_per_pixel")
        whole.irradiance = (c_double * 3)(*_rgb(irradiance, "irradiance"))
        shape_params_into(whole.shape, shape or {})
    else:
        light_array = _lights(lights)
        _camera(params, dict(camera or {}, width=width, height=height))
        params.ortho_height = to_float(ortho_height, "ortho_height")
        params.mm_per_unit = to_float(mm_per_unit, "mm_per_unit")
    params.eta = to_float(eta, "eta")
    params.exit = to_choice(exit, "exit", _EXITS)
    params.basis_count = to_int(basis, "basis", 2, 64)
    params.basis = to_choice(family, "family", BASIS_FAMILIES)
    params.tikhonov = to_float(tikhonov, "tikhonov")
    if nonnegative is not None:  # else the default: off, as the thesis; on for the photo alone
        params.nonnegative = int(bool(nonnegative))
    params.fit = to_choice(fit_to, "fit_to", _FIT_TO)
    params.r_max_mm = to_float(r_max_mm, "r_max_mm")
    params.max_side = to_int(max_side, "max_side", 8, 4096)
    if remove_highlights is not None:  # else on, as the thesis; off for the photo alone
        params.remove_highlights = int(bool(remove_highlights))
    params.subtract_minimum = int(bool(subtract_minimum))
    matte_array = _matte(matte, height, width)
    t0 = time.perf_counter()
    matte_pointer = None if matte_array is None else _lib.ptr(matte_array, c_uint8)
    with _owned_context(context) as ctx:
        mesh_handle = None if automatic else _mesh_handle(ctx, mesh)
        try:
            def start(callback, job_out):
                params.progress = callback
                if automatic:
                    return lib.arcus_translucency_estimate_auto(ctx._handle, width, height, _lib.ptr(pixels, c_float),
                                                                matte_pointer, byref(whole), job_out)
                return lib.arcus_translucency_estimate(ctx._handle, mesh_handle, width, height,
                                                       _lib.ptr(pixels, c_float), matte_pointer,
                                                       len(light_array), light_array, byref(params), job_out)

            def read(job):
                r = _lib.TranslucencyEstimateResultStruct()
                ctx._check(lib.arcus_job_get_translucency_estimate(job, byref(r)))
                edges, weights = np.empty(r.basis_count + 1), np.empty((r.basis_count, 3))
                ctx._check(lib.arcus_job_get_translucency_profile(job, _lib.ptr(edges), _lib.ptr(weights)))
                bits = c_uint64()
                ctx._check(lib.arcus_job_get_features(job, byref(bits)))
                hermite = np.empty((_HERMITE_SAMPLES, 3))
                ctx._check(lib.arcus_job_get_translucency_hermite(job, _HERMITE_SAMPLES, _lib.ptr(hermite)))
                return (r, edges, weights, hermite, _lib.feature_names(bits.value),
                        _system(ctx, job, r) if keep_system else None,
                        automatic_outputs(ctx, job, height, width) if automatic else {})

            r, edges, weights, hermite, features, system, found = ctx._run_job(
                start, progress, False, "arcus_translucency_estimate", reader=read)
        finally:
            if mesh_handle is not None:
                lib.arcus_mesh_release(mesh_handle)
    seconds = time.perf_counter() - t0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a channel outside diffusion is reported by .dipole.diffusive
        dipole = Dipole(r.dipole.sigma_a[:], r.dipole.sigma_s_prime[:], r.dipole.eta)
    return Estimate(
        dipole=dipole, profile=(edges, weights),
        condition={"A": np.array(r.condition_a[:]), "AtA": np.array(r.condition_normal[:])},
        solve={"iterations": np.array(r.iterations[:]), "residual": np.array(r.residual[:]),
               "dropped_columns": np.array(r.dropped_columns[:]), "fit_error": np.array(r.fit_error[:]),
               "image_error": np.array(r.image_error[:])},
        pixels={"width": r.width, "height": r.height, "object": r.object_pixels, "equations": r.equation_pixels},
        highlight_cut=r.highlight_cut, minimum_subtracted=np.array(r.minimum_subtracted[:]),
        timings={"geometry": r.geometry_seconds, "histograms": r.histogram_seconds, "solve": r.solve_seconds,
                 "total": seconds},
        features=features, system=system, hermite=Profile(r.r_max_mm, hermite, r.dipole.eta), fit=fit, **found)

