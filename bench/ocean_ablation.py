#!/usr/bin/env python3
"""ocean_ablation — thesis §5.3, Fig. 5.11: Baltic water with every inelastic event,
with none, and without anti-Stokes re-emission, side by side, and what differs.

    python3 bench/ocean_ablation.py [--out DIR] [--width 256] [--height 192]
                                    [--photons 1000000] [--seeds 1 2]

Renders the three bundled scenes scenes/ocean/fig5_11/baltic_inelastic.json,
baltic_no_inelastic.json and baltic_no_anti_stokes.json (the Fig. 5.10 view; by default
at the gallery's size and photons, 256 × 192 and 1 M, where the scenes' own are 512 × 384
and 2 M) with each seed, and their single scattering alone (exact: no photons).  Writes

- DIR/fig5_11.png: the three panels left to right as the thesis shows them (inelastic
  events included; no inelastic scattering; no anti-Stokes), at the scenes' shared
  exposure, from the first seed;
- DIR/fig5_11.md: per panel the image's mean colour (linear sRGB × exposure), its CIE
  1931 chromaticity and luminance, their differences from the left panel, the radiance
  around chlorophyll's 685 nm fluorescence, the same for single scattering alone, and
  the photon noise of each mean (half the spread between the seeds).

The library is the one ``arcus`` finds (ARCUS_LIBRARY picks one).
"""

import argparse
import json
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "bindings", "python"))

import arcus  # noqa: E402
import arcus.image  # noqa: E402
import arcus.ocean as ocean  # noqa: E402

PANELS = [("baltic_inelastic", "inelastic events included"),
          ("baltic_no_inelastic", "no inelastic scattering"),
          ("baltic_no_anti_stokes", "no anti-Stokes interactions")]
# IEC 61966-2-1: linear sRGB to CIE 1931 XYZ (D65); the images are linear sRGB.
SRGB_TO_XYZ = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]])


def scene_doc(name, width, height, photons, seed, multiple=True):
    with open(arcus.bundled_scene("ocean/fig5_11/" + name)) as f:
        doc = json.load(f)
    doc["view"]["camera"].update(width=width, height=height)
    doc["photons"].update(count=photons, seed=seed)
    doc["view"]["march"]["multiple_scattering"] = multiple
    return doc


def encode(linear):
    """8-bit sRGB as the PNG holds it (IEC 61966-2-1's transfer function, clamped)."""
    c = np.clip(linear, 0, 1)
    return np.round(255 * np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055))


def summary(r, exposure):
    """Mean colour (linear sRGB × exposure), the PNG's mean 8-bit sRGB, CIE xy,
    luminance Y, and the mean radiance over 675–695 nm relative to the mean over the grid."""
    pixels = r.image.reshape(-1, 3).astype(float) * exposure
    rgb = pixels.mean(axis=0)
    xyz = SRGB_TO_XYZ @ rgb
    spectrum = r.spectral.mean(axis=(0, 1))
    red = (r.wavelengths >= 675) & (r.wavelengths <= 695)
    return {"rgb": rgb, "png": encode(pixels), "srgb8": encode(pixels).mean(axis=0), "xy": xyz[:2] / xyz.sum(),
            "Y": xyz[1], "red": spectrum[red].mean() / spectrum.mean()}


def pm(values, fmt):
    """The mean of per-seed values, ± half their spread when there are several."""
    v = np.asarray(values, float)
    return fmt % v.mean() + (" ± " + fmt % (np.ptp(v) / 2) if len(v) > 1 else "")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default="out/ocean_ablation")
    p.add_argument("--width", type=int, default=256)
    p.add_argument("--height", type=int, default=192)
    p.add_argument("--photons", type=int, default=1_000_000)
    p.add_argument("--seeds", type=int, nargs="+", default=[1, 2])
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    t0 = time.time()
    with arcus.Context() as ctx:
        exposure = scene_doc(PANELS[0][0], 1, 1, 1, 1)["view"]["march"].get("exposure", 1.0)
        full, single, seconds = {}, {}, {}
        for name, _ in PANELS:
            for seed in a.seeds:
                t = time.time()
                full[name, seed] = ocean.render(scene_doc(name, a.width, a.height, a.photons, seed), context=ctx)
                seconds[name, seed] = time.time() - t
                print("%s seed %d: %.1f s" % (name, seed, seconds[name, seed]), flush=True)
            single[name] = ocean.render(scene_doc(name, a.width, a.height, 1000, 1, multiple=False), context=ctx)
    gap = np.ones((a.height, 4, 3), np.float32)
    row = []
    for i, (name, _) in enumerate(PANELS):
        row += ([gap] if i else []) + [full[name, a.seeds[0]].image * np.float32(exposure)]
    png = os.path.join(a.out, "fig5_11.png")
    arcus.image.write(png, np.concatenate(row, axis=1))

    lines = ["# Thesis Fig. 5.11: Baltic water, inelastic events on, off, and without anti-Stokes", "",
             "arcus %s, %s; %d × %d, %s photons, seeds %s; exposure %g; %.0f s in all." % (
                 arcus.__version__, time.strftime("%Y-%m-%d"), a.width, a.height, format(a.photons, ","),
                 " ".join(map(str, a.seeds)), exposure, time.time() - t0), "",
             "Mean colour: linear sRGB × exposure, averaged over the image; xy: CIE 1931; Y: luminance; "
             "Δ: from the left panel, rendered with the same seed; 685 nm: the mean radiance over 675–695 nm over "
             "the mean over the grid (chlorophyll's fluorescence); largest Δ 8-bit: the largest difference of any "
             "pixel's 8-bit sRGB value (any channel) from the left panel's (with photons: their noise too, since "
             "the switches change the photons' paths); ± half the spread between the seeds (the photon noise).",
             ""]
    for label, images in (("single and multiple scattering", {k: [full[k, s] for s in a.seeds] for k, _ in PANELS}),
                          ("single scattering alone (exact)", {k: [single[k]] for k, _ in PANELS})):
        lines += ["## " + label, "",
                  "| panel | mean linear sRGB | mean 8-bit sRGB (PNG) | x | y | Y | Δxy | ΔY/Y | 685 nm | "
                  "largest Δ 8-bit |", "|---|---|---|---|---|---|---|---|---|---|"]
        ref = [summary(r, exposure) for r in images[PANELS[0][0]]]
        for name, title in PANELS:
            s = [summary(r, exposure) for r in images[name]]
            m = {k: np.mean([v[k] for v in s], axis=0) for k in s[0]}
            lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                title, ", ".join("%.4f" % c for c in m["rgb"]), ", ".join("%.1f" % c for c in m["srgb8"]),
                pm([v["xy"][0] for v in s], "%.5f"), pm([v["xy"][1] for v in s], "%.5f"),
                pm([v["Y"] for v in s], "%.5f"),
                pm([np.linalg.norm(v["xy"] - r["xy"]) for v, r in zip(s, ref)], "%.5f"),
                pm([v["Y"] / r["Y"] - 1 for v, r in zip(s, ref)], "%+.4f"), pm([v["red"] for v in s], "%.3f"),
                pm([np.abs(v["png"] - r["png"]).max() for v, r in zip(s, ref)], "%.0f")))
        lines.append("")
    lines += ["Seconds per full render: " + ", ".join("%s %.1f" % (n, np.mean([seconds[n, s] for s in a.seeds]))
                                                   for n, _ in PANELS), ""]
    md = os.path.join(a.out, "fig5_11.md")
    with open(md, "w") as f:
        f.write("\n".join(lines))
    print("\n".join(lines))
    print("wrote", png, md)


if __name__ == "__main__":
    main()
