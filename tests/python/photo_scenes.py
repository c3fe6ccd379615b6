"""Synthetic photographs whose truth is known, for the single-image estimate (thesis §3.4,
§5.2): Fig. 3.10's four geometries under one directional light, rendered by the
translucency engine as opaque, translucent and very translucent objects, and a
Lambertian sphere in closed form (numpy alone: no arcus code in it).

The camera looks down −z with y up, so its frame is the world's: a light at azimuth θ
(in the image plane, from +x) and zenith φ (from the camera's axis) lies toward
(sinφ cosθ, sinφ sinθ, cosφ)."""

from functools import lru_cache
from pathlib import Path

import numpy as np

from arcus.translucency import Dipole, read_mesh, render

MESHES = Path(__file__).resolve().parents[2] / "data" / "meshes"

# Fig. 3.10's light.
FIG_3_10_LIGHT = (145.0, 45.0)

# The diffuse length ℓ_d (mm) of each material on objects 40–65 mm across: 1 mm gives
# a surface as good as opaque (the light spreads 1/20 of a radius), 12 mm one that
# glows through (the default sample spacing 1/σ′_t keeps the opaque render free of the
# samples' pattern, at 3–6 s a render).
MATERIALS = {"opaque": 1.0, "translucent": 4.0, "very translucent": 12.0}
MM_PER_UNIT = 20.0
SIZE = 128


# A coloured material: R_total and ℓ_d (mm) per channel, so that each channel is its own
# check; on objects 40–52 mm across.
COLOURED_R_TOTAL, COLOURED_DIFFUSE_LENGTH = np.array([0.85, 0.6, 0.35]), [6.0, 4.0, 2.0]


@lru_cache(maxsize=None)
def coloured_photograph(geometry):
    """The engine's render of `geometry` in the coloured material under Fig. 3.10's light
    (irradiance 1), orthographic; and the photo's scale, mm a pixel."""
    mesh = geometries()[geometry]
    extent = float(np.abs(mesh[0][:, :2]).max())
    camera = {"position": (0, 0, 5), "look_at": (0, 0, 0), "up": (0, 1, 0), "width": SIZE, "height": SIZE}
    material = Dipole.from_reflectance(COLOURED_R_TOTAL, COLOURED_DIFFUSE_LENGTH, eta=1.3)
    photo = render(material, mesh, [(toward(*FIG_3_10_LIGHT), 1.0)], camera, ortho_height=2.4 * extent,
                   mm_per_unit=MM_PER_UNIT, highlight_deg=0)
    return photo, 2.4 * extent / SIZE * MM_PER_UNIT


def toward(azimuth_deg, zenith_deg):
    t, p = np.radians(azimuth_deg), np.radians(zenith_deg)
    return np.array([np.sin(p) * np.cos(t), np.sin(p) * np.sin(t), np.cos(p)])


def angle_deg(a, b):
    """The angle between two directions, degrees."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(np.degrees(np.arccos(np.clip(a @ b / np.linalg.norm(a) / np.linalg.norm(b), -1, 1))))


def geometries():
    """Fig. 3.10's four: a sphere and three meshes (an ellipsoid, a torus tilted 60°
    toward the camera, a lumpy sphere), as (vertices, triangles) about the origin."""
    v, f = read_mesh(MESHES / "icosphere.obj")
    u = v / np.linalg.norm(v, axis=1, keepdims=True)
    around = np.arctan2(u[:, 1], u[:, 0])
    lumpy = v * (1 + 0.12 * np.sin(3 * around) * (1 - u[:, 2] ** 2) + 0.08 * u[:, 2])[:, None]
    tv, tf = read_mesh(MESHES / "torus.obj")
    c, s = np.cos(np.radians(60)), np.sin(np.radians(60))
    tilt = np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    return {"sphere": (v, f), "ellipsoid": (v * np.array([1.3, 0.8, 0.9]), f), "torus": (tv @ tilt.T, tf),
            "lumpy sphere": (lumpy, f)}


@lru_cache(maxsize=None)
def fig_3_10_photo(geometry, material):
    """Fig. 3.10's photo of one geometry and material, rendered once a session."""
    return photograph(geometries()[geometry], MATERIALS[material], [(*FIG_3_10_LIGHT, 1.0)])


