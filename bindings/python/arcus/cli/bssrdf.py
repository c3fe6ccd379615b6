"""arcus bssrdf render MESH: a translucent object through the dipole (thesis eq. 3.6–3.8,
docs/translucency.md), lit by directional lights, framed automatically unless a camera
is given; the output's extension picks the format (.png, .jpg, .exr, .hdr).

arcus bssrdf estimate PHOTO --mesh MESH --light ...: the BSSRDF of the object in an HDR
photograph (thesis §3.3.1): the piecewise-constant profile and the dipole fitted to it,
with --compare writing photo | re-render | difference and the profile's plot.

arcus bssrdf estimate PHOTO --auto: the same from the photo alone (thesis §3.4): the
lights and the shape found in it (printed; with --compare also depth.exr, normals.png
and relief.obj beside the re-render), §3.4's Hermite profile first."""

import argparse
import sys
import time
import warnings
from pathlib import Path

import numpy as np

from .. import translucency
from .._errors import ArgumentError
from ..context import Context
from ..progress import Progress
from . import resources
from .render import FORMATS, _device, _raw

# --quick: a preview in seconds: a quarter of the pixels a side (at least 64) and
# samples twice as far apart.
QUICK_SCALE = 4


def add(sub):
    p = sub.add_parser("bssrdf", help="translucent objects: render through the dipole BSSRDF",
                       description=__doc__, formatter_class=_raw())
    verbs = p.add_subparsers(dest="verb", metavar="VERB", required=True)
    r = verbs.add_parser("render", help="render a mesh of a translucent material", description=__doc__,
                         formatter_class=_raw(),
                         epilog="examples:\n  arcus bssrdf render torus --material skin1 --mm-per-unit 20 -o torus.png\n"
                                "  arcus bssrdf render my.ply --sigma-a 0.01 0.02 0.05 --sigma-s-prime 1 1.2 1.5 "
                                "--light 0 1 1 --light -1 0 0.3 0.3 0.3 0.3 -o my.exr")
    r.add_argument("mesh", help="a mesh file (.obj .ply .off .stl) or a bundled mesh's name (icosphere, torus, tower)")
    r.add_argument("--material", help="one of Jensen et al. 2001's: %s (default marble)" %
                   ", ".join(translucency.materials()))
    r.add_argument("--sigma-a", type=float, nargs=3, metavar=("R", "G", "B"), help="absorption, mm^-1")
    r.add_argument("--sigma-s-prime", type=float, nargs=3, metavar=("R", "G", "B"), help="reduced scattering, mm^-1")
    r.add_argument("--eta", type=float, help="relative refractive index (default 1.3, or the material's)")
    r.add_argument("--blend", nargs=2, action="append", metavar=("MATERIAL", "WEIGHT"),
                   help="§5.2's linear blend: Σ weight × the material's profile (repeat; one η among them)")
    r.add_argument("--light", type=float, nargs="+", action="append", metavar="X",
                   help="a directional light: DX DY DZ toward it, then an irradiance (one value or R G B; default "
                        "1); may be given several times (default: one from (1, 1, 1))")
    view_arguments(r)
    r.add_argument("--width", type=int, default=256)
    r.add_argument("--height", type=int, default=256)
    r.add_argument("--exit", choices=("thesis", "normalized"), default="thesis",
                   help="eq. 3.6's exit term as written, or divided by 1 − 2·FM1 (energy-conserving)")
    r.add_argument("--gather", choices=("hierarchical", "brute_force"), default="hierarchical")
    r.add_argument("--highlight", type=float, default=10.0, help="the Phong highlight's angle b, degrees (0: none)")
    r.add_argument("--spacing", type=float, default=0.0, help="irradiance samples' spacing, mm (0: 1/σ′_t)")
    r.add_argument("--quick", action="store_true", help="a preview in seconds: fewer pixels, coarser samples")
    r.add_argument("-o", "--output", action="append", metavar="OUT",
                   help="an image to write (%s); may be given several times (default: MESH.png here)"
                        % ", ".join(FORMATS))
    r.add_argument("--device", help="an OpenCL device: an index or part of its name")
    r.add_argument("--quiet", action="store_true", help="no progress bar")
    r.set_defaults(run=run_render)
    add_estimate(verbs)


