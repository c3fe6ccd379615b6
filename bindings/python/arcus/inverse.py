"""Genetic inverse rendering (thesis §3.2, §5.1): the genes of a dipole (σ_a, σ_s, g, η
and the highlight's angle b) or of an opaque Phong surface (k_d, k_s, b) whose render of
a known scene best matches a target image.  docs/translucency.md.

>>> found = genetic("target.exr", "scenes/translucency/table_5_1.json", seed=3)
>>> found.best                  # {"sigma_a": (3,), "sigma_s": (3,), "g": .., "eta": .., "b": ..}
>>> found.sigma_s_prime         # (1 − g)σ_s: what the image determines; σ_s and g alone are not
>>> found.history["best_fitness"]   # per generation, never rising

A scene is a JSON file (scenes/translucency/, read by the library's strict reader) or a
dict of the same keys: ``translucent_object`` ({"mesh": a file (relative to the JSON
file), a bundled mesh's name or (vertices, triangles), "mm_per_unit": ...}), ``lights``
([[dx, dy, dz, E or R, G, B], ...]), ``camera`` (as :func:`arcus.translucency.render`;
its size is the target's) and ``ortho_height``.
"""

import json
import os
import time
from ctypes import byref, c_float
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import _lib, _scene_file
from ._advance import _check_progress
from ._args import to_choice, to_float, to_int
from ._errors import ArgumentError
from ._lib import lib
from .context import _owned_context
from .translucency import _camera, _lights, _mesh_handle, _photo

__all__ = ["genetic", "GeneticResult", "GENES"]

_MODELS = {"dipole": 0, "phong": 1}
_SPACES = {"ycbcr": 0, "rgb": 1}
#: Each model's genes in order: (name, channels).
GENES = {"dipole": [("sigma_a", 3), ("sigma_s", 3), ("g", 1), ("eta", 1), ("b", 1)],
         "phong": [("k_d", 3), ("k_s", 1), ("b", 1)]}
_SCENE_KEYS = ("name", "description", "translucent_object", "camera", "ortho_height", "lights")


@dataclass(eq=False)
class GeneticResult:
    """A search of :func:`genetic`: ``best`` (the genes by name), ``best_genes`` (the
    flat vector), ``fitness`` (its relative RMS difference from the target),
    ``sigma_s_prime`` (dipole: (1 − g)σ_s), ``history`` (``best_fitness`` and
    ``mean_fitness`` per generation, ``best_genes`` (generations + 1, genes)),
    ``image`` (the best individual's render, (h, w, 3)), ``evaluations``, ``pixels``,
    ``samples``, ``search_fitness`` (the search's best before the polish),
    ``polish_steps`` and ``timings`` (seconds: cache, search, polish, total)."""
    model: str
    best: dict
    best_genes: np.ndarray
    fitness: float
    sigma_s_prime: np.ndarray
    history: dict
    image: np.ndarray
    evaluations: int
    pixels: int
    samples: int
    search_fitness: float
    polish_steps: int
    timings: dict


def _named(model, genes):
    out, at = {}, 0
    for name, count in GENES[model]:
        out[name] = np.array(genes[at:at + count]) if count > 1 else float(genes[at])
        at += count
    return out


def _flat(model, values, what):
    """A dict by gene name (or a flat sequence) as the flat gene vector."""
    if isinstance(values, dict):
        unknown = sorted(set(values) - {n for n, _ in GENES[model]})
        if unknown:
            raise ArgumentError("%s: unknown gene(s) %s for the %s model (known: %s)" % (
                what, ", ".join(unknown), model, ", ".join(n for n, _ in GENES[model])))
        return values
    flat = np.asarray(values, float).reshape(-1)
    size = sum(c for _, c in GENES[model])
    if flat.size != size:
        raise ArgumentError("%s: %d genes for the %s model, got %d" % (what, size, model, flat.size))
    return _named(model, flat)


