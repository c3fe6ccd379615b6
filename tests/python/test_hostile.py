"""Hostile input through the Python package: special files and loose JSON in every scene
reader, planted and oversized entries in the sweep's cache (with a second user), a cache
that cannot be written, Dask's local cluster reachable from outside, and a context
closed from another thread while it runs a job.

Each test is the regression test of a finding of the reliability probe of 34ca792.
"""

import io
import json
import os
import shutil
import socket
import stat
import subprocess
import sys
import tempfile
import threading
import time
import warnings
import zipfile
from pathlib import Path

import numpy as np
import pytest

import arcus
import arcus.sky as sky
import arcus.sweep as sweep
from arcus import _task_cache

NOBODY = 65534  # the second user of the cache tests (root gives files to it)


def finishes(call, seconds=20):
    """Runs ``call`` in a thread: (finished within ``seconds``, its exception or None).
    A reader that blocks on a FIFO would hang the test instead of failing it."""
    outcome = {}

    def run():
        try:
            call()
        except BaseException as exc:  # noqa: BLE001  (any exception is the outcome)
            outcome["error"] = exc

    t = threading.Thread(target=run, daemon=True)
    t.start()
    t.join(seconds)
    return not t.is_alive(), outcome.get("error")


def special_files(tmp_path):
    """A FIFO and a link to /dev/zero, each named like a scene."""
    fifo = tmp_path / "fifo.json"
    os.mkfifo(fifo)
    zero = tmp_path / "zero.json"
    zero.symlink_to("/dev/zero")
    return {"is a FIFO": fifo, "is a character device": zero}


# ---- scene readers: every file through the library's strict reader -----------------------


@pytest.mark.parametrize("reader", [
    lambda p: sky.load_scene(p),
    lambda p: sweep.load_spec(p),
    lambda p: sweep.ocean_grid(p, [0.1], [0.0], [0.0], cache_dir=False, client="serial"),
    lambda p: sweep.frames(p, "camera.vfov_deg", [30], cache_dir=False, client="serial"),
    lambda p: arcus.ocean.render(p, photons=100),
    lambda p: sweep.PhaseTables.load(p),
], ids=["sky.load_scene", "sweep.load_spec", "sweep.ocean_grid", "sweep.frames", "ocean.render", "PhaseTables.load"])
def test_scene_readers_refuse_special_files_without_blocking(tmp_path, reader):
    # They blocked on a FIFO for ever and read /dev/zero until MemoryError.
    for words, path in special_files(tmp_path).items():
        done, error = finishes(lambda: reader(path))
        assert done, "%s blocked on %s" % (reader, path)
        # The library names the kind of file; a saved sweep (numpy's reader) says what it is not.
        assert isinstance(error, arcus.Error) and (words in str(error) or "not a regular file" in str(error)), \
            (path, error)


def rainbow_scene(**changes):
    scene = {"sun": {"elevation_deg": 10, "samples": 4},
             "rain": {"box_min": [-1, 0, 10], "box_max": [1, 10, 20],
                      "populations": [{"shape": "sphere", "radius": 5e-4, "density": 100}]}}
    for path, value in changes.items():
        node = scene
        *parents, key = path.split(".")
        for p in parents:
            node = node.setdefault(p, {})
        node[key] = value
    return scene


@pytest.mark.parametrize("text, words", [
    (json.dumps(rainbow_scene(**{"sun.elevaton_deg": 10})), "$.sun.elevaton_deg: unknown key"),
    (json.dumps(rainbow_scene(**{"sun.samples": True})), "$.sun.samples: expected a non-negative integer"),
    (json.dumps(rainbow_scene(**{"sun.samples": 1.5})), "$.sun.samples: expected a non-negative integer, got 1.5"),
    (json.dumps(rainbow_scene(**{"sun.elevation_deg": True})), "$.sun.elevation_deg: expected a number"),
    (json.dumps(rainbow_scene(**{"tables.theta": {"range": [100, 180, 1e-9]}})), "more than 1000000"),
    ('{"rain": {"box_min": [0, 0, 0], "box_min": [1, 1, 1]}}', "$.rain.box_min: key given twice"),
])
def test_rainbow_scene_files_are_read_strictly(tmp_path, text, words):
    # sky.load_scene took unknown and repeated keys, true as a number and 1.5 as 1.
    path = tmp_path / "scene.json"
    path.write_text(text)
    with pytest.raises(arcus.ArgumentError) as err:
        sky.load_scene(path)
    assert words in str(err.value) and str(path) in str(err.value)


