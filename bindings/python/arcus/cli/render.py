"""arcus render SCENE [-o OUT ...]: renders a scene of any engine — a render scene
through curved light, an ocean scene, a rainbow sky — to the formats the output names
ask for (.png, .jpg, .exr, .hdr)."""

import argparse
import math
import shutil
import tempfile
import time
from pathlib import Path

from .. import _scene_file, image, mirage_profile, ocean, sky, sky_profile
from .._errors import ArgumentError
from ..context import Context
from ..progress import Progress
from . import resources

FORMATS = (".png", ".jpg", ".jpeg", ".exr", ".hdr")
# --quick: a preview in seconds.  The image shrinks by this factor per side (never below
# 64 pixels), rainbow tables use 9 wavelengths and coarser casts, ocean scenes trace a
# tenth of their photons.
QUICK_SCALE = 4


def add(sub):
    p = sub.add_parser("render", help="render a scene (curved-light render scene, ocean, rainbow sky)",
                       description=__doc__, epilog="examples:\n  arcus render inferior_mirage -o mirage.png\n"
                       "  arcus render rainbow/double_bow --quick -o bow.png -o bow.exr\n"
                       "  arcus render my_scene.json --width 400 --height 300",
                       formatter_class=_raw())
    p.add_argument("scene", nargs="?", help="a scene file, or a bundled scene's name (see --list)")
    p.add_argument("-o", "--output", action="append", metavar="OUT",
                   help="an image to write; the extension picks the format (%s); may be given several times "
                        "(default: SCENE.png here)" % ", ".join(FORMATS))
    p.add_argument("--quick", action="store_true", help="a preview in seconds: smaller image, fewer photons, "
                   "wavelengths and orientations")
    p.add_argument("--width", type=int, help="image width in pixels (default: the scene's)")
    p.add_argument("--height", type=int, help="image height in pixels (default: the scene's)")
    p.add_argument("--samples", type=int, help="rainbow skies: points on the sun's disc; ocean scenes: photons per "
                   "radiance estimate")
    p.add_argument("--thesis", action="store_const", const=True, help="ocean scenes: the thesis' settings (400 000 "
                   "photons of one wavelength, k = 250, the estimate at every pixel) before --photons, --samples")
    p.add_argument("--photons", type=int, help="ocean scenes: photons traced (default: the scene's; --quick: a "
                   "tenth)")
    p.add_argument("--seed", type=int, help="ocean scenes: the photons' seed; rainbow skies: the ice crystals' "
                   "orientations")
    p.add_argument("--wavelengths", type=int, help="rainbow skies: wavelengths of the phase tables (default: the "
                   "scene's; --quick: 9)")
    p.add_argument("--orientations", type=int, help="rainbow skies: orientations averaged per ice crystal (default: "
                   "the scene's; --quick: at most 100)")
    p.add_argument("--workers", type=int, help="rainbow skies: compute missing phase tables on a local Dask "
                   "cluster of N worker processes")
    p.add_argument("--scheduler", help="rainbow skies: compute missing phase tables on this Dask scheduler "
                   "(tcp://host:8786)")
    p.add_argument("--export-view", metavar="PATH", help="rainbow skies: also write the sky with its table for "
                   "the live preview (arcus view PATH)")
    p.add_argument("--profile", action="append", metavar="PATH", help="rainbow skies: also write the sky's "
                   "luminance and chromaticity against the angle from the sun, with where closed forms put its bows "
                   "and halos; render scenes in air: the rays of the image's centre column, height against "
                   "distance, beside the same rays without the inversions (.png, .svg, .pdf: a plot; .csv: the "
                   "numbers); may be given several times")
    p.add_argument("--device", help="an OpenCL device: an index or part of its name (default: ARCUS_DEVICE, else "
                   "a GPU, else the CPU)")
    p.add_argument("--list", action="store_true", help="list the bundled scenes and exit")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=run)


def _raw():
    return argparse.RawDescriptionHelpFormatter


def outputs_of(args, name):
    outputs = [Path(o) for o in (args.output or [name + ".png"])]
    for o in outputs:
        if o.suffix.lower() not in FORMATS:
            raise ArgumentError("-o %s: unknown image format %r (expected %s)" % (o, o.suffix, ", ".join(FORMATS)))
    for o in outputs:
        o.parent.mkdir(parents=True, exist_ok=True)
    return outputs


