"""Input images, read by the library (OpenImageIO) as every engine reads them."""

from ctypes import byref, c_float, c_uint32

import numpy as np

from . import _lib
from ._args import to_path
from ._lib import lib


def read(path):
    """The first image of ``path`` (EXR, HDR, PNG, JPEG, TIFF, PFM, ...) as linear RGB, an
    (height, width, 3) float32 array, top row first: integer files are decoded from sRGB
    unless they say they are linear, float files are taken as they are.  A missing or
    unreadable file raises :class:`arcus.Error` (status ``ARCUS_ERROR_IO``)."""
    encoded = to_path(path, "path")
    width, height = c_uint32(), c_uint32()
    _lib.check(lib.arcus_image_read(encoded, byref(width), byref(height), None))
    rgb = np.empty((height.value, width.value, 3), np.float32)
    _lib.check(lib.arcus_image_read(encoded, None, None, _lib.ptr(rgb, c_float)))
    return rgb
