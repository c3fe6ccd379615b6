#!/usr/bin/env python3
"""Derives data/ocean/presets.csv from the COASTℓOOC field data in data/ocean/coastlooc/.

One method for all five presets (sources: data/ocean/README.md, "presets.csv"):

- chlorophyll C: the median surface HPLC chlorophyll a of the preset's stations (100308);
- a_NAP(443) = A_STAR_NAP_443 × the median suspended particulate matter of those
  stations (100306), A_STAR_NAP_443 a published mass-specific NAP absorption at 443 nm,
  so no wavelength shift is needed;
- a_CDOM(443) = a published regional a_CDOM(λ0) × exp(−S (443 − λ0)), S the median CDOM
  slope of the preset's stations (100310); the Atlantic's is the Mediterranean's halved
  (Morel & Gentili 2009), already at 443 nm.

The stations of a preset are those of one COASTℓOOC area (100311); `cdom_coastal` takes
the Baltic stations no deeper than 10 m (100305).  Each value is rounded to two
significant digits.  The script prints every median with its interquartile range (the
station quartiles, for CDOM those of the slope) and the a*_NAP uncertainty, and writes
presets.csv; run data/ocean/make_water_tables.py after it.

    python3 data/ocean/derive_presets.py            # print and write presets.csv
    python3 data/ocean/derive_presets.py --check    # print; fail if presets.csv differs
    python3 data/ocean/derive_presets.py --cross-check   # also the AC-9 cross-check
                                                          # (needs the arcus package)
Only the standard library and numpy.
"""
import argparse
import csv
import math
import pathlib
import sys

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
DATA = HERE / "coastlooc"
PRESETS_CSV = HERE / "presets.csv"
HEADER = ["name", "chlorophyll_mg_per_m3", "a_nap_443_per_m", "a_cdom_443_per_m", "status"]

# Mass-specific NAP absorption at 443 nm [m²/g]: Babin et al. 2003's average for their
# coastal European stations (the COASTℓOOC data), as given second-hand (README, source
# C); a second value quoted for the same paper, 0.035, bounds its uncertainty.
A_STAR_NAP_443 = 0.041
A_STAR_NAP_443_OTHER = 0.035

# Published a_CDOM at a reference wavelength [1/m, nm] (README, sources B, D, E).
FERRARI_DOWELL_1998 = (2.26, 355.0)                   # southern Baltic coast, average
ASTORECA_2009 = (math.sqrt(0.20 * 1.31), 375.0)       # Southern Bight, geometric midpoint
PARA_2010 = (0.10, 350.0)                             # Bay of Marseilles, annual mean
MOREL_GENTILI_2009_RATIO = 0.5                        # Atlantic / Mediterranean a_y(443)

SHALLOW_M = 10.0  # cdom_coastal: bathymetry no deeper than this

# name, COASTℓOOC area, shallow only, CDOM source (None: the Mediterranean's × ratio)
PRESETS = [
    ("atlantic", "Atlantic Ocean", False, None),
    ("mediterranean", "Med. Sea (Case 2)", False, PARA_2010),
    ("baltic", "Baltic Sea", False, FERRARI_DOWELL_1998),
    ("north_sea", "North Sea", False, ASTORECA_2009),
    ("cdom_coastal", "Baltic Sea", True, FERRARI_DOWELL_1998),
]
STATUS = {
    "atlantic": "C:coastlooc_median;a_nap:coastlooc_spm_x_babin2003;a_cdom:morel_gentili2009_ratio_x_mediterranean",
    "mediterranean": "C:coastlooc_median;a_nap:coastlooc_spm_x_babin2003;a_cdom:para2010_coastlooc_slope",
    "baltic": "C:coastlooc_median;a_nap:coastlooc_spm_x_babin2003;a_cdom:ferrari_dowell1998_coastlooc_slope",
    "north_sea": "C:coastlooc_median;a_nap:coastlooc_spm_x_babin2003;a_cdom:astoreca2009_coastlooc_slope",
    "cdom_coastal": "C:coastlooc_shallow_baltic_median;a_nap:coastlooc_spm_x_babin2003;"
                    "a_cdom:ferrari_dowell1998_coastlooc_slope",
}

AC9_NM = (412, 440, 488, 510, 532, 555, 630, 650, 676, 715)


def read(name):
    with (DATA / name).open(newline="") as f:
        return list(csv.DictReader(f))


def number(text):
    return float("nan") if text in ("", "NA") else float(text)


