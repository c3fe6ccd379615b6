"""Finding and loading libarcus, and the ctypes mirror of include/arcus/arcus.h.

Everything that knows the C ABI lives here and in :mod:`arcus._structs` (the struct
layouts, re-exported here): function prototypes and the translation of a failed
``arcus_status`` into a Python exception.  The rest of the package only calls
``lib.<function>`` and :func:`check`.
"""

import ctypes
import ctypes.util
import os
import sys
from ctypes import POINTER, c_char_p, c_double, c_int, c_int32, c_size_t, c_uint32, c_uint64, c_void_p
from pathlib import Path

from ._errors import LibraryNotFoundError, error_for

# The file name CMake gives the shared library on each platform.
_LIBRARY_NAME = {"darwin": "libarcus.dylib", "win32": "arcus.dll"}.get(sys.platform, "libarcus.so")

from ._structs import (  # noqa: F401  (re-exported: the package uses _lib.<Struct>)
    DeviceInfoStruct,
    DipoleStruct,
    DipoleTermsStruct,
    DirectionalLightStruct,
    TranslucencyRenderParamsStruct,
    TranslucencyRenderStatsStruct,
    TranslucencyEstimateParamsStruct,
    TranslucencyEstimateResultStruct,
    DetectedLightStruct,
    LightDetectionStruct,
    PhotoShapeParamsStruct,
    TranslucencyAutoParamsStruct,
    ProfileTableStruct,
    GeneticParamsStruct,
    GeneticResultStruct,
    GENERATION_CALLBACK,
    InversionStruct,
    AtmosphereDescStruct,
    AdvanceParamsStruct,
    JobStatsStruct,
    CameraStruct,
    RenderStatsStruct,
    WavelengthGridStruct,
    SpectrumStruct,
    PhaseFunctionStruct,
    BioOpticalStruct,
    WaterIopsStruct,
    OceanLightStruct,
    OceanSetupStruct,
    OceanTraceParamsStruct,
    OceanTalliesStruct,
    OceanMarchStruct,
    OceanRenderStatsStruct,
    ParticleInfoStruct,
    RainbowParamsStruct,
    RainbowStatsStruct,
    MieEfficienciesStruct,
    DaylightDescStruct,
    OpticalDepthsStruct,
    RainbowTableStruct,
    RainbowSkyStruct,
    PROGRESS_CALLBACK,
    ERROR_CALLBACK,
)

# ---- prototypes -----------------------------------------------------------------------
# Handles are opaque, so c_void_p; out-handles are POINTER(c_void_p).
_status = c_int
_handle = c_void_p
_out_handle = POINTER(c_void_p)
_dvec = POINTER(c_double)  # const double[3] and double arrays alike
_u32vec = POINTER(c_uint32)

