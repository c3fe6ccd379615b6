"""Underwater light (thesis §3.5, §4.2, §5.3): water, spectral photon tracing, profiles.

::

    import arcus.ocean as ocean

    water = ocean.Water("baltic")                       # a preset, or Water(chlorophyll=0.5, ...)
    result = ocean.trace_photons(water, ocean.Light.point((0, 0, -5), 1.0), photons=400_000)
    print(result.tallies["absorbed"], result.absorbed_by_interaction)
    prof = ocean.profile(water, sun_zenith=30, depths=[0, 1, 2, 5, 10])
    print(prof.Ed[:, prof.wavelengths == 550])

Water is a description (plain Python values); each call creates the library's objects
on a context (``context=`` one of yours, else a new one on the default device).
Spectra are a number (flat), a pair ``(wavelengths_nm, values)`` or a dict with keys
``nm`` and ``values``.  Units: metres, nanometres, watts.
"""

import ctypes
import json
import math
import os
import tempfile
from ctypes import byref, c_double, c_int32, c_size_t, c_uint64, c_void_p
from dataclasses import dataclass, field

import numpy as np

from . import _lib, _scene_file
from ._args import to_path
from ._errors import ArgumentError
from ._lib import lib
from .context import _check_progress, _owned_context

#: The ten events of the thesis' roulette (§4.2), in its order.
EVENTS = ("absorb_water", "raman", "absorb_detritus", "absorb_phyto", "fluoresce_phyto", "absorb_cdom",
          "fluoresce_cdom", "scatter_water", "scatter_detritus", "scatter_phyto")
#: The constituents of arcus_water_get_coefficients' absorption and scattering rows.
CONSTITUENTS = ("water", "detritus", "phytoplankton", "cdom")
PRESETS = ("atlantic", "mediterranean", "baltic", "north_sea", "cdom_coastal")
_PHASES = dict(isotropic=0, rayleigh_like=1, hg=2, two_term_hg=3, table=4)
_LIGHTS = dict(point=0, spot=1, directional=2, sky=3)


class _Keep:
    """Keeps the numpy arrays behind ctypes pointers alive for one call."""

    def __init__(self):
        self.arrays = []

    def doubles(self, values, name):
        a = np.ascontiguousarray(np.asarray(values, dtype=np.float64).ravel())
        self.arrays.append(a)
        return a

    def spectrum(self, spec, name):
        s = _lib.SpectrumStruct()
        if isinstance(spec, dict):
            try:
                spec = (spec["nm"], spec["values"])
            except KeyError as exc:
                raise ArgumentError("%s: a spectrum dict needs 'nm' and 'values'" % name) from exc
        if isinstance(spec, (int, float)):
            nm, values = [550.0], [float(spec)]
        else:
            try:
                nm, values = spec
            except (TypeError, ValueError) as exc:
                raise ArgumentError("%s: a number, (wavelengths, values) or {'nm': ..., 'values': ...}" % name) \
                    from exc
        nm, values = self.doubles(nm, name + ".nm"), self.doubles(values, name + ".values")
        if nm.size != values.size:
            raise ArgumentError("%s: %d wavelengths but %d values" % (name, nm.size, values.size))
        s.count = nm.size
        s.nm = _lib.ptr(nm)
        s.values = _lib.ptr(values)
        return s

    def phase(self, phase, name):
        """A phase function: "isotropic", ("hg", g), ("two_term_hg", g_f, g_b, zeta),
        ("rayleigh_like", a), ("table", cosines, values), or None (isotropic)."""
        p = _lib.PhaseFunctionStruct()
        if phase is None:
            phase = "isotropic"
        if isinstance(phase, str):
            phase = (phase,)
        kind = phase[0]
        if kind not in _PHASES:
            raise ArgumentError("%s: unknown phase function %r (expected one of %s)"
                                % (name, kind, ", ".join(_PHASES)))
        p.kind = _PHASES[kind]
        args = phase[1:]
        try:
            if kind == "hg":
                (p.g_forward,) = args
            elif kind == "two_term_hg":
                p.g_forward, p.g_backward, p.forward_weight = args
            elif kind == "rayleigh_like":
                (p.a,) = args
            elif kind == "table":
                cos, val = self.doubles(args[0], name), self.doubles(args[1], name)
                if cos.size != val.size:
                    raise ArgumentError("%s: %d cosines but %d values" % (name, cos.size, val.size))
                p.table_count = cos.size
                p.table_cosines = _lib.ptr(cos)
                p.table_values = _lib.ptr(val)
        except (TypeError, ValueError) as exc:
            raise ArgumentError("%s: wrong parameters for %r: %r" % (name, kind, args)) from exc
        return p


