"""Scene files as Python reads them: through the library's strict reader, never open().

Every scene file (render, ocean and rainbow scenes, sweep specs) is read and checked by
``arcus_scene_load``: only a regular file (a FIFO or /dev/zero is refused, not read
for ever), at most ARCUS_MAX_SCENE_BYTES, valid JSON with no key given twice, and the
scene's schema: an unknown key, ``true`` where a number belongs or 1.5 where an integer
does is an error naming the file and the key path ("$.sun.samples").
"""

import json
from ctypes import byref, c_char_p, c_void_p

from . import _lib
from ._args import to_path
from ._errors import ArgumentError
from ._lib import lib
from .context import Context


def read(path, engines, name="scene"):
    """The scene file at ``path`` as the library read it: (engine, document dict).

    ``engines`` lists the engines whose scenes are wanted ("rainbow", "sweep", "ocean",
    "render", "curved"); a scene of another engine raises :class:`arcus.ArgumentError`
    naming both.  A file that cannot be read raises :class:`arcus.Error`
    (ARCUS_ERROR_IO); an invalid one :class:`arcus.ArgumentError` with the library's
    message.
    """
    encoded = to_path(path, name)
    # A context of its own: scene objects belong to one, and this one lives only for
    # the read (so a forked worker never inherits it).
    with Context() as ctx:
        handle = c_void_p()
        ctx._check(lib.arcus_scene_load(ctx._handle, encoded, byref(handle)))
        try:
            engine, document = c_char_p(), c_char_p()
            ctx._check(lib.arcus_scene_get_engine(handle, byref(engine)))
            ctx._check(lib.arcus_scene_get_document(handle, byref(document)))
            engine, text = _lib.decode(engine.value), _lib.decode(document.value)
        finally:
            lib.arcus_scene_release(handle)
    if engine not in engines:
        raise ArgumentError("%s: %s is a %s scene, not a %s one (scenes/README.md)"
                            % (name, _lib.decode(encoded), engine, " or ".join(engines)))
    return engine, json.loads(text)