def _set_genes(array, model, values, what):
    at = 0
    for name, count in GENES[model]:
        if name in values:
            v = np.broadcast_to(np.asarray(values[name], float), (count,)) if count > 1 else [values[name]]
            for k in range(count):
                array[at + k] = to_float(v[k], "%s['%s']" % (what, name))
        at += count


def _scene(scene):
    """(mesh, lights, camera, ortho_height, mm_per_unit) of a scene: a dict, or a JSON
    file read by the library's strict reader (engine "translucency"; a relative mesh
    path is relative to the file)."""
    folder = None
    if isinstance(scene, (str, os.PathLike)):
        folder = Path(os.fspath(scene)).parent
        _, scene = _scene_file.read(scene, ["translucency"])
    if not isinstance(scene, dict):
        raise ArgumentError("scene must be a dict or a JSON file, got %r" % (scene,))
    unknown = sorted(set(scene) - set(_SCENE_KEYS))
    if unknown:
        raise ArgumentError("scene: unknown key(s) %s (known: %s)" % (", ".join(unknown), ", ".join(_SCENE_KEYS)))
    if "translucent_object" not in scene or "lights" not in scene:
        raise ArgumentError("scene: 'translucent_object' and 'lights' are required")
    obj = scene["translucent_object"]
    if not isinstance(obj, dict) or "mesh" not in obj:
        raise ArgumentError("scene['translucent_object'] must be a dict with 'mesh' (and 'mm_per_unit')")
    mesh = obj["mesh"]
    if isinstance(mesh, str):
        mesh = _mesh_path(mesh, folder)
    lights = []
    for i, light in enumerate(scene["lights"]):
        if isinstance(light, (list, tuple)) and len(light) == 2:  # (direction, irradiance)
            lights.append(tuple(light))
        elif isinstance(light, (list, tuple)) and len(light) in (3, 4, 6):  # [dx, dy, dz, (E | R, G, B)]
            lights.append((light[:3], light[3:] if len(light) == 6 else light[3] if len(light) == 4 else 1.0))
        else:
            raise ArgumentError("scene['lights'][%d]: give [dx, dy, dz], then nothing, E or R G B; got %r"
                                % (i, light))
    return (mesh, lights, dict(scene.get("camera", {})), scene.get("ortho_height", 0.0),
            obj.get("mm_per_unit", 1.0))


def _mesh_path(name, folder):
    """A mesh file: relative to the scene's folder, as given, or a bundled mesh's name."""
    if folder is not None and not os.path.isabs(name) and (folder / name).is_file():
        return str(folder / name)
    if Path(name).is_file():
        return name
    from .cli.resources import mesh  # not at the top: arcus.cli imports arcus (as arcus.bundled_scene)
    return str(mesh(name))


