#!/usr/bin/env python3
"""rainbow_position_grid — the primary bow's maximum and first supernumerary of water
spheres, ray casting with the uniform approximation against Lorenz–Mie, over radii and
wavelengths.

    python3 bench/rainbow_position_grid.py [--out DIR] [--grid N] [--max-bounces P] [--quick]

For every radius of 8 log-spaced from 100 to 1000 µm and every wavelength of 400, 450,
…, 700 nm (water at 20 °C), the 1-D phase function at φ = 0 sampled every 0.01° and
averaged over 0.1° bins, as the tests do (tests/python/test_rainbow.py):

  primary        the bin centre of the largest bin from 1° inside Descartes' angle θ_R
                 (thesis eq. 4.20) to the first Airy minimum;
  supernumerary  the largest bin between Airy theory's first and second minima.

The windows come from geometry alone, not from either curve: near θ_R the two rays of
p = 2 put the Airy pattern at z = x^{2/3} (D''/2)^{-1/3} (θ − θ_R), with x = 2πa/λ and
D'' the second derivative of the deviation D(u) = π + 2 asin u − 4 asin(u/n) in the
impact parameter u = b/a at the rainbow ray (thesis §4.4.1; van de Hulst 1957 §13.2);
Ai(−z)² has its minima at the zeros of Ai, z = 2.338 and 4.088, its maxima at 1.019
and 3.248.  A third figure, "sliding", takes the 0.1° mean at every 0.01° offset
(bins placed anywhere) and its largest value in the same window: it shows how far
apart two maxima really are when they fall on either side of a bin edge.

Besides arcus (P = --max-bounces terms, default 3) against Mie, two diagnostics
separate what the uniform approximation does from what rays leave out:
  p=2 alone      arcus' p = 2 term against Debye's p = 2 term (no interference with
                 other terms: the uniform approximation by itself);
  Debye p≤P      Mie's primary/supernumerary found instead in the coherent sum of the
                 Debye terms p = 0…P, the light arcus traces: where it misses Mie's bin,
                 the terms p > P (rays after P − 1 internal reflections, near grazing
                 incidence, and the surface waves of Mie's remainder), whose ripple
                 rides on the bow, decide the bin.

Writes DIR/rainbow_positions.md (the table) and DIR/rainbow_positions.csv.  The
library is the one ``arcus`` finds (ARCUS_LIBRARY picks one).  See bench/README.md.
"""

import argparse
import csv
import math
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "bindings", "python"))

import arcus  # noqa: E402
import arcus.mie as mie  # noqa: E402
import arcus.rainbow as rainbow  # noqa: E402

RADII_UM = np.geomspace(100.0, 1000.0, 8)
WAVELENGTHS_NM = np.arange(400.0, 700.0 + 1e-9, 50.0)
AI_ZEROS = (2.33810741, 4.08794944)  # −z of the first two zeros of Ai (DLMF Table 9.9.1)
AIRY_MAXIMA = (1.01879297, 3.24819758)  # −z of the first two zeros of Ai'


def airy_scale(n, radius, wavelength_nm):
    """(θ_R [deg], degrees per unit of the Airy variable z) for the primary bow."""
    u = math.sqrt((4.0 - n * n) / 3.0)  # sin i at the rainbow ray: cos² i = (n² − 1)/3
    d2 = 2 * u / (1 - u * u) ** 1.5 - 4 * u / (n ** 3 * (1 - u * u / (n * n)) ** 1.5)
    x = 2 * math.pi * radius / (wavelength_nm * 1e-9)
    theta_r = 180.0 - 2.0 * math.degrees(math.asin(((4.0 - n * n) / 3.0) ** 1.5 / (n * n)))
    return theta_r, math.degrees(1.0 / (x ** (2.0 / 3.0) * (d2 / 2) ** (-1.0 / 3.0)))


