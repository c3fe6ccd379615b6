"""A rendered sky judged as photographs of bows and halos are measured: its light against
the angle from the sun (:func:`radial_profile`), and where closed forms put a scene's
features (:func:`reference_angles`), which ``arcus render --profile`` plots side by side."""

import numpy as np

from . import halo, rainbow
from ._args import to_float
from ._errors import ArgumentError
from .sky import load_scene


def radial_profile(image, step=0.1):
    """The sky's light against the scattering angle θ from the sun (what photographs of
    bows and halos are measured by): ``image`` an :class:`arcus.sky.SkyImage`, binned every
    ``step`` degrees.  Returns a dict of arrays over the bins that hold pixels: ``theta``
    (their centres), ``Y`` (the pixels' mean luminance), ``x``, ``y`` (the chromaticity
    of their mean XYZ) and ``pixels`` (how many)."""
    step = to_float(step, "step")
    if not step > 0:
        raise ArgumentError("step must be > 0 degrees, got %r" % step)
    theta = np.asarray(image.theta, dtype=float).ravel()
    xyz = np.asarray(image.xyz, dtype=float).reshape(-1, 3)
    keep = np.isfinite(theta) & np.all(np.isfinite(xyz), axis=1)
    bins = np.floor(theta[keep] / step).astype(np.int64)
    if bins.size == 0:
        raise ArgumentError("the image has no pixel with a scattering angle")
    first = bins.min()
    counts = np.bincount(bins - first)
    sums = np.stack([np.bincount(bins - first, weights=xyz[keep, c], minlength=counts.size) for c in range(3)])
    full = counts > 0
    mean = sums[:, full] / counts[full]
    total = np.maximum(mean.sum(axis=0), 1e-300)
    return {"theta": (np.flatnonzero(full) + first + 0.5) * step, "Y": mean[1], "x": mean[0] / total,
            "y": mean[1] / total, "pixels": counts[full]}


def reference_angles(scene):
    """Where closed forms put a scene's features, as scattering angles [deg] from the
    sun spanning 400–700 nm: [(low, high, label), ...].  Water drops: Descartes'
    primary and secondary bows (:func:`arcus.rainbow.rainbow_angle`; a bow's maximum lies
    within a degree inside, by the drops' size); randomly oriented ice: the 22° and
    46° halos' inner edges (:func:`arcus.halo.halo_angle`); plates with vertical axes:
    the parhelia at the sun's elevation (Bravais, :func:`arcus.halo.parhelion_angle`)."""
    scene = load_scene(scene)
    nm = (400.0, 700.0)
    out = []
    for p in scene.get("rain", {}).get("populations", []):
        if p.get("shape") in ("sphere", "raindrop"):
            n = [rainbow.refractive_index("water", w) for w in nm]
            for term, label in ((2, "primary bow"), (3, "secondary bow")):
                angles = [rainbow.rainbow_angle(k, term) for k in n]
                out.append((min(angles), max(angles), label))
        elif p.get("shape") == "crystal" and p.get("orientation", "random") == "random":
            for apex, label in ((60.0, "22° halo"), (90.0, "46° halo")):
                angles = [halo.halo_angle(w, apex) for w in nm]
                out.append((min(angles), max(angles), label))
        elif p.get("shape") == "crystal" and p.get("crystal") == "plate":
            e = float(scene.get("sun", {}).get("elevation_deg", 0.0))
            angles = [halo.parhelion_angle(rainbow.refractive_index("ice", w), e)[0] for w in nm]
            out.append((min(angles), max(angles), "parhelia"))
    unique = []
    for entry in out:  # two populations of drops name the same bows once
        if entry not in unique:
            unique.append(entry)
    return unique
