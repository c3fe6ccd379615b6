"""Sweeps of independent jobs on Dask: phase-function tables, ocean grids, animation frames.

::

    import arcus.sweep as sweep

    tables = sweep.phase_tables(
        [{"kind": "sphere", "radius": 5e-4}, {"kind": "sphere", "radius": 5e-4, "method": "mie"}],
        wavelengths=np.linspace(380, 700, 33), theta=np.arange(120, 150, 0.05), grid=1000)
    print(tables.phase.shape, tables.cross_section, tables.computed, tables.cached)
    tables.save("out/tables.npz")                     # PhaseTables.load("out/tables.npz")

Every sweep is a list of tasks, each a JSON-serialisable dict of everything that
decides its result, mapped by :func:`map_tasks` over

* a Dask cluster: ``client=`` a ``distributed.Client`` or a scheduler address
  (``"tcp://host:8786"``; start one with ``dask scheduler`` and ``dask worker ADDRESS``
  on the machines, each able to ``import arcus``);
* by default a ``LocalCluster`` of ``workers`` processes (one thread each) on this
  machine, started for the sweep and closed after it;
* or, with ``client="serial"`` or ``workers=0``, a plain loop in this process (the
  reference: the same task function, the same results bit for bit).

Each worker thread keeps one :class:`arcus.Context`.  Results are cached on disk, one
``.npz`` per task named by the SHA-256 of the task's canonical JSON (with the task
function's name and arcus' version), so a re-run, or a sweep interrupted or cut short
by a failed task, computes only what is missing.  The cache lies in ``cache_dir``
(default: ``tables/`` in the library's program cache — ``$ARCUS_CACHE_DIR/tables``,
else ``$XDG_CACHE_HOME/arcus/tables``, else ``~/.cache/arcus/tables``;
``ARCUS_CACHE_DIR=off`` or ``False``: none).  A file that is missing, truncated,
unreadable, of another key or whose checksum does not match its arrays is recomputed
and overwritten, never trusted.  A task's key covers its JSON, not the contents of
files a render scene names (meshes, textures): clear the cache when those change.

Dask is imported only when a cluster is used; ``dask[distributed]`` is optional for
``client="serial"``.
"""

import copy
import hashlib
import itertools
import math
import os
from dataclasses import dataclass

import numpy as np

from . import _scene_file, halo, mie, ocean, rainbow
from ._args import to_bool, to_choice, to_float, to_int, to_real_array
from ._errors import ArgumentError
# The tasks' runner, their disk cache and the results' .npz live in modules of their
# own; their public names are this module's.
from ._archive import _Archive
from ._phase_grid import (SHARED_THETA, SHARED_THETA_STEP, _shared_theta_index, _theta_task,  # noqa: F401
                          _theta_values)
from ._task_cache import MAX_CACHE_ENTRY_BYTES, _atomic_savez, default_cache_dir  # noqa: F401
from ._tasks import CACHE_FORMAT, CONNECT_TIMEOUT, TaskResults, _canonical, _plain, _worker_context, map_tasks  # noqa: F401

#: The most values one axis of a spec may have (as the library's reader: src/sweep/spec.h).
MAX_AXIS_VALUES = 10 ** 6
#: Particle kinds of :func:`phase_tables` and the keys each takes, with their defaults
#: (``...``: required).
_COMMON = dict(material="water", rotation=None, temperature_k=293.15)
PARTICLE_KEYS = dict(
    sphere=dict(radius=..., method="rays", **_COMMON),
    raindrop=dict(diameter=..., **_COMMON),
    mesh=dict(path=..., scale=1.0, smooth=True, **_COMMON),
    crystal=None,  # checked by arcus.halo.crystal_table on the worker
)
METHODS = dict(rays="rays", mie="mie")


# ---- phase-function tables -----------------------------------------------------------------


