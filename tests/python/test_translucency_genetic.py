"""Genetic inverse rendering (arcus.inverse.genetic, arcus_translucency_genetic, `arcus
inverse genetic`): the cache each individual is rendered through against the renderer;
an opaque Phong sphere's genes recovered from a render written here in NumPy (eq.
3.2–3.3, no code shared); Table 5.1's set-up run as the thesis ran it, its best fitness
never rising, and with the polish that follows the search, the medium recovered in 4
of 5 seeds; the same seed giving the same history (a determinism test); bad input
refused naming it."""

import json

import numpy as np
import pytest

import arcus
from arcus import image
from arcus.inverse import genetic
from arcus.translucency import Dipole, render

from conftest import REPO
from test_translucency_render import arcus_command

SCENE = str(REPO / "scenes" / "translucency" / "table_5_1.json")
# Table 5.1's ground truth: σ_s is marble's σ′_s with g = 0.5, so σ′_s is half of it.
TRUTH = {"sigma_a": [0.0021, 0.0041, 0.0071], "sigma_s": [2.19, 2.62, 3.0], "g": 0.5, "eta": 1.5, "b": 20.0}
TRUE_SIGMA_S_PRIME = np.array([1.095, 1.31, 1.5])


@pytest.fixture(scope="module")
def scene():
    return SCENE


@pytest.fixture(scope="module")
def target(scene):
    d = json.loads(open(scene).read())
    lights = [(light[:3], light[3]) for light in d["lights"]]
    mesh = str(REPO / "data" / "meshes" / (d["translucent_object"]["mesh"] + ".obj"))
    truth = Dipole(TRUTH["sigma_a"], TRUE_SIGMA_S_PRIME, TRUTH["eta"])
    return render(truth, mesh, lights, dict(d["camera"], width=48, height=48), ortho_height=d["ortho_height"],
                  mm_per_unit=d["translucent_object"]["mm_per_unit"], highlight_deg=TRUTH["b"], gather="brute_force")


def test_the_cache_renders_as_the_renderer(target, scene):
    # The truth's genes through the cache (√r bins, η nodes, the near disc) against the
    # brute-force render: within 1.5% relative RMS (measured 0.8% at 48–64 pixels).
    found = genetic(target.image, scene, population=2, generations=0, initial=TRUTH)
    m = target.covered
    assert np.sqrt(np.mean((found.image[m] - target.image[m]) ** 2)) / np.mean(target.image[m]) < 0.015
    assert found.fitness < 0.015 and found.pixels == m.sum()


@pytest.mark.heavy
def test_table_5_1_the_best_fitness_never_rises(target, scene):
    # §5.1's run as the thesis ran it (no polish): 40 individuals, 50 generations, 0.8 /
    # 0.8 / 0.8, from Table 3.1.  The best never rises and falls from Table 3.1's 0.83 to
    # below 0.12 (measured 0.05–0.08), every evaluation counted; alone it does not reach
    # the truth (docs/translucency.md gives five seeds).
    found = genetic(target.image, scene, seed=1, polish_steps=0)
    best = found.history["best_fitness"]
    assert len(best) == 51 and (np.diff(best) <= 0).all()
    assert best[0] > 0.5 and best[-1] < 0.12
    assert found.evaluations == 40 + 50 * 32
    assert found.polish_steps == 0 and found.fitness == found.search_fitness == best[-1]
    np.testing.assert_allclose(found.sigma_s_prime, (1 - found.best["g"]) * found.best["sigma_s"])