def test_a_scene_of_another_engine_is_named_as_such(repo):
    with pytest.raises(arcus.ArgumentError, match="is a render scene, not a rainbow one"):
        sky.load_scene(repo / "scenes" / "cross_room.json")


def test_an_axis_of_a_billion_values_is_refused_before_it_is_made():
    # {"range": [100, 180, 1e-9]} asked for 596 GiB.
    for args in ([100, 180, 1e-9], [0, 1e300, 1e-10]):  # the second's count overflows a float
        with pytest.raises(arcus.ArgumentError, match="more than 1000000"):
            sweep.spec_axis({"range": args}, "theta")


def test_a_spec_file_takes_what_the_python_call_takes(tmp_path):
    # The schema of spec files is the library's; Python's defaults (rotation None) pass it.
    path = tmp_path / "spec.json"
    path.write_text(json.dumps({"kind": "phase_tables", "theta": [130], "wavelengths": [500],
                                "particles": [{"kind": "sphere", "radius": 5e-4, "rotation": None}]}))
    assert sweep.load_spec(path)["particles"][0]["rotation"] is None


# ---- the sweep's cache: this user's alone -------------------------------------------------


def double(spec):
    """A task: a value the test can tell from a planted one."""
    return {"value": np.array([2.0 * spec["x"]])}


def run(cache_dir, xs=(1.0,)):
    return sweep.map_tasks(double, [{"x": x} for x in xs], cache_dir=cache_dir, client="serial")


def planted_copy(genuine, value):
    """The bytes of a cache entry like ``genuine`` (a path) with its value replaced and
    its key and checksum valid: anyone can compute both."""
    with np.load(genuine) as f:
        arrays = {name: f[name] for name in f.files}
    key = arrays.pop("_key")
    arrays.pop("_checksum")
    arrays["value"] = np.array([value])
    buf = io.BytesIO()
    np.savez(buf, **dict(arrays, _key=key, _checksum=np.array(_task_cache._checksum(arrays))))
    return buf.getvalue()


needs_root = pytest.mark.skipif(os.geteuid() != 0 or not shutil.which("setpriv"),
                                reason="a second user needs root and setpriv (CI runs as root)")


def as_nobody(*command, data=None):
    """Runs ``command`` as the second user (setpriv, as root)."""
    subprocess.run(["setpriv", "--reuid=%d" % NOBODY, "--regid=%d" % NOBODY, "--clear-groups", "--", *command],
                   input=data, check=True)


@needs_root
def test_a_shared_cache_directory_is_not_used_and_a_planted_entry_never_read(tmp_path):
    # A planted entry (valid key and checksum: anyone can compute them) set every value to
    # 42.  Now a directory others can write is not used at all.
    private = tmp_path / "private"
    genuine = run(private)
    assert genuine.results[0]["value"][0] == 2.0
    (entry,) = private.glob("*.npz")
    # In /tmp, which the second user can reach (pytest's tmp_path is private to root).
    shared = Path(tempfile.mkdtemp(prefix="arcus_shared_cache_"))
    try:
        shared.chmod(0o1777)  # as /tmp itself
        as_nobody("/bin/sh", "-c", 'cat > "$1"', "sh", str(shared / entry.name), data=planted_copy(entry, 42.0))
        assert (shared / entry.name).stat().st_uid == NOBODY
        with pytest.warns(RuntimeWarning, match="is not used: it is writable by group or others"):
            result = run(shared)
        assert result.results[0]["value"][0] == 2.0 and (result.computed, result.cached) == (1, 0)
        assert result.cache_dir is None
        assert [p.name for p in shared.iterdir()] == [entry.name], "nothing written there"
    finally:
        shutil.rmtree(shared)


@needs_root
def test_an_entry_another_user_owns_is_recomputed_and_replaced(tmp_path):
    run(tmp_path)
    (entry,) = tmp_path.glob("*.npz")
    entry.write_bytes(planted_copy(entry, 42.0))
    assert run(tmp_path).results[0]["value"][0] == 42.0, "control: this user's own entry is trusted"
    os.chown(entry, NOBODY, NOBODY)
    result = run(tmp_path)
    assert result.results[0]["value"][0] == 2.0 and result.computed == 1
    assert entry.stat().st_uid == os.geteuid(), "replaced by this user's"


