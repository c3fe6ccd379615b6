"""Running a sweep's tasks (:func:`arcus.sweep.map_tasks`): their keys, the disk cache,
a serial loop or a Dask cluster, and one arcus context per worker thread."""

import contextlib
import hashlib
import json
import os
import threading
import time
from dataclasses import dataclass

import numpy as np

from ._args import to_bool, to_int
from ._errors import ArgumentError
from ._task_cache import _Cache, default_cache_dir
from .context import Context
from .progress import Progress

#: Seconds to wait for a scheduler given by address before giving up.
CONNECT_TIMEOUT = 10.0
#: Part of every cache key: bump when the cache files' layout or a task's meaning changes.
CACHE_FORMAT = 1


# ---- JSON and keys -------------------------------------------------------------------------


def _plain(value, name):
    """``value`` (numpy arrays and scalars allowed) as plain JSON data, or ArgumentError."""
    def default(v):
        if isinstance(v, np.ndarray):
            return v.tolist()
        if isinstance(v, np.generic):
            return v.item()
        if isinstance(v, os.PathLike):
            return os.fspath(v)
        raise TypeError("%r is not JSON data" % (v,))
    try:
        return json.loads(json.dumps(value, default=default, allow_nan=False))
    except (TypeError, ValueError) as exc:
        raise ArgumentError("%s must be JSON data (numbers finite): %s" % (name, exc)) from None


def _canonical(value):
    """One text per value: sorted keys, no spaces; floats print exactly (repr)."""
    return json.dumps(value, sort_keys=True, separators=(",", ":"), allow_nan=False)


def _payload(result, function):
    """A task's return value as named numeric arrays (what the cache can hold)."""
    if not isinstance(result, dict) or not result:
        raise TypeError("%s must return a non-empty dict of arrays, got %r" % (function, type(result)))
    out = {}
    for name, value in result.items():
        a = np.asarray(value)
        if not isinstance(name, str) or name.startswith("_") or a.dtype.kind not in "biufc":
            raise TypeError("%s returned %r: %r; expected numeric arrays under names not starting with '_'"
                            % (function, name, a.dtype))
        out[name] = a
    return out


# ---- running tasks -------------------------------------------------------------------------


@dataclass
class TaskResults:
    """What :func:`map_tasks` did: ``results`` (one dict of arrays per task, in order),
    ``computed`` and ``cached`` (tasks computed now / read from the cache; a task listed
    twice counts once), ``cache_dir`` (None without a cache) and ``seconds``."""

    results: list
    computed: int
    cached: int
    cache_dir: object
    seconds: float


def _function_name(function):
    name = "%s.%s" % (getattr(function, "__module__", "?"), getattr(function, "__qualname__", "?"))
    if not callable(function) or "<" in name:
        # A lambda's or a local function's name says nothing about what it computes,
        # and the name keys the cache.
        raise ArgumentError("function must be a module-level function (its name keys the cache), got %r"
                            % (function,))
    return name


def _check_workers(workers):
    if workers is None:
        return None
    return to_int(workers, "workers", 0, 4096)


@contextlib.contextmanager
def _dask_client(client, workers, connect_timeout):
    """A distributed.Client for the sweep: the caller's, one connected to an address,
    or one on a LocalCluster of ``workers`` processes; whatever is started here is
    closed on leaving."""
    import distributed  # Dask only where a sweep runs on it: it takes seconds to import, and serial sweeps never need it
    if isinstance(client, distributed.Client):
        yield client
        return
    if isinstance(client, str):
        try:
            c = distributed.Client(client, timeout=connect_timeout, set_as_default=False)
        except ValueError as exc:
            raise ArgumentError("client: %r is not a Dask scheduler address (e.g. 'tcp://host:8786'): %s"
                                % (client, exc)) from None
        except OSError as exc:
            raise ConnectionError("client: no Dask scheduler answered at %r within %g s (%s)"
                                  % (client, connect_timeout, exc)) from None
        try:
            yield c
        finally:
            c.close()
        return
    # One thread a worker: a task keeps the device busy by itself.  Everything listens
    # on 127.0.0.1 only, and no dashboard is served: Dask authenticates nobody, so a
    # cluster reachable from the network runs whatever anyone sends it (docs/security.md;
    # for a dashboard or a cluster across machines, pass a Client of your own).
    # (Its HTTP server, health checks only then, takes a free port: a scheduler already on
    # 8787 is no reason for a clash.)
    cluster = distributed.LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                                       processes=True, host="127.0.0.1", dashboard_address="127.0.0.1:0",
                                       scheduler_kwargs={"dashboard": False})
    try:
        with distributed.Client(cluster, set_as_default=False) as c:
            yield c
    finally:
        cluster.close()


def _run_serial(function, tasks, finish, errors, **_):
    """Runs ``tasks`` (digest -> spec) here, one after another."""
    for digest, spec in tasks.items():
        try:
            finish(digest, function(spec))
        except Exception as exc:
            errors.append((digest, exc))


def _run_on_dask(function, tasks, finish, errors, *, client, workers, connect_timeout):
    """Runs ``tasks`` (digest -> spec) on Dask, finishing each as it arrives; on an
    interrupt the tasks still pending are cancelled."""
    import distributed  # as in _dask_client: Dask only where a sweep runs on it
    with _dask_client(client, workers, connect_timeout) as dask_client:
        prefix = getattr(function, "__name__", "task").strip("_")  # names the bar's row
        futures = dask_client.map(function, list(tasks.values()), key=["%s-%s" % (prefix, d) for d in tasks],
                                  pure=False)
        digest_of = {f.key: d for f, d in zip(futures, tasks)}
        try:
            # with_results: the results are fetched on the client's loop as they come,
            # not one round trip at a time from here
            for future, result in distributed.as_completed(futures, loop=dask_client.loop, with_results=True,
                                                           raise_errors=False):
                try:
                    if future.status != "finished":
                        future.result()  # raises the task's exception
                    finish(digest_of[future.key], result)
                except Exception as exc:
                    errors.append((digest_of[future.key], exc))
        except BaseException:  # interrupted: what finished is cached, the rest is dropped
            dask_client.cancel(futures)
            raise


