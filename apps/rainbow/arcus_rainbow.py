#!/usr/bin/env python3
"""The rainbow engine from the command line (thesis §4.4, §5.5): phase-function tables.

    arcus_rainbow.py table --particle sphere:RADIUS|raindrop:DIAMETER|mesh:PATH[:SCALE][:flat]
                           [--wavelengths FIRST LAST COUNT] [--theta FIRST LAST STEP]
                           [--phi PHI | --phi FIRST LAST STEP] [--grid N] [--max-bounces P]
                           [--material water|ice] [--temperature-k K] [--incoherent]
                           [-o OUT_PREFIX] [--plot OUT.png [--plot-wavelength NM] [--per-bounce]]
    arcus_rainbow.py mie   --particle sphere:RADIUS [--debye P] [same wavelength, theta,
                           material and output options]

table: casts rays at the particle once per wavelength (arcus.rainbow.phase_function) and
       writes OUT_PREFIX.csv (wavelength_nm, theta_deg[, phi_deg], parallel,
       perpendicular, unpolarized, p0..pP), OUT_PREFIX.npz (every array with its
       coordinates: wavelength, theta, phi, parallel, perpendicular, unpolarized,
       per_bounce, refractive_index, scattered) and OUT_PREFIX_unpolarized.npy
       (wavelengths × theta [× phi]).  Without --phi the table is at φ = 0 (fast: only
       the light reaching that half-plane is kept); one value gives that azimuth;
       FIRST LAST STEP a 2-D table over θ × φ.
mie:   Lorenz–Mie for a sphere (arcus.mie), with --debye P the Debye terms p = 0..P as
       the p columns / per_bounce; the same files, plus q_ext, q_sca, q_back and g per
       wavelength in the .npz.

A mesh's triangles approximate a smooth surface (normals interpolated from the
vertices) unless the particle ends in ":flat": flat faces, a crystal, whose light in one
orientation goes into single directions the table cannot hold (arcus.rainbow.Mesh).

--plot draws the unpolarized phase function around the bows (120°-145°, within the
table's θ) at one wavelength, averaged in 0.1° bins, with Lorenz–Mie overlaid for
spheres (scaled to the rays' normalisation: × Q_sca / Σ_p scattered_p, since the rays
leave diffraction out); --per-bounce adds a panel per term p with its Debye term.
Units: metres, nanometres, degrees.  Sizes accept SI suffixes: 0.5mm, 500um.  Errors
print the library's message and exit with status 2.
"""
import argparse
import math
import os
import sys
import time
from pathlib import Path

# The arcus package of this source tree, as tests/python/conftest.py finds it.
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bindings" / "python"))

import numpy as np  # noqa: E402

import arcus  # noqa: E402  (needs the sys.path entry above)
import arcus.mie as mie  # noqa: E402
import arcus.rainbow as rainbow  # noqa: E402
from arcus.progress import Progress  # noqa: E402

EXIT_ERROR = 2
PLOT_RANGE = (120.0, 145.0)  # degrees: both bows and Alexander's dark band
BIN = 0.1  # degrees, the plot's averaging bins


class Failure(Exception):
    """An error of the tool itself (not the library's), reported like the library's."""


# ---- arguments ------------------------------------------------------------------------

_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "nm": 1e-9, "cm": 1e-2}


def length(text):
    """A length in metres: "5e-4", "0.5mm", "500um"."""
    for unit in sorted(_UNITS, key=len, reverse=True):
        if text.endswith(unit):
            try:
                return float(text[:-len(unit)]) * _UNITS[unit]
            except ValueError:
                break
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError("not a length in metres (e.g. 5e-4, 0.5mm, 500um): %r" % text) from None


def particle_spec(text):
    """sphere:RADIUS, raindrop:DIAMETER or mesh:PATH[:SCALE][:flat|:smooth] -> (kind, values)."""
    kind, _, rest = text.partition(":")
    if kind not in ("sphere", "raindrop", "mesh") or not rest:
        raise argparse.ArgumentTypeError("expected sphere:RADIUS, raindrop:DIAMETER or mesh:PATH[:SCALE][:flat] "
                                         "(metres), got %r" % text)
    if kind == "mesh":
        smooth = True
        head, sep, tail = rest.rpartition(":")
        if sep and head and tail in ("flat", "smooth"):
            rest, smooth = head, tail == "smooth"
        path, scale = rest, 1.0
        head, sep, tail = rest.rpartition(":")
        if sep and head:
            try:
                path, scale = head, float(tail)
            except ValueError:
                path, scale = rest, 1.0  # a colon in the path itself
        return kind, (path, scale, smooth)
    return kind, (length(rest),)


