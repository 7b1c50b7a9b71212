"""relMSE against render time for path tracing, BDPT and multiplexed MLT on one scene.

    PYTHONPATH=build/python /usr/bin/python3 examples/spp_sweep.py [scenes/cornell-box.pbrt]

The reference is a 256-spp path-traced render of the same crop (its own noise sets a floor
under the curves; raise its spp for a longer run); writes spp_sweep.png.
"""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import pathspace

scene = pathspace.load(sys.argv[1] if len(sys.argv) > 1 else "scenes/cornell-box.pbrt")
common = dict(color="rgb", crop=(0.3, 0.7, 0.3, 0.7), seed=1)
reference = scene.render(integrator="path", spp=256, **common).image


def rel_mse(image):
    return float(np.mean((image - reference) ** 2 / (reference ** 2 + 1e-2)))


for integrator in ["path", "bdpt", "mmlt"]:
    times, errors = [], []
    for spp in [1, 2, 4, 8, 16, 32]:
        # A different seed from the reference's: its noise must not correlate with theirs.
        result = scene.render(integrator=integrator, spp=spp, **{**common, "seed": 2})
        times.append(result.stats["wall_time_s"])
        errors.append(rel_mse(result.image))
        print(f"{integrator:5s} {spp:3d} spp  {times[-1]:6.2f} s  relMSE {errors[-1]:.4g}")
    plt.loglog(times, errors, "o-", label=integrator)
plt.xlabel("render time (s)")
plt.ylabel("relMSE")
plt.legend()
plt.savefig("spp_sweep.png", dpi=120)
print("wrote spp_sweep.png")
