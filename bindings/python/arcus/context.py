"""Devices, contexts and advancing rays."""

import numbers
import threading
import weakref
from ctypes import byref, c_int32, c_size_t, c_uint32, c_uint64, c_void_p
from dataclasses import dataclass

import numpy as np

from . import _constants as C
from . import _lib
from ._args import to_choice, to_float, to_int, to_points, to_vec3
from ._errors import DEVICE_NOT_FOUND, ArgumentError, Error, error_for
from ._lib import lib
from .media import Field

__all__ = ["DeviceInfo", "devices", "Context", "AdvanceResult"]


# ---- devices --------------------------------------------------------------------------


@dataclass(frozen=True)
class DeviceInfo:
    """An OpenCL device as arcus sees it (``arcus_device_info``).

    Attributes:
        index: position in arcus' enumeration over all platforms; pass it to Context.
        name, platform: device and platform names.
        version: the device's OpenCL version string.
        is_gpu: True for a GPU.
        fp64: True when the device supports double precision.
        compute_units: OpenCL compute units.
        global_memory: bytes.
        lanes: SIMD lanes per work-item arcus compiles for.
    """

    index: int
    name: str
    platform: str
    version: str
    is_gpu: bool
    fp64: bool
    compute_units: int
    global_memory: int
    lanes: int

    @classmethod
    def _from_struct(cls, info):
        return cls(
            index=int(info.index),
            name=_lib.decode(info.name),
            platform=_lib.decode(info.platform),
            version=_lib.decode(info.version),
            is_gpu=bool(info.is_gpu),
            fp64=bool(info.fp64),
            compute_units=int(info.compute_units),
            global_memory=int(info.global_memory),
            lanes=int(info.lanes),
        )


def devices():
    """Every OpenCL device arcus can use, as a list of :class:`DeviceInfo`."""
    count = c_uint32()
    _lib.check(lib.arcus_device_count(byref(count)))
    found = []
    for index in range(count.value):
        info = _lib.DeviceInfoStruct()
        _lib.check(lib.arcus_device_get_info(index, byref(info)))
        found.append(DeviceInfo._from_struct(info))
    return found


def _device_index(device):
    """The int32 device index for arcus_context_create from Context's ``device``."""
    if device is None:
        return C.DEVICE_DEFAULT
    if isinstance(device, DeviceInfo):
        return device.index
    if isinstance(device, str):
        # The same rule as the ARCUS_DEVICE environment variable: a case-insensitive
        # part of the device or the platform name; the first match wins.
        wanted = device.lower()
        available = devices()
        for info in available:
            if wanted in info.name.lower() or wanted in info.platform.lower():
                return info.index
        names = ", ".join("%d: %s (%s)" % (d.index, d.name, d.platform) for d in available) or "none"
        raise Error(DEVICE_NOT_FOUND, "no device name or platform contains %r; devices: %s" % (device, names))
    if isinstance(device, numbers.Integral) and not isinstance(device, bool):
        return to_int(device, "device", -(2**31), 2**31 - 1)
    raise ArgumentError("device must be None, an int index, a name (str) or a DeviceInfo, got %r" % (device,))


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
    "record_path": lambda v: int(bool(v)),
}


def _advance_params(options):
    """arcus_advance_params: the library's defaults, overridden by every option not None."""
    params = _lib.AdvanceParamsStruct()
    _lib.check(lib.arcus_advance_params_init(byref(params)))
    for name, value in options.items():
        if value is None:
            continue
        if name == "box":
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


# ---- results --------------------------------------------------------------------------


