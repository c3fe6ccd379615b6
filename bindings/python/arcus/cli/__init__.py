"""The ``arcus`` command: one entry point to every engine (docs/cli.md).

    arcus render SCENE [-o OUT ...] [--quick]   an image of any engine's scene
    arcus bssrdf render MESH [--material M] [--light ...]   a translucent object (dipole)
    arcus inverse genetic SCENE.json --target PHOTO.exr   material genes by a genetic search
    arcus trace | view | ocean | rainbow | sweep | bench | info | gallery

Bad input (a scene's error names the file and the key path) prints one line and exits
with status 2; a tool's own failure keeps its exit status.
"""

import argparse
import sys

from .. import __version__
from . import bssrdf, gallery, info, inverse, render, tools

EXIT_BAD_INPUT = 2


def parser():
    p = argparse.ArgumentParser(prog="arcus", description="Light transport in participating media: curved light "
                                "and mirages, underwater light, rainbows and halos, translucency (docs/cli.md).")
    p.add_argument("--version", action="version", version="arcus %s" % __version__)
    sub = p.add_subparsers(dest="command", metavar="COMMAND", required=True)
    render.add(sub)
    bssrdf.add(sub)
    inverse.add(sub)
    tools.add(sub)
    info.add(sub)
    gallery.add(sub)
    return p


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        from .. import Error
    except Exception as exc:  # the library could not be loaded: say why, once
        print("arcus: %s" % exc, file=sys.stderr)
        return EXIT_BAD_INPUT
    try:
        args, extra = parser().parse_known_args(argv)
        if extra and not getattr(args, "passes_arguments", False):
            parser().error("unrecognized arguments: %s" % " ".join(extra))
        return args.run(args, *([extra] if getattr(args, "passes_arguments", False) else []))
    except Error as exc:
        print("arcus %s: %s" % (argv[0] if argv else "", exc.message if hasattr(exc, "message") else exc),
              file=sys.stderr)
        return EXIT_BAD_INPUT
    except (ValueError, OSError) as exc:
        print("arcus %s: %s" % (argv[0] if argv else "", exc), file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print("arcus: interrupted", file=sys.stderr)
        return 130