def view_arguments(p):
    """The flags of a view, shared by render and estimate."""
    p.add_argument("--mm-per-unit", type=float, default=10.0, help="how long a mesh unit is in mm (default 10)")
    p.add_argument("--position", type=float, nargs=3, metavar=("X", "Y", "Z"),
                   help="the camera's position (default: on +z, far enough to see the whole mesh)")
    p.add_argument("--look-at", type=float, nargs=3, metavar=("X", "Y", "Z"), help="default: the mesh's centre")
    p.add_argument("--up", type=float, nargs=3, metavar=("X", "Y", "Z"), help="default: +y")
    p.add_argument("--vfov", type=float, default=30.0, help="vertical field of view, degrees (default 30)")
    p.add_argument("--ortho", action="store_true", help="an orthographic view framing the mesh, as the thesis' "
                   "photographs")
    p.add_argument("--ortho-height", type=float, help="an orthographic view this tall (mesh units)")


def add_estimate(verbs):
    e = verbs.add_parser("estimate", help="estimate the BSSRDF of the object in an HDR photograph",
                         description=__doc__, formatter_class=_raw(),
                         epilog="example:\n  arcus bssrdf estimate photo.exr --mesh sphere.ply --light 0.3 0.5 1 "
                                "--ortho-height 2.2 --mm-per-unit 20 --compare out/")
    e.add_argument("photo", help="an HDR photograph (.exr, .hdr): linear radiance")
    e.add_argument("--mesh", help="the object's mesh file, or a bundled mesh's name (not with --auto)")
    e.add_argument("--auto", action="store_true",
                   help="no mesh and no lights: find both in the photo (thesis §3.4, docs/translucency-photo.md)")
    e.add_argument("--mm-per-pixel", type=float, default=1.0,
                   help="--auto: the photo's scale at the object, mm (default 1; moves l_d, not R_total)")
    e.add_argument("--irradiance", type=float, nargs="+", default=[1.0], metavar="E",
                   help="--auto: the lights' summed irradiance, one number or R G B, in the photo's units "
                        "(default 1: a photo cannot give it)")
    e.add_argument("--light", type=float, nargs="+", action="append", metavar="X",
                   help="a directional light as for render (default: one from (1, 1, 1))")
    view_arguments(e)
    e.add_argument("--matte", help="an image, non-zero on the object (default: the mesh's projection)")
    e.add_argument("--eta", type=float, default=1.3, help="the medium's index (default 1.3, as the thesis)")
    e.add_argument("--exit", choices=("thesis", "normalized"), default="thesis")
    e.add_argument("--basis", type=int, default=24, help="how many basis functions (default 24)")
    e.add_argument("--family", choices=sorted(translucency.BASIS_FAMILIES), default="piecewise_constant",
                   help="Table 3.2's family of basis functions (default piecewise_constant, as the thesis)")
    e.add_argument("--tikhonov", type=float, default=0.0,
                   help="λ: add λ × the mean diagonal of AᵀA to it (default 0: off, as the thesis)")
    e.add_argument("--nonnegative", action="store_true", help="keep the basis weights >= 0 (off in the thesis)")
    e.add_argument("--fit", choices=("dipole", "hermite"),
                   help="the model --compare re-renders: the fitted dipole (the default) or §3.4's monotone cubic "
                        "Hermite profile (the default with --auto)")
    e.add_argument("--fit-to", choices=("image", "profile"), default="image",
                   help="fit the dipole to the pixels it predicts (default) or to the profile's bins (the thesis)")
    e.add_argument("--compare", metavar="DIR", help="write DIR/compare.png (photo | re-render | difference) and "
                   "DIR/profile.png")
    e.add_argument("--device", help="an OpenCL device: an index or part of its name")
    e.add_argument("--quiet", action="store_true", help="no progress bar")
    e.set_defaults(run=run_estimate)


def bundled_mesh(name):
    """A mesh file: the path given, or one of data/meshes by its name without extension."""
    return resources.mesh(name)