@dataclass(eq=False)
class PhaseTables(_Archive):
    """Phase functions and cross-sections of particles over wavelengths (:func:`phase_tables`).

    Attributes:
        particles: the N particle specs (with their defaults filled in).
        wavelengths: (L,) [nm]; theta: (T,) [deg]; phi: None, one azimuth [deg] or (F,).
        phase: (N, L, T), or (N, L, F, T) for an array ``phi``: the unpolarised phase
            function per steradian, the light of p = 0..P integrating to 1.
        cross_section: (N, L) [m²]: the power per unit irradiance ``phase`` distributes.
        extinction: (N, L) [m²] (rays: twice the intercepted area, the extinction paradox).
        intercepted: (N, L) [m²]: the particle's projected area.
        remaining: (N, L): the fraction of the intercepted power not scattered in p ≤ P (0 for Mie).
        grid, max_bounces: the cast's parameters.
        computed, cached: tasks computed by this call / read from the cache (not saved).
    """

    particles: list
    wavelengths: np.ndarray
    theta: np.ndarray
    phi: object
    phase: np.ndarray
    cross_section: np.ndarray
    extinction: np.ndarray
    intercepted: np.ndarray
    remaining: np.ndarray
    grid: int
    max_bounces: int
    computed: int = 0
    cached: int = 0


def _particle(spec, i):
    """A particle spec checked, defaults filled in, a mesh's path made absolute."""
    name = "particles[%d]" % i
    if not isinstance(spec, dict):
        raise ArgumentError("%s must be a dict with a 'kind', got %r" % (name, spec))
    kind = spec.get("kind")
    if kind not in PARTICLE_KEYS:
        raise ArgumentError("%s: unknown kind %r (expected one of %s)"
                            % (name, kind, ", ".join(map(repr, PARTICLE_KEYS))))
    keys = PARTICLE_KEYS[kind]
    if keys is None:  # crystals: arcus.halo checks them and fills in their defaults
        try:
            return _plain(halo.normalise_spec(spec), name)
        except ArgumentError as exc:
            raise ArgumentError("%s: %s" % (name, exc.message)) from None
    if "temperature" in spec:  # arcus 0.9's °C key, converted at the edge
        if "temperature_k" in spec:
            raise ArgumentError("%s: give temperature_k (kelvin) or the deprecated temperature (°C), not both" % name)
        spec = dict(spec, temperature_k=rainbow.water_temperature_k(None, spec["temperature"]))
        del spec["temperature"]
    unknown = set(spec) - set(keys) - {"kind"}
    if unknown:
        raise ArgumentError("%s: unknown key %s for a %s (expected %s)"
                            % (name, ", ".join(map(repr, sorted(unknown))), kind, ", ".join(keys)))
    out = dict(kind=kind)
    for key, default in keys.items():
        if key not in spec and default is ...:
            raise ArgumentError("%s: a %s needs %r" % (name, kind, key))
        out[key] = spec.get(key, default)
    if kind == "sphere" and isinstance(out["radius"], (list, tuple, np.ndarray)):  # one per wavelength
        radii = [to_float(r, "%s.radius[%d]" % (name, j)) for j, r in enumerate(out["radius"])]
        bad = [j for j, r in enumerate(radii) if not (math.isfinite(r) and r > 0)]
        if not radii or bad:
            raise ArgumentError("%s.radius: one radius or one per wavelength, each a finite number > 0, got %r"
                                % (name, out["radius"]))
        out["radius"] = radii
    for key in ("radius", "diameter", "scale", "temperature_k"):
        if key in out and not isinstance(out[key], list):
            value = out[key] = to_float(out[key], "%s.%s" % (name, key))
            if not math.isfinite(value) or value <= 0:
                raise ArgumentError("%s.%s must be a finite number > 0, got %r" % (name, key, value))
    out["material"] = to_choice(out["material"], name + ".material", dict(water="water", ice="ice"))
    if out["rotation"] is not None:
        r = to_real_array(out["rotation"], name + ".rotation")
        if r.shape != (3, 3) or not np.isfinite(r).all():
            raise ArgumentError("%s.rotation must be a finite 3x3 matrix (particle -> world), got %r"
                                % (name, out["rotation"]))
        out["rotation"] = r.tolist()
    if kind == "sphere":
        out["method"] = to_choice(out["method"], name + ".method", METHODS)
    if kind == "mesh":
        if not isinstance(out["path"], (str, os.PathLike)):
            raise ArgumentError("%s.path must be a file name, got %r" % (name, out["path"]))
        out["path"] = os.path.abspath(os.fspath(out["path"]))  # the workers' working directory may differ
        if not os.path.isfile(out["path"]):
            raise ArgumentError("%s.path: no such file %r" % (name, out["path"]))
        out["smooth"] = to_bool(out["smooth"], name + ".smooth")
    return out


