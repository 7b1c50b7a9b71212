#!/usr/bin/env python3
"""Scene load time and peak memory: pathspace against pbrt-v4 on the same scene files.

    flock /tmp/ps-build.lock python3 bench/scene_load.py --pbrt PBRT [--runs N] SCENE.pbrt...

Each scene is rendered by both programs, whole process, at 1 sample per pixel with 2 threads
(the scene's own integrator, film and resolution; images go to a temporary folder), run
from the scene's folder as its relative paths expect. Per program: wall time (the best of
--runs runs, alternating the programs) and peak resident memory (the child's ru_maxrss,
from wait4). Ratios: pbrt-v4's time over ours (the goal: at least 2) and our memory over
pbrt-v4's (the goal: at most 0.85). A run that fails prints its last lines of output.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_PATHSPACE = os.path.join(HERE, "..", "build", "pathspace")


def run(cmd, cwd):
    """(wall seconds, peak RSS in MiB, exit status, output tail) of one process."""
    with tempfile.TemporaryFile() as out:
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(p.pid, 0)
        wall = time.perf_counter() - t0
        out.seek(0)
        tail = out.read().decode(errors="replace").splitlines()[-5:]
    code = os.waitstatus_to_exitcode(status)
    return wall, usage.ru_maxrss / 1024.0, code, tail


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--pbrt", required=True, help="pbrt-v4's pbrt binary")
    ap.add_argument("--pathspace", default=DEFAULT_PATHSPACE)
    ap.add_argument("--runs", type=int, default=1)
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    pathspace, pbrt = os.path.abspath(a.pathspace), os.path.abspath(a.pbrt)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in a.scenes:
            scene = os.path.abspath(scene)
            cwd, name = os.path.dirname(scene), os.path.basename(scene)
            out = os.path.join(tmp, "out.exr")
            cmds = {
                "pathspace": [pathspace, "render", name, "--spp", "1", "--threads", str(a.threads), "--quiet", "-o", out],
                "pbrt": [pbrt, "--nthreads", str(a.threads), "--spp", "1", "--outfile", out, name],
            }
            best = {}
            for _ in range(a.runs):
                for prog, cmd in cmds.items():
                    wall, rss, code, tail = run(cmd, cwd)
                    if code != 0:
                        print(f"{name}: {prog} exited with {code}:\n  " + "\n  ".join(tail), file=sys.stderr)
                        wall = rss = float("nan")
                    w0, r0 = best.get(prog, (float("inf"), 0.0))
                    best[prog] = (min(w0, wall), max(r0, rss))
                    print(f"  {name} {prog}: {wall:.2f} s, {rss:.0f} MiB", file=sys.stderr, flush=True)
            rows.append((os.path.relpath(scene), best))
    print("| scene | pathspace s | pbrt-v4 s | speed-up | pathspace MiB | pbrt-v4 MiB | memory ratio |")
    print("|---|---|---|---|---|---|---|")
    for scene, b in rows:
        (ws, rs), (wp, rp) = b["pathspace"], b["pbrt"]
        print(f"| {scene} | {ws:.2f} | {wp:.2f} | {wp / ws:.2f} | {rs:.0f} | {rp:.0f} | {rs / rp:.2f} |")


if __name__ == "__main__":
    main()
