"""Rainbows (thesis §2.1.1, §4.4, §5.5): phase functions of single particles.

::

    import numpy as np
    import arcus.rainbow as rainbow

    drop = rainbow.Sphere(250e-6)                        # radius in metres
    theta = np.arange(130.0, 145.0, 0.05)                # degrees from the forward direction
    r = rainbow.phase_function(drop, 650.0, theta, grid=1000, max_bounces=3)
    print(r.unpolarized, r.per_bounce[:, 2], r.refractive_index, r.stats["patches"])

A particle is a description (plain Python values: :class:`Sphere`, :class:`Raindrop`,
:class:`Mesh`, of a file or of arrays); the library's particle is created on a context
the first time it is used there (``context=`` one of yours, else a new one on the
default device).  The library casts a grid of rays at the particle, follows each through p = 0..P
(p − 1 internal reflections) with the phasors of both incident polarisations, and
collects them on a sphere of patches that is queried at the directions asked for,
adding the patches' phasors with their phases (interference) or their intensities.

Units: metres for sizes, nanometres (in vacuum) for wavelengths, kelvin for
temperatures, degrees for angles; the air around a particle has n = 1.
Frame: the light travels along +z; a direction (θ, φ) has θ from +z (0: forward,
180: straight back) and φ from +x toward +y.  Phase functions are per steradian,
normalised so that the light scattered in p = 0..P integrates to 1 over the sphere;
"parallel" and "perpendicular" are the scattered light's components in and normal
to the scattering plane for unpolarised incident light, and "unpolarized" their sum.

Lorenz–Mie and its Debye series, the reference for spheres, are in :mod:`arcus.mie`.
"""

import importlib
import math
import warnings
import weakref
from ctypes import POINTER, byref, c_double, c_size_t, c_uint32, c_uint64, c_void_p
from dataclasses import dataclass

import numpy as np

from . import _lib, _meshes
from ._args import to_bool, to_choice, to_float, to_int, to_path, to_real_array
from ._errors import ArgumentError
from ._lib import lib
from .context import _check_progress, _Handle, _owned_context

#: arcus_material values by name.
MATERIALS = dict(water=0, ice=1, fixed=2)
#: arcus_particle_kind values by name.
PARTICLE_KINDS = {0: "sphere", 1: "raindrop", 2: "mesh"}
#: The most terms P a cast traces (ARCUS_RAINBOW_MAX_BOUNCES).
MAX_BOUNCES = 15
CAUSTICS = dict(uniform="uniform", rays="rays")
POLARIZATIONS = dict(unpolarized="unpolarized", unpolarised="unpolarized", parallel="parallel",
                     perpendicular="perpendicular")

def _material(material, name="material"):
    return to_choice(material, name, MATERIALS)


# ---- refractive index ---------------------------------------------------------------


def water_temperature_k(temperature_k, temperature=None):
    """Water's temperature in kelvin, the unit of every arcus call; ``temperature`` is
    the °C keyword of arcus 0.9, still accepted (with a DeprecationWarning) and
    converted here, at the edge."""
    if temperature is None:
        return to_float(temperature_k, "temperature_k")
    warnings.warn("temperature (°C) is deprecated since arcus 0.10: pass temperature_k in kelvin",
                  DeprecationWarning, stacklevel=3)
    return to_float(temperature, "temperature") + 273.15


def refractive_index(material="water", wavelength=550.0, temperature_k=293.15, *, temperature=None):
    """The real refractive index of ``material`` ("water": IAPWS R9-97 at 1 atm and
    ``temperature_k`` kelvin; "ice": ice Ih) at the vacuum wavelength ``wavelength`` nm,
    relative to the air around it, taken as 1 (thesis §4.4.1.1).

    ``wavelength`` may be a number (a float comes back) or an array (an array of the
    same shape).  A wavelength or temperature outside the formulation's range raises
    :class:`arcus.ArgumentError` naming it."""
    m = _material(material)
    if m == MATERIALS["fixed"]:
        raise ArgumentError("material: 'water' or 'ice' (a fixed index is simply a number), got %r" % (material,))
    t = water_temperature_k(temperature_k, temperature)
    nm = to_real_array(wavelength, "wavelength")
    out = np.empty(nm.shape)
    n = c_double()
    for i, w in np.ndenumerate(nm):
        _lib.check(lib.arcus_rainbow_refractive_index(m, float(w), t, byref(n)))
        out[i] = n.value
    return float(out) if out.ndim == 0 else out