def _file_digest(path):
    """SHA-256 of a file's bytes: a mesh's content, not its name, keys its tables."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _wavelengths(values):
    wl = np.atleast_1d(to_real_array(values, "wavelengths"))
    if wl.ndim != 1 or wl.size == 0:
        raise ArgumentError("wavelengths must be a number or a non-empty 1-D array [nm], got shape %s" % (wl.shape,))
    bad = ~(np.isfinite(wl) & (wl > 0))
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise ArgumentError("wavelengths[%d] must be a finite number of nm > 0, got %r" % (i, float(wl[i])))
    return wl


def _phi(phi):
    """None, one azimuth (a float) or a 1-D array, as phase_function takes them."""
    if phi is None:
        return None
    angles = rainbow._angles(phi, "phi", None, None)
    return float(angles[0]) if np.ndim(phi) == 0 else angles


def _phase_task(task):
    """One particle at one wavelength (a task of :func:`phase_tables`)."""
    spec, wl, theta, grid, bounces = (task[k] for k in ("particle", "wavelength", "theta", "grid", "max_bounces"))
    theta = _theta_values(theta)
    phi = np.array(task["phi"], dtype=np.float64) if isinstance(task["phi"], list) else task["phi"]
    kind = spec["kind"]
    if kind == "crystal":
        r = halo.crystal_table(spec, wl, theta, phi, method=task["method"], max_bounces=bounces,
                               context=_worker_context())
        return {k: r[k] for k in ("phase", "cross_section", "extinction", "intercepted", "remaining")}
    if kind == "sphere" and spec["method"] == "mie":
        n = None if spec["material"] == "water" else rainbow.refractive_index(spec["material"], wl, spec["temperature_k"])
        m = mie.phase_function(spec["radius"], wl, theta, n=n, temperature_k=spec["temperature_k"])
        phase = m.unpolarized if np.ndim(phi) == 0 else np.broadcast_to(m.unpolarized, (len(phi), theta.size)).copy()
        area = math.pi * spec["radius"] ** 2
        return dict(phase=phase, cross_section=m.q_sca * area, extinction=m.q_ext * area, intercepted=area,
                    remaining=0.0)
    if kind == "sphere":
        particle = rainbow.Sphere(spec["radius"])
    elif kind == "raindrop":
        particle = rainbow.Raindrop(spec["diameter"])
    else:
        particle = rainbow.Mesh(spec["path"], scale=spec["scale"], smooth=spec["smooth"])
    r = rainbow.phase_function(particle, wl, theta, phi, grid=grid, max_bounces=bounces, material=spec["material"],
                               temperature_k=spec["temperature_k"], rotation=spec["rotation"], context=_worker_context())
    intercepted = r.stats["intercepted"]
    return dict(phase=np.ascontiguousarray(r.unpolarized.T),  # (T,) stays; (T, F) -> (F, T)
                cross_section=intercepted * float(np.sum(r.stats["scattered"])), extinction=2.0 * intercepted,
                intercepted=intercepted, remaining=r.stats["remaining"])

_phase_task.what = "phase tables (one particle, one wavelength each)"  # names the progress bar


def _at_wavelength(spec, j):
    """The particle as the j-th wavelength's task casts it.  Crystals: the j-th run of
    ``orientations`` of their quasi-random sequence, so that the wavelengths' tables
    average over different orientations and a colour summed over them has the noise of
    all of them together (arcus.halo.orientations); a sphere given a radius per
    wavelength (a size distribution's moving nodes, arcus.sky): the j-th, for the same
    reason; the rest are the same at every wavelength."""
    if spec["kind"] == "sphere" and isinstance(spec["radius"], list):
        return dict(spec, radius=spec["radius"][j])
    if spec["kind"] != "crystal":
        return spec
    return dict(spec, first_orientation=spec["first_orientation"] + j * spec["orientations"])


def phase_tables(particles, wavelengths, theta, phi=None, *, grid=1000, max_bounces=3, cache_dir=None, client=None,
                 workers=None, progress=False, connect_timeout=CONNECT_TIMEOUT):
    """Phase functions and cross-sections of ``particles`` at each of ``wavelengths``
    nm and scattering angles ``theta`` degrees: a :class:`PhaseTables`, one task per
    (particle, wavelength) on Dask (see the module's docstring for ``cache_dir``,
    ``client``, ``workers``, ``progress``).

    Args:
        particles: a list of dicts: ``{"kind": "sphere", "radius": m (or a list, one
            per wavelength), "method": "rays" | "mie"}``, ``{"kind": "raindrop", "diameter": m}``, ``{"kind": "mesh",
            "path": file, "scale": 1.0, "smooth": True}``, each optionally with
            ``"rotation"`` (3x3, particle -> world), ``"material"`` ("water", "ice") and
            ``"temperature_k"`` (kelvin; ``"temperature"`` in °C is the deprecated key
            of arcus 0.9); or ``{"kind": "crystal", ...}`` for
            :func:`arcus.halo.crystal_table`.  Mie ignores rotation and phi.
        phi: None (azimuth 0), one azimuth, or an array: tables over φ × θ.
        grid, max_bounces: the cast's rays per side and terms p = 0..P
            (:func:`arcus.rainbow.phase_function`); crystals trace beams, which need
            no grid.
    """
    if not isinstance(particles, (list, tuple)) or not particles:
        raise ArgumentError("particles must be a non-empty list of particle dicts, got %r" % (particles,))
    specs = [_particle(p, i) for i, p in enumerate(particles)]
    wl = _wavelengths(wavelengths)
    for i, s in enumerate(specs):
        if s["kind"] == "sphere" and isinstance(s["radius"], list) and len(s["radius"]) != wl.size:
            raise ArgumentError("particles[%d].radius: %d radii for %d wavelengths" % (i, len(s["radius"]), wl.size))
    theta = rainbow._angles(theta, "theta", 0.0, 180.0)
    phi = _phi(phi)
    grid = to_int(grid, "grid", 4, 8192)
    max_bounces = to_int(max_bounces, "max_bounces", 0, 15)
    common = dict(phi=phi.tolist() if isinstance(phi, np.ndarray) else phi, grid=grid, max_bounces=max_bounces)
    # A mesh's bytes key its tables too (the worker ignores them): an edited file is a new particle.
    files = [dict(file_sha256=_file_digest(s["path"])) if s["kind"] == "mesh" else {} for s in specs]
    shared = [_shared_theta_index(s, theta, phi) for s in specs]
    # Crystals' glints are traced as beams (exact; the grid does not enter), named in
    # their tasks so that tables cached from the grid casts before are not taken for them.
    for s, f in zip(specs, files):
        if s["kind"] == "crystal":
            f["method"] = "beams"
    tasks = [dict(common, particle=_at_wavelength(s, j), wavelength=float(w),
                  theta=_theta_task(theta if k is None else SHARED_THETA), **f)
             for s, f, k in zip(specs, files, shared) for j, w in enumerate(wl)]
    run = map_tasks(_phase_task, tasks, cache_dir=cache_dir, client=client, workers=workers, progress=progress,
                    connect_timeout=connect_timeout)
    n, count = len(specs), wl.size
    # Each caller's angles out of a shared table (a task listed twice shares its result).
    phases = [r["phase"] if shared[i // count] is None else r["phase"][..., shared[i // count]]
              for i, r in enumerate(run.results)]
    shape = (theta.size,) if not isinstance(phi, np.ndarray) else (phi.size, theta.size)
    for i, phase in enumerate(phases):
        if phase.shape != shape:  # a crystal's table comes from arcus.halo
            raise ValueError("task %d (%s) returned phase of shape %s, expected %s"
                             % (i, specs[i // count]["kind"], phase.shape, shape))

    def gathered(name):
        values = np.array(phases if name == "phase" else [r[name] for r in run.results], dtype=np.float64)
        return values.reshape((n, count) + values.shape[1:])

    return PhaseTables(particles=specs, wavelengths=wl, theta=theta, phi=phi, phase=gathered("phase"),
                       cross_section=gathered("cross_section"), extinction=gathered("extinction"),
                       intercepted=gathered("intercepted"), remaining=gathered("remaining"), grid=grid,
                       max_bounces=max_bounces, computed=run.computed, cached=run.cached)


# ---- scenes: ocean grids and animation frames ------------------------------------------------


def _scene(scene, name):
    """(document, directory): a scene file read, or a dict copied; the directory its
    relative file names are read against (None for a dict)."""
    if isinstance(scene, dict):
        return _plain(scene, name), None
    if not isinstance(scene, (str, os.PathLike)):
        raise ArgumentError("%s must be a scene file or a dict, got %r" % (name, scene))
    _, doc = _scene_file.read(scene, ("ocean", "render"), name)  # read and checked by the library
    return doc, os.path.dirname(os.path.abspath(scene))


def _resize(camera, width, height, name):
    """Sets the camera's size where asked (small images make a sweep cheap)."""
    if not isinstance(camera, dict):
        raise ArgumentError("%s has no camera" % name)
    for key, value in (("width", width), ("height", height)):
        if value is not None:
            camera[key] = to_int(value, key, 1, 16384)


def _axis(values, name):
    """A sweep axis: a number or a non-empty 1-D array of finite numbers."""
    a = np.atleast_1d(to_real_array(values, name))
    if a.ndim != 1 or a.size == 0 or not np.isfinite(a).all():
        raise ArgumentError("%s must be a finite number or a non-empty 1-D array of them, got %r" % (name, values))
    return a


@dataclass(eq=False)
class OceanGrid(_Archive):
    """Ocean renders over the bio-optical parameters (:func:`ocean_grid`): ``image``
    (C, Ad, Ay, H, W, 3) linear sRGB at ``chlorophyll`` (C,) [mg/m³], ``a_d400`` (Ad,)
    and ``a_y440`` (Ay,) [1/m]; ``scene`` the document rendered (with the camera size
    and other overrides, before the three values are set)."""

    chlorophyll: np.ndarray
    a_d400: np.ndarray
    a_y440: np.ndarray
    image: np.ndarray
    scene: dict
    computed: int = 0
    cached: int = 0


def _ocean_task(task):
    """One water of :func:`ocean_grid`: the ocean scene's view, linear sRGB."""
    image = ocean.render(task["scene"], context=_worker_context(), **task["overrides"]).image
    return dict(image=image)

_ocean_task.what = "ocean views"  # names the progress bar


def ocean_grid(scene, chlorophyll, a_d400, a_y440, *, width=64, height=48, photons=None, k=None, steps=None,
               estimator=None, cache_dir=None, client=None, workers=None, progress=False,
               connect_timeout=CONNECT_TIMEOUT):
    """The thesis' Fig. 5.8 as a grid: the ocean ``scene`` (a file or dict,
    scenes/README.md "Ocean scenes", with a bio-optical "water") rendered at
    ``width`` × ``height`` for every chlorophyll C [mg/m³] × a_d(400) × a_y(440) [1/m],
    one task each: an :class:`OceanGrid`.  ``photons``, ``k``, ``steps`` and
    ``estimator`` override the scene's (:func:`arcus.ocean.render`)."""
    doc, _ = _scene(scene, "scene")
    water = doc.get("water")
    if not isinstance(water, dict) or "iops" in water:
        raise ArgumentError("scene: ocean_grid needs an ocean scene with a bio-optical \"water\" (not \"iops\")")
    _resize(doc.get("view", {}).get("camera"), width, height, "scene.view")
    axes = [_axis(v, n) for v, n in ((chlorophyll, "chlorophyll"), (a_d400, "a_d400"), (a_y440, "a_y440"))]
    overrides = {n: to_int(v, n, 1, 2 ** 40) for n, v in dict(photons=photons, k=k, steps=steps).items()
                 if v is not None}
    if estimator is not None:
        overrides["estimator"] = to_choice(estimator, "estimator", dict(per_step="per_step", beam="beam"))
    tasks = []
    for c, d, y in itertools.product(*axes):
        task_doc = copy.deepcopy(doc)
        task_doc["water"].update(chlorophyll=float(c), a_d400=float(d), a_y440=float(y))
        tasks.append(dict(scene=task_doc, overrides=overrides))
    run = map_tasks(_ocean_task, tasks, cache_dir=cache_dir, client=client, workers=workers, progress=progress,
                    connect_timeout=connect_timeout)
    images = np.stack([r["image"] for r in run.results])
    return OceanGrid(chlorophyll=axes[0], a_d400=axes[1], a_y440=axes[2],
                     image=images.reshape(tuple(a.size for a in axes) + images.shape[1:]), scene=doc,
                     computed=run.computed, cached=run.cached)


@dataclass(eq=False)
class Frames(_Archive):
    """Animation frames of a render scene (:func:`frames`): ``image`` (N, H, W, 3)
    linear RGB, frame i with the scene's ``parameter`` (a path such as
    "camera.position.1") set to ``values[i]``; ``scene`` the document rendered."""

    parameter: str
    values: np.ndarray
    image: np.ndarray
    scene: dict
    computed: int = 0
    cached: int = 0


def _set(doc, path, value):
    """Sets the number at ``path`` ("camera.position.1": keys and list indices) in ``doc``."""
    parts = path.split(".")
    node = doc
    for depth, part in enumerate(parts):
        where = ".".join(parts[:depth]) or "the scene"
        if isinstance(node, list):
            if not part.isdigit() or int(part) >= len(node):
                raise ArgumentError("parameter: %r: %s has %d entries, no %r" % (path, where, len(node), part))
            part = int(part)
        elif not isinstance(node, dict) or part not in node:
            raise ArgumentError("parameter: %r: %s has no %r" % (path, where, part))
        if depth == len(parts) - 1:
            if isinstance(node[part], bool) or not isinstance(node[part], (int, float)):
                raise ArgumentError("parameter: %r is %r in the scene, not a number" % (path, node[part]))
            node[part] = value
        node = node[part]


def _frame_task(task):
    """One frame of :func:`frames`: the render scene's image."""
    result = _worker_context().render(task["scene"], techniques=task["techniques"], base_dir=task["base_dir"])
    return dict(image=result.image)

_frame_task.what = "frames"  # names the progress bar


def frames(scene, parameter, values, *, width=None, height=None, techniques=None, base_dir=None, cache_dir=None,
           client=None, workers=None, progress=False, connect_timeout=CONNECT_TIMEOUT):
    """Frames of a render scene (a file or dict with a "camera", scenes/README.md
    "Render scenes") with one number varied, one task per frame: a :class:`Frames`.

    ``parameter`` names the number by its path in the scene, keys and list indices
    joined by dots ("camera.position.1": the eye's height; "camera.vfov_deg"); frame i
    renders with it set to ``values[i]``.  ``width``/``height`` resize the camera;
    ``techniques`` as :meth:`arcus.Context.render`.  Relative file names in the scene
    are read against its file's directory (``base_dir`` for a dict, default the
    current directory), which the workers must see too.
    """
    doc, directory = _scene(scene, "scene")
    if "camera" not in doc:
        raise ArgumentError("scene: frames needs a render scene (one with a \"camera\")")
    if not isinstance(parameter, str) or not parameter:
        raise ArgumentError("parameter must be a path such as 'camera.position.1', got %r" % (parameter,))
    _resize(doc["camera"], width, height, "scene")
    values = _axis(values, "values")
    _set(copy.deepcopy(doc), parameter, 0.0)  # a bad path fails here, before any task
    if techniques is not None:
        techniques = [techniques] if isinstance(techniques, str) else list(techniques)
    base = os.path.abspath(directory or base_dir or ".")
    tasks = []
    for v in values:
        task_doc = copy.deepcopy(doc)
        _set(task_doc, parameter, float(v))
        tasks.append(dict(scene=task_doc, techniques=techniques, base_dir=base))
    run = map_tasks(_frame_task, tasks, cache_dir=cache_dir, client=client, workers=workers, progress=progress,
                    connect_timeout=connect_timeout)
    return Frames(parameter=parameter, values=values, image=np.stack([r["image"] for r in run.results]), scene=doc,
                  computed=run.computed, cached=run.cached)


# ---- sweeps described in JSON (apps/sweep/arcus_sweep.py) ------------------------------------


def spec_axis(value, name):
    """An axis of a JSON spec: a list of values, one value, {"linspace": [first, last,
    count]} or {"range": [first, last, step]} (last included when the steps reach it,
    as the ocean's wavelength grids)."""
    if isinstance(value, dict):
        if len(value) != 1 or next(iter(value)) not in ("linspace", "range"):
            raise ArgumentError("%s: a list, {\"linspace\": [first, last, count]} or {\"range\": [first, last, step]},"
                                " got %r" % (name, value))
        (form, args), = value.items()
        a = to_real_array(args, "%s.%s" % (name, form))
        if a.shape != (3,) or not np.isfinite(a).all():
            raise ArgumentError("%s.%s must be three finite numbers, got %r" % (name, form, args))
        first, last, third = (float(x) for x in a)  # Python floats: an overflow is inf, quietly
        if form == "linspace":
            return np.linspace(first, last, to_int(third, name + ".linspace count", 1, MAX_AXIS_VALUES))
        if not (third > 0 and last >= first):
            raise ArgumentError("%s.range needs step > 0 and last >= first, got %r" % (name, args))
        ratio = (last - first) / third
        count = math.floor(ratio + 1e-9) + 1 if math.isfinite(ratio) else math.inf
        if not count <= MAX_AXIS_VALUES:  # [100, 180, 1e-9] asked for 596 GiB
            raise ArgumentError("%s.range %r makes %.3g values, more than %d (a larger step?)"
                                % (name, args, count, MAX_AXIS_VALUES))
        count = int(count)
        values = first + third * np.arange(count)
        if abs(values[-1] - last) <= 1e-9 * third:
            values[-1] = last  # exactly: 0 + 1800 steps of 0.1 must not land past 180
        return values
    return value


#: Keys of each kind of JSON spec: the function's arguments, with axes by spec_axis.
SPEC_KINDS = dict(
    phase_tables=(phase_tables, ("particles", "wavelengths", "theta"), ("phi", "grid", "max_bounces"),
                  ("wavelengths", "theta", "phi")),
    ocean_grid=(ocean_grid, ("scene", "chlorophyll", "a_d400", "a_y440"),
                ("width", "height", "photons", "k", "steps", "estimator"), ("chlorophyll", "a_d400", "a_y440")),
    frames=(frames, ("scene", "parameter", "values"), ("width", "height", "techniques"), ("values",)),
)


def load_spec(path):
    """The sweep spec file at ``path`` (scenes/sweeps/*.json) read and checked by the
    library, as the dict :func:`run_spec` takes: an unknown or repeated key, a wrong
    type, an axis of more than MAX_AXIS_VALUES values or a file that is not a regular
    file raise :class:`arcus.Error` naming the file and the key."""
    return _scene_file.read(path, ("sweep",), "spec")[1]


def run_spec(spec, *, base_dir=".", **options):
    """Runs a sweep described in JSON (a dict, e.g. read from scenes/sweeps/*.json):
    ``{"kind": "phase_tables" | "ocean_grid" | "frames", ...}`` with the arguments of
    that function (axes also as {"linspace": [first, last, count]} or {"range": [first,
    last, step]}); "name" and "description" are free.  Relative file names (a scene, a
    mesh's path) are read against ``base_dir``, the spec file's directory.  ``options``
    go to the function (client, workers, cache_dir, progress, connect_timeout).
    Returns its result (with ``save``)."""
    if not isinstance(spec, dict):
        raise ArgumentError("spec must be a JSON object, got %r" % (spec,))
    kind = spec.get("kind")
    if kind not in SPEC_KINDS:
        raise ArgumentError("spec: unknown kind %r (expected one of %s)" % (kind, ", ".join(map(repr, SPEC_KINDS))))
    function, required, optional, axes = SPEC_KINDS[kind]
    args = {k: v for k, v in spec.items() if k not in ("kind", "name", "description")}
    unknown = set(args) - set(required) - set(optional)
    if unknown:
        raise ArgumentError("spec: unknown key %s for kind %r (expected %s)"
                            % (", ".join(map(repr, sorted(unknown))), kind, ", ".join(required + optional)))
    missing = [k for k in required if k not in args]
    if missing:
        raise ArgumentError("spec: kind %r needs %s" % (kind, ", ".join(map(repr, missing))))
    for k in axes:
        if k in args:
            args[k] = spec_axis(args[k], "spec." + k)

    def resolve(path):
        return path if not isinstance(path, str) or os.path.isabs(path) else os.path.join(base_dir, path)

    if "scene" in args:
        args["scene"] = resolve(args["scene"])
    if kind == "phase_tables" and isinstance(args["particles"], list):
        args["particles"] = [dict(p, path=resolve(p["path"])) if isinstance(p, dict) and "path" in p else p
                             for p in args["particles"]]
    return function(**args, **options)
