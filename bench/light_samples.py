#!/usr/bin/env python3
"""Splitting next-event estimation (--light-samples N, issue 41 part 4): efficiency 1/(V T)
of N = 1, 2, 4, 8 light samples per path vertex, against N = 1.

For each case, renders at a fixed spp with --seeds seeds per N, alternating the Ns within each
seed. Two efficiencies per N, each over N = 1's (above 1: splitting gains):
  - measured: V the relMSE against a long path-traced reference (cached in build/bench-cache/,
    shared with bench/bdpt_light_paths.py and bench/shadow_roulette.py), T the process's user
    + system CPU seconds;
  - reported: the `efficiency` --stats writes (its own variance estimate over the render's
    wall time; docs/strategy-figures.md), and the light technique's share of the image.
--no-reference skips the reference and the measured column (a quick check that it runs).
Run from the repository root, under the lock for the whole measurement:

  flock /tmp/ps-build.lock python3 bench/light_samples.py [--seeds 3] [--samples 1,2,4,8] [CASE...]
"""
import argparse
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bdpt_light_paths import SCENES, reference  # noqa: E402
from many_lights import PATHSPACE, ROOT, cpu_timed, relmse  # noqa: E402

# case -> (scene, spp)
CASES = {
    "cornell-path": ("cornell-box", 16),
    "corridor-path": ("corridor", 16),
    "street-path": ("street", 16),
}


def run(scene, spp, seed, threads, n, out, stats):
    cmd = [PATHSPACE, "render", scene, "--integrator", "path", "--threads", str(threads), "--seed", str(seed),
           "--spp", str(spp), "--quiet", "-o", out, "--stats", stats, "--light-samples", str(n)]
    cpu = cpu_timed(cmd)
    with open(stats) as f:
        st = json.load(f)
    light = next(t for t in st["techniques"]["list"] if t["name"] == "light")
    return cpu, st["efficiency"] or 0.0, light["share"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cases", nargs="*", default=list(CASES))
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--samples", default="1,2,4,8")
    ap.add_argument("--spp", type=int, default=0, help="override every case's spp (0: the case's)")
    ap.add_argument("--no-reference", action="store_true")
    ap.add_argument("--cache", default=os.path.join(ROOT, "build", "bench-cache"))
    a = ap.parse_args()
    os.makedirs(a.cache, exist_ok=True)
    ns = [int(x) for x in a.samples.split(",")]
    print("| case | " + " | ".join(f"N = {n}: relMSE, CPU s, light share, efficiency measured / reported" for n in ns) + " |")
    print("|---|" + "---|" * len(ns))
    mean = lambda v: sum(v) / len(v)  # noqa: E731
    with tempfile.TemporaryDirectory() as tmp:
        out, stats = os.path.join(tmp, "x.pfm"), os.path.join(tmp, "s.json")
        for case in a.cases:
            name, spp = CASES[case]
            spp = a.spp or spp
            scene, refSpp = SCENES[name]
            ref = None if a.no_reference else reference(name, scene, refSpp, a.cache, a.threads)
            err, cpu, eff, share = ({n: [] for n in ns} for _ in range(4))
            for seed in range(1, a.seeds + 1):
                for n in ns:
                    t, e, s = run(scene, spp, seed, a.threads, n, out, stats)
                    cpu[n].append(t)
                    eff[n].append(e)
                    share[n].append(s)
                    err[n].append(relmse(out, ref) if ref else float("nan"))
            base = mean(err[ns[0]]) * mean(cpu[ns[0]])
            cells = []
            for n in ns:
                measured = base / (mean(err[n]) * mean(cpu[n])) if ref else float("nan")
                reported = mean(eff[n]) / mean(eff[ns[0]]) if mean(eff[ns[0]]) > 0 else float("nan")
                cells.append(f"{mean(err[n]):.4g}, {mean(cpu[n]):.2f}, {mean(share[n]):.3f}, "
                             f"**{measured:.2f}** / {reported:.2f}")
            print(f"| {case} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
