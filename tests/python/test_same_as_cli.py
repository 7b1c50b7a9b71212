"""The image from Python is the command line's, bit for bit, at the same seed and options."""
import numpy as np
import pytest

from conftest import read_pfm, run_cli

CASES = [
    # (Python options, the same on the command line)
    (dict(spp=4, seed=7), ["--spp", 4, "--seed", 7]),
    (dict(spp=2, color="rgb", integrator="bdpt", maxdepth=3), ["--spp", 2, "--color", "rgb", "--integrator", "bdpt", "--maxdepth", 3]),
    (dict(spp=2, integrator="light", sampler="halton"), ["--spp", 2, "--integrator", "light", "--sampler", "halton"]),
    (dict(spp=4, integrator="mmlt", bootstrap=2000, chains=16, large_step_probability=0.5),
     ["--spp", 4, "--integrator", "mmlt", "--bootstrap", 2000, "--chains", 16, "--large-step-probability", 0.5]),
    (dict(spp=3, crop=(0.25, 0.75, 0.1, 0.6), threads=1), ["--spp", 3, "--crop", 0.25, 0.75, 0.1, 0.6, "--threads", 1]),
]


@pytest.mark.parametrize("options,cli", CASES, ids=lambda c: str(c) if isinstance(c, dict) else "")
def test_image_equals_the_command_lines(pathspace, binary, small_scene, tmp_path, options, cli):
    out = tmp_path / "cli.pfm"
    status, err = run_cli(binary, small_scene, *cli, "-o", out)
    assert status == 0, err
    expected = read_pfm(out)

    result = pathspace.load(str(small_scene)).render(**options)
    image = result.image
    assert image.dtype == np.float32 and image.shape == expected.shape
    assert np.array_equal(image, expected)
    assert image.any()
    # The writer is the command line's: the same bytes.
    mine = tmp_path / "python.pfm"
    result.write(str(mine))
    assert mine.read_bytes() == out.read_bytes()


def test_rerendering_a_scene_gives_the_first_image(pathspace, small_scene):
    """Each render starts from the scene's own settings (an option does not stay behind)."""
    scene = pathspace.load(str(small_scene))
    first = np.array(scene.render(spp=2).image)
    scene.render(spp=1, seed=3, crop=(0, 0.5, 0, 0.5), maxdepth=1, integrator="bdpt")
    assert np.array_equal(scene.render(spp=2).image, first)


def test_row_zero_is_the_top(pathspace):
    """A light above a camera looking at the horizon: the top rows are the bright ones."""
    scene = pathspace.load_string("""LookAt 0 0 0  0 0 -1  0 1 0
Camera "perspective" "float fov" [ 90 ]
Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "bool twosided" true
  Shape "bilinearmesh" "point3 P" [ -50 10 50  50 10 50  -50 10 -50  50 10 -50 ]
AttributeEnd
""")
    image = scene.render(spp=1, color="rgb").image
    assert image[0].sum() > 0 and image[-1].sum() == 0


def test_variance_and_statistics_are_the_command_lines(pathspace, binary, small_scene, tmp_path):
    out, stats_file = tmp_path / "cli.pfm", tmp_path / "stats.json"
    status, err = run_cli(binary, small_scene, "--spp", 4, "-o", out, "--aov", "variance", "--stats", stats_file)
    assert status == 0, err
    result = pathspace.load(str(small_scene)).render(spp=4, aovs=["variance"])
    expected = read_pfm(tmp_path / "cli.variance.pfm")
    assert result.variance.shape == expected.shape[:2]
    assert np.array_equal(result.variance, expected[:, :, 0])
    assert result.aovs["variance"] is not None

    import json
    cli_stats = json.loads(stats_file.read_text())
    stats = result.stats
    # The figures per technique are the command line's alone: they render a QMC sampler's spp as
    # scrambled sets (docs/strategy-figures.md), which the module's renders never do.
    assert set(stats) == set(cli_stats) - {"techniques"}
    for key in ["integrator", "color", "sampler", "resolution", "pixels", "seed", "maxdepth", "spp_target", "spp_mean",
                "camera_paths", "rays", "mean_pixel_variance", "interrupted"]:
        assert stats[key] == cli_stats[key], key


def test_bdpt_strategy_images_sum_to_the_image(pathspace, small_scene):
    result = pathspace.load(str(small_scene)).render(spp=2, integrator="bdpt", maxdepth=3, bdpt_strategies=True)
    weighted = [img for name, img in result.strategies.items() if not name.endswith("unweighted")]
    assert "s1_t2" in result.strategies and "s1_t2_unweighted" in result.strategies
    total = np.sum(weighted, axis=0)
    assert np.allclose(total, result.image, rtol=1e-4, atol=1e-6)
