"""The arcus command, run as a user would: from a folder outside the repository, on
bundled scenes by name, with the output format following the file name, and exit
status 2 with a message naming the file and key on bad input."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest

import arcus
from arcus import image

from conftest import BINDINGS

pytestmark = pytest.mark.end_to_end


def arcus_command(*args, cwd):
    env = dict(os.environ, PYTHONPATH=str(BINDINGS))
    return subprocess.run([sys.executable, "-m", "arcus.cli", *args], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=600)


def test_version_is_the_librarys(tmp_path):
    r = arcus_command("--version", cwd=tmp_path)
    assert r.returncode == 0
    assert r.stdout.strip() == "arcus %s" % arcus.__version__


def test_a_bundled_scene_renders_by_name_from_anywhere_in_every_format(tmp_path):
    outputs = ["m.png", "m.jpg", "m.hdr", "sub/m.exr"]
    r = arcus_command("render", "inferior_mirage", "--quick", *sum((["-o", o] for o in outputs), []), cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    # Each format read back: the PNG is the engine's own sRGB, the JPEG its lossy copy
    # (a few code values: 0.05 in linear), the HDR the EXR's RGB to RGBE's 8-bit
    # mantissa (2^-7 relative).
    png, jpg = image.read(tmp_path / "m.png"), image.read(tmp_path / "m.jpg")
    exr, hdr = image.read(tmp_path / "sub" / "m.exr"), image.read(tmp_path / "m.hdr")
    assert png.shape == (100, 200, 3)  # --quick: a quarter of 800 × 400 per side
    assert np.mean(np.abs(png - jpg)) < 0.05
    assert np.all(np.abs(hdr - exr) <= exr.max(axis=2, keepdims=True) / 128 + 1e-6)


def test_the_default_output_is_the_scenes_name_here(tmp_path):
    r = arcus_command("render", "rainbow/cloudbow", "--quick", "--width", "32", "--height", "24", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert image.read(tmp_path / "cloudbow.png").shape == (24, 32, 3)


def test_a_skys_profile_peaks_where_descartes_puts_the_primary_bow(tmp_path):
    # The double bow's primary, 500 µm drops through the sun's disc, is brightest a
    # fraction of a degree inside Descartes' angle (137.6° at 700 nm to 139.4° at 400 nm,
    # thesis eq. 4.20): the profile's θ is the angle from the sun, its Y the sky's.
    r = arcus_command("render", "rainbow/double_bow", "--quick", "--width", "96", "--height", "72", "-o", "b.png",
                      "--profile", "p.csv", "--profile", "p.png", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    table = np.loadtxt(tmp_path / "p.csv", delimiter=",", skiprows=1)
    theta, y = table[:, 0], table[:, 1]
    assert np.all(np.diff(theta) > 0) and np.all(table[:, 4] >= 1)
    bows = (theta > 125) & (theta < 141)
    assert 136.5 < theta[bows][np.argmax(y[bows])] < 139.5
    assert image.read(tmp_path / "p.png").shape[2] == 3


def test_a_mirages_profile_is_its_ray_fan(tmp_path):
    """`arcus render SCENE --profile` for a render scene in air writes its rays with and
    without the inversions (arcus.mirage_profile): a CSV of both fans and a plot."""
    r = arcus_command("render", "inferior_mirage", "--quick", "-o", "m.png", "--profile", "rays.csv", "--profile",
                      "rays.png", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    rows = np.genfromtxt(tmp_path / "rays.csv", delimiter=",", names=True)
    assert set(np.unique(rows["inversions"])) == {0.0, 1.0} and (tmp_path / "rays.png").stat().st_size > 1000


@pytest.mark.parametrize("args, words", [
    (["render", "no_such_scene"], ["no_such_scene"]),
    (["render", "inferior_mirage", "-o", "x.gif"], ["x.gif", ".png"]),
    (["render", "inferior_mirage", "--samples", "4"], ["--samples", "render"]),
    (["render", "mirage"], ["curved", "arcus trace"]),
    (["render", "rainbow/cloudbow", "--profile", "p.gif"], ["p.gif", ".csv"]),
    (["render", "ocean/atlantic", "--profile", "p.png"], ["--profile", "rainbow skies and render scenes"]),
    (["render", "cross_room", "--profile", "p.png"], ["--profile", "cross_room.json", "not an atmosphere"]),
    (["render", "{typo}"], ["typo.json", "$.sun.sampels"]),
])
def test_bad_input_exits_2_naming_what_is_wrong(tmp_path, repo, args, words):
    scene = json.loads((repo / "scenes" / "rainbow" / "cloudbow.json").read_text())
    scene["sun"]["sampels"] = 1
    (tmp_path / "typo.json").write_text(json.dumps(scene))
    r = arcus_command(*[a.replace("{typo}", str(tmp_path / "typo.json")) for a in args], cwd=tmp_path)
    assert r.returncode == 2
    for w in words:
        assert w in r.stderr, r.stderr
    assert "Traceback" not in r.stderr