_PROTOTYPES = {
    # name: (restype, argtypes)
    "arcus_status_string": (c_char_p, [c_int]),
    "arcus_get_version": (_status, [POINTER(c_int), POINTER(c_int), POINTER(c_int)]),
    "arcus_last_error": (c_char_p, []),
    "arcus_device_count": (_status, [POINTER(c_uint32)]),
    "arcus_device_get_info": (_status, [c_uint32, POINTER(DeviceInfoStruct)]),
    "arcus_context_create": (_status, [c_int32, _out_handle]),
    "arcus_context_retain": (_status, [_handle]),
    "arcus_context_release": (_status, [_handle]),
    "arcus_context_get_device": (_status, [_handle, POINTER(DeviceInfoStruct)]),
    "arcus_context_last_error": (c_char_p, [_handle]),
    "arcus_context_set_error_callback": (_status, [_handle, ERROR_CALLBACK, c_void_p]),
    "arcus_field_create_constant": (_status, [_handle, c_double, _out_handle]),
    "arcus_field_create_linear": (_status, [_handle, c_double, _dvec, _out_handle]),
    "arcus_field_create_linear_n2": (_status, [_handle, c_double, _dvec, _out_handle]),
    "arcus_field_create_luneburg": (_status, [_handle, _dvec, c_double, _out_handle]),
    "arcus_field_create_fisheye": (_status, [_handle, _dvec, c_double, c_double, _out_handle]),
    "arcus_atmosphere_desc_init": (_status, [POINTER(AtmosphereDescStruct)]),
    "arcus_field_create_atmosphere": (_status, [_handle, POINTER(AtmosphereDescStruct), _out_handle]),
    "arcus_field_create_grid": (_status, [_handle, _dvec, _u32vec, _dvec, _dvec, _out_handle]),
    "arcus_field_create_grid_from_file": (_status, [_handle, c_char_p, c_int32, _u32vec, _dvec, _dvec, _out_handle]),
    "arcus_field_retain": (_status, [_handle]),
    "arcus_field_release": (_status, [_handle]),
    "arcus_field_get_kind": (_status, [_handle, POINTER(c_int)]),
    "arcus_field_evaluate": (_status, [_handle, c_size_t, _dvec, _dvec, _dvec]),
    "arcus_advance_params_init": (_status, [POINTER(AdvanceParamsStruct)]),
    "arcus_features_to_string": (_status, [c_uint64, c_char_p, c_size_t]),
    "arcus_curved_advance": (
        _status,
        [_handle, _handle, POINTER(AdvanceParamsStruct), c_size_t, _dvec, _dvec, _dvec, _out_handle],
    ),
    "arcus_job_retain": (_status, [_handle]),
    "arcus_job_release": (_status, [_handle]),
    "arcus_job_get_count": (_status, [_handle, POINTER(c_size_t)]),
    "arcus_job_get_curved_end_states": (
        _status,
        [_handle, _dvec, _dvec, POINTER(c_uint64), POINTER(c_int32), _dvec],
    ),
    "arcus_job_get_curved_path_size": (_status, [_handle, POINTER(c_size_t)]),
    "arcus_job_get_curved_paths": (_status, [_handle, POINTER(c_uint64), _dvec, POINTER(c_uint64)]),
    "arcus_job_get_curved_failures": (_status, [_handle, POINTER(c_int32)]),
    "arcus_job_get_features": (_status, [_handle, POINTER(c_uint64)]),
    "arcus_job_get_stats": (_status, [_handle, POINTER(JobStatsStruct)]),
    "arcus_scene_load": (_status, [_handle, c_char_p, _out_handle]),
    "arcus_scene_load_with_meshes": (_status, [_handle, c_char_p, c_size_t, POINTER(c_char_p), POINTER(c_void_p),
                                               _out_handle]),
    "arcus_scene_retain": (_status, [_handle]),
    "arcus_scene_release": (_status, [_handle]),
    "arcus_scene_get_name": (_status, [_handle, POINTER(c_char_p)]),
    "arcus_scene_get_description": (_status, [_handle, POINTER(c_char_p)]),
    "arcus_scene_get_document": (_status, [_handle, POINTER(c_char_p)]),
    "arcus_scene_get_engine": (_status, [_handle, POINTER(c_char_p)]),
    "arcus_mesh_create": (_status, [_handle, c_size_t, _dvec, c_size_t, _u32vec, _out_handle]),
    "arcus_mesh_retain": (_status, [_handle]),
    "arcus_mesh_release": (_status, [_handle]),
    "arcus_mesh_get_counts": (_status, [_handle, POINTER(c_size_t), POINTER(c_size_t)]),
    "arcus_mesh_load": (_status, [_handle, c_char_p, _out_handle]),
    "arcus_mesh_get_arrays": (_status, [_handle, c_void_p, c_void_p]),
    "arcus_scene_get_field": (_status, [_handle, _out_handle]),
    "arcus_scene_get_advance_params": (_status, [_handle, POINTER(AdvanceParamsStruct)]),
    "arcus_scene_get_ray_count": (_status, [_handle, POINTER(c_size_t)]),
    "arcus_scene_get_rays": (_status, [_handle, _dvec, _dvec, _dvec, POINTER(c_int32)]),
    "arcus_curved_advance_scene": (_status, [_handle, PROGRESS_CALLBACK, c_void_p, _out_handle]),
    "arcus_renderer_create": (_status, [_handle, _out_handle]),
    "arcus_renderer_retain": (_status, [_handle]),
    "arcus_renderer_release": (_status, [_handle]),
    "arcus_renderer_set_techniques": (_status, [_handle, c_uint32]),
    "arcus_renderer_get_techniques": (_status, [_handle, POINTER(c_uint32)]),
    "arcus_renderer_set_camera": (_status, [_handle, POINTER(CameraStruct)]),
    "arcus_renderer_get_camera": (_status, [_handle, POINTER(CameraStruct)]),
    "arcus_renderer_set_integrator": (_status, [_handle, POINTER(AdvanceParamsStruct)]),
    "arcus_renderer_get_integrator": (_status, [_handle, POINTER(AdvanceParamsStruct)]),
    "arcus_render_frame": (_status, [_handle, PROGRESS_CALLBACK, c_void_p, _out_handle]),
    "arcus_job_get_render_stats": (_status, [_handle, POINTER(RenderStatsStruct)]),
    "arcus_job_get_render_image_size": (_status, [_handle, POINTER(c_uint32), POINTER(c_uint32)]),
    "arcus_job_get_render_image": (_status, [_handle, POINTER(ctypes.c_float)]),
    "arcus_job_get_render_hits": (
        _status,
        [_handle, _dvec, POINTER(c_int32), POINTER(c_int32), _dvec, POINTER(c_uint32), POINTER(c_uint32)],
    ),
    "arcus_job_write_render_image": (_status, [_handle, c_char_p, c_char_p]),
    "arcus_bio_optical_init": (_status, [POINTER(BioOpticalStruct)]),
    "arcus_bio_optical_preset": (_status, [c_char_p, POINTER(BioOpticalStruct)]),
    "arcus_water_create": (_status, [_handle, POINTER(BioOpticalStruct), _out_handle]),
    "arcus_water_create_iops": (_status, [_handle, POINTER(WaterIopsStruct), _out_handle]),
    "arcus_water_retain": (_status, [_handle]),
    "arcus_water_release": (_status, [_handle]),
    "arcus_water_get_coefficients": (_status, [_handle, POINTER(WavelengthGridStruct), _dvec, _dvec, _dvec]),
    "arcus_ocean_setup_init": (_status, [POINTER(OceanSetupStruct)]),
    "arcus_ocean_trace_params_init": (_status, [POINTER(OceanTraceParamsStruct)]),
    "arcus_ocean_trace": (
        _status,
        [_handle, _handle, POINTER(OceanSetupStruct), POINTER(OceanTraceParamsStruct), _out_handle],
    ),
    "arcus_job_get_ocean_tallies": (_status, [_handle, POINTER(OceanTalliesStruct)]),
    "arcus_job_get_ocean_by_interaction": (_status, [_handle, _dvec, _dvec]),
    "arcus_job_get_ocean_irradiance": (_status, [_handle, _dvec, _dvec, _dvec]),
    "arcus_ocean_march_init": (_status, [POINTER(OceanMarchStruct)]),
    "arcus_ocean_render": (
        _status,
        [_handle, _handle, POINTER(OceanSetupStruct), POINTER(OceanTraceParamsStruct), POINTER(CameraStruct),
         POINTER(OceanMarchStruct), _out_handle],
    ),
    "arcus_ocean_render_scene": (_status, [_handle, PROGRESS_CALLBACK, c_void_p, _out_handle]),
    "arcus_job_get_ocean_render_stats": (_status, [_handle, POINTER(OceanRenderStatsStruct)]),
    "arcus_job_get_ocean_image": (
        _status,
        [_handle, POINTER(c_uint32), POINTER(c_uint32), POINTER(c_uint32), _dvec, POINTER(ctypes.c_float), _dvec],
    ),
    "arcus_job_write_ocean_image": (_status, [_handle, c_char_p, c_char_p, c_int32]),
    "arcus_job_get_ocean_photons": (
        _status,
        [_handle, POINTER(c_size_t), _dvec, _dvec, _dvec, _dvec, POINTER(c_int32)],
    ),
    "arcus_rainbow_refractive_index": (_status, [c_int32, c_double, c_double, _dvec]),
    "arcus_particle_create_sphere": (_status, [_handle, c_double, _out_handle]),
    "arcus_particle_create_raindrop": (_status, [_handle, c_double, _out_handle]),
    "arcus_particle_create_mesh": (_status, [_handle, c_char_p, c_double, c_int32, _out_handle]),
    "arcus_particle_create_from_mesh": (_status, [_handle, c_double, c_int32, _out_handle]),
    "arcus_particle_retain": (_status, [_handle]),
    "arcus_particle_release": (_status, [_handle]),
    "arcus_particle_get_info": (_status, [_handle, POINTER(ParticleInfoStruct)]),
    "arcus_rainbow_params_init": (_status, [POINTER(RainbowParamsStruct)]),
    "arcus_rainbow_cast": (_status, [_handle, _handle, POINTER(RainbowParamsStruct), _out_handle]),
    "arcus_job_get_rainbow_stats": (_status, [_handle, POINTER(RainbowStatsStruct)]),
    "arcus_job_get_rainbow_phase": (_status, [_handle, c_size_t, _dvec, _dvec, c_int32, _dvec, _dvec, _dvec]),
    "arcus_job_get_rainbow_phasors": (_status, [_handle, c_size_t, _dvec, _dvec, _dvec]),
    "arcus_job_get_rainbow_glints": (_status, [_handle, POINTER(c_size_t), POINTER(c_uint32), _dvec, _dvec, _dvec]),
    "arcus_rainbow_trace_beams": (_status, [_handle, _handle, POINTER(RainbowParamsStruct), c_size_t, _dvec,
                                            _out_handle]),
    "arcus_rainbow_sky_init": (_status, [POINTER(RainbowSkyStruct)]),
    "arcus_rainbow_render": (_status, [_handle, POINTER(RainbowTableStruct), POINTER(RainbowSkyStruct), _out_handle]),
    "arcus_job_get_rainbow_image": (
        _status, [_handle, POINTER(c_uint32), POINTER(c_uint32), POINTER(ctypes.c_float), POINTER(ctypes.c_float),
                  POINTER(ctypes.c_float)]),
    "arcus_job_write_rainbow_image": (_status, [_handle, c_char_p, c_char_p]),
    "arcus_image_write": (_status, [c_char_p, c_uint32, c_uint32, POINTER(ctypes.c_float)]),
    "arcus_image_read": (_status, [c_char_p, POINTER(c_uint32), POINTER(c_uint32), POINTER(ctypes.c_float),
                                   ctypes.c_size_t]),
    "arcus_rainbow_mie": (
        _status,
        [c_double, c_double, c_double, c_double, c_size_t, _dvec, _dvec, _dvec, _dvec, _dvec,
         POINTER(MieEfficienciesStruct)],
    ),
    "arcus_rainbow_mie_debye": (
        _status,
        [c_double, c_double, c_double, c_double, c_uint32, c_size_t, _dvec, _dvec, _dvec, _dvec, _dvec],
    ),
    "arcus_daylight_desc_init": (_status, [POINTER(DaylightDescStruct)]),
    "arcus_daylight_optical_depths": (_status, [POINTER(DaylightDescStruct), c_double, c_size_t, _dvec,
                                                POINTER(OpticalDepthsStruct)]),
    "arcus_daylight_sky_radiance": (_status, [POINTER(DaylightDescStruct), c_double, c_size_t, _dvec, _dvec, c_size_t,
                                              _dvec, _dvec]),
    "arcus_daylight_sky_image": (_status, [POINTER(DaylightDescStruct), c_double, c_double, c_uint32, c_uint32,
                                           POINTER(ctypes.c_float)]),
    "arcus_daylight_ground_irradiance": (_status, [POINTER(DaylightDescStruct), c_double, c_size_t, _dvec, _dvec,
                                                   _dvec]),
    "arcus_daylight_solar_irradiance": (_status, [c_size_t, _dvec, c_double, _dvec]),
    "arcus_daylight_limb_darkening": (_status, [c_size_t, _dvec, _dvec, _dvec]),
    "arcus_translucency_dipole_get_terms": (_status, [POINTER(DipoleStruct), POINTER(DipoleTermsStruct)]),
    "arcus_translucency_dipole_profile": (_status, [POINTER(DipoleStruct), c_double, c_int32, c_size_t, _dvec,
                                                    _dvec]),
    "arcus_translucency_dipole_from_material": (_status, [c_char_p, POINTER(DipoleStruct)]),
    "arcus_translucency_material_name": (_status, [c_uint32, POINTER(c_char_p)]),
    "arcus_translucency_dipole_from_reflectance": (_status, [_dvec, _dvec, c_double, POINTER(DipoleStruct)]),
    "arcus_translucency_henyey_greenstein": (_status, [c_double, c_size_t, _dvec, _dvec]),
    "arcus_translucency_fresnel_reflectance": (_status, [c_double, c_double, c_double, _dvec]),
    "arcus_translucency_render_params_init": (_status, [POINTER(TranslucencyRenderParamsStruct)]),
    "arcus_translucency_render": (_status, [_handle, _handle, POINTER(DipoleStruct), c_size_t,
                                            POINTER(DirectionalLightStruct), POINTER(TranslucencyRenderParamsStruct),
                                            _out_handle]),
    "arcus_job_get_translucency_stats": (_status, [_handle, POINTER(TranslucencyRenderStatsStruct)]),
    "arcus_job_get_translucency_image": (_status, [_handle, c_void_p, c_void_p, c_void_p]),
    "arcus_translucency_estimate_params_init": (_status, [POINTER(TranslucencyEstimateParamsStruct)]),
    "arcus_translucency_estimate": (_status, [_handle, _handle, c_uint32, c_uint32, c_void_p, c_void_p, c_size_t,
                                              POINTER(DirectionalLightStruct),
                                              POINTER(TranslucencyEstimateParamsStruct), _out_handle]),
    "arcus_job_get_translucency_estimate": (_status, [_handle, POINTER(TranslucencyEstimateResultStruct)]),
    "arcus_translucency_detect_lights": (_status, [_handle, c_uint32, c_uint32, c_void_p, c_void_p,
                                                   POINTER(LightDetectionStruct)]),
    "arcus_translucency_photo_shape_params_init": (_status, [POINTER(PhotoShapeParamsStruct)]),
    "arcus_translucency_auto_params_init": (_status, [POINTER(TranslucencyAutoParamsStruct)]),
    "arcus_translucency_estimate_auto": (_status, [_handle, c_uint32, c_uint32, c_void_p, c_void_p,
                                                   POINTER(TranslucencyAutoParamsStruct), _out_handle]),
    "arcus_job_get_translucency_auto": (_status, [_handle, POINTER(LightDetectionStruct), c_void_p, c_void_p, c_void_p,
                                                  POINTER(c_size_t), POINTER(c_size_t), c_void_p, c_void_p]),
    "arcus_translucency_estimate_shape": (_status, [_handle, c_uint32, c_uint32, c_void_p, c_void_p,
                                                    POINTER(PhotoShapeParamsStruct), _dvec, _dvec, c_void_p]),
    "arcus_job_get_translucency_profile": (_status, [_handle, _dvec, _dvec]),
    "arcus_translucency_render_table": (_status, [_handle, _handle, POINTER(ProfileTableStruct), c_size_t,
                                                  POINTER(DirectionalLightStruct),
                                                  POINTER(TranslucencyRenderParamsStruct), _out_handle]),
    "arcus_job_get_translucency_hermite": (_status, [_handle, c_uint32, _dvec]),
    "arcus_translucency_genetic_params_init": (_status, [c_int32, POINTER(GeneticParamsStruct)]),
    "arcus_translucency_genetic": (_status, [_handle, _handle, c_uint32, c_uint32, c_void_p, c_size_t,
                                             POINTER(DirectionalLightStruct), POINTER(GeneticParamsStruct),
                                             _out_handle]),
    "arcus_job_get_translucency_genetic": (_status, [_handle, POINTER(GeneticResultStruct)]),
    "arcus_job_get_translucency_genetic_history": (_status, [_handle, _dvec, _dvec, _dvec]),
    "arcus_job_get_translucency_genetic_image": (_status, [_handle, c_void_p]),
    "arcus_job_get_translucency_system": (_status, [_handle, c_uint32, _dvec, _dvec, _dvec]),
    "arcus_job_get_translucency_sources": (_status, [_handle, _dvec, _dvec, _dvec, _dvec]),
    "arcus_job_get_translucency_sub_sources": (_status, [_handle, _dvec, _dvec]),
}

