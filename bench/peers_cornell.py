#!/usr/bin/env python3
"""The shared Cornell box side by side with the peers: whole-process wall and user times of
pathspace, Tungsten and (optionally) pbrt-v4, path tracing and BDPT, 256x256, 64 spp,
maxdepth 8, 2 threads, in alternating rounds so that each ratio is taken within one round
(this machine's speed drifts between minutes).

    flock /tmp/ps-build.lock python3 bench/peers_cornell.py --rounds 5 \
        [--tungsten ~/peers/tungsten/build/tungsten] [--pbrt ~/peers/pbrt-v4/build/pbrt] \
        [--ours build/pathspace] [--extra=--color=rgb] [--json out.json]

Peers are built by ../shared/peers/README.md; a peer whose binary is missing is left out.
"""
import argparse
import json
import os
import re
import resource
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SHARED = os.path.join(ROOT, "..", "shared")
SCENE = os.path.join(SHARED, "scenes", "cornell-box", "scene-v4-256.pbrt")
TUNGSTEN_SCENES = os.path.join(SHARED, "peers", "tungsten-scenes")


def timed(cmd, cwd=None):
    """Wall and user+sys CPU seconds of one child process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(cmd, cwd=cwd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def pbrt_scene(out, integ):
    """The scene with pbrt-v4's integrator and maxdepth 8 written in (pbrt has no such flags;
    the file is self-contained, so its copy renders the same elsewhere)."""
    path = os.path.join(out, f"cornell-{integ}.pbrt")
    with open(SCENE) as f:
        text = f.read()
    head, rest = text.split("\n", 1)  # Integrator "path", then its "integer maxdepth" line
    assert head.strip() == 'Integrator "path"', head
    rest = re.sub(r'"integer maxdepth"\s*\[\s*\d+\s*\]', '"integer maxdepth" [ 8 ]', rest, count=1)
    text = f'Integrator "{integ}"\n' + rest
    with open(path, "w") as f:
        f.write(text)
    return path


def main():
    home = os.path.expanduser("~")
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--ours", default=os.path.join(ROOT, "build", "pathspace"))
    ap.add_argument("--tungsten", default=os.path.join(home, "peers", "tungsten", "build", "tungsten"))
    ap.add_argument("--pbrt", default=os.path.join(home, "peers", "pbrt-v4", "build", "pbrt"))
    ap.add_argument("--no-pbrt", action="store_true", help="leave pbrt-v4 out (it takes 10-45 s a render)")
    ap.add_argument("--integrators", default="path,bdpt")
    ap.add_argument("--extra", action="append", default=[], help="an extra argument for pathspace (repeatable)")
    ap.add_argument("--json", help="write every run's figures here")
    args = ap.parse_args()

    out = tempfile.mkdtemp(prefix="peers-cornell-")
    tungsten_scene = {"path": "cornell-box-md8.tungsten.json", "bdpt": "cornell-box-md8-bdpt.tungsten.json"}
    runs = []
    for r in range(args.rounds):
        for integ in args.integrators.split(","):
            row = {"round": r + 1, "integrator": integ}
            ours = [args.ours, "render", SCENE, "--integrator", integ, "--spp", "64", "--maxdepth", "8",
                    "--threads", "2", "--quiet", "-o", os.path.join(out, "ours.pfm")] + args.extra
            row["pathspace"] = timed(ours)
            if os.path.exists(args.tungsten):
                row["tungsten"] = timed([args.tungsten, "-t", "2", "--spp", "64", "-d", out, tungsten_scene[integ]],
                                        cwd=TUNGSTEN_SCENES)
            if os.path.exists(args.pbrt) and not args.no_pbrt:
                row["pbrt-v4"] = timed([args.pbrt, "--nthreads", "2", "--spp", "64", "--seed", "1", "--quiet",
                                        "--outfile", os.path.join(out, "pbrt.exr"), pbrt_scene(out, integ)])
            runs.append(row)
            line = f"round {r + 1} {integ:5s} pathspace {row['pathspace'][0]:6.2f} s (user {row['pathspace'][1]:5.2f})"
            for peer in ("tungsten", "pbrt-v4"):
                if peer in row:
                    line += (f"  {peer} {row[peer][0]:6.2f} s (user {row[peer][1]:5.2f})"
                             f"  ours/{peer} {row['pathspace'][0] / row[peer][0]:.2f}")
            print(line, flush=True)
    for integ in args.integrators.split(","):
        for peer in ("tungsten", "pbrt-v4"):
            ratios = [row["pathspace"][0] / row[peer][0] for row in runs if row["integrator"] == integ and peer in row]
            if ratios:
                print(f"{integ}: pathspace / {peer} wall time {min(ratios):.2f}-{max(ratios):.2f} over {len(ratios)} rounds")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(runs, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
