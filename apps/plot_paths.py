#!/usr/bin/env python3
"""Draws the ray paths that arcus_trace wrote, in the plane of the fan.

    python3 apps/plot_paths.py out/mirage [--vscale K] [--out FILE]

Reads DIR/paths.csv and DIR/rays.csv (and DIR/scene.json, which arcus_trace writes
beside them, for the medium and the fan) and writes DIR/paths.png.  Rays are coloured
by their launch angle in the fan.

Frames:
  flat atmosphere       horizontal distance along the fan vs height y, ground at y = 0
  spherical atmosphere  distance along the Earth's surface vs height above it
  any other medium      the fan's plane: along its central direction vs across it
In the atmospheres the vertical scale is exaggerated to fill the figure unless
--vscale gives the exaggeration (1: true scale); the y label states the one used.
The fan's plane is always drawn at true scale.
A ray that reaches the ground is cut there and marked with x, and the title counts
the rays that dipped below their start and turned up again before the ground (the
mirage).
Without scene.json (a hand-made directory) the plane is fitted to the paths.
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)
import numpy as np  # noqa: E402
from mpl_toolkits.axes_grid1 import make_axes_locatable  # noqa: E402

EARTH_RADIUS = 6371000.0  # arcus.h, ARCUS_EARTH_RADIUS
HEIGHT_TOLERANCE = 1e-6  # m: closer than this to the ground is on it; a smaller dip is rounding


def unit(v):
    return v / np.linalg.norm(v)


def read_rays(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    column = lambda *names: np.array([[float(r[n]) for n in names] for r in rows])  # noqa: E731
    return {
        "origin": column("origin_x", "origin_y", "origin_z"),
        "direction": column("dir_x", "dir_y", "dir_z"),
        "status": [r["status"] for r in rows],
    }


def read_paths(path, count):
    """One (points × 3) array per ray, in ray order."""
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    rays = data[:, 0].astype(int)
    return [data[rays == i, 2:5] for i in range(count)]


def read_scene(directory):
    """The scene arcus_trace copied beside its output (a regular file: a FIFO or a device
    there would block or never end), or None."""
    path = os.path.join(directory, "scene.json")
    if not os.path.isfile(path):
        return None
    with open(path) as f:
        return json.load(f)


def fan_basis(scene, rays, paths):
    """(e1, e2, normal): e1 the fan's central direction, e2 = normal × e1, so that
    positive launch angles turn from e1 towards e2."""
    fan = (scene or {}).get("rays", {}).get("fan")
    if fan:
        e1 = unit(np.array(fan["direction"], float))
        normal = unit(np.array(fan["plane_normal"], float))
    else:  # explicit ray lists: the plane that fits the paths best
        points = np.concatenate(paths)
        _, _, vt = np.linalg.svd(points - points.mean(axis=0), full_matrices=False)
        normal = vt[2]
        mean_dir = rays["direction"].mean(axis=0)
        e1 = unit(mean_dir - mean_dir.dot(normal) * normal)
    return e1, np.cross(normal, e1), normal


def launch_angles(rays, e1, e2):
    d = rays["direction"]
    return np.degrees(np.arctan2(d @ e2, d @ e1))


class FlatAtmosphere:
    """x: horizontal distance from the fan's origin along the fan; y: height."""

    is_atmosphere = True
    labels = ("horizontal distance (m)", "height y (m)")

    def __init__(self, origin, e1):
        up = np.array([0.0, 1.0, 0.0])
        self.origin, self.along = origin, unit(e1 - e1.dot(up) * up)

    def project(self, p):
        return (p - self.origin) @ self.along, p[:, 1]


class SphericalAtmosphere:
    """x: distance along the Earth's surface from below the origin; y: height above it."""

    is_atmosphere = True
    labels = ("distance along the surface (m)", "height above the surface (m)")

    def __init__(self, origin, e1):
        self.up = unit(origin)
        self.along = unit(e1 - e1.dot(self.up) * self.up)

    def project(self, p):
        return EARTH_RADIUS * np.arctan2(p @ self.along, p @ self.up), np.linalg.norm(p, axis=1) - EARTH_RADIUS


