#!/usr/bin/env python3
"""The translucency engine's gallery steps (docs/translucency.md), one command each:

    python3 apps/translucency/showcase.py estimate --out DIR [--side N]
        A synthetic photo of an apple sphere (40 mm, two lights) estimated back (thesis
        §3.3.1): DIR/compare.png (photo | re-render | difference), DIR/profile.png (the
        estimated profile against the fitted dipole and §3.4's Hermite curve) and
        DIR/estimate.md (R_total, ℓ_d against Jensen's measured values).
    python3 apps/translucency/showcase.py table_3_3 --out DIR [--side N]
        Thesis Table 3.3: Jensen's six materials on the torus of Table 5.1's scene, each
        photo rendered by the dipole and estimated back; DIR/table_3_3.md (reduced albedo
        and extinction: the measured values, the thesis' estimates and errors, ours) and
        DIR/table_3_3.png (the photos above their re-renders).
    python3 apps/translucency/showcase.py photo --out DIR [--side N]
        Thesis §3.4, §5.2: a synthetic photograph of an apple lumpy sphere under one light,
        estimated from the photo alone (no mesh, no lights):
        DIR/photo_estimate.png (photograph | estimated shape, its normals as colours |
        re-render under the lights found) and DIR/photo_estimate.md (the light found, R_total
        against Jensen's measured values).
    python3 apps/translucency/showcase.py genetic --out DIR [--side N]
        Table 5.1's genetic search (§5.1) on scenes/translucency/table_5_1.json:
        DIR/genetic.png (target | best render) and DIR/table_5_1.md (the best genes
        every tenth generation beside the truth).
"""

import argparse
import json
import os
import sys
from pathlib import Path

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "bindings", "python"))

from arcus import image  # noqa: E402
from arcus.cli import resources  # noqa: E402
from arcus.cli.bssrdf import write_comparison  # noqa: E402
from arcus.inverse import genetic  # noqa: E402
from arcus.translucency import Dipole, estimate_bssrdf, read_mesh, render  # noqa: E402

LIGHTS = [((0.3, 0.5, 1), 1.0), ((-1, 0.2, 0.3), 0.3)]
VIEW = {"position": (0, 0, 5), "look_at": (0, 0, 0)}

# Thesis Table 3.3's estimates: reduced albedo α′ and reduced extinction σ′_t (mm⁻¹), R G B.
# Its reference columns are Jensen et al. 2001's measured values (Dipole.from_material).
THESIS_3_3 = {
    "apple": ((0.9969, 0.9985, 0.9686), (2.2428, 2.3216, 2.0202)),
    "cream": ((1.0000, 1.0000, 0.9967), (7.4580, 5.9233, 3.4267)),
    "marble": ((1.0000, 1.0000, 1.0000), (2.3543, 2.7351, 3.0359)),
    "potato": ((1.0000, 0.9999, 0.9145), (0.6690, 0.6806, 0.5651)),
    "skimmilk": ((0.9898, 1.0000, 0.9981), (0.6875, 1.2602, 1.8943)),
    "wholemilk": ((1.0000, 1.0000, 0.9818), (2.4968, 3.1725, 3.7553)),
}


def estimate(out, side):
    sphere = str(resources.mesh("icosphere"))
    truth = Dipole.from_material("apple")
    view = dict(VIEW, width=side, height=side)
    photo = render(truth, sphere, LIGHTS, view, ortho_height=2.2, mm_per_unit=20, highlight_deg=0).image
    e = estimate_bssrdf(photo, sphere, LIGHTS, view, ortho_height=2.2, mm_per_unit=20)
    again = render(e.dipole, sphere, LIGHTS, view, ortho_height=2.2, mm_per_unit=20, highlight_deg=0).image
    write_comparison(Path(out), photo, again, e, e.dipole)
    rows = ["| | R | G | B |", "|---|---|---|---|"]
    for name, est, ref in (("R_total", e.dipole.total_reflectance, truth.total_reflectance),
                           ("ℓ_d, mm", e.dipole.diffuse_length, truth.diffuse_length)):
        rows.append("| %s estimated | %s |" % (name, " | ".join("%.3g" % v for v in est)))
        rows.append("| %s Jensen et al. 2001 | %s |" % (name, " | ".join("%.3g" % v for v in ref)))
    with open(os.path.join(out, "estimate.md"), "w") as f:
        f.write("Apple, a 40 mm sphere at %d², 24 piecewise-constant functions, the dipole fitted to the image "
                "(%.1f s):\n\n%s\n" % (side, e.timings["total"], "\n".join(rows)))


def torus_scene():
    """Table 5.1's scene (a torus 54 mm across, lit from the front and from behind): its
    path, and its mesh, lights and view as render and estimate_bssrdf take them."""
    scene = os.path.join(ROOT, "scenes", "translucency", "table_5_1.json")
    if not os.path.isfile(scene):
        scene = str(resources.scene("translucency/table_5_1"))
    doc = json.load(open(scene))
    lights = [(light[:3], light[3]) for light in doc["lights"]]
    view = dict(ortho_height=doc["ortho_height"], mm_per_unit=doc["translucent_object"]["mm_per_unit"])
    return scene, str(resources.mesh(doc["translucent_object"]["mesh"])), lights, doc["camera"], view


