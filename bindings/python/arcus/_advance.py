"""The advance's parameters (Python keywords to arcus_advance_params and back), its
result (:class:`AdvanceResult`) and the progress callback's check."""

from ctypes import byref
from dataclasses import dataclass

import numpy as np

from . import _constants as C
from . import _lib
from ._args import to_bool, to_choice, to_float, to_int, to_vec3
from ._errors import ArgumentError
from ._lib import lib


_UINT32_MAX = 2**32 - 1
_UINT64_MAX = 2**64 - 1

# Context.advance keyword -> its conversion to the arcus_advance_params member of the
# same name.  Integers are range-checked because ctypes would silently wrap them.
_PARAM_CONVERSIONS = {
    "method": lambda v: to_choice(v, "method", C.METHODS),
    "precision": lambda v: to_choice(v, "precision", C.PRECISIONS),
    "length": lambda v: to_float(v, "length"),
    "step": lambda v: to_float(v, "step"),
    "rtol": lambda v: to_float(v, "rtol"),
    "atol": lambda v: to_float(v, "atol"),
    "min_step": lambda v: to_float(v, "min_step"),
    "max_step": lambda v: to_float(v, "max_step"),
    "max_rejections": lambda v: to_int(v, "max_rejections", 0, _UINT32_MAX),
    "max_steps": lambda v: to_int(v, "max_steps", 0, _UINT64_MAX),
    "path_capacity": lambda v: to_int(v, "path_capacity", 0, _UINT32_MAX),
    "record_path": lambda v: int(to_bool(v, "record_path")),
}


def _advance_params(options):
    """arcus_advance_params: the library's defaults, overridden by every option not None."""
    params = _lib.AdvanceParamsStruct()
    _lib.check(lib.arcus_advance_params_init(byref(params)))
    for name, value in options.items():
        if value is None:
            continue
        if name == "box":
            if isinstance(value, (str, bytes)):
                raise ArgumentError("box must be (min, max), two 3-vectors, got %r" % (value,))
            try:
                low, high = value
            except (TypeError, ValueError):
                raise ArgumentError("box must be (min, max), two 3-vectors, got %r" % (value,)) from None
            params.use_box = 1
            params.box_min = _lib.vec3(to_vec3(low, "box min"))
            params.box_max = _lib.vec3(to_vec3(high, "box max"))
        else:
            setattr(params, name, _PARAM_CONVERSIONS[name](value))
    return params


_METHOD_NAMES = {value: name for name, value in C.METHODS.items()}
_PRECISION_NAMES = {value: name for name, value in C.PRECISIONS.items()}


def _advance_options(params):
    """The keyword arguments of Context.advance that state ``params`` (no progress)."""
    return {
        "method": _METHOD_NAMES[params.method],
        "precision": _PRECISION_NAMES[params.precision],
        "length": params.length,
        "step": params.step,
        "rtol": params.rtol,
        "atol": params.atol,
        "min_step": params.min_step,
        "max_step": params.max_step,
        "max_rejections": int(params.max_rejections),
        "max_steps": int(params.max_steps),
        "box": (tuple(params.box_min), tuple(params.box_max)) if params.use_box else None,
        "record_path": bool(params.record_path),
        "path_capacity": int(params.path_capacity),
    }


def _check_progress(progress):
    if progress is not None and not callable(progress):
        raise ArgumentError("progress must be a callable (fraction -> cancel?) or None, got %r" % (progress,))


# ---- results --------------------------------------------------------------------------


@dataclass(eq=False)  # element-wise array comparison has no single truth value
class AdvanceResult:
    """Every ray's result of :meth:`Context.advance` or :meth:`Scene.advance` (N rays).

    Attributes:
        positions: (N, 3) end positions.
        directions: (N, 3) unit end directions.
        steps: (N,) uint64 accepted steps.
        status: (N,) int32 per-ray status (:data:`arcus.RAY_DONE`, ...).
        lengths: (N,) arc length travelled.
        failures: (N,) int32 why each ``RAY_FAILED`` ray failed
            (:data:`arcus.FAILURE_TOLERANCE`, ...); :data:`arcus.FAILURE_NONE` for the others.
        features: names of the kernel features the job compiled with, e.g.
            ``{"CURVED_DP45", "CURVED_FIELD_LINEAR"}``; ``feature_bits`` is the raw bit mask.
        stats: timings and layout: build_seconds, kernel_seconds, total_seconds,
            program_origin ("built", "memory cache" or "disk cache"), launches (slices),
            lanes, groups.
        paths: with ``record_path``, ray i's kept points as a (k_i, 3) array (views into
            ``path_points``); None otherwise.
        path_offsets: (N + 1,) uint64; ray i's points are
            ``path_points[path_offsets[i]:path_offsets[i + 1]]``.
        path_points: (M, 3) every kept point of every ray.
        path_needed: (N,) uint64 points each full path has (more than kept when the
            path capacity overflowed).
    """

    positions: np.ndarray
    directions: np.ndarray
    steps: np.ndarray
    status: np.ndarray
    lengths: np.ndarray
    failures: np.ndarray
    features: frozenset
    feature_bits: int
    stats: dict
    paths: list = None
    path_offsets: np.ndarray = None
    path_points: np.ndarray = None
    path_needed: np.ndarray = None

    def __len__(self):
        return len(self.positions)

    @property
    def status_names(self):
        """Per-ray status as names ("DONE", "LEFT_BOX", ...)."""
        return [C.RAY_STATUS_NAMES.get(int(s), str(int(s))) for s in self.status]

    @property
    def failure_names(self):
        """Per-ray failure reason as names ("NONE", "TOLERANCE", ...)."""
        return [C.FAILURE_NAMES.get(int(f), str(int(f))) for f in self.failures]

    def __repr__(self):
        codes, counts = np.unique(self.status, return_counts=True)
        tally = ", ".join("%s: %d" % (C.RAY_STATUS_NAMES.get(int(c), c), n) for c, n in zip(codes, counts))
        return "AdvanceResult(%d rays {%s}, features=%s)" % (len(self), tally, " ".join(sorted(self.features)))