def profile_of(args):
    """The render's profile, a dipole (dipole_of) or §5.2's linear blend of materials,
    and the dipoles it is made of."""
    if not args.blend:
        d = dipole_of(args)
        return d, [d]
    if args.material or args.sigma_a or args.sigma_s_prime:
        raise ArgumentError("--blend or --material/--sigma-a/--sigma-s-prime, not both")
    parts, weights = [], []
    for name, weight in args.blend:
        d = translucency.Dipole.from_material(name)
        parts.append(d if args.eta is None else translucency.Dipole(d.sigma_a, d.sigma_s_prime, args.eta))
        try:
            weights.append(float(weight))
        except ValueError:
            raise ArgumentError("--blend %s %s: the weight is not a number" % (name, weight)) from None
    return translucency.Profile.blend(parts, weights), parts


def dipole_of(args):
    if args.material and (args.sigma_a or args.sigma_s_prime):
        raise ArgumentError("--material or --sigma-a/--sigma-s-prime, not both")
    if bool(args.sigma_a) != bool(args.sigma_s_prime):
        raise ArgumentError("--sigma-a and --sigma-s-prime go together")
    if args.sigma_a:
        return translucency.Dipole(args.sigma_a, args.sigma_s_prime, 1.3 if args.eta is None else args.eta)
    d = translucency.Dipole.from_material(args.material or "marble")
    return d if args.eta is None else translucency.Dipole(d.sigma_a, d.sigma_s_prime, args.eta)


def lights_of(args):
    if not args.light:
        return [((1.0, 1.0, 1.0), 1.0)]
    lights = []
    for i, values in enumerate(args.light):
        if len(values) not in (3, 4, 6):
            raise ArgumentError("--light #%d: give DX DY DZ, then nothing, one irradiance or R G B (got %d numbers)"
                                % (i + 1, len(values)))
        lights.append((values[:3], values[3:] if len(values) == 6 else values[3] if len(values) == 4 else 1.0))
    return lights


def camera_of(args, vertices):
    """The camera: what was given, the rest framing the mesh's bounding sphere."""
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    centre, radius = (lo + hi) / 2, max(float(np.linalg.norm(hi - lo)) / 2, 1e-12)
    look_at = np.array(args.look_at if args.look_at else centre, float)
    fit = radius / np.sin(np.radians(args.vfov) / 2) * 1.1  # the whole sphere within the view, 10% spare
    position = np.array(args.position if args.position else look_at + [0, 0, fit], float)
    camera = {"position": position, "look_at": look_at, "up": args.up or (0, 1, 0), "vfov_deg": args.vfov,
              "width": args.width, "height": args.height}
    ortho = args.ortho_height if args.ortho_height else 2.2 * radius if args.ortho else 0.0
    if args.ortho_height is not None and not args.ortho_height > 0:
        raise ArgumentError("--ortho-height: expected a height > 0, got %g" % args.ortho_height)
    return camera, ortho


