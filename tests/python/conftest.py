"""pytest setup for the Python bindings: import `arcus` from bindings/python.

The package finds libarcus itself (ARCUS_LIBRARY, else a build*/ directory of this
source tree, else an installed one); set ARCUS_LIBRARY to test a particular build.
"""

import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
BINDINGS = REPO / "bindings" / "python"
sys.path.insert(0, str(BINDINGS))

import arcus  # noqa: E402  (needs the sys.path entry above)


# The engines a test module needs, by its name; a library built without one of them
# (ARCUS_WITH_<ENGINE>=OFF) skips the module.  Modules named for no engine need them all.
_MODULE_ENGINES = (
    (("test_ocean",), {"ocean"}),
    (("test_rainbow", "test_sky", "test_halo", "test_sweep", "test_view_rainbow"), {"rainbow"}),
    (("test_render",), {"curved", "render"}),
    (("test_translucency",), {"translucency"}),
    (("test_advance", "test_fields", "test_paths", "test_progress", "test_determinism", "test_wavelengths",
      "test_devices"), {"curved"}),
)


def pytest_collection_modifyitems(config, items):
    for item in items:
        module = item.module.__name__.rpartition(".")[2]
        needed = next((engines for prefixes, engines in _MODULE_ENGINES if module.startswith(prefixes)),
                      {"curved", "render", "ocean", "rainbow", "translucency"})
        missing = needed - arcus.ENGINES
        if missing:
            item.add_marker(pytest.mark.skip(reason="libarcus built without " + ", ".join(sorted(missing))))


def pytest_configure(config):
    config.addinivalue_line("markers", "end_to_end: runs the arcus command or the documentation as a user does "
                            "(subprocesses; the sanitizer run skips them, they test no library code of their own)")
    config.addinivalue_line("markers", "external_reference: runs a reference outside the library (Mitsuba 3, the "
                            "tests' NumPy tracer) and little library code (the sanitizer run skips them)")
    config.addinivalue_line("markers", "heavy: a physics check of seconds whose library calls the module's smaller "
                            "tests make too (the sanitizer run skips it: kernels are not instrumented, CI's time is)")
    config.addinivalue_line("markers", "full_size: reproduces a thesis table at its own size (minutes instrumented; "
                            "the sanitizer run skips them, their library calls run instrumented in smaller tests)")


@pytest.fixture(scope="session")
def ctx():
    """One context for the whole session, so each kernel variant is compiled once."""
    with arcus.Context() as context:
        yield context


@pytest.fixture(scope="session")
def repo():
    """The repository root."""
    return REPO