def test_an_entry_others_can_write_or_a_link_is_not_read(tmp_path):
    run(tmp_path)
    (entry,) = tmp_path.glob("*.npz")
    entry.write_bytes(planted_copy(entry, 42.0))
    entry.chmod(0o666)
    assert run(tmp_path).results[0]["value"][0] == 2.0
    elsewhere = tmp_path / "elsewhere.npz"
    elsewhere.write_bytes(planted_copy(entry, 42.0))
    entry.unlink()
    entry.symlink_to(elsewhere)
    assert run(tmp_path).results[0]["value"][0] == 2.0
    assert not entry.is_symlink(), "the link was replaced, not written through"
    assert np.load(elsewhere)["value"][0] == 42.0


def test_an_entry_inflating_past_the_bound_is_not_decompressed(tmp_path, monkeypatch):
    # A 2 MB entry inflating to 2.3 GB took 60 s and 2.3 GB: the declared sizes are now
    # held to the bound before anything is inflated (here a bound of 1 MiB, an entry of 8).
    run(tmp_path)
    (entry,) = tmp_path.glob("*.npz")
    with np.load(entry) as f:
        arrays = {name: f[name] for name in f.files}
    arrays["value"] = np.zeros(1 << 20)  # 8 MiB of zeros, a few kB compressed
    arrays["_checksum"] = np.array(_task_cache._checksum({k: v for k, v in arrays.items() if not k.startswith("_")}))
    with zipfile.ZipFile(entry, "w", zipfile.ZIP_DEFLATED) as z:
        for name, a in arrays.items():
            buf = io.BytesIO()
            np.lib.format.write_array(buf, a)
            z.writestr(name + ".npy", buf.getvalue())
    assert entry.stat().st_size < 100_000
    monkeypatch.setattr(_task_cache, "MAX_CACHE_ENTRY_BYTES", 1 << 20)
    inflated = []
    monkeypatch.setattr(np.lib.format, "read_array", lambda *a, **k: inflated.append(1))
    result = run(tmp_path)
    assert result.computed == 1 and not inflated, "refused from the zip's directory alone"


def test_an_array_header_claiming_more_than_its_member_holds_is_refused(tmp_path):
    run(tmp_path)
    (entry,) = tmp_path.glob("*.npz")
    with np.load(entry) as f:
        arrays = {name: f[name] for name in f.files}
    buf = io.BytesIO()
    np.lib.format.write_array_header_1_0(buf, {"descr": "<f8", "fortran_order": False, "shape": (1 << 40,)})
    members = {name + ".npy": None for name in arrays}
    with zipfile.ZipFile(entry, "w") as z:
        for name in members:
            if name == "value.npy":
                z.writestr(name, buf.getvalue() + b"\0" * 8)
            else:
                b = io.BytesIO()
                np.lib.format.write_array(b, arrays[name[:-4]])
                z.writestr(name, b.getvalue())
    assert run(tmp_path).computed == 1


def test_cache_directories_and_entries_are_private_whatever_the_umask(tmp_path):
    old = os.umask(0)
    try:
        run(tmp_path / "a" / "b")
    finally:
        os.umask(old)
    assert stat.S_IMODE((tmp_path / "a").stat().st_mode) == 0o700
    assert stat.S_IMODE((tmp_path / "a" / "b").stat().st_mode) == 0o700
    (entry,) = (tmp_path / "a" / "b").glob("*.npz")
    assert stat.S_IMODE(entry.stat().st_mode) == 0o600


def test_a_cache_that_cannot_be_written_costs_only_the_cache(tmp_path):
    # A write error failed every task ("task 0" blamed) and returned nothing; a directory
    # where an entry belongs failed every later run.
    run(tmp_path, xs=(1.0, 2.0))
    for entry in tmp_path.glob("*.npz"):
        entry.unlink()
        entry.mkdir()  # in the way of the entry
    _task_cache._warned.clear()
    with pytest.warns(RuntimeWarning, match="cannot write to the table cache"):
        result = run(tmp_path, xs=(1.0, 2.0))
    assert [r["value"][0] for r in result.results] == [2.0, 4.0] and result.computed == 2
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # warned once, not at every task or run
        assert [r["value"][0] for r in run(tmp_path, xs=(1.0, 2.0)).results] == [2.0, 4.0]


# ---- Dask ---------------------------------------------------------------------------------


def outward_address():
    """This machine's address on its outward interface (no packet is sent), or None."""
    try:
        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
            s.connect(("192.0.2.1", 9))  # TEST-NET-1: only the route is looked up
            address = s.getsockname()[0]
    except OSError:
        return None
    return None if address.startswith("127.") else address


