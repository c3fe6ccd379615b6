#!/usr/bin/env python3
"""Writes the meshes of the "cross room" (thesis §5.4.2.1; scenes/cross_room.json):
a 5 x 5 x 5 m room, x, y, z in [0, 5] (y up, the floor at y = 0), lit through a
cross-shaped window in its ceiling.  Every face points into the room.

  cross_room.obj          the four walls and the ceiling, the ceiling with a
                          cross-shaped hole (a 5 x 5 grid of rectangles cut at the
                          cross's edges, its 5 cross cells left out): 48 triangles
  cross_room_floor.obj    the floor: 2 triangles
  cross_room_window.obj   the opening itself, the 5 cells the ceiling leaves out (10
                          triangles, facing down like the ceiling): the scene gives
                          them the material "window", which photons cross and whose
                          outline is where the sun's photons start (src/render/photons.h)

The cross is centred at (x, z) = (1, 2.5) on the ceiling, arms 1.6 m long and 0.4 m
wide (area 1.12 m^2), along x and z.

Run from anywhere: python3 data/meshes/make_cross_room.py (standard library only; the
output is the same bit for bit on every run).
"""
import os

HERE = os.path.dirname(os.path.abspath(__file__))

SIZE = 5.0
CROSS_X, CROSS_Z = 1.0, 2.5  # the cross's centre on the ceiling
ARM, HALF_WIDTH = 0.8, 0.2   # half the arm's length, half its width


def sub(a, b):
    return tuple(p - q for p, q in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(p * q for p, q in zip(a, b))


class Mesh:
    def __init__(self):
        self.verts, self.index, self.faces = [], {}, []

    def vertex(self, p):
        key = tuple(round(c, 9) for c in p)
        if key not in self.index:
            self.index[key] = len(self.verts)
            self.verts.append(key)
        return self.index[key]

    def quad(self, p0, p1, p2, p3, normal):
        """Two triangles of the rectangle p0 p1 p2 p3 (in order round it), wound so
        that their normal is `normal`."""
        if dot(cross(sub(p1, p0), sub(p2, p0)), normal) < 0:
            p1, p3 = p3, p1
        a, b, c, d = (self.vertex(p) for p in (p0, p1, p2, p3))
        self.faces += [(a, b, c), (a, c, d)]

    def write(self, name, comment):
        path = os.path.join(HERE, name)
        with open(path, "w", newline="\n") as f:
            f.write("# %s\n# written by make_cross_room.py; CC0 1.0\n" % comment)
            for v in self.verts:
                f.write("v %s\n" % " ".join(fmt(c) for c in v))
            for t in self.faces:
                f.write("f %d %d %d\n" % tuple(i + 1 for i in t))
        print("%s: %d vertices, %d triangles" % (path, len(self.verts), len(self.faces)))


def fmt(x):
    s = "%.6f" % x
    s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def in_cross(i, j):
    return (i == 2 and 1 <= j <= 3) or (j == 2 and 1 <= i <= 3)


def main():
    s = SIZE
    room, floor, window = Mesh(), Mesh(), Mesh()
    # Walls, facing in.
    room.quad((0, 0, 0), (0, 0, s), (0, s, s), (0, s, 0), (1, 0, 0))     # x = 0
    room.quad((s, 0, 0), (s, 0, s), (s, s, s), (s, s, 0), (-1, 0, 0))    # x = 5
    room.quad((0, 0, 0), (s, 0, 0), (s, s, 0), (0, s, 0), (0, 0, 1))     # z = 0
    room.quad((0, 0, s), (s, 0, s), (s, s, s), (0, s, s), (0, 0, -1))    # z = 5
    # The ceiling, cut along the cross's edges; the cross's cells are the window.
    xs = [0.0, CROSS_X - ARM, CROSS_X - HALF_WIDTH, CROSS_X + HALF_WIDTH, CROSS_X + ARM, s]
    zs = [0.0, CROSS_Z - ARM, CROSS_Z - HALF_WIDTH, CROSS_Z + HALF_WIDTH, CROSS_Z + ARM, s]
    for i in range(5):
        for j in range(5):
            x0, x1, z0, z1 = xs[i], xs[i + 1], zs[j], zs[j + 1]
            target = window if in_cross(i, j) else room
            target.quad((x0, s, z0), (x1, s, z0), (x1, s, z1), (x0, s, z1), (0, -1, 0))
    floor.quad((0, 0, 0), (s, 0, 0), (s, 0, s), (0, 0, s), (0, 1, 0))
    room.write("cross_room.obj", "cross room: walls and a ceiling with a cross-shaped hole, facing in")
    floor.write("cross_room_floor.obj", "cross room: the floor, facing up")
    window.write("cross_room_window.obj", "cross room: the cross-shaped opening in the ceiling, facing down")


if __name__ == "__main__":
    main()
