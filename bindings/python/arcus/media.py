"""Deprecated since arcus 0.10: the index-of-refraction fields are :mod:`arcus.fields`,
the name the C API (``arcus_field_*``) uses.  This alias stays for one release."""

import warnings

from .fields import *  # noqa: F401,F403
from .fields import __all__  # noqa: F401

warnings.warn("arcus.media is deprecated since arcus 0.10: import arcus.fields", DeprecationWarning, stacklevel=2)
