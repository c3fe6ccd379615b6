"""apps/ocean/arcus_ocean.py: trace and profile on small scenes write their files, the
energy in tallies.json balances, and a bad scene exits with status 2 and the library's
message naming the key."""

import csv
import json
import subprocess
import sys
from pathlib import Path

import pytest

TOOL = Path(__file__).resolve().parents[2] / "apps" / "ocean" / "arcus_ocean.py"


def small_scene(**extra):
    """A cheap ocean scene: a lamp in Baltic water, 20 nm bands, few photons."""
    scene = {"name": "small", "water": {"preset": "baltic"}, "grid": {"first_nm": 400, "last_nm": 700, "step_nm": 20},
             "lights": [{"type": "point", "position": [0, 0, -5], "spectrum": 1.0}],
             "photons": {"count": 4000, "max_interactions": 8, "seed": 3}}
    scene.update(extra)
    return scene


def run_tool(tmp_path, scene, *args):
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    return subprocess.run([sys.executable, str(TOOL), *args[:1], str(path), *args[1:], "--quiet"],
                          capture_output=True, text=True, timeout=600)


def test_trace_writes_balanced_tallies_and_figures(tmp_path):
    out = tmp_path / "out"
    r = run_tool(tmp_path, small_scene(), "trace", "--out", str(out))
    assert r.returncode == 0, r.stderr
    for name in ("tallies.json", "fig5_9.png", "fig5_12.png"):
        assert (out / name).stat().st_size > 0
    doc = json.loads((out / "tallies.json").read_text())
    t = doc["tallies"]
    assert t["photons"] == 4000 and t["max_interactions"] == 8
    booked = t["absorbed"] + t["escaped"] + t["past_limit"] + t["bottom"]
    assert booked == pytest.approx(t["emitted"], rel=1e-9)
    assert len(doc["by_interaction"]["absorbed"]) == 9
    assert set(doc["events"]) >= {"absorb_water", "raman", "fluoresce_cdom", "scatter_phyto"}
    assert set(doc["per_constituent"]) == {"water", "detritus", "phytoplankton", "cdom"}


def test_photons_override(tmp_path):
    out = tmp_path / "out"
    r = run_tool(tmp_path, small_scene(), "trace", "--out", str(out), "--photons", "1000")
    assert r.returncode == 0, r.stderr
    assert json.loads((out / "tallies.json").read_text())["tallies"]["photons"] == 1000


def test_profile_writes_csv_and_plot(tmp_path):
    scene = small_scene(lights=[{"type": "sun", "zenith_deg": 30, "spectrum": 1.0}, {"type": "sky", "spectrum": 0.2}],
                        medium={"surface": True}, profile={"depths": [0, 1, 2], "layer": 0.1})
    out = tmp_path / "out"
    r = run_tool(tmp_path, scene, "profile", "--out", str(out))
    assert r.returncode == 0, r.stderr
    assert (out / "profile.png").stat().st_size > 0
    with open(out / "profile.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert list(rows[0]) == ["depth_m", "wavelength_nm", "Ed", "Eu", "E0", "Ed_elastic_do", "Eu_elastic_do",
                             "E0_elastic_do"]  # a sunlit column: the discrete-ordinates reference beside
    assert len(rows) == 3 * 16  # depths × wavelengths (400–700 nm at 20)
    surface = [float(row["Ed"]) for row in rows if float(row["depth_m"]) == 0]
    assert min(surface) > 0


def test_bad_scene_exits_2_naming_the_key(tmp_path):
    scene = small_scene()
    scene["water"]["chlorophyl"] = 1.0
    r = run_tool(tmp_path, scene, "trace", "--out", str(tmp_path / "out"))
    assert r.returncode == 2
    assert "$.water.chlorophyl" in r.stderr and "unknown key" in r.stderr
    assert not (tmp_path / "out").exists()


def test_profile_without_depths_exits_2(tmp_path):
    r = run_tool(tmp_path, small_scene(), "profile", "--out", str(tmp_path / "out"))
    assert r.returncode == 2
    assert "$.profile" in r.stderr
