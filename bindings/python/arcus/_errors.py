"""Exceptions raised by the arcus bindings.

Kept in a module of its own, free of any ctypes code, so that the library loader can
raise them before the shared library (and hence the rest of the package) exists.
"""

# Status codes of arcus.h that the Python side raises itself; the library's own
# names for every code come from arcus_status_string at run time.
INVALID_ARGUMENT = 1
DEVICE_NOT_FOUND = 3

_STATUS_NAMES = {
    INVALID_ARGUMENT: "ARCUS_ERROR_INVALID_ARGUMENT",
    DEVICE_NOT_FOUND: "ARCUS_ERROR_DEVICE_NOT_FOUND",
}


class Error(Exception):
    """A failed arcus call.

    Attributes:
        code: the ``arcus_status`` value (an int, 0 never appears here).
        status: its name as the library spells it, e.g. ``"ARCUS_ERROR_INVALID_ARGUMENT"``.
        message: what went wrong and which argument, as the library reported it (or,
            for checks done in Python before calling the library, as the binding did).
        result: for ``ARCUS_ERROR_INVALID_RAYS``, ``ARCUS_ERROR_PATH_OVERFLOW`` and
            ``ARCUS_ERROR_CANCELLED`` the library still produced every ray's result (the
            flagged rays marked, the unfinished ones ``RAY_CANCELLED``); it is attached
            here as an :class:`arcus.AdvanceResult` so nothing is lost.  ``None`` otherwise.
    """

    def __init__(self, code, message, status=None, result=None):
        self.code = int(code)
        self.status = status or _STATUS_NAMES.get(self.code, "ARCUS_STATUS_%d" % self.code)
        self.message = message or "(the library gave no message)"
        self.result = result
        super().__init__("%s: %s" % (self.status, self.message))


class ArgumentError(Error, ValueError):
    """An invalid argument (``ARCUS_ERROR_INVALID_ARGUMENT``).

    Raised both by the binding's own checks (array shapes, unknown method names, ...),
    before any call into the library, and for the library's own argument checks.  It is
    also a :class:`ValueError`, so code that handles plain Python value errors catches it.
    """

    def __init__(self, message, status=None, result=None):
        super().__init__(INVALID_ARGUMENT, message, status, result)


class LibraryNotFoundError(Error, ImportError):
    """``libarcus`` could not be loaded; the message lists every place that was tried.

    Raised while importing :mod:`arcus`, hence also an :class:`ImportError`.
    """

    def __init__(self, message):
        # Not an arcus_status: the library never ran.  -1 keeps `code` an int.
        super().__init__(-1, message, status="ARCUS_LIBRARY_NOT_FOUND")


def error_for(code, message, status=None, result=None):
    """The exception for a failed call with status ``code`` (ArgumentError when apt)."""
    if code == INVALID_ARGUMENT:
        return ArgumentError(message, status, result)
    return Error(code, message, status, result)