class Water:
    """Water by the bio-optical model: ``Water(preset=None, **parameters)`` with the
    parameters of ``arcus_bio_optical`` (chlorophyll, a_d400, a_y440, s_d, s_y,
    chlorophyll_yield, cdom_yield_scale, raman_scale, ...), starting from the thesis'
    values or a preset's; or by inherent optical properties: :meth:`from_iops`."""

    def __init__(self, preset=None, **parameters):
        bio = _lib.BioOpticalStruct()
        if preset is None:
            _lib.check(lib.arcus_bio_optical_init(byref(bio)))
        else:
            if not isinstance(preset, str):
                raise ArgumentError("preset: a name among %s, got %r" % (", ".join(PRESETS), preset))
            _lib.check(lib.arcus_bio_optical_preset(preset.encode(), byref(bio)))
        self.preset = preset
        self._iops = None
        names = [f for f, _ in _lib.BioOpticalStruct._fields_ if f not in ("detritus_phase", "stokes_only")]
        names.append("anti_stokes")
        self.parameters = {n: getattr(bio, n) for n in names[:-1]}
        self.parameters["anti_stokes"] = not bio.stokes_only
        for key, value in parameters.items():
            if key not in self.parameters:
                raise ArgumentError("Water: unknown parameter %r (expected one of %s)" % (key, ", ".join(names)))
            if key == "anti_stokes":
                self.parameters[key] = bool(value)
                continue
            try:
                self.parameters[key] = float(value)
            except (TypeError, ValueError) as exc:
                raise ArgumentError("Water: %s must be a number, got %r" % (key, value)) from exc
        self._detritus_phase = bio.detritus_phase

    @classmethod
    def from_iops(cls, absorption, scattering, phase=("hg", 0.9), raman=False, chlorophyll=0.0,
                  chlorophyll_yield=0.1, a_y440=0.0, s_y=0.014, anti_stokes=True):
        """Water given by absorption and scattering spectra [1/m] and a phase function,
        optionally with Raman and the fluorescent constituents added."""
        w = cls.__new__(cls)
        w.preset = None
        w.parameters = {}
        w._iops = dict(absorption=absorption, scattering=scattering, phase=phase, raman=bool(raman),
                       chlorophyll=float(chlorophyll), chlorophyll_yield=float(chlorophyll_yield),
                       a_y440=float(a_y440), s_y=float(s_y), anti_stokes=bool(anti_stokes))
        return w

    def __repr__(self):
        if self._iops is not None:
            return "Water.from_iops(...)"
        return "Water(%r, %s)" % (self.preset, ", ".join("%s=%g" % kv for kv in self.parameters.items()))

    def _create(self, ctx):
        """The library's water on ``ctx`` (an arcus.Context): a handle to release."""
        keep = _Keep()
        out = c_void_p()
        if self._iops is None:
            bio = _lib.BioOpticalStruct()
            for k, v in self.parameters.items():
                if k == "anti_stokes":
                    bio.stokes_only = int(not v)
                else:
                    setattr(bio, k, v)
            bio.detritus_phase = self._detritus_phase
            ctx._check(lib.arcus_water_create(ctx._handle, byref(bio), byref(out)))
        else:
            o = self._iops
            s = _lib.WaterIopsStruct()
            s.absorption = keep.spectrum(o["absorption"], "absorption")
            s.scattering = keep.spectrum(o["scattering"], "scattering")
            s.phase = keep.phase(o["phase"], "phase")
            s.raman = int(o["raman"])
            s.chlorophyll, s.chlorophyll_yield = o["chlorophyll"], o["chlorophyll_yield"]
            s.a_y440, s.s_y = o["a_y440"], o["s_y"]
            s.stokes_only = int(not o["anti_stokes"])
            ctx._check(lib.arcus_water_create_iops(ctx._handle, byref(s), byref(out)))
        return out

    def coefficients(self, grid=(380.0, 780.0, 5.0), context=None):
        """The model on a wavelength grid (first, last, step nm): a dict with
        ``wavelengths``, ``events`` (10 × n, the roulette's coefficients [1/m], rows in
        :data:`EVENTS` order), ``absorption`` and ``scattering`` (4 × n, rows in
        :data:`CONSTITUENTS` order), ``extinction``."""
        g = _grid(grid)
        with _owned_context(context) as ctx:
            handle = self._create(ctx)
            try:
                n = g.count
                events, absorption, scattering = np.zeros((10, n)), np.zeros((4, n)), np.zeros((4, n))
                ctx._check(lib.arcus_water_get_coefficients(handle, byref(g), _lib.ptr(events),
                                                            _lib.ptr(absorption), _lib.ptr(scattering)))
            finally:
                lib.arcus_water_release(handle)
        return dict(wavelengths=g.first_nm + g.step_nm * np.arange(g.count), events=events, absorption=absorption,
                    scattering=scattering, extinction=events.sum(axis=0))


