#!/usr/bin/env python3
"""BDPT with fewer light subpaths than camera samples (--light-paths F) at equal time.

For each scene, the path tracer and BDPT at each light path share F run for the same
whole-process wall time T (--time), 2 threads, --seeds seeds each; relMSE against a long
path-traced reference (cached in build/bench-cache/; the many-light scenes share
bench/many_lights.py's), mean over the seeds, and each configuration's relMSE over the path
tracer's. Run from the repository root, under the lock for the whole measurement:

  flock /tmp/ps-build.lock python3 bench/bdpt_light_paths.py [--time 3] [--seeds 2] [--shares 1,0.1,0.01,auto]
"""
import argparse
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from many_lights import HERE, ROOT, ours, relmse  # noqa: E402

SHARED = os.path.join(os.path.dirname(ROOT), "shared", "scenes")
# name -> (scene, reference spp)
SCENES = {
    "corridor": (os.path.join(HERE, "scenes", "many-lights", "corridor.pbrt"), 2048),
    "street": (os.path.join(HERE, "scenes", "many-lights", "street.pbrt"), 2048),
    "emissive-mesh": (os.path.join(HERE, "scenes", "many-lights", "emissive-mesh.pbrt"), 2048),
    "cornell-box": (os.path.join(SHARED, "cornell-box", "scene-v4-256.pbrt"), 4096),
}


def reference(name, scene, spp, cache, threads):
    # The many-light scenes' references are bench/many_lights.py's (same name, same command).
    path = os.path.join(cache, f"many-lights-{name}-ref{spp}.pfm" if "cornell" not in name else f"{name}-ref{spp}.pfm")
    if not os.path.exists(path):
        print(f"  reference: {name}, path, {spp} spp", flush=True)
        ours(scene, path, 1000, threads, spp=spp)
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="*", default=list(SCENES))
    ap.add_argument("--time", type=float, default=3.0)
    ap.add_argument("--seeds", type=int, default=2)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--shares", default="1,0.5,0.25,0.125")
    ap.add_argument("--cache", default=os.path.join(ROOT, "build", "bench-cache"))
    a = ap.parse_args()
    os.makedirs(a.cache, exist_ok=True)
    shares = [x if x == "auto" else f"{float(x):g}" for x in a.shares.split(",")]
    configs = [("path", [])] + [(f"bdpt {f}", ["--light-paths", f]) for f in shares]
    print("| scene | " + " | ".join(c for c, _ in configs) + " |")
    print("|---|" + "---|" * len(configs))
    with tempfile.TemporaryDirectory() as tmp:
        for name in a.scenes:
            scene, refSpp = SCENES[name]
            ref = reference(name, scene, refSpp, a.cache, a.threads)
            cells = []
            for label, extra in configs:
                integ = label.split()[0]
                errs = []
                for seed in range(1, a.seeds + 1):
                    out = os.path.join(tmp, "x.pfm")
                    t = ours(scene, out, seed, a.threads, seconds=a.time, integrator=integ, extra=extra)
                    errs.append(relmse(out, ref) * t / a.time)  # at T: relMSE falls as 1/time
                cells.append(sum(errs) / len(errs))
            base = cells[0]
            print(f"| {name} | " + " | ".join(f"{c:.4g} ({c / base:.2f})" for c in cells) + " |", flush=True)


if __name__ == "__main__":
    main()