# ---- particles ----------------------------------------------------------------------


class Particle:
    """A particle description; the library's particle is created per context on first
    use (:meth:`info` shows what the library made of it)."""

    kind = None

    def __init__(self):
        # Context state -> its _Handle of this particle.  Weak keys: a context that is
        # gone needs no particle; the context also releases the handle when closed.
        self._handles = weakref.WeakKeyDictionary()

    def _create(self, ctx_handle, out):  # pragma: no cover - overridden
        raise NotImplementedError

    def _handle_on(self, ctx):
        """The library handle of this particle on ``ctx`` (an arcus.Context)."""
        ctx_handle = ctx._handle
        state = ctx._state
        with state.lock:
            handle = self._handles.get(state)
            if handle is None:
                out = c_void_p()
                ctx._check(self._create(ctx_handle, byref(out)))
                handle = _Handle(out.value, lib.arcus_particle_release)
                self._handles[state] = handle
                state.objects.add(handle)  # released with the context at the latest
            return handle.value

    def info(self, context=None):
        """What the library made of the particle: a dict with ``kind``,
        ``equivalent_radius`` (of the sphere of equal volume, m), ``volume`` (m³),
        ``bound_radius`` (m) and ``triangles`` (meshes)."""
        with _owned_context(context) as ctx:
            s = _lib.ParticleInfoStruct()
            ctx._check(lib.arcus_particle_get_info(self._handle_on(ctx), byref(s)))
        d = {name: getattr(s, name) for name, _ in s._fields_}
        d["kind"] = PARTICLE_KINDS.get(s.kind, str(s.kind))
        return d


class Sphere(Particle):
    """A sphere of ``radius`` metres (traced in closed form)."""

    kind = "sphere"

    def __init__(self, radius):
        super().__init__()
        self.radius = to_float(radius, "radius")

    def _create(self, ctx_handle, out):
        return lib.arcus_particle_create_sphere(ctx_handle, self.radius, out)

    def __repr__(self):
        return "Sphere(radius=%r)" % self.radius


class Raindrop(Particle):
    """The thesis' falling raindrop (eq. 4.21, Table 4.4) of equivalent ``diameter``
    metres, 1e-3 to 6e-3: flattened underneath, its symmetry axis its own y (up)."""

    kind = "raindrop"

    def __init__(self, diameter):
        super().__init__()
        self.diameter = to_float(diameter, "diameter")

    def _create(self, ctx_handle, out):
        return lib.arcus_particle_create_raindrop(ctx_handle, self.diameter, out)

    def __repr__(self):
        return "Raindrop(diameter=%r)" % self.diameter