def _grid(grid):
    """A WavelengthGridStruct from (first, last, step) nm; a single wavelength for first = last."""
    try:
        first, last, step = (float(x) for x in grid)
    except (TypeError, ValueError) as exc:
        raise ArgumentError("grid: (first_nm, last_nm, step_nm), got %r" % (grid,)) from exc
    if not (step > 0 and last >= first):
        raise ArgumentError("grid: needs step > 0 and last >= first, got %r" % (grid,))
    count = int(round((last - first) / step)) + 1
    return _lib.WavelengthGridStruct(first, step, count)


@dataclass(frozen=True)
class Light:
    """A light: use :meth:`point`, :meth:`spot`, :meth:`directional` or :meth:`sky`."""

    kind: str
    spectrum: object
    position: tuple = (0.0, 0.0, 0.0)
    direction: tuple = (0.0, 0.0, -1.0)
    half_angle_deg: float = 30.0
    radius: float = 0.0

    @classmethod
    def point(cls, position, spectrum):
        """Isotropic from ``position``; ``spectrum`` in W/nm."""
        return cls("point", spectrum, tuple(position))

    @classmethod
    def spot(cls, position, direction, half_angle_deg, spectrum):
        return cls("spot", spectrum, tuple(position), tuple(direction), float(half_angle_deg))

    @classmethod
    def directional(cls, direction, spectrum, position=(0.0, 0.0, 0.0), radius=0.0):
        """A parallel beam; W/m²/nm (per m² of surface in a column with a surface)."""
        return cls("directional", spectrum, tuple(position), tuple(direction), radius=float(radius))

    @classmethod
    def sun(cls, zenith_deg, spectrum, azimuth_deg=0.0):
        """Sunlight from ``zenith_deg`` onto a flat surface (a directional light)."""
        z, a = math.radians(zenith_deg), math.radians(azimuth_deg)
        return cls.directional((-math.sin(z) * math.cos(a), -math.sin(z) * math.sin(a), -math.cos(z)), spectrum)

    @classmethod
    def sky(cls, spectrum):
        """Uniform sky radiance onto the surface; W/m²/nm of plane irradiance."""
        return cls("sky", spectrum)

    def _struct(self, keep, name):
        if self.kind not in _LIGHTS:
            raise ArgumentError("%s: unknown light kind %r" % (name, self.kind))
        s = _lib.OceanLightStruct()
        s.kind = _LIGHTS[self.kind]
        s.position = (c_double * 3)(*self.position)
        s.direction = (c_double * 3)(*self.direction)
        s.half_angle_deg = self.half_angle_deg
        s.radius = self.radius
        s.spectrum = keep.spectrum(self.spectrum, name + ".spectrum")
        return s


