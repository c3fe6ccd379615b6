#!/usr/bin/env python3
"""halo_bench — what a halo's smoothness costs in time.

    python3 bench/halo_bench.py [--out DIR] [--quick]

The `halo` scene's crystals (scenes/rainbow/halo.json: random 50 µm columns, its grid,
bounces and θ axis) at 550 nm, averaged over N orientations drawn two ways: as arcus
draws them (quasi-random over the prism's symmetry wedge, arcus.halo.orientations) and
as independent uniform rotations (normalised Gaussian quaternions, what arcus drew before
this benchmark).  Noise: the relative RMS, over 1° past the halo's edge to 59.5°, of each table
(averaged over the sun's disc, 0.533° across, as the sky is) against a reference of
many more quasi-random orientations (its own noise is part of what is measured).
Then what the sky's wavelengths do with it: a scene's K wavelengths take K successive
runs of N orientations of one sequence (arcus.sweep.phase_tables), so a colour summed
over them averages K·N orientations: the mean of K such tables at 550 nm against the
same reference.  Writes DIR/halo.md and DIR/halo.csv.
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
import arcus.halo as halo  # noqa: E402
from ocean_bench import machine  # noqa: E402  (one description of the machine for every benchmark)
from profiles import over_the_sun, write_csv  # noqa: E402

NM = 550.0


def scene_crystals():
    """The halo scene's crystal spec and table settings."""
    with open(os.path.join(ROOT, "scenes", "rainbow", "halo.json")) as f:
        scene = json.load(f)
    population = scene["rain"]["populations"][0]
    spec = {"kind": "crystal", "shape": population["crystal"], "size": population["size"],
            "orientation": population["orientation"], "seed": population["seed"]}
    return spec, scene["tables"]


def independent_rotations(count, seed):
    """Uniform on SO(3), independently: normalised Gaussian quaternions."""
    q = np.random.default_rng(seed).standard_normal((count, 4))
    w, x, y, z = (q / np.linalg.norm(q, axis=1, keepdims=True)).T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=-1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=-1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=-1)], axis=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join("out", "bench", "halo"))
    ap.add_argument("--quick", action="store_true", help="N up to 1000 against 8000, runs of 250 (about 3 minutes on two cores)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    spec, tables = scene_crystals()
    theta = np.round(np.arange(0.0, 60.0 + 1e-9, 0.1), 10)
    grid, bounces = tables.get("grid", halo.GRID), tables.get("max_bounces", halo.MAX_BOUNCES)
    counts = [250, 500, 1000] if args.quick else [250, 500, 1000, 2000, 4000]
    reference_count = 8000 if args.quick else 20000
    edge = halo.halo_angle(NM)
    band = (theta > edge + 1.0) & (theta < 59.5)
    rows = []
    with arcus.Context() as ctx:
        def table(count, rotations=None, first=0):
            t = halo.crystal_table(dict(spec, orientations=count, first_orientation=first), NM, theta, grid=grid,
                                   max_bounces=bounces, rotations=rotations, context=ctx)
            return over_the_sun(theta, t["phase"]), t["seconds"]

        def noise(profile):
            relative = (profile[band] - reference[band]) / reference[band]
            return float(np.sqrt(np.mean(relative ** 2))), float(np.max(np.abs(relative)))
        reference, reference_s = table(reference_count)
        print("reference: %d quasi-random orientations, %.1f s" % (reference_count, reference_s), flush=True)
        for count in counts:
            for sampling in ("quasi-random, symmetry wedge", "independent"):
                rotations = independent_rotations(count, spec.get("seed", 1)) if sampling == "independent" else None
                profile, seconds = table(count, rotations)
                rms, worst = noise(profile)
                rows.append({"sampling": sampling, "orientations": count, "wavelengths": 1,
                             "seconds": round(seconds, 2), "noise": rms, "worst": worst})
                print("%-30s %5d  %6.1f s  noise %.3f" % (sampling, count, seconds, rms), flush=True)
        per_wavelength = 1000 if not args.quick else 250
        runs = [table(per_wavelength, first=k * per_wavelength) for k in range(9)]
        for k in (3, 9):
            rms, worst = noise(np.mean([profile for profile, _ in runs[:k]], axis=0))
            rows.append({"sampling": "successive runs, one per wavelength", "orientations": per_wavelength,
                         "wavelengths": k, "seconds": round(sum(s for _, s in runs[:k]), 2), "noise": rms,
                         "worst": worst})
            print("%d runs of %d: noise %.3f" % (k, per_wavelength, rms), flush=True)
    write_csv(os.path.join(args.out, "halo.csv"), rows)
    m = machine()
    lines = ["# Halo: orientations against noise and time", "",
             "The `halo` scene's columns at %g nm (grid %d, P = %d, θ step 0.1°), averaged over the sun's disc; "
             "noise: relative RMS from %.1f° to 59.5° against %d quasi-random orientations (%.0f s).  "
             "%s, %d cores, %s; arcus %s, %s." % (NM, grid, bounces, edge + 1.0, reference_count, reference_s,
                                                  m["cpu"], m["cores"], m["device"], m["arcus"], m["date"]),
             "", "| sampling | orientations | tables averaged | seconds | noise | worst |", "|---|---|---|---|---|---|"]
    lines += ["| %s | %d | %d | %.1f | %.1f%% | %.0f%% |" % (r["sampling"], r["orientations"], r["wavelengths"],
                                                           r["seconds"], 100 * r["noise"], 100 * r["worst"])
              for r in rows]
    with open(os.path.join(args.out, "halo.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote %s" % os.path.join(args.out, "halo.md"))


if __name__ == "__main__":
    main()
