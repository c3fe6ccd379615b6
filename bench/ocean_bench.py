#!/usr/bin/env python3
"""ocean_bench — what accuracy costs in time, for arcus' ocean engine.

    python3 bench/ocean_bench.py [--out DIR] [--scene scenes/ocean/mediterranean.json] [--quick]

Writes DIR/ocean.md (tables), DIR/ocean.csv (one row per measurement) and
DIR/ocean_error_vs_time.png (image error against time, one curve per estimator):

1. photon tracing throughput (photons/s, interactions/s; 400 000 photons, median of 3
   warm runs) for three presets, and the target "400 000 photons traced in < 1 s";
2. image error against time: a beam reference with many photons at a reduced
   resolution, its own noise (two seeds at a quarter of its photons), and a sweep over
   photons, k and march steps for both estimators (per-step only where affordable);
3. the headline targets: the thesis' image settings (512×384, 200 steps, 400 000
   photons, k = 250) in < 60 s per estimator, and beam ≥ 5× faster than per-step at
   equal error;
4. the machine, the date, arcus' version.

The library is the one ``arcus`` finds (ARCUS_LIBRARY picks one).  See bench/README.md,
"ocean_bench".
"""

import argparse
import datetime
import json
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
import arcus.ocean as ocean  # noqa: E402
from ocean_report import (FULL, NOISE_SEEDS, QUICK, REF_SEED, SWEEP_SEED, THESIS, equal_error,  # noqa: E402
                          write_csv, write_md, write_plot)


def log(msg):
    print(msg, flush=True)


# ---- machine ----------------------------------------------------------------------------

def machine():
    cpu = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        devs = arcus.devices()
        dev = devs[0]
        device = "%s (%s, %d compute units)" % (dev.name, dev.platform, dev.compute_units)
    except Exception as exc:  # the report still says what failed
        device = "unknown device (%s)" % exc
    return dict(cpu=cpu, cores=os.cpu_count(), device=device, arcus=arcus.__version__,
                library=str(arcus.library_path), date=datetime.datetime.now().strftime("%Y-%m-%d %H:%M"),
                python=sys.version.split()[0])


def loadavg():
    try:
        with open("/proc/loadavg") as f:
            return " ".join(f.read().split()[:3])
    except OSError:
        return "n/a"


# ---- 1. tracing throughput --------------------------------------------------------------

def scene_light(doc):
    """The scene's first point light (the image scenes' lamp), for the traces."""
    for L in doc.get("lights", []):
        if L.get("type") == "point":
            return ocean.Light.point(L["position"], L["spectrum"])
    return ocean.Light.point((0.0, 0.0, -10.0), 1.0)


def bench_trace(ctx, doc, plan):
    light = scene_light(doc)
    max_inter = doc.get("photons", {}).get("max_interactions", 5)
    n = plan["trace_photons"]
    rows = []
    for preset in plan["trace_presets"]:
        water = ocean.Water(preset)
        ocean.trace_photons(water, light, photons=n, max_interactions=max_inter, seed=1, context=ctx)  # warm
        walls, kernels, inter = [], [], None
        for rep in range(plan["trace_repeats"]):
            t0 = time.perf_counter()
            r = ocean.trace_photons(water, light, photons=n, max_interactions=max_inter, seed=11 + rep,
                                    context=ctx)
            walls.append(time.perf_counter() - t0)
            kernels.append(r.stats["kernel_seconds"])
            inter = r.tallies["interactions"] if inter is None else inter
        wall, kern = statistics.median(walls), statistics.median(kernels)
        row = dict(kind="trace", preset=preset, photons=n, max_interactions=max_inter,
                   repeats=plan["trace_repeats"], interactions=int(inter), wall_s=wall, kernel_s=kern,
                   wall_min_s=min(walls), wall_max_s=max(walls),
                   photons_per_s=n / wall, interactions_per_s=inter / wall,
                   photons_per_kernel_s=n / kern if kern > 0 else float("nan"))
        log("  trace %-13s %d photons: wall %.3f s (kernel %.3f s), %.3g photons/s, %.3g interactions/s"
            % (preset, n, wall, kern, row["photons_per_s"], row["interactions_per_s"]))
        rows.append(row)
    return rows


# ---- 2. images --------------------------------------------------------------------------

