#!/usr/bin/env python3
"""Writes the meshes of the render scenes (scenes/*.json), in metres, y up:

  shuttle.obj  a space-shuttle-like orbiter standing on its landing gear, 37 m long
               (nose toward +x), 23.8 m wingspan, 17.3 m to the top of the tail fin:
               a lofted fuselage, delta wings with a leading-edge glove, a tail fin,
               three engine bells and three gear legs; the origin is on the ground
               under the fuselage's middle
  castle.obj   a castle 130 m x 90 m: curtain walls 14 m high with crenellations,
               four round corner towers 26 m high with conical roofs, a gatehouse and
               a square keep 38 m high with a pyramid roof; the origin is on the ground
               at its centre, the front (the gate) toward -x
  castle_trim.obj  the castle's details, for a second material: the gate, a string
               course 6-7.2 m up around the outside of the curtain walls and arrow
               slits 8.5-11 m up, each standing 0.3 m proud of the wall (in the same
               frame as castle.obj)

Every part is a closed, consistently wound solid (parts may overlap one another); no
degenerate triangles.  Deterministic: run it again to rewrite the files bit for bit.
Run from anywhere: python3 data/meshes/make_scene_meshes.py (standard library only).
Licence of the output: CC0 1.0.
"""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))


class Mesh:
    def __init__(self):
        self.verts, self.faces = [], []

    def vertex(self, p):
        self.verts.append(tuple(float(c) for c in p))
        return len(self.verts) - 1

    def tri(self, a, b, c):
        self.faces.append((a, b, c))

    def quad(self, a, b, c, d):
        self.faces += [(a, b, c), (a, c, d)]


def loft(mesh, sections, start_tip=None, end_tip=None):
    """Rings of equal vertex count (each ring counter-clockwise seen from +x, listed
    from -x to +x); closed by a tip vertex or a centre fan at each end."""
    n = len(sections[0])
    rings = [[mesh.vertex(p) for p in ring] for ring in sections]
    for r0, r1 in zip(rings, rings[1:]):
        for k in range(n):
            a, b, c, d = r0[k], r0[(k + 1) % n], r1[(k + 1) % n], r1[k]
            mesh.quad(a, b, c, d)

    def cap(ring, tip, outward_plus_x):
        centre = mesh.vertex(tip)
        for k in range(n):
            a, b = ring[k], ring[(k + 1) % n]
            if outward_plus_x:
                mesh.tri(centre, a, b)
            else:
                mesh.tri(centre, b, a)

    first, last = sections[0], sections[-1]
    cap(rings[0], start_tip or centroid(first), False)
    cap(rings[-1], end_tip or centroid(last), True)


def centroid(points):
    return tuple(sum(p[i] for p in points) / len(points) for i in range(3))


def prism(mesh, polygon, axis, lo, hi):
    """A convex polygon (counter-clockwise in its plane) extruded along `axis` (1: y,
    2: z) from lo to hi.  Polygon points are (u, v): for axis 1, (x, z); for axis 2,
    (x, y)."""

    def point(u, v, w):
        return (u, w, v) if axis == 1 else (u, v, w)

    m = len(polygon)
    bottom = [mesh.vertex(point(u, v, lo)) for u, v in polygon]
    top = [mesh.vertex(point(u, v, hi)) for u, v in polygon]
    # The (u, v, w) frame is right-handed for axis 2 and left-handed for axis 1.
    flip = axis == 1
    for k in range(1, m - 1):
        if flip:
            mesh.tri(top[0], top[k + 1], top[k])
            mesh.tri(bottom[0], bottom[k], bottom[k + 1])
        else:
            mesh.tri(top[0], top[k], top[k + 1])
            mesh.tri(bottom[0], bottom[k + 1], bottom[k])
    for k in range(m):
        a, b = k, (k + 1) % m
        if flip:
            mesh.quad(bottom[a], top[a], top[b], bottom[b])
        else:
            mesh.quad(bottom[a], bottom[b], top[b], top[a])


def box(mesh, lo, hi):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    prism(mesh, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)], 2, z0, z1)