# ---- finding the library --------------------------------------------------------------


def _source_root():
    """The repository root this package sits in (it holds include/arcus/arcus.h), or None."""
    for root in Path(__file__).resolve().parents:
        if (root / "include" / "arcus" / "arcus.h").is_file():
            return root
    return None


def _candidates():
    """Yields (description, path-or-name or None) in the order they are tried.

    In the source tree, ``build/`` (the default build directory) comes first, then
    any other ``build*/`` in name order.  A None path records a place looked at that
    offered nothing, for the error message.  A generator, so that the slow
    find_library (it runs ldconfig) only runs when the source tree has no library.
    """
    # `pip install .` puts the library inside the package (pyproject.toml).
    yield "the package's own (pip install .)", str(Path(__file__).resolve().parent / "lib" / _LIBRARY_NAME)
    root = _source_root()
    if root is None:
        yield "source tree", None
    else:
        others = sorted(p for p in root.glob("build*") if p.is_dir() and p.name != "build")
        for build in [root / "build"] + others:
            yield "source tree build", str(build / _LIBRARY_NAME)
    yield "installed (ctypes.util.find_library('arcus'))", ctypes.util.find_library("arcus")
    yield "installed (sys.prefix)", str(Path(sys.prefix) / "lib" / _LIBRARY_NAME)