@dataclass(eq=False)  # element-wise array comparison has no single truth value
class AdvanceResult:
    """Every ray's result of :meth:`Context.advance` (N rays).

    Attributes:
        positions: (N, 3) end positions.
        directions: (N, 3) unit end directions.
        steps: (N,) uint64 accepted steps.
        status: (N,) int32 per-ray status (:data:`arcus.RAY_DONE`, ...).
        lengths: (N,) arc length travelled.
        features: names of the kernel features the job compiled with, e.g.
            ``{"DP45", "ANALYTIC_FIELD"}``; ``feature_bits`` is the raw bit mask.
        stats: timings and layout: build_seconds, kernel_seconds, total_seconds,
            cache_hit (bool), lanes, groups.
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

    def __repr__(self):
        codes, counts = np.unique(self.status, return_counts=True)
        tally = ", ".join("%s: %d" % (C.RAY_STATUS_NAMES.get(int(c), c), n) for c, n in zip(codes, counts))
        return "AdvanceResult(%d rays {%s}, features=%s)" % (len(self), tally, " ".join(sorted(self.features)))


# ---- context --------------------------------------------------------------------------


class _Handle:
    """Owns one reference to a library object and releases it exactly once.

    weakref.finalize rather than __del__: it also runs at interpreter exit while the
    library is still loaded, and never sees half-torn-down module globals.
    """

    __slots__ = ("value", "_finalizer", "__weakref__")

    def __init__(self, value, release):
        self.value = value
        self._finalizer = weakref.finalize(self, release, value)

    def release(self):
        self._finalizer()


class _ContextState:
    """What a Context owns, kept outside it so the finalizer does not keep it alive."""

    def __init__(self, handle):
        self.handle = handle
        # Realised fields: Field description -> _Handle.  Weak keys: once a description
        # is gone nobody can ask for it again, so its library object is released.
        self.fields = weakref.WeakKeyDictionary()
        self.callback = None  # the ctypes wrapper must outlive its registration
        self.lock = threading.Lock()

    def release(self):
        if self.callback is not None:
            lib.arcus_context_set_error_callback(self.handle, _lib.ERROR_CALLBACK(), None)
            self.callback = None
        for handle in list(self.fields.values()):
            handle.release()
        self.fields.clear()
        lib.arcus_context_release(self.handle)
        self.handle = None


class Context:
    """An arcus context on one OpenCL device; realises fields and advances rays.

    Args:
        device: None for the default device (the ARCUS_DEVICE environment variable if
            set, else the first GPU, else the first CPU); an int index from
            :func:`arcus.devices`; a :class:`DeviceInfo`; or a string matched
            case-insensitively against the device and platform names (first match).

    Use as a context manager or call :meth:`close`; otherwise the library objects are
    released when the Context is garbage collected.  Calls are thread safe (the library
    serialises them per context); use one context per thread for parallel work.
    """

    def __init__(self, device=None):
        index = _device_index(device)
        handle = c_void_p()
        # No context exists yet, so a failure's message is the per-thread one.
        _lib.check(lib.arcus_context_create(index, byref(handle)))
        self._state = _ContextState(handle)
        self._finalizer = weakref.finalize(self, self._state.release)
        self._device = None

    # -- lifetime --

    def close(self):
        """Releases the context and every field realised on it (idempotent)."""
        self._finalizer()

    @property
    def closed(self):
        """True after :meth:`close`."""
        return not self._finalizer.alive

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __repr__(self):
        if self.closed:
            return "<arcus.Context (closed)>"
        return "<arcus.Context on %d: %s>" % (self.device.index, self.device.name)

    @property
    def _handle(self):
        if self.closed:
            raise ArgumentError("this arcus.Context is closed")
        return self._state.handle

    def _check(self, code):
        _lib.check(code, self._handle)

    # -- queries --

    @property
    def device(self):
        """The :class:`DeviceInfo` of this context's device."""
        if self._device is None:
            info = _lib.DeviceInfoStruct()
            self._check(lib.arcus_context_get_device(self._handle, byref(info)))
            self._device = DeviceInfo._from_struct(info)
        return self._device

    @property
    def last_error(self):
        """The message of the last failed call on this context ("" if none)."""
        return _lib.last_error(self._handle)

    def set_error_callback(self, callback):
        """Calls ``callback(status_name, message)`` for every error on this context.

        It runs on the failing thread, inside the library call; exceptions it raises
        are printed and ignored (ctypes cannot propagate them through C).  None removes it.
        """
        if callback is None:
            wrapper = _lib.ERROR_CALLBACK()
        else:
            def wrapper_function(_user, code, message):
                callback(_lib.status_name(code), _lib.decode(message))

            wrapper = _lib.ERROR_CALLBACK(wrapper_function)
        self._check(lib.arcus_context_set_error_callback(self._handle, wrapper, None))
        self._state.callback = wrapper if callback is not None else None

    # -- fields --

    def _field(self, medium):
        """The library handle of ``medium`` on this context, created on first use."""
        if not isinstance(medium, Field):
            raise ArgumentError("field must be an arcus.media field (Constant, Linear, ...), got %r" % (medium,))
        ctx = self._handle
        with self._state.lock:
            handle = self._state.fields.get(medium)
            if handle is None:
                out = c_void_p()
                self._check(medium._create(ctx, byref(out)))
                handle = _Handle(out, lib.arcus_field_release)
                self._state.fields[medium] = handle
            return handle.value

    def field_kind(self, medium):
        """The library's kind name of ``medium`` ("LINEAR", "GRID", ...), realising it."""
        kind = c_int32()
        self._check(lib.arcus_field_get_kind(self._field(medium), byref(kind)))
        return C.FIELD_KINDS.get(kind.value, str(kind.value))

    def evaluate(self, medium, positions):
        """n and its gradient of ``medium`` at ``positions`` ((N, 3) or (3,)).

        Host-side, double precision, the kernels' formulas (``arcus_field_evaluate``).
        Returns ``(n, gradient)`` with shapes (N,) and (N, 3).
        """
        points = to_points(positions, "positions")
        handle = self._field(medium)
        n = np.empty(len(points))
        gradient = np.empty((len(points), 3))
        self._check(lib.arcus_field_evaluate(handle, len(points), _lib.ptr(points), _lib.ptr(n), _lib.ptr(gradient)))
        return n, gradient

    # -- advancing rays --

    def advance(self, field, origins, directions, *, method=None, step=None, rtol=None, atol=None, length=None,
                record_path=None, precision=None, box=None, max_steps=None, min_step=None, max_step=None,
                max_rejections=None, path_capacity=None):
        """Advances rays through ``field`` along the ray equation d/ds(n dr/ds) = ∇n.

        Args:
            field: an :mod:`arcus.media` field.
            origins, directions: (N, 3) arrays (or one (3,) ray); directions need not be
                unit length.
            method: "dp45" (adaptive Dormand-Prince 5(4)), "rk4", "rk2" or "euler".
            step: the fixed step; for dp45 the initial step (0: automatic).
            rtol, atol: dp45 tolerances per step (> 0).
            length: arc length to advance, metres (> 0).
            record_path: keep every point of every path.
            precision: "double" or "float".
            box: ``(min, max)`` corners; a ray stops where it leaves the box.
            max_steps: accepted steps before a ray stops (status RAY_STEP_LIMIT).
            min_step, max_step, max_rejections: dp45 step control.
            path_capacity: points kept per ray (0: automatic).

        Every argument left as None keeps the library's default
        (``arcus_advance_params_init``: dp45, double, length 1, rtol 1e-9, atol 1e-12).

        Returns an :class:`AdvanceResult`.  Raises :class:`arcus.Error`; for
        ARCUS_ERROR_INVALID_RAYS (some rays had NaN/Inf/zero input) and
        ARCUS_ERROR_PATH_OVERFLOW the error's ``result`` holds every ray's result.
        """
        points = to_points(origins, "origins")
        heading = to_points(directions, "directions")
        if len(points) != len(heading):
            raise ArgumentError(
                "origins and directions must hold the same number of rays, got %d and %d" % (len(points), len(heading))
            )
        params = _advance_params(dict(
            method=method, precision=precision, length=length, step=step, rtol=rtol, atol=atol, min_step=min_step,
            max_step=max_step, max_rejections=max_rejections, max_steps=max_steps, box=box, record_path=record_path,
            path_capacity=path_capacity))
        ctx = self._handle
        field_handle = self._field(field)
        job = c_void_p()
        code = lib.arcus_advance(ctx, field_handle, byref(params), len(points), _lib.ptr(points), _lib.ptr(heading),
                                 None, byref(job))
        if code not in (C.SUCCESS, C.ERROR_INVALID_RAYS, C.ERROR_PATH_OVERFLOW):
            self._check(code)
        # The message lives only until the next call on the context: read it first.
        message = self.last_error if code != C.SUCCESS else ""
        if not job.value:  # arcus.h promises a job with these three statuses
            raise Error(code, "arcus_advance returned %s but no job (a library bug); message: %r"
                        % (_lib.status_name(code), message), _lib.status_name(code))
        try:
            result = self._read_job(job, bool(params.record_path))
        finally:
            lib.arcus_job_release(job)
        if code != C.SUCCESS:
            raise error_for(code, message, _lib.status_name(code), result=result)
        return result

    def _read_job(self, job, record_path):
        count = c_size_t()
        self._check(lib.arcus_job_get_count(job, byref(count)))
        n = count.value
        positions = np.empty((n, 3))
        directions = np.empty((n, 3))
        steps = np.empty(n, dtype=np.uint64)
        status = np.empty(n, dtype=np.int32)
        lengths = np.empty(n)
        self._check(lib.arcus_job_get_end_states(
            job, _lib.ptr(positions), _lib.ptr(directions), _lib.ptr(steps, c_uint64), _lib.ptr(status, c_int32),
            _lib.ptr(lengths)))
        bits = c_uint64()
        self._check(lib.arcus_job_get_features(job, byref(bits)))
        stats = _lib.JobStatsStruct()
        self._check(lib.arcus_job_get_stats(job, byref(stats)))
        result = AdvanceResult(
            positions=positions,
            directions=directions,
            steps=steps,
            status=status,
            lengths=lengths,
            features=_lib.feature_names(bits.value),
            feature_bits=bits.value,
            stats={
                "build_seconds": stats.build_seconds,
                "kernel_seconds": stats.kernel_seconds,
                "total_seconds": stats.total_seconds,
                "program_origin": ("built", "memory cache", "disk cache")[stats.program_origin],
                "launches": stats.launches,
                "lanes": stats.lanes,
                "groups": stats.groups,
            },
        )
        if record_path:
            total = c_size_t()
            self._check(lib.arcus_job_get_path_size(job, byref(total)))
            offsets = np.empty(n + 1, dtype=np.uint64)
            points = np.empty((total.value, 3))
            needed = np.empty(n, dtype=np.uint64)
            self._check(lib.arcus_job_get_paths(job, _lib.ptr(offsets, c_uint64), _lib.ptr(points),
                                                _lib.ptr(needed, c_uint64)))
            result.path_offsets = offsets
            result.path_points = points
            result.path_needed = needed
            result.paths = [points[int(offsets[i]):int(offsets[i + 1])] for i in range(n)]
        return result
