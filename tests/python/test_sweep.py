"""arcus.sweep: sweeps on Dask give the serial loop's results bit for bit, survive a
killed worker, reuse their disk cache without trusting a damaged file, refuse bad
input clearly; and apps/sweep/arcus_sweep.py on a tiny spec.

One LocalCluster of two worker processes serves the module; the killed-worker test
has its own, so the others never see a worker restarting.
"""

import json
import os
import signal
import subprocess
import sys
import threading
import time
import zipfile

import numpy as np
import pytest

import arcus
import arcus.sweep as sweep

distributed = pytest.importorskip("distributed")

THETA = np.arange(120.0, 150.0, 0.5)
WAVELENGTHS = [450.0, 550.0, 650.0]
PARTICLES = [{"kind": "sphere", "radius": 5e-4}, {"kind": "sphere", "radius": 5e-4, "method": "mie"}]
FIELDS = ("phase", "cross_section", "extinction", "intercepted", "remaining")


def cluster_client(workers=2):
    cluster = distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                       dashboard_address=":0")
    return cluster, distributed.Client(cluster, set_as_default=False)


@pytest.fixture(scope="module")
def client():
    cluster, c = cluster_client()
    yield c
    c.close()
    cluster.close()


def assert_same_tables(a, b):
    for name in FIELDS:
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)


def tables(**options):
    options.setdefault("cache_dir", False)
    return sweep.phase_tables(PARTICLES, WAVELENGTHS, THETA, grid=100, **options)


@pytest.fixture(scope="module")
def serial():
    return tables(client="serial")


# ---- results --------------------------------------------------------------------------------


def test_cluster_equals_serial(client, serial, tmp_path):
    t = tables(client=client, cache_dir=tmp_path)
    assert_same_tables(t, serial)
    assert (t.computed, t.cached) == (6, 0)
    assert t.phase.shape == (2, 3, THETA.size) and t.cross_section.shape == (2, 3)
    # what the fields mean: rays scatter sum(scattered) of the intercepted area and
    # extinguish twice it; Mie's efficiencies are about 2 for a large drop
    assert np.all(serial.extinction[0] == 2 * serial.intercepted[0])
    ratio = serial.cross_section[0] / serial.intercepted[0]
    assert np.all((ratio < 1) & (ratio > 0.99))
    area = np.pi * 5e-4 ** 2
    np.testing.assert_allclose(serial.intercepted[1], area)
    np.testing.assert_allclose(serial.extinction[1] / area, 2.0, atol=0.02)
    assert np.all(serial.remaining[1] == 0) and np.all((serial.remaining[0] > 0) & (serial.remaining[0] < 0.01))
    again = tables(client=client, cache_dir=tmp_path)  # the cache: nothing left to compute
    assert (again.computed, again.cached) == (0, 6)
    assert_same_tables(again, serial)


def test_two_dimensional_tables(client, tmp_path):
    phi = [0.0, 30.0, 90.0]
    options = dict(phi=phi, grid=60, cache_dir=False)
    local = sweep.phase_tables(PARTICLES, WAVELENGTHS[:2], THETA, client="serial", **options)
    assert local.phase.shape == (2, 2, 3, THETA.size)
    np.testing.assert_array_equal(local.phase[1, :, 0], local.phase[1, :, 2])  # Mie: the same for every phi
    assert_same_tables(sweep.phase_tables(PARTICLES, WAVELENGTHS[:2], THETA, client=client, **options), local)
    local.save(tmp_path / "t.npz")
    back = sweep.PhaseTables.load(tmp_path / "t.npz")
    assert_same_tables(back, local)
    np.testing.assert_array_equal(back.phi, phi)
    assert back.particles == local.particles and (back.grid, back.max_bounces) == (60, 3)
    with np.load(tmp_path / "t.npz") as f:  # a plain .npz: the specs as JSON text
        assert json.loads(str(f["particles"]))[1]["method"] == "mie"


