#!/usr/bin/env python3
"""halo_bench — what a halo's smoothness costs in time.

    python3 bench/halo_bench.py [--out DIR] [--quick]

The `halo` scene's crystals (scenes/rainbow/halo.json: random 50 µm columns, its
bounces and θ axis) at 550 nm, averaged over N orientations, their glints found two
ways: traced as beams (exact, arcus.rainbow.trace_beams: what the tables use) and cast
as a grid of 32 rays a side (what they used before), with orientations drawn as arcus
draws them (quasi-random over the prism's symmetry wedge, arcus.halo.orientations) or as
independent uniform rotations.  Noise: the relative RMS, over 1° past the halo's edge to
59.5°, of each table (averaged over the sun's disc, 0.533° across, as the sky is) against
a reference of many more beam-traced orientations of another seed (its own noise is
part of what is measured; the grid's bias is part of the grid's).  Then what the sky's wavelengths do
with it: a scene's K wavelengths take K successive runs of N orientations of one
sequence (arcus.sweep.phase_tables), so a colour summed over them averages K·N
orientations: the mean of K such tables at 550 nm against the same reference.  Writes
DIR/halo.md and DIR/halo.csv.
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
    ap.add_argument("--quick", action="store_true", help="N up to 4000 against 20 000 (about a minute on two cores)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    spec, tables = scene_crystals()
    theta = np.round(np.arange(0.0, 60.0 + 1e-9, 0.1), 10)
    bounces = tables.get("max_bounces", halo.MAX_BOUNCES)
    grid = 32  # the halo scene's cast before beams
    # (method, sampling, orientations) per row
    settings = [("beams", "quasi-random", n) for n in ([1000, 4000] if args.quick else [1000, 4000, 16000, 64000])]
    settings += [("beams", "independent", 4000)]
    settings += [("grid %d" % grid, "quasi-random", n) for n in ([500] if args.quick else [1000, 2500])]
    reference_count = 20000 if args.quick else 200000
    edge = halo.halo_angle(NM)
    band = (theta > edge + 1.0) & (theta < 59.5)
    rows = []
    with arcus.Context() as ctx:
        def table(count, method="beams", rotations=None, first=0, seed=spec.get("seed", 1)):
            t = halo.crystal_table(dict(spec, orientations=count, first_orientation=first, seed=seed), NM, theta,
                                   method="grid" if method.startswith("grid") else "beams", grid=grid,
                                   max_bounces=bounces, rotations=rotations, context=ctx)
            return over_the_sun(theta, t["phase"]), t["seconds"]

        def noise(profile):
            relative = (profile[band] - reference[band]) / reference[band]
            return float(np.sqrt(np.mean(relative ** 2))), float(np.max(np.abs(relative)))
        # another seed's sequence: the tables' orientations are not among the reference's
        reference, reference_s = table(reference_count, seed=spec.get("seed", 1) + 100)
        print("reference: %d quasi-random orientations as beams, %.1f s" % (reference_count, reference_s), flush=True)
        for method, sampling, count in settings:
            rotations = independent_rotations(count, spec.get("seed", 1)) if sampling == "independent" else None
            profile, seconds = table(count, method, rotations)
            rms, worst = noise(profile)
            rows.append({"method": method, "sampling": sampling, "orientations": count, "wavelengths": 1,
                         "seconds": round(seconds, 2), "noise": rms, "worst": worst})
            print("%-8s %-13s %6d  %6.1f s  noise %.4f" % (method, sampling, count, seconds, rms), flush=True)
        per_wavelength = 2000
        runs = [table(per_wavelength, first=k * per_wavelength) for k in range(9)]
        for k in (3, 9):
            rms, worst = noise(np.mean([profile for profile, _ in runs[:k]], axis=0))
            rows.append({"method": "beams", "sampling": "successive runs, one per wavelength",
                         "orientations": per_wavelength, "wavelengths": k,
                         "seconds": round(sum(s for _, s in runs[:k]), 2), "noise": rms, "worst": worst})
            print("%d runs of %d: noise %.4f" % (k, per_wavelength, rms), flush=True)
    write_csv(os.path.join(args.out, "halo.csv"), rows)
    m = machine()
    lines = ["# Halo: orientations against noise and time", "",
             "The `halo` scene's columns at %g nm (P = %d, θ step 0.1°), averaged over the sun's disc; "
             "noise: relative RMS from %.1f° to 59.5° against %d quasi-random orientations of another seed "
             "traced as beams "
             "(%.0f s).  %s, %d cores, %s; arcus %s, %s." % (NM, bounces, edge + 1.0, reference_count, reference_s,
                                                            m["cpu"], m["cores"], m["device"], m["arcus"], m["date"]),
             "", "| glints | sampling | orientations | tables averaged | seconds | noise | worst |",
             "|---|---|---|---|---|---|---|"]
    lines += ["| %s | %s | %d | %d | %.1f | %.2f%% | %.1f%% |" % (r["method"], r["sampling"], r["orientations"],
                                                                r["wavelengths"], r["seconds"], 100 * r["noise"],
                                                                100 * r["worst"])
              for r in rows]
    with open(os.path.join(args.out, "halo.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote %s" % os.path.join(args.out, "halo.md"))


if __name__ == "__main__":
    main()