@dataclass(frozen=True)
class TraceResult:
    """What a photon trace found: ``tallies`` (dict: emitted, absorbed, escaped,
    past_limit, bottom [W], photons, interactions, stored; and per event in
    :data:`EVENTS` order ``count``, ``arriving``, ``absorbed_by``), energy
    ``absorbed_by_interaction`` and ``escaped_by_interaction`` (index j: at / after the
    j-th interaction; thesis Fig. 5.9), ``wavelengths`` and ``depths`` with the
    irradiances ``Ed``, ``Eu``, ``E0`` [W/m²/nm] (depth × wavelength) when depths were
    asked for, the stored ``photons`` (dict of arrays) when asked for, ``features`` (the
    kernel features compiled) and ``stats``."""

    tallies: dict
    absorbed_by_interaction: np.ndarray
    escaped_by_interaction: np.ndarray
    wavelengths: np.ndarray
    depths: np.ndarray
    Ed: np.ndarray
    Eu: np.ndarray
    E0: np.ndarray
    photons: dict
    features: frozenset
    stats: dict = field(default_factory=dict)

    def per_constituent(self):
        """Energy absorbed (inelastic: the energy difference) and scattered per
        constituent (thesis Fig. 5.12): {constituent: {"absorbed": W, "scattered": W}}."""
        t = self.tallies
        absorbed, arriving = t["absorbed_by"], t["arriving"]
        groups = dict(water=(0, 1, 7), detritus=(2, 8), phytoplankton=(3, 4, 9), cdom=(5, 6))
        out = {}
        for name, events in groups.items():
            out[name] = dict(absorbed=float(sum(absorbed[e] for e in events)),
                             scattered=float(sum(arriving[e] for e in events if e in (1, 4, 6, 7, 8, 9))))
        return out