def test_save_load(serial, tmp_path):
    serial.save(tmp_path / "s.npz")
    back = sweep.PhaseTables.load(tmp_path / "s.npz")
    assert_same_tables(back, serial)
    assert back.phi is None and back.particles == serial.particles
    np.testing.assert_array_equal(back.wavelengths, WAVELENGTHS)
    with pytest.raises(arcus.ArgumentError, match="holds PhaseTables, not Frames"):
        sweep.Frames.load(tmp_path / "s.npz")
    with pytest.raises(arcus.ArgumentError, match="cannot read"):
        sweep.PhaseTables.load(tmp_path / "missing.npz")


@pytest.mark.heavy
def test_killed_worker_loses_nothing(tmp_path):
    """A worker SIGKILLed while it runs a task: the scheduler runs that task again
    elsewhere, and the tables come out complete and equal to the serial loop's."""
    particles = [{"kind": "sphere", "radius": 5e-4}]
    wavelengths = np.linspace(420.0, 680.0, 8)
    options = dict(grid=500, cache_dir=tmp_path)  # about 0.2-0.5 s a task: time to land the kill
    cluster, c = cluster_client()
    try:
        pids = c.run(os.getpid)
        victim = sorted(pids)[0]
        out, errors = [], []

        def run():
            try:
                out.append(sweep.phase_tables(particles, wavelengths, THETA, client=c, **options))
            except Exception as exc:  # reported below
                errors.append(exc)

        thread = threading.Thread(target=run)
        thread.start()
        killed = False
        deadline = time.monotonic() + 60
        while thread.is_alive() and time.monotonic() < deadline:
            # mid-sweep: some tables are in, and the victim is running one
            if list(tmp_path.glob("*.npz")) and c.processing().get(victim):
                os.kill(pids[victim], signal.SIGKILL)
                killed = True
                break
            time.sleep(0.01)
        thread.join(120)
        assert killed, "the sweep ended before the kill could land"
        assert not errors, errors
        assert pids[victim] not in c.run(os.getpid).values()  # it really died
    finally:
        c.close()
        cluster.close()
    result = out[0]
    assert (result.computed, result.cached) == (8, 0)
    reference = sweep.phase_tables(particles, wavelengths, THETA, client="serial", **dict(options, cache_dir=False))
    assert_same_tables(result, reference)


