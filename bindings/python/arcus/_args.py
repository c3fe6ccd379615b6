"""Conversion of Python arguments to what the C API takes, with clear errors.

Shapes and types are checked here, before any library call, so the message names the
Python argument; values (a radius <= 0, rtol <= 0, NaN) are left to the library,
which is the one authority on what it accepts.  Nothing is coerced silently: a
string is never read as a number or a flag, a bool never as a number, and a path
never loses what follows a NUL character.
"""

import numbers
import os

import numpy as np

from ._errors import ArgumentError

_BOOLS = (bool, np.bool_)


def _is_real(value):
    """A real number that is not a bool (numpy scalars included)."""
    return isinstance(value, numbers.Real) and not isinstance(value, _BOOLS)


def to_float(value, name):
    """``value`` as a float; only real numbers (not bools, not strings)."""
    if not _is_real(value):
        raise ArgumentError("%s must be a real number, got %r" % (name, value))
    return float(value)


def to_int(value, name, low, high):
    """``value`` as an int in [low, high]; an integral float (1e6) is accepted exactly.

    ctypes silently wraps integers that do not fit the C type (-1 becomes 2**32 - 1 for
    a uint32_t), hence the explicit range.
    """
    if not _is_real(value):
        raise ArgumentError("%s must be an integer, got %r" % (name, value))
    try:
        number = int(value)
    except (OverflowError, ValueError):  # inf, nan
        raise ArgumentError("%s must be an integer, got %r" % (name, value)) from None
    if number != value or not low <= number <= high:
        raise ArgumentError("%s must be an integer in [%d, %d], got %r" % (name, low, high, value))
    return number


def to_bool(value, name):
    """``value`` as a bool; only True or False (numpy bools too), never a string or 0/1."""
    if not isinstance(value, _BOOLS):
        raise ArgumentError("%s must be True or False, got %r" % (name, value))
    return bool(value)


def to_real_array(value, name):
    """``value`` as a float64 numpy array; refuses strings, bools, complex and other objects."""
    try:
        array = np.asarray(value)
    except (TypeError, ValueError) as exc:  # ragged nesting
        raise ArgumentError("%s must be an array of real numbers: %s" % (name, exc)) from None
    if array.dtype.kind == "O" and all(_is_real(v) for v in array.flat):
        array = array.astype(np.float64)  # a list mixing Python and numpy numbers, Fractions, ...
    if array.dtype.kind not in "iuf":
        raise ArgumentError("%s must be an array of real numbers, got %r" % (name, value))
    return np.asarray(array, dtype=np.float64, order="C")  # keeps a 0-d shape, unlike ascontiguousarray


def to_vec3(value, name):
    """``value`` as a tuple of three floats (x, y, z)."""
    array = to_real_array(value, name)
    if array.shape != (3,):
        raise ArgumentError("%s must be three numbers (x, y, z), got shape %s" % (name, array.shape))
    return tuple(float(v) for v in array)


def to_points(value, name):
    """``value`` as a C-contiguous float64 (N, 3) array; a single (3,) point gives N = 1."""
    array = to_real_array(value, name)
    if array.shape == (3,):
        array = array.reshape(1, 3)
    if array.ndim != 2 or array.shape[1] != 3:
        raise ArgumentError("%s must have shape (N, 3) or (3,), got %s" % (name, array.shape))
    return array


def to_per_ray(value, name, count):
    """One number for every ray, or an (N,) array with N = ``count``: a float64 (N,) array."""
    if _is_real(value) or (isinstance(value, np.ndarray) and value.ndim == 0):
        return np.full(count, float(to_real_array(value, name)))
    array = to_real_array(value, name)
    if array.shape != (count,):
        raise ArgumentError("%s must be one number or an array of shape (%d,) (one per ray), got shape %s"
                            % (name, count, array.shape))
    return array


def to_path(value, name):
    """A file system path (str, bytes or os.PathLike) as the bytes the C API takes.

    ctypes passes bytes as a C string, which ends at the first NUL: the library would
    read another, shorter path.  Such a path is refused.
    """
    if not isinstance(value, (str, bytes, os.PathLike)):
        raise ArgumentError("%s must be a path (str or os.PathLike), got %r" % (name, value))
    try:
        encoded = os.fsencode(value)
    except (TypeError, UnicodeError) as exc:
        raise ArgumentError("%s is not a usable path: %s" % (name, exc)) from None
    if b"\0" in encoded:
        raise ArgumentError("%s contains a NUL character, which would cut the path short: %r" % (name, value))
    return encoded


def to_choice(value, name, choices):
    """The value ``choices[value]`` for a name in ``choices`` (case-insensitive)."""
    key = value.lower() if isinstance(value, str) else None
    if key not in choices:
        raise ArgumentError("%s must be one of %s, got %r" % (name, ", ".join(map(repr, choices)), value))
    return choices[key]