def lathe(mesh, centre, profile, sectors):
    """A solid of revolution about the vertical through `centre`: profile is
    (height, radius) from the bottom (radius > 0) to the top (radius 0 or > 0)."""
    cx, cy, cz = centre
    bottom = mesh.vertex((cx, cy + profile[0][0], cz))
    rings = []
    for h, r in profile:
        if r == 0:
            rings.append(None)
            continue
        rings.append([mesh.vertex((cx + r * math.cos(2 * math.pi * s / sectors), cy + h,
                                   cz + r * math.sin(2 * math.pi * s / sectors))) for s in range(sectors)])
    for s in range(sectors):
        t = (s + 1) % sectors
        mesh.tri(bottom, rings[0][s], rings[0][t])
    for i in range(len(profile) - 1):
        r0, r1 = rings[i], rings[i + 1]
        for s in range(sectors):
            t = (s + 1) % sectors
            if r1 is None:
                tip = mesh.vertex((cx, cy + profile[i + 1][0], cz)) if s == 0 else tip
                mesh.tri(r0[s], tip, r0[t])
            else:
                mesh.quad(r0[s], r1[s], r1[t], r0[t])
    if rings[-1] is not None:
        top = mesh.vertex((cx, cy + profile[-1][0], cz))
        for s in range(sectors):
            t = (s + 1) % sectors
            mesh.tri(top, rings[-1][t], rings[-1][s])


# ---- the orbiter -------------------------------------------------------------------

def fuselage_section(x, half_width, bottom, top, count=24, power=2.6):
    """A rounded-rectangle (superellipse) section at x, counter-clockwise seen from +x
    (z to the left, y up: angle from +z toward +y is clockwise seen from +x, so we go
    from +y toward +z)."""
    cy, b = 0.5 * (bottom + top), 0.5 * (top - bottom)
    ring = []
    for k in range(count):
        a = 2 * math.pi * k / count
        c, s = math.cos(a), math.sin(a)
        y = cy + b * math.copysign(abs(s) ** (2 / power), s)
        z = -half_width * math.copysign(abs(c) ** (2 / power), c)
        ring.append((x, y, z))
    return ring


def shuttle():
    mesh = Mesh()
    belly = 2.0
    # (x, half width, bottom, top): the nose at x = +18.5, the tail at -18.5.
    stations = [(-17.2, 2.2, belly + 0.6, belly + 5.4), (-14.0, 2.6, belly, belly + 5.6),
                (6.0, 2.6, belly, belly + 5.6), (9.5, 2.5, belly, belly + 5.6),  # crew cabin
                (12.0, 2.3, belly + 0.05, belly + 5.0), (14.5, 1.9, belly + 0.2, belly + 4.0),
                (16.5, 1.3, belly + 0.5, belly + 3.1), (17.8, 0.7, belly + 0.9, belly + 2.3)]
    sections = [fuselage_section(x, w, b, t) for x, w, b, t in stations]
    loft(mesh, sections, end_tip=(18.5, belly + 1.5, 0.0))
    # Delta wings with the leading-edge glove, 0.8 m thick at the root line.
    for side in (1, -1):
        plan = [(8.0, 2.4), (-4.0, 5.6), (-14.6, 11.9), (-16.8, 11.9), (-16.8, 2.4)]  # counter-clockwise in (x, z)
        if side < 0:
            plan = [(u, -v) for u, v in reversed(plan)]
        prism(mesh, plan, 1, belly + 0.1, belly + 0.9)
    # Tail fin (x, y) and its rudder, 0.8 m thick.
    prism(mesh, [(-18.5, belly + 5.0), (-9.8, belly + 5.0), (-15.6, 17.3), (-18.3, 17.3)], 2, -0.4, 0.4)
    # OMS pods either side of the fin.
    for side in (1, -1):
        z0 = 1.2 * side
        pod = [fuselage_section(x, 0.9, belly + 4.3, belly + 6.1) for x in (-18.0, -11.0)]
        pod = [[(p[0], p[1], p[2] + z0) for p in ring] for ring in pod]
        loft(mesh, pod, end_tip=(-9.5, belly + 5.5, z0))
    # Three main engine bells behind the tail.
    for y, z in ((belly + 4.2, 0.0), (belly + 2.4, 1.3), (belly + 2.4, -1.3)):
        bell = []
        for x, r in ((-20.6, 1.15), (-19.0, 0.75), (-17.4, 0.45)):
            bell.append([(x, y + r * math.sin(2 * math.pi * k / 16), z - r * math.cos(2 * math.pi * k / 16))
                         for k in range(16)])
        loft(mesh, bell)
    # Landing gear: a nose leg and two main legs down to the ground.
    box(mesh, (11.6, 0.0, -0.35), (12.4, belly + 0.3, 0.35))
    for side in (1, -1):
        box(mesh, (-5.4, 0.0, 3.2 * side - 0.5), (-4.2, belly + 0.3, 3.2 * side + 0.5))
    return mesh