class Mesh(Particle):
    """A closed triangle mesh, its coordinates multiplied by ``scale`` to give metres:
    ``Mesh(path)`` a file (OBJ, PLY, OFF, STL) read by the library,
    :meth:`Mesh.from_arrays` vertices and triangles in memory.  The same vertices and
    triangles give the same particle either way.  The library's mesh is made when the
    particle is first used on a context; a missing file, bad arrays or an open mesh
    raise then.

    ``smooth`` says what the triangles stand for:

    * True (the default): they approximate a smooth surface (a measured drop, a
      tessellated sphere).  Normals and their curvature are interpolated from the
      vertices, so the phase function is the smooth surface's: a fine enough
      icosphere gives a sphere's rainbows.
    * False: the faces really are flat (a crystal).  In one orientation each sequence
      of faces a ray passes through sends all its light into a single direction, a
      peak that no patch between neighbouring rays can hold; so the phase function
      is about zero apart from light falling between such peaks, while the cast's
      ``stats`` (``scattered``) still give each term's power.  This is what flat
      faces do, not a fault; averaging over orientations spreads the peaks out.
    """

    kind = "mesh"

    def __init__(self, path, scale=1.0, smooth=True):
        super().__init__()
        self._path = to_path(path, "path")
        self.path = path
        self.vertices = self.triangles = None
        self.scale = to_float(scale, "scale")
        self.smooth = to_bool(smooth, "smooth")

    @classmethod
    def from_arrays(cls, vertices, triangles, scale=1.0, smooth=True):
        """A mesh of ``vertices`` ((N, 3) real numbers: x y z each, in the units ``scale``
        turns into metres) and ``triangles`` ((M, 3) integers: vertex indices from 0),
        copied: changing the arrays afterwards changes nothing.  Shapes and types are
        checked here; the values (finite coordinates, indices below N, at least one
        triangle, a closed mesh) by the library when the particle is first used, whose
        messages name the C API's flat arrays ("indices[7] = 12 is not below
        vertex_count 10": row 7 // 3, column 7 % 3 of ``triangles``)."""
        v, t = _meshes.mesh_arrays(vertices, triangles)
        mesh = cls.__new__(cls)
        Particle.__init__(mesh)
        mesh._path = mesh.path = None
        mesh.vertices, mesh.triangles = v, t
        mesh.scale = to_float(scale, "scale")
        mesh.smooth = to_bool(smooth, "smooth")
        return mesh

    def _create(self, ctx_handle, out):
        if self.vertices is None:
            return lib.arcus_particle_create_mesh(ctx_handle, self._path, self.scale, int(self.smooth), out)
        mesh = c_void_p()
        status = _meshes.create(ctx_handle, self.vertices, self.triangles, byref(mesh))
        if status != 0:
            return status
        try:  # the particle keeps its own copy of the mesh
            return lib.arcus_particle_create_from_mesh(mesh, self.scale, int(self.smooth), out)
        finally:
            lib.arcus_mesh_release(mesh)

    def __repr__(self):
        if self.vertices is None:
            return "Mesh(%r, scale=%r, smooth=%r)" % (self.path, self.scale, self.smooth)
        return "Mesh.from_arrays(<%d vertices>, <%d triangles>, scale=%r, smooth=%r)" % (
            len(self.vertices), len(self.triangles), self.scale, self.smooth)


# ---- the phase function -------------------------------------------------------------


@dataclass(frozen=True, eq=False)  # element-wise array comparison has no single truth value
class PhaseResult:
    """A particle's phase function from :func:`phase_function` (per steradian; the light
    of p = 0..P integrates to 1 over the sphere).

    Attributes:
        theta: (T,) scattering angles [deg].
        phi: the azimuth [deg] of a 1-D table (a float), or the (F,) azimuths of a 2-D one.
        parallel, perpendicular: (T,) or (T, F): components in and normal to the
            scattering plane, for unpolarised incident light.
        unpolarized: parallel + perpendicular.
        per_bounce: (T, P+1) or (T, F, P+1): term p alone (p − 1 internal reflections),
            unpolarised.  Coherent, the terms interfere with one another too, so they
            need not add up to ``unpolarized``; incoherent, they do.
        polarization: which of the three :attr:`value` is.
        refractive_index: the particle's index relative to air at this wavelength.
        wavelength: [nm].
        coherent: phasors added with their phases (True) or intensities (False).
        stats: arcus_rainbow_stats as a dict (rays, hits, edge_rays, patches,
            patches_rejected, patches_folded, intercepted [m²], scattered (P+1,) and remaining as
            fractions of the intercepted power, seconds per stage) plus total_seconds.
        features: kernel features the cast compiled (e.g. {"RAINBOW_MESH"}).
        incident: the phase function for the polarised light asked for with
            ``incident=`` (same shape as ``parallel``), else None.
        glints: for a flat-faced Mesh, whose light in one orientation leaves in single
            directions: a dict of arrays ``term`` (p), ``direction`` (N, 3, unit),
            ``area`` (the cast area feeding each, m²) and ``cross_section`` (its power per
            unit irradiance, m²); else None.
    """

    theta: np.ndarray
    phi: object
    parallel: np.ndarray
    perpendicular: np.ndarray
    unpolarized: np.ndarray
    per_bounce: np.ndarray
    polarization: str
    refractive_index: float
    wavelength: float
    coherent: bool
    stats: dict
    features: frozenset
    incident: object = None
    glints: object = None

    @property
    def value(self):
        """The phase function of the polarisation asked for (``polarization``)."""
        return getattr(self, self.polarization)

    @property
    def max_bounces(self):
        return self.per_bounce.shape[-1] - 1


