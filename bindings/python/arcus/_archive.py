"""A sweep's result saved as a plain .npz and read back (arcus.sweep's PhaseTables,
OceanGrid and Frames): arrays as they are, the rest as JSON text, nothing pickled."""

import contextlib
import json
import os
import stat
from dataclasses import fields

import numpy as np

from ._errors import ArgumentError
from ._task_cache import _atomic_savez
from ._tasks import _canonical


class _Archive:
    """save()/load() of a sweep's result as a plain .npz: arrays as they are, numbers as
    0-d arrays, everything else (specs, scenes, None) as JSON text, listed in ``_json``."""

    _transient = ("computed", "cached")

    def save(self, path):
        """Writes the result to ``path`` (a .npz, written atomically)."""
        arrays, as_json = dict(type=np.array(type(self).__name__)), []
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name in self._transient:
                continue
            if isinstance(value, np.ndarray):
                arrays[f.name] = value
            elif isinstance(value, (int, float)) and not isinstance(value, bool):
                arrays[f.name] = np.array(value)
            else:
                arrays[f.name] = np.array(_canonical(value))
                as_json.append(f.name)
        arrays["_json"] = np.array(as_json, dtype=str)
        _atomic_savez(os.fspath(path), arrays)

    @classmethod
    def load(cls, path):
        """Reads a file written by :meth:`save`."""
        with contextlib.suppress(OSError):  # a missing file: numpy says so below
            # A FIFO would block the read for ever, a device never end.
            if not stat.S_ISREG(os.stat(path).st_mode):
                raise ArgumentError("path: %r is not a regular file (a saved sweep)" % (os.fspath(path),))
        try:
            with np.load(path, allow_pickle=False) as f:
                arrays = {name: f[name] for name in f.files}
        except (OSError, ValueError) as exc:
            raise ArgumentError("path: cannot read %r as a saved sweep: %s" % (os.fspath(path), exc)) from None
        kind = str(arrays.get("type", "no saved sweep"))
        if kind != cls.__name__:
            raise ArgumentError("path: %r holds %s, not %s" % (os.fspath(path), kind, cls.__name__))
        as_json = set(arrays.get("_json", np.array([], dtype=str)).tolist())
        names = [f.name for f in fields(cls) if f.name not in cls._transient]
        missing = [n for n in names if n not in arrays]
        if missing:
            raise ArgumentError("path: %r lacks %s" % (os.fspath(path), ", ".join(missing)))
        values = {n: json.loads(str(arrays[n])) if n in as_json else arrays[n] for n in names}
        return cls(**{n: v.item() if isinstance(v, np.ndarray) and v.ndim == 0 else v for n, v in values.items()})
