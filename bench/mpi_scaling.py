#!/usr/bin/env python3
"""MPI overhead on this 2-core machine (strong scaling): the shared Cornell box, 256x256,
64 spp, path tracer, rendered by 1 process x 2 threads, by 2 processes x 1 thread (mpirun,
each bound to a core, and unbound) and by 1 process x 1 thread, alternating, RUNS times
each. Prints per setup the best and median render time (the statistics' wall_time_s, from
the processes' common start to the end of the last pass, plus the film's reduction to rank 0,
reduction_by_purpose's "film": scene loading and MPI start-up excluded) and its ratio to 1 process x 2
threads (the MPI overhead is the 2-process ratio minus 1), the reduction's time and bytes,
the best whole-command time and the CPU seconds of the whole command (every process,
mpirun's included: work the machine did, whatever else ran on it).
    flock /tmp/ps-build.lock python3 bench/mpi_scaling.py [RUNS] [INTEGRATOR]   (from the repository root)
INTEGRATOR: path (default, 64 spp) or a Metropolis one, pssmlt, mmlt or mlt (16 mutations per
pixel, the default 100000 bootstrap samples and 1000 chains): its bootstrap and chains split
over the processes (README), the reduction of its splat film, and the agreement after every
pass of mutations.
"""
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

runs = int(sys.argv[1]) if len(sys.argv) > 1 else 5
integrator = sys.argv[2] if len(sys.argv) > 2 else "path"
spp = "64" if integrator == "path" else "16"
root = os.getcwd()
binary = os.path.join(root, "build", "pathspace")
scene = os.path.join(root, "..", "shared", "scenes", "cornell-box", "scene-v4-256.pbrt")
mpirun = ["mpirun", "--oversubscribe", "--allow-run-as-root", "-n", "2"]
setups = {
    "1 process x 2 threads": ([], 2),
    "2 processes x 1 thread, bound": (mpirun + ["--bind-to", "core", "--map-by", "core"], 1),
    "2 processes x 1 thread": (mpirun + ["--bind-to", "none"], 1),
    "1 process x 1 thread": ([], 1),
}
results = {name: {"render": [], "command": [], "cpu": [], "reduction": [], "bytes": 0} for name in setups}
with tempfile.TemporaryDirectory() as tmp:
    for run in range(runs):
        for name, (launcher, threads) in setups.items():
            stats = os.path.join(tmp, "s.json")
            cmd = launcher + [binary, "render", "--quiet", "--integrator", integrator, "--spp", spp, "--threads",
                              str(threads), scene, "-o", os.path.join(tmp, "out.exr"), "--stats", stats]
            t0, c0 = time.monotonic(), resource.getrusage(resource.RUSAGE_CHILDREN)
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            command, c1 = time.monotonic() - t0, resource.getrusage(resource.RUSAGE_CHILDREN)
            s = json.load(open(stats))
            r = results[name]
            # The final reduction only: the stop decisions and the bootstrap merge happen within
            # wall_time_s (reduction_seconds counts every collective of the run).
            film = s["reduction_by_purpose"].get("film", {"seconds": 0.0, "bytes": 0.0})
            r["render"].append(s["wall_time_s"] + film["seconds"])
            r["reduction"].append(film["seconds"])
            r["command"].append(command)
            r["cpu"].append(c1.ru_utime + c1.ru_stime - c0.ru_utime - c0.ru_stime)
            r["bytes"] = film["bytes"]
base = min(results["1 process x 2 threads"]["render"])
baseMedian = statistics.median(results["1 process x 2 threads"]["render"])
print(f"Cornell box 256x256, {integrator}, --spp {spp}; {runs} alternating runs each (best / median seconds)")
for name, r in results.items():
    best, med = min(r["render"]), statistics.median(r["render"])
    print(f"{name:31s} render+reduction {best:.3f} / {med:.3f} s (x{best / base:.3f} / x{med / baseMedian:.3f}) | "
          f"reduction {statistics.median(r['reduction']) * 1e3:.1f} ms, {r['bytes'] / 1e6:.1f} MB per process | "
          f"command {min(r['command']):.3f} s, {min(r['cpu']):.3f} CPU s")