class FanPlane:
    """x, y: the components along e1 and e2 (through the world origin, so that the
    medium's centre lands where it is)."""

    is_atmosphere = False
    labels = ("along the fan's direction (m)", "across, in the fan's plane (m)")

    def __init__(self, e1, e2):
        self.e1, self.e2 = e1, e2

    def project(self, p):
        return p @ self.e1, p @ self.e2


def make_frame(medium, origin, e1, e2):
    if medium.get("type") != "atmosphere":
        return FanPlane(e1, e2)
    if medium.get("spherical", False):
        return SphericalAtmosphere(origin, e1)
    return FlatAtmosphere(origin, e1)


def cut_at_ground(x, y):
    """The path up to where it first reaches height 0 (interpolated), and whether it did."""
    below = np.nonzero(y <= HEIGHT_TOLERANCE)[0]
    if len(below) == 0:
        return x, y, False
    k = below[0]
    if k == 0:
        return x[:1], y[:1], True
    t = y[k - 1] / (y[k - 1] - y[k])  # linear crossing of y = 0 in the last segment
    xg = x[k - 1] + t * (x[k] - x[k - 1])
    return np.append(x[:k], xg), np.append(y[:k], 0.0), True


def turned_up(y, grounded):
    """Dipped below its start, then climbed again without touching the ground."""
    if grounded or len(y) < 3:
        return False
    lowest = int(np.argmin(y))
    return y[0] - y[lowest] > HEIGHT_TOLERANCE and lowest < len(y) - 1


def draw_medium_outline(ax, medium, frame, origin, normal):
    """The sphere of a Luneburg or fish-eye medium, cut by the fan's plane."""
    if medium.get("type") not in ("luneburg", "fisheye") or not isinstance(frame, FanPlane):
        return
    centre = np.array(medium["center"], float)
    offset = (centre - origin).dot(normal)  # the fan's plane holds its origin
    cx, cy = frame.project(centre[None, :])
    r2 = medium["radius"] ** 2 - offset**2
    if r2 > 0:
        style = "-" if medium["type"] == "luneburg" else "--"  # fish-eye: R is only a scale
        ax.add_patch(plt.Circle((cx[0], cy[0]), np.sqrt(r2), fill=False, ls=style, color="0.4", lw=1))


def draw_atmosphere_marks(ax, medium):
    """The ground and the tops of the inversion layers."""
    ax.axhspan(ax.get_ylim()[0], 0, color="#c8b48c", alpha=0.5, lw=0)
    ax.axhline(0, color="#8c6d3f", lw=1)
    for inv in medium.get("inversions", []):
        ax.axhline(inv["top"], color="0.5", ls=":", lw=1)
        ax.annotate("inversion top", (ax.get_xlim()[1], inv["top"]), ha="right", va="bottom", fontsize=8,
                    color="0.4")


def set_vertical_exaggeration(ax, vscale):
    """Heights from the bottom of the plot up, in the range that draws a metre up
    vscale times as long as a metre along (the layout, unlike set_aspect's, stays)."""
    ax.figure.canvas.draw()
    box = ax.get_window_extent()
    (x0, x1), (y0, _) = ax.get_xlim(), ax.get_ylim()
    ax.set_ylim(y0, y0 + (x1 - x0) * box.height / box.width / vscale)


def vertical_exaggeration(ax):
    ax.figure.canvas.draw()
    box = ax.get_window_extent()
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    return (box.height / (y1 - y0)) / (box.width / (x1 - x0))


def load(directory):
    rays = read_rays(os.path.join(directory, "rays.csv"))
    paths_file = os.path.join(directory, "paths.csv")
    if not os.path.exists(paths_file):
        sys.exit(f"plot_paths: no {paths_file}: set \"record_path\": true in the scene")
    return rays, read_paths(paths_file, len(rays["status"])), read_scene(directory)


