"""arcus.mirage_profile: a mirage drawn as the rays of its image's centre column, beside
the same rays without the inversions (``arcus render SCENE --profile``).  What the fan
must show: where the air is layered the fan folds (one height at the object seen at
several rows: the multiple images), where it is not it does not; the rows' elevations
are the pinhole camera's.  The command's side (`arcus render SCENE --profile`, bad input
refused before anything is rendered) is in test_cli.py."""

import json
import math

import numpy as np
import pytest

import arcus
import arcus.mirage_profile as mirage_profile


def scene(repo, name):
    return json.loads((repo / "scenes" / ("%s.json" % name)).read_text())


def heights_at(fan, distance):
    """Each ray's height where it passes `distance`, NaN for a ray that met the ground before."""
    return np.array([np.interp(distance, d, h) if d[-1] >= distance else math.nan
                     for d, h in zip(fan["distance"], fan["height"])])


@pytest.mark.parametrize("name", ["inferior_mirage", "fata_morgana"])
def test_layers_fold_the_fan_and_plain_air_does_not(ctx, repo, name):
    """At the object, rows top to bottom see lower and lower heights in plain air (no
    fold: one image); with the scene's layers some lower row sees higher than a row
    above it (a fold: the inverted image of the inferior mirage, the Fata Morgana's
    stretched towers)."""
    doc = scene(repo, name)
    folded, plain = (mirage_profile.ray_fan(doc, rows=41, inversions=on, context=ctx) for on in (True, False))
    at = folded["object_distance"]
    assert at == pytest.approx({"inferior_mirage": 2000.0, "fata_morgana": 12000.0}[name], rel=1e-3)
    h_plain, h_folded = heights_at(plain, at), heights_at(folded, at)
    seen = np.isfinite(h_plain)
    assert seen.sum() >= 10 and np.all(np.diff(h_plain[seen]) < 0)
    seen = np.isfinite(h_folded)
    assert np.any(np.diff(h_folded[seen]) > 0)


def test_rows_are_the_pinhole_cameras(ctx, repo):
    """The fan's rows from the image's top to its bottom span the field of view less a
    pixel (row centres), as the renderer's camera places them."""
    doc = scene(repo, "inferior_mirage")
    fan = mirage_profile.ray_fan(doc, rows=5, context=ctx)
    camera = doc["camera"]
    half = math.radians(camera["vfov_deg"]) / 2
    span = 2 * math.degrees(math.atan((1 - 1 / camera["height"]) * math.tan(half)))
    # the camera looks 0.06° up: a tilt changes the span by ~1e-7°
    assert fan["elevation_deg"][0] - fan["elevation_deg"][-1] == pytest.approx(span, abs=1e-5)
    assert np.all(np.diff(fan["elevation_deg"]) < 0)


def test_a_field_that_is_not_air_is_refused(repo):
    with pytest.raises(arcus.ArgumentError, match="atmosphere"):
        mirage_profile.ray_fan(scene(repo, "cross_room"))
