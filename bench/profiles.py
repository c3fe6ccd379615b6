"""What the sky benchmarks share: a profile in θ seen through the sun's disc, the CIE
weights of a wavelength sampling, and rows written as CSV."""

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


# Wyman, Sloan & Shirley (2013), multi-lobe fit to the CIE 1931 2° observer: (weight, μ, σ below, σ above).
CMF = {"x": [(1.056, 599.8, 37.9, 31.0), (0.362, 442.0, 16.0, 26.7), (-0.065, 501.1, 20.4, 26.2)],
       "y": [(0.821, 568.8, 46.9, 40.5), (0.286, 530.9, 16.3, 31.1)],
       "z": [(1.217, 437.0, 11.8, 36.0), (0.681, 459.0, 26.0, 13.8)]}


def cmf(name, lam):
    total = np.zeros_like(lam)
    for weight, mu, below, above in CMF[name]:
        sigma = np.where(lam < mu, below, above)
        total += weight * np.exp(-0.5 * ((lam - mu) / sigma) ** 2)
    return total


def band_weights(wl):
    """(3, W): each sample's CIE X, Y, Z weight, the integral over the band around it
    (halfway to its neighbours, the ends' half bands included)."""
    edges = np.concatenate([[wl[0]], (wl[1:] + wl[:-1]) / 2, [wl[-1]]])
    out = np.zeros((3, wl.size))
    for i in range(wl.size):
        lam = np.linspace(edges[i], edges[i + 1], 41)
        for c, name in enumerate("xyz"):
            out[c, i] = np.trapezoid(cmf(name, lam), lam)
    return out


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