def spec_text(spec):
    """The --particle text of a parsed spec (for --particle=... and abbreviations)."""
    kind, values = spec
    if kind == "mesh":
        path, scale, smooth = values
        return "mesh:%s:%g%s" % (path, scale, "" if smooth else ":flat")
    return "%s:%g" % (kind, values[0])


def make_particle(spec):
    kind, values = spec
    return dict(sphere=rainbow.Sphere, raindrop=rainbow.Raindrop, mesh=rainbow.Mesh)[kind](*values)


def wavelengths_of(args):
    first, last, count = args.wavelengths
    if not (count >= 1 and count == int(count)):
        raise Failure("--wavelengths: COUNT must be a positive integer, got %g" % count)
    if count == 1 or first == last:
        return np.array([float(first)])
    return np.linspace(first, last, int(count))


def range_of(first, last, step, name):
    """FIRST..LAST inclusive in steps of STEP (the last one kept despite rounding)."""
    if not (step > 0 and last >= first):
        raise Failure("%s: needs STEP > 0 and LAST >= FIRST, got %g %g %g" % (name, first, last, step))
    count = int(math.floor((last - first) / step + 1e-9)) + 1
    return first + step * np.arange(count)


def phi_of(args):
    """None, a number (1-D at that azimuth) or an array (2-D)."""
    if args.phi is None:
        return None
    if len(args.phi) == 1:
        return float(args.phi[0])
    if len(args.phi) == 3:
        return range_of(*args.phi, name="--phi")
    raise Failure("--phi: one value, or FIRST LAST STEP, got %d values" % len(args.phi))


def index_of(material, nm, temperature_k):
    return rainbow.refractive_index(material, nm, temperature_k)


def water_temperature_k(args):
    """--temperature-k, or the deprecated --temperature (°C) converted."""
    return args.temperature_k if args.temperature is None else args.temperature + 273.15


# ---- progress -------------------------------------------------------------------------


# ---- output ---------------------------------------------------------------------------


def prefix_of(args, default):
    prefix = Path(args.output or default)
    prefix.parent.mkdir(parents=True, exist_ok=True)
    return prefix


def write_table(prefix, wl, theta, phi, par, perp, unpol, per_bounce, extra):
    """OUT.csv, OUT.npz and OUT_unpolarized.npy; ``phi``: None (no φ column), or the
    (F,) azimuths of a 2-D table (arrays W × T × F [× P+1]).  ``extra`` goes into the
    .npz too (it may override ``phi`` there).  Returns the paths."""
    columns = ["wavelength_nm", "theta_deg"] + ([] if phi is None else ["phi_deg"]) + [
        "parallel", "perpendicular", "unpolarized"]
    if per_bounce is not None:
        columns += ["p%d" % p for p in range(per_bounce.shape[-1])]
    if phi is None:
        grids = np.meshgrid(wl, theta, indexing="ij")
    else:
        grids = np.meshgrid(wl, theta, phi, indexing="ij")
    cols = [g.ravel() for g in grids] + [par.ravel(), perp.ravel(), unpol.ravel()]
    if per_bounce is not None:
        cols += list(per_bounce.reshape(-1, per_bounce.shape[-1]).T)
    paths = [prefix.with_name(prefix.name + ".csv"), prefix.with_name(prefix.name + ".npz"),
             prefix.with_name(prefix.name + "_unpolarized.npy")]
    np.savetxt(paths[0], np.column_stack(cols), delimiter=",", header=",".join(columns), comments="", fmt="%.10g")
    arrays = dict(wavelength=wl, theta=theta, phi=np.array([] if phi is None else phi), parallel=par,
                  perpendicular=perp, unpolarized=unpol)
    if per_bounce is not None:
        arrays["per_bounce"] = per_bounce
    arrays.update(extra)
    np.savez(paths[1], **arrays)
    np.save(paths[2], unpol)
    return paths


def binned(theta, values, lo, hi):
    """Means of ``values`` (along axis 0) in BIN-degree bins over [lo, hi]: (centres, means)."""
    edges = np.arange(lo, hi + BIN / 2, BIN)
    if edges.size < 2:
        edges = np.array([lo, hi])
    which = np.digitize(theta, edges) - 1
    centres, means = [], []
    for b in range(edges.size - 1):
        sel = which == b
        if sel.any():
            centres.append(0.5 * (edges[b] + edges[b + 1]))
            means.append(values[sel].mean(axis=0))
    return np.array(centres), np.array(means)


