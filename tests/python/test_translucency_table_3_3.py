"""Thesis Table 3.3 (issue 21 §6): Jensen et al. 2001's six materials estimated back from
synthetic photos of a mesh.  apps/translucency/showcase.py renders each material on the
torus of scenes/translucency/table_5_1.json (54 mm across, lit from the front and from
behind, 200² as the thesis' photos) through the dipole and estimates it; here the
estimates are held to the thesis' own mean errors (computed from its published columns,
not from ours) and to the issue's bounds: R_total within 3% per channel, ℓ_d within 15%
where it is below a quarter of the object's size.  The torus, not the sphere: its cast
shadows and the backlight give the image edges a profile shows in (docs/translucency.md
says why a sphere under directional lights does not pin a short ℓ_d)."""

import importlib.util
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def showcase():
    spec = importlib.util.spec_from_file_location("showcase", REPO / "apps" / "translucency" / "showcase.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.full_size
def test_table_3_3_is_no_worse_than_the_thesis(showcase):
    rows = showcase.table_3_3(200, rerender=False)
    ours, theirs = [[], []], [[], []]
    for r in rows:
        truth, found = r["truth"], r["estimate"].dipole
        measured = showcase.reduced(truth)
        for k, (mine, thesis) in enumerate(zip(showcase.reduced(found), showcase.THESIS_3_3[r["material"]])):
            ours[k] += list(np.abs(mine / measured[k] - 1))
            theirs[k] += list(np.abs(np.asarray(thesis) / measured[k] - 1))
        total = found.total_reflectance / truth.total_reflectance - 1
        length = found.diffuse_length / truth.diffuse_length - 1
        print(r["material"], "R_total", np.round(100 * total, 2), "l_d", np.round(100 * length, 1))
        assert np.all(np.abs(total) < 0.03), r["material"]
        short = truth.diffuse_length < 54 / 4
        assert np.all(np.abs(length[short]) < 0.15), r["material"]
    print("mean errors: albedo %.3f%% (thesis %.3f%%), extinction %.2f%% (thesis %.2f%%)" % (
        100 * np.mean(ours[0]), 100 * np.mean(theirs[0]), 100 * np.mean(ours[1]), 100 * np.mean(theirs[1])))
    assert np.mean(ours[0]) <= np.mean(theirs[0])  # the thesis: 1.00%
    assert np.mean(ours[1]) <= np.mean(theirs[1])  # the thesis: 3.74%
