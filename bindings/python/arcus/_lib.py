"""Finding and loading libarcus, and the ctypes mirror of include/arcus/arcus.h.

Everything that knows the C ABI lives here: struct layouts, function prototypes and
the translation of a failed ``arcus_status`` into a Python exception.  The rest of the
package only calls ``lib.<function>`` and :func:`check`.
"""

import ctypes
import ctypes.util
import os
import sys
from ctypes import POINTER, c_char, c_char_p, c_double, c_int, c_int32, c_size_t, c_uint32, c_uint64, c_void_p
from pathlib import Path

from ._errors import LibraryNotFoundError, error_for

# The file name CMake gives the shared library on each platform.
_LIBRARY_NAME = {"darwin": "libarcus.dylib", "win32": "arcus.dll"}.get(sys.platform, "libarcus.so")

# ---- structs (field order and types exactly as in arcus.h) ---------------------------
# C enums are passed as `int`, which is what every ABI arcus targets uses for them.


class DeviceInfoStruct(ctypes.Structure):
    """arcus_device_info."""

    _fields_ = [
        ("index", c_uint32),
        ("name", c_char * 256),
        ("platform", c_char * 256),
        ("version", c_char * 128),
        ("is_gpu", c_int32),
        ("fp64", c_int32),
        ("compute_units", c_uint32),
        ("global_memory", c_uint64),
        ("lanes", c_uint32),
    ]


class InversionStruct(ctypes.Structure):
    """arcus_inversion."""

    _fields_ = [("base", c_double), ("top", c_double), ("delta_t", c_double)]


class AtmosphereDescStruct(ctypes.Structure):
    """arcus_atmosphere_desc."""

    _fields_ = [
        ("spherical", c_int32),
        ("wavelength", c_double),
        ("sea_level_temperature", c_double),
        ("sea_level_pressure", c_double),
        ("inversion_count", c_uint32),
        ("inversions", POINTER(InversionStruct)),
    ]


#: int32_t (*arcus_progress_callback)(void* user, double fraction)
PROGRESS_CALLBACK = ctypes.CFUNCTYPE(c_int32, c_void_p, c_double)


class AdvanceParamsStruct(ctypes.Structure):
    """arcus_advance_params."""

    _fields_ = [
        ("method", c_int),
        ("precision", c_int),
        ("length", c_double),
        ("step", c_double),
        ("rtol", c_double),
        ("atol", c_double),
        ("min_step", c_double),
        ("max_step", c_double),
        ("max_rejections", c_uint32),
        ("max_steps", c_uint64),
        ("use_box", c_int32),
        ("box_min", c_double * 3),
        ("box_max", c_double * 3),
        ("record_path", c_int32),
        ("path_capacity", c_uint32),
        ("progress", PROGRESS_CALLBACK),  # NULL: PROGRESS_CALLBACK()
        ("progress_user", c_void_p),
    ]


class JobStatsStruct(ctypes.Structure):
    """arcus_job_stats."""

    _fields_ = [
        ("build_seconds", c_double),
        ("kernel_seconds", c_double),
        ("total_seconds", c_double),
        ("program_origin", c_int32),
        ("lanes", c_uint32),
        ("groups", c_uint32),
        ("launches", c_uint32),
    ]


class CameraStruct(ctypes.Structure):
    _fields_ = [
        ("position", c_double * 3),
        ("look_at", c_double * 3),
        ("up", c_double * 3),
        ("vfov_deg", c_double),
        ("width", c_uint32),
        ("height", c_uint32),
    ]


class RenderStatsStruct(ctypes.Structure):
    _fields_ = [(name, c_double) for name in
                ("trace_seconds", "walk_seconds", "photon_seconds", "shade_seconds", "total_seconds")] + [
        (name, c_uint64) for name in
        ("pixels", "rays_traced", "rays_mirrored", "rays_interpolated", "rays_cached", "rays_unresolved", "steps",
         "tests", "shadow_rays", "photons", "cache_bytes")] + [("techniques", c_uint32)]



# ---- the ocean engine (arcus_ocean.h) --------------------------------------------------


class WavelengthGridStruct(ctypes.Structure):
    _fields_ = [("first_nm", c_double), ("step_nm", c_double), ("count", c_uint32)]


class SpectrumStruct(ctypes.Structure):
    _fields_ = [("count", c_uint32), ("nm", POINTER(c_double)), ("values", POINTER(c_double))]