def run(args):
    if args.list:
        for name, path in resources.bundled_scenes().items():
            print(name)
        return 0
    if not args.scene:
        raise ArgumentError("render: give a scene file or a bundled scene's name (arcus render --list)")
    for flag in ("width", "height", "samples", "wavelengths", "orientations"):
        value = getattr(args, flag)
        if value is not None and not 1 <= value <= 65536:
            raise ArgumentError("--%s: expected 1..65536, got %d" % (flag, value))
    if args.photons is not None and not 1 <= args.photons <= 10 ** 9:
        raise ArgumentError("--photons: expected 1..10^9, got %d" % args.photons)
    path = resources.scene(args.scene)
    engine, doc = _scene_file.read(path, ("render", "ocean", "rainbow", "curved", "sweep"))
    if engine in ("curved", "sweep"):
        raise ArgumentError("%s is a %s scene, which has no image: use `arcus %s %s`"
                            % (path, engine, "trace" if engine == "curved" else "sweep", args.scene))
    name = doc.get("name") or path.stem
    outputs = outputs_of(args, name)
    for profile in args.profile or []:
        check_profile(Path(profile))
    started = time.monotonic()
    with Context(_device(args.device)) as ctx, tempfile.TemporaryDirectory(prefix="arcus-render-") as tmp:
        exr, png = Path(tmp) / "image.exr", Path(tmp) / "image.png"
        with Progress("rendering " + name, quiet=args.quiet) as bar:
            summary = RENDERERS[engine](ctx, path, doc, args, str(exr), str(png), bar if bar.shown else None)
        for out in outputs:
            write_output(out, exr, png)
    print("%s (%s scene): %s in %.1f s; wrote %s" % (name, engine, summary, time.monotonic() - started,
                                                     ", ".join(str(o.resolve()) for o in outputs)))
    return 0


def _device(device):
    if device is None:
        return None
    return int(device) if device.isdigit() else device


def write_output(out, exr, png):
    """Copies the engine's own EXR (every channel) or PNG (its exposure and tone curve),
    or converts them: JPEG from the PNG's colours, Radiance HDR from the EXR's RGB."""
    suffix = out.suffix.lower()
    if suffix == ".exr":
        shutil.copyfile(exr, out)
    elif suffix == ".png":
        shutil.copyfile(png, out)
    elif suffix in (".jpg", ".jpeg"):
        image.write(out, image.read(png))
    else:
        image.write(out, image.read(exr))


