#!/usr/bin/env python3
"""Renders a rainbow sky (thesis §5.5.2): arcus_rainbow_render.py SCENE.json -o OUT.exr --png OUT.png

The scene (scenes/rainbow/*.json) names the camera, the sun, the box of rain with its
drop populations and the background.  The drops' phase tables come from the sweep cache
(computed where missing: here, or on Dask with --workers / --scheduler), then the sky
is marched on the default OpenCL device.  Prints where it wrote the images, the table
and render times, and the kernel features the render compiled.

Examples:
  arcus_rainbow_render.py scenes/rainbow/double_bow.json -o out/rainbow/double_bow.exr --png out/rainbow/double_bow.png
  arcus_rainbow_render.py scenes/rainbow/twinned.json --png twinned.png --workers 2
  arcus_rainbow_render.py scenes/rainbow/cloudbow.json --png cloudbow.png --scheduler tcp://10.0.0.5:8786
  arcus_rainbow_render.py scenes/rainbow/halo.json --export-view out/halo.sky.json && build/arcus_view out/halo.sky.json
"""

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bindings" / "python"))

import arcus  # noqa: E402  (needs the sys.path entry above)
from arcus import sky  # noqa: E402
from arcus.progress import Progress  # noqa: E402

EXIT_ERROR = 2


def parser():
    p = argparse.ArgumentParser(prog="arcus_rainbow_render.py", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    p.add_argument("scene", help="a rainbow scene (JSON)")
    p.add_argument("-o", "--exr", help="write linear R, G, B, X, Y, Z and the scattering angle to this EXR")
    p.add_argument("--png", help="write an sRGB PNG")
    p.add_argument("--width", type=int, help="override the scene's image width")
    p.add_argument("--height", type=int, help="override the scene's image height")
    p.add_argument("--sun-samples", type=int, help="points averaged over the sun's disc")
    p.add_argument("--march-steps", type=int, help="steps across the rain")
    p.add_argument("--cache", help="the phase-table cache (default: $ARCUS_CACHE_DIR or ~/.cache/arcus/tables)")
    p.add_argument("--workers", type=int, help="compute missing tables on a local Dask cluster of N workers")
    p.add_argument("--scheduler", help="compute missing tables on this Dask scheduler (tcp://host:8786)")
    p.add_argument("--export-view", metavar="PATH",
                   help="also write the scene with its table for the live preview (build/arcus_view PATH)")
    p.add_argument("--quiet", action="store_true", help="no progress bars")
    return p


def main(argv=None):
    args = parser().parse_args(sys.argv[1:] if argv is None else argv)
    if args.exr is None and args.png is None and args.export_view is None:
        print("arcus_rainbow_render: nothing to write: give -o OUT.exr, --png OUT.png or --export-view PATH",
              file=sys.stderr)
        return EXIT_ERROR
    for path in (args.exr, args.png, args.export_view):
        if path:
            Path(path).parent.mkdir(parents=True, exist_ok=True)
    client = args.scheduler if args.scheduler else (None if args.workers else "serial")
    bar = Progress("rendering " + Path(args.scene).stem, quiet=args.quiet)
    try:
        result = sky.render(args.scene, exr=args.exr, png=args.png, width=args.width, height=args.height,
                            sun_samples=args.sun_samples, march_steps=args.march_steps, cache_dir=args.cache,
                            client=client, workers=args.workers, progress=bar if not args.quiet else None)
        if args.export_view:
            sky.export(args.scene, args.export_view, table=result.table, width=args.width, height=args.height,
                       sun_samples=args.sun_samples, march_steps=args.march_steps)
    except arcus.Error as exc:
        bar.close()
        print("arcus_rainbow_render: %s" % exc.message, file=sys.stderr)
        return EXIT_ERROR
    except (ValueError, OSError) as exc:
        bar.close()
        print("arcus_rainbow_render: %s" % exc, file=sys.stderr)
        return EXIT_ERROR
    bar.close()
    t = result.table
    print("%s: %d × %d, %d wavelengths, %d tables (%d computed, %d from the cache) in %.1f s, render %.2f s, "
          "features: %s" % (args.scene, result.image.shape[1], result.image.shape[0], t.wavelengths.size,
                            t.computed + t.cached, t.computed, t.cached, result.seconds["table"],
                            result.seconds["render"], " ".join(sorted(result.features)) or "none"))
    for path in (args.exr, args.png, args.export_view):
        if path:
            print("wrote %s" % Path(path).resolve())
    return 0


if __name__ == "__main__":
    sys.exit(main())
