#!/usr/bin/env python3
"""sky_bench — what accuracy costs in time, for arcus' rainbow skies.

    python3 bench/sky_bench.py [--out DIR] [--quick] [--cache DIR]

Writes DIR/sky.md (tables) and DIR/sky.csv (one row per measurement):

1. Accuracy against time, one knob at a time, for a Marshall–Palmer rain (5 mm/h,
   drops 0.2–1.2 mm, Lorenz–Mie tables: the renderer's own discretisation is measured,
   not the phase functions') at 400 × 300 before a dark cloud: the wavelength count
   (8, 16, 33, 66), the drop-size bins (1, 2, 4, 8), the points over the sun's disc
   (1, 4, 16) and the march steps (1, 4, 16, 64), each against a reference of 99
   wavelengths, 16 bins, 64 sun points and 256 steps.  Error: the RMS difference of the
   linear sRGB image over the reference's RMS, and the same for luminance Y.  Time per
   stage: the tables (the sweep; "computed" tables are new, the rest read from the
   cache) and the render (the disc average, the march, colour).
2. The target: the five scenes of the thesis' Fig. 5.25 (scenes/rainbow: cloudbow_50um,
   marshall_palmer, double_bow, twinned, supernumerary_200um) at 800 × 600 from cached
   tables in ≤ 10 s each on two cores: each is rendered once to fill the cache, then
   timed from the cache (reading the tables, summing them, rendering).
3. What a sky image costs: double_bow (a Rayleigh sky spectrum) against storm_sky (the
   same rain and tables before data/rainbow/sky/storm_sky.png), render time only, the
   median of 5 each.
4. The machine, the date, arcus' version.

The library is the one ``arcus`` finds (ARCUS_LIBRARY picks one).
"""

import argparse
import copy
import csv
import importlib.util
import os
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "bindings", "python"))

import arcus  # noqa: E402
from arcus import sky  # noqa: E402
from ocean_bench import loadavg, machine  # noqa: E402  (one description of the machine for every benchmark)

THESIS_SCENES = ["cloudbow_50um", "marshall_palmer", "double_bow", "twinned", "supernumerary_200um"]
REFERENCE = dict(wavelengths=99, bins=16, sun_samples=64, march_steps=256)
KNOBS = {"wavelengths": [8, 16, 33, 66], "bins": [1, 2, 4, 8], "sun_samples": [1, 4, 16], "march_steps": [1, 4, 16, 64]}


def knob_scene(wavelengths, bins, **_):
    """The accuracy scene: Marshall–Palmer rain of spheres (Lorenz–Mie) at 400 × 300."""
    scene = sky.load_scene(os.path.join(ROOT, "scenes", "rainbow", "marshall_palmer.json"))
    scene = copy.deepcopy(scene)
    scene["image"].update(width=400, height=300)
    scene["rain"]["populations"] = [{"shape": "sphere", "distribution": "marshall_palmer", "rain_rate_mm_h": 5,
                                     "diameter_range_mm": [0.2, 1.2], "bins": bins, "method": "mie",
                                     "nonspherical_above_mm": 100.0}]
    scene["tables"].update(wavelengths={"linspace": [380, 700, wavelengths]}, theta={"range": [100, 180, 0.05]})
    return scene


def relative_rms(image, reference):
    return float(np.sqrt(np.mean((image - reference) ** 2)) / np.sqrt(np.mean(reference ** 2)))


def run_knob(settings, ctx, cache, reference=None):
    scene = knob_scene(**settings)
    table = sky.volume_table(scene, cache_dir=cache)
    t0 = time.perf_counter()
    result = sky.render(scene, table=table, sun_samples=settings["sun_samples"],
                        march_steps=settings["march_steps"], context=ctx)
    render_s = time.perf_counter() - t0
    row = dict(settings, table_s=table.seconds, computed=table.computed, cached=table.cached, render_s=render_s)
    if reference is not None:
        row["rgb_error"] = relative_rms(result.image, reference.image)
        row["y_error"] = relative_rms(result.xyz[..., 1], reference.xyz[..., 1])
    return row, result


def thesis_scene(name, ctx, cache):
    path = os.path.join(ROOT, "scenes", "rainbow", name + ".json")
    sky.render(path, cache_dir=cache, context=ctx)  # fills the cache (and compiles the kernel)
    t0 = time.perf_counter()
    result = sky.render(path, cache_dir=cache, context=ctx)
    total = time.perf_counter() - t0
    return dict(scene=name, width=result.image.shape[1], height=result.image.shape[0],
                wavelengths=result.table.wavelengths.size, tables=result.table.cached + result.table.computed,
                table_s=result.seconds["table"], render_s=result.seconds["render"], total_s=total,
                features=" ".join(sorted(result.features)) or "none")


def storm_sky_scene(folder):
    """scenes/rainbow/storm_sky.json as a dict, its panorama made in `folder` when the
    data folder has none (data/rainbow/sky/make_storm_sky.py writes it; it is not shipped)."""
    scene = sky.load_scene(os.path.join(ROOT, "scenes", "rainbow", "storm_sky.json"))
    made = os.path.join(ROOT, "data", "rainbow", "sky", "storm_sky.png")
    if not os.path.exists(made):
        spec = importlib.util.spec_from_file_location("make_storm_sky", os.path.join(os.path.dirname(made),
                                                                                        "make_storm_sky.py"))
        maker = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(maker)
        made = os.path.join(folder, "storm_sky.png")
        maker.write(made)
    scene["background"]["sky"]["image"] = made
    return scene


