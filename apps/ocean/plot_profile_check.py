#!/usr/bin/env python3
"""Checks one sunlit ocean profile of the Monte Carlo engine against the deterministic
discrete-ordinates reference, and draws it.

    python3 apps/ocean/plot_profile_check.py [--out out/ocean] [--photons 200000] [--batches 16]

Configuration: sun at 30 deg (plane irradiance 1 W/m^2/nm on the surface) over a flat
Fresnel surface (n = 1.34), ocean-like water a = 0.05, b = 0.25 /m with a two-term
Henyey-Greenstein phase function (0.983 HG(0.924) + 0.017 HG(-0.2), g = 0.905),
semi-infinite, monochromatic (550 nm, one 1 nm band), no Raman.

The Monte Carlo runs as --batches independent seeds; the points are the batch means and
the error bars +-2 standard errors (batch spread / sqrt(batches)).  E_0 is the engine's
track-length tally, a layer average over --layer m about each depth, so the reference
E_0 is averaged over the same (clipped) layer.

Writes OUT/profile_check.png (E_d, E_u, E_0 against depth, log scale) and
OUT/profile_check.md (the table, with relative differences and deviations in standard
errors), and prints where.  Set ARCUS_LIBRARY to pick a libarcus build.
"""
import argparse
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "bindings" / "python"))

import arcus  # noqa: E402
import arcus.ocean as ocean  # noqa: E402
import arcus.discrete_ordinates as ref  # noqa: E402
import arcus.ocean_reference as ocean_reference  # noqa: E402

A, B = 0.05, 0.25
G_F, G_B, ZETA = 0.924, -0.20, 0.983
SUN, N_WATER = 30.0, 1.34
DEPTHS = np.array([0.0, 1.0, 2.0, 3.0, 5.0, 7.5, 10.0, 15.0, 20.0, 25.0, 30.0, 40.0])
GRID = (550.0, 550.0, 1.0)