def genetic(target, scene, model="dipole", population=40, generations=50, seed=0, *, replacement=0.8,
            crossover=0.8, mutation=0.8, mutation_range=0.3, fitness_threshold=0.0, fitness_space="ycbcr",
            polish_steps=20, initial=None, lower=None, upper=None, on_generation=None, progress=None,
            context=None):
    """Searches for the genes of ``model`` ("dipole" or "phong") whose render of
    ``scene`` best matches ``target`` (an HDR file or an (h, w, 3) array of linear
    radiance): a :class:`GeneticResult`.  §5.1's defaults: 40 individuals, 50
    generations, replacement, crossover and mutation probabilities 0.8, mutations of
    ±0–30%; Table 3.1's initial genes.  ``polish_steps``: then Levenberg–Marquardt steps
    from the best individual (not in the thesis; 0: its search alone).  ``initial``/``lower``/``upper``: genes by name
    (``GENES``) or flat; ``fitness_space``: "ycbcr" (the thesis' main text) or "rgb";
    ``on_generation(generation, best_fitness, best_genes_dict)``: after each generation
    (True stops the search)."""
    model = model if model in _MODELS else to_choice(model, "model", _MODELS)
    _check_progress(progress)
    pixels = _photo(target)
    height, width = pixels.shape[:2]
    mesh, lights, camera, ortho_height, mm_per_unit = _scene(scene)
    light_array = _lights(lights)
    params = _lib.GeneticParamsStruct()
    _lib.check(lib.arcus_translucency_genetic_params_init(_MODELS[model], byref(params)))
    _camera(params, dict(camera, width=width, height=height))
    params.ortho_height = to_float(ortho_height, "scene['ortho_height']")
    params.mm_per_unit = to_float(mm_per_unit, "scene['mm_per_unit']")
    params.population = to_int(population, "population", 2, 10000)
    params.generations = to_int(generations, "generations", 0, 100000)
    params.seed = to_int(seed, "seed", 0, 2 ** 64 - 1)
    params.polish_steps = to_int(polish_steps, "polish_steps", 0, 1000)
    for name, value in (("replacement", replacement), ("crossover", crossover), ("mutation", mutation),
                        ("mutation_range", mutation_range), ("fitness_threshold", fitness_threshold)):
        setattr(params, name, to_float(value, name))
    params.fitness_space = to_choice(fitness_space, "fitness_space", _SPACES)
    for field, values in (("initial", initial), ("lower", lower), ("upper", upper)):
        if values is not None:
            _set_genes(getattr(params, field), model, _flat(model, values, field), field)
    gene_count = sum(c for _, c in GENES[model])
    raised = []

    def generation_hook(_user, generation, best, genes):
        if on_generation is None:
            return 0
        try:
            return 1 if on_generation(generation, best, _named(model, genes[:gene_count])) else 0
        except BaseException as exc:  # ctypes would print and drop it: stop, and raise it below
            raised.append(exc)
            return 1

    hook = _lib.GENERATION_CALLBACK(generation_hook)
    params.on_generation = hook
    t0 = time.perf_counter()
    with _owned_context(context) as ctx:
        mesh_handle = _mesh_handle(ctx, mesh)
        try:
            def start(callback, job_out):
                params.progress = callback
                return lib.arcus_translucency_genetic(ctx._handle, mesh_handle, width, height,
                                                      _lib.ptr(pixels, c_float), len(light_array), light_array,
                                                      byref(params), job_out)

            def read(job):
                r = _lib.GeneticResultStruct()
                ctx._check(lib.arcus_job_get_translucency_genetic(job, byref(r)))
                runs = r.generations_run + 1
                best, mean = np.empty(runs), np.empty(runs)
                genes = np.empty((runs, r.gene_count))
                ctx._check(lib.arcus_job_get_translucency_genetic_history(job, _lib.ptr(best), _lib.ptr(mean),
                                                                          _lib.ptr(genes)))
                image = np.empty((height, width, 3), np.float32)
                ctx._check(lib.arcus_job_get_translucency_genetic_image(job, _lib.ptr(image, c_float)))
                return r, best, mean, genes, image

            try:
                r, best, mean, genes, image = ctx._run_job(start, progress, False, "arcus_translucency_genetic",
                                                           reader=read)
            finally:
                if raised:
                    raise raised[0]
        finally:
            lib.arcus_mesh_release(mesh_handle)
    flat = np.array(r.best[:r.gene_count])
    return GeneticResult(
        model=model, best=_named(model, flat), best_genes=flat, fitness=r.best_fitness,
        sigma_s_prime=np.array(r.sigma_s_prime[:]) if model == "dipole" else None,
        history={"best_fitness": best, "mean_fitness": mean, "best_genes": genes}, image=image,
        evaluations=r.evaluations, pixels=r.pixels, samples=r.samples, search_fitness=r.search_fitness,
        polish_steps=r.polish_steps,
        timings={"cache": r.cache_seconds, "search": r.search_seconds, "polish": r.polish_seconds,
                 "total": time.perf_counter() - t0})
