"""arcus info: the version, the OpenCL devices, the caches and the kernel features."""

import os

from .. import FEATURES, __version__, devices, library_path
from .._task_cache import default_cache_dir
from . import resources


def add(sub):
    p = sub.add_parser("info", help="version, OpenCL devices, caches and kernel features",
                       description=__doc__)
    p.set_defaults(run=run)


def _size(path):
    total = files = 0
    for root, _, names in os.walk(path):
        for n in names:
            try:
                total += os.lstat(os.path.join(root, n)).st_size
                files += 1
            except OSError:
                pass
    return "%d files, %.1f MB" % (files, total / 1e6)


# Which engine compiles which features: the bit ranges of arcus_core.h and the engines'
# headers (curved light: 0-23, render: 24-31, ocean: 32-39, rainbow: 40-47).
ENGINES = (("curved light", 0, 24), ("render", 24, 32), ("ocean", 32, 40), ("rainbow", 40, 48))


def run(args):
    print("arcus %s" % __version__)
    print("library: %s" % library_path)
    print("bundled scenes: %s/scenes (%d)" % (resources.share_dir(), len(resources.bundled_scenes())))
    print("devices:")
    for d in devices():
        print("  %d: %s (%s) — %s, %s, %d compute units, %.1f GB%s" % (
            d.index, d.name, d.platform, d.version, "GPU" if d.is_gpu else "CPU", d.compute_units,
            d.global_memory / 1e9, ", fp64" if d.fp64 else ", no fp64"))
    tables = default_cache_dir()
    if tables is False:
        print("caches: off (ARCUS_CACHE_DIR=off)")
    else:
        programs = os.path.dirname(tables)
        print("caches:")
        print("  compiled kernels: %s (%s)" % (programs, _size(programs) if os.path.isdir(programs) else "empty"))
        print("  phase tables and sweeps: %s (%s)" % (tables, _size(tables) if os.path.isdir(tables) else "empty"))
    print("kernel features (compiled only where a scene needs them):")
    for engine, low, high in ENGINES:
        names = [n for n, bit in FEATURES.items() if low <= bit.bit_length() - 1 < high]
        print("  %-13s %s" % (engine + ":", " ".join(names)))
    return 0