def trace_photons(water, light, photons=400_000, max_interactions=5, seed=1, *, grid=(380.0, 780.0, 5.0),
                  store=False, depths=None, layer=0.1, surface=False, n_water=1.34, bottom_depth=math.inf,
                  bottom_albedo=0.0, box=None, force_inelastic=False, wavelengths_per_photon=4, progress=None,
                  context=None):
    """Traces ``photons`` spectral photons from ``light`` (a :class:`Light` or a list)
    through ``water`` (thesis §4.2): a :class:`TraceResult`.

    ``box``: ((x0, y0, z0), (x1, y1, z1)) bounds photons leave through; ``surface``: a
    flat air–water surface at z = 0 with water below; ``depths``: irradiance tallies of
    a plane-parallel column (needs the surface, or a box whose top is z = 0);
    ``wavelengths_per_photon``: 1..4, what each stored photon carries (hero wavelengths:
    the largest divisor of the grid's sample count not above it; 1: the thesis' one)."""
    if not isinstance(water, Water):
        raise ArgumentError("water: an arcus.ocean.Water, got %r" % (water,))
    _check_progress(progress)
    lights = list(light) if isinstance(light, (list, tuple)) else [light]
    keep = _Keep()
    setup = _lib.OceanSetupStruct()
    _lib.check(lib.arcus_ocean_setup_init(byref(setup)))
    setup.grid = _grid(grid)
    structs = (_lib.OceanLightStruct * max(1, len(lights)))()
    for i, L in enumerate(lights):
        if not isinstance(L, Light):
            raise ArgumentError("light[%d]: an arcus.ocean.Light, got %r" % (i, L))
        structs[i] = L._struct(keep, "lights[%d]" % i)
    setup.light_count = len(lights)
    setup.lights = structs
    setup.surface = int(bool(surface))
    setup.n_water, setup.bottom_depth, setup.bottom_albedo = n_water, bottom_depth, bottom_albedo
    if box is not None:
        setup.box_lo = (c_double * 3)(*box[0])
        setup.box_hi = (c_double * 3)(*box[1])
    depth_array = keep.doubles([] if depths is None else depths, "depths")
    setup.depth_count = depth_array.size
    setup.depths = _lib.ptr(depth_array) if depth_array.size else None
    setup.layer = layer
    params = _lib.OceanTraceParamsStruct()
    _lib.check(lib.arcus_ocean_trace_params_init(byref(params)))
    params.photons, params.max_interactions, params.seed = int(photons), int(max_interactions), int(seed)
    params.store_photons, params.force_inelastic = int(bool(store)), int(bool(force_inelastic))
    if not (isinstance(wavelengths_per_photon, int) and 1 <= wavelengths_per_photon <= 4):
        raise ArgumentError("wavelengths_per_photon: must be an integer in 1..4, got %r" % (wavelengths_per_photon,))
    params.wavelengths_per_photon = wavelengths_per_photon

    with _owned_context(context) as ctx:
        handle = water._create(ctx)
        try:
            def start(callback, job_out):
                params.progress = callback
                return lib.arcus_ocean_trace(ctx._handle, handle, byref(setup), byref(params), job_out)

            def read(job):
                return _read_trace(ctx, job, setup.grid, depth_array, bool(store))

            return ctx._run_job(start, progress, False, "arcus_ocean_trace", reader=read)
        finally:
            lib.arcus_water_release(handle)


def _read_trace(ctx, job, grid, depths, store):
    t = _lib.OceanTalliesStruct()
    ctx._check(lib.arcus_job_get_ocean_tallies(job, byref(t)))
    tallies = {name: getattr(t, name) for name, _ in t._fields_ if name not in ("count", "arriving", "absorbed_by")}
    for name in ("count", "arriving", "absorbed_by"):
        tallies[name] = np.array(getattr(t, name)[:])
    m = t.interaction_bins + 1
    absorbed, escaped = np.zeros(m), np.zeros(m)
    ctx._check(lib.arcus_job_get_ocean_by_interaction(job, _lib.ptr(absorbed), _lib.ptr(escaped)))
    n = grid.count
    shape = (depths.size, n)
    ed, eu, e0 = np.zeros(shape), np.zeros(shape), np.zeros(shape)
    if depths.size:
        ctx._check(lib.arcus_job_get_ocean_irradiance(job, _lib.ptr(ed), _lib.ptr(eu), _lib.ptr(e0)))
    photons = {}
    if store:
        count = c_size_t()
        ctx._check(lib.arcus_job_get_ocean_photons(job, byref(count), None, None, None, None, None))
        k = count.value
        photons = dict(positions=np.zeros((k, 3)), directions=np.zeros((k, 3)), powers=np.zeros(k),
                       wavelengths=np.zeros(k), events=np.zeros(k, dtype=np.int32))
        ctx._check(lib.arcus_job_get_ocean_photons(
            job, byref(count), _lib.ptr(photons["positions"]), _lib.ptr(photons["directions"]),
            _lib.ptr(photons["powers"]), _lib.ptr(photons["wavelengths"]), _lib.ptr(photons["events"], c_int32)))
    features = c_uint64()
    ctx._check(lib.arcus_job_get_features(job, byref(features)))
    stats = _lib.JobStatsStruct()
    ctx._check(lib.arcus_job_get_stats(job, byref(stats)))
    return TraceResult(tallies=tallies, absorbed_by_interaction=absorbed, escaped_by_interaction=escaped,
                       wavelengths=grid.first_nm + grid.step_nm * np.arange(n), depths=depths.copy(), Ed=ed, Eu=eu,
                       E0=e0, photons=photons, features=_lib.feature_names(features.value),
                       stats={name: getattr(stats, name) for name, _ in stats._fields_})


