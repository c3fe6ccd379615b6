#!/usr/bin/env python3
"""The ocean engine from the command line (thesis §3.5, §4.2, §5.3).

    arcus_ocean.py trace   SCENE.json [--out DIR] [--photons N]
    arcus_ocean.py profile SCENE.json [--out DIR] [--photons N]
    arcus_ocean.py render  SCENE.json [-o OUT.exr] [--png OUT.png] [--photons N] [--k K]
                           [--steps S] [--estimator per_step|beam]

trace:   traces the scene's photons and writes DIR/tallies.json (where the energy went:
         totals, per event, per interaction number, per constituent), DIR/fig5_9.png
         (energy absorbed per interaction, thesis Fig. 5.9) and DIR/fig5_12.png (energy
         per event and constituent, thesis Fig. 5.12).
profile: irradiance profiles of a scene with a "profile": DIR/profile.csv (depth,
         wavelength, Ed, Eu, E0 and, for a column lit by the sun and a sky, the same
         by discrete ordinates with elastic scattering only: arcus.ocean_reference) and
         DIR/profile.png (Ed, Eu, E0 against depth at a few wavelengths, the photons'
         as points over the reference's lines; the K_d spectrum).
render:  renders the scene's "view" (arcus.ocean.render).

DIR defaults to out/ocean/<scene name>.  The library reads and checks the scene first
(scenes/README.md, "Ocean scenes"): a bad scene prints its message, which names the
file and the JSON path, and exits with status 2.  On a terminal a progress bar shows
on stderr unless --quiet.
"""
import argparse
import csv
import json
import math
import os
import sys
from pathlib import Path

# The arcus package of this source tree, as tests/python/conftest.py finds it.
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bindings" / "python"))

import numpy as np  # noqa: E402

import arcus  # noqa: E402  (needs the sys.path entry above)
import arcus.ocean as ocean  # noqa: E402
import arcus.ocean_reference as ocean_reference  # noqa: E402
from arcus.progress import Progress  # noqa: E402

EXIT_ERROR = 2


class Failure(Exception):
    """An error of the tool itself (not the library's), reported like the library's."""


# ---- the scene ------------------------------------------------------------------------


def check_scene(ctx, path):
    """The scene as the library read and checked it: the document (dict) of an ocean
    scene; another engine's scene is a Failure."""
    from arcus import _scene_file
    engine, doc = _scene_file.read(path, ("ocean", "render", "rainbow", "sweep", "curved"))
    if engine != "ocean":
        raise Failure("%s: not an ocean scene (no \"water\"; scenes/README.md, \"Ocean scenes\")" % path)
    return doc


def _phase(p):
    """A scene's phase object as arcus.ocean's tuple."""
    kind = p["kind"]
    if kind == "hg":
        return ("hg", p["g"])
    if kind == "two_term_hg":
        return ("two_term_hg", p["g_forward"], p["g_backward"], p["forward_weight"])
    if kind == "rayleigh_like":
        return ("rayleigh_like", p.get("a", 0.835))
    if kind == "table":
        return ("table", p["cosines"], p["values"])
    return "isotropic"


def water_of(w):
    if "iops" in w:
        i = dict(w["iops"])
        i["phase"] = _phase(i["phase"])
        return ocean.Water.from_iops(**i)
    params = {k: v for k, v in w.items() if k != "preset"}
    return ocean.Water(w.get("preset"), **params)


def light_of(L):
    kind, spectrum = L["type"], L["spectrum"]
    if kind == "point":
        return ocean.Light.point(L["position"], spectrum)
    if kind == "spot":
        return ocean.Light.spot(L["position"], L["direction"], L["half_angle_deg"], spectrum)
    if kind == "sun":
        return ocean.Light.sun(L["zenith_deg"], spectrum, L.get("azimuth_deg", 0.0))
    if kind == "directional":
        return ocean.Light.directional(L["direction"], spectrum, L.get("position", (0.0, 0.0, 0.0)),
                                       L.get("radius", 0.0))
    return ocean.Light.sky(spectrum)