def stations():
    """Surface stations keyed by id: area, bathymetry, C, SPM, S_CDOM, S_NAP."""
    table = {r["station"]: {"station": r["station"], "area": r["area"]} for r in read("100311.csv")}
    columns = [("100305.csv", "bathymetry_m", "bathymetry_m"),
               ("100308.csv", "chlorophyll_a_mg_m3", "chl"),
               ("100306.csv", "suspended_particulate_matter_g_m3", "spm"),
               ("100310.csv", "s_cdom_nm1", "s_cdom"),
               ("100310.csv", "s_nap_nm1", "s_nap")]
    for name, column, key in columns:
        for r in read(name):
            if r["station"] in table:  # 100310 also holds samples below the surface
                table[r["station"]][key] = number(r[column])
    return table


def members(table, area, shallow):
    """The preset's stations.  Bathymetry is negative below sea level; a station
    without it is left out of the shallow set."""
    out = [s for s in table.values() if s["area"] == area]
    if shallow:
        out = [s for s in out if s.get("bathymetry_m", math.nan) >= -SHALLOW_M]
    return out


def stats(rows, key):
    """Median, first and third quartile (numpy's linear interpolation) and count."""
    x = np.array([r.get(key, math.nan) for r in rows], dtype=float)
    x = x[np.isfinite(x)]
    q1, med, q3 = np.percentile(x, [25, 50, 75])
    return float(med), float(q1), float(q3), int(x.size)


def two_digits(x):
    """The CSV's text of x: two significant digits."""
    return f"{x:#.2g}".rstrip(".")


def derive():
    """Per preset: the CSV's values and everything printed about them."""
    table = stations()
    by_name = {}
    # The Atlantic's CDOM comes from the Mediterranean's: presets with a source first.
    for name, area, shallow, source in sorted(PRESETS, key=lambda p: p[3] is None):
        rows = members(table, area, shallow)
        chl, spm, s_cdom, s_nap = (stats(rows, k) for k in ("chl", "spm", "s_cdom", "s_nap"))
        nap = tuple(A_STAR_NAP_443 * v for v in spm[:3])
        if source is None:
            med = by_name["mediterranean"]["cdom"]
            cdom = tuple(MOREL_GENTILI_2009_RATIO * v for v in med)
        else:
            a0, nm = source
            # A steeper slope (third quartile) gives less at 443 nm.
            cdom = tuple(a0 * math.exp(-s * (443 - nm)) for s in (s_cdom[0], s_cdom[2], s_cdom[1]))
        r = dict(name=name, area=area, shallow=shallow, n=len(rows), chl=chl, spm=spm, s_cdom=s_cdom,
                 s_nap=s_nap, nap=nap, cdom=cdom)
        r["csv"] = [name, two_digits(chl[0]), two_digits(nap[0]), two_digits(cdom[0]), STATUS[name]]
        by_name[name] = r
    return [by_name[p[0]] for p in PRESETS]


def report(derived):
    print(f"a*_NAP(443) = {A_STAR_NAP_443} m²/g (other quoted value {A_STAR_NAP_443_OTHER}: "
          f"a_NAP × {A_STAR_NAP_443_OTHER / A_STAR_NAP_443:.2f})")
    print("median [interquartile range] (stations)")
    for r in derived:
        where = r["area"] + (f", bathymetry <= {SHALLOW_M:g} m" if r["shallow"] else "")
        fmt = lambda v, d=3: f"{v[0]:.{d}g} [{v[1]:.{d}g}, {v[2]:.{d}g}]"
        print(f"{r['name']} ({where}; {r['n']} stations)")
        print(f"  C            {fmt(r['chl'])} mg/m³ ({r['chl'][3]})")
        print(f"  SPM          {fmt(r['spm'])} g/m³ ({r['spm'][3]})")
        print(f"  a_NAP(443)   {fmt(r['nap'])} 1/m")
        print(f"  S_CDOM       {fmt(r['s_cdom'])} 1/nm ({r['s_cdom'][3]})")
        print(f"  S_NAP        {fmt(r['s_nap'])} 1/nm ({r['s_nap'][3]})")
        print(f"  a_CDOM(443)  {fmt(r['cdom'])} 1/m (range: the slope's)")
        print(f"  -> {','.join(r['csv'][:4])}")


def csv_text(derived):
    lines = [",".join(HEADER)] + [",".join(r["csv"]) for r in derived]
    return "\n".join(lines) + "\n"


