#!/usr/bin/env python3
"""The twinned bow (thesis Fig. 5.24): why a mixture of drop sizes shows two primary bows.

    python3 apps/rainbow/plot_twinned.py [--out out/rainbow] [--grid 1000]

Falling drops above about 1 mm are flattened underneath (the thesis' raindrop, eq. 4.21
with Table 4.4).  Seen at the top of a rainbow — light scattered down to an observer,
the drop's vertical plane, φ = −90° here — a flattened drop bends the primary bow to
a larger scattering angle than the sphere of equal volume, while in its horizontal
plane (a circular section) the bow stays where the sphere has it.  A shower of small,
spherical drops (500 µm radius) mixed with large, flattened ones (2 mm diameter)
therefore shows two bows near the top of the arc: the twinned rainbow.

Writes OUT/twinned.png (phase functions per drop and of the mixture at 650 nm) and
OUT/twinned.csv, and prints the bows' angles.
"""

import argparse
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "bindings", "python"))

import arcus  # noqa: E402
import arcus.rainbow as rainbow  # noqa: E402

NM = 650.0


def bins(theta, y, width=0.1):
    edges = np.arange(theta[0], theta[-1] + 1e-9, width)
    idx = np.digitize(theta, edges) - 1
    centres = 0.5 * (edges[1:] + edges[:-1])
    return centres, np.array([y[idx == k].mean() for k in range(len(centres))])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="out/rainbow")
    ap.add_argument("--grid", type=int, default=1000)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    theta = np.arange(130.0, 150.0, 0.01)
    with arcus.Context() as ctx:
        sphere = rainbow.phase_function(rainbow.Sphere(500e-6), NM, theta, phi=-90.0, grid=args.grid, context=ctx)
        drop = rainbow.phase_function(rainbow.Raindrop(2e-3), NM, theta, phi=-90.0, grid=args.grid, context=ctx)
        level = rainbow.phase_function(rainbow.Raindrop(2e-3), NM, theta, phi=0.0, grid=args.grid, context=ctx)
    # The mixture: equal numbers of both drops, each weighted by the power it scatters
    # (its cross-section times its phase function's normalisation).
    w_sphere = sphere.stats["intercepted"] * float(np.sum(sphere.stats["scattered"]))
    w_drop = drop.stats["intercepted"] * float(np.sum(drop.stats["scattered"]))
    mixture = (w_sphere * sphere.unpolarized + w_drop * drop.unpolarized) / (w_sphere + w_drop)
    c, s_b = bins(theta, sphere.unpolarized)
    _, d_b = bins(theta, drop.unpolarized)
    _, l_b = bins(theta, level.unpolarized)
    _, m_b = bins(theta, mixture)
    bow = rainbow.rainbow_angle(sphere.refractive_index, 2)

    def begins(result):  # where the p = 2 light (the primary bow) starts
        p2 = result.per_bounce[:, 2]
        return float(theta[np.argmax(p2 > 0)]) if np.any(p2 > 0) else float("nan")

    print("geometric bow of a sphere: %.2f°" % bow)
    print("primary bow begins: 500 µm sphere %.2f°, 2 mm raindrop vertical plane %.2f°, horizontal plane %.2f°"
          % (begins(sphere), begins(drop), begins(level)))
    np.savetxt(os.path.join(args.out, "twinned.csv"), np.column_stack([c, s_b, d_b, l_b, m_b]), delimiter=",",
               header="theta_deg,sphere_500um,raindrop_2mm_vertical,raindrop_2mm_horizontal,mixture", comments="")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is missing: wrote the CSV only")
        return
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.semilogy(c, s_b, label="sphere, 500 µm radius")
    ax.semilogy(c, d_b, label="raindrop, 2 mm diameter, vertical plane (top of the bow)")
    ax.semilogy(c, l_b, ":", label="the same raindrop, horizontal plane")
    ax.semilogy(c, m_b, "k", lw=1.5, label="equal numbers of both: the twinned bow")
    ax.axvline(bow, color="grey", lw=0.5)
    ax.set_xlabel("scattering angle [deg]")
    ax.set_ylabel("phase function [1/sr] (0.1° bins)")
    ax.set_title("Twinned primary bow at %.0f nm (thesis Fig. 5.24)" % NM)
    ax.set_ylim(1e-3, None)
    ax.legend(fontsize=7)
    fig.tight_layout()
    path = os.path.join(args.out, "twinned.png")
    fig.savefig(path, dpi=120)
    print("wrote %s and twinned.csv" % path)


if __name__ == "__main__":
    main()
