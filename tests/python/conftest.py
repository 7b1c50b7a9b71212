"""Shared fixtures of the Python tests: the built command line, small scenes, a CLI runner.

Run by the test command (CTest test `python`), which sets PYTHONPATH to the built module and
PATHSPACE_BINARY to the command line; by hand: PYTHONPATH=build/python python3 -m pytest tests/python
"""
import os
import pathlib
import subprocess

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]

# A small box lit by a quad in its ceiling: every integrator can render it, in well under a
# second at a few samples per pixel.
SMALL_SCENE = """LookAt 0 1 3.5  0 1 0  0 1 0
Camera "perspective" "float fov" [ 40 ]
Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 18 ] "string filename" [ "small.exr" ]
Sampler "sobol" "integer pixelsamples" [ 4 ]
WorldBegin
MakeNamedMaterial "white" "string type" [ "diffuse" ] "rgb reflectance" [ 0.7 0.7 0.7 ]
MakeNamedMaterial "red" "string type" [ "diffuse" ] "rgb reflectance" [ 0.6 0.1 0.1 ]
NamedMaterial "white"
Shape "bilinearmesh" "point3 P" [ -1 0 1  1 0 1  -1 0 -1  1 0 -1 ]
Shape "bilinearmesh" "point3 P" [ -1 0 -1  1 0 -1  -1 2 -1  1 2 -1 ]
Shape "bilinearmesh" "point3 P" [ -1 2 -1  1 2 -1  -1 2 1  1 2 1 ]
NamedMaterial "red"
Shape "bilinearmesh" "point3 P" [ 1 0 1  1 0 -1  1 2 1  1 2 -1 ]
AttributeBegin
  Translate 0 0.4 0
  NamedMaterial "white"
  Shape "sphere" "float radius" [ 0.4 ]
AttributeEnd
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 8 8 8 ]
  Shape "bilinearmesh" "point3 P" [ -0.3 1.99 -0.3  0.3 1.99 -0.3  -0.3 1.99 0.3  0.3 1.99 0.3 ]
AttributeEnd
"""


@pytest.fixture(scope="session")
def pathspace():
    import pathspace as module
    return module


@pytest.fixture(scope="session")
def binary():
    path = os.environ.get("PATHSPACE_BINARY", str(REPO / "build" / "pathspace"))
    if not os.access(path, os.X_OK):
        pytest.fail(f"the command line is not built at {path} (set PATHSPACE_BINARY)")
    return path


@pytest.fixture
def small_scene(tmp_path):
    path = tmp_path / "small.pbrt"
    path.write_text(SMALL_SCENE)
    return path


def run_cli(binary, *args):
    """Runs `pathspace render ...`; returns (exit status, stderr). Not --quiet: like a render from
    Python, it keeps the noise estimate (which --max-memory's figures count)."""
    done = subprocess.run([binary, "render", *map(str, args)], capture_output=True, text=True, timeout=300)
    return done.returncode, done.stderr


def read_pfm(path):
    """A PFM file as float32 (height, width, 3), row 0 the top (PFM stores the bottom row first)."""
    data = pathlib.Path(path).read_bytes()
    magic, size, scale, pixels = data.split(b"\n", 3)
    assert magic == b"PF"
    width, height = map(int, size.split())
    dtype = "<f4" if float(scale) < 0 else ">f4"
    image = np.frombuffer(pixels, dtype=dtype).reshape(height, width, 3)
    return np.flipud(image).astype(np.float32)
