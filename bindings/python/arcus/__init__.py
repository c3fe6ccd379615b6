"""arcus: light transport in non-linear media (curved rays) over OpenCL.

A thin ctypes layer over the C library libarcus with numpy in and out::

    import arcus
    from arcus.fields import Linear

    with arcus.Context() as ctx:
        result = ctx.advance(Linear(1.0, (0, 0.1, 0)), origins, directions, length=10.0)
        print(result.positions, result.status)
        scene = ctx.load_scene("scenes/mirage.json")   # read by the library
        print(scene.advance().status_names)

The shared library is looked up, in order, at the ARCUS_LIBRARY environment variable
(a path), in a build directory of the source tree this package lives in
(``build/`` first, then ``build*/``), then among installed libraries;
:data:`library_path` says which one was loaded.
"""

import ctypes as _ctypes

from . import daylight, fields, halo, image, mie, ocean, rainbow, sky, sweep, translucency
from ._constants import (
    DEVICE_DEFAULT,
    EARTH_RADIUS,
    FAILURE_INDEX_NOT_POSITIVE,
    FAILURE_NAMES,
    FAILURE_NONE,
    FAILURE_NOT_FINITE,
    FAILURE_TOLERANCE,
    FIELD_KINDS,
    METHODS,
    PRECISIONS,
    RAY_DONE,
    RAY_CANCELLED,
    RAY_FAILED,
    RAY_INVALID_INPUT,
    RAY_LEFT_BOX,
    RAY_STATUS_NAMES,
    RAY_STEP_LIMIT,
)
from ._errors import ArgumentError, Error, LibraryNotFoundError
from ._lib import ENGINES, FEATURES, feature_names
from ._lib import check as _check
from ._lib import lib as _libarcus
from ._lib import library_path  # the path (or soname) libarcus was loaded from
from .context import AdvanceResult, Context, DeviceInfo, RenderResult, Scene, SceneField, devices


def _version():
    major, minor, patch = _ctypes.c_int(), _ctypes.c_int(), _ctypes.c_int()
    _check(_libarcus.arcus_get_version(_ctypes.byref(major), _ctypes.byref(minor), _ctypes.byref(patch)))
    return "%d.%d.%d" % (major.value, minor.value, patch.value)


#: Version of the loaded libarcus ("major.minor.patch", from arcus_get_version).
__version__ = _version()

__all__ = [
    "AdvanceResult",
    "ArgumentError",
    "Context",
    "DEVICE_DEFAULT",
    "DeviceInfo",
    "EARTH_RADIUS",
    "Error",
    "FAILURE_INDEX_NOT_POSITIVE",
    "FAILURE_NAMES",
    "FAILURE_NONE",
    "FAILURE_NOT_FINITE",
    "FAILURE_TOLERANCE",
    "ENGINES",
    "FEATURES",
    "FIELD_KINDS",
    "LibraryNotFoundError",
    "METHODS",
    "PRECISIONS",
    "RAY_CANCELLED",
    "RAY_DONE",
    "RAY_FAILED",
    "RAY_INVALID_INPUT",
    "RAY_LEFT_BOX",
    "RAY_STATUS_NAMES",
    "RAY_STEP_LIMIT",
    "RenderResult",
    "Scene",
    "SceneField",
    "daylight",
    "devices",
    "feature_names",
    "fields",
    "library_path",
    "mie",
    "ocean",
    "rainbow",
    "render",
    "translucency",
]


def render(scene, techniques=None, frames=1, exr=None, png=None, device=DEVICE_DEFAULT, base_dir=".", meshes=None):
    """Renders a render scene (a file, or a dict built in Python) on a new context of
    ``device``, with any meshes from memory its objects name: see :meth:`Context.render`.
    Returns a :class:`RenderResult` (image as numpy, hits, figures)."""
    with Context(device) as ctx:
        return ctx.render(scene, techniques=techniques, frames=frames, exr=exr, png=png, base_dir=base_dir,
                          meshes=meshes)


def bundled_scene(name):
    """The path of a scene shipped with arcus, by name ("inferior_mirage",
    "rainbow/halo", "ocean/atlantic"), wherever arcus is installed; relative file names
    inside a scene resolve against its own folder, so it works from any directory."""
    from .cli.resources import scene  # not at the top: arcus.cli imports arcus, and `import arcus` needs no CLI
    return scene(name)


def __getattr__(name):
    # arcus.media, the 0.9 name of arcus.fields: imported (and warned of) only when used.
    if name == "media":
        import importlib
        return importlib.import_module(".media", __name__)
    raise AttributeError("module 'arcus' has no attribute %r" % (name,))
