"""The water presets and the field data they come from (data/ocean/README.md, "presets.csv").

data/ocean/derive_presets.py derives the five presets from the COASTℓOOC stations copied
in data/ocean/coastlooc/; these tests check that the CSV the library embeds is that
derivation's output, that the library's presets hold those numbers, and the physics of
the cross-check against the same stations' AC-9 (docs/ocean.md).
"""

import importlib.util
import math

import numpy as np
import pytest

import arcus.ocean as ocean


@pytest.fixture(scope="module")
def derive(repo):
    spec = importlib.util.spec_from_file_location("derive_presets", repo / "data" / "ocean" / "derive_presets.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_derivation_reproduces_presets_csv_deterministically(derive, repo, capsys):
    """Consistency: the script, run twice on the copied data, gives presets.csv byte for
    byte (medians and quartiles of fixed station sets: no randomness), and its --check
    mode agrees without writing."""
    first, second = derive.csv_text(derive.derive()), derive.csv_text(derive.derive())
    assert first == second
    assert first == (repo / "data" / "ocean" / "presets.csv").read_text()
    assert derive.main(["--check"]) == 0
    out = capsys.readouterr().out
    assert "median [interquartile range]" in out and "wrote" not in out
    # Station counts per area are the ESSD paper's (38, 61, 57, 99): the area assignment.
    counts = {r["name"]: r["n"] for r in derive.derive()}
    assert (counts["atlantic"], counts["mediterranean"], counts["baltic"], counts["north_sea"]) == (38, 61, 57, 99)
    # No value is a placeholder any more: every quantity names its source.
    for line in first.splitlines()[1:]:
        status = line.split(",")[4]
        assert "unverified" not in status and "placeholder" not in status
        assert [s.split(":")[0] for s in status.split(";")] == ["C", "a_nap", "a_cdom"]


def test_library_presets_hold_the_derived_values(repo, ctx):
    """At 443 nm, where the CSV's quantities are defined, the library's preset absorbs what
    the CSV says: preset() carries a_NAP(443) to a_d(400) and a_CDOM(443) to a_y(440) with
    the model's slopes and the model carries them back, so only rounding separates them
    (relative 1e-12 covers the two exponentials' round trip, ~1e-15).  Phytoplankton:
    C × Table 3.4 interpolated linearly between 440 nm (0.035) and 500 nm (0.020 m²/mg)."""
    rows = [line.split(",") for line in (repo / "data" / "ocean" / "presets.csv").read_text().splitlines()[1:]]
    assert [r[0] for r in rows] == list(ocean.PRESETS)
    for name, c, nap, cdom, _ in rows:
        w = ocean.Water(name)
        assert w.parameters["chlorophyll"] == float(c)
        k = w.coefficients(grid=(443.0, 443.0, 1.0), context=ctx)
        a = dict(zip(ocean.CONSTITUENTS, k["absorption"][:, 0]))
        assert a["detritus"] == pytest.approx(float(nap), rel=1e-12)
        assert a["cdom"] == pytest.approx(float(cdom), rel=1e-12)
        assert a["phytoplankton"] == pytest.approx(float(c) * (0.035 + (0.020 - 0.035) * 3 / 60), rel=1e-12)


@pytest.fixture(scope="module")
def cross_check(derive, ctx):
    return derive.cross_check(context=ctx)


def test_docs_show_the_cross_check_as_the_script_computes_it(derive, cross_check, repo):
    """docs/ocean.md's table is the script's output for the presets and model of this tree."""
    assert derive.markdown(cross_check) in (repo / "docs" / "ocean.md").read_text()


def test_presets_absorb_and_scatter_as_their_stations_do_at_440nm(derive, cross_check):
    """Physics sanity of the cross-check: a preset built from its area's median
    constituents must absorb and scatter as water of that area does.  At 440 nm, next to
    443 nm where the presets are defined, each preset's a − a_w and b_p lie within the
    range its own stations' AC-9 measured, an independent instrument (the other bands
    test the model's spectral shapes, which docs/ocean.md reports band by band).  And the
    Atlantic, the clearest water, absorbs and scatters least of the five, in the model as
    at the stations."""
    xc = cross_check
    for name, per_nm in xc.items():
        v = per_nm[440]
        for key in ("a", "bp"):
            m = v[key]
            assert m is not None and m["n"] >= 8, (name, key)
            assert m["min"] <= v["model"][key] <= m["max"], (name, key, v["model"][key], m)
        assert math.isclose(v["model"]["c"], v["model"]["a"] + v["model"]["bp"], rel_tol=1e-12)
    for key in ("a", "bp"):
        model = {n: xc[n][440]["model"][key] for n in xc}
        stations = {n: xc[n][440][key]["median"] for n in xc}
        assert min(model, key=model.get) == "atlantic" and min(stations, key=stations.get) == "atlantic"
    # What the cross-check compares with is what it claims: in file 100304 a and c are
    # both net of pure water and b_p = c − a, row by row.  The values are rounded to 1e-4
    # or finer, so the three roundings differ by at most 3 × 0.5e-4.
    rows = [[derive.number(r[k]) for k in ("a_m1", "c_m1", "bp_m1")] for r in derive.read("100304.csv")]
    rows = np.array([r for r in rows if all(math.isfinite(x) for x in r)])
    assert len(rows) > 1000
    assert np.max(np.abs(rows[:, 1] - rows[:, 0] - rows[:, 2])) <= 1.5e-4
