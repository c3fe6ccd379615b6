"""A mirage drawn as its rays, as papers on mirages draw them: the rays of a render
scene's image, a fan down its centre column, traced through the scene's air
(:meth:`arcus.Context.advance`) as height above the ground against distance, beside the
same rays through the same air without its inversions — what the eye would see
without the mirage.  ``arcus render SCENE --profile PATH`` plots them.

Where the fan folds (rays from different rows crossing at the object's distance), one
height is seen at several rows: the mirage's multiple images.  Rays stop where they
reach the ground."""

import math

import numpy as np

from ._constants import EARTH_RADIUS
from ._errors import ArgumentError
from .context import _owned_context
from .fields import StandardAtmosphere

#: How far the fan is traced without an object to reach (the Novaya Zemlya sun): far
#: enough for the lowest rays that miss the ground to climb out of a ground-level layer.
OPEN_REACH_M = 200e3


def _unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def _heights(points, spherical):
    """Height above the ground and distance along it from the first point, per point."""
    if not spherical:
        return points[:, 1], np.hypot(points[:, 0] - points[0, 0], points[:, 2] - points[0, 2])
    r = np.linalg.norm(points, axis=1)
    cos = np.clip(points @ points[0] / (r * r[0]), -1.0, 1.0)
    return r - EARTH_RADIUS, EARTH_RADIUS * np.arccos(cos)


def _object_distance(doc, eye, spherical):
    """The distance to the scene's farthest object (a mesh) [m], or None."""
    far = None
    for obj in doc.get("objects", []):
        if obj.get("type") == "mesh" and "translate" in obj:
            _, distance = _heights(np.array([eye, obj["translate"]], dtype=float), spherical)
            far = max(far or 0.0, float(distance[1]))
    return far


def ray_fan(doc, *, rows=33, inversions=True, context=None):
    """The rays of ``rows`` rows spread evenly down the centre column of a render
    scene's image (``doc``: the scene as read, with an "atmosphere" field), traced
    through its air (``inversions=False``: without the inversions).  Returns a dict:
    ``elevation_deg`` (rows,) each ray's apparent elevation above the eye's horizontal,
    ``distance`` and ``height`` (lists of arrays, m, along each ray until it meets the
    ground or reaches ``reach``: 1.2 times the farthest object's distance, else
    :data:`OPEN_REACH_M`), ``object_distance`` (m, or None) and ``layers`` [(base, top,
    delta_t)]."""
    field_doc = doc.get("field", {})
    if field_doc.get("type") != "atmosphere":
        raise ArgumentError("a ray fan needs a scene whose field is an atmosphere, got field type %r"
                            % (field_doc.get("type"),))
    spherical = bool(field_doc.get("spherical", False))
    layers = [(float(i["base"]), float(i["top"]), float(i["delta_t"])) for i in field_doc.get("inversions", [])]
    field = StandardAtmosphere(spherical=spherical, wavelength=float(field_doc.get("wavelength", 550.0)),
                               inversions=layers if inversions else ())
    camera = doc["camera"]
    eye = np.asarray(camera["position"], dtype=float)
    forward = _unit(np.asarray(camera["look_at"], dtype=float) - eye)
    up = np.asarray(camera.get("up", [0, 1, 0]), dtype=float)
    up = _unit(up - (up @ forward) * forward)
    height = int(camera.get("height", 400))
    # row centres as the renderer's pinhole camera places them, top to bottom
    picked = np.linspace(0, height - 1, rows).round().astype(int)
    screen = 1 - 2 * (picked + 0.5) / height
    tan_half = math.tan(math.radians(float(camera["vfov_deg"])) / 2)
    directions = np.array([_unit(forward + s * tan_half * up) for s in screen])
    local_up = _unit(eye) if spherical else np.array([0.0, 1.0, 0.0])
    elevation = np.degrees(np.arcsin(np.clip(directions @ local_up, -1.0, 1.0)))
    object_distance = _object_distance(doc, eye, spherical)
    reach = 1.2 * object_distance if object_distance else OPEN_REACH_M
    with _owned_context(context) as ctx:
        result = ctx.advance(field, np.tile(eye, (rows, 1)), directions, length=reach * 1.01, record_path=True,
                             rtol=1e-9, atol=1e-9)
    distances, heights = [], []
    for path in result.paths:
        points = path if len(path) and np.allclose(path[0], eye) else np.vstack([eye, path])
        h, d = _heights(points, spherical)
        end = np.flatnonzero(h < 0)
        stop = end[0] + 1 if end.size else h.size
        distances.append(d[:stop])
        heights.append(h[:stop])
    return {"elevation_deg": elevation, "distance": distances, "height": heights, "reach": reach,
            "object_distance": object_distance, "layers": layers}


def write_ray_fan(path, doc, context=None):
    """The scene's ray fan with and without its inversions: a CSV (ray, elevation,
    inversions on/off, distance, height per point) or a plot (.png, .svg, .pdf)."""
    fans = {on: ray_fan(doc, inversions=on, context=context) for on in (True, False)}
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.suffix.lower() == ".csv":
        with open(path, "w") as f:
            f.write("ray,elevation_deg,inversions,distance_m,height_m\n")
            for on, fan in fans.items():
                for i, (e, d, h) in enumerate(zip(fan["elevation_deg"], fan["distance"], fan["height"])):
                    for x, y in zip(d, h):
                        f.write("%d,%.6f,%d,%.3f,%.4f\n" % (i, e, int(on), x, y))
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fan, plain = fans[True], fans[False]
    km = fan["reach"] >= 20e3
    scale = 1e-3 if km else 1.0
    fig, ax = plt.subplots(figsize=(5.2, 3.4))
    # the layers and, where there is one, the top row's height at the object
    top = 1.5 * max((t for _, t, _ in fan["layers"]), default=1.0)
    if fan["object_distance"]:
        d, h = fan["distance"][0], fan["height"][0]
        top = max(top, float(np.interp(fan["object_distance"], d, h)))
        ax.axvline(fan["object_distance"] * scale, color="k", lw=0.8, ls=":")
        ax.annotate("object", (fan["object_distance"] * scale, 1.02 * top), ha="center", va="bottom", fontsize=7)
    for base, layer_top, delta_t in fan["layers"]:
        ax.axhspan(base, layer_top, color="tab:orange" if delta_t > 0 else "tab:blue", alpha=0.12, lw=0)
    colours = plt.cm.viridis(np.linspace(0, 1, len(fan["height"])))
    for d, h in zip(plain["distance"], plain["height"]):
        ax.plot(d * scale, h, color="0.6", lw=0.6, ls="--")
    for c, d, h in zip(colours, fan["distance"], fan["height"]):
        ax.plot(d * scale, h, color=c, lw=0.8)
    ax.set_xlim(0, fan["reach"] * scale)
    ax.set_ylim(-0.02 * top, 1.1 * top)
    ax.set_xlabel("distance along the ground [%s]" % ("km" if km else "m"))
    ax.set_ylabel("height [m]")
    ax.set_title("rays of the image's centre column, top row (purple) to bottom (yellow);\n"
                 "dashed: the same rays without the inversions (shaded: %s)"
                 % ("warm layers" if any(t > 0 for *_, t in fan["layers"]) else "inversions"), fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