def profile(water, sun_zenith, depths, *, photons=400_000, grid=(380.0, 780.0, 5.0), sun=1.0, sky=0.0,
            surface=True, n_water=1.34, bottom_depth=math.inf, bottom_albedo=0.0, layer=None, seed=1,
            max_interactions=10_000, progress=None, context=None):
    """Irradiance profiles of a plane-parallel column, as oceanographers use them: the
    sun at ``sun_zenith`` degrees (``sun``: its plane irradiance on the horizontal
    surface, W/m²/nm) and optionally a uniform sky (``sky``, W/m²/nm of plane
    irradiance) above a flat surface with Fresnel transmission (``surface=False``: the
    beam starts just below a free top, no interface, at ``sun_zenith`` in the water).
    Photons are followed until absorbed or gone (``max_interactions``, 10 000, is a
    safety net).  Returns the :class:`TraceResult`, with ``Ed``, ``Eu``, ``E0`` and
    :func:`diffuse_attenuation` for K_d."""
    lights = [Light.sun(sun_zenith, sun)]
    if sky:
        lights.append(Light.sky(sky))
    depths = np.asarray(depths, dtype=np.float64)
    if layer is None:
        spacing = np.diff(np.unique(depths))
        layer = float(min(0.1, 0.2 * spacing.min())) if spacing.size else 0.1
    box = None if surface else ((-math.inf, -math.inf, -math.inf), (math.inf, math.inf, 0.0))
    return trace_photons(water, lights, photons, max_interactions, seed, grid=grid, depths=depths, layer=layer,
                         surface=surface, n_water=n_water, bottom_depth=bottom_depth, bottom_albedo=bottom_albedo,
                         box=box, progress=progress, context=context)


def diffuse_attenuation(depths, irradiance):
    """K_d between successive depths: −d ln E / dz (per wavelength column)."""
    depths = np.asarray(depths, dtype=np.float64)
    e = np.asarray(irradiance, dtype=np.float64)
    with np.errstate(divide="ignore", invalid="ignore"):
        return -np.diff(np.log(e), axis=0) / np.diff(depths)[:, None]


@dataclass(frozen=True)
class OceanImage:
    """A rendered underwater image: ``image`` (H, W, 3) linear sRGB float32, ``spectral``
    (H, W, n) radiance [W/m²/sr/nm] at ``wavelengths``, ``stats`` (per-stage seconds,
    photons stored), ``features`` (kernel features compiled), ``tallies`` (where the
    photons' energy went)."""

    image: np.ndarray
    spectral: np.ndarray
    wavelengths: np.ndarray
    stats: dict
    features: frozenset
    tallies: dict


def _read_image(ctx, job, exr, png, spectral_bands):
    w, h, n = ctypes.c_uint32(), ctypes.c_uint32(), ctypes.c_uint32()
    ctx._check(lib.arcus_job_get_ocean_image(job, byref(w), byref(h), byref(n), None, None, None))
    rgb = np.zeros((h.value, w.value, 3), dtype=np.float32)
    spec = np.zeros((h.value, w.value, n.value))
    nm = np.zeros(n.value)
    ctx._check(lib.arcus_job_get_ocean_image(job, None, None, None, _lib.ptr(nm), _lib.ptr(rgb, ctypes.c_float),
                                             _lib.ptr(spec)))
    if exr is not None or png is not None:
        ctx._check(lib.arcus_job_write_ocean_image(job, None if exr is None else to_path(exr, "exr"),
                                                    None if png is None else to_path(png, "png"),
                                                    int(bool(spectral_bands))))
    rs = _lib.OceanRenderStatsStruct()
    ctx._check(lib.arcus_job_get_ocean_render_stats(job, byref(rs)))
    stats = {name: getattr(rs, name) for name, _ in rs._fields_}
    js = _lib.JobStatsStruct()
    ctx._check(lib.arcus_job_get_stats(job, byref(js)))
    stats.update({"kernel_seconds": js.kernel_seconds, "build_seconds": js.build_seconds})
    features = c_uint64()
    ctx._check(lib.arcus_job_get_features(job, byref(features)))
    t = _lib.OceanTalliesStruct()
    ctx._check(lib.arcus_job_get_ocean_tallies(job, byref(t)))
    tallies = {name: getattr(t, name) for name, _ in t._fields_ if name not in ("count", "arriving", "absorbed_by")}
    return OceanImage(image=rgb, spectral=spec, wavelengths=nm, stats=stats,
                      features=_lib.feature_names(features.value), tallies=tallies)