def reference(depths, layer, streams=32):
    """E_d, E_u at the planes and E_0 averaged over [z - layer/2, z + layer/2] ∩ water."""
    water = ocean.Water.from_iops(A, B, phase=("two_term_hg", G_F, G_B, ZETA))
    r = ocean_reference.elastic_profile(water, [ocean.Light.sun(SUN, 1.0)], depths, grid=GRID, n_water=N_WATER,
                                        layer=layer, streams=streams)
    return {q: r[q][:, 0] for q in ("Ed", "Eu", "E0")}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=str(REPO / "out" / "ocean"), help="output directory (default out/ocean)")
    p.add_argument("--photons", type=int, default=200_000, help="photons per batch")
    p.add_argument("--batches", type=int, default=16, help="independent seeds")
    p.add_argument("--layer", type=float, default=0.05, help="E_0 layer thickness [m]")
    p.add_argument("--seed", type=int, default=1, help="first seed")
    args = p.parse_args(argv)
    if args.batches < 2:
        p.error("--batches must be >= 2 (the error bars come from their spread)")

    water = ocean.Water.from_iops(A, B, phase=("two_term_hg", G_F, G_B, ZETA))
    t0 = time.perf_counter()
    with arcus.Context() as ctx:
        runs = [ocean.profile(water, SUN, DEPTHS, photons=args.photons, grid=GRID, surface=True, n_water=N_WATER,
                              layer=args.layer, seed=args.seed + k, context=ctx) for k in range(args.batches)]
    seconds = time.perf_counter() - t0
    mc = {}
    for q in ("Ed", "Eu", "E0"):
        rows = np.array([getattr(r, q)[:, 0] for r in runs])
        mc[q] = (rows.mean(axis=0), rows.std(axis=0, ddof=1) / math.sqrt(args.batches))
    past = sum(r.tallies["past_limit"] for r in runs) / sum(r.tallies["emitted"] for r in runs)
    r32 = reference(DEPTHS, args.layer)
    r64 = reference(DEPTHS, args.layer, streams=64)

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 7.0))
    colours = dict(Ed="tab:blue", Eu="tab:red", E0="tab:green")
    labels = dict(Ed="$E_d$", Eu="$E_u$", E0="$E_0$")
    zfine = np.linspace(0.0, DEPTHS[-1], 200)
    rfine = reference(zfine, args.layer)
    for q in ("Ed", "Eu", "E0"):
        mean, se = mc[q]
        ax.plot(rfine[q], zfine, "-", color=colours[q], lw=1.2, label=labels[q] + " reference (discrete ordinates, N = 32)")
        ax.errorbar(mean, DEPTHS, xerr=2 * se, fmt="o", ms=4, mfc="none", color=colours[q], capsize=2,
                    label=labels[q] + " Monte Carlo (±2 SE)")
    ax.set_xscale("log")
    ax.invert_yaxis()
    ax.set_xlabel("irradiance / plane irradiance on the surface")
    ax.set_ylabel("depth [m]")
    ax.set_title(f"Sun {SUN:g}° over a Fresnel surface; a = {A}, b = {B} /m, TTHG g = {ref.two_term_hg(ZETA, G_F, G_B).g:.3f}\n"
                 f"{args.batches} × {args.photons:,} photons, $E_0$ layer {args.layer:g} m", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=2, frameon=False)
    fig.tight_layout()
    png = out / "profile_check.png"
    fig.savefig(png, dpi=130)
    plt.close(fig)

    lines = [f"# Ocean profile check: Monte Carlo vs discrete ordinates",
             "",
             f"Sun {SUN:g}° (plane irradiance 1 on the surface) over a flat Fresnel surface (n = {N_WATER}); "
             f"a = {A} /m, b = {B} /m, phase {ZETA} HG({G_F}) + {1 - ZETA:.3f} HG({G_B}); semi-infinite; 550 nm.",
             f"Monte Carlo: {args.batches} batches × {args.photons:,} photons (seeds {args.seed}..{args.seed + args.batches - 1}), "
             f"{seconds:.1f} s; past the interaction limit: {past:.1e} of the energy.",
             f"Reference: arcus.ocean_reference (discrete ordinates), 32 streams (|32 − 64 streams| ≤ "
             f"{max(np.max(np.abs(r32[q] - r64[q]) / r32[q]) for q in r32):.1e} relative); "
             f"E_0 averaged over the same {args.layer:g} m layer as the tally.",
             "rel. = MC / ref − 1; (n SE) = the difference in Monte Carlo standard errors.",
             "",
             "| depth [m] | E_d MC | E_d ref | E_u MC | E_u ref | E_0 MC | E_0 ref | rel. E_d | rel. E_u | rel. E_0 |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for i, z in enumerate(DEPTHS):
        cells = [f"{z:g}"]
        for q in ("Ed", "Eu", "E0"):
            cells += [f"{mc[q][0][i]:.5e}", f"{r32[q][i]:.5e}"]
        for q in ("Ed", "Eu", "E0"):
            mean, se = mc[q]
            d = mean[i] - r32[q][i]
            cells.append(f"{d / r32[q][i]:+.2%} ({d / se[i]:+.1f} SE)" if se[i] > 0 else f"{d / r32[q][i]:+.2%}")
        lines.append("| " + " | ".join(cells) + " |")
    worst = max(abs(mc[q][0][i] - r32[q][i]) / mc[q][1][i] for q in mc for i in range(DEPTHS.size) if mc[q][1][i] > 0)
    lines += ["", f"Largest deviation: {worst:.2f} standard errors."]
    md = out / "profile_check.md"
    md.write_text("\n".join(lines) + "\n")
    print(f"wrote {png}")
    print(f"wrote {md}")
    print(f"largest deviation {worst:.2f} SE; {args.batches} x {args.photons} photons in {seconds:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