def _angles(value, name, low, high):
    array = to_real_array(value, name)
    if array.ndim > 1:
        raise ArgumentError("%s must be a number or a 1-D array, got shape %s" % (name, array.shape))
    bad = ~np.isfinite(array)
    if low is not None:
        bad |= (array < low) | (array > high)
    if bad.any():
        i = int(np.flatnonzero(bad.ravel())[0])
        what = "finite" if low is None else "within [%g, %g] degrees" % (low, high)
        raise ArgumentError("%s[%d] must be %s, got %r" % (name, i, what, float(array.ravel()[i])))
    return np.ascontiguousarray(np.atleast_1d(array))


def _rotation(rotation):
    if rotation is None:
        return [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
    r = to_real_array(rotation, "rotation")
    if r.shape not in ((3, 3), (9,)):
        raise ArgumentError("rotation must be a 3x3 matrix (particle -> world), got shape %s" % (r.shape,))
    return [float(v) for v in r.ravel()]


def _material_params(wavelength, material, temperature_k, temperature, refractive_index):
    """arcus_rainbow_params at ``wavelength`` nm with the particle's material (see
    :func:`phase_function`), the rest at their defaults."""
    params = _lib.RainbowParamsStruct()
    _lib.check(lib.arcus_rainbow_params_init(byref(params)))
    params.wavelength_nm = wavelength
    params.temperature_k = water_temperature_k(temperature_k, temperature)
    m = _material(material)
    if refractive_index is not None:
        if m != MATERIALS["water"] and m != MATERIALS["fixed"]:
            raise ArgumentError("refractive_index and material=%r exclude one another" % (material,))
        params.material = MATERIALS["fixed"]
        params.refractive_index = to_float(refractive_index, "refractive_index")
    elif m == MATERIALS["fixed"]:
        raise ArgumentError("material='fixed' needs refractive_index")
    else:
        params.material = m
    return params


def _read_glints(ctx, job):
    """A job's glints as a dict of arrays (term, direction, area, cross_section), or None."""
    n_glints = c_size_t(0)
    ctx._check(lib.arcus_job_get_rainbow_glints(job, byref(n_glints), None, None, None, None))
    if not n_glints.value:
        return None
    g_term = np.zeros(n_glints.value, dtype=np.uint32)
    g_dir, g_area, g_cross = np.zeros((n_glints.value, 3)), np.zeros(n_glints.value), np.zeros(n_glints.value)
    ctx._check(lib.arcus_job_get_rainbow_glints(
        job, byref(n_glints), g_term.ctypes.data_as(POINTER(c_uint32)), _lib.ptr(g_dir), _lib.ptr(g_area),
        _lib.ptr(g_cross)))
    return dict(term=g_term, direction=g_dir, area=g_area, cross_section=g_cross)


def trace_beams(particle, wavelength, rotations, max_bounces=3, material="ice", temperature_k=293.15,
                refractive_index=None, context=None, progress=None):
    """The glints of a convex flat-faced :class:`Mesh` (an ice crystal) at ``wavelength``
    nm in each of ``rotations`` ((N, 3, 3) particle -> world, the light along +z; N up to
    65536), traced as beams (arcus_rainbow_trace_beams): each face the light enters is
    followed as a polygon, cut exactly among the faces it meets, so the glints' areas and
    powers are exact where :func:`phase_function`'s grid counts rays.

    Returns a dict: ``term``, ``direction`` (N_g, 3), ``area`` (the incident
    cross-section feeding each glint, m²) and ``cross_section`` (its power per unit
    irradiance, m²) of every orientation's glints in turn, and ``stats`` (intercepted:
    the shadows' mean area; scattered (P+1,) and remaining: fractions of it; rays: the
    beam pieces traced; cast_seconds)."""
    if not isinstance(particle, Mesh):
        raise ArgumentError("particle must be an arcus.rainbow Mesh with flat faces, got %r" % (particle,))
    wl = to_float(wavelength, "wavelength")
    r = to_real_array(rotations, "rotations")
    if r.ndim != 3 or r.shape[1:] != (3, 3) or not 1 <= len(r) <= 65536:
        raise ArgumentError("rotations must be an array of shape (N, 3, 3), N from 1 to 65536, got %s" % (r.shape,))
    r = np.ascontiguousarray(r, dtype=float)
    params = _material_params(wl, material, temperature_k, None, refractive_index)
    params.max_bounces = to_int(max_bounces, "max_bounces", 0, 2 ** 32 - 1)
    _check_progress(progress)
    with _owned_context(context) as ctx:
        handle = particle._handle_on(ctx)

        def start(callback, job_out):
            params.progress = callback
            return lib.arcus_rainbow_trace_beams(ctx._handle, handle, byref(params), len(r), _lib.ptr(r), job_out)

        def read(job):
            s = _lib.RainbowStatsStruct()
            ctx._check(lib.arcus_job_get_rainbow_stats(job, byref(s)))
            glints = _read_glints(ctx, job) or dict(term=np.zeros(0, dtype=np.uint32), direction=np.zeros((0, 3)),
                                                    area=np.zeros(0), cross_section=np.zeros(0))
            glints["stats"] = {"intercepted": s.intercepted,
                               "scattered": np.array(s.scattered[:params.max_bounces + 1]),
                               "remaining": s.remaining, "rays": s.rays, "cast_seconds": s.cast_seconds,
                               "refractive_index": s.refractive_index}
            return glints

        return ctx._run_job(start, progress, False, "arcus_rainbow_trace_beams", reader=read)


def phase_function(particle, wavelength, theta, phi=None, grid=1000, max_bounces=3, polarization="unpolarized",
                   alpha=0.3, edge_rays=True, material="water", temperature_k=293.15, refractive_index=None,
                   rotation=None, coherent=True, caustics="uniform", incident=None, context=None, progress=None,
                   *, temperature=None):
    """The phase function of ``particle`` at ``wavelength`` nm (in vacuum, one value) and
    scattering angles ``theta`` degrees (0 forward, 180 back): a :class:`PhaseResult`.

    Args:
        particle: a :class:`Sphere`, :class:`Raindrop` or :class:`Mesh` (sizes in metres).
        phi: None: a 1-D table at azimuth 0 (only the patches reaching that half-plane
            are kept: fast); a number: a 1-D table at that azimuth [deg]; a 1-D array:
            a 2-D table over θ × φ (every patch is kept; slower).
        grid: rays per side of the cast grid (4-8192; the cast is grid² rays).
        max_bounces: P, terms p = 0..P (0-15).
        polarization: which component :attr:`PhaseResult.value` is: "unpolarized",
            "parallel" or "perpendicular" (all three are always computed).
        alpha: the grid's warp, eq. 4.27-4.28 (0.3; 1: uniform).
        edge_rays: move grid points just outside onto the projected edge (§4.4.3.1).
        material: "water" (at ``temperature_k`` kelvin; ``temperature``, in °C, is
            the deprecated spelling of arcus 0.9) or "ice"; ``refractive_index`` (a
            number) overrides it with a fixed index at every wavelength.
        rotation: the particle's orientation, a 3x3 particle -> world rotation.
        coherent: add phasors with their phases (interference, eq. 4.31), or
            intensities (geometric optics).
        caustics: with ``coherent``, how the two rays of one term that meet at a fold
            caustic (a rainbow angle) add: "uniform" (the uniform, Airy, approximation of
            the same two rays: finite, peaking where the wave does) or "rays" (eq. 4.31
            alone, as the thesis: the intensity peaks at the geometric caustic).
        incident: None, or the incident light's polarisation as two complex
            amplitudes (I_x, I_y) along x and y (normalised to unit power): then
            :attr:`PhaseResult.incident` holds the phase function for that light,
            |I_x E_h + I_y E_v|² over the outgoing frame (eq. 4.32-4.34); (1, 0) is
            light polarised in the plane φ = 0, (1, 1j) circular.  Needs coherent phasors
            with the default caustics.
        context: an arcus.Context (else a new one on the default device).
        progress: ``progress(fraction)`` during the cast; returning True cancels it.
    """
    if not isinstance(particle, Particle):
        raise ArgumentError("particle must be an arcus.rainbow Sphere, Raindrop or Mesh, got %r" % (particle,))
    if not (isinstance(wavelength, (int, float)) or np.ndim(wavelength) == 0):
        raise ArgumentError("wavelength must be one number (nm) here; for tables over wavelengths call this per "
                            "wavelength or use apps/rainbow/arcus_rainbow.py table, got %r" % (wavelength,))
    wl = to_float(wavelength.item() if isinstance(wavelength, np.ndarray) else wavelength, "wavelength")
    theta = _angles(theta, "theta", 0.0, 180.0)
    two_d = phi is not None and np.ndim(phi) > 0
    if phi is None:
        phis, query_phi = np.zeros(1), 0.0
    else:
        phis = _angles(phi, "phi", None, None)
        query_phi = math.nan if two_d else float(phis[0])
    polarization = to_choice(polarization, "polarization", POLARIZATIONS)
    params = _material_params(wl, material, temperature_k, temperature, refractive_index)
    params.grid = to_int(grid, "grid", 0, 2 ** 32 - 1)
    params.max_bounces = to_int(max_bounces, "max_bounces", 0, 2 ** 32 - 1)
    params.alpha = to_float(alpha, "alpha")
    params.edge_rays = int(to_bool(edge_rays, "edge_rays"))
    params.rotation = (c_double * 9)(*_rotation(rotation))
    params.query_phi_deg = query_phi
    coherent = to_bool(coherent, "coherent")
    if incident is not None:
        try:
            ix, iy = (complex(v) for v in incident)
        except (TypeError, ValueError):
            raise ArgumentError("incident must be two complex amplitudes (I_x, I_y), got %r" % (incident,)) from None
        power = abs(ix) ** 2 + abs(iy) ** 2
        if not (math.isfinite(power) and power > 0):
            raise ArgumentError("incident must carry some light (|I_x|² + |I_y|² > 0), got %r" % (incident,))
        if not coherent or caustics != "uniform":
            raise ArgumentError("incident needs coherent=True and caustics='uniform'")
        ix, iy = ix / math.sqrt(power), iy / math.sqrt(power)
    # arcus_job_get_rainbow_phase's mode: 0 intensities, 1 phasors with the uniform caustics, 2 plain phasors
    mode = 0 if not coherent else {"uniform": 1, "rays": 2}[to_choice(caustics, "caustics", CAUSTICS)]
    _check_progress(progress)

    if two_d:
        tt, ff = np.meshgrid(theta, phis, indexing="ij")
        q_theta, q_phi, shape = np.ascontiguousarray(tt.ravel()), np.ascontiguousarray(ff.ravel()), tt.shape
    else:
        q_theta, q_phi, shape = theta, np.full(theta.size, phis[0]), theta.shape

    with _owned_context(context) as ctx:
        handle = particle._handle_on(ctx)

        def start(callback, job_out):
            params.progress = callback
            return lib.arcus_rainbow_cast(ctx._handle, handle, byref(params), job_out)

        def read(job):
            terms = params.max_bounces + 1
            count = q_theta.size
            par, perp, per = np.zeros(count), np.zeros(count), np.zeros((count, terms))
            ctx._check(lib.arcus_job_get_rainbow_phase(
                job, count, _lib.ptr(q_theta), _lib.ptr(q_phi), mode, _lib.ptr(par), _lib.ptr(perp),
                _lib.ptr(per)))
            s = _lib.RainbowStatsStruct()
            ctx._check(lib.arcus_job_get_rainbow_stats(job, byref(s)))
            stats = {name: getattr(s, name) for name, _ in s._fields_ if name != "scattered"}
            stats["scattered"] = np.array(s.scattered[:terms])
            js = _lib.JobStatsStruct()
            ctx._check(lib.arcus_job_get_stats(job, byref(js)))
            stats["total_seconds"] = js.total_seconds
            bits = c_uint64()
            ctx._check(lib.arcus_job_get_features(job, byref(bits)))
            par, perp = par.reshape(shape), perp.reshape(shape)
            polarised = None
            if incident is not None:
                raw = np.zeros(count * terms * 8)
                ctx._check(lib.arcus_job_get_rainbow_phasors(job, count, _lib.ptr(q_theta), _lib.ptr(q_phi),
                                                         _lib.ptr(raw)))
                e = raw.reshape(count, terms, 4, 2).sum(axis=1)
                e = e[..., 0] + 1j * e[..., 1]  # E_hθ, E_hφ, E_vθ, E_vφ
                l_theta, l_phi = ix * e[:, 0] + iy * e[:, 2], ix * e[:, 1] + iy * e[:, 3]
                cross = s.intercepted * float(np.sum(stats["scattered"]))
                polarised = ((np.abs(l_theta) ** 2 + np.abs(l_phi) ** 2) / cross).reshape(shape)
            glints = _read_glints(ctx, job)
            return PhaseResult(incident=polarised, glints=glints, theta=theta.copy(), phi=phis.copy() if two_d else float(phis[0]), parallel=par,
                               perpendicular=perp, unpolarized=par + perp, per_bounce=per.reshape(shape + (terms,)),
                               polarization=polarization, refractive_index=s.refractive_index, wavelength=wl,
                               coherent=coherent, stats=stats, features=_lib.feature_names(bits.value))

        return ctx._run_job(start, progress, False, "arcus_rainbow_cast", reader=read)


def rainbow_angle(n, p=2):
    """The geometric-optics rainbow angle of term ``p`` (2: primary, 3: secondary) for
    refractive index ``n`` (Descartes' minimum deviation; thesis eq. 4.20 for p = 2), as
    a scattering angle in degrees from the forward direction (about 138° and 129° for
    water)."""
    k = p - 1  # internal reflections
    n = float(n)
    if not 1 < n < p:
        raise ArgumentError("n must lie in (1, %d) for p = %d, got %r" % (p, p, n))
    cos_i = math.sqrt((n * n - 1) / (k * (k + 2)))  # incidence of minimum deviation
    i = math.acos(cos_i)
    r = math.asin(math.sin(i) / n)
    deviation = 2 * (i - r) + k * (math.pi - 2 * r)  # total turning angle
    theta = math.degrees(deviation) % 360.0
    return 360.0 - theta if theta > 180.0 else theta


def __getattr__(name):
    # arcus.rainbow.render, the 0.9 name of arcus.sky.render, found by name when used:
    # sky sits above this module (its tables come from sweep, which runs this module's
    # phase functions), so this module imports nothing of it.
    if name == "render":
        warnings.warn("arcus.rainbow.render is deprecated since arcus 0.10: use arcus.sky.render",
                      DeprecationWarning, stacklevel=2)
        return importlib.import_module(__package__ + ".sky").render
    raise AttributeError("module %r has no attribute %r" % (__name__, name))