def sample_angles(n, radius, wavelength_nm):
    """0.01° samples (at bin centres ± 0.005 …) on whole 0.1° bins covering the windows."""
    theta_r, deg = airy_scale(n, radius, wavelength_nm)
    lo = math.floor((theta_r - 1.0) * 10) / 10
    hi = math.ceil((theta_r + AI_ZEROS[1] * deg + 0.2) * 10) / 10
    return np.round(lo + 0.005 + 0.01 * np.arange(int(round((hi - lo) * 100))), 10)


def positions(theta, y, n, radius, wavelength_nm):
    """The primary maximum and first supernumerary of y(θ) [deg]: bin centres of 0.1°
    bins (whole bins of 10 samples of ``sample_angles``) and the sliding-bin maxima."""
    theta_r, deg = airy_scale(n, radius, wavelength_nm)
    means = np.asarray(y, float).reshape(-1, 10).mean(axis=1)
    centres = np.round(theta.reshape(-1, 10).mean(axis=1), 6)
    sliding = np.convolve(y, np.full(10, 0.1), mode="valid")  # window k covers samples k … k + 9
    s_centres = 0.5 * (theta[:-9] + theta[9:])
    first_min, second_min = theta_r + AI_ZEROS[0] * deg, theta_r + AI_ZEROS[1] * deg
    out = {}
    for name, a, b in (("primary", theta_r - 1.0, first_min), ("supernumerary", first_min, second_min)):
        sel = (centres >= a) & (centres < b)
        out[name] = float(centres[sel][np.argmax(means[sel])])
        sel = (s_centres >= a) & (s_centres < b)
        out[name + "_sliding"] = float(s_centres[sel][np.argmax(sliding[sel])])
    return out


def measure(radius, wavelength_nm, grid, max_bounces, ctx):
    """One (radius, wavelength): the positions of arcus, Mie, arcus' p = 2, Debye's
    p = 2 and Debye's p ≤ P sum, with seconds."""
    n = rainbow.refractive_index("water", wavelength_nm)
    theta = sample_angles(n, radius, wavelength_nm)
    t0 = time.perf_counter()
    r = rainbow.phase_function(rainbow.Sphere(radius), wavelength_nm, theta, grid=grid, max_bounces=max_bounces,
                               context=ctx)
    t1 = time.perf_counter()
    m = mie.phase_function(radius, wavelength_nm, theta, n=n)
    t2 = time.perf_counter()
    d = mie.debye(radius, wavelength_nm, theta, n=n, max_p=max_bounces)
    t3 = time.perf_counter()
    debye_sum = np.abs(d.s1.sum(axis=1)) ** 2 + np.abs(d.s2.sum(axis=1)) ** 2
    row = dict(radius_um=radius * 1e6, wavelength_nm=wavelength_nm, n=n, size_parameter=m.size_parameter,
               arcus_s=t1 - t0, mie_s=t2 - t1, debye_s=t3 - t2, samples=theta.size)
    for name, y in (("arcus", r.unpolarized), ("mie", m.unpolarized), ("arcus_p2", r.per_bounce[:, 2]),
                    ("debye_p2", d.unpolarized[:, 2]), ("debye_sum", debye_sum)):
        for key, value in positions(theta, y, n, radius, wavelength_nm).items():
            row[name + "_" + key] = value
    theta_r, deg = airy_scale(n, radius, wavelength_nm)
    row["theta_r"] = theta_r
    row["airy_primary"] = theta_r + AIRY_MAXIMA[0] * deg
    row["airy_supernumerary"] = theta_r + AIRY_MAXIMA[1] * deg
    return row


