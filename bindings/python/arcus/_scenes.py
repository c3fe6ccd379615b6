"""What a scene file gives: a curved scene's rays, field and settings
(:class:`Scene`, :class:`SceneField`) and a rendered frame (:class:`RenderResult`)."""

import ctypes
from ctypes import byref, c_char_p, c_int32, c_size_t, c_uint32, c_void_p
from dataclasses import dataclass

import numpy as np

from . import _constants as C
from . import _lib
from ._args import to_path
from ._errors import ArgumentError, Error
from ._lib import lib
from .fields import Field

from ._advance import _advance_options, _check_progress
from ._lifetime import _Handle


# ---- scenes -----------------------------------------------------------------------------


@dataclass(frozen=True)
class RenderResult:
    """A rendered frame: ``image`` (H, W, 3) linear RGB float32; per pixel ``objects``
    (index in the scene's "objects", -1 none), ``primitives``, ``points`` (H, W, 3; NaN
    for none), ``distances`` (arc length), ``steps`` and ``tests``; ``stats`` a dict of
    the frame's figures (seconds per stage, rays, steps, tests, ...)."""

    image: np.ndarray
    objects: np.ndarray
    primitives: np.ndarray
    points: np.ndarray
    distances: np.ndarray
    steps: np.ndarray
    tests: np.ndarray
    stats: dict


def _render_result(context, job, exr, png):
    w, h = c_uint32(), c_uint32()
    context._check(lib.arcus_job_get_render_image_size(job, byref(w), byref(h)))
    shape = (h.value, w.value)
    image = np.empty(shape + (3,), dtype=np.float32)
    context._check(lib.arcus_job_get_render_image(job, _lib.ptr(image, ctypes.c_float)))
    points = np.empty(shape + (3,))
    objects = np.empty(shape, dtype=np.int32)
    primitives = np.empty(shape, dtype=np.int32)
    distances = np.empty(shape)
    steps = np.empty(shape, dtype=np.uint32)
    tests = np.empty(shape, dtype=np.uint32)
    context._check(lib.arcus_job_get_render_hits(job, _lib.ptr(points), _lib.ptr(objects, c_int32),
                                          _lib.ptr(primitives, c_int32), _lib.ptr(distances),
                                          _lib.ptr(steps, c_uint32), _lib.ptr(tests, c_uint32)))
    st = _lib.RenderStatsStruct()
    context._check(lib.arcus_job_get_render_stats(job, byref(st)))
    stats = {name: getattr(st, name) for name, _ in st._fields_}
    if exr is not None or png is not None:
        context._check(lib.arcus_job_write_render_image(job, None if exr is None else to_path(exr, "exr"),
                                                 None if png is None else to_path(png, "png")))
    return RenderResult(image, objects, primitives, points, distances, steps, tests, stats)


class SceneField(Field):
    """The field of a :class:`Scene`: the library object the scene created.

    Use it as the ``field`` of :meth:`Context.advance`, ``evaluate`` or ``field_kind``
    with the Context that loaded the scene; another context refuses it (ArgumentError).
    """

    def __init__(self, context, handle, scene_name):
        self._context = context
        self._ref = context._own(handle)
        self.scene_name = scene_name

    def _handle_on(self, context):
        if context is not self._context:
            raise ArgumentError("field: the field of scene %r belongs to the arcus.Context that loaded the scene; "
                                "load the scene on this context to use its field here" % (self.scene_name,))
        return self._ref.value

    def _create(self, ctx_handle, out):
        raise ArgumentError("a scene's field is made by the scene")  # never reached: _handle_on answers

    def __repr__(self):
        return "<arcus.SceneField of scene %r>" % (self.scene_name,)


def _read_only(array):
    array.flags.writeable = False
    return array


class Scene:
    """A scene file read by the library (``arcus_scene_load``): made by :meth:`Context.load_scene`.

    Attributes:
        name, description, engine: strings from the file ("curved" is the engine).
        document: the scene as the library read it (JSON text).
        origins, directions: (N, 3) the scene's rays (read-only arrays).
        wavelengths: (N,) per-ray wavelengths in nm, or None if the scene gives none.
        params: the scene's integrator settings as :meth:`Context.advance` keywords
            (method, length, rtol, ..., box (None or (min, max)), record_path, ...).
        field: a :class:`SceneField`, the scene's medium, for this scene's Context.

    ``ctx.advance(scene.field, scene.origins, scene.directions,
    wavelengths=scene.wavelengths, **scene.params)`` runs the job :meth:`advance` runs.
    The library objects are released when the Scene is garbage collected, or with
    its Context.
    """

    def __init__(self, context, handle):
        self._context = context
        self._ref = context._own(handle)
        scene = handle.value
        self.engine = self._string(lib.arcus_scene_get_engine)
        self.name = self._string(lib.arcus_scene_get_name)
        self.description = self._string(lib.arcus_scene_get_description)
        self.document = self._string(lib.arcus_scene_get_document)
        if self.engine != "curved":
            raise Error(C.ERROR_UNSUPPORTED, "scene %r is for the %r engine; this package handles curved scenes"
                        % (self.name, self.engine), _lib.status_name(C.ERROR_UNSUPPORTED))
        count = c_size_t()
        context._check(lib.arcus_scene_get_ray_count(scene, byref(count)))
        origins = np.empty((count.value, 3))
        directions = np.empty((count.value, 3))
        wavelengths = np.empty(count.value)
        given = c_int32()
        context._check(lib.arcus_scene_get_rays(scene, _lib.ptr(origins), _lib.ptr(directions),
                                                _lib.ptr(wavelengths), byref(given)))
        self.origins = _read_only(origins)
        self.directions = _read_only(directions)
        self.wavelengths = _read_only(wavelengths) if given.value else None
        params = _lib.AdvanceParamsStruct()
        context._check(lib.arcus_scene_get_advance_params(scene, byref(params)))
        self._params = _advance_options(params)
        field = c_void_p()
        context._check(lib.arcus_scene_get_field(scene, byref(field)))
        self.field = SceneField(context, _Handle(field, lib.arcus_field_release), self.name)

    @property
    def params(self):
        """The scene's integrator settings as :meth:`Context.advance` keywords (a new dict)."""
        return dict(self._params)

    def _string(self, getter):
        text = c_char_p()
        self._context._check(getter(self._ref.value, byref(text)))
        return _lib.decode(text.value)

    def __len__(self):
        return len(self.origins)

    def __repr__(self):
        return "<arcus.Scene %r (%s, %d rays)>" % (self.name, self.engine, len(self))

    def advance(self, progress=None):
        """Advances the scene's rays through its field with its settings (``arcus_curved_advance_scene``).

        ``progress`` is that of :meth:`Context.advance` (must not call this scene's
        context).  Returns an :class:`AdvanceResult`; raises :class:`arcus.Error` as
        :meth:`Context.advance` does, partial results attached.
        """
        _check_progress(progress)
        self._context._handle  # closed or called from a progress callback: raises
        scene = self._ref.value

        def start(callback, job):
            return lib.arcus_curved_advance_scene(scene, callback, None, job)

        return self._context._run_job(start, progress, self._params["record_path"], "arcus_curved_advance_scene")
