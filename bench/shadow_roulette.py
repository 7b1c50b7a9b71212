#!/usr/bin/env python3
"""Russian roulette on shadow rays (--shadow-roulette A): efficiency 1/(V T) against every
shadow ray traced (A = 0).

For each scene and integrator, renders at a fixed spp with --seeds seeds per share A,
alternating the shares within each seed; V is the relMSE against a long path-traced
reference (cached in build/bench-cache/, shared with bench/bdpt_light_paths.py), T the
process's user + system CPU seconds. Prints per share the mean relMSE, the mean CPU time,
the shadow rays skipped, and the efficiency over A = 0's (above 1: the roulette gains).
Run from the repository root, under the lock for the whole measurement:

  flock /tmp/ps-build.lock python3 bench/shadow_roulette.py [--seeds 4] [--shares 0,0.1,0.3,1] [CASE...]
"""
import argparse
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bdpt_light_paths import SCENES, reference  # noqa: E402
from many_lights import PATHSPACE, ROOT, cpu_timed, relmse  # noqa: E402

# case -> (scene, integrator, spp, extra arguments)
CASES = {
    "cornell-path": ("cornell-box", "path", 16, []),
    "cornell-bdpt": ("cornell-box", "bdpt", 8, []),
    "corridor-path": ("corridor", "path", 16, []),
    "corridor-bdpt": ("corridor", "bdpt", 8, []),
    "street-path": ("street", "path", 16, []),
    "emissive-mesh-bdpt": ("emissive-mesh", "bdpt", 8, []),
}


def run(scene, integrator, spp, seed, threads, share, extra, out, stats):
    cmd = [PATHSPACE, "render", scene, "--integrator", integrator, "--threads", str(threads), "--seed", str(seed),
           "--spp", str(spp), "--quiet", "-o", out, "--stats", stats, "--shadow-roulette", f"{share:g}", *extra]
    cpu = cpu_timed(cmd)
    with open(stats) as f:
        st = json.load(f)
    return cpu, st["shadow_rays_skipped"] / max(1, st["shadow_rays"] + st["shadow_rays_skipped"])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cases", nargs="*", default=list(CASES))
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--shares", default="0,0.1,0.3,1")
    ap.add_argument("--cache", default=os.path.join(ROOT, "build", "bench-cache"))
    a = ap.parse_args()
    os.makedirs(a.cache, exist_ok=True)
    shares = [float(x) for x in a.shares.split(",")]
    print("| case | " + " | ".join(f"A = {s:g}: relMSE, CPU s, skipped, efficiency" for s in shares) + " |")
    print("|---|" + "---|" * len(shares))
    with tempfile.TemporaryDirectory() as tmp:
        out, stats = os.path.join(tmp, "x.pfm"), os.path.join(tmp, "s.json")
        for case in a.cases:
            name, integ, spp, extra = CASES[case]
            scene, refSpp = SCENES[name]
            ref = reference(name, scene, refSpp, a.cache, a.threads)
            err = {s: [] for s in shares}
            cpu = {s: [] for s in shares}
            skip = {s: [] for s in shares}
            for seed in range(1, a.seeds + 1):
                for s in shares:
                    t, k = run(scene, integ, spp, seed, a.threads, s, extra, out, stats)
                    err[s].append(relmse(out, ref))
                    cpu[s].append(t)
                    skip[s].append(k)
            mean = lambda v: sum(v) / len(v)  # noqa: E731
            base = mean(err[shares[0]]) * mean(cpu[shares[0]])
            cells = [f"{mean(err[s]):.4g}, {mean(cpu[s]):.2f}, {100 * mean(skip[s]):.0f}%, "
                     f"**{base / (mean(err[s]) * mean(cpu[s])):.2f}**" for s in shares]
            print(f"| {case} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
