"""Every code example of the README and the docs runs as written: Python blocks as
scripts, shell lines of the `arcus` command in a temporary folder outside the
repository, the README's C program compiled against an installed copy of the library
(`cmake --install`, then `pkg-config` as its first line says) and run.  C fragments
(blocks without a main) continue that program: they run inside a main that made `ctx`,
from the repository root their relative scene paths point into."""

import os
import re
import shlex
import shutil
import subprocess
import sys

import pytest

from conftest import BINDINGS, REPO

pytestmark = pytest.mark.end_to_end

PAGES = [REPO / "README.md", REPO / "scenes" / "README.md", REPO / "bindings" / "python" / "README.md"] + \
    sorted((REPO / "docs").glob("*.md"))
BUILD = REPO / "build"

# Shell lines that are not the arcus command's: the Quick start scripts and the
# installation (CI runs them as its own stages), and the live preview, which waits for
# a person at a display (tests/python/test_view_rainbow.py drives it under Xvfb).
NOT_RUN = ("bash scripts/", "pip install", "cd ", "arcus view", "arcus gallery", "cmake ", "clinfo")


def blocks(language):
    """(page, index, text) of every ```language block."""
    found = []
    for page in PAGES:
        text = page.read_text()
        for i, m in enumerate(re.finditer(r"^```%s\n(.*?)^```" % language, text, re.S | re.M)):
            found.append((page, i, m.group(1)))
    return found


def ids(found):
    return ["%s#%d" % (page.relative_to(REPO), i) for page, i, _ in found]


def environment(tmp_path):
    return dict(os.environ, PYTHONPATH=str(BINDINGS), MPLBACKEND="Agg", HOME=os.environ.get("HOME", str(tmp_path)))


PYTHON = blocks("python")


@pytest.mark.parametrize("page, index, code", PYTHON, ids=ids(PYTHON))
def test_python_examples_run_from_outside_the_repository(tmp_path, page, index, code):
    script = tmp_path / "example.py"
    script.write_text(code)
    r = subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=environment(tmp_path), capture_output=True,
                       text=True, timeout=900)
    assert r.returncode == 0, r.stderr[-3000:]


def shell_lines(code):
    """The commands of a shell block: continuations joined, comments dropped."""
    joined = code.replace("\\\n", " ")
    lines = []
    for line in joined.splitlines():
        words = shlex.split(line, comments=True)
        if words:
            lines.append(words)
    return lines


SHELL = [b for b in blocks("sh") if any(w[0] == "arcus" for w in shell_lines(b[2]))]


@pytest.mark.parametrize("page, index, code", SHELL, ids=ids(SHELL))
def test_shell_examples_run_in_a_folder_outside_the_repository(tmp_path, page, index, code):
    ran = 0
    for words in shell_lines(code):
        line = " ".join(words)
        if line.startswith(NOT_RUN):
            continue
        assert words[0] == "arcus", "a shell example that is not an arcus command: %s" % line
        r = subprocess.run([sys.executable, "-m", "arcus.cli"] + words[1:], cwd=tmp_path,
                           env=environment(tmp_path), capture_output=True, text=True, timeout=900)
        assert r.returncode == 0, "%s\n%s" % (line, r.stderr[-3000:])
        ran += 1
    assert ran > 0


C_BLOCKS = blocks("c")
PROGRAM = next(code for _, _, code in C_BLOCKS if "int main" in code)


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """libarcus installed from the CMake build into a fresh prefix, as a C user does."""
    if not (BUILD / "cmake_install.cmake").exists():
        pytest.fail("the C examples compile against `cmake --install build`: build the library first")
    prefix = tmp_path_factory.mktemp("prefix")
    subprocess.run(["cmake", "--install", str(BUILD), "--prefix", str(prefix)], check=True, capture_output=True)
    return next(prefix.glob("lib*/pkgconfig")).parent / "pkgconfig"


def compile_and_run(source, folder, pkgconfig, cwd):
    (folder / "example.c").write_text(source)
    env = dict(os.environ, PKG_CONFIG_PATH=str(pkgconfig))
    env.pop("LD_LIBRARY_PATH", None)  # the .pc file's rpath must find the library
    flags = subprocess.run(["pkg-config", "--cflags", "--libs", "arcus"], env=env, check=True, capture_output=True,
                           text=True).stdout.split()
    cc = shutil.which("cc") or "gcc"
    subprocess.run([cc, "-std=c99", "-Wall", "-Werror", str(folder / "example.c"), *flags, "-o",
                    str(folder / "example")], check=True, capture_output=True, env=env)
    return subprocess.run([str(folder / "example")], cwd=cwd, env=env, capture_output=True, text=True, timeout=600)


def test_the_c_program_builds_against_the_installed_library_and_runs(tmp_path, installed):
    r = compile_and_run(PROGRAM, tmp_path, installed, tmp_path)
    assert r.returncode == 0, r.stderr
    assert "the ray ends at (2000.0," in r.stdout  # it reached the end of its 2 km


FRAGMENTS = [b for b in C_BLOCKS if "int main" not in b[2]]


@pytest.mark.parametrize("page, index, code", FRAGMENTS, ids=ids(FRAGMENTS))
def test_c_fragments_run_inside_a_program(tmp_path, installed, page, index, code):
    source = ("#include <arcus/arcus.h>\n#include <stdio.h>\n\nint main(void) {\n"
              "  arcus_context_t* ctx;\n"
              "  if (arcus_context_create(ARCUS_DEVICE_DEFAULT, &ctx) != ARCUS_SUCCESS) return 1;\n"
              "  {\n%s\n  }\n  arcus_context_release(ctx);\n  return 0;\n}\n" % code)
    r = compile_and_run(source, tmp_path, installed, REPO)
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""  # the fragments print the library's message on failure
