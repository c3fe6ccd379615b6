"""ocean_report — the ocean benchmark's plan, its targets and its report.

What bench/ocean_bench.py measures (the plans and the targets) and what it makes of the
rows it measured: the Pareto fronts, the beam against the per-step estimate at equal
error, and the files it writes (ocean.md, ocean.csv, ocean_error_vs_time.png).
bench/README.md, "ocean_bench", says what each row is.
"""

import csv
import math
import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


# ---- the plan ---------------------------------------------------------------------------

FULL = dict(
    trace_photons=400_000, trace_presets=("mediterranean", "baltic", "atlantic"), trace_repeats=3,
    size=(128, 96),
    ref=dict(photons=4_000_000, k=250, steps=200),
    noise_photons=1_000_000,
    beam_photons=(100_000, 200_000, 400_000, 800_000), beam_k=(50, 100, 250), beam_steps=(200,),
    beam_extra_steps=(50, 100),      # at (400 000, 250): what the march steps cost and buy
    per_step_photons=(100_000, 400_000), per_step_k=(50, 250), per_step_steps=(200,),
    per_step_subsample=(4, 16),      # at the most photons and k: one step of every m (march.step_subsample)
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
    per_step_subsample=(4,),
    full_res=False,
)
THESIS = dict(size=(512, 384), photons=400_000, k=250, steps=200)   # the image settings of the thesis
TARGET_TRACE_S = 1.0
TARGET_IMAGE_S = 60.0
TARGET_SPEEDUP = 5.0
REF_SEED = 1001                    # the reference
NOISE_SEEDS = (2001, 2002)         # the reference-noise pair
SWEEP_SEED = 7                     # every sweep image (≠ the reference's seeds)


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


def write_md(path, m, args, plan, trace_rows, ref, noise, sweep, full, eq, eq_full, elapsed, loads, subsampled=()):
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
    if subsampled:
        n, k, st = subsampled[0]["photons"], subsampled[0]["k"], subsampled[0]["steps"]
        every = next((r for r in sweep if r["estimator"] == "per_step" and (r["photons"], r["k"], r["steps"]) == (n, k, st)),
                     None)
        add("")
        add("### Per-step with step subsampling (%s photons, k = %d, %d steps)" % (fmt_count(n), k, st))
        add("")
        add("`march.step_subsample` m: the estimate at one step of every m, jittered per pixel, weighted by m "
            "(unbiased); the same photons as the sweep's every-step image.")
        add("")
        add("| m | total [s] | error spectral / sRGB | vs every step: spectral / sRGB |")
        add("|---|---|---|---|")
        for r in ([every] if every else []) + list(subsampled):
            add("| %d | %s | %.4f / %.4f | %s |" % (r.get("subsample", 1), fmt(r["total_s"]), r["err_spectral"], r["err_srgb"],
                                                 "%.4f / %.4f" % (r["err_every_spectral"], r["err_every_srgb"])
                                                 if "err_every_spectral" in r else "—"))
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
    for r in [ref] + noise["rows"] + sweep + list(subsampled) + full:
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