# The thesis' image settings (§5.3): 400 000 photons of one wavelength each, 250 per
# estimate, the estimate at every pixel.  The bundled scenes spend 2 M photons of four
# wavelengths at k = 1250 (the same radius) with the estimate at every fourth pixel:
# a fifth of the noise in half the time (docs/benchmarks.md, "Underwater light").
THESIS_SETTINGS = {"photons": {"count": 400_000, "wavelengths_per_photon": 1},
                   "march": {"k": 250, "estimate_stride": 1}}


def use_thesis_settings(doc):
    """Puts :data:`THESIS_SETTINGS` into an ocean scene's dict, in place."""
    doc.setdefault("photons", {}).update(THESIS_SETTINGS["photons"])
    doc.setdefault("view", {}).setdefault("march", {}).update(THESIS_SETTINGS["march"])


def render(scene, *, photons=None, k=None, steps=None, estimator=None, thesis=False, exr=None, png=None,
           spectral=False, progress=None, context=None):
    """Renders an ocean scene — a file (scenes/README.md, "Ocean scenes"; read and
    checked by the library) or a dict of the same schema — its "view", and returns an
    :class:`OceanImage`; writes ``exr`` (linear; with ``spectral``, a channel per
    wavelength) and ``png`` (sRGB) if given.  ``thesis``: the thesis' settings
    (:data:`THESIS_SETTINGS`) in place of the scene's; then ``photons``, ``k``,
    ``steps``, ``estimator`` ("per_step" or "beam") override."""
    overrides = dict(photons=photons, k=k, steps=steps, estimator=estimator)
    if isinstance(scene, dict) or thesis or any(v is not None for v in overrides.values()):
        # The library reads scene files: a dict, or a file with overrides, goes through
        # a copy (ocean scenes name no other files, so it may live anywhere).
        if isinstance(scene, dict):
            doc = json.loads(json.dumps(scene))
        else:
            doc = _scene_file.read(scene, ("ocean",))[1]  # read and checked by the library
        if thesis:
            use_thesis_settings(doc)
        if photons is not None:
            doc.setdefault("photons", {})["count"] = int(photons)
        march = doc.setdefault("view", {}).setdefault("march", {})
        if k is not None:
            march["k"] = int(k)
        if steps is not None:
            march["steps"] = int(steps)
        if estimator is not None:
            march["estimator"] = estimator
        # Ocean scenes name no other files, so the copy may live anywhere.
        with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
            json.dump(doc, f)
        try:
            return render(f.name, exr=exr, png=png, spectral=spectral, progress=progress, context=context)
        finally:
            os.unlink(f.name)
    _check_progress(progress)
    with _owned_context(context) as ctx:
        handle = c_void_p()
        ctx._check(lib.arcus_scene_load(ctx._handle, to_path(scene, "scene"), byref(handle)))
        try:
            def start(callback, job_out):
                return lib.arcus_ocean_render_scene(handle, callback, None, job_out)

            result = ctx._run_job(start, progress, False, "arcus_ocean_render_scene",
                                  reader=lambda job: _read_image(ctx, job, exr, png, spectral))
        finally:
            lib.arcus_scene_release(handle)
        return result

