"""Constants mirrored from include/arcus/arcus.h.

The C header is the contract; these values must match it exactly (the tests compare
the defaults with the library).  Kernel feature names come from the library itself
(arcus.FEATURES), which holds the one table of them.
"""

#: Earth's radius in metres used by the spherical atmosphere (ARCUS_EARTH_RADIUS).
EARTH_RADIUS = 6371000.0

#: Device index meaning "the ARCUS_DEVICE environment variable, else the first GPU,
#: else the first CPU" (ARCUS_DEVICE_DEFAULT).
DEVICE_DEFAULT = -1

# Per-ray status (arcus_ray_status).
#: The ray reached the requested arc length.
RAY_DONE = 0
#: The ray left the box; its end state is where the path crossed the box.
RAY_LEFT_BOX = 1
#: ``max_steps`` accepted steps were taken before reaching the length.
RAY_STEP_LIMIT = 2
#: The ray failed; AdvanceResult.failures says why (FAILURE_*).
RAY_FAILED = 3
#: NaN/Inf origin or direction, a zero direction, or a wavelength outside 300..1690 nm;
#: the ray was not traced.
RAY_INVALID_INPUT = 4
#: The job was cancelled (the progress callback asked so) before the ray finished.
RAY_CANCELLED = 5

#: Per-ray status code -> name ("DONE", "LEFT_BOX", ...).
RAY_STATUS_NAMES = {
    RAY_DONE: "DONE",
    RAY_LEFT_BOX: "LEFT_BOX",
    RAY_STEP_LIMIT: "STEP_LIMIT",
    RAY_FAILED: "FAILED",
    RAY_INVALID_INPUT: "INVALID_INPUT",
    RAY_CANCELLED: "CANCELLED",
}

# Why a ray failed (arcus_ray_failure, AdvanceResult.failures).
#: The ray did not fail.
FAILURE_NONE = 0
#: dp45: no step >= min_step met the tolerance within max_rejections tries.
FAILURE_TOLERANCE = 1
#: The state became NaN or infinite (overflow).
FAILURE_NOT_FINITE = 2
#: The ray reached a point where n <= 0.
FAILURE_INDEX_NOT_POSITIVE = 3

#: Failure code -> name ("NONE", "TOLERANCE", ...).
FAILURE_NAMES = {
    FAILURE_NONE: "NONE",
    FAILURE_TOLERANCE: "TOLERANCE",
    FAILURE_NOT_FINITE: "NOT_FINITE",
    FAILURE_INDEX_NOT_POSITIVE: "INDEX_NOT_POSITIVE",
}

#: Integration method name -> arcus_method value.  ``"dp45"`` is adaptive
#: (Dormand-Prince 5(4)); the others take fixed steps of size ``step``.
METHODS = {"euler": 0, "rk2": 1, "rk4": 2, "dp45": 3}

#: Precision name -> arcus_precision value.
PRECISIONS = {"double": 0, "float": 1}

#: Field kind value (arcus_field_kind) -> name.
FIELD_KINDS = {
    0: "CONSTANT",
    1: "LINEAR",
    2: "LINEAR_N2",
    3: "LUNEBURG",
    4: "FISHEYE",
    5: "ATMOSPHERE",
    6: "GRID",
}

#: arcus_program_origin value -> AdvanceResult.stats["program_origin"].
PROGRAM_ORIGINS = {0: "built", 1: "memory cache", 2: "disk cache"}

# arcus_status values the binding has to tell apart; every other failure is simply
# raised with the library's name for it.
SUCCESS = 0
ERROR_UNSUPPORTED = 4
#: The job exists and holds every ray's result; the error carries it (Error.result).
ERROR_INVALID_RAYS = 8
ERROR_PATH_OVERFLOW = 9
ERROR_CANCELLED = 10
PARTIAL_RESULTS = (ERROR_INVALID_RAYS, ERROR_PATH_OVERFLOW, ERROR_CANCELLED)