def test_the_local_cluster_listens_on_loopback_only_and_serves_no_dashboard(repo):
    # The sweep's LocalCluster served its dashboard on 0.0.0.0, without authentication.
    # In a process of its own: a dashboard another cluster of this process registered
    # would be served by every later scheduler.
    pytest.importorskip("distributed")
    script = """
import socket, sys, urllib.error, urllib.request
sys.path.insert(0, %r)
from arcus import _tasks
with _tasks._dask_client(None, 1, 10) as client:
    info = client.scheduler_info()
    addresses = [client.scheduler.address] + list(info["workers"])
    assert all(a.startswith("tcp://127.0.0.1:") for a in addresses), addresses
    port = info["services"]["dashboard"]  # the HTTP server: health checks only
    assert port != 8787
    try:
        urllib.request.urlopen("http://127.0.0.1:%%d/status" %% port, timeout=10)
        raise AssertionError("a dashboard is served")
    except urllib.error.HTTPError as err:
        assert err.code == 404, err.code
    outward = %r
    if outward:
        try:
            urllib.request.urlopen("http://%%s:%%d/health" %% (outward, port), timeout=5)
            raise AssertionError("reachable from outside")
        except urllib.error.URLError:
            pass
print("loopback only")
""" % (str(repo / "bindings" / "python"), outward_address())
    r = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and "loopback only" in r.stdout, r.stderr[-2000:]


# ---- a context closed from another thread -------------------------------------------------


def test_closing_a_context_cancels_its_running_job_which_keeps_its_results():
    # close() blocked until the job ended; then the job raised "Context is closed" and its
    # results were lost.  Now the job is cancelled at its next slice and raises
    # ARCUS_ERROR_CANCELLED with what it had.
    from arcus.fields import Linear
    ctx = arcus.Context()
    origins = np.zeros((64, 3))
    directions = np.tile([1.0, 0.0, 0.0], (64, 1))
    outcome = {}

    def job():
        try:
            ctx.advance(Linear(1.0, (0, 0.1, 0)), origins, directions, length=1e4, method="rk4", step=1e-5,
                        max_steps=2_000_000_000)
        except arcus.Error as exc:
            outcome["error"] = exc

    t = threading.Thread(target=job, daemon=True)  # hours of work unless cancelled
    t.start()
    time.sleep(1.0)  # the job runs
    closed, _ = finishes(ctx.close, 30)
    t.join(30)
    assert closed and not t.is_alive()
    error = outcome["error"]
    assert error.status == "ARCUS_ERROR_CANCELLED" and "close() was called from another thread" in error.message
    result = error.result
    assert result is not None and len(result) == 64
    assert set(result.status_names) == {"CANCELLED"} and np.all(result.lengths > 0), "where each ray got to"
    with pytest.raises(arcus.ArgumentError, match="closed"):
        ctx.device


def test_closing_a_context_cancels_its_render(tmp_path):
    # The same for a render frame (which has no partial result): cancelled, not waited for.
    scene = tmp_path / "slow.json"
    scene.write_text(json.dumps({
        "name": "slow", "medium": {"type": "linear", "n0": 1.0, "gradient": [0, 1e-4, 0]},
        "integrator": {"method": "rk4", "step": 0.001, "length": 200},
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "vfov_deg": 40, "width": 256, "height": 256},
        "materials": {"m": {"diffuse": [0.5, 0.5, 0.5]}},
        "objects": [{"type": "sphere", "center": [0, 0, -150], "radius": 1, "material": "m"}],
        "sky": {"type": "constant", "color": [0, 0, 1]}}))
    ctx = arcus.Context()
    outcome = {}

    def render():
        try:
            outcome["result"] = ctx.render(scene, techniques=[])
        except arcus.Error as exc:
            outcome["error"] = exc

    t = threading.Thread(target=render, daemon=True)  # hours of work unless cancelled
    t.start()
    time.sleep(1.0)
    # A generous bound: with a cold kernel cache the frame first compiles its program,
    # which no callback interrupts (measured 70 s on two busy cores); the render itself
    # would take hours.
    closed, _ = finishes(ctx.close, 240)
    t.join(240)
    assert closed and not t.is_alive()
    error = outcome.get("error")
    assert error is not None, "the render finished before close(): make it slower"
    assert error.status == "ARCUS_ERROR_CANCELLED" and "close() was called from another thread" in error.message
