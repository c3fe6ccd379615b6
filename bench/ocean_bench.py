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
import csv
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

# ---- the plan ---------------------------------------------------------------------------

FULL = dict(
    trace_photons=400_000, trace_presets=("mediterranean", "baltic", "atlantic"), trace_repeats=3,
    size=(128, 96),
    ref=dict(photons=4_000_000, k=250, steps=200),
    noise_photons=1_000_000,
    beam_photons=(100_000, 200_000, 400_000, 800_000), beam_k=(50, 100, 250), beam_steps=(200,),
    beam_extra_steps=(50, 100),      # at (400 000, 250): what the march steps cost and buy
    per_step_photons=(100_000, 400_000), per_step_k=(50, 250), per_step_steps=(200,),
    full_res=True,
    # at 512×384: the reference for the errors there, and the beam's extra photon counts
    full_ref_photons=2_000_000, full_beam_photons=(800_000,),
)
QUICK = dict(
    trace_photons=400_000, trace_presets=("mediterranean", "baltic"), trace_repeats=3,
    size=(32, 24),
    ref=dict(photons=200_000, k=100, steps=100),
    noise_photons=50_000,
    beam_photons=(10_000, 20_000, 40_000), beam_k=(25, 100), beam_steps=(100,),
    beam_extra_steps=(50,),
    per_step_photons=(10_000, 40_000), per_step_k=(25,), per_step_steps=(100,),
    full_res=False,
)
THESIS = dict(size=(512, 384), photons=400_000, k=250, steps=200)   # the image settings of the thesis
TARGET_TRACE_S = 1.0
TARGET_IMAGE_S = 60.0
TARGET_SPEEDUP = 5.0
REF_SEED = 1001                    # the reference
NOISE_SEEDS = (2001, 2002)         # the reference-noise pair
SWEEP_SEED = 7                     # every sweep image (≠ the reference's seeds)


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
           thesis=True):
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
                              (march, "estimator", estimator)):
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
    # estimate at every fourth pixel: docs/benchmarks.md, "the issue-22 target")
    ph, march = doc["photons"], doc["view"]["march"]
    log("  %d×%d, the scene's settings: %d photons, k = %d, every %d pixels ..."
        % (size + (ph["count"], march["k"], march.get("estimate_stride", 1))))
    img, wall = render(ctx, scene_path, doc, size=size, seed=SWEEP_SEED, thesis=False)
    row = image_row("scene default", march["estimator"], size, ph["count"], march["k"], march["steps"], SWEEP_SEED,
                    img, wall, ref)
    log("    total %.2f s, error %.4f spectral, %.4f sRGB" % (row["total_s"], row["err_spectral"], row["err_srgb"]))
    rows.append(row)
    return rows


# ---- analysis ---------------------------------------------------------------------------

def pareto(rows, err="err_spectral", t="total_s"):
    """The rows no cheaper row beats in error, by time."""
    front, best = [], math.inf
    for r in sorted(rows, key=lambda r: (r[t], r[err])):
        if r[err] < best:
            front.append(r)
            best = r[err]
    return front


def equal_error(sweep, err="err_spectral"):
    """Beam against per-step at the per-step estimator's best error."""
    ps = [r for r in sweep if r["estimator"] == "per_step"]
    bm = [r for r in sweep if r["estimator"] == "beam"]
    if not ps or not bm:
        return None
    target = min(ps, key=lambda r: r[err])
    e = target[err]
    front = pareto(bm, err)
    out = dict(per_step=target, error=e, front=front, beam=None, ratio=None, interp_time=None, interp_ratio=None,
               how="")
    hit = next((i for i, r in enumerate(front) if r[err] <= e), None)
    if hit is not None:
        b = front[hit]
        out["beam"], out["ratio"] = b, target["total_s"] / b["total_s"]
        if hit > 0:
            a = front[hit - 1]        # cheaper, error above e: interpolate log t against log error
            f = (math.log(e) - math.log(a[err])) / (math.log(b[err]) - math.log(a[err]))
            out["interp_time"] = math.exp(math.log(a["total_s"]) + f * (math.log(b["total_s"]) - math.log(a["total_s"])))
            out["how"] = "interpolated"
        else:
            out["interp_time"] = b["total_s"]
            out["how"] = "the cheapest beam run already has a lower error (no interpolation: an upper bound on the beam's time)"
    elif len(front) >= 2 and front[-1][err] < front[-2][err]:
        a, b = front[-2], front[-1]   # extrapolate the last segment of the front
        f = (math.log(e) - math.log(a[err])) / (math.log(b[err]) - math.log(a[err]))
        out["interp_time"] = math.exp(math.log(a["total_s"]) + f * (math.log(b["total_s"]) - math.log(a["total_s"])))
        out["how"] = "extrapolated"
    if out["interp_time"]:
        out["interp_ratio"] = target["total_s"] / out["interp_time"]
    return out