# The engine each call belongs to, by its name (arcus_core.h, "Names"); the core's calls
# match none.  A library may be built without an engine (ARCUS_WITH_<ENGINE>=OFF).
_ENGINE_CALLS = {
    "curved": ("arcus_curved_", "arcus_job_get_curved_", "arcus_field_", "arcus_atmosphere_desc_init",
               "arcus_advance_params_init", "arcus_scene_get_field", "arcus_scene_get_advance_params",
               "arcus_scene_get_ray"),
    "render": ("arcus_render", "arcus_job_get_render_", "arcus_job_write_render_"),
    "ocean": ("arcus_ocean_", "arcus_water_", "arcus_bio_optical_", "arcus_job_get_ocean_", "arcus_job_write_ocean_"),
    "rainbow": ("arcus_rainbow_", "arcus_particle_", "arcus_job_get_rainbow_", "arcus_job_write_rainbow_"),
    "translucency": ("arcus_translucency_", "arcus_job_get_translucency_"),
}


def _engine_of(name):
    return next((engine for engine, prefixes in _ENGINE_CALLS.items() if name.startswith(prefixes)), None)


def _engines_built(dll):
    """The engines `dll` was built with: those whose calls it exports."""
    return {engine for engine in _ENGINE_CALLS
            if any(_engine_of(name) == engine and hasattr(dll, name) for name in _PROTOTYPES)}


