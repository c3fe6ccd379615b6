#!/usr/bin/env python3
"""spectral_bench — do the sky scenes' wavelengths resolve their interference?

    python3 bench/spectral_bench.py [--out DIR] [--cache DIR] [--quick]

For each bundled rainbow scene of spheres (single sizes and distributions, Mie and the
rays method), the radial profile of the rain's single-scattered light — the scene's
volume table β(θ, λ) lit by the scene's sun, through the CIE 1931 observer and averaged
over the sun's disc — at the scene's own wavelengths (with and without its band
samples) against every 2 nm (161 wavelengths over 380-700 nm) and, for single sizes by
Mie, against the scene's bands each integrated at 0.25 nm.  Reports, over the
scattering angles the scene's image shows, the luminance Y's relative RMS and worst
difference and the chromaticity x, y's worst relative difference; the target is 1 %
for each.  Writes DIR/spectral.md and DIR/spectral.csv.

Left out: scenes whose particles need 2-D tables (falling raindrops, Marshall–Palmer's
flattened drops, oriented crystals; their cost at 161 wavelengths is hours) and the
random crystals of `halo`, whose colours come from dispersion, not interference.
--quick: two scenes, 4 nm.  The tables go to the sweep cache (--cache), so a second run
costs seconds.
"""

import argparse
import copy
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "bindings", "python"))
sys.path.insert(0, HERE)

from arcus import sky, sky_profile  # noqa: E402
from ocean_bench import machine  # noqa: E402  (one description of the machine for every benchmark)
from profiles import band_weights, over_the_sun, write_csv  # noqa: E402

SCENES = ["supernumerary", "supernumerary_200um", "supernumerary_500um", "double_bow", "red_sun", "cloudbow_50um",
          "cloudbow"]
QUICK_SCENES = ["supernumerary", "cloudbow_50um"]
TARGET = 0.01


def profile(doc, wavelengths, cache, band_samples=None):
    """θ, (Y, x, y) over it through the sun's disc, and the table's seconds: at
    ``wavelengths`` with the scene's band samples (or ``band_samples``)."""
    doc = copy.deepcopy(doc)
    doc["tables"]["wavelengths"] = [float(w) for w in wavelengths]
    if band_samples is not None:
        doc["tables"]["band_samples"] = band_samples
    table = sky.volume_table(doc, cache_dir=cache)
    sun = sky.sun_spectrum(doc["sun"], table.wavelengths, sky.atmosphere_of(doc))
    xyz = over_the_sun(table.theta, band_weights(table.wavelengths) @ (sun[:, None] * table.beta[:, 0, :]))
    total = xyz.sum(axis=0)
    return table.theta, xyz[1], xyz[0] / total, xyz[1] / total, table.seconds


def visible_theta(doc, table):
    """The scattering angles at which the scene's image shows rain: (lowest, highest)
    [deg].  Above the horizon only: below it the ground, hit within 200 m by a camera a
    few metres up, hides rain that starts 150 m away or more (every bundled scene), and
    the highest angle above it is 180° less the sun's elevation."""
    theta = sky.render(doc, table=table, width=40, height=30, sun_samples=1, march_steps=1).theta
    return float(theta.min()), float(min(theta.max(), 179.5, 180.0 - doc["sun"]["elevation_deg"]))


def image_profile(doc, wavelengths, cache, band_samples=None):
    """The scene's radial profile as ``arcus render --profile`` draws it — rain, sky and
    ground, every pixel of a 400 × 300 render binned by its angle from the sun every
    0.1° — at ``wavelengths`` (with the scene's band samples, or ``band_samples``)."""
    doc = copy.deepcopy(doc)
    doc["tables"]["wavelengths"] = [float(w) for w in wavelengths]
    if band_samples is not None:
        doc["tables"]["band_samples"] = band_samples
    p = sky_profile.radial_profile(sky.render(doc, width=400, height=300, cache_dir=cache), 0.1)
    return p["theta"], (p["Y"], p["x"], p["y"])


def reference_scene(doc):
    """The 2 nm reference's scene and band samples: a size distribution by Mie takes 200
    moving sizes (the most a population may) and two points a band, 64 400 sizes over the
    161 wavelengths, so that its own size noise stays well below the target (with the
    scene's 48 sizes at every 2 nm, the reference alone put `cloudbow` 1.3 % off)."""
    ref = copy.deepcopy(doc)
    spread = [p for p in ref["rain"]["populations"] if p.get("method") == "mie" and "distribution" in p]
    for p in spread:
        p["bins"] = 200
    return ref, (2 if spread else 1), ("× 200 sizes × 2" if spread else "")