@pytest.mark.full_size
def test_table_5_1_recovers_the_medium_in_four_of_five_seeds(target, scene):
    # Issue 21 §6: σ′_s, η and b within 10% in at least 4 of 5 seeds.  With the default
    # polish (20 Levenberg–Marquardt steps from the search's best, through the same
    # cache) every seed lands within 3% here at 48² (1.5% at 64², 0.2% at 128²); the
    # polish only keeps steps that lower the fitness, so the best still never rises.
    hits = 0
    for seed in range(5):
        found = genetic(target.image, scene, seed=seed)
        assert found.fitness <= found.search_fitness == found.history["best_fitness"][-1]
        errors = np.r_[found.sigma_s_prime / TRUE_SIGMA_S_PRIME, found.best["eta"] / TRUTH["eta"],
                       found.best["b"] / TRUTH["b"]] - 1
        print("seed", seed, "fitness %.4f (search %.4f)" % (found.fitness, found.search_fitness),
              "errors %", np.round(100 * errors, 1))
        hits += bool(np.all(np.abs(errors) < 0.10))
    assert hits >= 4


def test_the_same_seed_gives_the_same_history_determinism(target, scene):
    a = genetic(target.image, scene, population=10, generations=5, seed=4)
    b = genetic(target.image, scene, population=10, generations=5, seed=4)
    c = genetic(target.image, scene, population=10, generations=5, seed=5)
    for key in ("best_fitness", "mean_fitness", "best_genes"):
        np.testing.assert_array_equal(a.history[key], b.history[key])
    assert not np.array_equal(a.history["mean_fitness"], c.history["mean_fitness"])


def phong_sphere(k_d, k_s, b_deg, lights, side):
    """Eq. 3.2–3.3 on the unit sphere seen orthographically down −z, 2.2 units tall."""
    c = (np.arange(side) + 0.5) / side
    x, y = np.meshgrid((c - 0.5) * 2.2, (0.5 - c) * 2.2)
    inside = x * x + y * y < 1
    n = np.stack([x, y, np.sqrt(np.clip(1 - x * x - y * y, 0, None))], -1)
    exponent = -np.log(2) / np.log(np.cos(np.radians(b_deg)))
    out = np.zeros((side, side, 3))
    for direction, irradiance in lights:
        light = np.asarray(direction, float) / np.linalg.norm(direction)
        cos_i = np.clip(n @ light, 0, None)[..., None]
        cos_a = np.clip((2 * cos_i * n - light)[..., 2:3], 0, None)
        out += (np.asarray(k_d) / np.pi + k_s * (exponent + 2) / (2 * np.pi) * cos_a ** exponent) * cos_i * irradiance
    out[~inside] = 0
    return out.astype(np.float32)


PHONG_LIGHTS = [((0.3, 0.5, 1.0), np.array([1.0, 0.9, 0.8])), ((-1.0, 0.2, 0.3), np.array([0.3, 0.3, 0.3]))]
PHONG_SCENE = {"translucent_object": {"mesh": "icosphere"}, "lights": [(d, tuple(e)) for d, e in PHONG_LIGHTS],
               "ortho_height": 2.2, "camera": {"position": (0, 0, 5), "look_at": (0, 0, 0)}}


def test_a_short_phong_search_is_deterministic():
    # The Phong model's calls, small enough for the sanitizer run (the recovery below is heavy).
    photo = phong_sphere([0.6, 0.3, 0.15], 0.25, 15.0, PHONG_LIGHTS, 24)
    a = genetic(photo, PHONG_SCENE, model="phong", population=6, generations=2, seed=3, fitness_space="rgb")
    b = genetic(photo, PHONG_SCENE, model="phong", population=6, generations=2, seed=3, fitness_space="rgb")
    for key in ("best_fitness", "mean_fitness", "best_genes"):
        np.testing.assert_array_equal(a.history[key], b.history[key])