# ---- output -----------------------------------------------------------------------------

def fmt(x, spec="%.2f"):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "—"
    return spec % x


def cfg(r):
    return "%s photons, k %d, %d steps" % (fmt_count(r["photons"]), r["k"], r["steps"])


def fmt_count(n):
    return "%gM" % (n / 1e6) if n >= 1_000_000 else "%gk" % (n / 1e3)


def write_csv(path, rows):
    keys = []
    for r in rows:
        for k in r:
            if k not in keys:
                keys.append(k)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in r.items()})


def write_plot(path, sweep, ref, noise, eq):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.2))
    style = dict(beam=("tab:blue", "o", "beam (Jarosz et al. 2008)"), per_step=("tab:red", "s", "per-step k-NN"))
    for ax, err, title in ((axes[0], "err_spectral", "spectral radiance"), (axes[1], "err_srgb", "linear sRGB")):
        for est, (col, mk, label) in style.items():
            rs = [r for r in sweep if r["estimator"] == est]
            if not rs:
                continue
            ax.scatter([r["total_s"] for r in rs], [r[err] for r in rs], color=col, marker=mk, s=28, alpha=0.6)
            front = pareto(rs, err)
            ax.plot([r["total_s"] for r in front], [r[err] for r in front], color=col, marker=mk, label=label + " (Pareto front)")
            for r in rs:
                ax.annotate("%s/%d/%d" % (fmt_count(r["photons"]), r["k"], r["steps"]), (r["total_s"], r[err]),
                            fontsize=6, xytext=(3, 3), textcoords="offset points", color=col)
        ax.axhline(noise[err.split("_")[1]], color="gray", ls="--", lw=1,
                   label="noise of one %s-photon beam image (≥ the reference's)" % fmt_count(noise["photons"]))
        if err == "err_spectral" and eq and eq.get("interp_time"):
            ax.plot([eq["interp_time"]], [eq["error"]], marker="*", ms=14, color="k", ls="none",
                    label="beam at per-step's best error (%s)" % eq["how"].split(" ")[0])
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("render time, total [s]")
        ax.set_ylabel("relative RMS error vs reference (%s)" % title)
        ax.set_title("%s error vs time — %d×%d, reference: beam %s photons, k %d, %d steps"
                     % (title, ref["width"], ref["height"], fmt_count(ref["photons"]), ref["k"], ref["steps"]),
                     fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def equal_error_row(eq, size, note=""):
    """The target row "beam ≥ 5× faster than per-step at equal error" for one size."""
    ps = eq["per_step"]
    if eq["beam"] is not None:
        b = eq["beam"]
        meas = ("per-step's best spectral error %.4f (%s) in %.1f s; cheapest beam run with error ≤ that: %s, "
                "error %.4f, %.1f s → **%.1f×**" % (eq["error"], cfg(ps), ps["total_s"], cfg(b), b["err_spectral"],
                                                    b["total_s"], eq["ratio"]))
        if eq["how"] == "interpolated":
            meas += "; log-log interpolated along the beam's Pareto front: %.1f s → %.1f×" % (
                eq["interp_time"], eq["interp_ratio"])
        res = "PASS" if eq["ratio"] >= TARGET_SPEEDUP else "MISS"
    elif eq["interp_time"]:
        meas = ("per-step's best spectral error %.4f (%s) in %.1f s; no beam run reaches it; extrapolated along "
                "the beam's front: %.1f s → %.1f×" % (eq["error"], cfg(ps), ps["total_s"], eq["interp_time"],
                                                       eq["interp_ratio"]))
        res = ("PASS" if eq["interp_ratio"] >= TARGET_SPEEDUP else "MISS") + " (extrapolated)"
    else:
        meas = "per-step's best error %.4f: no beam run reaches it, no front to extrapolate" % eq["error"]
        res = "undetermined"
    return "| beam ≥ 5× faster than per-step at equal error (times: library total_seconds, %d×%d%s) | %s | %s |" % (
        size[0], size[1], note, meas, res)


def write_md(path, m, args, plan, trace_rows, ref, noise, sweep, full, eq, eq_full, elapsed, loads):
    L = []
    add = L.append
    add("# ocean_bench — what accuracy costs in time%s" % (" (--quick: a smoke test, not numbers to report)"
                                                          if args.quick else ""))
    add("")
    add("Machine: %s, %d cores; OpenCL device %s; arcus %s (%s); Python %s; %s.  Load average before %s, after %s.  "
        "Scene: `%s`.  Run time %.0f s."
        % (m["cpu"], m["cores"], m["device"], m["arcus"], m["library"], m["python"], m["date"], loads[0], loads[1],
           os.path.relpath(args.scene, ROOT), elapsed))
    add("")
    add("## Targets")
    add("")
    add("| target | measured | result |")
    add("|---|---|---|")
    worst = max(trace_rows, key=lambda r: r["wall_s"])
    add("| %s photons traced in < 1 s (every preset; median wall time) | slowest: %s %.3f s wall, %.3f s kernel | %s |"
        % (format(plan["trace_photons"], ",").replace(",", " "), worst["preset"], worst["wall_s"], worst["kernel_s"],
           "PASS" if worst["wall_s"] < TARGET_TRACE_S else "MISS"))
    for est in ("beam", "per_step"):
        r = next((x for x in full if x["estimator"] == est and x["kind"] == "full" and x["photons"] == THESIS["photons"]),
                 None)
        name = "thesis image settings, %s: 512×384, 200 steps, 400 000 photons, k = 250 in < 60 s" % est
        if r is None:
            add("| %s | not run (--quick) | — |" % name)
        elif r.get("cancelled"):
            proj = r["wall_s"] / r["fraction_done"] if r["fraction_done"] > 0 else float("nan")
            add("| %s | > %.0f s: cancelled at %.0f %% (--full-cap), about %.0f s projected | MISS |"
                % (name, r["wall_s"], 100 * r["fraction_done"], proj))
        else:
            add("| %s | %.1f s total (trace %.2f, map %.2f, estimate %.2f; wall %.1f s) | %s |"
                % (name, r["total_s"], r["trace_s"], r["map_s"], r["estimate_s"], r["wall_s"],
                   "PASS" if r["wall_s"] < TARGET_IMAGE_S else "MISS"))
    sd = next((x for x in full if x["kind"] == "scene default"), None)
    if sd is not None:
        thesis_beam = next((x for x in full if x["estimator"] == "beam" and x["kind"] == "full"
                            and x["photons"] == THESIS["photons"] and not x.get("cancelled")), None)
        add("| the scene's own settings (%s photons of several wavelengths, k = %d, the estimate at every 4th pixel) "
            "at 512×384 | %.1f s total; error %.4f spectral, %.4f sRGB (the thesis' settings, beam: %s) | — |"
            % (fmt_count(sd["photons"]), sd["k"], sd["total_s"], sd["err_spectral"], sd["err_srgb"],
               "%.4f, %.4f" % (thesis_beam["err_spectral"], thesis_beam["err_srgb"]) if thesis_beam else "not run"))
    if eq_full is not None:
        add(equal_error_row(eq_full, THESIS["size"], ", the thesis' size"))
    if eq is None:
        add("| beam ≥ 5× faster than per-step at equal error | no per-step runs | — |")
    else:
        add(equal_error_row(eq, (ref["width"], ref["height"]), ", the sweep's size"))
    add("")
    fb = next((x for x in full if x["estimator"] == "beam" and x["kind"] == "full" and not x.get("cancelled")
               and x["photons"] == THESIS["photons"]), None)
    fp = next((x for x in full if x["estimator"] == "per_step" and not x.get("cancelled")), None)
    if fb and fp:
        add("At the thesis' settings (512×384, same photons, k and steps; not equal error) per-step takes %.1f× the "
            "beam's time (total %.1f s against %.1f s)." % (fp["total_s"] / fb["total_s"], fp["total_s"], fb["total_s"]))
        add("")
    add("Equal error means equal spectral error against a beam reference of many photons at the same size (%s "
        "photons at 512×384, %s at the sweep's size), so the per-step estimator's own bias counts against it.  At "
        "the sweep's reduced size the beam's per-image costs that do not depend on the pixels (the photons' radii "
        "and their BVH) weigh more than at 512×384, where the thesis' images are made."
        % (fmt_count(plan.get("full_ref_photons", 0)), fmt_count(plan["ref"]["photons"])))
    add("")
    add("## 1. Photon tracing throughput")
    add("")
    add("%s photons from the scene's lamp, ≤ %d interactions, unbounded water; a warm-up trace per preset, "
        "then the median of %d (seeds 11…).  Wall: the whole `trace_photons` call (water creation, tallies read "
        "back); kernel: the device's time in the trace kernel."
        % (format(plan["trace_photons"], ",").replace(",", " "), trace_rows[0]["max_interactions"],
           plan["trace_repeats"]))
    add("")
    add("| preset | interactions | wall [s] (min–max) | kernel [s] | photons/s (wall) | interactions/s (wall) | "
        "photons/s (kernel) | < 1 s |")
    add("|---|---|---|---|---|---|---|---|")
    for r in trace_rows:
        add("| %s | %d | %.3f (%.3f–%.3f) | %.3f | %.3g | %.3g | %.3g | %s |"
            % (r["preset"], r["interactions"], r["wall_s"], r["wall_min_s"], r["wall_max_s"], r["kernel_s"],
               r["photons_per_s"], r["interactions_per_s"], r["photons_per_kernel_s"],
               "PASS" if r["wall_s"] < TARGET_TRACE_S else "MISS"))
    add("")
    add("## 2. Image error against time (%d×%d)" % (ref["width"], ref["height"]))
    add("")
    add("Reference: beam estimator, %s photons, k = %d, %d steps, seed %d, %d×%d: %.1f s (trace %.2f, map %.2f, "
        "estimate %.2f).  Every sweep image uses seed %d.  Error = relative RMS error against the reference, "
        "√(mean (x − ref)²) / √(mean ref²): *spectral* over all pixels and %d wavelengths of the spectral radiance, "
        "*sRGB* over all pixels and channels of the linear sRGB image."
        % (fmt_count(ref["photons"]), ref["k"], ref["steps"], REF_SEED, ref["width"], ref["height"], ref["total_s"],
           ref["trace_s"], ref["map_s"], ref["estimate_s"], SWEEP_SEED, ref.get("wavelengths", 0)))
    add("")
    best_err = min(r["err_spectral"] for r in sweep)
    add("**Reference noise.**  Two beam images at %s photons (seeds %d, %d; k = %d, %d steps): one image's noise "
        "|A − B|/√2 is %.4f (spectral), %.4f (sRGB) of the reference's RMS.  The reference has %g× the photons, so "
        "its own noise is below that (for a k-nearest estimate at fixed k it falls between N^-1/2 and the beam's "
        "~N^-1/6: %.4f–%.4f spectral).  The smallest tabulated spectral error is %.4f: the reference's noise is at "
        "most %.0f %% of it (%.0f–%.0f %% by the scaling)%s.  The reference's own bias (beam, k = %d at %s "
        "photons) is not in these numbers; the per-step estimator's different bias is."
        % (fmt_count(noise["photons"]), NOISE_SEEDS[0], NOISE_SEEDS[1], ref["k"], ref["steps"], noise["spectral"],
           noise["srgb"], ref["photons"] / noise["photons"],
           noise["spectral"] * (noise["photons"] / ref["photons"]) ** 0.5,
           noise["spectral"] * (noise["photons"] / ref["photons"]) ** (1 / 6), best_err,
           100 * noise["spectral"] / best_err,
           100 * noise["spectral"] * (noise["photons"] / ref["photons"]) ** 0.5 / best_err,
           100 * noise["spectral"] * (noise["photons"] / ref["photons"]) ** (1 / 6) / best_err,
           " — errors near it are limited by the reference, not by the configuration"
           if noise["spectral"] > 0.5 * best_err else "", ref["k"], fmt_count(ref["photons"])))
    add("")
    add("### Side by side (total seconds; spectral / sRGB error)")
    add("")
    add("| photons | k | steps | beam [s] | beam error | per-step [s] | per-step error | per-step / beam time |")
    add("|---|---|---|---|---|---|---|---|")
    keys = sorted({(r["photons"], r["k"], r["steps"]) for r in sweep}, key=lambda x: (x[2] != 200, x[0], x[1], x[2]))
    for key in keys:
        b = next((r for r in sweep if r["estimator"] == "beam" and (r["photons"], r["k"], r["steps"]) == key), None)
        p = next((r for r in sweep if r["estimator"] == "per_step" and (r["photons"], r["k"], r["steps"]) == key), None)
        add("| %s | %d | %d | %s | %s | %s | %s | %s |"
            % (fmt_count(key[0]), key[1], key[2], fmt(b and b["total_s"]),
               "%.4f / %.4f" % (b["err_spectral"], b["err_srgb"]) if b else "—", fmt(p and p["total_s"]),
               "%.4f / %.4f" % (p["err_spectral"], p["err_srgb"]) if p else "not run",
               "%.1f×" % (p["total_s"] / b["total_s"]) if (p and b) else "—"))
    add("")
    add("### Every image: stages")
    add("")
    add("Seconds per stage, wall intervals inside the render that sum to its total: trace (photons), map (k-d map; "
        "beam: + the photons' k-nearest radii and their BVH), estimate (= total − trace − map: light tables, the "
        "march kernel, colour).  `lib est` is the library's own `estimate_seconds`; kernel = device time of the "
        "launches (march; trace).")
    add("")
    add("| kind | estimator | size | photons | k | steps | seed | trace | map | estimate | total | wall | lib est | "
        "kernel | stored | error spectral | error sRGB |")
    add("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in [ref] + noise["rows"] + sweep + full:
        add("| %s | %s | %d×%d | %s | %d | %d | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %d | %s | %s |"
            % (r["kind"] + (" (cancelled)" if r.get("cancelled") else ""), r["estimator"], r["width"], r["height"],
               fmt_count(r["photons"]), r["k"], r["steps"], r["seed"], r["trace_s"], r["map_s"], r["estimate_s"],
               r["total_s"], r["wall_s"], r["lib_estimate_s"], r["kernel_s"], r["photons_stored"],
               fmt(r.get("err_spectral"), "%.4f"), fmt(r.get("err_srgb"), "%.4f")))
    add("")
    if not full:
        add("Full-resolution renders (512×384) skipped: --quick.")
        add("")
    add("Plot: `ocean_error_vs_time.png` (error against total time, log-log; a curve per estimator through its "
        "Pareto front, every run a point labelled photons/k/steps).")
    add("")
    with open(path, "w") as f:
        f.write("\n".join(L))


# ---- main -------------------------------------------------------------------------------

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
    write_md(md, m, args, plan, trace_rows, ref, noise, sweep, full, eq, eq_full, elapsed, (load0, load1))
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
