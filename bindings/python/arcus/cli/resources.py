"""Where the command finds what it ships with: bundled scenes and data, the C++ tools
and the Python apps, whether arcus was installed with `pip install .` (all of it inside
the package) or runs from a source tree with a CMake build in build/."""

import os
from pathlib import Path

from .. import _lib
from .._errors import ArgumentError

PACKAGE = Path(__file__).resolve().parents[1]


def share_dir():
    """The folder holding scenes/, data/, apps/ and bench/: the package's share/arcus when
    installed, else the source tree's root."""
    installed = PACKAGE / "share" / "arcus"
    if (installed / "scenes").is_dir():
        return installed
    root = _lib._source_root()
    if root is not None:
        return root
    raise ArgumentError("arcus: no bundled scenes: neither %s nor a source tree holds them; reinstall with "
                        "`pip install .` from the arcus source" % installed)


def bundled_scenes():
    """Every bundled scene file: {name relative to scenes/ without .json: path}."""
    scenes = share_dir() / "scenes"
    return {str(p.relative_to(scenes).with_suffix("")): p for p in sorted(scenes.rglob("*.json"))}


def scene(name):
    """The scene file ``name`` names: a path to a file, or a bundled scene by name
    ("inferior_mirage", "rainbow/halo", or "halo" when only one scene has that name)."""
    if Path(name).is_file():
        return Path(name)
    scenes = bundled_scenes()
    if name in scenes:
        return scenes[name]
    matches = [p for n, p in scenes.items() if Path(n).name == name]
    if len(matches) == 1:
        return matches[0]
    if len(matches) > 1:
        raise ArgumentError("%s: several bundled scenes have this name: %s" % (
            name, ", ".join(sorted(str(p.relative_to(share_dir() / "scenes").with_suffix("")) for p in matches))))
    raise ArgumentError("%s: neither a scene file nor a bundled scene (`arcus render --list` lists them)" % name)


def scene_or_word(word):
    """``word`` as a scene file when it names a bundled scene and no file, else as given."""
    if Path(word).is_file():
        return word
    try:
        return str(scene(word))
    except ArgumentError:
        return word


def tool(name):
    """The path of a C++ tool (arcus_view, arcus_trace, the benchmarks): the package's
    bin/ when installed, else the source tree's build/."""
    candidates = [PACKAGE / "bin" / name]
    root = _lib._source_root()
    if root is not None:
        candidates += [root / "build" / name, root / "build" / "bench" / name]
    for c in candidates:
        if c.is_file() and os.access(c, os.X_OK):
            return c
    raise ArgumentError("arcus: %s is not built (looked in %s); install arcus with `pip install .` or build it with "
                        "cmake" % (name, ", ".join(str(c.parent) for c in candidates)))


def script(relative):
    """A Python app shipped with arcus (``apps/ocean/arcus_ocean.py``, ``bench/sky_bench.py``)."""
    path = share_dir() / relative
    if not path.is_file():
        raise ArgumentError("arcus: %s is missing from %s" % (relative, share_dir()))
    return path


def mesh(name):
    """A mesh file: the path given, or one of data/meshes by its name without extension."""
    if Path(name).is_file():
        return Path(name)
    meshes = share_dir() / "data" / "meshes"
    found = sorted(meshes.glob(name + ".*")) if "/" not in name else []
    found = [f for f in found if f.suffix.lower() in (".obj", ".ply", ".off", ".stl")]
    if len(found) == 1:
        return found[0]
    raise ArgumentError("%s: neither a mesh file nor a bundled mesh (%s)" % (
        name, ", ".join(sorted(p.stem for p in meshes.glob("*.obj")) + sorted(p.stem for p in meshes.glob("*.ply")))))