def plot_range(theta):
    lo, hi = max(PLOT_RANGE[0], theta.min()), min(PLOT_RANGE[1], theta.max())
    if hi - lo < BIN:
        lo, hi = theta.min(), theta.max()
    return lo, hi


def pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def plot(path, title, theta, curve, per_bounce, reference, debye_terms, n, lo, hi):
    """The unpolarized phase function (and per term p) in [lo, hi], binned; reference:
    (θ, values) of Lorenz–Mie or None; debye_terms: (θ, (·, P+1)) or None."""
    plt = pyplot()
    panels = 2 if per_bounce is not None else 1
    fig, axes = plt.subplots(panels, 1, figsize=(9, 4.2 * panels), squeeze=False)
    ax = axes[0, 0]
    sel = (theta >= lo) & (theta <= hi)
    x, y = binned(theta[sel], curve[sel], lo, hi)
    ax.plot(x, y, "-", color="tab:blue", lw=1.4, label="arcus rays (%g° bins)" % BIN)
    if reference is not None:
        rx, ry = binned(*reference, lo, hi)
        ax.plot(rx, ry, "-", color="black", lw=0.9, alpha=0.8, label="Lorenz–Mie")
    for p, name in ((2, "primary"), (3, "secondary")):
        try:
            a = rainbow.rainbow_angle(n, p)
        except arcus.Error:
            continue
        if lo <= a <= hi:
            ax.axvline(a, color="grey", ls=":", lw=0.8)
            ax.text(a, 1.0, " %s %.2f°" % (name, a), transform=ax.get_xaxis_transform(), fontsize=7, va="top")
    ax.set_yscale("log")
    ax.set_xlim(lo, hi)
    ax.set_xlabel("scattering angle θ [deg]")
    ax.set_ylabel("phase function [1/sr]")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=10)
    if per_bounce is not None:
        bx = axes[1, 0]
        cmap = plt.get_cmap("tab10")
        x, ys = binned(theta[sel], per_bounce[sel], lo, hi)
        for p in range(per_bounce.shape[-1]):
            c = cmap(p % 10)
            v = np.where(ys[:, p] > 0, ys[:, p], np.nan)
            bx.plot(x, v, "-", color=c, lw=1.3, label="p = %d" % p)
            if debye_terms is not None and p < debye_terms[1].shape[-1]:
                dx, dy = binned(debye_terms[0], debye_terms[1][:, p], lo, hi)
                bx.plot(dx, np.where(dy > 0, dy, np.nan), "--", color=c, lw=0.9, label="Debye p = %d" % p)
        bx.set_yscale("log")
        top = np.nanmax(ys) if ys.size and np.isfinite(ys).any() else 1.0
        if top > 0:
            bx.set_ylim(top * 1e-5, top * 2)  # Debye terms far below the rays' are noise here
        bx.set_xlim(lo, hi)
        bx.set_xlabel("scattering angle θ [deg]")
        bx.set_ylabel("phase function [1/sr]")
        bx.grid(alpha=0.3, which="both")
        bx.legend(fontsize=7, ncol=2)
        bx.set_title("per term p (p − 1 internal reflections)%s"
                     % ("; dashed: Debye series" if debye_terms is not None else ""), fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def mie_reference(radius, nm, n, lo, hi, max_p, scale_to):
    """Lorenz–Mie (and Debye terms up to max_p, or None) on a fine grid in [lo, hi],
    scaled to the rays' normalisation when ``scale_to`` (Σ_p scattered_p) is given."""
    fine = np.arange(lo, hi + 1e-9, 0.01)
    m = mie.phase_function(radius, nm, fine, n=n)
    scale = m.q_sca / scale_to if scale_to else 1.0
    reference = (fine, m.unpolarized * scale)
    terms = None
    if max_p is not None:
        d = mie.debye(radius, nm, fine, n=n, max_p=max_p)
        terms = (fine, d.unpolarized * scale)
    return reference, terms


def pick_wavelength(wl, wanted):
    if wanted is None:
        return len(wl) // 2
    return int(np.argmin(np.abs(wl - wanted)))


# ---- table ----------------------------------------------------------------------------


def cmd_table(args):
    particle = make_particle(args.particle)
    wl = wavelengths_of(args)
    theta = range_of(*args.theta, name="--theta")
    phi = phi_of(args)
    two_d = phi is not None and np.ndim(phi) > 0
    results = []
    with arcus.Context() as ctx:
        bar = Progress("casting", total=len(wl), unit="λ", quiet=args.quiet)
        try:
            for nm in wl:
                results.append(rainbow.phase_function(
                    particle, float(nm), theta, phi=phi, grid=args.grid, max_bounces=args.max_bounces,
                    material=args.material, temperature_k=water_temperature_k(args), coherent=not args.incoherent, caustics=args.caustics,
                    context=ctx))
                bar.advance()
        finally:
            bar.close()
        info = particle.info(ctx)
    par = np.stack([r.parallel for r in results])
    perp = np.stack([r.perpendicular for r in results])
    per = np.stack([r.per_bounce for r in results])
    unpol = par + perp
    extra = dict(refractive_index=np.array([r.refractive_index for r in results]),
                 scattered=np.stack([r.stats["scattered"] for r in results]),
                 remaining=np.array([r.stats["remaining"] for r in results]),
                 coherent=np.array(not args.incoherent), grid=np.array(args.grid),
                 particle=np.array(args.particle_text))
    prefix = prefix_of(args, "out/rainbow/table")
    extra["phi"] = np.atleast_1d(np.asarray(0.0 if phi is None else phi, dtype=float))  # a 1-D table's φ too
    paths = write_table(prefix, wl, theta, phi if two_d else None, par, perp, unpol, per, extra)
    if args.plot:
        k = pick_wavelength(wl, args.plot_wavelength)
        r = results[k]
        col = (lambda a: a[:, int(np.argmin(np.abs(phi)))]) if two_d else (lambda a: a)
        lo, hi = plot_range(theta)
        reference = terms = None
        if isinstance(particle, rainbow.Sphere):
            reference, terms = mie_reference(particle.radius, float(wl[k]), r.refractive_index, lo, hi,
                                               r.max_bounces if args.per_bounce else None,
                                               float(r.stats["scattered"].sum()))
        title = "%s at %g nm (n = %.5f), grid %d, %s" % (args.particle_text, wl[k], r.refractive_index, args.grid,
                                                         "incoherent" if args.incoherent else "coherent")
        plot(args.plot, title, theta, col(r.unpolarized), col(r.per_bounce) if args.per_bounce else None, reference,
             terms, r.refractive_index, lo, hi)
        paths.append(Path(args.plot))
    shape = " x ".join(str(s) for s in unpol.shape)
    print("%s (equivalent radius %.4g m): %s table (wavelengths x theta%s), %.1f s casting; wrote %s"
          % (args.particle_text, info["equivalent_radius"], shape, " x phi" if two_d else "",
             sum(r.stats["total_seconds"] for r in results), ", ".join(str(p) for p in paths)))


# ---- mie ------------------------------------------------------------------------------


def cmd_mie(args):
    kind, values = args.particle
    if kind != "sphere":
        raise Failure("--particle: Lorenz–Mie is for spheres only (sphere:RADIUS), got %s" % args.particle_text)
    if args.phi is not None:
        raise Failure("--phi: a sphere's phase function does not depend on φ for unpolarised light")
    radius = values[0]
    wl = wavelengths_of(args)
    theta = range_of(*args.theta, name="--theta")
    rows = dict(par=[], perp=[], per=[], n=[], q_ext=[], q_sca=[], q_back=[], g=[])
    start = time.monotonic()
    bar = Progress("Lorenz–Mie", total=len(wl), unit="λ", quiet=args.quiet)
    try:
        for nm in wl:
            n = index_of(args.material, float(nm), water_temperature_k(args))
            m = mie.phase_function(radius, float(nm), theta, n=n)
            rows["par"].append(m.parallel)
            rows["perp"].append(m.perpendicular)
            for key in ("q_ext", "q_sca", "q_back", "g"):
                rows[key].append(getattr(m, key))
            rows["n"].append(n)
            if args.debye is not None:
                rows["per"].append(mie.debye(radius, float(nm), theta, n=n, max_p=args.debye).unpolarized)
            bar.advance()
    finally:
        bar.close()
    par, perp = np.stack(rows["par"]), np.stack(rows["perp"])
    per = np.stack(rows["per"]) if args.debye is not None else None
    unpol = par + perp
    extra = {key: np.array(rows[key]) for key in ("q_ext", "q_sca", "q_back", "g")}
    extra["refractive_index"] = np.array(rows["n"])
    extra["radius"] = np.array(radius)
    prefix = prefix_of(args, "out/rainbow/mie")
    paths = write_table(prefix, wl, theta, None, par, perp, unpol, per, extra)
    if args.plot:
        k = pick_wavelength(wl, args.plot_wavelength)
        lo, hi = plot_range(theta)
        title = "Lorenz–Mie: sphere of radius %g m at %g nm (n = %.5f, x = %.1f)" % (
            radius, wl[k], rows["n"][k], 2 * math.pi * radius / (wl[k] * 1e-9))
        plot(args.plot, title, theta, unpol[k], per[k] if (per is not None and args.per_bounce) else None, None,
             None, rows["n"][k], lo, hi)
        paths.append(Path(args.plot))
    print("sphere of radius %g m: Lorenz–Mie%s, %d wavelengths x %d angles, %.1f s; wrote %s"
          % (radius, "" if args.debye is None else " with Debye terms p = 0..%d" % args.debye, len(wl), theta.size,
             time.monotonic() - start, ", ".join(str(p) for p in paths)))


# ---- main -----------------------------------------------------------------------------


def parser():
    p = argparse.ArgumentParser(prog=os.environ.get("ARCUS_PROG", "arcus_rainbow.py"), description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    sub = p.add_subparsers(dest="command", required=True)

    def common(s, default_out):
        s.add_argument("--particle", required=True, type=particle_spec, metavar="KIND:SIZE",
                       help="sphere:RADIUS, raindrop:DIAMETER (1-6 mm) or mesh:PATH[:SCALE][:flat] (sizes in metres; "
                            "a mesh is smooth unless :flat)")
        s.add_argument("--wavelengths", nargs=3, type=float, default=[380.0, 700.0, 33], metavar=("FIRST", "LAST",
                                                                                                 "COUNT"),
                       help="wavelengths in nm (default 380 700 33)")
        s.add_argument("--theta", nargs=3, type=float, default=[0.0, 180.0, 0.05], metavar=("FIRST", "LAST", "STEP"),
                       help="scattering angles in degrees (default 0 180 0.05)")
        s.add_argument("--phi", nargs="+", type=float, metavar="PHI",
                       help="azimuth in degrees, or FIRST LAST STEP for a 2-D table (default: 0)")
        s.add_argument("--material", choices=("water", "ice"), default="water", help="default water")
        s.add_argument("--temperature-k", type=float, default=293.15, help="water's temperature [K] (293.15)")
        s.add_argument("--temperature", type=float, help="deprecated since 0.10: water's temperature [°C]")
        s.add_argument("-o", "--output", metavar="OUT_PREFIX",
                       help="writes OUT_PREFIX.csv, .npz and _unpolarized.npy (default %s)" % default_out)
        s.add_argument("--plot", metavar="OUT.png", help="plot around the bows at one wavelength")
        s.add_argument("--plot-wavelength", type=float, metavar="NM",
                       help="the plot's wavelength (nearest in the table; default the middle one)")
        s.add_argument("--per-bounce", action="store_true", help="the plot gets a panel per term p")
        s.add_argument("--quiet", action="store_true", help="no progress bar")

    t = sub.add_parser("table", help="ray-traced phase functions (arcus.rainbow)")
    common(t, "out/rainbow/table")
    t.add_argument("--grid", type=int, default=1000, help="rays per side of the cast grid (1000)")
    t.add_argument("--max-bounces", type=int, default=3, help="P: terms p = 0..P (3)")
    t.add_argument("--incoherent", action="store_true", help="add intensities (no interference)")
    t.add_argument("--caustics", choices=("uniform", "rays"), default="uniform",
                   help="at a rainbow angle: the uniform (Airy) approximation of its two rays (default), or their "
                        "plain sum as the thesis (eq. 4.31)")
    m = sub.add_parser("mie", help="Lorenz–Mie and Debye terms for a sphere (arcus.mie)")
    common(m, "out/rainbow/mie")
    m.add_argument("--debye", type=int, metavar="P", help="also the Debye terms p = 0..P")
    return p


COMMANDS = dict(table=cmd_table, mie=cmd_mie)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    args = parser().parse_args(argv)
    # The particle as typed, for titles and the .npz.
    args.particle_text = argv[argv.index("--particle") + 1] if "--particle" in argv else spec_text(args.particle)
    try:
        COMMANDS[args.command](args)
    except arcus.Error as exc:
        print("arcus_rainbow: %s" % exc.message, file=sys.stderr)
        return EXIT_ERROR
    except (Failure, OSError) as exc:
        print("arcus_rainbow: %s" % exc, file=sys.stderr)
        return EXIT_ERROR
    return 0


if __name__ == "__main__":
    sys.exit(main())
