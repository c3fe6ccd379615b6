"""Devices, contexts, advancing rays and loading scenes."""

import contextlib
import json
import numbers
import os
import tempfile
import threading
import weakref
from ctypes import byref, c_int32, c_size_t, c_uint32, c_uint64, c_void_p
from dataclasses import dataclass

import numpy as np

from . import _constants as C
from . import _lib, _meshes
from ._args import to_int, to_path, to_per_ray, to_points
from ._errors import DEVICE_NOT_FOUND, ArgumentError, Error, error_for
from ._advance import AdvanceResult, _advance_params, _check_progress  # noqa: F401  (re-exported)
from ._lib import lib
from ._lifetime import _active, _ContextState, _deferred, _flush_deferred, _Handle, _release  # noqa: F401
from .fields import Field

# Defined beside the scenes they come from; Context.load_scene and render make them.
from ._scenes import RenderResult, Scene, SceneField, _render_result  # noqa: F401

__all__ = ["DeviceInfo", "devices", "Context", "AdvanceResult", "Scene", "SceneField"]


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


# ---- context --------------------------------------------------------------------------


class Context:
    """An arcus context on one OpenCL device; realises fields, advances rays, loads scenes.

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
        self._finalizer = weakref.finalize(self, _release, self._state.release)
        self._device = None

    # -- lifetime --

    def close(self):
        """Releases the context, every field realised on it and its scenes (idempotent).

        Safe from any thread: jobs running on the context in other threads are cancelled
        at their next slice (slices last about a quarter second; a kernel build or a
        photon map under way is finished first) and raise :class:`arcus.Error`
        ``ARCUS_ERROR_CANCELLED`` with what they had computed attached (``.result``);
        close() returns once they have, and later calls raise "closed"."""
        self._not_in_progress_callback()
        state = self._state
        me = threading.get_ident()
        try:
            with state.jobs:
                state.closing = True
                state.jobs.wait_for(lambda: sum(state.job_threads.values()) == state.job_threads[me])
        finally:
            # Interrupted while waiting, the context is released all the same: the
            # library's jobs hold references of their own until they return.
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
        if self._device is None and self._state in _active():
            return "<arcus.Context (running a job)>"
        return "<arcus.Context on %d: %s>" % (self.device.index, self.device.name)

    def _not_in_progress_callback(self):
        if self._state in _active():
            raise ArgumentError("a progress callback must not call the arcus.Context running its job "
                                "(the library holds the context's lock until the job returns)")

    @property
    def _handle(self):
        state = self._state
        # A job's own thread may go on reading its results while close() waits for it.
        if self.closed or (state.closing and not state.job_threads[threading.get_ident()]):
            raise ArgumentError("this arcus.Context is closed")
        self._not_in_progress_callback()
        return state.handle

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
        if callback is not None and not callable(callback):
            raise ArgumentError("callback must be a callable (status, message) or None, got %r" % (callback,))
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
            raise ArgumentError("field must be an arcus.fields field (Constant, Linear, ...) or a Scene's field, "
                                "got %r" % (medium,))
        ctx = self._handle
        bound = medium._handle_on(self)  # a scene's field has its one handle
        if bound is not None:
            return bound
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

        Host-side, double precision, the kernels' formulas (``arcus_field_evaluate``), at
        the field's own wavelength.  Returns ``(n, gradient)`` with shapes (N,) and (N, 3).
        """
        points = to_points(positions, "positions")
        handle = self._field(medium)
        n = np.empty(len(points))
        gradient = np.empty((len(points), 3))
        self._check(lib.arcus_field_evaluate(handle, len(points), _lib.ptr(points), _lib.ptr(n), _lib.ptr(gradient)))
        return n, gradient

    # -- advancing rays --

    def advance(self, field, origins, directions, *, wavelengths=None, progress=None, method=None, step=None,
                rtol=None, atol=None, length=None, record_path=None, precision=None, box=None, max_steps=None,
                min_step=None, max_step=None, max_rejections=None, path_capacity=None):
        """Advances rays through ``field`` along the ray equation d/ds(n dr/ds) = ∇n.

        Args:
            field: an :mod:`arcus.fields` field, or the ``field`` of a :class:`Scene`
                loaded on this context.
            origins, directions: (N, 3) arrays (or one (3,) ray); directions need not be
                unit length.
            wavelengths: per-ray vacuum wavelengths in nm, an (N,) array or one number
                for all.  A dispersive field (the atmosphere) evaluates n at each ray's
                wavelength (300..1690 nm; a ray outside is RAY_INVALID_INPUT); other
                fields ignore them.  None: the field's own wavelength.
            progress: ``progress(fraction)``, called after each slice of a long job with
                the fraction done (0..1); a true return value cancels the job.  It runs
                while the library holds this context's lock: it must not call this
                context (that raises ArgumentError).  An exception it raises cancels the
                job and is re-raised here.
            method: "dp45" (adaptive Dormand-Prince 5(4)), "rk4", "rk2" or "euler".
            step: the fixed step; for dp45 the initial step (0: automatic).
            rtol, atol: dp45 tolerances per step (> 0).
            length: arc length to advance, metres (> 0).
            record_path: True to keep every point of every path (a bool).
            precision: "double" or "float".
            box: ``(min, max)`` corners; a ray stops where it leaves the box.
            max_steps: accepted steps before a ray stops (status RAY_STEP_LIMIT).
            min_step, max_step, max_rejections: dp45 step control.
            path_capacity: points kept per ray (0: automatic).

        Every argument left as None keeps the library's default
        (``arcus_advance_params_init``: dp45, double, length 1, rtol 1e-9, atol 1e-12).

        Returns an :class:`AdvanceResult`.  Raises :class:`arcus.Error`; for
        ARCUS_ERROR_INVALID_RAYS (some rays had bad input), ARCUS_ERROR_PATH_OVERFLOW and
        ARCUS_ERROR_CANCELLED (``progress`` asked so) the error's ``result`` holds every
        ray's result.
        """
        points = to_points(origins, "origins")
        heading = to_points(directions, "directions")
        if len(points) != len(heading):
            raise ArgumentError(
                "origins and directions must hold the same number of rays, got %d and %d" % (len(points), len(heading))
            )
        per_ray = None if wavelengths is None else to_per_ray(wavelengths, "wavelengths", len(points))
        _check_progress(progress)
        params = _advance_params(dict(
            method=method, precision=precision, length=length, step=step, rtol=rtol, atol=atol, min_step=min_step,
            max_step=max_step, max_rejections=max_rejections, max_steps=max_steps, box=box, record_path=record_path,
            path_capacity=path_capacity))
        ctx = self._handle
        field_handle = self._field(field)

        def start(callback, job):
            params.progress = callback
            return lib.arcus_curved_advance(ctx, field_handle, byref(params), len(points), _lib.ptr(points),
                                     _lib.ptr(heading), _lib.ptr(per_ray), job)

        return self._run_job(start, progress, bool(params.record_path), "arcus_curved_advance")

    def _run_job(self, start, progress, record_path, what, reader=None):
        """Runs ``start(callback, job_out)`` (a library call making a job) and reads its job
        (``reader(job)``; default: an advance job's rays).

        ``progress`` (checked already) is wrapped for the library: its return value
        cancels, and an exception it raises (ctypes would print and drop it) cancels the
        job and is raised here once the library has returned.
        """
        ctx = self._handle
        with self._running_job():
            return self._run_registered_job(ctx, start, progress, record_path, what, reader)

    @contextlib.contextmanager
    def _running_job(self):
        """This thread runs a job on the context for the block: close() from another
        thread cancels it (through its progress callback) and waits for the block to end."""
        state = self._state
        me = threading.get_ident()
        with state.jobs:
            if state.closing:
                raise ArgumentError("this arcus.Context is closed")
            state.job_threads[me] += 1
        try:
            yield
        finally:
            with state.jobs:
                state.job_threads[me] -= 1
                state.jobs.notify_all()

    def _run_registered_job(self, ctx, start, progress, record_path, what, reader):
        raised = []
        closed_meanwhile = []
        state = self._state

        # Always a callback: close() from another thread cancels the job through it.
        def on_progress(_user, fraction):
            if state.closing:
                closed_meanwhile.append(True)
                return 1
            if progress is None:
                return 0
            active = _active()
            active.append(state)
            try:
                return 1 if progress(fraction) else 0
            except BaseException as exc:  # KeyboardInterrupt too: it cancels the job
                raised.append(exc)
                return 1
            finally:
                active.pop()

        callback = _lib.PROGRESS_CALLBACK(on_progress)
        job = c_void_p()
        try:
            code = start(callback, byref(job))
        finally:
            _flush_deferred()
        # The message lives only until the next call on the context: read it first.
        message = _lib.last_error(ctx) if code != C.SUCCESS else ""
        if closed_meanwhile:
            message += " (arcus.Context.close() was called from another thread)"
        try:
            if raised:
                raise raised[0]
            if code != C.SUCCESS and code not in C.PARTIAL_RESULTS:
                raise error_for(code, message, _lib.status_name(code))
            if not job.value:  # arcus.h promises a job with these statuses
                raise Error(code, "%s returned %s but no job (a library bug); message: %r"
                            % (what, _lib.status_name(code), message), _lib.status_name(code))
            result = reader(job) if reader else self._read_job(job, record_path)
        finally:
            if job.value:
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
        failures = np.empty(n, dtype=np.int32)
        self._check(lib.arcus_job_get_curved_end_states(
            job, _lib.ptr(positions), _lib.ptr(directions), _lib.ptr(steps, c_uint64), _lib.ptr(status, c_int32),
            _lib.ptr(lengths)))
        self._check(lib.arcus_job_get_curved_failures(job, _lib.ptr(failures, c_int32)))
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
            failures=failures,
            features=_lib.feature_names(bits.value),
            feature_bits=bits.value,
            stats={
                "build_seconds": stats.build_seconds,
                "kernel_seconds": stats.kernel_seconds,
                "total_seconds": stats.total_seconds,
                "program_origin": C.PROGRAM_ORIGINS.get(stats.program_origin, str(stats.program_origin)),
                "launches": stats.launches,
                "lanes": stats.lanes,
                "groups": stats.groups,
            },
        )
        if record_path:
            total = c_size_t()
            self._check(lib.arcus_job_get_curved_path_size(job, byref(total)))
            offsets = np.empty(n + 1, dtype=np.uint64)
            points = np.empty((total.value, 3))
            needed = np.empty(n, dtype=np.uint64)
            self._check(lib.arcus_job_get_curved_paths(job, _lib.ptr(offsets, c_uint64), _lib.ptr(points),
                                                _lib.ptr(needed, c_uint64)))
            result.path_offsets = offsets
            result.path_points = points
            result.path_needed = needed
            result.paths = [points[int(offsets[i]):int(offsets[i + 1])] for i in range(n)]
        return result

    # -- scenes --

    def load_scene(self, path):
        """Loads a scene file (JSON, scenes/README.md) on this context: a :class:`Scene`.

        The library reads and checks the file (``arcus_scene_load``); ``path`` is a str
        or os.PathLike.  Raises arcus.Error: ARCUS_ERROR_IO if the file cannot be read,
        ArgumentError for invalid JSON or an invalid scene (the message names the file
        and the key, e.g. ``$.medium.radius``).
        """
        encoded = to_path(path, "path")
        ctx = self._handle
        out = c_void_p()
        self._check(lib.arcus_scene_load(ctx, encoded, byref(out)))
        return Scene(self, _Handle(out, lib.arcus_scene_release))

    def render(self, path, techniques=None, frames=1, exr=None, png=None, base_dir=".", width=None, height=None,
               progress=None, meshes=None):
        """Renders a render scene: ``path`` names a scene file with a "camera", or is a
        dict of the same schema built in Python (its relative file names are read
        against ``base_dir``, the current directory by default).

        ``techniques``: None (the scene's own), or names among "smart_step", "symmetry",
        "undersample", "path_cache"; ``frames``: frames rendered with the camera at rest
        (the result is the last one's).  ``exr``/``png``: optional files to write.
        ``width``/``height`` override the camera's image size (the field of view stays);
        ``progress(fraction)`` sees each frame's progress.  ``meshes``: geometry from
        memory for the scene's objects to name, ``{name: (vertices, triangles)}`` ((N, 3)
        reals and (M, 3) vertex indices, e.g. ``(mesh.vertices, mesh.faces)``): an
        object ``{"type": "mesh", "mesh": name}`` takes it instead of a "file"
        (``arcus_scene_load_with_meshes``); a name the scene uses that is not given, or a
        given mesh it does not use, raises ArgumentError.  Returns a :class:`RenderResult`.  Raises arcus.Error with the library's message
        (a scene error names the file and the key).
        """
        frames = to_int(frames, "frames", 1, 100000)
        if isinstance(path, dict):
            # The library reads scene files: a dict goes through one, beside the files
            # it names, and is removed afterwards.
            with tempfile.NamedTemporaryFile("w", suffix=".json", dir=base_dir, delete=False) as f:
                json.dump(path, f)
            try:
                return self.render(f.name, techniques, frames, exr, png, width=width, height=height,
                                   progress=progress, meshes=meshes)
            finally:
                os.unlink(f.name)
        encoded = to_path(path, "path")
        bits = None
        if techniques is not None:
            names = dict(smart_step=1, symmetry=2, undersample=4, path_cache=8)
            if isinstance(techniques, str):
                techniques = [techniques]
            bits = 0
            for t in techniques:
                if t not in names:
                    raise ArgumentError("techniques: unknown technique %r (expected one of %s)"
                                        % (t, ", ".join(sorted(names))))
                bits |= names[t]
        size = (None if width is None else to_int(width, "width", 1, 1 << 16),
                None if height is None else to_int(height, "height", 1, 1 << 16))
        _check_progress(progress)
        given = _meshes.named(meshes)
        with self._running_job():
            return self._render_file(encoded, bits, frames, exr, png, size, progress, given)

    def _render_file(self, encoded, bits, frames, exr, png, size, progress, given):
        state = self._state

        # close() from another thread cancels the frame (a frame has no partial result).
        def on_progress(_user, fraction):
            if progress is not None:
                progress(fraction)
            return 1 if state.closing else 0
        cancel_on_close = _lib.PROGRESS_CALLBACK(on_progress)
        scene = c_void_p()
        _meshes.load_scene(self, encoded, given, byref(scene))
        scene_ref = _Handle(scene, lib.arcus_scene_release)
        renderer = c_void_p()
        try:
            self._check(lib.arcus_renderer_create(scene, byref(renderer)))
            renderer_ref = _Handle(renderer, lib.arcus_renderer_release)
            if bits is not None:
                self._check(lib.arcus_renderer_set_techniques(renderer, bits))
            if size != (None, None):
                camera = _lib.CameraStruct()
                self._check(lib.arcus_renderer_get_camera(renderer, byref(camera)))
                camera.width = size[0] or camera.width
                camera.height = size[1] or camera.height
                self._check(lib.arcus_renderer_set_camera(renderer, byref(camera)))
            job = None
            for _ in range(frames):
                out = c_void_p()
                code = lib.arcus_render_frame(renderer, cancel_on_close, None, byref(out))
                if code != C.SUCCESS and state.closing:
                    raise error_for(code, _lib.last_error(self._handle) + " (arcus.Context.close() was called "
                                    "from another thread)", _lib.status_name(code))
                self._check(code)
                if job is not None:
                    lib.arcus_job_release(job)
                job = out
            try:
                return _render_result(self, job, exr, png)
            finally:
                lib.arcus_job_release(job)
        finally:
            if renderer:
                renderer_ref.release()
            scene_ref.release()

    def _own(self, handle):
        """Releases ``handle`` (a _Handle) with this context at the latest."""
        self._state.objects.add(handle)
        return handle


@contextlib.contextmanager
def _owned_context(context=None):
    """``with _owned_context(context) as ctx``: the caller's :class:`Context`, left open,
    or (``context`` None) a new one on the default device, closed on leaving.  The one
    helper behind every engine's ``context=None`` argument."""
    if context is None:
        with Context() as ctx:
            yield ctx
        return
    if not isinstance(context, Context):
        raise ArgumentError("context must be an arcus.Context or None, got %r" % (context,))
    yield context
