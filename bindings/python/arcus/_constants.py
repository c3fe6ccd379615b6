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
#: DP45 could not meet the tolerance, or the state became non-finite.
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

# arcus_status values the binding has to tell apart; every other failure is simply
# raised with the library's name for it.
SUCCESS = 0
ERROR_INVALID_RAYS = 8
ERROR_PATH_OVERFLOW = 9
ERROR_CANCELLED = 10