def add_colour_bar(fig, ax, norm):
    """Added first, so that the axes have their final size when scales are measured."""
    colour_axes = make_axes_locatable(ax).append_axes("right", size="3%", pad=0.1)  # as tall as the plot
    scalar = plt.cm.ScalarMappable(cmap="viridis", norm=norm)
    fig.colorbar(scalar, cax=colour_axes, label="launch angle in the fan (deg)")


def draw_paths(ax, frame, paths, colours):
    """Draws each path; returns how many turned up and how many reached the ground."""
    turned = grounded_count = 0
    for path, colour in zip(paths, colours):
        if len(path) == 0:
            continue
        x, y = frame.project(path)
        grounded = False
        if frame.is_atmosphere:
            x, y, grounded = cut_at_ground(x, y)
            turned += turned_up(y, grounded)
            grounded_count += grounded
        ax.plot(x, y, color=colour, lw=0.8)
        if grounded:
            ax.plot(x[-1], y[-1], "x", color="k", ms=4)
    return turned, grounded_count


def plot(directory, vscale, out_file):
    rays, paths, scene = load(directory)
    scene = scene or {}
    medium = scene.get("field", scene.get("medium", {}))  # "medium": the 0.9 spelling
    e1, e2, normal = fan_basis(scene, rays, paths)
    frame = make_frame(medium, rays["origin"][0], e1, e2)
    angles = launch_angles(rays, e1, e2)
    norm = plt.Normalize(angles.min(), angles.max())

    fig, ax = plt.subplots(figsize=(11, 5.5) if frame.is_atmosphere else (7.5, 7))
    add_colour_bar(fig, ax, norm)
    turned, grounded = draw_paths(ax, frame, paths, plt.get_cmap("viridis")(norm(angles)))
    ox, oy = frame.project(rays["origin"])
    ax.plot(ox, oy, "o", color="crimson", ms=5, ls="none")

    name = (scene or {}).get("name", os.path.basename(os.path.normpath(directory)))
    title = f"{name}: {len(paths)} rays"
    ax.set_xlabel(frame.labels[0])
    if frame.is_atmosphere:
        ax.set_ylim(bottom=min(ax.get_ylim()[0], -0.03 * np.ptp(ax.get_ylim())))  # room to show the ground
        if vscale is not None:
            set_vertical_exaggeration(ax, vscale)
        draw_atmosphere_marks(ax, medium)
        title += f"; {turned} dipped and turned up before the ground, {grounded} reached the ground"
        ax.set_ylabel(f"{frame.labels[1]}  (vertical scale ×{vertical_exaggeration(ax):.3g})")
    else:
        draw_medium_outline(ax, medium, frame, rays["origin"][0], normal)
        ax.set_aspect("equal")
        ax.set_ylabel(frame.labels[1])
    ax.set_title(title, fontsize=10)
    ax.grid(True, lw=0.3, alpha=0.5)
    fig.savefig(out_file, dpi=130, bbox_inches="tight")
    summary = f" ({turned} rays turned up, {grounded} reached the ground)" if frame.is_atmosphere else ""
    print(f"plot_paths: wrote {out_file}{summary}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("directory", help="an arcus_trace output directory (holds rays.csv, paths.csv)")
    parser.add_argument("--vscale", type=float, default=None,
                        help="vertical exaggeration of atmosphere plots (1: true scale; default: fill the "
                             "figure); other media are always drawn at true scale")
    parser.add_argument("--out", default=None, help="output image (default DIR/paths.png)")
    args = parser.parse_args()
    if args.vscale is not None and args.vscale <= 0:
        parser.error("--vscale must be positive")
    plot(args.directory, args.vscale, args.out or os.path.join(args.directory, "paths.png"))


if __name__ == "__main__":
    main()
