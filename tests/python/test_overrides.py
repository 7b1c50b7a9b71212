"""Overrides without editing the file give the image of the edited file, bit for bit, and the
render after one does not read the meshes again."""
import numpy as np
import pytest

from conftest import SMALL_SCENE

# The small box with its sphere's place taken by a PLY mesh (a tetrahedron) read from a file.
PLY = """ply
format ascii 1.0
element vertex 4
property float x
property float y
property float z
element face 4
property list uchar int vertex_indices
end_header
-0.4 0 -0.3
0.4 0 -0.3
0 0 0.4
0 0.7 0
3 0 1 2
3 0 1 3
3 1 2 3
3 2 0 3
"""
SCENE = SMALL_SCENE.replace('Shape "sphere" "float radius" [ 0.4 ]', 'Shape "plymesh" "string filename" "mesh.ply"')
OPTIONS = dict(spp=2, seed=3, color="rgb")


@pytest.fixture
def scene_dir(tmp_path):
    (tmp_path / "mesh.ply").write_text(PLY)
    return tmp_path


def edited(pathspace, scene_dir, old, new):
    assert old in SCENE
    return pathspace.load_string(SCENE.replace(old, new), str(scene_dir)).render(**OPTIONS).image


@pytest.mark.parametrize("override,old,new", [
    (lambda s: s.set_resolution(20, 30),
     '"integer xresolution" [ 24 ] "integer yresolution" [ 18 ]', '"integer xresolution" [ 20 ] "integer yresolution" [ 30 ]'),
    (lambda s: s.set_camera((0.5, 1.2, 3), (0, 0.8, 0), (0, 1, 0)), "LookAt 0 1 3.5  0 1 0  0 1 0", "LookAt 0.5 1.2 3  0 0.8 0  0 1 0"),
    (lambda s: s.set_material("red", "reflectance", (0.1, 0.2, 0.6)),
     '"red" "string type" [ "diffuse" ] "rgb reflectance" [ 0.6 0.1 0.1 ]',
     '"red" "string type" [ "diffuse" ] "rgb reflectance" [ 0.1 0.2 0.6 ]'),
    (lambda s: s.set_light_scale(0, 2.5), 'AreaLightSource "diffuse" "rgb L" [ 8 8 8 ]',
     'AreaLightSource "diffuse" "rgb L" [ 8 8 8 ] "float scale" [ 2.5 ]'),
])
def test_override_renders_the_edited_file_without_reading_meshes(pathspace, scene_dir, override, old, new):
    expected = edited(pathspace, scene_dir, old, new)
    scene = pathspace.load_string(SCENE, str(scene_dir))
    first = scene.render(**OPTIONS).image
    (scene_dir / "mesh.ply").unlink()  # a second read would fail
    override(scene)
    image = scene.render(**OPTIONS).image
    assert image.shape == expected.shape and np.array_equal(image, expected)
    assert image.shape != first.shape or not np.array_equal(image, first)


def test_bad_overrides(pathspace, scene_dir):
    scene = pathspace.load_string(SCENE, str(scene_dir))
    assert scene.lights == ['AreaLightSource "diffuse" at <string>:20:3']
    with pytest.raises(ValueError, match="positive"):
        scene.set_resolution(0, 10)
    with pytest.raises(ValueError, match="must differ"):
        scene.set_camera((0, 1, 2), (0, 1, 2))
    with pytest.raises(ValueError, match='no material named "blue" .*"red", "white"'):
        scene.set_material("blue", "reflectance", 0.5)
    with pytest.raises(ValueError, match="three numbers"):
        scene.set_material("red", "reflectance", (1, 2))
    with pytest.raises(ValueError, match="light 1 of 1"):
        scene.set_light_scale(1, 2.0)
    assert scene.render(spp=1).image.any()  # the refused overrides left the scene as it was
