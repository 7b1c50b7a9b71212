"""The arrays share the render's buffers, outlive the scene and the result in either order,
and 200 renders keep the process's memory flat."""
import gc
import subprocess
import sys

import numpy as np
import pytest

TINY = """LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" [ 30 ]
Film "rgb" "integer xresolution" [ 64 ] "integer yresolution" [ 48 ]
Sampler "independent" "integer pixelsamples" [ 1 ]
WorldBegin
LightSource "infinite" "rgb L" [ 1 1 1 ]
Material "diffuse"
Shape "sphere" "float radius" [ 1 ]
"""


def test_the_array_is_a_view_not_a_copy(pathspace):
    result = pathspace.load_string(TINY).render(color="rgb", aovs=["variance"])
    a, b = result.image, result.image
    assert a.ctypes.data == b.ctypes.data and np.shares_memory(a, b)
    assert a.base is not None and not a.flags.writeable
    assert np.shares_memory(result.variance, result.aovs["variance"])


# Dropping the scene and the result, then reading the arrays, in a process of its own: a freed
# buffer of this size is unmapped (glibc gives buffers over 128 KiB their own mapping), so
# reading it crashes that process rather than passing on memory nothing reused yet.
SURVIVES = """
import gc, sys
import numpy as np
import pathspace
scene = pathspace.load_string(sys.argv[1].replace("64", "256").replace("48", "192"))
result = scene.render(color="rgb", aovs=["variance"])
image, variance = result.image, result.variance
kept, kept_variance = image.copy(), variance.copy()
objects = {"scene": scene, "result": result}
del scene, result
for name in sys.argv[2:]:
    del objects[name]
    gc.collect()
other = pathspace.load_string(sys.argv[1]).render(color="rgb", seed=5, spp=2)
junk = [np.full((192, 256, 3), 7.0, np.float32) for _ in range(20)]
assert np.array_equal(image, kept) and np.array_equal(variance, kept_variance), "changed"
print("kept")
"""


@pytest.mark.parametrize("order", [("scene", "result"), ("result", "scene")])
def test_the_array_survives_dropping_scene_and_result(order):
    done = subprocess.run([sys.executable, "-c", SURVIVES, TINY, *order], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and done.stdout.strip() == "kept", (done.returncode, done.stderr[-2000:])


def rss_bytes():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) * 1024
    raise RuntimeError("no VmRSS")


def test_200_renders_keep_memory_flat(pathspace):
    scene = pathspace.load_string(TINY)

    def one():
        result = scene.render(color="rgb", seed=1, aovs=["variance"])
        assert result.image.sum() > 0 and result.stats["spp_mean"] == 1

    for _ in range(20):  # warm-up: pools and caches reach their size
        one()
    gc.collect()
    before = rss_bytes()
    for _ in range(200):
        one()
    gc.collect()
    growth = rss_bytes() - before
    # A leaked result (image and variance, 74 KB) per render would be 15 MB.
    assert growth < 4 * 2**20, f"RSS grew by {growth / 2**20:.1f} MiB over 200 renders"