def trace_args(doc, photons=None):
    """arcus.ocean.trace_photons' arguments for the scene: (water, lights, keywords)."""
    g = doc.get("grid", {})
    m = doc.get("medium", {})
    p = doc.get("photons", {})
    prof = doc.get("profile")
    kw = dict(photons=int(photons if photons is not None else p.get("count", 400_000)),
              max_interactions=p.get("max_interactions", 5), seed=p.get("seed", 1),
              grid=(g.get("first_nm", 380.0), g.get("last_nm", 780.0), g.get("step_nm", 5.0)),
              surface=m.get("surface", False), n_water=m.get("n_water", 1.34),
              bottom_depth=math.inf if m.get("bottom_depth") is None else m["bottom_depth"],
              bottom_albedo=m.get("bottom_albedo", 0.0))
    if m.get("box") is not None:
        lo = [-math.inf if v is None else v for v in m["box"]["min"]]
        hi = [math.inf if v is None else v for v in m["box"]["max"]]
        kw["box"] = (lo, hi)
    if prof is not None:
        kw["depths"] = prof["depths"]
        kw["layer"] = prof.get("layer", 0.1)
    return water_of(doc["water"]), [light_of(L) for L in doc["lights"]], kw


def out_dir(args, doc):
    d = Path(args.out) if args.out else Path("out") / "ocean" / doc["name"]
    d.mkdir(parents=True, exist_ok=True)
    return d


# ---- progress -------------------------------------------------------------------------


def traced(ctx, doc, args, what):
    water, lights, kw = trace_args(doc, args.photons)
    with Progress(what, quiet=args.quiet) as bar:
        return ocean.trace_photons(water, lights, progress=bar, context=ctx, **kw)


# ---- trace ----------------------------------------------------------------------------


def plain(value):
    """JSON-ready: numpy arrays and scalars as lists and floats."""
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [plain(v) for v in value]
    if isinstance(value, np.generic):
        return value.item()
    return value


def tallies_document(doc, r):
    t = r.tallies
    booked = t["absorbed"] + t["escaped"] + t["past_limit"] + t["bottom"]
    totals = {k: t[k] for k in ("emitted", "absorbed", "escaped", "past_limit", "bottom", "photons",
                                "interactions", "stored", "max_interactions")}
    events = {name: dict(count=t["count"][e], arriving=t["arriving"][e], absorbed=t["absorbed_by"][e])
              for e, name in enumerate(ocean.EVENTS)}
    return plain(dict(
        scene=doc["name"], tallies=totals,
        balance=dict(booked=booked, relative_error=abs(booked - t["emitted"]) / t["emitted"] if t["emitted"] else 0.0),
        events=events,
        by_interaction=dict(absorbed=r.absorbed_by_interaction, escaped=r.escaped_by_interaction),
        per_constituent=r.per_constituent(), features=sorted(r.features), stats=r.stats))


def pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def plot_fig5_9(r, name, path):
    """Energy absorbed per interaction number and its running total, as fractions of
    the emitted energy (thesis Fig. 5.9: after ~5 interactions nothing more is absorbed)."""
    plt = pyplot()
    emitted = r.tallies["emitted"] or 1.0
    absorbed = r.absorbed_by_interaction / emitted
    j = np.arange(absorbed.size)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.bar(j, absorbed, color="tab:blue", label="absorbed at interaction j")
    ax.plot(j, np.cumsum(absorbed), "o-", color="tab:red", label="absorbed up to interaction j")
    ax.set_xlabel("interaction number j")
    ax.set_ylabel("fraction of the emitted energy")
    ax.set_xticks(j)
    ax.set_ylim(0, 1.05)
    ax.grid(axis="y", alpha=0.3)
    ax.legend(loc="center right")
    ax.set_title("%s: energy absorbed per interaction (thesis Fig. 5.9)\n"
                 "past the limit: %.2g, escaped: %.2g" % (name, r.tallies["past_limit"] / emitted,
                                                         r.tallies["escaped"] / emitted), fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


# Which constituent each event belongs to (ocean.EVENTS order), for Fig. 5.12's colours.
EVENT_CONSTITUENT = ("water", "water", "detritus", "phytoplankton", "phytoplankton", "cdom", "cdom", "water",
                     "detritus", "phytoplankton")
CONSTITUENT_COLOUR = dict(water="tab:blue", detritus="tab:brown", phytoplankton="tab:green", cdom="goldenrod")


def plot_fig5_12(r, name, path):
    """Energy reaching each of the ten events and the energy they absorb (inelastic:
    the energy lost to the longer wavelength), per constituent (thesis Fig. 5.12)."""
    plt = pyplot()
    t = r.tallies
    emitted = t["emitted"] or 1.0
    arriving, absorbed = np.asarray(t["arriving"]) / emitted, np.asarray(t["absorbed_by"]) / emitted
    x = np.arange(len(ocean.EVENTS))
    colours = [CONSTITUENT_COLOUR[c] for c in EVENT_CONSTITUENT]
    fig, ax = plt.subplots(figsize=(9, 5))
    ax.bar(x - 0.2, arriving, 0.4, color=colours, edgecolor="black", linewidth=0.5)
    ax.bar(x + 0.2, absorbed, 0.4, color=colours, edgecolor="black", linewidth=0.5, hatch="//", alpha=0.6)
    positive = np.concatenate([arriving[arriving > 0], absorbed[absorbed > 0]])
    if positive.size:
        ax.set_yscale("log")
        ax.set_ylim(positive.min() / 3, 3 * positive.max())
    ax.set_xticks(x)
    ax.set_xticklabels(ocean.EVENTS, rotation=35, ha="right")
    ax.set_ylabel("fraction of the emitted energy")
    from matplotlib.patches import Patch
    handles = [Patch(color=c, label=n) for n, c in CONSTITUENT_COLOUR.items()]
    handles += [Patch(facecolor="white", edgecolor="black", label="energy arriving"),
                Patch(facecolor="white", edgecolor="black", hatch="//", label="energy absorbed")]
    ax.legend(handles=handles, fontsize=8, ncol=2)
    ax.grid(axis="y", alpha=0.3, which="both")
    ax.set_title("%s: energy per event and constituent (thesis Fig. 5.12)" % name, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def cmd_trace(ctx, doc, args):
    r = traced(ctx, doc, args, "tracing")
    d = out_dir(args, doc)
    tallies = tallies_document(doc, r)
    (d / "tallies.json").write_text(json.dumps(tallies, indent=2) + "\n")
    plot_fig5_9(r, doc["name"], d / "fig5_9.png")
    plot_fig5_12(r, doc["name"], d / "fig5_12.png")
    t = r.tallies
    print("%s: %d photons, %.4g W emitted: absorbed %.4f, escaped %.4f, past the limit %.4f, bottom %.4f "
          "(balance %.1e); wrote %s/{tallies.json,fig5_9.png,fig5_12.png}"
          % (doc["name"], t["photons"], t["emitted"], t["absorbed"] / t["emitted"], t["escaped"] / t["emitted"],
             t["past_limit"] / t["emitted"], t["bottom"] / t["emitted"], tallies["balance"]["relative_error"], d))


# ---- profile --------------------------------------------------------------------------


def elastic_reference(ctx, doc, photons):
    """The scene's column by discrete ordinates (arcus.ocean_reference), or None where
    it is not plane-parallel (a box, a point or spot light, a lit disc)."""
    water, lights, kw = trace_args(doc, photons)
    if "box" in kw:
        return None
    keys = ("grid", "surface", "n_water", "bottom_depth", "bottom_albedo", "layer")
    try:
        return ocean_reference.elastic_profile(water, lights, kw["depths"], context=ctx,
                                               **{k: kw[k] for k in keys})
    except ValueError:
        return None


def plot_profile(r, ref, name, path):
    """Ed, Eu, E0 against depth at a few wavelengths (log scale): the photons' as points,
    the elastic reference's as lines; and K_d's spectrum between successive depths."""
    plt = pyplot()
    wl, depths = r.wavelengths, r.depths
    picks = sorted({int(np.argmin(np.abs(wl - nm))) for nm in (412, 443, 490, 550, 620, 680)})
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 5))
    cmap = plt.get_cmap("viridis")
    quantities = (("Ed", "-", "o"), ("Eu", ":", "v"), ("E0", "--", "s"))
    for i, k in enumerate(picks):
        c = cmap(i / max(1, len(picks) - 1))
        for q, style, marker in quantities:
            e = getattr(r, q)[:, k]
            ax.plot(np.where(e > 0, e, np.nan), depths, marker, color=c, ms=4, mfc="none" if q != "Ed" else c)
            if ref is not None:
                ax.plot(ref[q][:, k], depths, style, color=c, lw=1)
    # the legend: a colour per wavelength, a marker (photons) and a line (reference) per quantity
    handles = [plt.Line2D([], [], color=cmap(i / max(1, len(picks) - 1)), lw=3, label="%g nm" % wl[k])
               for i, k in enumerate(picks)]
    handles += [plt.Line2D([], [], color="k", marker=m, ls=style if ref is not None else "none", lw=1, ms=4,
                           mfc="none" if q != "Ed" else "k", label=q) for q, style, m in quantities]
    positive = np.concatenate([getattr(r, q)[getattr(r, q) > 0] for q, _, _ in quantities])
    if positive.size:  # the reference goes on where the photons run out: a decade further
        ax.set_xlim(positive.min() / 10, positive.max() * 2)
    ax.set_xscale("log")
    ax.invert_yaxis()
    ax.set_xlabel("irradiance [W/m²/nm]")
    ax.set_ylabel("depth [m]")
    ax.legend(handles=handles, fontsize=7, ncol=3)
    ax.grid(alpha=0.3, which="both")
    title = "%s: Ed, Eu, E0 by photons (markers)" % name
    if ref is not None:
        title += ";\nlines: discrete ordinates, elastic only (Raman and fluorescence as losses)"
    ax.set_title(title, fontsize=9)
    kd = ocean.diffuse_attenuation(depths, r.Ed)
    kd_ref = None if ref is None else ocean.diffuse_attenuation(depths, ref["Ed"])
    for j in range(kd.shape[0]):
        c = cmap(j / max(1, kd.shape[0] - 1))
        bx.plot(wl, kd[j], ".", color=c, ms=3, label="%g–%g m" % (depths[j], depths[j + 1]))
        if kd_ref is not None:
            bx.plot(wl, kd_ref[j], "-", color=c, lw=1)
    bx.set_xlabel("wavelength [nm]")
    bx.set_ylabel("K_d [1/m]")
    bx.set_yscale("log")
    bx.grid(alpha=0.3, which="both")
    if kd.shape[0]:
        bx.legend(fontsize=7)
    bx.set_title("diffuse attenuation of Ed: photons (points), discrete ordinates (lines)"
                 if ref is not None else "diffuse attenuation of Ed", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def cmd_profile(ctx, doc, args):
    if "profile" not in doc:
        raise Failure("%s: $.profile: missing: the scene asks for no irradiance depths" % args.scene)
    # arcus.ocean.profile has no progress callback: trace_photons with the scene's own
    # lights and column gives the same profile and the bar.
    r = traced(ctx, doc, args, "profile")
    ref = elastic_reference(ctx, doc, args.photons)
    d = out_dir(args, doc)
    with open(d / "profile.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["depth_m", "wavelength_nm", "Ed", "Eu", "E0"]
                   + ([] if ref is None else ["Ed_elastic_do", "Eu_elastic_do", "E0_elastic_do"]))
        for j, z in enumerate(r.depths):
            for k, nm in enumerate(r.wavelengths):
                row = [float(z), float(nm), r.Ed[j, k], r.Eu[j, k], r.E0[j, k]]
                if ref is not None:
                    row += [ref["Ed"][j, k], ref["Eu"][j, k], ref["E0"][j, k]]
                w.writerow([repr(float(v)) for v in row])
    plot_profile(r, ref, doc["name"], d / "profile.png")
    print("%s: %d photons, %d depths x %d wavelengths%s; wrote %s/{profile.csv,profile.png}"
          % (doc["name"], r.tallies["photons"], r.depths.size, r.wavelengths.size,
             "" if ref is None else ", beside discrete ordinates", d))


# ---- render ---------------------------------------------------------------------------


def cmd_render(ctx, doc, args):
    if "view" not in doc:
        raise Failure("%s: $.view: missing: the scene has no camera to render from" % args.scene)
    exr, png = args.output, args.png
    if exr is None and png is None:
        d = out_dir(args, doc)
        exr, png = str(d / "image.exr"), str(d / "image.png")
    with Progress("rendering", quiet=args.quiet) as bar:
        result = ocean.render(args.scene, photons=args.photons, k=args.k, steps=args.steps, estimator=args.estimator,
                              thesis=args.thesis, exr=exr, png=png, progress=bar, context=ctx)
    h, w = result.image.shape[:2]
    stats = ", ".join("%s %.3g" % (k, v) for k, v in result.stats.items() if isinstance(v, float))
    print("%s: %dx%d; %s; wrote %s" % (doc["name"], w, h, stats, " and ".join(p for p in (exr, png) if p)))


# ---- main -----------------------------------------------------------------------------


def parser():
    p = argparse.ArgumentParser(prog=os.environ.get("ARCUS_PROG", "arcus_ocean.py"),
                                description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)

    def common(s):
        s.add_argument("scene", help="an ocean scene file (scenes/README.md, \"Ocean scenes\")")
        s.add_argument("--photons", type=int, help="photons to trace (default: the scene's)")
        s.add_argument("--quiet", action="store_true", help="no progress bar")

    t = sub.add_parser("trace", help="tallies, thesis Fig. 5.9 and 5.12")
    common(t)
    t.add_argument("--out", help="output directory (default out/ocean/<name>)")
    pr = sub.add_parser("profile", help="irradiance profiles Ed, Eu, E0 and K_d")
    common(pr)
    pr.add_argument("--out", help="output directory (default out/ocean/<name>)")
    r = sub.add_parser("render", help="renders the scene's view")
    common(r)
    r.add_argument("-o", "--output", metavar="OUT.exr", help="linear EXR to write")
    r.add_argument("--png", metavar="OUT.png", help="sRGB PNG to write")
    r.add_argument("--out", help="directory of image.exr and image.png when neither -o nor --png is given")
    r.add_argument("--k", type=int, help="photons per radiance estimate (default: the scene's)")
    r.add_argument("--steps", type=int, help="ray-marching steps (default: the scene's)")
    r.add_argument("--estimator", choices=("per_step", "beam"), help="radiance estimate (default: the scene's)")
    r.add_argument("--thesis", action="store_true", help="the thesis' settings: 400 000 photons of one wavelength, "
                   "k = 250, the estimate at every pixel (then --photons, --k override)")
    return p


COMMANDS = dict(trace=cmd_trace, profile=cmd_profile, render=cmd_render)


def main(argv=None):
    args = parser().parse_args(argv)
    try:
        with arcus.Context() as ctx:
            doc = check_scene(ctx, args.scene)
            COMMANDS[args.command](ctx, doc, args)
    except arcus.Error as exc:
        print("arcus_ocean: %s" % exc.message, file=sys.stderr)
        return EXIT_ERROR
    except (Failure, OSError) as exc:
        print("arcus_ocean: %s" % exc, file=sys.stderr)
        return EXIT_ERROR
    return 0


if __name__ == "__main__":
    sys.exit(main())