def photograph(mesh, diffuse_length_mm, lights, size=SIZE):
    """The engine's render of `mesh` of a grey material (R_total 0.8, the given ℓ_d, η
    1.3) under `lights` ([(azimuth, zenith, irradiance)]), orthographic, framed with a
    fifth of the view to spare: a :class:`arcus.translucency.Rendered`."""
    vertices = mesh[0]
    extent = float(np.abs(vertices[:, :2]).max())
    dipole = Dipole.from_reflectance([0.8] * 3, [diffuse_length_mm] * 3, eta=1.3)
    camera = {"position": (0, 0, 5), "look_at": (0, 0, 0), "up": (0, 1, 0), "width": size, "height": size}
    return render(dipole, mesh, [(toward(a, z), e) for a, z, e in lights], camera, ortho_height=2.4 * extent,
                  mm_per_unit=MM_PER_UNIT, highlight_deg=0)


def lambertian_sphere(lights, size=SIZE, radius=50.0, ambient=0.0):
    """A Lambertian sphere in closed form: radiance Σ I max(0, n·l) (+ ambient) at each
    pixel centre inside a disc of `radius` pixels; (image (size, size, 3) float32,
    matte (size, size) bool, normals (size, size, 3))."""
    y, x = np.mgrid[0:size, 0:size] + 0.5
    u, v = (x - size / 2) / radius, -(y - size / 2) / radius
    inside = u * u + v * v < 1
    normals = np.stack([u, v, np.sqrt(np.clip(1 - u * u - v * v, 0, 1))], -1)
    luminance = np.full((size, size), float(ambient))
    for a, z, e in lights:
        luminance += e * np.clip(normals @ toward(a, z), 0, None)
    luminance = np.where(inside, luminance, 0)
    return np.repeat(luminance[..., None], 3, -1).astype(np.float32), inside, np.where(inside[..., None], normals, 0)


def seen_normals(mesh, size=SIZE):
    """What :func:`photograph`'s camera sees of `mesh`, cast here in numpy (no arcus
    code): per pixel centre the nearest triangle along −z, its vertex normals
    (area-weighted) interpolated there; (normals (size, size, 3), seen (size, size))."""
    vertices, triangles = np.asarray(mesh[0], float), np.asarray(mesh[1], int)
    extent = float(np.abs(vertices[:, :2]).max())
    pixel = 2.4 * extent / size
    corner = np.cross(vertices[triangles[:, 1]] - vertices[triangles[:, 0]],
                      vertices[triangles[:, 2]] - vertices[triangles[:, 0]])
    vertex_normals = np.zeros_like(vertices)
    for k in range(3):
        np.add.at(vertex_normals, triangles[:, k], corner)
    vertex_normals /= np.linalg.norm(vertex_normals, axis=1, keepdims=True)
    centres = (np.arange(size) + 0.5) * pixel - 1.2 * extent
    px, py = np.meshgrid(centres, -centres)
    depth = np.full((size, size), -np.inf)
    normals = np.zeros((size, size, 3))
    for t in triangles:
        a, b, c = vertices[t]
        lo, hi = np.minimum(np.minimum(a, b), c), np.maximum(np.maximum(a, b), c)
        cols = np.nonzero((centres >= lo[0]) & (centres <= hi[0]))[0]
        rows = np.nonzero((-centres >= lo[1]) & (-centres <= hi[1]))[0]
        if not len(cols) or not len(rows):
            continue
        x, y = px[np.ix_(rows, cols)], py[np.ix_(rows, cols)]
        det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
        if abs(det) < 1e-15:
            continue
        u = ((x - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (y - a[1])) / det
        v = ((b[0] - a[0]) * (y - a[1]) - (x - a[0]) * (b[1] - a[1])) / det
        inside = (u >= 0) & (v >= 0) & (u + v <= 1)
        z = a[2] + u * (b[2] - a[2]) + v * (c[2] - a[2])
        nearer = inside & (z > depth[np.ix_(rows, cols)])
        if not nearer.any():
            continue
        n = ((1 - u - v)[..., None] * vertex_normals[t[0]] + u[..., None] * vertex_normals[t[1]]
             + v[..., None] * vertex_normals[t[2]])
        n /= np.linalg.norm(n, axis=-1, keepdims=True)
        block_depth, block_normals = depth[np.ix_(rows, cols)], normals[np.ix_(rows, cols)]
        block_depth[nearer], block_normals[nearer] = z[nearer], n[nearer]
        depth[np.ix_(rows, cols)], normals[np.ix_(rows, cols)] = block_depth, block_normals
    return normals, np.isfinite(depth)
