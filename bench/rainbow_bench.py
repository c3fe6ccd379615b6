#!/usr/bin/env python3
"""rainbow_bench — what accuracy costs in time, for arcus' rainbow engine.

    python3 bench/rainbow_bench.py [--out DIR] [--quick]

Writes DIR/rainbow.md (tables), DIR/rainbow.csv (one row per measurement) and
DIR/rainbow_error_vs_time.png:

1. the cast grid (100² … 2000²) against error and time per stage (cast, patches, BVH
   build, queries) for a 500 µm water sphere at 650 nm, P = 3, 3600 query angles
   (0.05°): error against our Lorenz–Mie (the whole phase function around the bows)
   and against the p = 2 Debye term (the primary bow alone), in 0.1° bins;
2. the same figures at grid 1000 for radii of 100, 200 and 500 µm (at 100 µm
   diffraction and surface waves, which rays leave out, matter more);
3. the targets: grid 1000, P = 3, 3600 angles, one wavelength in ≤ 10 s; a 2-D table of
   1800 × 360 directions for a 2 mm raindrop in ≤ 30 s; our Mie at size parameter
   10 000 over 3600 angles in ≤ 1 s (the thesis needed 30 minutes per wavelength for
   its queries alone);
4. the machine, the date, arcus' version.

Error measures (on 0.1° bins of 0.01° samples; scale-free; "(rays)": the same with the
thesis' plain sum of rays at the caustic, caustics="rays", instead of the uniform
approximation):
  bow corr   1 − the correlation of ray tracing and Mie over 134°-142° (the issue asks
             ≥ 0.95, i.e. ≤ 0.05);
  p=2 L1     Σ|RT − Debye| / Σ Debye for the primary-bow term alone over the lit side
             (bow + 0.5° … 170°), both in m²/sr (ray tracing × its cross-section, Debye
             × Mie's), so the normalisation is checked too;
  supern.    the largest distance between the first two supernumerary maxima of ray
             tracing and of Mie [deg] (the issue asks ≤ 0.05°).
The library is the one ``arcus`` finds (ARCUS_LIBRARY picks one).  See bench/README.md,
"rainbow_bench".
"""

import argparse
import csv
import math
import os
import statistics
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "bindings", "python"))

import arcus  # noqa: E402
import arcus.mie as mie  # noqa: E402
import arcus.rainbow as rainbow  # noqa: E402
from ocean_bench import machine  # noqa: E402  (one description of the machine for every benchmark)

NM = 650.0
THETA = np.arange(0.025, 180.0, 0.05)  # the target's 3600 angles: timing
# Errors are measured on bins filled 10 samples each: a bin's mean then stands for its
# integral, which matters at the geometric caustic, where the rays' intensity has an
# integrable 1/sqrt peak that sparse sampling would miss or hit by chance.
DENSE = np.arange(0.005, 180.0, 0.01)


def bins(theta, y, lo, hi):
    """Means of y over 0.1° bins [lo, hi); their centres."""
    edges = np.arange(lo, hi + 1e-9, 0.1)
    idx = np.digitize(theta, edges) - 1
    centres = 0.5 * (edges[1:] + edges[:-1])
    means = np.array([y[idx == k].mean() if np.any(idx == k) else 0.0 for k in range(len(centres))])
    return centres, means


def maxima(centres, y, start, stop):
    return [c for i, c in enumerate(centres[1:-1], 1) if start <= c <= stop and y[i] > y[i - 1] and y[i] >= y[i + 1]]


def errors(radius, grid, ctx):
    """The error measures of a sphere's 1-D table at `grid`, on DENSE: with the uniform
    approximation at the caustic (the default) and, for the bow, with the thesis' plain
    sum of rays (caustics="rays")."""
    result = rainbow.phase_function(rainbow.Sphere(radius), NM, DENSE, grid=grid, max_bounces=3, context=ctx)
    rays = rainbow.phase_function(rainbow.Sphere(radius), NM, DENSE, grid=grid, max_bounces=3, caustics="rays",
                                  context=ctx)
    n = result.refractive_index
    m = mie.phase_function(radius, NM, DENSE, n=n)
    d = mie.debye(radius, NM, DENSE, n=n, max_p=3)
    c, mb = bins(DENSE, m.unpolarized, 130, 145)
    window = (c > 134) & (c < 142)
    bow = rainbow.rainbow_angle(n, 2)
    near = (c > bow - 2) & (c < bow + 2)
    primary = float(c[near][np.argmax(mb[near])])
    out = dict(mie_primary_deg=primary)
    for name, r in (("", result), ("rays_", rays)):
        _, rt = bins(DENSE, r.unpolarized, 130, 145)
        out[name + "bow_corr"] = 1 - float(np.corrcoef(rt[window], mb[window])[0, 1])
        out[name + "primary_deg"] = float(c[near][np.argmax(rt[near])])
        rm, mm = maxima(c, rt, primary + 0.3, 144), maxima(c, mb, primary + 0.3, 144)
        out[name + "supernumerary_deg"] = (max(abs(a - b) for a, b in zip(rm[:2], mm[:2]))
                                           if len(rm) >= 2 and len(mm) >= 2 else float("nan"))
    # p = 2 in absolute units over the lit side
    s = result.stats
    cross = s["intercepted"] * float(np.sum(s["scattered"]))
    mie_cross = m.q_sca * math.pi * radius * radius
    lo = math.ceil((bow + 0.5) * 10) / 10
    _, a = bins(DENSE, result.per_bounce[:, 2] * cross, lo, 170)
    _, b = bins(DENSE, d.unpolarized[:, 2] * mie_cross, lo, 170)
    out["p2_l1"] = float(np.sum(np.abs(a - b)) / np.sum(b))
    return out


