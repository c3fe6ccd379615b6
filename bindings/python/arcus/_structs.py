"""The ctypes mirror of the structs of include/arcus/arcus.h: field order and types
exactly as in C (tests/python/test_library.py checks every size and offset against the
compiled library), and the callback types.  Imported through :mod:`arcus._lib`."""

import ctypes
from ctypes import POINTER, c_char, c_char_p, c_double, c_int, c_int32, c_uint32, c_uint64, c_void_p

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
        ("wavelengths_per_photon", c_uint32),
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
        ("estimate_stride", c_uint32),
        ("photon_tile", c_double),
        ("step_subsample", c_uint32),
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
        ("temperature_k", c_double),
        ("refractive_index", c_double),
        ("grid", c_uint32),
        ("alpha", c_double),
        ("max_bounces", c_uint32),
        ("edge_rays", c_int32),
        ("rotation", c_double * 9),
        ("query_phi_deg", c_double),
        ("progress", PROGRESS_CALLBACK),
        ("progress_user", c_void_p),
        ("temperature_c", c_double),  # deprecated (0.9, °C): NaN, unused here
    ]


class RainbowStatsStruct(ctypes.Structure):
    """arcus_rainbow_stats."""

    _fields_ = [("refractive_index", c_double)] + [
        (name, c_uint64) for name in ("rays", "hits", "edge_rays", "patches", "patches_rejected",
                                      "patches_folded")] + [
        ("intercepted", c_double), ("scattered", c_double * 16), ("remaining", c_double)] + [
        (name, c_double) for name in ("cast_seconds", "patch_seconds", "bvh_seconds", "query_seconds")]


class DaylightDescStruct(ctypes.Structure):
    """arcus_daylight_desc."""

    _fields_ = [("site_height", c_double), ("ozone_du", c_double), ("aerosol_depth_500", c_double),
                ("angstrom_exponent", c_double), ("aerosol_scale_height", c_double), ("co2_ppm", c_double),
                ("aerosol_albedo", c_double), ("aerosol_asymmetry", c_double), ("ground_albedo", c_double)]


class OpticalDepthsStruct(ctypes.Structure):
    """arcus_optical_depths."""

    _fields_ = [("rayleigh", c_double), ("ozone", c_double), ("aerosol", c_double)]


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


class DipoleStruct(ctypes.Structure):
    _fields_ = [
        ("sigma_a", c_double * 3),
        ("sigma_s_prime", c_double * 3),
        ("eta", c_double),
    ]


class DirectionalLightStruct(ctypes.Structure):
    _fields_ = [
        ("direction", c_double * 3),
        ("irradiance", c_double * 3),
    ]


class TranslucencyRenderParamsStruct(ctypes.Structure):
    _fields_ = [
        ("camera", CameraStruct),
        ("ortho_height", c_double),
        ("mm_per_unit", c_double),
        ("exit", c_int32),
        ("profile_scale", c_double),
        ("profile_scaling", c_int32),
        ("sample_spacing_mm", c_double),
        ("gather", c_int32),
        ("max_solid_angle", c_double),
        ("highlight_deg", c_double),
        ("progress", PROGRESS_CALLBACK),
        ("progress_user", c_void_p),
    ]


class TranslucencyRenderStatsStruct(ctypes.Structure):
    _fields_ = [
        ("width", c_uint32),
        ("height", c_uint32),
        ("samples", c_uint64),
        ("sample_spacing_mm", c_double),
        ("surface_area_mm2", c_double),
        ("covered_pixels", c_uint64),
        ("tree_nodes", c_uint64),
        ("mean_visits", c_double),
        ("irradiance_seconds", c_double),
        ("gather_seconds", c_double),
    ]


class ProfileTableStruct(ctypes.Structure):
    _fields_ = [
        ("count", c_uint32),
        ("reach_mm", c_double),
        ("values", ctypes.POINTER(c_double)),
        ("eta", c_double),
    ]


#: int32_t (*arcus_generation_callback)(void* user, uint32_t generation, double best, const double* genes)
GENERATION_CALLBACK = ctypes.CFUNCTYPE(c_int32, c_void_p, c_uint32, c_double, ctypes.POINTER(c_double))


class GeneticParamsStruct(ctypes.Structure):
    _fields_ = [
        ("camera", CameraStruct),
        ("ortho_height", c_double),
        ("mm_per_unit", c_double),
        ("model", c_int32),
        ("population", c_uint32),
        ("generations", c_uint32),
        ("replacement", c_double),
        ("crossover", c_double),
        ("mutation", c_double),
        ("mutation_range", c_double),
        ("fitness_threshold", c_double),
        ("fitness_space", c_int32),
        ("seed", c_uint64),
        ("initial", c_double * 9),
        ("lower", c_double * 9),
        ("upper", c_double * 9),
        ("progress", PROGRESS_CALLBACK),
        ("progress_user", c_void_p),
        ("on_generation", GENERATION_CALLBACK),
        ("generation_user", c_void_p),
        ("polish_steps", c_uint32),
    ]