def check_mie(radius=1000e-6, nm=400.0):
    """Our Lorenz–Mie (arcus.mie) against an independent one (miepython, Prahl) at
    x = 15 708: the largest |S| difference relative to the largest |S| over the bow."""
    import miepython  # an independent implementation; only this check needs it

    n = rainbow.refractive_index("water", nm)
    theta = sample_angles(n, radius, nm)
    t0 = time.perf_counter()
    m = mie.phase_function(radius, nm, theta, n=n)
    ours = time.perf_counter() - t0
    t0 = time.perf_counter()
    s1, s2 = miepython.S1_S2(n, m.size_parameter, np.cos(np.radians(theta)), norm="wiscombe")
    theirs = time.perf_counter() - t0
    for name, a, b in (("S1", m.s1, s1), ("S2", m.s2, s2)):
        print("Mie x = %.0f, %d angles: max ||%s| − |%s_miepython|| / max |%s| = %.1e (ours %.3f s, miepython "
              "%s %.1f s)" % (m.size_parameter, theta.size, name, name, name,
                              np.max(np.abs(np.abs(a) - np.abs(b))) / np.max(np.abs(a)), ours,
                              miepython.__version__, theirs), flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "bench"))
    ap.add_argument("--grid", type=int, default=600, help="rays a side (600: the tests')")
    ap.add_argument("--max-bounces", type=int, default=3, help="terms p = 0..P (3: arcus' default)")
    ap.add_argument("--quick", action="store_true", help="the grid's corners and centre only")
    ap.add_argument("--check-mie", action="store_true",
                    help="compare our Mie with miepython's (pip install miepython) at the grid's largest size "
                         "parameter, 1000 µm at 400 nm, over the bow's angles, first")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    if args.check_mie:
        check_mie()
    radii, nms = RADII_UM, WAVELENGTHS_NM
    cases = [(r, w) for r in radii for w in nms]
    if args.quick:
        cases = [(radii[i], nms[j]) for i, j in ((0, 0), (0, -1), (-1, 0), (-1, -1), (4, 3))]
    ctx = arcus.Context()
    rainbow.phase_function(rainbow.Sphere(5e-4), 650.0, [138.0], grid=16, context=ctx)  # build the programs once
    rows = []
    t_start = time.perf_counter()
    for r_um, nm in cases:
        row = measure(r_um * 1e-6, nm, args.grid, args.max_bounces, ctx)
        rows.append(row)
        print("%6.1f µm %3.0f nm  primary arcus %.2f Mie %.2f (%+.2f)  supern. arcus %.2f Mie %.2f (%+.2f)"
              "  p=2: %+.2f %+.2f  Debye p≤%d: %.2f %.2f" % (
                  r_um, nm, row["arcus_primary"], row["mie_primary"], row["arcus_primary"] - row["mie_primary"],
                  row["arcus_supernumerary"], row["mie_supernumerary"],
                  row["arcus_supernumerary"] - row["mie_supernumerary"],
                  row["arcus_p2_primary"] - row["debye_p2_primary"],
                  row["arcus_p2_supernumerary"] - row["debye_p2_supernumerary"], args.max_bounces,
                  row["debye_sum_primary"], row["debye_sum_supernumerary"]), flush=True)
    total = time.perf_counter() - t_start
    ctx.close()

    keys = list(rows[0])
    with open(os.path.join(args.out, "rainbow_positions.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    from ocean_bench import machine  # one description of the machine for every benchmark
    m = machine()
    hit = lambda a, b: abs(a - b) < 0.051  # noqa: E731  (the same bin: centres 0.1° apart are not)
    lines = ["# rainbow_position_grid", "",
             "%s, %d cores; device %s; arcus %s; %s; grid %d, P = %d; %.0f s for %d cases" % (
                 m["cpu"], m["cores"], m["device"], m["arcus"], m["date"], args.grid, args.max_bounces, total,
                 len(rows)), "",
             "Bin centres [deg] of 0.1° bins of 0.01° samples; Δ = arcus − Mie; (sliding: the same "
             "with the bins placed anywhere); p=2: arcus' p = 2 term − Debye's; Debye p≤%d: the coherent sum "
             "of Debye's terms 0…%d." % (args.max_bounces, args.max_bounces), "",
             "| radius µm | nm | x | primary arcus | Mie | Δ | (sliding Δ) | p=2 Δ | Debye p≤%d | "
             "supern. arcus | Mie | Δ | (sliding Δ) | p=2 Δ | Debye p≤%d |" % (args.max_bounces, args.max_bounces),
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| %.1f | %.0f | %.0f | %.2f | %.2f | %+.2f | %+.2f | %+.2f | %.2f | %.2f | %.2f | %+.2f | %+.2f "
                     "| %+.2f | %.2f |" % (
                         r["radius_um"], r["wavelength_nm"], r["size_parameter"], r["arcus_primary"],
                         r["mie_primary"], r["arcus_primary"] - r["mie_primary"],
                         r["arcus_primary_sliding"] - r["mie_primary_sliding"],
                         r["arcus_p2_primary"] - r["debye_p2_primary"], r["debye_sum_primary"],
                         r["arcus_supernumerary"], r["mie_supernumerary"],
                         r["arcus_supernumerary"] - r["mie_supernumerary"],
                         r["arcus_supernumerary_sliding"] - r["mie_supernumerary_sliding"],
                         r["arcus_p2_supernumerary"] - r["debye_p2_supernumerary"], r["debye_sum_supernumerary"]))
    for what in ("primary", "supernumerary"):
        lines += ["", "%s, arcus / Mie [deg] (bold: not the same bin)" % what.capitalize(), "",
                  "| radius µm | " + " | ".join("%.0f nm" % w for w in nms) + " |",
                  "|---|" + "---|" * len(nms)]
        for r_um in sorted({r["radius_um"] for r in rows}):
            cells = []
            for w in nms:
                r = next((r for r in rows if r["radius_um"] == r_um and r["wavelength_nm"] == w), None)
                if r is None:
                    cells.append("")
                    continue
                cell = "%.2f / %.2f" % (r["arcus_" + what], r["mie_" + what])
                cells.append(cell if hit(r["arcus_" + what], r["mie_" + what]) else "**%s**" % cell)
            lines.append("| %.1f | %s |" % (r_um, " | ".join(cells)))
    for what in ("primary", "supernumerary"):
        decided = [r for r in rows if abs(r["debye_sum_%s_sliding" % what] - r["mie_%s_sliding" % what]) <= 0.05 + 1e-9]
        within = sum(abs(r["arcus_%s_sliding" % what] - r["mie_%s_sliding" % what]) <= 0.05 + 1e-9 for r in decided)
        lines += ["", "%s, bins placed anywhere: Debye p≤%d within 0.05° of Mie at %d/%d; there, arcus within "
                  "0.05° of Mie at %d/%d; the others: %s" % (
                      what, args.max_bounces, len(decided), len(rows), within, len(decided),
                      ", ".join("%.0f µm %.0f nm" % (r["radius_um"], r["wavelength_nm"]) for r in rows
                                if r not in decided) or "none")]
    for what in ("primary", "supernumerary"):
        full = sum(hit(r["arcus_" + what], r["mie_" + what]) for r in rows)
        p2 = sum(hit(r["arcus_p2_" + what], r["debye_p2_" + what]) for r in rows)
        dsum = sum(hit(r["arcus_" + what], r["debye_sum_" + what]) for r in rows)
        lines += ["", "%s: arcus in Mie's bin %d/%d; p = 2 in Debye's p = 2 bin %d/%d; arcus in the bin of "
                  "Debye p≤%d %d/%d; largest |sliding Δ| %.2f°" % (
                      what, full, len(rows), p2, len(rows), args.max_bounces, dsum, len(rows),
                      max(abs(r["arcus_%s_sliding" % what] - r["mie_%s_sliding" % what]) for r in rows))]
    lines += ["", "seconds per case: arcus %.2f (median), Mie %.3f (largest), Debye %.3f (largest)" % (
        float(np.median([r["arcus_s"] for r in rows])), max(r["mie_s"] for r in rows),
        max(r["debye_s"] for r in rows))]
    with open(os.path.join(args.out, "rainbow_positions.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    print("\nwrote %s/rainbow_positions.md, rainbow_positions.csv" % args.out)


if __name__ == "__main__":
    main()