def timed_sphere(radius, grid, ctx, repeats):
    """The 1-D table at φ = 0 for a sphere: (result, median wall seconds)."""
    walls, result = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        result = rainbow.phase_function(rainbow.Sphere(radius), NM, THETA, grid=grid, max_bounces=3, context=ctx)
        walls.append(time.perf_counter() - t0)
    return result, statistics.median(walls)


def stage_row(kind, label, result, wall, extra=None):
    s = result.stats
    row = dict(section=kind, case=label, wall_s=wall, cast_s=s["cast_seconds"], patches_s=s["patch_seconds"],
               bvh_s=s["bvh_seconds"], query_s=s["query_seconds"], patches=int(s["patches"]),
               folded=int(s["patches_folded"]))
    row.update(extra or {})
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "bench"))
    ap.add_argument("--quick", action="store_true", help="grids up to 500 and one repeat (a smoke run)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    grids = (100, 200, 500) if args.quick else (100, 200, 500, 1000, 2000)
    repeats = 1 if args.quick else 3
    rows = []
    ctx = arcus.Context()
    # one warm-up: the programs are built (or loaded from the cache) once per process
    rainbow.phase_function(rainbow.Sphere(5e-4), NM, THETA[:10], grid=16, context=ctx)

    # ---- 1. grid against error and time
    print("grid sweep (500 µm sphere, 650 nm, P = 3, 3600 angles)", flush=True)
    for g in grids:
        result, wall = timed_sphere(5e-4, g, ctx, 1 if g > 1000 else repeats)
        e = errors(5e-4, g, ctx)
        rows.append(stage_row("grid", "%d²" % g, result, wall, dict(grid=g, radius_um=500, **e)))
        print("  grid %5d: %.2f s, bow corr err %.3f (rays %.3f), p2 L1 %.3f, supern %.3f°" % (
            g, wall, e["bow_corr"], e["rays_bow_corr"], e["p2_l1"], e["supernumerary_deg"]), flush=True)

    # ---- 2. drop sizes at grid 1000
    print("drop sizes (grid 1000)", flush=True)
    size_grid = 500 if args.quick else 1000
    for r_um in (100, 200, 500):
        result, wall = timed_sphere(r_um * 1e-6, size_grid, ctx, 1)
        e = errors(r_um * 1e-6, size_grid, ctx)
        rows.append(stage_row("size", "%d µm" % r_um, result, wall, dict(grid=size_grid, radius_um=r_um, **e)))
        print("  %d µm: bow corr err %.3f (rays %.3f), p2 L1 %.3f, supern %.3f°, primary %.2f° (rays %.2f°) Mie %.2f°"
              % (r_um, e["bow_corr"], e["rays_bow_corr"], e["p2_l1"], e["supernumerary_deg"], e["primary_deg"],
                 e["rays_primary_deg"], e["mie_primary_deg"]), flush=True)

    # ---- 3. targets
    print("targets", flush=True)
    result, wall = timed_sphere(5e-4, 1000, ctx, repeats)
    rows.append(stage_row("target", "sphere 1000², P=3, 3600 angles, 1 wavelength", result, wall,
                          dict(target_s=10.0)))
    theta2 = np.arange(0.05, 180.0, 0.1)   # 1800
    phi2 = np.arange(-179.5, 180.0, 1.0)  # 360
    drop = rainbow.Raindrop(2e-3)
    walls = []
    for _ in range(1 if args.quick else 2):
        t0 = time.perf_counter()
        r2 = rainbow.phase_function(drop, NM, theta2, phi=phi2, grid=size_grid, max_bounces=3, context=ctx)
        walls.append(time.perf_counter() - t0)
    integral = float(np.sum(r2.unpolarized * np.sin(np.radians(theta2))[:, None]) * math.radians(0.1) * math.radians(1))
    rows.append(stage_row("target", "raindrop 2 mm, 2-D 1800×360, grid %d" % size_grid, r2, statistics.median(walls),
                          dict(target_s=30.0, integral=integral)))
    x_radius = 10000 * NM * 1e-9 / (2 * math.pi)  # size parameter 10 000
    mie_walls = []
    for _ in range(5):
        t0 = time.perf_counter()
        mie.phase_function(x_radius, NM, THETA, n=1.3317)
        mie_walls.append(time.perf_counter() - t0)
    rows.append(dict(section="target", case="Mie x = 10 000, 3600 angles", wall_s=statistics.median(mie_walls),
                     target_s=1.0))
    # every azimuth (no φ filter) at grid 1000: what the 1-D fast path saves
    t0 = time.perf_counter()
    r_all = rainbow.phase_function(rainbow.Sphere(5e-4), NM, THETA, phi=np.array([0.0]), grid=size_grid,
                                   context=ctx)
    rows.append(stage_row("target", "sphere %d², every azimuth kept" % size_grid, r_all, time.perf_counter() - t0))
    ctx.close()

    # ---- outputs
    keys = sorted({k for r in rows for k in r})
    with open(os.path.join(args.out, "rainbow.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    m = machine()
    lines = ["# rainbow_bench", "", "%s, %d cores; device %s; arcus %s; %s" % (
        m["cpu"], m["cores"], m["device"], m["arcus"], m["date"]), "",
             "## Grid against error and time (500 µm sphere, 650 nm, P = 3, 3600 angles)", "",
             "| grid | wall s | cast s | patches s | BVH s | queries s | patches | bow corr err | (rays) | p=2 L1 | "
             "supern. ° |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["section"] == "grid":
            lines.append("| %s | %.2f | %.2f | %.2f | %.2f | %.3f | %d | %.3f | %.3f | %.3f | %.3f |" % (
                r["case"], r["wall_s"], r["cast_s"], r["patches_s"], r["bvh_s"], r["query_s"], r["patches"],
                r["bow_corr"], r["rays_bow_corr"], r["p2_l1"], r["supernumerary_deg"]))
    lines += ["", "## Drop sizes (grid %d)" % size_grid, "",
              "| radius | bow corr err | (rays) | p=2 L1 | supern. ° | primary ° | (rays) | Mie's ° |",
              "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["section"] == "size":
            lines.append("| %s | %.3f | %.3f | %.3f | %.3f | %.2f | %.2f | %.2f |" % (
                r["case"], r["bow_corr"], r["rays_bow_corr"], r["p2_l1"], r["supernumerary_deg"], r["primary_deg"],
                r["rays_primary_deg"], r["mie_primary_deg"]))
    lines += ["", "## Targets", "", "| case | wall s | target s | holds |", "|---|---|---|---|"]
    for r in rows:
        if r["section"] == "target":
            target = r.get("target_s")
            lines.append("| %s | %.2f | %s | %s |" % (r["case"], r["wall_s"], "%.0f" % target if target else "–",
                                                      ("yes" if r["wall_s"] <= target else "NO") if target else "–"))
    lines += ["", "The thesis needed 30 minutes per wavelength for its queries alone (§4.4.3.2)."]
    with open(os.path.join(args.out, "rainbow.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        g = [r for r in rows if r["section"] == "grid"]
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.loglog([r["wall_s"] for r in g], [r["p2_l1"] for r in g], "o-", label="p = 2 vs Debye (L1)")
        ax.loglog([r["wall_s"] for r in g], [r["bow_corr"] for r in g], "s-", label="1 − corr vs Mie, 134–142°")
        ax.loglog([r["wall_s"] for r in g], [r["rays_bow_corr"] for r in g], "s:",
                  label="the same, plain sum of rays (thesis)")
        for r in g:
            ax.annotate(r["case"], (r["wall_s"], r["p2_l1"]), fontsize=8)
        ax.set_xlabel("wall time per wavelength [s]")
        ax.set_ylabel("error")
        ax.set_title("rainbow: error against time (500 µm sphere)")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, "rainbow_error_vs_time.png"), dpi=120)
    except ImportError:
        pass
    print("\n".join(lines))
    print("\nwrote %s/rainbow.md, rainbow.csv, rainbow_error_vs_time.png" % args.out)


if __name__ == "__main__":
    main()