def reduced(d):
    """A dipole's reduced albedo α′ and reduced extinction σ′_t (mm⁻¹), per channel."""
    extinction = np.asarray(d.sigma_a) + np.asarray(d.sigma_s_prime)
    return np.asarray(d.sigma_s_prime) / extinction, extinction


def table_3_3(side, rerender=True):
    """Per material of Table 3.3: the truth, the estimate from a dipole-rendered photo
    of the torus at side² (true η, exit as the thesis), the photo and (when asked) the
    estimate's re-render."""
    _, mesh, lights, camera, view = torus_scene()
    camera = dict(camera, width=side, height=side)
    rows = []
    for name in THESIS_3_3:
        truth = Dipole.from_material(name)
        photo = render(truth, mesh, lights, camera, highlight_deg=0, **view).image
        e = estimate_bssrdf(photo, mesh, lights, camera, eta=truth.eta, subtract_minimum=False, **view)
        again = render(e.dipole, mesh, lights, camera, highlight_deg=0, **view).image if rerender else None
        rows.append(dict(material=name, truth=truth, estimate=e, photo=photo, again=again))
    return rows


def table_3_3_page(out, side):
    rows = table_3_3(side)
    top = max(float(r["photo"].max()) for r in rows) or 1.0
    image.write(os.path.join(out, "table_3_3.png"), np.concatenate(
        [np.concatenate([r["photo"] for r in rows], axis=1), np.concatenate([r["again"] for r in rows], axis=1)],
        axis=0) * (0.9 / top))
    pct = (lambda a, b: 100 * np.abs(np.asarray(a) / np.asarray(b) - 1))
    f3 = (lambda v, fmt: " ".join(fmt % x for x in v))
    lines = ["| material | α′ measured | α′ thesis | error | α′ arcus | error | σ′_t measured | σ′_t thesis | "
             "error | σ′_t arcus | error |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    errors = {"thesis": [[], []], "arcus": [[], []]}
    for r in rows:
        (alb, ext), (t_alb, t_ext), (a_alb, a_ext) = reduced(r["truth"]), THESIS_3_3[r["material"]], \
            reduced(r["estimate"].dipole)
        for who, (x, y) in (("thesis", (t_alb, t_ext)), ("arcus", (a_alb, a_ext))):
            errors[who][0] += list(pct(x, alb))
            errors[who][1] += list(pct(y, ext))
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["material"], f3(alb, "%.4f"), f3(t_alb, "%.4f"), f3(pct(t_alb, alb), "%.2f%%"),
            f3(a_alb, "%.4f"), f3(pct(a_alb, alb), "%.2f%%"), f3(ext, "%.3f"), f3(t_ext, "%.3f"),
            f3(pct(t_ext, ext), "%.1f%%"), f3(a_ext, "%.3f"), f3(pct(a_ext, ext), "%.1f%%")))
    lines.append("| mean | | | %.2f%% | | %.2f%% | | | %.1f%% | | %.1f%% |" % (
        np.mean(errors["thesis"][0]), np.mean(errors["arcus"][0]), np.mean(errors["thesis"][1]),
        np.mean(errors["arcus"][1])))
    seconds = sum(r["estimate"].timings["total"] for r in rows)
    with open(os.path.join(out, "table_3_3.md"), "w") as f:
        f.write("Thesis Table 3.3 reproduced: Jensen et al. 2001's materials (R G B) on a torus 54 mm across, lit "
                "from the front and from behind (scenes/translucency/table_5_1.json), each photo rendered by the "
                "dipole at %d² and estimated back (24 piecewise-constant functions, the dipole fitted to the "
                "image, the true η; %.0f s for the six estimates).  The photos are above their re-renders in "
                "table_3_3.png.\n\n%s\n" % (side, seconds, "\n".join(lines)))
    return rows


