#!/usr/bin/env python3
"""fogbow_bench — what a fog bow's sizes and wavelengths cost, and what too few of them do.

    python3 bench/fogbow_bench.py [--out DIR] [--quick]

The `cloudbow` scene's droplets (scenes/rainbow/cloudbow.json: a gamma distribution of
10 µm effective radius, Lorenz–Mie) as its tables sample them — its Gauss–Legendre size
bins and its wavelengths — with fewer or more bins, and half or twice the wavelengths,
against an integration 10× finer in
both (5× with --quick).  Each is the volume scattering coefficient β(θ, λ) of the
populations arcus.sky.populations makes, times the scene's daylight sun, summed to
colour (CIE 1931 by Wyman, Sloan & Shirley's 2013 fit, each wavelength weighted by the
band around it, as the renderer weights its samples) and averaged over the sun's disc:
the radial profile of single-scattered light the image shows, 120°-179.5° from the sun.
Error: the relative RMS and largest difference of luminance Y, the largest of the
chromaticities x and y.  Writes DIR/fogbow.md and DIR/fogbow.csv.
"""

import argparse
import json
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "bindings", "python"))

import arcus  # noqa: E402
from arcus import _drop_sizes, mie, sky  # noqa: E402
from ocean_bench import machine  # noqa: E402  (one description of the machine for every benchmark)
from profiles import band_weights, over_the_sun, write_csv  # noqa: E402

THETA = np.round(np.arange(120.0, 180.0 + 1e-9, 0.05), 10)
def scene():
    with open(os.path.join(ROOT, "scenes", "rainbow", "cloudbow.json")) as f:
        return json.load(f)


def profile(doc, bins, wavelengths):
    """(Y, x, y) over THETA, and the seconds its Mie tables took."""
    # The bins as arcus.sky.populations makes them, beyond the scene files' 200.
    population = doc["rain"]["populations"][0]
    log_density, (lo, hi) = _drop_sizes.cloud_droplets(population, population["distribution"], "cloudbow")
    radii, weights = _drop_sizes.gauss_bins(lo, hi, bins)
    log_n = log_density(radii)
    densities = np.exp(log_n - log_n.max()) * weights
    densities *= population["total_density"] / densities.sum()
    started = time.perf_counter()
    beta = np.zeros((wavelengths.size, THETA.size))
    for radius, density in zip(radii, densities):
        for k, wl in enumerate(wavelengths):
            m = mie.phase_function(radius, wl, THETA)
            beta[k] += density * m.q_sca * np.pi * radius ** 2 * m.unpolarized
    seconds = time.perf_counter() - started
    sun = sky.sun_spectrum(doc["sun"], wavelengths, sky.atmosphere_of(doc))
    xyz = band_weights(wavelengths) @ (sun[:, None] * beta)
    xyz = over_the_sun(THETA, xyz)
    total = xyz.sum(axis=0)
    return xyz[1], xyz[0] / total, xyz[1] / total, seconds


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join("out", "bench", "fogbow"))
    ap.add_argument("--quick", action="store_true", help="against a 5× finer integration (minutes, not ten)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    doc = scene()
    own_bins = int(doc["rain"]["populations"][0]["bins"])
    lo, hi, count = doc["tables"]["wavelengths"]["linspace"]
    finer = 5 if args.quick else 10
    reference = profile(doc, own_bins * finer, np.linspace(lo, hi, (count - 1) * finer + 1))
    print("reference: %d bins x %d wavelengths, %.0f s" % (own_bins * finer, (count - 1) * finer + 1, reference[3]),
          flush=True)
    band = slice(None, np.searchsorted(THETA, 179.5))
    rows = []
    settings = [(bins, count) for bins in sorted({4, 8, 16, 24, own_bins, 2 * own_bins})]
    settings += [(own_bins, (count - 1) // 2 + 1), (own_bins, 2 * (count - 1) + 1)]
    for bins, wavelengths in settings:
        Y, x, y, seconds = profile(doc, bins, np.linspace(lo, hi, wavelengths))
        relative = (Y[band] - reference[0][band]) / reference[0][band]
        rows.append({"bins": bins, "wavelengths": wavelengths, "seconds": round(seconds, 2),
                     "Y_rms": float(np.sqrt(np.mean(relative ** 2))), "Y_worst": float(np.abs(relative).max()),
                     "xy_worst": float(max(np.abs(x - reference[1])[band].max(), np.abs(y - reference[2])[band].max()))})
        print(rows[-1], flush=True)
    write_csv(os.path.join(args.out, "fogbow.csv"), rows)
    m = machine()
    lines = ["# Fog bow: size bins against error and time", "",
             "The `cloudbow` scene's droplets (its own: %d bins, %d wavelengths), the profile of single-scattered "
             "light 120°-179.5° from the sun against %d bins × %d wavelengths (%.0f s of Mie).  %s, %d cores; "
             "arcus %s, %s." % (own_bins, count, own_bins * finer, (count - 1) * finer + 1, reference[3], m["cpu"],
                               m["cores"], m["arcus"], m["date"]),
             "", "| size bins | wavelengths | Mie s | Y: RMS | Y: worst | x, y: worst |", "|---|---|---|---|---|---|"]
    lines += ["| %d | %d | %.1f | %.2f%% | %.2f%% | %.4f |" % (r["bins"], r["wavelengths"], r["seconds"],
                                                           100 * r["Y_rms"], 100 * r["Y_worst"], r["xy_worst"])
              for r in rows]
    with open(os.path.join(args.out, "fogbow.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote %s" % os.path.join(args.out, "fogbow.md"))


if __name__ == "__main__":
    main()