@pytest.mark.heavy  # five full searches; the Phong model's calls run instrumented in the short one above
def test_phong_genes_are_recovered_from_a_numpy_render():
    truth = {"k_d": [0.6, 0.3, 0.15], "k_s": 0.25, "b": 15.0}
    photo = phong_sphere(truth["k_d"], truth["k_s"], truth["b"], PHONG_LIGHTS, 64)
    scene = PHONG_SCENE
    # The icosphere's 1280 facets against the sphere leave 2.4% at the true genes.  In
    # RGB, over 5 seeds, k_s and b come within 10% and k_d within 15% (the search alone
    # measured 4%, 3% and 13%, the blue: the darkest channel; with the default polish
    # 3.1%, 1.5% and 0.2%, in YCbCr too).
    for seed in range(5):
        found = genetic(photo, scene, model="phong", seed=seed, fitness_space="rgb")
        assert found.sigma_s_prime is None
        np.testing.assert_allclose(found.best["k_s"], truth["k_s"], rtol=0.10)
        np.testing.assert_allclose(found.best["b"], truth["b"], rtol=0.10)
        np.testing.assert_allclose(found.best["k_d"], truth["k_d"], rtol=0.15)
    found = genetic(photo, scene, model="phong", seed=0)
    np.testing.assert_allclose([found.best["k_s"], found.best["b"]], [truth["k_s"], truth["b"]], rtol=0.10)
    np.testing.assert_allclose(found.best["k_d"][:2], truth["k_d"][:2], rtol=0.10)


@pytest.mark.parametrize("kwargs, words", [
    ({"model": "marble"}, ["model"]),
    ({"population": 1}, ["population"]),
    ({"replacement": 1.5}, ["replacement"]),
    ({"polish_steps": 1001}, ["polish_steps"]),
    ({"fitness_space": "lab"}, ["fitness_space"]),
    ({"lower": {"eta": 2.5}}, ["lower", "eta"]),
    ({"upper": {"g": 1.0}}, ["upper", "g"]),
    ({"initial": {"b": float("nan")}}, ["initial", "b"]),
    ({"initial": {"kd": 1}}, ["kd"]),
])
def test_bad_input_is_refused_naming_it(target, scene, kwargs, words):
    with pytest.raises(arcus.ArgumentError) as err:
        genetic(target.image, scene, generations=1, **kwargs)
    for word in words:
        assert word in str(err.value), (word, str(err.value))


def test_bad_targets_and_scenes_are_refused(target, scene, tmp_path):
    bad = target.image.copy()
    bad[20, 20, 1] = np.nan
    with pytest.raises(arcus.ArgumentError, match="target"):
        genetic(bad, scene, generations=1)
    with pytest.raises(arcus.ArgumentError, match="lights"):
        genetic(target.image, {"translucent_object": {"mesh": "torus"}}, generations=1)
    # The library's strict reader: an unknown key, a light of two numbers, both named.
    (tmp_path / "s.json").write_text('{"translucent_object": {"mesh": "torus"}, "lights": [[0, 1, 0]], "colour": 1}')
    with pytest.raises(arcus.ArgumentError, match="colour"):
        genetic(target.image, tmp_path / "s.json", generations=1)
    (tmp_path / "s.json").write_text('{"translucent_object": {"mesh": "torus"}, "lights": [[0, 1]]}')
    with pytest.raises(arcus.ArgumentError, match=r"lights\[0\]"):
        genetic(target.image, tmp_path / "s.json", generations=1)
    with pytest.raises(arcus.ArgumentError, match="8-bit"):
        image.write(tmp_path / "t.png", target.image / target.image.max())
        genetic(tmp_path / "t.png", scene, generations=1)


@pytest.mark.end_to_end
def test_the_command_prints_table_5_1s_columns_and_writes_the_best(target, scene, tmp_path):
    image.write(tmp_path / "target.exr", target.image)
    r = arcus_command("inverse", "genetic", scene, "--target", "target.exr", "--generations", "10", "--seed", "2",
                      "-o", "best.png", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "sigma_s'" in r.stdout and "   10 " in r.stdout
    assert image.read(tmp_path / "best.png").shape == (48, 48, 3)
    r = arcus_command("inverse", "genetic", scene, "--target", "missing.exr", "--quiet", cwd=tmp_path)
    assert r.returncode == 2 and "missing.exr" in r.stderr
