"""arcus_view previews the rainbow skies arcus.sky.export writes: its screenshot of the
file's sky, taken in a real (Xvfb) window, is the library's PNG of the same sky
(arcus_job_write_rainbow_image) byte for byte, a sky image included, and a file whose β is cut short is
refused with exit status 2 and a message naming it.

arcus_view is looked for next to the libarcus these tests load (the build tree puts both
in the build directory), or at ARCUS_VIEW; the tests are skipped without it or without
xvfb-run (scripts/bootstrap.sh installs xvfb)."""

import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

import arcus
from arcus import sky
from image_files import write_pfm

REPO = Path(__file__).resolve().parents[2]


def find_view():
    if os.environ.get("ARCUS_VIEW"):
        return Path(os.environ["ARCUS_VIEW"])
    return Path(os.path.realpath(arcus.library_path)).parent / "arcus_view"


VIEW = find_view()
XVFB_RUN = shutil.which("xvfb-run")
pytestmark = [
    pytest.mark.skipif(not (VIEW.is_file() and os.access(VIEW, os.X_OK)),
                       reason="no arcus_view at %s (build the arcus_view target, or set ARCUS_VIEW)" % VIEW),
    pytest.mark.skipif(XVFB_RUN is None, reason="xvfb-run not found (scripts/bootstrap.sh installs xvfb)"),
]


def run_view(*args):
    """arcus_view under Xvfb: (its own exit status, stdout, stderr).  xvfb-run may replace
    a non-zero status with its own (5, when removing its temporary directory fails), so
    the status is read from inside."""
    env = dict(os.environ)
    # The X and GL libraries leave blocks LeakSanitizer cannot attribute (test_view.sh).
    env["ASAN_OPTIONS"] = env.get("ASAN_OPTIONS", "") + (":" if env.get("ASAN_OPTIONS") else "") + "detect_leaks=0"
    done = subprocess.run([XVFB_RUN, "-a", "-s", "-screen 0 1280x1024x24", "sh", "-c",
                           '"$@"; echo "arcus_view exit status $?"', "sh", str(VIEW), *map(str, args)],
                          capture_output=True, text=True, env=env, timeout=300)
    lines = done.stdout.rstrip("\n").split("\n")
    assert lines and lines[-1].startswith("arcus_view exit status "), (done.returncode, done.stdout, done.stderr)
    return int(lines[-1].split()[-1]), "\n".join(lines[:-1]), done.stderr


def double_bow(exposure=0.0, raindrops=False, image_sky=False):
    """scenes/rainbow/double_bow.json at 160 × 120 with a small table (8 wavelengths,
    grid 200): seconds on two cores.  raindrops: 2 mm falling drops instead of the
    spheres, whose table depends on the azimuth too (β's φ axis, 30° steps, a coarse
    θ axis).  image_sky: a panorama file as the sky."""
    scene = json.loads((REPO / "scenes" / "rainbow" / "double_bow.json").read_text())
    scene["image"].update(width=160, height=120, exposure=exposure)
    scene["tables"].update(wavelengths={"linspace": [380, 700, 8]}, grid=200, band_samples=1)
    if raindrops:
        scene["rain"]["populations"] = [{"shape": "raindrop", "diameter": 2e-3, "density": 300}]
        scene["tables"].update(grid=100, phi_step_deg=30, theta={"range": [120, 180, 0.5]})
    if image_sky:
        scene["background"]["sky"] = {"image": str(image_sky), "scale": 0.05}
    return scene


def storm_sky_pfm(path):
    """data/rainbow/sky/make_storm_sky.py's panorama as a PFM file."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("make_storm_sky",
                                                  REPO / "data" / "rainbow" / "sky" / "make_storm_sky.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return write_pfm(path, module.storm_sky())


@pytest.fixture(scope="module")
def cache(tmp_path_factory):
    return tmp_path_factory.mktemp("tables")


@pytest.mark.parametrize("options", [{}, {"exposure": 25.0}, {"raindrops": True}, {"image_sky": True}],
                         ids=["auto_exposure", "fixed_exposure", "azimuth_table", "image_sky"])
def test_screenshot_is_the_library_png(ctx, cache, tmp_path, options):
    if options.get("image_sky"):
        options = dict(options, image_sky=storm_sky_pfm(tmp_path / "storm_sky.pfm"))
    scene = double_bow(**options)
    path = tmp_path / "double_bow.rainbow.json"
    table = sky.export(scene, path, cache_dir=cache)
    assert (table.phi.size > 1) == bool(options.get("raindrops"))
    # The library's PNG of the same sky (the members export wrote) and table.
    rendered = sky.render(scene, table=table, png=tmp_path / "library.png", context=ctx)
    # Not a blank image that both would agree on: sky, bows and ground.
    assert rendered.image.std() > 0 and rendered.image.max() > 2 * rendered.image.mean()

    status, out, err = run_view(path, "--frames", 2, "--screenshot", tmp_path / "view.png")
    assert status == 0, err
    assert "frame 2: 160x120" in out and "wrote" in out, out
    library, view = (tmp_path / "library.png").read_bytes(), (tmp_path / "view.png").read_bytes()
    assert view == library, "arcus_view's screenshot differs from arcus_job_write_rainbow_image's PNG"


def test_short_beta_file_is_refused(cache, tmp_path):
    path = tmp_path / "double_bow.rainbow.json"
    sky.export(double_bow(), path, cache_dir=cache)
    beta = tmp_path / json.loads(path.read_text())["table"]["beta_file"]
    size = beta.stat().st_size
    beta.write_bytes(beta.read_bytes()[: size - 8])  # one value short

    status, _, err = run_view(path, "--frames", 1)
    assert status == 2, err
    assert str(beta) in err and str(path) in err, err
    assert "%d bytes" % (size - 8) in err and "too short" in err, err


def test_bad_sky_member_is_named(cache, tmp_path):
    path = tmp_path / "double_bow.rainbow.json"
    sky.export(double_bow(), path, cache_dir=cache)
    doc = json.loads(path.read_text())
    doc["sky"]["sun_irradiance"] = doc["sky"]["sun_irradiance"][:3]
    path.write_text(json.dumps(doc))

    status, _, err = run_view(path, "--frames", 1)
    assert status == 2, err
    assert str(path) in err and "sky.sun_irradiance holds 3 numbers, not 8" in err, err