class PhaseFunctionStruct(ctypes.Structure):
    _fields_ = [
        ("kind", c_int32),
        ("a", c_double),
        ("g_forward", c_double),
        ("g_backward", c_double),
        ("forward_weight", c_double),
        ("table_count", c_uint32),
        ("table_cosines", POINTER(c_double)),
        ("table_values", POINTER(c_double)),
    ]


class BioOpticalStruct(ctypes.Structure):
    _fields_ = [(name, c_double) for name in (
        "chlorophyll", "a_d400", "a_y440", "s_d", "s_y", "chlorophyll_yield", "cdom_yield_scale", "raman_scale",
        "detritus_scattering_reference_a_d400")] + [("detritus_phase", PhaseFunctionStruct),
                                                    ("stokes_only", c_int32)]


class WaterIopsStruct(ctypes.Structure):
    _fields_ = [
        ("absorption", SpectrumStruct),
        ("scattering", SpectrumStruct),
        ("phase", PhaseFunctionStruct),
        ("raman", c_int32),
        ("chlorophyll", c_double),
        ("chlorophyll_yield", c_double),
        ("a_y440", c_double),
        ("s_y", c_double),
        ("stokes_only", c_int32),
    ]


class OceanLightStruct(ctypes.Structure):
    _fields_ = [
        ("kind", c_int32),
        ("position", c_double * 3),
        ("direction", c_double * 3),
        ("half_angle_deg", c_double),
        ("radius", c_double),
        ("spectrum", SpectrumStruct),
    ]


class OceanSetupStruct(ctypes.Structure):
    _fields_ = [
        ("grid", WavelengthGridStruct),
        ("light_count", c_uint32),
        ("lights", POINTER(OceanLightStruct)),
        ("surface", c_int32),
        ("n_water", c_double),
        ("bottom_depth", c_double),
        ("bottom_albedo", c_double),
        ("box_lo", c_double * 3),
        ("box_hi", c_double * 3),
        ("depth_count", c_uint32),
        ("depths", POINTER(c_double)),
        ("layer", c_double),
    ]


class OceanTraceParamsStruct(ctypes.Structure):
    _fields_ = [
        ("photons", c_uint64),
        ("max_interactions", c_uint32),
        ("seed", c_uint64),
        ("store_photons", c_int32),
        ("force_inelastic", c_int32),
        ("progress", PROGRESS_CALLBACK),
        ("progress_user", c_void_p),
    ]


class OceanTalliesStruct(ctypes.Structure):
    _fields_ = [(name, c_uint64) for name in ("photons", "interactions", "stored")] + [
        (name, c_double) for name in ("emitted", "past_limit", "bottom", "escaped", "absorbed")] + [
        (name, c_double * 10) for name in ("count", "arriving", "absorbed_by")] + [
        ("max_interactions", c_uint32), ("interaction_bins", c_uint32)]

class OceanMarchStruct(ctypes.Structure):
    _fields_ = [
        ("steps", c_uint32),
        ("distance", c_double),
        ("k", c_uint32),
        ("estimator", c_int32),
        ("single_scattering", c_int32),
        ("multiple_scattering", c_int32),
        ("exposure", c_double),
    ]


class OceanRenderStatsStruct(ctypes.Structure):
    _fields_ = [(name, c_double) for name in ("trace_seconds", "map_seconds", "estimate_seconds", "total_seconds")] + [
        ("photons_stored", c_uint64)]



# ---- rainbows and Lorenz–Mie (arcus_rainbow.h) ----------------------------------------


class ParticleInfoStruct(ctypes.Structure):
    """arcus_particle_info."""

    _fields_ = [("kind", c_int32), ("equivalent_radius", c_double), ("volume", c_double),
                ("bound_radius", c_double), ("triangles", c_uint32)]


class RainbowParamsStruct(ctypes.Structure):
    """arcus_rainbow_params."""

    _fields_ = [
        ("wavelength_nm", c_double),
        ("material", c_int32),
        ("temperature_c", c_double),
        ("refractive_index", c_double),
        ("grid", c_uint32),
        ("alpha", c_double),
        ("max_bounces", c_uint32),
        ("edge_rays", c_int32),
        ("rotation", c_double * 9),
        ("query_phi_deg", c_double),
        ("progress", PROGRESS_CALLBACK),
        ("progress_user", c_void_p),
    ]


class RainbowStatsStruct(ctypes.Structure):
    """arcus_rainbow_stats."""

    _fields_ = [("refractive_index", c_double)] + [
        (name, c_uint64) for name in ("rays", "hits", "edge_rays", "patches", "patches_rejected",
                                      "patches_folded")] + [
        ("intercepted", c_double), ("scattered", c_double * 16), ("remaining", c_double)] + [
        (name, c_double) for name in ("cast_seconds", "patch_seconds", "bvh_seconds", "query_seconds")]