def run_render(args):
    for flag in ("width", "height"):
        if not 1 <= getattr(args, flag) <= 16384:
            raise ArgumentError("--%s: expected 1..16384, got %d" % (flag, getattr(args, flag)))
    mesh_path = bundled_mesh(args.mesh)
    profile, dipoles = profile_of(args)
    lights = lights_of(args)
    if args.quick:
        args.width, args.height = (max(64, s // QUICK_SCALE) for s in (args.width, args.height))
    outputs = [Path(o) for o in (args.output or [mesh_path.stem + ".png"])]
    for o in outputs:
        if o.suffix.lower() not in FORMATS:
            raise ArgumentError("-o %s: unknown image format %r (expected %s)" % (o, o.suffix, ", ".join(FORMATS)))
        o.parent.mkdir(parents=True, exist_ok=True)
    started = time.monotonic()
    with Context(_device(args.device)) as ctx:
        vertices, _ = translucency.read_mesh(mesh_path, context=ctx)
        camera, ortho = camera_of(args, vertices)
        spacing = args.spacing
        if args.quick and spacing == 0:
            spacing = 2 / float(max(np.max(d.sigma_t_prime) for d in dipoles))
        with Progress("rendering " + mesh_path.stem, quiet=args.quiet) as bar:
            result = translucency.render(profile, mesh_path, lights, camera, ortho_height=ortho,
                                         mm_per_unit=args.mm_per_unit, exit=args.exit, gather=args.gather,
                                         highlight_deg=args.highlight, sample_spacing_mm=spacing,
                                         out=outputs, progress=bar if bar.shown else None, context=ctx)
    s = result.stats
    print("%s: %d × %d, %d irradiance samples %.3g mm apart, %s gather in %.1f s; wrote %s" % (
        mesh_path.stem, args.width, args.height, s["samples"], s["sample_spacing_mm"], args.gather,
        time.monotonic() - started, ", ".join(str(o.resolve()) for o in outputs)))
    return 0


def run_estimate(args):
    if args.auto:
        return run_automatic(args)
    if not args.mesh:
        raise ArgumentError("--mesh: give the object's mesh, or --auto to estimate it from the photo")
    from .. import image
    args.fit = args.fit or "dipole"
    mesh_path = bundled_mesh(args.mesh)
    lights = lights_of(args)
    photo = translucency._photo(args.photo)
    args.height, args.width = photo.shape[:2]
    matte = None if args.matte is None else image.read(args.matte).max(axis=2) > 0
    started = time.monotonic()
    with Context(_device(args.device)) as ctx:
        vertices, _ = translucency.read_mesh(mesh_path, context=ctx)
        camera, ortho = camera_of(args, vertices)
        with Progress("estimating (distance histograms)", quiet=args.quiet) as bar:
            est = translucency.estimate_bssrdf(photo, mesh_path, lights, camera, basis=args.basis,
                                               family=args.family, tikhonov=args.tikhonov,
                                               nonnegative=args.nonnegative, fit=args.fit, fit_to=args.fit_to,
                                               ortho_height=ortho, mm_per_unit=args.mm_per_unit,
                                               eta=args.eta, exit=args.exit, matte=matte,
                                               progress=bar if bar.shown else None, context=ctx)
        print_estimate(args, est, started)
        if args.compare:
            out = Path(args.compare)
            out.mkdir(parents=True, exist_ok=True)
            again = translucency.render(est.fitted, mesh_path, lights, camera, ortho_height=ortho,
                                        mm_per_unit=args.mm_per_unit, exit=args.exit, highlight_deg=0, context=ctx)
            write_comparison(out, photo, again.image, est, est.dipole)
            print("wrote %s, %s" % ((out / "compare.png").resolve(), (out / "profile.png").resolve()))
    return 0


def print_estimate(args, est, started):
    """The estimate's summary line and its table, per channel."""
    d = est.dipole
    print("%s: %d × %d pixels used (%d equations), %d %s functions to %.3g mm, %.1f s" % (
        Path(args.photo).name, est.pixels["width"], est.pixels["height"], est.pixels["equations"], args.basis,
        args.family.replace("_", "-"), est.profile[0][-1], time.monotonic() - started))
    rows = [("sigma_a [1/mm]", d.sigma_a), ("sigma_s' [1/mm]", d.sigma_s_prime), ("albedo a'", d.albedo),
            ("sigma_t' [1/mm]", d.sigma_t_prime), ("l_d [mm]", d.diffuse_length),
            ("R_total", d.total_reflectance), ("cond(A)", est.condition["A"]),
            ("QMR iterations", est.solve["iterations"]), ("image error", est.solve["image_error"]),
            ("fit error", est.solve["fit_error"]), ("Hermite R_total", est.hermite.total_reflectance)]
    print("%-18s %12s %12s %12s" % ("", "R", "G", "B"))
    for name, values in rows:
        print("%-18s %12.5g %12.5g %12.5g" % ((name,) + tuple(values)))


def run_automatic(args):
    """arcus bssrdf estimate PHOTO --auto: the lights, the shape and the BSSRDF from the
    photo alone."""
    from .. import image
    if args.mesh or args.light:
        raise ArgumentError("--auto finds the mesh and the lights in the photo: give neither --mesh nor --light")
    if len(args.irradiance) not in (1, 3):
        raise ArgumentError("--irradiance: give one number or R G B (got %d numbers)" % len(args.irradiance))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        photo = translucency._photo(args.photo, eight_bit="warn")
    for warning in caught:
        print("arcus bssrdf: warning: %s" % warning.message, file=sys.stderr)
    matte = None if args.matte is None else image.read(args.matte).max(axis=2) > 0
    started = time.monotonic()
    with Context(_device(args.device)) as ctx:
        with Progress("estimating from the photo alone", quiet=args.quiet) as bar:
            est = translucency.estimate_bssrdf(
                photo, basis=args.basis, family=args.family, tikhonov=args.tikhonov,
                nonnegative=True if args.nonnegative else None, fit=args.fit or "hermite", fit_to=args.fit_to,
                eta=args.eta, exit=args.exit, matte=matte, mm_per_pixel=args.mm_per_pixel,
                irradiance=args.irradiance if len(args.irradiance) == 3 else args.irradiance[0],
                progress=bar if bar.shown else None, context=ctx)
        found = est.lights
        print("%s: the object has %d pixels (%s), %d light%s:" % (
            Path(args.photo).name, found.object_pixels, "segmented" if found.segmented else "the matte's",
            len(found.lights), "" if len(found.lights) == 1 else "s"))
        for light in found.lights:
            print("  azimuth %6.1f° ± %.1f°, zenith %5.1f° ± %.1f°, toward (%.3f, %.3f, %.3f), intensity %.2f" % (
                light.azimuth_deg, light.azimuth_spread_deg, light.zenith_deg, light.zenith_spread_deg,
                *light.direction, light.intensity))
        print_estimate(args, est, started)
        print("the dipole is approximate here; the Hermite profile is the estimate (docs/translucency-photo.md)")
        if args.compare:
            out = Path(args.compare)
            out.mkdir(parents=True, exist_ok=True)
            height, width = photo.shape[:2]
            camera = {"position": (0, 0, 4 * max(width, height)), "look_at": (0, 0, 0), "up": (0, 1, 0),
                      "width": width, "height": height}
            irradiance = args.irradiance * 3 if len(args.irradiance) == 1 else args.irradiance
            lights = [(light.direction, [e * light.intensity for e in irradiance]) for light in found.lights]
            again = translucency.render(est.fitted, est.relief, lights, camera, ortho_height=height,
                                        mm_per_unit=args.mm_per_pixel, exit=args.exit, highlight_deg=0, context=ctx)
            write_comparison(out, photo, again.image, est, est.dipole)
            write_shape(out, est)
            print("wrote %s" % ", ".join(str((out / n).resolve()) for n in
                                         ("compare.png", "profile.png", "depth.exr", "normals.png", "relief.obj")))
    return 0


def write_shape(out, est):
    """The shape the photo gave: depth (pixels, EXR), normals (as colours, 0.5 + n/2),
    the closed mesh (OBJ, in pixels)."""
    from .. import image
    shape = est.shape
    image.write(out / "depth.exr", np.repeat(shape.depth[..., None], 3, axis=2).astype(np.float32))
    image.write(out / "normals.png", np.where(shape.mask[..., None], 0.5 + 0.5 * shape.normals, 0))
    vertices, triangles = est.relief
    with open(out / "relief.obj", "w") as f:
        f.write("# arcus bssrdf estimate --auto: the closed mesh of the photo's depth, in pixels\n")
        f.writelines("v %.6g %.6g %.6g\n" % tuple(v) for v in vertices)
        f.writelines("f %d %d %d\n" % tuple(t + 1) for t in triangles)


def write_comparison(out, photo, rendered, est, dipole):
    """photo | re-render | |difference| side by side (one exposure), and the profile plot."""
    from .. import image
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    top = float(np.percentile(photo[photo.max(axis=2) > 0].max(axis=1), 99.5)) if (photo > 0).any() else 1.0
    scale = 0.9 / top if top > 0 else 1.0
    strip = np.concatenate([photo, rendered, np.abs(photo - rendered)], axis=1) * scale
    image.write(out / "compare.png", strip)
    edges, weights = est.profile
    r = np.linspace(0, edges[-1], 400)[1:]
    fig, ax = plt.subplots(figsize=(6, 4))
    for c, colour in enumerate("rgb"):
        ax.stairs(np.maximum(weights[:, c], 1e-12), edges, color=colour, alpha=0.5,
                  label="estimate, %s" % "RGB"[c])
        ax.plot(r, dipole.Rd(r)[:, c], color=colour, label="fitted dipole, %s" % "RGB"[c])
        ax.plot(r, est.hermite.Rd(r)[:, c], color=colour, linestyle=":", label="Hermite (§3.4), %s" % "RGB"[c])
    ax.set_yscale("log")
    ax.set_ylim(bottom=1e-6 * max(float(weights.max()), 1e-30))  # empty or negative bins sit below the frame
    ax.set_xlabel("r [mm]")
    ax.set_ylabel("R_d [1/mm²]")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "profile.png", dpi=100)
    plt.close(fig)
