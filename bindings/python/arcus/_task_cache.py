"""The sweeps' disk cache: one .npz per task, named by the SHA-256 of its key, this
user's alone (docs/security.md).  Used by :func:`arcus.sweep.map_tasks`."""

import contextlib
import hashlib
import math
import os
import stat
import tempfile
import warnings
import zipfile

import numpy as np



def default_cache_dir():
    """The cache directory when none is given: ``tables/`` beside the library's compiled
    programs (``$ARCUS_CACHE_DIR``, else ``$XDG_CACHE_HOME/arcus``, else
    ``~/.cache/arcus``); False when ``ARCUS_CACHE_DIR=off`` turns caching off."""
    if os.environ.get("ARCUS_CACHE_DIR"):
        env = os.environ["ARCUS_CACHE_DIR"]
        return False if env == "off" else os.path.join(env, "tables")
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "arcus", "tables")


def _checksum(arrays):
    """SHA-256 of named arrays: names, dtypes, shapes and bytes."""
    h = hashlib.sha256()
    for name in sorted(arrays):
        a = np.ascontiguousarray(arrays[name])
        h.update(("%s|%s|%s|" % (name, a.dtype.str, a.shape)).encode())
        h.update(memoryview(a.reshape(-1)).cast("B"))  # the bytes, without a copy
    return h.hexdigest()


def _atomic_savez(path, arrays):
    """Writes ``arrays`` to ``path`` as .npz through a temporary file and os.replace, so
    a reader (or a crash) never sees half a file."""
    directory = os.path.dirname(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=directory, prefix=".tmp-", suffix=".npz")
    try:
        with os.fdopen(fd, "wb") as f:
            np.savez(f, **arrays)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


#: The largest cache entry read back, uncompressed: a task's arrays (a phase table is a
#: few MB, an ocean or frame image tens).  An entry declaring more is not decompressed.
MAX_CACHE_ENTRY_BYTES = 512 << 20

_warned = set()  # (directory, reason) pairs already warned about


def _warn_once(key, message):
    if key not in _warned:
        _warned.add(key)
        warnings.warn(message, RuntimeWarning, stacklevel=3)


def _distrust(st):
    """Why a directory or entry (its os.stat_result) is not to be trusted, or None: it
    must be this user's own and writable by nobody else (docs/security.md)."""
    if st.st_uid != os.geteuid():
        return "it is owned by uid %d, not by this user (uid %d)" % (st.st_uid, os.geteuid())
    if st.st_mode & (stat.S_IWGRP | stat.S_IWOTH):
        return "it is writable by group or others"
    return None


def _private_directory(path):
    """``path`` made (each missing component 0700, whatever the umask) and checked to be
    this user's own and writable by nobody else; None, with a warning once, when it is
    not (then nothing is cached)."""
    path = os.path.abspath(path)
    parts = path.split(os.sep)
    for i in range(2, len(parts) + 1):
        try:
            os.mkdir(os.sep.join(parts[:i]), 0o700)
        except FileExistsError:
            pass
        except OSError:
            break  # the check below says why
    try:
        st = os.stat(path)
        why = None if stat.S_ISDIR(st.st_mode) else "it is not a directory"
        why = why or _distrust(st)
    except OSError as exc:
        why = "it cannot be used: %s" % exc.strerror
    if why:
        _warn_once((path, "dir"), "arcus.sweep: the table cache %s is not used: %s; someone else could plant "
                   "entries there.  Make it yours (chown, chmod go-w) or give another cache_dir; until then "
                   "nothing is cached." % (path, why))
        return None
    return path


def _checked_npz(f):
    """The arrays of the .npz file object ``f``, each member's declared size checked
    against the bound before anything is decompressed (a 2 MB entry inflating to
    2.3 GB took 60 s): None when any member is not a plain numeric array or the total
    exceeds MAX_CACHE_ENTRY_BYTES."""
    with zipfile.ZipFile(f) as z:
        members = z.infolist()
        if sum(m.file_size for m in members) > MAX_CACHE_ENTRY_BYTES:
            return None
        arrays = {}
        for m in members:
            if not m.filename.endswith(".npy"):
                return None
            with z.open(m) as member:
                version = np.lib.format.read_magic(member)
                if version not in ((1, 0), (2, 0)):  # what np.savez writes
                    return None
                read_header = np.lib.format.read_array_header_1_0 if version == (1, 0) else \
                    np.lib.format.read_array_header_2_0
                shape, _, dtype = read_header(member)
                # What the header claims must fit in what the member holds: numpy
                # allocates the array from the header before reading it.
                if dtype.hasobject or math.prod(shape) * dtype.itemsize > m.file_size:
                    return None
            with z.open(m) as member:
                arrays[m.filename[:-4]] = np.lib.format.read_array(member, allow_pickle=False)
        return arrays


class _Cache:
    """One .npz per task: the payload arrays, ``_key`` (the task's canonical JSON) and
    ``_checksum`` (of the payload).  ``directory`` None: no cache.

    The cache is this user's alone (docs/security.md): a directory someone else owns or
    can write is not used (a warning, once), an entry not this user's own, a link, or
    one larger than MAX_CACHE_ENTRY_BYTES is not read (it is recomputed), and entries
    are written 0600 to a fresh temporary file renamed into place.  A cache that cannot
    be written costs only the cache: a warning, and the results are returned.
    """

    def __init__(self, directory):
        self.directory = None if directory is None else _private_directory(directory)

    def _path(self, digest):
        return os.path.join(self.directory, digest + ".npz")

    def read(self, digest, key):
        """The cached payload of the task, or None if there is no trustworthy one."""
        if self.directory is None:
            return None
        try:
            fd = os.open(self._path(digest), os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC)
        except OSError:  # missing, a link, unreadable
            return None
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode) or _distrust(st) or st.st_size > MAX_CACHE_ENTRY_BYTES:
            os.close(fd)
            return None
        with os.fdopen(fd, "rb") as f:
            try:
                arrays = _checked_npz(f)
            except Exception:  # truncated, not a zip, CRC error, bad header: recompute
                return None
        if arrays is None:
            return None
        stored_key, stored_sum = arrays.pop("_key", None), arrays.pop("_checksum", None)
        if stored_key is None or stored_sum is None or str(stored_key) != key or str(stored_sum) != _checksum(arrays):
            return None
        return arrays

    def write(self, digest, key, payload):
        if self.directory is None:
            return
        try:
            _atomic_savez(self._path(digest), dict(payload, _key=np.array(key), _checksum=np.array(_checksum(payload))))
        except OSError as exc:
            _warn_once((self.directory, "write"), "arcus.sweep: cannot write to the table cache %s (%s); the "
                       "results are returned but not cached" % (self.directory, exc))