class MieEfficienciesStruct(ctypes.Structure):
    """arcus_mie_efficiencies."""

    _fields_ = [("q_ext", c_double), ("q_sca", c_double), ("q_back", c_double), ("g", c_double)]


class RainbowTableStruct(ctypes.Structure):
    """arcus_rainbow_table."""

    _fields_ = [
        ("wavelength_count", c_uint32),
        ("wavelengths_nm", POINTER(c_double)),
        ("theta_count", c_uint32),
        ("theta_first_deg", c_double),
        ("theta_last_deg", c_double),
        ("phi_count", c_uint32),
        ("scattering", POINTER(c_double)),
        ("extinction", POINTER(c_double)),
    ]


class RainbowSkyStruct(ctypes.Structure):
    """arcus_rainbow_sky."""

    _fields_ = [
        ("width", c_uint32),
        ("height", c_uint32),
        ("camera_position", c_double * 3),
        ("camera_forward", c_double * 3),
        ("camera_up", c_double * 3),
        ("fov_deg", c_double),
        ("sun_elevation_deg", c_double),
        ("sun_azimuth_deg", c_double),
        ("sun_diameter_deg", c_double),
        ("sun_samples", c_uint32),
        ("sun_irradiance", POINTER(c_double)),
        ("sky_radiance", POINTER(c_double)),
        ("ground_radiance", POINTER(c_double)),
        ("sky_image", POINTER(ctypes.c_float)),
        ("sky_image_width", c_uint32),
        ("sky_image_height", c_uint32),
        ("sky_image_scale", c_double),
        ("rain_min", c_double * 3),
        ("rain_max", c_double * 3),
        ("march_steps", c_uint32),
        ("exposure", c_double),
        ("progress", PROGRESS_CALLBACK),
        ("progress_user", c_void_p),
    ]


