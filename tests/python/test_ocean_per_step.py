"""The ocean engine's per-step estimate (thesis §4.2, eq. 4.6): step subsampling
(march.step_subsample) is unbiased, and bad values are refused by name.  The search
itself is checked against brute force in tests/unit/test_photon_map.cpp."""
import math

import numpy as np
import pytest

import arcus
import arcus.ocean as ocean


def scene(subsample, estimator="per_step", steps=200):
    return {"name": "per_step", "water": {"preset": "mediterranean"},
            "grid": {"first_nm": 400, "last_nm": 700, "step_nm": 20},
            "lights": [{"type": "point", "position": [4, 0, -10], "spectrum": 1.0}],
            "photons": {"count": 40000, "max_interactions": 5, "seed": 3, "wavelengths_per_photon": 1},
            "view": {"camera": {"position": [0, 0, -10], "look_at": [1, 0, -10], "up": [0, 0, 1], "vfov_deg": 50,
                                "width": 24, "height": 18},
                     "march": {"steps": steps, "distance": 15, "k": 50, "estimator": estimator,
                               "single_scattering": False, "multiple_scattering": True,
                               "step_subsample": subsample}}}


def test_subsampled_steps_estimate_the_sum_over_every_step(ctx):
    """With step_subsample m the per-step estimate is made at one step of every block of
    m, uniform in it (independently per pixel and block), and weighted by m: given the
    photons, each pixel's expected value is the every-step estimate.  The same photons
    (same seed) both ways, so the 432 pixels' differences are independent with mean 0
    under that claim: their mean must lie within 4 standard errors of 0 (a 6e-5 chance of
    failing if it holds).  Measured: means 0.3 % and 0.6 % of the pixels' mean value, the
    standard errors 0.6 % (the differences spread 12–13 %); a weight of 1 instead of m
    would move the mean by −86 %.  m = 7 leaves a shorter last block (200 = 28·7 + 4),
    weighted by its own 4 steps."""
    every = ocean.render(scene(1), context=ctx).spectral.sum(axis=2).ravel()
    for m in (7, 8):
        some = ocean.render(scene(m), context=ctx).spectral.sum(axis=2).ravel()
        d = (some - every) / every.mean()
        se = d.std(ddof=1) / math.sqrt(d.size)
        assert d.std() > 1e-3, "the subsampled image should differ pixel by pixel"
        assert abs(d.mean()) < 4 * se, (m, d.mean(), se)


def test_bad_step_subsample_is_refused(ctx):
    for subsample, estimator, message in ((0, "per_step", "step_subsample"),
                                          (201, "per_step", r"march.step_subsample: must be in 1..march.steps"),
                                          (4, "beam", "per-step estimate only")):
        with pytest.raises(arcus.ArgumentError, match=message):
            ocean.render(scene(subsample, estimator), context=ctx)