def _absent(name, engine):
    def call(*args):
        raise error_for(4, "%s: this libarcus was built without the %s engine (ARCUS_WITH_%s=OFF)"
                        % (name, engine, engine.upper()), "ARCUS_ERROR_UNSUPPORTED")
    return call


def _open(path):
    """ctypes.CDLL(path) with every prototype set; raises OSError or AttributeError.

    A call of an engine the library was built without stands in as a function that
    raises arcus.Error (status UNSUPPORTED) naming the engine; any other missing
    symbol (a stale build) is an AttributeError naming it."""
    dll = ctypes.CDLL(path)
    built = _engines_built(dll)
    for name, (restype, argtypes) in _PROTOTYPES.items():
        engine = _engine_of(name)
        if engine is not None and engine not in built:
            setattr(dll, name, _absent(name, engine))
            continue
        func = getattr(dll, name)  # AttributeError names the missing symbol
        func.restype = restype
        func.argtypes = argtypes
    return dll


def _how_to_fix():
    root = _source_root() or "<arcus source>"
    return (
        "Install arcus with `pip install {0}` (it builds the library), build it (cmake -S {0} -B {0}/build "
        "-DCMAKE_BUILD_TYPE=Release && cmake --build {0}/build) or set ARCUS_LIBRARY to the path of libarcus."
        .format(root)
    )


