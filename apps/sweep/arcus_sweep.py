#!/usr/bin/env python3
"""Sweeps of independent arcus jobs on Dask, described in JSON (arcus.sweep).

    arcus_sweep.py SPEC.json [--scheduler ADDRESS | --workers N] [--cache DIR | --no-cache]
                   [-o OUT.npz] [--quiet]

SPEC.json: {"kind": "phase_tables" | "ocean_grid" | "frames", ...} with the arguments
of that function of arcus.sweep; axes are lists or {"linspace": [first, last, count]}
or {"range": [first, last, step]}; relative file names are read against the spec's
directory.  Examples: scenes/sweeps/*.json.

Runs the tasks on a LocalCluster of N worker processes (default: one per core; 0: a
plain loop in this process) or on the Dask scheduler at ADDRESS (``dask scheduler``,
then ``dask worker ADDRESS`` on each machine), reusing the disk cache (default
$ARCUS_CACHE_DIR, else ~/.cache/arcus/tables), writes OUT.npz (default
out/sweeps/<spec name>.npz; load it with arcus.sweep.PhaseTables.load, OceanGrid.load
or Frames.load) and says how many tasks were computed and how many read from the
cache.  On a terminal Dask's progress bar shows unless --quiet.  A bad spec, or a
scheduler that does not answer, prints one line and exits with status 2; a failed
task exits with status 1 (the tasks that finished are cached).
"""
import argparse
import os
import sys
from pathlib import Path

# The arcus package of this source tree, as tests/python/conftest.py finds it.
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bindings" / "python"))

import arcus  # noqa: E402  (needs the sys.path entry above)
import arcus.sweep as sweep  # noqa: E402

EXIT_FAILED, EXIT_BAD_SPEC = 1, 2


def main(argv=None):
    parser = argparse.ArgumentParser(prog=os.environ.get("ARCUS_PROG", "arcus_sweep.py"), description=__doc__.split("\n\n")[0])
    parser.add_argument("spec", help="the sweep, a JSON file (scenes/sweeps/*.json)")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS", help="a running Dask scheduler, e.g. tcp://host:8786")
    where.add_argument("--workers", type=int, metavar="N", help="local worker processes (default: one per core; "
                       "0: a plain loop in this process)")
    cache = parser.add_mutually_exclusive_group()
    cache.add_argument("--cache", metavar="DIR", help="the task cache (default: %s)" % sweep.default_cache_dir())
    cache.add_argument("--no-cache", action="store_true", help="compute every task, keep nothing")
    parser.add_argument("-o", "--out", metavar="OUT.npz", help="default: out/sweeps/<spec name>.npz")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    args = parser.parse_args(argv)

    name = Path(args.spec).stem
    try:
        try:
            spec = sweep.load_spec(args.spec)  # read and checked by the library
        except arcus.Error as exc:  # a missing or special file too; the message names the file and key
            print("arcus_sweep: %s" % exc.message.splitlines()[0], file=sys.stderr)
            return EXIT_BAD_SPEC
        cache_dir = False if args.no_cache else args.cache
        result = sweep.run_spec(spec, base_dir=os.path.dirname(os.path.abspath(args.spec)),
                                client=args.scheduler, workers=args.workers, cache_dir=cache_dir,
                                progress=not args.quiet and sys.stdout.isatty())
    except (ValueError, ConnectionError) as exc:  # arcus.ArgumentError is a ValueError
        message = exc.message if isinstance(exc, arcus.Error) else str(exc)  # without the status name
        print("arcus_sweep: %s: %s" % (args.spec, message.splitlines()[0]), file=sys.stderr)
        return EXIT_BAD_SPEC
    except Exception as exc:  # a task failed on a worker; the note names it
        print("arcus_sweep: %s: %s" % (args.spec, exc), file=sys.stderr)
        for note in getattr(exc, "__notes__", []):
            print("arcus_sweep: %s" % note, file=sys.stderr)
        return EXIT_FAILED
    out = args.out or os.path.join("out", "sweeps", name + ".npz")
    result.save(out)
    where = "no cache" if args.no_cache else "cache %s" % (args.cache or sweep.default_cache_dir())
    table = result.phase if isinstance(result, sweep.PhaseTables) else result.image
    print("arcus_sweep: wrote %s (%s %s): %d tasks, %d computed, %d read from the cache (%s)"
          % (out, "phase" if table is not getattr(result, "image", None) else "image", table.shape,
             result.computed + result.cached, result.computed, result.cached, where))
    return 0


if __name__ == "__main__":  # the guard also keeps Dask's spawned workers from running it again
    sys.exit(main())