def compare(mine, reference, band):
    """Y's relative RMS and worst difference and x, y's worst relative one over ``band``."""
    relative = (mine[0] - reference[0])[band] / reference[0][band]
    xy = max(np.abs(m - r)[band].max() / r[band].min() for m, r in zip(mine[1:], reference[1:]))
    return float(np.sqrt(np.mean(relative ** 2))), float(np.abs(relative).max()), float(xy)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join("out", "bench", "spectral"))
    ap.add_argument("--cache", default=None, help="the sweep cache (default: arcus' own)")
    ap.add_argument("--quick", action="store_true", help="two scenes against 4 nm")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    step = 4.0 if args.quick else 2.0
    fine = np.arange(380.0, 700.0 + 1e-9, step)
    rows = []
    for name in QUICK_SCENES if args.quick else SCENES:
        doc = sky.load_scene(os.path.join(ROOT, "scenes", "rainbow", name + ".json"))
        own = sky.wavelengths_of(doc["tables"])
        samples = int(doc["tables"].get("band_samples", 1))
        ref_doc, ref_samples, ref_sizes = reference_scene(doc)
        theta, *points, points_seconds = profile(ref_doc, fine, args.cache, band_samples=ref_samples)
        references = {("%g nm points " % step + ref_sizes).strip(): points}
        single_mie = all(p.get("method") == "mie" and "radius" in p for p in doc["rain"]["populations"])
        if single_mie and not args.quick:
            # the bands themselves, each integrated at 0.25 nm: single sizes' Mie ripples
            # (morphology-dependent resonances, ~0.1 nm apart at 0.3 mm) average out
            k = int(round((own[1] - own[0]) / 0.25))
            references["bands at 0.25 nm"] = profile(doc, own, args.cache, band_samples=k)[1:4]
        low, high = visible_theta(doc, sky.volume_table(doc, cache_dir=args.cache))
        band = (theta >= low) & (theta <= high)
        # the scene's whole profile, background included, as the target reads
        pixels_theta, fine_image = image_profile(ref_doc, fine, args.cache, band_samples=ref_samples)
        _, own_image = image_profile(doc, own, args.cache)
        y_rms, y_worst, xy = compare(own_image, fine_image, np.ones(pixels_theta.size, dtype=bool))
        rows.append({"scene": name, "theta_shown": "%.0f-%.0f" % (pixels_theta[0], pixels_theta[-1]),
                     "wavelengths": own.size, "band_samples": samples,
                     "reference": ("%g nm points " % step + ref_sizes).strip() + ": the image's profile (rain, sky, ground)",
                     "Y_rms": y_rms,
                     "Y_worst": y_worst, "xy_worst_relative": xy, "table_seconds": float("nan")})
        print(rows[-1], flush=True)
        for settings in sorted({1, samples}):
            _, *mine, seconds = profile(doc, own, args.cache, band_samples=settings)
            for ref_name, reference in references.items():
                y_rms, y_worst, xy = compare(mine, reference, band)
                rows.append({"scene": name, "theta_shown": "%.0f-%.0f" % (low, high), "wavelengths": own.size,
                             "band_samples": settings, "reference": ref_name, "Y_rms": y_rms, "Y_worst": y_worst,
                             "xy_worst_relative": xy, "table_seconds": round(seconds, 1)})
                print(rows[-1], flush=True)
    write_csv(os.path.join(args.out, "spectral.csv"), rows)
    m = machine()
    lines = ["# Sky scenes: wavelengths against finer spectral integrations", "",
             "The rain's single-scattered light through the sun's disc and the CIE 1931 observer, at each scene's "
             "own wavelengths (× band samples: each table the mean over that many points across its band) against "
             "%d wavelengths at every %g nm, and, for single sizes by Mie, against the scene's own bands each integrated at "
             "0.25 nm; over the scattering angles at which the scene's image shows rain; and the scene's whole "
             "profile (rain, sky and ground, from 400 × 300 renders); target %g %%.  Table seconds: the sweep "
             "(cached tables cost nothing).  %s, %d cores; arcus %s, %s."
             % (fine.size, step, 100 * TARGET, m["cpu"], m["cores"], m["arcus"], m["date"]), "",
             "| scene | θ shown | wavelengths × band samples | reference | Y: RMS | Y: worst | x, y: worst "
             "(relative) | within %g %% |" % (100 * TARGET), "|---|---|---|---|---|---|---|---|"]
    lines += ["| %s | %s° | %d × %d | %s | %.2f%% | %.2f%% | %.2f%% | %s |"
              % (r["scene"], r["theta_shown"], r["wavelengths"], r["band_samples"], r["reference"], 100 * r["Y_rms"],
                 100 * r["Y_worst"], 100 * r["xy_worst_relative"],
                 "yes" if max(r["Y_worst"], r["xy_worst_relative"]) <= TARGET else "no") for r in rows]
    with open(os.path.join(args.out, "spectral.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote %s" % os.path.join(args.out, "spectral.md"))


if __name__ == "__main__":
    main()