def render(ctx, scene_path, doc, *, size, photons=None, k=None, steps=None, estimator=None, seed, progress=None,
           thesis=True, subsample=None):
    """Renders ``doc`` (the scene read from ``scene_path``) with these settings (None: the
    scene's); returns (OceanImage, wall seconds).  ``thesis``: photons of one wavelength,
    the estimate at every pixel, as the thesis' estimators were compared (§5.3)."""
    d = json.loads(json.dumps(doc))
    if thesis:
        ocean.use_thesis_settings(d)
    d["view"]["camera"]["width"], d["view"]["camera"]["height"] = int(size[0]), int(size[1])
    ph = d.setdefault("photons", {})
    ph["seed"] = int(seed)
    march = d["view"].setdefault("march", {})
    for group, key, value in ((ph, "count", photons), (march, "k", k), (march, "steps", steps),
                              (march, "estimator", estimator), (march, "step_subsample", subsample)):
        if value is not None:
            group[key] = value
    t0 = time.perf_counter()
    img = ocean.render(d, context=ctx, progress=progress)
    return img, time.perf_counter() - t0


def rel_rms(a, ref):
    a, ref = np.asarray(a, dtype=np.float64), np.asarray(ref, dtype=np.float64)
    den = math.sqrt(float(np.mean(ref * ref)))
    return math.sqrt(float(np.mean((a - ref) ** 2))) / den if den > 0 else float("nan")


def image_row(kind, estimator, size, photons, k, steps, seed, img, wall, ref=None):
    s = img.stats
    # The library's stages: trace_seconds, map_seconds (k-d map; for the beam also the
    # photons' radii and their BVH) are wall intervals that partition the render with the
    # rest; its estimate_seconds for the beam also counts the radii and BVH interval
    # (bench/README.md), so the estimate stage here is total − trace − map.
    total, trace, mp = s["total_seconds"], s["trace_seconds"], s["map_seconds"]
    row = dict(kind=kind, estimator=estimator, width=size[0], height=size[1], photons=photons, k=k, steps=steps,
               seed=seed, trace_s=trace, map_s=mp, estimate_s=max(0.0, total - trace - mp),
               lib_estimate_s=s["estimate_seconds"], total_s=total, wall_s=wall,
               kernel_s=s["kernel_seconds"], build_s=s["build_seconds"], photons_stored=int(s["photons_stored"]),
               wavelengths=int(img.spectral.shape[-1]))
    if ref is not None:
        row["err_spectral"] = rel_rms(img.spectral, ref.spectral)
        row["err_srgb"] = rel_rms(img.image, ref.image)
    return row