def load():
    """Loads libarcus; returns (ctypes.CDLL, the path or name it was loaded from).

    Order: the ARCUS_LIBRARY environment variable (authoritative: if it is set and
    unusable that is an error, never silently replaced by another build), the one
    installed inside the package, a build in the source tree, an installed library.  Raises LibraryNotFoundError listing every
    place tried and why each failed.
    """
    explicit = os.environ.get("ARCUS_LIBRARY")
    if explicit:
        try:
            return _open(explicit), explicit
        except (OSError, AttributeError) as exc:
            raise LibraryNotFoundError(
                "ARCUS_LIBRARY=%s could not be loaded as libarcus: %s. Point ARCUS_LIBRARY at a built "
                "libarcus.so, or unset it to search the source tree and installed locations." % (explicit, exc)
            ) from None

    tried = ["ARCUS_LIBRARY environment variable: not set"]
    for description, path in _candidates():
        if path is None:
            tried.append("%s: nothing found" % description)
            continue
        # A bare name from find_library is resolved by the dynamic loader; a path that
        # does not exist is simply not there and is not worth an OSError's wording.
        if os.sep in path and not os.path.exists(path):
            tried.append("%s: %s (not found)" % (description, path))
            continue
        try:
            return _open(path), path
        except (OSError, AttributeError) as exc:
            tried.append("%s: %s (%s)" % (description, path, exc))
    raise LibraryNotFoundError(
        "libarcus could not be found. Looked in:\n  " + "\n  ".join(tried) + "\n" + _how_to_fix()
    )


