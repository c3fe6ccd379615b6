"""Images read and written by the library (OpenImageIO) as every engine reads and writes them."""

from ctypes import byref, c_float, c_uint32

import numpy as np

from . import _lib
from ._args import to_path
from ._errors import ArgumentError
from ._lib import lib


def read(path):
    """The first image of ``path`` (EXR, HDR, PNG, JPEG, TIFF, PFM, ...) as linear RGB, an
    (height, width, 3) float32 array, top row first: integer files are decoded from sRGB
    unless they say they are linear, float files are taken as they are.  A missing or
    unreadable file raises :class:`arcus.Error` (status ``ARCUS_ERROR_IO``); so do a file
    that is not a regular file and one of more than ``ARCUS_MAX_IMAGE_PIXELS`` pixels
    (2^28 unless set).  A NaN or infinite value raises :class:`arcus.ArgumentError`."""
    encoded = to_path(path, "path")
    width, height = c_uint32(), c_uint32()
    _lib.check(lib.arcus_image_read(encoded, byref(width), byref(height), None, 0))
    rgb = np.empty(height.value * width.value * 3, np.float32)
    # The file may change between the calls: the library writes only what fits, and says
    # what size it read.
    _lib.check(lib.arcus_image_read(encoded, byref(width), byref(height), _lib.ptr(rgb, c_float), rgb.size))
    return rgb[: height.value * width.value * 3].reshape(height.value, width.value, 3)


def write(path, rgb):
    """Writes ``rgb``, an (height, width, 3) array of linear RGB, top row first, to
    ``path`` in the format its extension names: ``.exr`` and ``.hdr`` keep the values
    (linear float), ``.png`` and ``.jpg`` are 8-bit sRGB clamped to [0, 1].  Another
    extension raises :class:`arcus.ArgumentError`; a NaN or infinite value
    :class:`arcus.Error` (``ARCUS_ERROR_NOT_FINITE``)."""
    encoded = to_path(path, "path")
    pixels = np.ascontiguousarray(rgb, dtype=np.float32)
    if pixels.ndim != 3 or pixels.shape[2] != 3 or pixels.shape[0] < 1 or pixels.shape[1] < 1:
        raise ArgumentError("rgb: expected an (height, width, 3) array, got shape %r" % (pixels.shape,))
    _lib.check(lib.arcus_image_write(encoded, pixels.shape[1], pixels.shape[0], _lib.ptr(pixels, c_float)))