def _scaled(size, quick):
    return max(64, size // QUICK_SCALE) if quick else size


def _refuse(args, flag, engine, why):
    if getattr(args, flag) is not None:
        raise ArgumentError("--%s does not apply to %s scenes: %s" % (flag.replace("_", "-"), engine, why))


RAINBOW_ONLY = ("wavelengths", "orientations", "workers", "scheduler", "export_view")



def render_curved(ctx, path, doc, args, exr, png, bar):
    for flag in RAINBOW_ONLY:
        _refuse(args, flag, "render", "it applies to rainbow skies")
    _refuse(args, "samples", "render", "they trace one ray per pixel")
    _refuse(args, "seed", "render", "they have no random numbers but their photons' fixed sequence")
    _refuse(args, "photons", "render", "a render scene's photon map is set in its file (\"photons\")")
    _refuse(args, "thesis", "render", "it sets an ocean scene's photons")
    if args.profile and doc.get("field", {}).get("type") != "atmosphere":
        raise ArgumentError("--profile draws a render scene's rays through its air: %s's field is %r, not an "
                            "atmosphere" % (path, doc.get("field", {}).get("type")))
    camera = doc["camera"]
    width = args.width or _scaled(camera["width"], args.quick)
    height = args.height or _scaled(camera["height"], args.quick)
    result = ctx.render(path, exr=exr, png=png, width=width, height=height, progress=bar)
    for profile in args.profile or []:
        mirage_profile.write_ray_fan(Path(profile), doc, context=ctx)
    return "%d × %d, %d rays traced" % (width, height, result.stats.get("rays_traced", 0))


def render_ocean(ctx, path, doc, args, exr, png, bar):
    for flag in RAINBOW_ONLY + ("profile",):
        _refuse(args, flag, "ocean", "it applies to rainbow skies and render scenes")
    camera = doc["view"]["camera"]
    camera["width"] = args.width or _scaled(camera["width"], args.quick)
    camera["height"] = args.height or _scaled(camera["height"], args.quick)
    if args.thesis:
        ocean.use_thesis_settings(doc)
    photons = doc.setdefault("photons", {})
    if args.quick:
        photons["count"] = max(10000, photons.get("count", 400000) // 10)
    if args.photons is not None:
        photons["count"] = args.photons
    if args.seed is not None:
        photons["seed"] = args.seed
    if args.samples is not None:
        doc["view"].setdefault("march", {})["k"] = args.samples
    ocean.render(doc, exr=exr, png=png, progress=bar, context=ctx)
    return "%d × %d, %d photons" % (camera["width"], camera["height"], photons.get("count", 400000))


def quick_rainbow(doc):
    """A rainbow scene's tables at preview settings: 9 wavelengths, casts of at most 300
    rays a side, at most 2000 crystal orientations (traced as beams: about 3 s for a
    halo) and 24 size bins (with the fog bow's 2 band samples at 33 wavelengths these
    leave its luminance 1.2% RMS off a fine integration: bench/fogbow_bench.py)."""
    tables = doc.setdefault("tables", {})
    tables["wavelengths"] = {"linspace": [380, 700, 9]}
    tables["grid"] = min(tables.get("grid", 1000), 300)
    for p in doc["rain"]["populations"]:
        if "orientations" in p:
            p["orientations"] = min(p["orientations"], 2000)
        if "bins" in p:
            p["bins"] = min(p["bins"], 24)


def render_rainbow(ctx, path, doc, args, exr, png, bar):
    _refuse(args, "photons", "rainbow", "a sky is marched, not photon-mapped")
    _refuse(args, "thesis", "rainbow", "it sets an ocean scene's photons")
    img = doc.get("image", {})
    width = args.width or _scaled(img.get("width", 800), args.quick)
    height = args.height or _scaled(img.get("height", 600), args.quick)
    if args.quick:
        quick_rainbow(doc)
    if args.wavelengths is not None:
        doc.setdefault("tables", {})["wavelengths"] = {"linspace": [380, 700, args.wavelengths]}
    if args.orientations is not None:
        for p in doc["rain"]["populations"]:
            if "orientations" in p:
                p["orientations"] = args.orientations
    if args.seed is not None:
        for p in doc["rain"]["populations"]:
            if p.get("shape") == "crystal":
                p["seed"] = args.seed
    samples = args.samples if args.samples is not None else (4 if args.quick else None)
    march_steps = 16 if args.quick else None
    base_dir = str(Path(path).resolve().parent)
    client = args.scheduler if args.scheduler else (None if args.workers else "serial")
    result = sky.render(doc, exr=exr, png=png, width=width, height=height, sun_samples=samples,
                        march_steps=march_steps, base_dir=base_dir, client=client, workers=args.workers,
                        progress=bar, context=ctx)
    for profile in args.profile or []:
        write_profile(Path(profile), result, doc)
    if args.export_view:
        Path(args.export_view).parent.mkdir(parents=True, exist_ok=True)
        sky.export(doc, args.export_view, table=result.table, width=width, height=height, sun_samples=samples,
                   march_steps=march_steps, base_dir=base_dir)
    t = result.table
    return "%d × %d, %d wavelengths, %d phase tables (%d computed, %d cached)" % (
        width, height, t.wavelengths.size, t.computed + t.cached, t.computed, t.cached)


PROFILE_FORMATS = (".png", ".svg", ".pdf", ".csv")


def check_profile(path):
    if path.suffix.lower() not in PROFILE_FORMATS:
        raise ArgumentError("--profile %s: unknown format %r (expected %s)" % (path, path.suffix,
                                                                            ", ".join(PROFILE_FORMATS)))


def write_profile(path, result, doc):
    """The rendered sky's radial profile (arcus.sky_profile.radial_profile, 0.1° bins): a CSV of
    θ, Y, x, y, pixels, or a plot of Y (relative to its largest) and x, y against θ with
    the closed forms' angles (arcus.sky_profile.reference_angles) shaded."""
    profile = sky_profile.radial_profile(result, 0.1)
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.suffix.lower() == ".csv":
        columns = ("theta", "Y", "x", "y", "pixels")
        with open(path, "w") as f:
            f.write("theta_deg,Y,x,y,pixels\n")
            for row in zip(*(profile[c] for c in columns)):
                f.write("%.2f,%.6g,%.6f,%.6f,%d\n" % row)
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(5.2, 3.9), height_ratios=(2, 1))
    theta = profile["theta"]
    # Relative to the sky's brightest beyond 1° from the sun: the sun's disc and its
    # aureole, when in the frame, would flatten everything else.
    away = theta >= 1.0
    top.plot(theta, profile["Y"] / (profile["Y"][away] if away.any() else profile["Y"]).max(), color="k", lw=1)
    bottom.plot(theta, profile["x"], color="tab:red", lw=1, label="x")
    bottom.plot(theta, profile["y"], color="tab:green", lw=1, label="y")
    last = -math.inf
    for low, high, label in sorted(sky_profile.reference_angles(doc)):
        if high < theta.min() or low > theta.max():
            continue
        for ax in (top, bottom):
            ax.axvspan(low, high, color="tab:blue", alpha=0.15, lw=0)
        # Labels of neighbouring spans (the two bows, 9° apart) one above the other.
        height = 1.12 if low - last < 0.15 * (theta.max() - theta.min()) else 1.02
        last = low
        top.annotate(label, (0.5 * (low + high), height), ha="center", va="bottom", fontsize=7, color="tab:blue",
                     annotation_clip=False)
    top.set_ylabel("luminance (relative)")
    top.set_ylim(0, 1.1)
    bottom.set_ylabel("chromaticity")
    bottom.set_xlabel("angle from the sun θ [deg]  (shaded: closed forms, 400–700 nm)")
    bottom.legend(fontsize=7, loc="best")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


RENDERERS = {"render": render_curved, "ocean": render_ocean, "rainbow": render_rainbow}