lib, library_path = load()
#: The engines the loaded library was built with ({"curved", "render", "ocean", "rainbow"}
#: by default); the calls of the others raise arcus.Error.
ENGINES = frozenset(_engines_built(lib))


# ---- errors ---------------------------------------------------------------------------


def decode(raw):
    """A C string from the library as str ('' for NULL)."""
    return raw.decode("utf-8", "replace") if raw else ""


def status_name(code):
    """The library's name for an arcus_status value."""
    return decode(lib.arcus_status_string(code))


def last_error(ctx_handle=None):
    """The message of the last failed call: per context if given, else per thread."""
    if ctx_handle is not None:
        return decode(lib.arcus_context_last_error(ctx_handle))
    return decode(lib.arcus_last_error())


def check(code, ctx_handle=None):
    """Raises the matching arcus.Error when ``code`` is not ARCUS_SUCCESS.

    The message is read at once because the library keeps it only until the next call.
    """
    if code != 0:
        raise error_for(code, last_error(ctx_handle), status_name(code))


def _read_features():
    """Kernel feature name -> ARCUS_FEATURE_* bit, from the library's own table."""
    table = {}
    buffer = ctypes.create_string_buffer(256)
    for shift in range(64):
        if lib.arcus_features_to_string(1 << shift, buffer, len(buffer)) == 0:
            table[decode(buffer.value)] = 1 << shift
    return table


#: Kernel feature name -> bit (ARCUS_FEATURE_*), as the library defines them.
FEATURES = _read_features()


def feature_names(bits):
    """The names of the ARCUS_FEATURE_* bits set in ``bits``, as a frozenset."""
    return frozenset(name for name, bit in FEATURES.items() if bits & bit)


def vec3(values):
    """A ``double[3]`` for the ``const double v[3]`` parameters."""
    return (c_double * 3)(*values)


def ptr(array, ctype=c_double):
    """A pointer to the data of a C-contiguous numpy array (or NULL for None)."""
    if array is None:
        return None
    return array.ctypes.data_as(POINTER(ctype))