# ---- cross-check against the AC-9 (needs the arcus package) --------------------------


def summary(x):
    """Median, quartiles, extremes and count of a list, or None when empty."""
    if not x:
        return None
    q = np.percentile(x, [50, 25, 75, 0, 100])
    return dict(median=q[0], q1=q[1], q3=q[2], min=q[3], max=q[4], n=len(x))


def ac9_by_area(table, area, shallow):
    """Per AC-9 wavelength: summaries of the stations' a − a_w, c − a_w and b_p."""
    ids = {s["station"] for s in members(table, area, shallow)}
    values = {nm: {"a": [], "c": [], "bp": []} for nm in AC9_NM}
    for r in read("100304.csv"):
        if r["station"] in ids:
            v = values[int(r["wavelength"])]
            for key, column in (("a", "a_m1"), ("c", "c_m1"), ("bp", "bp_m1")):
                x = number(r[column])
                if math.isfinite(x):
                    v[key].append(x)
    return {nm: {k: summary(x) for k, x in v.items()} for nm, v in values.items()}


def model_by_preset(name, context=None):
    """The library's preset at the AC-9 wavelengths: absorption minus pure water's
    (detritus + phytoplankton + CDOM) and particle scattering (detritus +
    phytoplankton) [1/m]."""
    import arcus.ocean as ocean

    c = ocean.Water(name).coefficients(grid=(AC9_NM[0], AC9_NM[-1], 1.0), context=context)
    rows = ocean.CONSTITUENTS
    a = c["absorption"][[rows.index(k) for k in ("detritus", "phytoplankton", "cdom")]].sum(axis=0)
    b = c["scattering"][[rows.index(k) for k in ("detritus", "phytoplankton")]].sum(axis=0)
    at = {int(round(w)): i for i, w in enumerate(c["wavelengths"])}
    return {nm: dict(a=float(a[at[nm]]), bp=float(b[at[nm]]), c=float(a[at[nm]] + b[at[nm]])) for nm in AC9_NM}


def cross_check(context=None):
    """{preset: {nm: {"model": {a, bp, c}, "a"|"bp"|"c": station summary or None}}}."""
    table = stations()
    out = {}
    for name, area, shallow, _ in PRESETS:
        meas, model = ac9_by_area(table, area, shallow), model_by_preset(name, context)
        out[name] = {nm: dict(model=model[nm], **meas[nm]) for nm in AC9_NM}
    return out


def cell(m):
    return f"{m['median']:.3g} [{m['q1']:.3g}, {m['q3']:.3g}] ({m['n']})" if m else "none"


def position(model, m):
    """Where a model value lies against the stations' interquartile range."""
    return "" if m is None else "below" if model < m["q1"] else "above" if model > m["q3"] else "in"


def print_cross_check(xc):
    print("\nAC-9 cross-check: model | stations' median [interquartile range] (n)")
    for name, per_nm in xc.items():
        print(name)
        for nm, v in per_nm.items():
            print(f"  {nm} nm  " + "   ".join(f"{k} {v['model'][k]:.3g} | {cell(v[k])}" for k in ("a", "bp", "c")))


def markdown(xc, nms=(440, 488, 555, 676)):
    """docs/ocean.md's cross-check table: a − a_w and b_p at a few AC-9 bands."""
    lines = ["| preset | nm | a − a_w model | stations: median [IQR] (n) | | b_p model | stations: median [IQR] (n) | |",
             "|---|---|---|---|---|---|---|---|"]
    for name, per_nm in xc.items():
        for nm in nms:
            v = per_nm[nm]
            cells = [name, str(nm)]
            for k in ("a", "bp"):
                cells += [f"{v['model'][k]:.3g}", cell(v[k]), position(v["model"][k], v[k])]
            lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--check", action="store_true", help="do not write; fail if presets.csv differs")
    p.add_argument("--cross-check", action="store_true", help="also compare with the AC-9 (needs arcus)")
    args = p.parse_args(argv)
    derived = derive()
    report(derived)
    text = csv_text(derived)
    if args.check:
        if PRESETS_CSV.read_text() != text:
            print("presets.csv differs from the derivation", file=sys.stderr)
            return 1
    else:
        PRESETS_CSV.write_text(text)
        print(f"wrote {PRESETS_CSV}")
    if args.cross_check:
        xc = cross_check()
        print_cross_check(xc)
        print("\n" + markdown(xc))
    return 0


if __name__ == "__main__":
    sys.exit(main())
