"""Every option's bad value raises ValueError with the command line's message; scene errors
raise SceneError with the place and the message the command line prints."""
import pytest

from conftest import run_cli

BAD = [
    # (Python keyword arguments, the same on the command line)
    (dict(spp=0), ["--spp", "0"]),
    (dict(spp=1.5), ["--spp", "1.5"]),
    (dict(time=0), ["--time", "0"]),
    (dict(threads=-1), ["--threads", "-1"]),
    (dict(seed=-1), ["--seed", "-1"]),
    (dict(seed=2**63), ["--seed", str(2**63)]),
    (dict(maxdepth=-2), ["--maxdepth", "-2"]),
    (dict(integrator="sppm"), ["--integrator", "sppm"]),
    (dict(mis="max"), ["--mis", "max"]),
    (dict(sampler="pmj"), ["--sampler", "pmj"]),
    (dict(adaptive="always"), ["--adaptive", "always"]),
    (dict(adaptive="sequential", integrator="bdpt"), ["--adaptive", "sequential", "--integrator", "bdpt"]),
    (dict(color="cmyk"), ["--color", "cmyk"]),
    (dict(aovs=["depth"]), ["--aov", "depth"]),
    (dict(crop=(0, 2, 0, 1)), ["--crop", "0", "2", "0", "1"]),
    (dict(crop=(0.5, 0.2, 0, 1)), ["--crop", "0.5", "0.2", "0", "1"]),
    (dict(crop=(0, 1, 0)), ["--crop", "0", "1", "0"]),
    (dict(crop=(0, 1, 0, 1), pixelbounds=(0, 4, 0, 4)), ["--crop", "0", "1", "0", "1", "--pixelbounds", "0", "4", "0", "4"]),
    (dict(pixelbounds=(0, 100, 0, 4)), ["--pixelbounds", "0", "100", "0", "4"]),
    (dict(max_memory="lots"), ["--max-memory", "lots"]),
    (dict(max_memory="1K"), ["--max-memory", "1K"]),
    (dict(chains=0, integrator="pssmlt"), ["--chains", "0", "--integrator", "pssmlt"]),
    (dict(chains=10), ["--chains", "10"]),
    (dict(bootstrap=0, integrator="mmlt"), ["--bootstrap", "0", "--integrator", "mmlt"]),
    (dict(large_step_probability=1.5, integrator="pssmlt"), ["--large-step-probability", "1.5", "--integrator", "pssmlt"]),
    (dict(camera_step_probability=-0.1, integrator="mmlt"), ["--camera-step-probability", "-0.1", "--integrator", "mmlt"]),
    (dict(sigma=0, integrator="pssmlt"), ["--sigma", "0", "--integrator", "pssmlt"]),
    (dict(sigma=0.1, integrator="mlt"), ["--sigma", "0.1", "--integrator", "mlt"]),
    (dict(strategy_pilot=0.5), ["--strategy-pilot", "0.5"]),
    (dict(strategy_pilot=1, integrator="mmlt"), ["--strategy-pilot", "1", "--integrator", "mmlt"]),
    (dict(two_stage=-1, integrator="mmlt"), ["--two-stage", "-1", "--integrator", "mmlt"]),
    (dict(two_stage=0, two_stage_black_level=0.2, integrator="mmlt"),
     ["--two-stage", "0", "--two-stage-black-level", "0.2", "--integrator", "mmlt"]),
    (dict(mlt_mutations="lens=1"), ["--mlt-mutations", "lens=1"]),
    (dict(mlt_direct=-1, integrator="mlt"), ["--mlt-direct", "-1", "--integrator", "mlt"]),
    (dict(bdpt_strategies=True), ["--bdpt-strategies", "strategies"]),
]


@pytest.mark.parametrize("options,cli", BAD, ids=lambda c: str(c) if isinstance(c, dict) else "")
def test_bad_value_raises_the_command_lines_message(pathspace, binary, small_scene, tmp_path, options, cli):
    status, err = run_cli(binary, small_scene, *cli, "-o", tmp_path / "out.exr")
    assert status == 2, err
    expected = err.splitlines()[0]
    scene = pathspace.load(str(small_scene))
    with pytest.raises(ValueError) as caught:
        scene.render(**options)
    assert str(caught.value) == expected
    scene.render(spp=1)  # the scene still renders


def test_unknown_option_is_a_type_error(pathspace, small_scene):
    with pytest.raises(TypeError, match="unexpected keyword argument 'spp_'"):
        pathspace.load(str(small_scene)).render(spp_=4)


@pytest.mark.parametrize("text,line,column", [
    ('WorldBegin\nShape "sphere" "float radius" [ 1 \n', 2, None),
    ('Film "rgb" "integer xresolution" [ -4 ]\nWorldBegin\n', 1, 1),
    ('WorldBegin\nFrobnicate 1\n', 2, 1),
    ('WorldBegin\nShape "plymesh" "string filename" "missing.ply"\n', 2, 1),
])
def test_scene_error_says_where(pathspace, binary, tmp_path, text, line, column):
    path = tmp_path / "bad.pbrt"
    path.write_text(text)
    status, err = run_cli(binary, path, "-o", tmp_path / "out.exr")
    assert status == 2
    with pytest.raises(pathspace.SceneError) as caught:
        pathspace.load(str(path)).render(spp=1)
    error = caught.value
    assert str(error) == err.splitlines()[0]
    assert error.file == str(path) and error.line == line
    if column is not None:
        assert error.column == column
    assert isinstance(error, ValueError)


def test_scene_error_from_a_string(pathspace):
    with pytest.raises(pathspace.SceneError) as caught:
        pathspace.load_string('WorldBegin\n  Frobnicate 1\n')
    assert (caught.value.file, caught.value.line, caught.value.column) == ("<string>", 2, 3)
    assert str(caught.value).startswith("<string>:2:3: error: ")


def test_missing_scene_file(pathspace, tmp_path):
    with pytest.raises(pathspace.SceneError, match="missing.pbrt"):
        pathspace.load(str(tmp_path / "missing.pbrt"))
