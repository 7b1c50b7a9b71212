#!/usr/bin/env python3
"""Time-budgeted renders against fixed sample counts: does `--time` keep the sampler's
stratification? Per binary (PATHSPACE or --binary, repeatable, to compare builds in the same
minutes), `path` on a scene at a fixed --spp and with an unbounded --spp stopped by --time,
--seeds seeds each, 2 threads, as a user renders (no --stats, which would split the samples
into scrambled sets); relMSE against the cached reference of
bench/bdpt_light_paths.py and relMSE x spp (the error of one sample per pixel: equal for the
two when the budgeted render keeps the fixed one's stratification, larger when it does not).
Run from the repository root, under the lock:

  flock /tmp/ps-build.lock python3 bench/time_budget.py [--scene cornell-box] [--spp 64] [--time 1.5] [--seeds 4]
"""
import argparse
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bdpt_light_paths import SCENES, reference  # noqa: E402
import many_lights  # noqa: E402
from many_lights import PATHSPACE, ours, relmse  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="cornell-box", choices=list(SCENES))
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--time", type=float, default=1.5)
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--binary", action="append", help="pathspace binaries to compare (default: PATHSPACE)")
    ap.add_argument("--cache", default=os.path.join(os.path.dirname(PATHSPACE), "bench-cache"))
    a = ap.parse_args()
    os.makedirs(a.cache, exist_ok=True)
    scene, refSpp = SCENES[a.scene]
    ref = reference(a.scene, scene, refSpp, a.cache, a.threads)
    with tempfile.TemporaryDirectory() as tmp:
        out, st = os.path.join(tmp, "o.pfm"), os.path.join(tmp, "s.json")
        for binary in a.binary or [PATHSPACE]:
            for label, budget in ((f"--spp {a.spp}", a.spp), (f"--time {a.time:g}", None)):
                rows = []
                for seed in range(1, a.seeds + 1):
                    many_lights.PATHSPACE = binary
                    if budget:
                        ours(scene, out, seed, a.threads, spp=budget, stats=st)
                    else:
                        ours(scene, out, seed, a.threads, seconds=a.time, stats=st)
                    spp = json.load(open(st))["spp_mean"]
                    rows.append((spp, relmse(out, ref)))
                spp = sum(r[0] for r in rows) / len(rows)
                err = sum(r[1] for r in rows) / len(rows)
                per = [r[0] * r[1] for r in rows]
                print(f"{binary} {label}: spp {spp:.1f}, relMSE {err:.5f}, relMSE x spp {min(per):.4f}-{max(per):.4f}",
                      flush=True)


if __name__ == "__main__":
    main()
