"""Writes the ground textures of the render scenes (README.md here): procedural, so
that no photograph's licence is needed; numpy, scipy and Pillow (matplotlib's).
Run again to rewrite them (the seeds are fixed).

dry_lakebed.jpg: a playa like Rogers Dry Lake's, where the shuttle landed
(scenes/inferior_mirage.json), 1024 x 1024 texels over 64 m (6.25 cm a texel), tiling
in both directions: buff clay (sRGB about 200, 184, 160: albedo near 0.5, as playas
measure) mottled by damper and drier patches metres across, split by desiccation
cracks into polygons of 0.3-1.2 m.
"""
import pathlib

import numpy as np
from PIL import Image
from scipy.spatial import cKDTree

SIZE = 1024  # texels a side
TILE_M = 64.0  # metres a side


def periodic_noise(rng, size, beta, lo_m, hi_m):
    """White noise filtered to a 1/f^beta spectrum between wavelengths hi_m and lo_m
    metres: periodic in both directions, since it is made by an FFT. Unit variance."""
    f = np.fft.fftfreq(size, d=TILE_M / size)
    k = np.hypot(*np.meshgrid(f, f, indexing="ij"))
    band = (k >= 1 / hi_m) & (k <= 1 / lo_m)
    amplitude = np.where(band, np.maximum(k, 1e-9) ** (-beta / 2), 0.0)
    field = np.fft.ifft2(np.fft.fft2(rng.standard_normal((size, size))) * amplitude).real
    return (field - field.mean()) / field.std()


def crack_distance(rng, size, cells):
    """Per texel, the gap between its distances to the nearest and second-nearest of
    `cells` random seeds (0 on a Voronoi edge), in texels; seeds repeat across the
    tile's edges so the pattern tiles."""
    seeds = rng.uniform(0, size, (cells, 2))
    tiled = np.concatenate([seeds + size * np.array([dx, dy]) for dx in (-1, 0, 1) for dy in (-1, 0, 1)])
    y, x = np.mgrid[0:size, 0:size]
    d, _ = cKDTree(tiled).query(np.column_stack([x.ravel() + 0.5, y.ravel() + 0.5]), k=2)
    return (d[:, 1] - d[:, 0]).reshape(size, size)


def dry_lakebed(rng):
    clay = np.array([200, 184, 160]) / 255.0
    patches = periodic_noise(rng, SIZE, 3.0, 2.0, 32.0)   # damp and dry patches, metres across
    grain = periodic_noise(rng, SIZE, 1.0, 0.125, 1.0)    # the crust's texture
    polygons = 0.6 / (TILE_M / SIZE)                       # mean crack spacing in texels
    gap = crack_distance(rng, SIZE, int((SIZE / polygons) ** 2))
    cracks = np.clip(1.0 - gap / 1.5, 0.0, 1.0)          # lines about 1.5 texels wide
    shade = 1.0 + 0.08 * patches + 0.03 * grain - 0.35 * cracks
    tint = 1.0 + 0.02 * patches[..., None] * np.array([1.0, 0.0, -1.0])  # damper: a little cooler
    return np.clip(clay * shade[..., None] * tint, 0, 1)


def main():
    here = pathlib.Path(__file__).resolve().parent
    rgb = dry_lakebed(np.random.default_rng(22))
    Image.fromarray(np.round(rgb * 255).astype(np.uint8)).save(here / "dry_lakebed.jpg", quality=90)


if __name__ == "__main__":
    main()