def image_sky_cost(ctx, cache, repeats=5):
    """Median render seconds of the same rain before a sky spectrum and a sky image."""
    out = []
    with tempfile.TemporaryDirectory() as folder:
        scenes = ((os.path.join(ROOT, "scenes", "rainbow", "double_bow.json"), "double_bow", "Rayleigh spectrum"),
                  (storm_sky_scene(folder), "storm_sky", "image, 1024 × 512 PNG"))
        for scene, name, background in scenes:
            table = sky.render(scene, cache_dir=cache, context=ctx).table
            times = [sky.render(scene, table=table, context=ctx).seconds["render"] for _ in range(repeats)]
            out.append(dict(scene=name, background=background, render_s=float(np.median(times))))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "bench"))
    ap.add_argument("--cache", default=None, help="the phase-table cache (default: the sweep's)")
    ap.add_argument("--quick", action="store_true", help="fewer settings, smaller reference (a smoke run)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    start = time.perf_counter()
    reference = dict(REFERENCE)
    knobs = KNOBS
    if args.quick:
        reference = dict(wavelengths=33, bins=4, sun_samples=16, march_steps=64)
        knobs = {"wavelengths": [8, 16], "bins": [1, 2], "sun_samples": [1, 4], "march_steps": [1, 4]}

    rows = []
    with arcus.Context() as ctx:
        ref_row, ref = run_knob(reference, ctx, args.cache)
        ref_row.update(knob="reference", rgb_error=0.0, y_error=0.0)
        rows.append(ref_row)
        for knob, values in knobs.items():
            for v in values:
                row, _ = run_knob(dict(reference, **{knob: v}), ctx, args.cache, ref)
                row["knob"] = knob
                rows.append(row)
                print("%-12s %-4s rgb %.2e  Y %.2e  table %.2f s (%d new)  render %.3f s"
                      % (knob, v, row["rgb_error"], row["y_error"], row["table_s"], row["computed"],
                         row["render_s"]), flush=True)
        scenes = [] if args.quick else [thesis_scene(name, ctx, args.cache) for name in THESIS_SCENES]
        for s in scenes:
            print("%-20s %d × %d: %.2f s from cached tables (tables %.2f s, render %.2f s)"
                  % (s["scene"], s["width"], s["height"], s["total_s"], s["table_s"], s["render_s"]), flush=True)
        backgrounds = [] if args.quick else image_sky_cost(ctx, args.cache)

    m = machine()
    fields = ["knob", "wavelengths", "bins", "sun_samples", "march_steps", "rgb_error", "y_error", "table_s",
              "computed", "cached", "render_s"]
    with open(os.path.join(args.out, "sky.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    lines = ["# Rainbow skies: what accuracy costs in time", "",
             "Machine: %s, %d cores; device %s; arcus %s; %s; load average %s; %.0f s in all."
             % (m["cpu"], m["cores"], m["device"], m["arcus"], m["date"], loadavg(), time.perf_counter() - start), "",
             "## Accuracy against time (Marshall–Palmer spheres, Lorenz–Mie tables, 400 × 300)", "",
             "Reference: %(wavelengths)d wavelengths, %(bins)d size bins, %(sun_samples)d sun points, "
             "%(march_steps)d march steps.  Error: RMS of the difference over the reference's RMS." % reference, "",
             "| knob | value | sRGB error | Y error | tables [s] (new) | render [s] |", "|---|---|---|---|---|---|"]
    for r in rows:
        value = "—" if r["knob"] == "reference" else r[r["knob"]]
        lines.append("| %s | %s | %.2e | %.2e | %.2f (%d) | %.3f |" % (r["knob"], value, r["rgb_error"], r["y_error"],
                                                                        r["table_s"], r["computed"], r["render_s"]))
    if scenes:
        lines += ["", "## Target: the five thesis scenes (Fig. 5.25) at 800 × 600 from cached tables, ≤ 10 s each", "",
                  "| scene | wavelengths | tables | tables from cache [s] | render [s] | total [s] | features | target |",
                  "|---|---|---|---|---|---|---|---|"]
        for s in scenes:
            lines.append("| %s | %d | %d | %.2f | %.2f | %.2f | %s | %s |"
                         % (s["scene"], s["wavelengths"], s["tables"], s["table_s"], s["render_s"], s["total_s"],
                            s["features"], "PASS" if s["total_s"] <= 10 else "MISS"))
    if backgrounds:
        lines += ["", "## What a sky image costs (800 × 600, 33 wavelengths, render only, median of 5)", "",
                  "| scene | sky | render [s] |", "|---|---|---|"]
        lines += ["| %s | %s | %.3f |" % (b["scene"], b["background"], b["render_s"]) for b in backgrounds]
    text = "\n".join(lines) + "\n"
    with open(os.path.join(args.out, "sky.md"), "w") as f:
        f.write(text)
    print(text)
    print("wrote %s" % os.path.join(args.out, "sky.md"))


if __name__ == "__main__":
    main()
