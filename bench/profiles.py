"""What the sky benchmarks share: a profile in θ seen through the sun's disc, and rows
written as CSV."""

import csv

import numpy as np

#: The sun's angular radius [deg].
SUN_RADIUS_DEG = 0.2665


def over_the_sun(theta, profile):
    """``profile`` (…, T) on uniformly spaced ``theta`` averaged over the sun's disc, as a
    sky shows it: offsets across the disc weighted by the chord there."""
    x = np.linspace(-SUN_RADIUS_DEG, SUN_RADIUS_DEG, 201)
    w = np.sqrt(np.maximum(SUN_RADIUS_DEG ** 2 - x ** 2, 0.0))
    w /= w.sum()
    profile = np.asarray(profile, dtype=float)
    flat = profile.reshape(-1, profile.shape[-1])
    out = sum(wi * np.array([np.interp(theta + xi, theta, p) for p in flat]) for xi, wi in zip(x, w))
    return out.reshape(profile.shape)


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