#: void (*arcus_error_callback)(void* user, arcus_status status, const char* message)
ERROR_CALLBACK = ctypes.CFUNCTYPE(None, c_void_p, c_int, c_char_p)

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
    "arcus_advance": (
        _status,
        [_handle, _handle, POINTER(AdvanceParamsStruct), c_size_t, _dvec, _dvec, _dvec, _out_handle],
    ),
    "arcus_job_retain": (_status, [_handle]),
    "arcus_job_release": (_status, [_handle]),
    "arcus_job_get_count": (_status, [_handle, POINTER(c_size_t)]),
    "arcus_job_get_end_states": (
        _status,
        [_handle, _dvec, _dvec, POINTER(c_uint64), POINTER(c_int32), _dvec],
    ),
    "arcus_job_get_path_size": (_status, [_handle, POINTER(c_size_t)]),
    "arcus_job_get_paths": (_status, [_handle, POINTER(c_uint64), _dvec, POINTER(c_uint64)]),
    "arcus_job_get_failures": (_status, [_handle, POINTER(c_int32)]),
    "arcus_job_get_features": (_status, [_handle, POINTER(c_uint64)]),
    "arcus_job_get_stats": (_status, [_handle, POINTER(JobStatsStruct)]),
    "arcus_scene_load": (_status, [_handle, c_char_p, _out_handle]),
    "arcus_scene_retain": (_status, [_handle]),
    "arcus_scene_release": (_status, [_handle]),
    "arcus_scene_get_name": (_status, [_handle, POINTER(c_char_p)]),
    "arcus_scene_get_description": (_status, [_handle, POINTER(c_char_p)]),
    "arcus_scene_get_document": (_status, [_handle, POINTER(c_char_p)]),
    "arcus_scene_get_engine": (_status, [_handle, POINTER(c_char_p)]),
    "arcus_scene_get_field": (_status, [_handle, _out_handle]),
    "arcus_scene_get_advance_params": (_status, [_handle, POINTER(AdvanceParamsStruct)]),
    "arcus_scene_get_ray_count": (_status, [_handle, POINTER(c_size_t)]),
    "arcus_scene_get_rays": (_status, [_handle, _dvec, _dvec, _dvec, POINTER(c_int32)]),
    "arcus_scene_advance": (_status, [_handle, PROGRESS_CALLBACK, c_void_p, _out_handle]),
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
    "arcus_job_get_image_size": (_status, [_handle, POINTER(c_uint32), POINTER(c_uint32)]),
    "arcus_job_get_image": (_status, [_handle, POINTER(ctypes.c_float)]),
    "arcus_job_get_hits": (
        _status,
        [_handle, _dvec, POINTER(c_int32), POINTER(c_int32), _dvec, POINTER(c_uint32), POINTER(c_uint32)],
    ),
    "arcus_job_write_image": (_status, [_handle, c_char_p, c_char_p]),
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
    "arcus_refractive_index": (_status, [c_int32, c_double, c_double, _dvec]),
    "arcus_particle_create_sphere": (_status, [_handle, c_double, _out_handle]),
    "arcus_particle_create_raindrop": (_status, [_handle, c_double, _out_handle]),
    "arcus_particle_create_mesh": (_status, [_handle, c_char_p, c_double, c_int32, _out_handle]),
    "arcus_particle_retain": (_status, [_handle]),
    "arcus_particle_release": (_status, [_handle]),
    "arcus_particle_get_info": (_status, [_handle, POINTER(ParticleInfoStruct)]),
    "arcus_rainbow_params_init": (_status, [POINTER(RainbowParamsStruct)]),
    "arcus_rainbow_cast": (_status, [_handle, _handle, POINTER(RainbowParamsStruct), _out_handle]),
    "arcus_job_get_rainbow_stats": (_status, [_handle, POINTER(RainbowStatsStruct)]),
    "arcus_job_rainbow_phase": (_status, [_handle, c_size_t, _dvec, _dvec, c_int32, _dvec, _dvec, _dvec]),
    "arcus_job_rainbow_phasors": (_status, [_handle, c_size_t, _dvec, _dvec, _dvec]),
    "arcus_job_get_rainbow_glints": (_status, [_handle, POINTER(c_size_t), POINTER(c_uint32), _dvec, _dvec, _dvec]),
    "arcus_rainbow_sky_init": (_status, [POINTER(RainbowSkyStruct)]),
    "arcus_rainbow_render": (_status, [_handle, POINTER(RainbowTableStruct), POINTER(RainbowSkyStruct), _out_handle]),
    "arcus_job_get_rainbow_image": (
        _status, [_handle, POINTER(c_uint32), POINTER(c_uint32), POINTER(ctypes.c_float), POINTER(ctypes.c_float),
                  POINTER(ctypes.c_float)]),
    "arcus_job_write_rainbow_image": (_status, [_handle, c_char_p, c_char_p]),
    "arcus_image_read": (_status, [c_char_p, POINTER(c_uint32), POINTER(c_uint32), POINTER(ctypes.c_float),
                                   ctypes.c_size_t]),
    "arcus_mie": (
        _status,
        [c_double, c_double, c_double, c_double, c_size_t, _dvec, _dvec, _dvec, _dvec, _dvec,
         POINTER(MieEfficienciesStruct)],
    ),
    "arcus_mie_debye": (
        _status,
        [c_double, c_double, c_double, c_double, c_uint32, c_size_t, _dvec, _dvec, _dvec, _dvec, _dvec],
    ),
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
    root = _source_root()
    if root is None:
        yield "source tree", None
    else:
        others = sorted(p for p in root.glob("build*") if p.is_dir() and p.name != "build")
        for build in [root / "build"] + others:
            yield "source tree build", str(build / _LIBRARY_NAME)
    yield "installed (ctypes.util.find_library('arcus'))", ctypes.util.find_library("arcus")
    yield "installed (sys.prefix)", str(Path(sys.prefix) / "lib" / _LIBRARY_NAME)


def _open(path):
    """ctypes.CDLL(path) with every prototype set; raises OSError or AttributeError."""
    dll = ctypes.CDLL(path)
    for name, (restype, argtypes) in _PROTOTYPES.items():
        func = getattr(dll, name)  # AttributeError names the missing symbol
        func.restype = restype
        func.argtypes = argtypes
    return dll


def _how_to_fix():
    root = _source_root() or "<arcus source>"
    return (
        "Build the library (cmake -S {0} -B {0}/build -DCMAKE_BUILD_TYPE=Release && cmake --build {0}/build) "
        "or set ARCUS_LIBRARY to the path of libarcus.".format(root)
    )


def load():
    """Loads libarcus; returns (ctypes.CDLL, the path or name it was loaded from).

    Order: the ARCUS_LIBRARY environment variable (authoritative: if it is set and
    unusable that is an error, never silently replaced by another build), a build in
    the source tree, an installed library.  Raises LibraryNotFoundError listing every
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