def bench_images(ctx, scene_path, doc, plan):
    size = plan["size"]
    rows = []
    # warm: each estimator's kernels compiled (or fetched from the caches) before timing
    for est in ("beam", "per_step"):
        img, _ = render(ctx, scene_path, doc, size=(16, 12), photons=5000, k=10, steps=10, estimator=est, seed=1)
        log("  warm-up %-8s build %.2f s" % (est, img.stats["build_seconds"]))

    r = plan["ref"]
    log("  reference: beam, %d photons, k = %d, %d steps, %d×%d, seed %d ..."
        % (r["photons"], r["k"], r["steps"], size[0], size[1], REF_SEED))
    ref, wall = render(ctx, scene_path, doc, size=size, estimator="beam", seed=REF_SEED, **r)
    row = image_row("reference", "beam", size, r["photons"], r["k"], r["steps"], REF_SEED, ref, wall)
    rows.append(row)
    log("    %.1f s" % row["total_s"])

    # the reference's noise: two seeds at a quarter of its photons
    pair = []
    for seed in NOISE_SEEDS:
        img, wall = render(ctx, scene_path, doc, size=size, estimator="beam", seed=seed,
                           photons=plan["noise_photons"], k=r["k"], steps=r["steps"])
        row = image_row("noise", "beam", size, plan["noise_photons"], r["k"], r["steps"], seed, img, wall, ref)
        rows.append(row)
        pair.append(img)
        log("  noise pair seed %d: %d photons, %.1f s, error vs reference %.4f (spectral)"
            % (seed, plan["noise_photons"], row["total_s"], row["err_spectral"]))
    # std of one image at that count: |A − B| / √2, relative to the reference's RMS
    noise = dict(photons=plan["noise_photons"],
                 spectral=rel_rms(pair[0].spectral - pair[1].spectral + ref.spectral, ref.spectral) / math.sqrt(2),
                 srgb=rel_rms(pair[0].image - pair[1].image + ref.image, ref.image) / math.sqrt(2))

    configs = []
    for n in plan["beam_photons"]:
        for k in plan["beam_k"]:
            for st in plan["beam_steps"]:
                configs.append(("beam", n, k, st))
    mid_n = plan["beam_photons"][len(plan["beam_photons"]) // 2]
    for st in plan["beam_extra_steps"]:
        configs.append(("beam", mid_n, max(plan["beam_k"]), st))
    for n in plan["per_step_photons"]:
        for k in plan["per_step_k"]:
            for st in plan["per_step_steps"]:
                configs.append(("per_step", n, k, st))
    for i, (est, n, k, st) in enumerate(configs):
        img, wall = render(ctx, scene_path, doc, size=size, photons=n, k=k, steps=st, estimator=est,
                           seed=SWEEP_SEED)
        row = image_row("sweep", est, size, n, k, st, SWEEP_SEED, img, wall, ref)
        rows.append(row)
        log("  [%2d/%d] %-8s %7d photons k %3d steps %3d: trace %.2f map %.2f estimate %.2f total %.2f s, "
            "error %.4f spectral, %.4f sRGB" % (i + 1, len(configs), est, n, k, st, row["trace_s"], row["map_s"],
                                               row["estimate_s"], row["total_s"], row["err_spectral"],
                                               row["err_srgb"]))
    # the per-step estimate at one step of every m, beside the every-step image of the
    # same photons: its error, and how far it is from the every-step image (its own noise)
    n, k, st = plan["per_step_photons"][-1], max(plan["per_step_k"]), plan["per_step_steps"][0]
    every = None
    for m in plan.get("per_step_subsample", ()):
        if every is None:
            every, _ = render(ctx, scene_path, doc, size=size, photons=n, k=k, steps=st, estimator="per_step",
                              seed=SWEEP_SEED)
        img, wall = render(ctx, scene_path, doc, size=size, photons=n, k=k, steps=st, estimator="per_step",
                           seed=SWEEP_SEED, subsample=m)
        row = image_row("subsample", "per_step", size, n, k, st, SWEEP_SEED, img, wall, ref)
        row.update(subsample=m, err_every_spectral=rel_rms(img.spectral, every.spectral),
                   err_every_srgb=rel_rms(img.image, every.image))
        rows.append(row)
        log("  per-step, one step of every %d: total %.2f s, error %.4f spectral (%.4f from every step)"
            % (m, row["total_s"], row["err_spectral"], row["err_every_spectral"]))
    return rows, noise


def bench_full_res(ctx, scene_path, doc, cap_s, plan):
    """The thesis' settings at 512×384 for both estimators, the beam with more photons
    too, each image's error against a many-photon beam reference at that size: the
    equal-error comparison where the thesis' images are made."""
    size, k, steps = THESIS["size"], THESIS["k"], THESIS["steps"]
    log("  reference %d×%d: beam, %d photons, k = %d, %d steps ..." % (size + (plan["full_ref_photons"], k, steps)))
    ref, wall = render(ctx, scene_path, doc, size=size, photons=plan["full_ref_photons"], k=k, steps=steps,
                       estimator="beam", seed=REF_SEED)
    rows = [image_row("full reference", "beam", size, plan["full_ref_photons"], k, steps, REF_SEED, ref, wall)]
    log("    %.1f s" % rows[0]["total_s"])
    runs = [("beam", THESIS["photons"]), ("per_step", THESIS["photons"])] + [
        ("beam", n) for n in plan["full_beam_photons"]]
    for est, photons in runs:
        log("  %d×%d, %s, %d photons, k = %d, %d steps ..." % (size + (est, photons, k, steps)))
        state = dict(t0=time.perf_counter(), fraction=0.0, cancelled=False)

        def progress(fraction, state=state):
            state["fraction"] = fraction
            if cap_s and time.perf_counter() - state["t0"] > cap_s:
                state["cancelled"] = True
                return True
            return False

        img, wall = render(ctx, scene_path, doc, size=size, photons=photons, k=k, steps=steps, estimator=est,
                           seed=SWEEP_SEED, progress=progress)
        row = image_row("full", est, size, photons, k, steps, SWEEP_SEED, img, wall,
                        None if state["cancelled"] else ref)
        row["cancelled"] = state["cancelled"]
        if state["cancelled"]:
            row["fraction_done"] = state["fraction"]
            log("    cancelled at %.0f %% after %.1f s (--full-cap)" % (100 * state["fraction"], wall))
        else:
            log("    trace %.2f map %.2f estimate %.2f total %.2f s (wall %.2f s), error %.4f spectral"
                % (row["trace_s"], row["map_s"], row["estimate_s"], row["total_s"], row["wall_s"],
                   row["err_spectral"]))
        rows.append(row)
    # the bundled scene's own settings (more photons, each of several wavelengths, the
    # estimate at every fourth pixel: docs/benchmarks_ocean.md, "the issue-22 target")
    ph, march = doc["photons"], doc["view"]["march"]
    log("  %d×%d, the scene's settings: %d photons, k = %d, every %d pixels ..."
        % (size + (ph["count"], march["k"], march.get("estimate_stride", 1))))
    img, wall = render(ctx, scene_path, doc, size=size, seed=SWEEP_SEED, thesis=False)
    row = image_row("scene default", march["estimator"], size, ph["count"], march["k"], march["steps"], SWEEP_SEED,
                    img, wall, ref)
    log("    total %.2f s, error %.4f spectral, %.4f sRGB" % (row["total_s"], row["err_spectral"], row["err_srgb"]))
    rows.append(row)
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=os.path.join("out", "bench"), help="output directory (default out/bench)")
    ap.add_argument("--scene", default=os.path.join(ROOT, "scenes", "ocean", "mediterranean.json"),
                    help="an ocean image scene (default scenes/ocean/mediterranean.json)")
    ap.add_argument("--quick", action="store_true", help="everything small, < 60 s: a smoke test")
    ap.add_argument("--full-cap", type=float, default=0.0, metavar="S",
                    help="cancel a full-resolution render after S seconds and project its time (default: no cap)")
    args = ap.parse_args(argv)
    plan = QUICK if args.quick else FULL
    os.makedirs(args.out, exist_ok=True)
    with open(args.scene) as f:
        doc = json.load(f)
    if "water" not in doc or "view" not in doc:
        ap.error("%s: not an ocean image scene (needs \"water\" and \"view\")" % args.scene)

    t_start = time.perf_counter()
    load0 = loadavg()
    m = machine()
    log("ocean_bench%s: %s, %d cores; %s; arcus %s" % (" --quick" if args.quick else "", m["cpu"], m["cores"],
                                                       m["device"], m["arcus"]))
    ctx = arcus.Context()
    try:
        log("1. tracing throughput")
        trace_rows = bench_trace(ctx, doc, plan)
        log("2. image error against time (%d×%d)" % plan["size"])
        image_rows, noise = bench_images(ctx, args.scene, doc, plan)
        full = []
        if plan["full_res"]:
            log("3. the thesis' image settings at full resolution")
            full = bench_full_res(ctx, args.scene, doc, args.full_cap, plan)
        else:
            log("3. full-resolution renders skipped (--quick)")
    finally:
        ctx.close()
    elapsed = time.perf_counter() - t_start
    load1 = loadavg()

    ref = next(r for r in image_rows if r["kind"] == "reference")
    noise["rows"] = [r for r in image_rows if r["kind"] == "noise"]
    sweep = [r for r in image_rows if r["kind"] == "sweep"]
    eq = equal_error(sweep)
    eq_full = equal_error([r for r in full if r["kind"] == "full" and not r.get("cancelled")])  # the thesis' tracer

    md, csv_path, png = (os.path.join(args.out, n) for n in ("ocean.md", "ocean.csv", "ocean_error_vs_time.png"))
    write_csv(csv_path, trace_rows + image_rows + full)
    write_md(md, m, args, plan, trace_rows, ref, noise, sweep, full, eq, eq_full, elapsed, (load0, load1),
             [r for r in image_rows if r["kind"] == "subsample"])
    write_plot(png, sweep, ref, noise, eq)
    log("")
    with open(md) as f:
        targets = f.read().split("## Targets", 1)[1].split("## 1.", 1)[0].strip()
    log(targets)
    log("")
    log("wrote %s, %s, %s (%.0f s)" % (md, csv_path, png, elapsed))
    return 0


if __name__ == "__main__":
    sys.exit(main())