# ---- the castle ----------------------------------------------------------------------

def castle():
    mesh = Mesh()
    hx, hz = 65.0, 45.0  # half extents of the curtain wall's centre line
    wall_h, thick = 14.0, 3.0
    merlon_h, merlon_w, gap = 2.0, 2.5, 2.5
    # Curtain walls: four boxes, and merlons along their tops.
    walls = [((-hx - thick / 2, 0, -hz), (-hx + thick / 2, wall_h, hz)),
             ((hx - thick / 2, 0, -hz), (hx + thick / 2, wall_h, hz)),
             ((-hx, 0, -hz - thick / 2), (hx, wall_h, -hz + thick / 2)),
             ((-hx, 0, hz - thick / 2), (hx, wall_h, hz + thick / 2))]
    for lo, hi in walls:
        box(mesh, lo, hi)
        along_x = (hi[0] - lo[0]) > (hi[2] - lo[2])
        length = (hi[0] - lo[0]) if along_x else (hi[2] - lo[2])
        count = int((length - 16.0) // (merlon_w + gap))
        start = -0.5 * (count * (merlon_w + gap) - gap)
        for k in range(count):
            a = start + k * (merlon_w + gap)
            if along_x:
                box(mesh, (a, wall_h, lo[2]), (a + merlon_w, wall_h + merlon_h, hi[2]))
            else:
                box(mesh, (lo[0], wall_h, a), (hi[0], wall_h + merlon_h, a + merlon_w))
    # Round corner towers with conical roofs.
    for cx in (-hx, hx):
        for cz in (-hz, hz):
            lathe(mesh, (cx, 0.0, cz), [(0.0, 7.0), (22.0, 7.0), (22.0, 8.2), (26.0, 8.2), (26.0, 7.4),
                                        (36.0, 0.0)], 20)
    # A gatehouse of two square towers flanking the gate in the front (-x) wall.
    for side in (1, -1):
        box(mesh, (-hx - 5.0, 0.0, side * 6.0 - 4.5), (-hx + 4.0, 20.0, side * 6.0 + 4.5))
        for k in range(3):
            z = side * 6.0 - 4.0 + 3.2 * k
            box(mesh, (-hx - 5.0, 20.0, z), (-hx - 3.0, 22.0, z + 1.8))
    box(mesh, (-hx - 3.5, 9.0, -2.0), (-hx + 3.0, 17.0, 2.0))  # the arch's lintel block
    # The keep: a square tower 38 m with merlons and a pyramid roof.
    kx, kz, kh = 10.0, 0.0, 38.0
    box(mesh, (kx - 11, 0.0, kz - 11), (kx + 11, kh, kz + 11))
    for k in range(4):
        a = -11 + 1.0 + 5.5 * k
        for lo, hi in (((kx - 11, kh, kz + a), (kx - 9.5, kh + 2.5, kz + a + 3.0)),
                       ((kx + 9.5, kh, kz + a), (kx + 11, kh + 2.5, kz + a + 3.0)),
                       ((kx + a, kh, kz - 11), (kx + a + 3.0, kh + 2.5, kz - 9.5)),
                       ((kx + a, kh, kz + 9.5), (kx + a + 3.0, kh + 2.5, kz + 11))):
            box(mesh, lo, hi)
    lathe(mesh, (kx, kh, kz), [(0.0, 9.0), (16.0, 0.0)], 4)
    return mesh


def castle_trim():
    mesh = Mesh()
    hx, hz, thick, proud = 65.0, 45.0, 3.0, 0.3
    ox, oz = hx + thick / 2, hz + thick / 2  # the outer faces of the curtain walls
    # The gate in the front wall, between the gatehouse towers.
    box(mesh, (-ox - proud, 0.0, -1.9), (-ox + 0.1, 8.5, 1.9))
    # The string course around the outside, in pieces between the corner towers (and
    # the gatehouse on the front).
    y0, y1 = 6.0, 7.2
    for z0, z1 in ((-hz + 7.5, -10.5), (10.5, hz - 7.5)):
        box(mesh, (-ox - proud, y0, z0), (-ox + 0.1, y1, z1))
    box(mesh, (ox - 0.1, y0, -hz + 7.5), (ox + proud, y1, hz - 7.5))
    for sign in (1, -1):
        z0, z1 = (oz - 0.1, oz + proud) if sign > 0 else (-oz - proud, -oz + 0.1)
        box(mesh, (-hx + 7.5, y0, z0), (hx - 7.5, y1, z1))
    # Arrow slits, 0.8 m wide, every 8 m.
    slit = (8.5, 11.0, 0.4)
    for k in range(-3, 4):
        z = 8.0 * k + (4.0 if k >= 0 else -4.0)
        if abs(z) > hz - 10 or abs(z) < 11:
            continue
        box(mesh, (-ox - proud, slit[0], z - slit[2]), (-ox + 0.1, slit[1], z + slit[2]))
        box(mesh, (ox - 0.1, slit[0], z - slit[2]), (ox + proud, slit[1], z + slit[2]))
    for k in range(-6, 7):
        x = 8.0 * k + 4.0
        if abs(x) > hx - 10:
            continue
        for sign in (1, -1):
            z0, z1 = (oz - 0.1, oz + proud) if sign > 0 else (-oz - proud, -oz + 0.1)
            box(mesh, (x - slit[2], slit[0], z0), (x + slit[2], slit[1], z1))
    return mesh


# ---- output ------------------------------------------------------------------------

def check(mesh, name):
    for f in mesh.faces:
        a, b, c = (mesh.verts[i] for i in f)
        u = [b[i] - a[i] for i in range(3)]
        v = [c[i] - a[i] for i in range(3)]
        n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        assert math.sqrt(sum(x * x for x in n)) > 1e-9, name + ": degenerate triangle"
    # Closed and consistently wound: every directed edge appears once, its reverse once.
    edges = {}
    for f in mesh.faces:
        for k in range(3):
            e = (f[k], f[(k + 1) % 3])
            edges[e] = edges.get(e, 0) + 1
    for (a, b), count in edges.items():
        assert count == 1 and edges.get((b, a)) == 1, name + ": not closed or not consistently wound"


def outward(mesh, name):
    # Every closed part (a connected set of triangles) has a positive signed volume:
    # its normals point outwards.
    parent = list(range(len(mesh.verts)))

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for f in mesh.faces:
        for k in (1, 2):
            parent[find(f[k])] = find(f[0])
    volume = {}
    for f in mesh.faces:
        a, b, c = (mesh.verts[i] for i in f)
        v = (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
             a[2] * (b[0] * c[1] - b[1] * c[0])) / 6
        volume[find(f[0])] = volume.get(find(f[0]), 0.0) + v
    assert all(v > 0 for v in volume.values()), name + ": a part has inward normals"


def fmt(x):
    s = repr(round(x, 6))
    return s[:-2] if s.endswith(".0") else s


def write_obj(mesh, name, comment):
    check(mesh, name)
    outward(mesh, name)
    with open(os.path.join(HERE, name), "w", newline="\n") as f:
        f.write("# %s\n# generated by make_scene_meshes.py (CC0); %d vertices, %d triangles\n"
                % (comment, len(mesh.verts), len(mesh.faces)))
        for v in mesh.verts:
            f.write("v %s %s %s\n" % tuple(fmt(c) for c in v))
        for a, b, c in mesh.faces:
            f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))
    print("%s: %d triangles" % (name, len(mesh.faces)))


if __name__ == "__main__":
    write_obj(shuttle(), "shuttle.obj", "a space-shuttle-like orbiter on its gear, 37 m long, nose toward +x")
    write_obj(castle(), "castle.obj", "a castle 130 m x 90 m, keep 54 m to the roof's tip, gate toward -x")
    write_obj(castle_trim(), "castle_trim.obj", "the castle's gate, string course and arrow slits (frame of castle.obj)")
