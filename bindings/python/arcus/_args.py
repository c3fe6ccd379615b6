"""Conversion of Python arguments to what the C API takes, with clear errors.

Shapes and types are checked here, before any library call, so the message names the
Python argument; values (a radius <= 0, rtol <= 0, NaN) are left to the library,
which is the one authority on what it accepts.
"""

import numpy as np

from ._errors import ArgumentError


def to_float(value, name):
    """``value`` as a float."""
    try:
        return float(value)
    except (TypeError, ValueError):
        raise ArgumentError("%s must be a number, got %r" % (name, value)) from None


def to_int(value, name, low, high):
    """``value`` as an int in [low, high].

    ctypes silently wraps integers that do not fit the C type (-1 becomes 2**32 - 1 for
    a uint32_t), hence the explicit range.
    """
    try:
        number = int(value)
    except (TypeError, ValueError):
        raise ArgumentError("%s must be an integer, got %r" % (name, value)) from None
    if number != value or not low <= number <= high:
        raise ArgumentError("%s must be an integer in [%d, %d], got %r" % (name, low, high, value))
    return number


def to_vec3(value, name):
    """``value`` as a tuple of three floats (x, y, z)."""
    try:
        array = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise ArgumentError("%s must be three numbers (x, y, z), got %r" % (name, value)) from None
    if array.shape != (3,):
        raise ArgumentError("%s must be three numbers (x, y, z), got shape %s" % (name, array.shape))
    return tuple(float(v) for v in array)


def to_points(value, name):
    """``value`` as a C-contiguous float64 (N, 3) array; a single (3,) point gives N = 1."""
    try:
        array = np.ascontiguousarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ArgumentError("%s must be an array of 3-vectors: %s" % (name, exc)) from None
    if array.shape == (3,):
        array = array.reshape(1, 3)
    if array.ndim != 2 or array.shape[1] != 3:
        raise ArgumentError("%s must have shape (N, 3) or (3,), got %s" % (name, array.shape))
    return array


def to_choice(value, name, choices):
    """The value ``choices[value]`` for a name in ``choices`` (case-insensitive)."""
    key = value.lower() if isinstance(value, str) else value
    if key not in choices:
        raise ArgumentError("%s must be one of %s, got %r" % (name, ", ".join(map(repr, choices)), value))
    return choices[key]
