#!/usr/bin/env python3
"""Writes the ice-crystal meshes for halos (arcus.halo), flat-faced hexagonal prisms:

  crystals/hex_column.off  length/diameter 2   (a column: 22° halo, 46° halo via its ends)
  crystals/hex_plate.off   length/diameter 0.2 (a plate: sundogs when falling horizontally)

A regular hexagonal prism of circumscribed radius 1 (corner to axis; the "diameter" of
the aspect ratio is the corner-to-corner width 2), its axis along the mesh's y, its side
faces' corners at azimuths 0°, 60°, ..., 300° about y (from +x toward −z, i.e. in the
x-z plane: corner k at (cos 60°k, ±L/2, −sin 60°k)), length L = 2 · aspect.  Each side
face is two triangles and each end a fan of four from its corner 0: 20 triangles, 12
vertices, every edge shared by exactly two triangles, all wound counter-clockwise seen
from outside (outward normals; the script checks both, and a positive volume).

Load one with ``arcus.rainbow.Mesh(path, scale=radius_in_metres, smooth=False)``.
:func:`arcus.halo.hexagonal_prism` builds the same triangles in memory (the tests check
that these files equal its output), so the package does not need the files.

Run from anywhere: python3 data/rainbow/make_crystals.py [--check] (standard library
only; --check compares the files with what would be written and fails on a difference).
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CRYSTALS = {"hex_column.off": 2.0, "hex_plate.off": 0.2}


def hexagonal_prism(aspect):
    """(vertices, triangles) of the prism above: 12 (x, y, z) and 20 (a, b, c)."""
    if not (isinstance(aspect, (int, float)) and math.isfinite(aspect) and aspect > 0):
        raise ValueError("aspect must be a positive number, got %r" % (aspect,))
    half = float(aspect)  # L/2 = aspect · diameter / 2 = aspect · 1
    s = math.sqrt(3) / 2  # cos 60°k and −sin 60°k, written out so that the ring is exactly symmetric
    ring = [(1.0, 0.0), (0.5, -s), (-0.5, -s), (-1.0, 0.0), (-0.5, s), (0.5, s)]
    vertices = [(x, half, z) for x, z in ring] + [(x, -half, z) for x, z in ring]
    triangles = []
    for k in range(6):
        a, b = k, (k + 1) % 6  # top corners, counter-clockwise about +y seen from above
        triangles += [(a, 6 + a, 6 + b), (a, 6 + b, b)]
    triangles += [(0, 1 + k, 2 + k) for k in range(4)]  # top (+y) fan
    triangles += [(6, 8 + k, 7 + k) for k in range(4)]  # bottom (−y) fan, reversed
    _check(vertices, triangles)
    return vertices, triangles


def _check(vertices, triangles):
    edges = {}
    volume = 0.0
    centre = [sum(v[a] for v in vertices) / len(vertices) for a in range(3)]
    for t in triangles:
        for i in range(3):
            e = (t[i], t[(i + 1) % 3])
            if e in edges:
                raise AssertionError("edge %s used twice in one direction: inconsistent winding" % (e,))
            edges[e] = True
        p, q, r = (vertices[i] for i in t)
        u = [q[a] - p[a] for a in range(3)]
        w = [r[a] - p[a] for a in range(3)]
        n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
        mid = [(p[a] + q[a] + r[a]) / 3 - centre[a] for a in range(3)]
        if sum(n[a] * mid[a] for a in range(3)) <= 0:
            raise AssertionError("triangle %s faces inward" % (t,))
        volume += sum(p[a] * (q[(a + 1) % 3] * r[(a + 2) % 3] - q[(a + 2) % 3] * r[(a + 1) % 3]) for a in range(3)) / 6
    for a, b in edges:
        if (b, a) not in edges:
            raise AssertionError("edge (%d, %d) has no twin: the mesh is open" % (a, b))
    if volume <= 0:
        raise AssertionError("negative volume %g" % volume)


def _fmt(x):
    return repr(float(x) + 0.0)  # the shortest text that reads back exactly; no "-0.0"


def off_text(aspect):
    """The OFF file of hexagonal_prism(aspect) as a string."""
    vertices, triangles = hexagonal_prism(aspect)
    # no comment lines: OpenMesh's OFF reader takes them for data ("the mesh has no faces")
    lines = ["OFF", "%d %d 0" % (len(vertices), len(triangles))]
    lines += [" ".join(_fmt(c) for c in v) for v in vertices]
    lines += ["3 %d %d %d" % t for t in triangles]
    return "\n".join(lines) + "\n"


def main(argv):
    check = "--check" in argv[1:]
    out = os.path.join(HERE, "crystals")
    os.makedirs(out, exist_ok=True)
    stale = []
    for name, aspect in CRYSTALS.items():
        path = os.path.join(out, name)
        text = off_text(aspect)
        if check:
            try:
                with open(path) as f:
                    if f.read() != text:
                        stale.append(path)
            except FileNotFoundError:
                stale.append(path)
        else:
            with open(path, "w") as f:
                f.write(text)
            print("wrote", os.path.relpath(path))
    if stale:
        print("out of date:", ", ".join(stale), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
