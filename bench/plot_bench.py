#!/usr/bin/env python3
"""Plots arcus_bench's CSVs as the panels of thesis Fig. 5.13 (a)–(h).

    python3 bench/plot_bench.py [OUT_DIR]     (default out/bench)

Writes OUT_DIR/fig5_13.png (all eight panels), fig5_13_<a..h>.png (one panel each) and
float.png (float against double).  Runs headless: it uses matplotlib's Agg backend.
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # no display needed: the benchmark runs on servers and in CI
import matplotlib.pyplot as plt  # noqa: E402

METHODS = ["euler", "rk2", "rk4", "dp45"]
LABELS = {"euler": "Euler", "rk2": "RK2", "rk4": "RK4", "dp45": "DP45"}
COLORS = {"euler": "tab:blue", "rk2": "tab:orange", "rk4": "tab:green", "dp45": "tab:red", "odeint": "tab:gray"}


def read_rows(path):
    """The rows of one CSV, numbers as floats."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for row in rows:
        for key, value in row.items():
            if key not in ("impl", "method", "precision"):
                row[key] = float(value)
    return rows


def series(rows, x, y, **match):
    """(xs, ys) of the rows whose columns equal `match`, sorted by x."""
    picked = sorted((r[x], r[y]) for r in rows if all(r[k] == v for k, v in match.items()))
    return [p[0] for p in picked], [p[1] for p in picked]


def plot_methods(ax, rows, x, y, methods, peer=False):
    """One line per arcus method (max error solid; mean error dotted when y is the max error);
    the peer's one- and all-thread lines when asked."""
    for m in methods:
        xs, ys = series(rows, x, y, impl="arcus", method=m, precision="double")
        if xs:
            ax.plot(xs, ys, "o-", color=COLORS[m], label=LABELS[m], markersize=4)
        if y == "err_max_m":
            xs, ys = series(rows, x, "err_mean_m", impl="arcus", method=m, precision="double")
            if xs:
                ax.plot(xs, ys, ":", color=COLORS[m], linewidth=1)
    if peer:
        for threads in sorted({r["threads"] for r in rows if r["impl"] == "odeint"}):
            xs, ys = series(rows, x, y, impl="odeint", threads=threads)
            style = "s--" if threads == 1 else "^-."
            ax.plot(xs, ys, style, color=COLORS["odeint"], markersize=4,
                    label=f"odeint dopri5, {int(threads)} thread{'s' if threads > 1 else ''}")


def style_axes(ax, title, xlabel, ylabel, invert_x=False):
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_title(title, fontsize=10)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)
    if invert_x:  # smaller step / tolerance = more accuracy, read left to right
        ax.invert_xaxis()
    ax.legend(fontsize=7)


def panels():
    """The eight Fig. 5.13 panels: (letter, title, csv, x column, x label, y column, methods, peer, invert)."""
    t, e = "time_per_ray_s", "err_max_m"
    fixed, dp, every = METHODS[:3], ["dp45"], METHODS
    return [
        ("a", "(a) time vs step", "step.csv", "step", "step (m)", t, fixed, False, True),
        ("b", "(b) time vs tolerance", "tolerance.csv", "tol", "tolerance", t, dp, True, True),
        ("c", "(c) error vs step", "step.csv", "step", "step (m)", e, fixed, False, True),
        ("d", "(d) error vs tolerance", "tolerance.csv", "tol", "tolerance", e, dp, True, True),
        ("e", "(e) time vs distance", "distance.csv", "length", "path length (m)", t, every, False, False),
        ("f", "(f) error vs distance", "distance.csv", "length", "path length (m)", e, every, False, False),
        ("g", "(g) time vs gradient", "gradient.csv", "gradient", "gradient of n (1/m)", t, every, False, False),
        ("h", "(h) error vs gradient", "gradient.csv", "gradient", "gradient of n (1/m)", e, every, False, False),
    ]


def y_label(column):
    return "time per ray (s)" if column == "time_per_ray_s" else "end-point error (m); dotted: mean"


def draw_panel(ax, out, spec):
    _, title, csv_name, x, xlabel, y, methods, peer, invert = spec
    plot_methods(ax, read_rows(out / csv_name), x, y, methods, peer)
    style_axes(ax, title, xlabel, y_label(y), invert)


def plot_fig5_13(out):
    specs = panels()
    fig, axes = plt.subplots(4, 2, figsize=(11, 16))
    for ax, spec in zip(axes.flat, specs):
        draw_panel(ax, out, spec)
    fig.suptitle("arcus: performance of numerical methods (thesis Fig. 5.13), n = 1 + 0.1·y")
    fig.tight_layout()
    fig.savefig(out / "fig5_13.png", dpi=110)
    plt.close(fig)
    for spec in specs:
        fig, ax = plt.subplots(figsize=(5.5, 4))
        draw_panel(ax, out, spec)
        fig.tight_layout()
        fig.savefig(out / f"fig5_13_{spec[0]}.png", dpi=110)
        plt.close(fig)


def plot_float(out):
    """Speed against error for each float/double pair: what giving up precision buys."""
    rows = read_rows(out / "float.csv")
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for method in ("rk4", "dp45"):
        for precision, marker in (("double", "o"), ("float", "s")):
            pts = [(r["err_max_m"], r["rays_per_s"]) for r in rows if r["method"] == method and r["precision"] == precision]
            if pts:
                ax.plot(*zip(*pts), marker, color=COLORS[method], label=f"{LABELS[method]} {precision}",
                        fillstyle="full" if precision == "double" else "none")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("max end-point error (m)")
    ax.set_ylabel("rays per second")
    ax.set_title("float against double, L = 1000", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "float.png", dpi=110)
    plt.close(fig)


def main():
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/bench")
    plot_fig5_13(out)
    plot_float(out)
    print(f"plots: {out}/fig5_13.png, fig5_13_[a-h].png, float.png")


if __name__ == "__main__":
    main()