def search(out, side):
    scene, mesh, lights, camera, view = torus_scene()
    truth = {"sigma_a": [0.0021, 0.0041, 0.0071], "sigma_s": [2.19, 2.62, 3.0], "g": 0.5, "eta": 1.5, "b": 20.0}
    medium = Dipole(truth["sigma_a"], (1 - truth["g"]) * np.array(truth["sigma_s"]), truth["eta"])
    target = render(medium, mesh, lights, dict(camera, width=side, height=side), highlight_deg=truth["b"],
                    **view).image
    rows = {}
    found = genetic(target, scene, seed=1,
                    on_generation=lambda g, f, genes: rows.__setitem__(g, (f, genes)) if g % 10 == 0 else None)
    top = float(target.max()) or 1.0
    image.write(os.path.join(out, "genetic.png"), np.concatenate([target, found.image], axis=1) * (0.9 / top))
    names = [("η", "eta", None), ("g", "g", None), ("b", "b", None)] + \
        [("σ_s,%s" % "RGB"[c], "sigma_s", c) for c in range(3)] + [("σ_a,%s" % "RGB"[c], "sigma_a", c) for c in range(3)]
    head = "| | truth | %s |" % " | ".join("#%d" % g for g in sorted(rows))
    lines = [head, "|---|---|%s" % ("---|" * len(rows))]
    for label, key, c in names:
        value = (lambda genes: genes[key] if c is None else genes[key][c])
        lines.append("| %s | %.4g | %s |" % (label, truth[key] if c is None else truth[key][c],
                                             " | ".join("%.4g" % value(rows[g][1]) for g in sorted(rows))))
    lines.append("| fitness | | %s |" % " | ".join("%.3f" % rows[g][0] for g in sorted(rows)))
    with open(os.path.join(out, "table_5_1.md"), "w") as f:
        f.write("Table 5.1's search (40 × 50, seed 1) at %d², the target beside the best render; the search's "
                "best fitness %.3f, %.4f after %d polish steps; σ′_s = (1 − g)σ_s found: %s against 1.10 1.31 "
                "1.50, η %.3f against 1.5, b %.1f° against 20° (%.1f s; docs/translucency.md: five seeds, the "
                "polish, and why σ_s and g alone are not identifiable).  The search's best genes every tenth "
                "generation:\n\n%s\n"
                % (side, found.search_fitness, found.fitness, found.polish_steps,
                   " ".join("%.3g" % v for v in found.sigma_s_prime), found.best["eta"], found.best["b"],
                   found.timings["total"], "\n".join(lines)))


def from_the_photo(out, side):
    v, f = read_mesh(resources.mesh("icosphere"))
    u = v / np.linalg.norm(v, axis=1, keepdims=True)
    lumpy = v * (1 + 0.12 * np.sin(3 * np.arctan2(u[:, 1], u[:, 0])) * (1 - u[:, 2] ** 2) + 0.08 * u[:, 2])[:, None]
    truth = Dipole.from_material("apple")
    zenith, azimuth = np.radians(45), np.radians(145)  # Fig. 3.10's light
    toward = (np.sin(zenith) * np.cos(azimuth), np.sin(zenith) * np.sin(azimuth), np.cos(zenith))
    view = dict(VIEW, up=(0, 1, 0), width=side, height=side)
    extent = float(np.abs(lumpy[:, :2]).max())
    photo = render(truth, (lumpy, f), [(toward, 1.0)], view, ortho_height=2.4 * extent, mm_per_unit=20,
                   highlight_deg=0).image
    mm_per_pixel = 2.4 * extent * 20 / side
    e = estimate_bssrdf(photo, mm_per_pixel=mm_per_pixel)
    seen = {"position": (0, 0, 4 * side), "look_at": (0, 0, 0), "up": (0, 1, 0), "width": side, "height": side}
    lights = [(light.direction, light.intensity) for light in e.lights.lights]
    again = render(e.hermite, e.relief, lights, seen, ortho_height=side, mm_per_unit=mm_per_pixel,
                   highlight_deg=0).image
    top = float(np.percentile(photo[photo.max(axis=2) > 0].max(axis=1), 99.5))
    normals = np.where(e.shape.mask[..., None], 0.5 + 0.5 * e.shape.normals, 0) * top / 0.9
    image.write(Path(out) / "photo_estimate.png", np.concatenate([photo, normals, again], axis=1) * (0.9 / top))
    light = e.lights.lights[0]
    rows = ["| | R | G | B |", "|---|---|---|---|",
            "| R_total, §3.4's Hermite profile | %s |" % " | ".join("%.3g" % x for x in e.hermite.total_reflectance),
            "| R_total, the dipole (approximate) | %s |" % " | ".join("%.3g" % x for x in e.dipole.total_reflectance),
            "| R_total, Jensen et al. 2001 | %s |" % " | ".join("%.3g" % x for x in truth.total_reflectance)]
    with open(os.path.join(out, "photo_estimate.md"), "w") as f:
        f.write("Apple, a lumpy sphere at %d², from the photo alone (%.1f s).  The light: azimuth %.1f°, zenith "
                "%.0f° (the truth: 145°, 45°).\n\n%s\n" % (side, e.timings["total"], light.azimuth_deg,
                                                          light.zenith_deg, "\n".join(rows)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("part", choices=("estimate", "photo", "table_3_3", "genetic"))
    ap.add_argument("--out", required=True)
    ap.add_argument("--side", type=int, default=0,
                    help="pixels a side (default: 200 estimate, photo and table_3_3, 64 genetic)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    if args.part == "estimate":
        estimate(args.out, args.side or 200)
    elif args.part == "photo":
        from_the_photo(args.out, args.side or 200)
    elif args.part == "table_3_3":
        table_3_3_page(args.out, args.side or 200)
    else:
        search(args.out, args.side or 64)
    print("wrote %s" % os.path.abspath(args.out))


if __name__ == "__main__":
    main()