def map_tasks(function, specs, *, cache_dir=None, client=None, workers=None, progress=False,
              connect_timeout=CONNECT_TIMEOUT):
    """Maps ``function`` over ``specs`` (JSON-serialisable task descriptions), each
    result a dict of numeric arrays, with the disk cache and a Dask cluster (see the
    module's docstring): a :class:`TaskResults`.

    Only the tasks without a trustworthy cache file run; each result is cached as soon
    as it arrives.  A failing task does not stop the others: they finish (and are
    cached), then the first failure is raised again with a note naming its task.

    Args:
        function: a module-level function ``function(spec) -> {name: array}``,
            importable on the workers; its qualified name is part of the cache key.
        specs: a list of dicts; each is passed through JSON first, so the task sees
            exactly what keyed it.
        cache_dir: a directory, None (:func:`default_cache_dir`) or False (no cache).
        client: None (a LocalCluster here), a ``distributed.Client``, a scheduler
            address, or "serial" (a loop in this process).
        workers: the LocalCluster's worker processes (default: os.cpu_count()); 0: serial.
        progress: show a progress bar on a terminal (:class:`arcus.progress.Progress`):
            what is computed, how many results were cached, done/total and an ETA.
        connect_timeout: seconds to wait for a scheduler given by address.
    """
    started = time.monotonic()
    name = _function_name(function)
    workers = _check_workers(workers)
    progress = to_bool(progress, "progress")
    named_serial = isinstance(client, str) and client == "serial"
    serial = named_serial or workers == 0
    if not (client is None or named_serial) and workers is not None:
        raise ArgumentError("workers applies to the local cluster only, not with client=%r" % (client,))
    if not (client is None or isinstance(client, str)):
        import distributed  # as in _dask_client: a client object means Dask is in use already
        if not isinstance(client, distributed.Client):
            raise ArgumentError("client must be None, 'serial', a scheduler address or a distributed.Client, got %r"
                                % (client,))
    if not isinstance(specs, (list, tuple)):
        raise ArgumentError("specs must be a list of task dicts, got %r" % (type(specs),))
    specs = [_plain(s, "specs[%d]" % i) for i, s in enumerate(specs)]
    if cache_dir is None:
        cache_dir = default_cache_dir()
    if cache_dir is False:
        cache = _Cache(None)
    else:
        cache = _Cache(os.fspath(default_cache_dir() if cache_dir is None else cache_dir))

    # Tasks by digest: a task listed twice runs once.
    keys = [_canonical(dict(function=name, spec=s, arcus=_arcus_version(), format=CACHE_FORMAT)) for s in specs]
    digests = [hashlib.sha256(k.encode()).hexdigest() for k in keys]
    payloads = {}
    for d, k in zip(digests, keys):
        if d not in payloads:
            payloads[d] = cache.read(d, k)
    cached = sum(p is not None for p in payloads.values())
    missing = {}  # the tasks not in the cache: digest -> (key, spec), in the order given
    for d, k, s in zip(digests, keys, specs):
        if payloads[d] is None:
            missing.setdefault(d, (k, s))

    bar = None
    if progress and missing:
        what = getattr(function, "what", name)  # e.g. "phase tables (one particle, one wavelength)"
        bar = Progress("%s: %d cached, computing %d%s" % (what, cached, len(missing), "" if serial else " on Dask"),
                       total=len(missing), unit="tasks")

    def finish(digest, result):
        payloads[digest] = _payload(result, name)
        cache.write(digest, missing[digest][0], payloads[digest])
        if bar is not None:
            bar.advance()

    errors = []
    if missing:
        run = _run_serial if serial else _run_on_dask
        try:
            run(function, {d: s for d, (_, s) in missing.items()}, finish, errors, client=client, workers=workers,
                connect_timeout=connect_timeout)
        finally:
            if bar is not None:
                bar.close()
    if errors:
        order = list(missing)
        digest, exc = min(errors, key=lambda e: order.index(e[0]))
        index = digests.index(digest)
        others = len(missing) - len(errors)
        exc.add_note("arcus.sweep: task %d of %d failed: %s(%s); %d of the %d tasks run failed%s"
                     % (index, len(specs), name, _canonical(specs[index])[:300], len(errors), len(missing),
                        "" if not others else "; the %d others finished%s" % (others, " and are cached"
                                                                               if cache.directory else "")))
        raise exc
    return TaskResults(results=[payloads[d] for d in digests], computed=len(missing), cached=cached,
                       cache_dir=cache.directory, seconds=time.monotonic() - started)


def _arcus_version():
    from . import __version__  # not at the top: the package's __init__ imports sweep, which imports this module
    return __version__


# ---- one Context per worker thread -------------------------------------------------------

_contexts = {}  # (pid, thread) -> arcus.Context: a forked child makes its own


def _worker_context():
    """This worker thread's arcus.Context, created on first use (one per thread: a
    context serialises its jobs)."""
    key = (os.getpid(), threading.get_ident())
    ctx = _contexts.get(key)
    if ctx is None:
        ctx = _contexts[key] = Context()
    return ctx
