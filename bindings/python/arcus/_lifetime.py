"""How the package's references to library objects live and die: each held by a
:class:`_Handle` (released once, by its owner or its finalizer), a context's by a
:class:`_ContextState` (with the jobs running on it), and releases made while a
progress callback runs deferred until the library returns."""

import collections
import threading
import weakref

from . import _lib
from ._lib import lib


# ---- releasing library objects ----------------------------------------------------------
# A progress callback runs with its context's lock held by the library, and dropping the
# last reference to an object of a context takes that lock: a release on the callback's
# thread (the callback dropping a field, or the garbage collector running a finalizer
# there) would deadlock.  So while a progress callback runs on a thread, releases made
# on that thread wait in _deferred until the library call that ran the callback returns.

_local = threading.local()  # .active: the _ContextStates whose progress callback runs on this thread
_deferred = collections.deque()  # (function, args); deque appends and pops are atomic


def _active():
    active = getattr(_local, "active", None)
    if active is None:
        active = _local.active = []
    return active


def _release(function, *args):
    if _active():
        _deferred.append((function, args))
    else:
        function(*args)


def _flush_deferred():
    if _active():
        return
    while True:
        try:
            function, args = _deferred.popleft()
        except IndexError:
            return
        function(*args)


class _Handle:
    """Owns one reference to a library object and releases it exactly once.

    weakref.finalize rather than __del__: it also runs at interpreter exit while the
    library is still loaded, and never sees half-torn-down module globals.
    """

    __slots__ = ("value", "_finalizer", "__weakref__")

    def __init__(self, value, release):
        self.value = value
        self._finalizer = weakref.finalize(self, _release, release, value)

    def release(self):
        self._finalizer()


class _ContextState:
    """What a Context owns, kept outside it so the finalizer does not keep it alive."""

    def __init__(self, handle):
        self.handle = handle
        # Realised fields: Field description -> _Handle.  Weak keys: once a description
        # is gone nobody can ask for it again, so its library object is released.
        self.fields = weakref.WeakKeyDictionary()
        # Scenes' and scene fields' _Handles, released with the context at the latest.
        self.objects = weakref.WeakSet()
        self.callback = None  # the ctypes wrapper must outlive its registration
        self.lock = threading.Lock()
        # Jobs running on this context, by thread, and close(): once closing, new calls
        # are refused and every running job is cancelled at its next slice, then close()
        # waits for them to return their results before releasing the context.
        self.jobs = threading.Condition()
        self.job_threads = collections.Counter()
        self.closing = False

    def release(self):
        if self.callback is not None:
            lib.arcus_context_set_error_callback(self.handle, _lib.ERROR_CALLBACK(), None)
            self.callback = None
        for handle in list(self.fields.values()) + list(self.objects):
            handle.release()
        self.fields.clear()
        lib.arcus_context_release(self.handle)
        self.handle = None
