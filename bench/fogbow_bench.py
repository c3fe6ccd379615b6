#!/usr/bin/env python3
"""fogbow_bench — what a fog bow's sizes and wavelengths cost, and what too few of them do.

    python3 bench/fogbow_bench.py [--out DIR] [--quick]

The `cloudbow` scene's droplets (scenes/rainbow/cloudbow.json: a gamma distribution of
10 µm effective radius, Lorenz–Mie) as its tables sample them — sizes that move with
the wavelength (arcus.sky.populations), its wavelengths and their band samples — with
fewer or more of each, and the fixed Gauss–Legendre bins arcus took before, against
fixed bins and wavelengths 10× finer in both (5× with --quick).  Each is the volume scattering coefficient β(θ, λ) of the
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
#: Mie calls per wavelength of the fixed Gauss–Legendre bins arcus took before its
#: moving sizes (96 bins, 33 wavelengths); the reference is 10× finer in both.
BEFORE = 96
def scene():
    with open(os.path.join(ROOT, "scenes", "rainbow", "cloudbow.json")) as f:
        return json.load(f)


def fixed_bins(doc, bins, sub):
    """Gauss–Legendre bins, the same at every wavelength (arcus before 0.10's moving
    sizes; the reference, beyond the scene files' 200 bins): [(radii, densities)], one
    per wavelength."""
    population = doc["rain"]["populations"][0]
    log_density, (lo, hi) = _drop_sizes.cloud_droplets(population, population["distribution"], "cloudbow")
    radii, weights = _drop_sizes.gauss_bins(lo, hi, bins)
    log_n = log_density(radii)
    densities = np.exp(log_n - log_n.max()) * weights
    densities *= population["total_density"] / densities.sum()
    return [(radii, densities)] * sub.size


def moving_sizes(doc, bins, sub):
    """The sizes arcus.sky.populations gives the scene's tables: [(radii, densities)], one
    per wavelength."""
    rain = dict(doc["rain"], populations=[dict(doc["rain"]["populations"][0], bins=bins)])
    pops = sky.populations(rain, doc["sun"]["elevation_deg"], sub.size)
    radii = np.array([np.broadcast_to(s["radius"], (sub.size,)) for s, _ in pops])
    densities = np.array([np.broadcast_to(d, (sub.size,)) for _, d in pops])
    return list(zip(radii.T, densities.T))


def profile(doc, bins, wavelengths, band_samples=1, sizes=moving_sizes):
    """(Y, x, y) over THETA, and the seconds its Mie tables took."""
    sub = sky.band_wavelengths(wavelengths, band_samples)
    started = time.perf_counter()
    beta = np.zeros((sub.size, THETA.size))
    for k, (wl, (radii, densities)) in enumerate(zip(sub.ravel(), sizes(doc, bins, sub))):
        for radius, density in zip(radii, densities):
            m = mie.phase_function(radius, wl, THETA)
            beta[k] += density * m.q_sca * np.pi * radius ** 2 * m.unpolarized
    beta = beta.reshape(sub.shape + (THETA.size,)).mean(axis=1)  # each band: its samples' mean
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
    own_samples = int(doc["tables"].get("band_samples", 1))
    lo, hi, count = doc["tables"]["wavelengths"]["linspace"]
    finer = 5 if args.quick else 10
    calls = BEFORE
    reference = profile(doc, calls * finer, np.linspace(lo, hi, (count - 1) * finer + 1), sizes=fixed_bins)
    print("reference: %d fixed bins x %d wavelengths, %.0f s" % (calls * finer, (count - 1) * finer + 1, reference[3]),
          flush=True)
    band = slice(None, np.searchsorted(THETA, 179.5))
    rows = []
    # (sizes, bins, wavelengths, band samples): the fixed bins of before, then the moving
    # sizes at fewer, as many and more Mie calls
    settings = [("fixed", calls, count, 1)]
    settings += [("moving", bins, count, 1) for bins in sorted({12, 24, calls // 2, calls, 2 * calls})]
    settings += [("moving", bins, count, samples) for bins, samples in
                 ((calls // 4, 2), (calls // 2, 2), (calls // 3, 3), (calls, 2), (calls // 2, 4))]
    settings += [("moving", calls, (count - 1) // 2 + 1, 1), ("moving", calls, 2 * (count - 1) + 1, 1)]
    for kind, bins, wavelengths, samples in settings:
        Y, x, y, seconds = profile(doc, bins, np.linspace(lo, hi, wavelengths), samples,
                                   fixed_bins if kind == "fixed" else moving_sizes)
        relative = (Y[band] - reference[0][band]) / reference[0][band]
        rows.append({"sizes": kind, "bins": bins, "wavelengths": wavelengths, "band_samples": samples,
                     "seconds": round(seconds, 2),
                     "Y_rms": float(np.sqrt(np.mean(relative ** 2))), "Y_worst": float(np.abs(relative).max()),
                     "xy_worst": float(max(np.abs(x - reference[1])[band].max(), np.abs(y - reference[2])[band].max()))})
        print(rows[-1], flush=True)
    write_csv(os.path.join(args.out, "fogbow.csv"), rows)
    m = machine()
    lines = ["# Fog bow: size bins against error and time", "",
             "The `cloudbow` scene's droplets (its own: %d moving sizes × %d band samples, %d wavelengths), the "
             "profile of single-scattered light 120°-179.5° from the sun against %d fixed bins × %d wavelengths "
             "(%.0f s of Mie).  %s, %d cores; arcus %s, %s."
             % (own_bins, own_samples, count, calls * finer, (count - 1) * finer + 1, reference[3], m["cpu"],
                m["cores"], m["arcus"], m["date"]),
             "", "| sizes | bins | wavelengths | band samples | Mie s | Y: RMS | Y: worst | x, y: worst |",
             "|---|---|---|---|---|---|---|---|"]
    lines += ["| %s | %d | %d | %d | %.1f | %.2f%% | %.2f%% | %.4f |"
              % (r["sizes"], r["bins"], r["wavelengths"], r["band_samples"], r["seconds"], 100 * r["Y_rms"],
                 100 * r["Y_worst"], r["xy_worst"]) for r in rows]
    with open(os.path.join(args.out, "fogbow.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote %s" % os.path.join(args.out, "fogbow.md"))


if __name__ == "__main__":
    main()