def test_cache_never_trusts_a_damaged_file(serial, tmp_path):
    first = tables(client="serial", cache_dir=tmp_path)
    assert (first.computed, first.cached) == (6, 0)
    files = sorted(tmp_path.glob("*.npz"))
    assert len(files) == 6 and not list(tmp_path.glob(".tmp-*"))  # one per task, no temporaries left
    second = tables(client="serial", cache_dir=tmp_path)
    assert (second.computed, second.cached) == (0, 6)

    truncated, flipped, forged, deleted = files[:4]
    truncated.write_bytes(truncated.read_bytes()[:200])
    data = bytearray(flipped.read_bytes())
    data[len(data) // 2] ^= 0xFF
    flipped.write_bytes(bytes(data))
    with np.load(forged) as f:  # a well-formed file whose table no longer matches its checksum
        arrays = {name: f[name] for name in f.files}
    arrays["phase"] = arrays["phase"] * 2
    np.savez(forged, **arrays)
    assert zipfile.is_zipfile(forged)
    deleted.unlink()  # an interrupted sweep: only this one is missing

    third = tables(client="serial", cache_dir=tmp_path)
    assert (third.computed, third.cached) == (4, 2)
    assert_same_tables(third, serial)
    fourth = tables(client="serial", cache_dir=tmp_path)  # the damaged files were replaced
    assert (fourth.computed, fourth.cached) == (0, 6)


def test_scenes_whose_angles_are_a_subset_share_one_table_exactly(tmp_path):
    # The ray-cast tables live on the shared 0.01 degree grid: double_bow's angles (100-180
    # every 0.05) and supernumerary's (120-180 every 0.02) are both slices of it, so the
    # second scene computes nothing.  The slices are the point samples the cast gives at
    # those angles asked directly (the phase function is read off the cast at any
    # direction); np.arange's angles differ from the shared grid's by float rounding
    # (~1e-11 degrees), which moves a sample by far less than 1e-9 of the peak.
    drop, wl = [{"kind": "sphere", "radius": 5e-4}], [450.0, 650.0]
    bow = sweep.phase_tables(drop, wl, np.arange(100, 180.001, 0.05), grid=120, cache_dir=tmp_path, client="serial")
    assert (bow.computed, bow.cached) == (2, 0)
    theta = np.arange(120, 180.001, 0.02)
    fringes = sweep.phase_tables(drop, wl, theta, grid=120, cache_dir=tmp_path, client="serial")
    assert (fringes.computed, fringes.cached) == (0, 2)
    direct = arcus.rainbow.phase_function(arcus.rainbow.Sphere(5e-4), 650.0, theta, grid=120, max_bounces=3)
    np.testing.assert_allclose(fringes.phase[0, 1], direct.unpolarized, rtol=1e-9, atol=1e-9 * direct.unpolarized.max())
    # A grid off the shared one (0.015 degrees) is computed on its own angles.
    odd = sweep.phase_tables(drop, wl, np.arange(130, 140, 0.015), grid=120, cache_dir=tmp_path, client="serial")
    assert odd.computed == 2


def test_default_cache_dir(monkeypatch, tmp_path):
    monkeypatch.setenv("ARCUS_CACHE_DIR", str(tmp_path / "a"))
    assert sweep.default_cache_dir() == os.path.join(str(tmp_path / "a"), "tables")  # beside the programs
    monkeypatch.setenv("ARCUS_CACHE_DIR", "off")
    assert sweep.default_cache_dir() is False
    monkeypatch.delenv("ARCUS_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "x"))
    assert sweep.default_cache_dir() == os.path.join(str(tmp_path / "x"), "arcus", "tables")


def test_failing_task_names_itself_and_the_rest_are_cached(tmp_path):
    particles = [{"kind": "sphere", "radius": 5e-4, "method": "mie"}, {"kind": "raindrop", "diameter": 9e-3}]
    with pytest.raises(arcus.Error) as info:  # the library refuses a 9 mm raindrop
        sweep.phase_tables(particles, WAVELENGTHS, THETA, grid=50, client="serial", cache_dir=tmp_path)
    assert "task 3 of 6 failed" in "".join(info.value.__notes__)
    assert len(list(tmp_path.glob("*.npz"))) == 3  # the Mie tables finished and are kept


@pytest.mark.heavy  # four ocean renders, serial and on Dask: both paths run instrumented in smaller tests
def test_ocean_grid_and_frames(client, repo):
    options = dict(width=12, height=8, photons=20000, k=40, steps=30, cache_dir=False)
    scene = repo / "scenes" / "ocean" / "fig5_8" / "c0_ad0_ay0.json"
    local = sweep.ocean_grid(scene, [0.0, 1.0], [0.1], [0.0, 0.1], client="serial", **options)
    assert local.image.shape == (2, 1, 2, 8, 12, 3)
    assert not np.array_equal(local.image[0, 0, 0], local.image[1, 0, 0])  # chlorophyll changes the water's hue
    np.testing.assert_array_equal(sweep.ocean_grid(scene, [0.0, 1.0], [0.1], [0.0, 0.1], client=client,
                                                   **options).image, local.image)

    scene = repo / "scenes" / "inferior_mirage.json"
    options = dict(width=40, height=20, cache_dir=False)
    local = sweep.frames(scene, "camera.position.1", [1.0, 4.0], client="serial", **options)
    assert local.image.shape == (2, 20, 40, 3)
    assert not np.array_equal(local.image[0], local.image[1])
    np.testing.assert_array_equal(sweep.frames(scene, "camera.position.1", [1.0, 4.0], client=client,
                                               **options).image, local.image)
    assert not list((repo / "scenes").glob("tmp*.json"))  # the frames' scene copies are gone


def test_crystal_goes_to_halo(tmp_path):
    halo = pytest.importorskip("arcus.halo")
    if not hasattr(halo, "crystal_table"):
        pytest.skip("arcus.halo has no crystal_table")
    spec = {"kind": "crystal", "shape": "plate", "orientations": 3}
    theta = np.arange(0.5, 180.0, 1.0)
    t = sweep.phase_tables([spec], [550.0], theta, grid=16, client="serial", cache_dir=False)
    direct = halo.crystal_table(spec, 550.0, theta, grid=16, max_bounces=3)
    np.testing.assert_array_equal(t.phase[0, 0], direct["phase"])
    assert t.cross_section[0, 0] == direct["cross_section"] and t.particles[0]["size"] == 50e-6


# ---- bad input --------------------------------------------------------------------------------


@pytest.mark.parametrize("particles, wavelengths, match", [
    ([], WAVELENGTHS, "particles must be a non-empty list"),
    ([{"kind": "cube", "size": 1}], WAVELENGTHS, r"particles\[0\]: unknown kind 'cube'"),
    ([{"kind": "sphere", "radius": 5e-4, "radus": 1}], WAVELENGTHS, "unknown key 'radus'"),
    ([{"kind": "sphere"}], WAVELENGTHS, "a sphere needs 'radius'"),
    ([{"kind": "sphere", "radius": -1.0}], WAVELENGTHS, r"particles\[0\].radius must be a finite number > 0"),
    ([{"kind": "sphere", "radius": 1e-3, "method": "exact"}], WAVELENGTHS, r"method must be one of"),
    ([{"kind": "mesh", "path": "/nonexistent.obj"}], WAVELENGTHS, "no such file"),
    ([{"kind": "sphere", "radius": 1e-3, "rotation": [1, 0, 0]}], WAVELENGTHS, "3x3 matrix"),
    (PARTICLES, [450.0, float("nan")], r"wavelengths\[1\] must be a finite number"),
    (PARTICLES, [], "non-empty"),
])
def test_bad_input(particles, wavelengths, match):
    with pytest.raises(arcus.ArgumentError, match=match):
        sweep.phase_tables(particles, wavelengths, THETA, client="serial", cache_dir=False)


def test_bad_options():
    with pytest.raises(arcus.ArgumentError, match="theta"):
        sweep.phase_tables(PARTICLES, WAVELENGTHS, [190.0], client="serial")
    with pytest.raises(arcus.ArgumentError, match="workers must be an integer"):
        sweep.phase_tables(PARTICLES, WAVELENGTHS, THETA, workers=-1)
    with pytest.raises(arcus.ArgumentError, match="client must be"):
        sweep.phase_tables(PARTICLES, WAVELENGTHS, THETA, client=42)
    with pytest.raises(arcus.ArgumentError, match="module-level function"):
        sweep.map_tasks(lambda spec: spec, [{}], client="serial")
    with pytest.raises(arcus.ArgumentError, match=r"parameter: 'camera.position.7'"):
        sweep.frames({"camera": {"position": [0, 1, 2]}}, "camera.position.7", [1.0], client="serial")
    with pytest.raises(arcus.ArgumentError, match="bio-optical"):
        sweep.ocean_grid({"water": {"iops": {}}, "view": {"camera": {}}}, [0], [0], [0], client="serial")


def test_bad_scheduler_address():
    started = time.monotonic()
    with pytest.raises(ConnectionError, match="client: no Dask scheduler answered at 'tcp://127.0.0.1:9'"):
        tables(client="tcp://127.0.0.1:9", connect_timeout=1.0)
    assert time.monotonic() - started < 15
    with pytest.raises(arcus.ArgumentError, match="is not a Dask scheduler address"):
        tables(client="nonsense::address", connect_timeout=1.0)


# ---- the command ------------------------------------------------------------------------------


def run_cli(repo, *args):
    env = dict(os.environ, PYTHONPATH=str(repo / "bindings" / "python"))
    return subprocess.run([sys.executable, str(repo / "apps" / "sweep" / "arcus_sweep.py"), *map(str, args)],
                          capture_output=True, text=True, timeout=120, env=env)


def test_cli(repo, client, tmp_path):
    spec = dict(kind="phase_tables", particles=PARTICLES, wavelengths={"linspace": [450, 650, 3]},
                theta={"range": [120, 149.5, 0.5]}, grid=100)
    path = tmp_path / "tiny.json"
    path.write_text(json.dumps(spec))
    args = (path, "--scheduler", client.scheduler.address, "--cache", tmp_path / "cache", "-o", tmp_path / "t.npz")
    r = run_cli(repo, *args)
    assert r.returncode == 0, r.stderr
    assert "6 tasks, 6 computed, 0 read from the cache" in r.stdout
    result = sweep.PhaseTables.load(tmp_path / "t.npz")
    np.testing.assert_array_equal(result.theta, THETA)
    np.testing.assert_array_equal(result.wavelengths, WAVELENGTHS)
    assert_same_tables(result, tables(client="serial"))
    r = run_cli(repo, *args)
    assert r.returncode == 0 and "6 tasks, 0 computed, 6 read from the cache" in r.stdout, r.stderr


# The spec file is read and checked by the library: its messages name the key's path.
@pytest.mark.parametrize("spec, match", [
    ({"kind": "phase_table"}, '$.kind: "phase_table" is not one of phase_tables, ocean_grid, frames'),
    ({"kind": "phase_tables", "particles": [], "wavelengths": [500], "theta": [130]},
     "$.particles: expected at least one particle"),
    ({"kind": "phase_tables", "particles": PARTICLES, "wavelengths": {"linspace": [400, 700]}, "theta": [130]},
     "$.wavelengths.linspace: expected [first, last, count]"),
    ({"kind": "frames", "scene": "x.json", "parameter": "camera.vfov_deg", "values": [1], "fps": 24},
     "$.fps: unknown key"),
    ({"kind": "phase_tables", "particles": PARTICLES, "wavelengths": [500], "theta": [130], "grid": 1.5},
     "$.grid: expected a non-negative integer, got 1.5"),
    ({"kind": "phase_tables", "particles": PARTICLES, "wavelengths": [500], "theta": {"range": [100, 180, 1e-9]}},
     "$.theta.range: makes 80000000001 values, more than 1000000"),
    ("not json", "not valid JSON"),
    ('{"kind": "frames", "kind": "frames"}', "$.kind: key given twice"),
])
def test_cli_bad_spec(repo, tmp_path, spec, match):
    path = tmp_path / "bad.json"
    path.write_text(spec if isinstance(spec, str) else json.dumps(spec))
    r = run_cli(repo, path, "--workers", "0", "--no-cache", "-o", tmp_path / "never.npz")
    assert r.returncode == 2, (r.stdout, r.stderr)
    assert match in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert not (tmp_path / "never.npz").exists()


def test_a_radius_per_wavelength_is_each_wavelengths_own_sphere_determinism(tmp_path):
    """A sphere given one radius per wavelength (a size distribution's moving sizes,
    arcus.sky) is, at each wavelength, the sphere of that radius: the same tables to the
    bit as asking for each alone (a determinism test of the bookkeeping); a list of the
    wrong length or with a bad radius is refused naming it."""
    theta = np.linspace(130.0, 150.0, 41)
    radii, wavelengths = [4e-6, 6e-6], [450.0, 600.0]
    both = sweep.phase_tables([{"kind": "sphere", "radius": radii, "method": "mie"}], wavelengths, theta,
                              client="serial", cache_dir=False)
    for j, (r, w) in enumerate(zip(radii, wavelengths)):
        alone = sweep.phase_tables([{"kind": "sphere", "radius": r, "method": "mie"}], [w], theta,
                                   client="serial", cache_dir=False)
        assert np.array_equal(both.phase[0, j], alone.phase[0, 0])
        assert both.cross_section[0, j] == alone.cross_section[0, 0]
    with pytest.raises(arcus.ArgumentError, match=r"particles\[0\].radius: 2 radii for 3 wavelengths"):
        sweep.phase_tables([{"kind": "sphere", "radius": radii, "method": "mie"}], [450.0, 500.0, 600.0], theta,
                           client="serial", cache_dir=False)
    with pytest.raises(arcus.ArgumentError, match=r"particles\[0\].radius: one radius or one per wavelength"):
        sweep.phase_tables([{"kind": "sphere", "radius": [4e-6, -1.0], "method": "mie"}], wavelengths, theta,
                           client="serial", cache_dir=False)