class GeneticResultStruct(ctypes.Structure):
    _fields_ = [
        ("model", c_int32),
        ("gene_count", c_uint32),
        ("generations_run", c_uint32),
        ("evaluations", c_uint64),
        ("best", c_double * 9),
        ("best_fitness", c_double),
        ("sigma_s_prime", c_double * 3),
        ("pixels", c_uint32),
        ("samples", c_uint64),
        ("cache_seconds", c_double),
        ("search_seconds", c_double),
        ("search_fitness", c_double),
        ("polish_steps", c_uint32),
        ("polish_evaluations", c_uint64),
        ("polish_seconds", c_double),
    ]


class TranslucencyEstimateParamsStruct(ctypes.Structure):
    _fields_ = [
        ("camera", CameraStruct),
        ("ortho_height", c_double),
        ("mm_per_unit", c_double),
        ("eta", c_double),
        ("exit", c_int32),
        ("basis_count", c_uint32),
        ("basis", c_int32),
        ("r_max_mm", c_double),
        ("max_side", c_uint32),
        ("remove_highlights", c_int32),
        ("subtract_minimum", c_int32),
        ("fit", c_int32),
        ("progress", PROGRESS_CALLBACK),
        ("progress_user", c_void_p),
        ("tikhonov", c_double),
        ("nonnegative", c_int32),
    ]


class DipoleTermsStruct(ctypes.Structure):
    _fields_ = [
        ("albedo", c_double * 3),
        ("sigma_t_prime", c_double * 3),
        ("sigma_tr", c_double * 3),
        ("diffuse_length", c_double * 3),
        ("z_r", c_double * 3),
        ("z_v", c_double * 3),
        ("total_reflectance", c_double * 3),
        ("diffusive", c_int32 * 3),
        ("f_dr", c_double),
        ("a", c_double),
        ("exit_transmittance", c_double),
    ]


#: void (*arcus_error_callback)(void* user, arcus_status status, const char* message)
ERROR_CALLBACK = ctypes.CFUNCTYPE(None, c_void_p, c_int, c_char_p)


class DetectedLightStruct(ctypes.Structure):
    _fields_ = [
        ("azimuth_deg", c_double),
        ("zenith_deg", c_double),
        ("direction", c_double * 3),
        ("intensity", c_double),
        ("azimuth_spread_deg", c_double),
        ("zenith_spread_deg", c_double),
    ]


MAX_DETECTED_LIGHTS = 4  # ARCUS_MAX_DETECTED_LIGHTS


class LightDetectionStruct(ctypes.Structure):
    _fields_ = [
        ("count", c_uint32),
        ("lights", DetectedLightStruct * MAX_DETECTED_LIGHTS),
        ("object_pixels", c_uint32),
        ("contour_pixels", c_uint32),
        ("segmented", c_int32),
        ("contour_misfit", c_double),
        ("seconds", c_double),
    ]


class PhotoShapeParamsStruct(ctypes.Structure):
    _fields_ = [
        ("method", c_int32),
        ("sigma_spatial", c_double),
        ("sigma_intensity", c_double),
        ("base_weight", c_double),
        ("detail_weight", c_double),
        ("inflation", c_double),
        ("relief", c_double),
    ]


class TranslucencyAutoParamsStruct(ctypes.Structure):
    _fields_ = [
        ("estimate", TranslucencyEstimateParamsStruct),
        ("shape", PhotoShapeParamsStruct),
        ("mm_per_pixel", c_double),
        ("irradiance", c_double * 3),
    ]


class TranslucencyEstimateResultStruct(ctypes.Structure):
    _fields_ = [
        ("width", c_uint32),
        ("height", c_uint32),
        ("object_pixels", c_uint32),
        ("equation_pixels", c_uint32),
        ("highlight_cut", c_double),
        ("minimum_subtracted", c_double * 3),
        ("r_max_mm", c_double),
        ("basis_count", c_uint32),
        ("dipole", DipoleStruct),
        ("terms", DipoleTermsStruct),
        ("iterations", c_int32 * 3),
        ("residual", c_double * 3),
        ("condition_a", c_double * 3),
        ("condition_normal", c_double * 3),
        ("dropped_columns", c_uint32 * 3),
        ("fit_error", c_double * 3),
        ("geometry_seconds", c_double),
        ("histogram_seconds", c_double),
        ("solve_seconds", c_double),
        ("basis", c_int32),
        ("near_radius_mm", c_double),
        ("image_error", c_double * 3),
        ("refined_radius_mm", c_double),
        ("sub_source_count", c_uint32),
    ]
