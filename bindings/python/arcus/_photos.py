"""Photographs handed to the estimates: HDR files or arrays of linear radiance, 8-bit
images refused or read with a warning, mattes checked against them."""

import os
import warnings

import numpy as np

from . import image
from ._errors import ArgumentError


_EIGHT_BIT = (".png", ".jpg", ".jpeg", ".bmp", ".gif")


def read_photo(photo, eight_bit="refuse"):
    """The photo as an (h, w, 3) float32 array: an array, or an HDR file (EXR, HDR, PFM).
    8-bit images (a file of an 8-bit format, a uint8 array) hold display codes, not
    radiance: ``eight_bit="refuse"`` raises, ``"warn"`` warns and reads them as codes
    over 255."""
    what = None
    if isinstance(photo, (str, os.PathLike)):
        path = os.fspath(photo)
        if path.lower().endswith(_EIGHT_BIT):
            what = path
        else:
            photo = image.read(path)
    elif isinstance(photo, np.ndarray) and photo.dtype == np.uint8:
        what = "the uint8 array"
    if what is not None:
        message = ("photo: %s is an 8-bit image, whose values are display codes, not radiance: give an HDR "
                   "photograph (.exr, .hdr)" % what)
        if eight_bit == "refuse":
            raise ArgumentError(message)
        warnings.warn(message + "; read as codes over 255, the estimate is only as good as they are linear",
                      stacklevel=3)
        photo = image.read(photo) if isinstance(photo, (str, os.PathLike)) else np.asarray(photo) / 255.0
    array = np.ascontiguousarray(photo, dtype=np.float32)
    if array.ndim != 3 or array.shape[2] != 3:
        raise ArgumentError("photo must be an (height, width, 3) array or an HDR file, got shape %s" % (array.shape,))
    return array


def read_matte(matte, height, width):
    """The matte as an (h, w) uint8 array of 0 and 1, or None."""
    if matte is None:
        return None
    array = np.ascontiguousarray(np.asarray(matte) != 0, dtype=np.uint8)
    if array.shape != (height, width):
        raise ArgumentError("matte must have the photo's shape %s, got %s" % ((height, width), array.shape))
    return array
