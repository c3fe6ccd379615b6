"""The main job end to end: `arcus gallery` makes its page, and a real browser (Debian's
headless Chromium) opens it: every picture decodes, nothing is logged as an error, and a
screenshot is kept (build/test-artifacts/gallery.png)."""

import os
import re
import shutil
import subprocess
import sys

import pytest

from conftest import BINDINGS, REPO

pytestmark = pytest.mark.end_to_end

ARTIFACTS = REPO / "build" / "test-artifacts"


def chromium():
    path = shutil.which("chromium") or shutil.which("chromium-browser")
    if path is None:
        pytest.fail("Chromium is missing: scripts/bootstrap.sh installs Debian's chromium")
    return path


def browse(page, *flags):
    # --no-sandbox: CI runs as root, where Chromium's sandbox refuses to start.
    # --virtual-time-budget lets the page's load handler run before the DOM is dumped.
    cmd = [chromium(), "--headless=new", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
           "--enable-logging=stderr", "--v=0", "--virtual-time-budget=10000", *flags, page.as_uri()]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def gallery(tmp_path_factory):
    out = tmp_path_factory.mktemp("gallery")
    env = dict(os.environ, PYTHONPATH=str(BINDINGS))
    r = subprocess.run([sys.executable, "-m", "arcus.cli", "gallery", "--out", str(out), "--quiet"],
                       cwd=out, env=env, capture_output=True, text=True, timeout=1800)
    assert r.returncode == 0, r.stdout + r.stderr + (out / "gallery.log").read_text()[-4000:]
    assert str(out / "index.html") in r.stdout  # it says where the page is
    return out / "index.html"


def test_every_picture_of_the_gallery_decodes_in_a_browser(gallery):
    text = gallery.read_text()
    pictures = text.count("<img ")
    # Every section of the page, one per engine and the benchmarks, has pictures.
    for section in ("Curved light", "Underwater light", "Rainbows", "Rainbow skies", "What accuracy costs"):
        assert section in text
    assert pictures >= 25
    r = browse(gallery, "--dump-dom")
    assert r.returncode == 0, r.stderr
    decoded = re.search(r'data-images="(\d+)/(\d+)"', r.stdout)
    assert decoded is not None, "the page's load check did not run: " + r.stdout[:500]
    assert decoded.group(1) == decoded.group(2) == str(pictures)
    errors = [line for line in r.stderr.splitlines() if "CONSOLE" in line or "Uncaught" in line]
    assert errors == []


def test_a_screenshot_of_the_gallery_is_kept(gallery):
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    shot = ARTIFACTS / "gallery.png"
    if shot.exists():
        shot.unlink()
    r = browse(gallery, "--window-size=1200,6000", "--screenshot=%s" % shot)
    assert r.returncode == 0, r.stderr
    assert shot.stat().st_size > 10000  # a page of pictures, not a blank one
