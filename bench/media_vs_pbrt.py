#!/usr/bin/env python3
"""Media against pbrt-v4's volpath (issue 36, bench part): equal-time relMSE on a fog scene and
a cloud, and the load time and peak memory of a NanoVDB cloud.

Scenes: bench/scenes/media-fog.pbrt (the camera in chromatic homogeneous fog, an area light
behind columns) and bench/scenes/media-cloud.pbrt (a 128^3 NanoVDB cloud, high albedo, sun and
sky). The cloud's .nvdb is written into the cache by tests/tools/make_nvdb (`make_nvdb FILE
cloud N`, built with the tests) and the scene read from a copy naming it.

For each scene:
  1. a long reference: pathspace `path`, spectral (pbrt-v4 renders spectrally), a render of
     --ref-time seconds (30 times the runs' by default), seed 1000 (cached in
     build/bench-cache/; delete it, and the .nvdb, after changing a scene or make_nvdb);
  2. equal-time runs of the same whole-process wall time T (--time), 2 threads, --seeds seeds,
     alternating the two renderers within each seed: pbrt-v4 volpath (its --spp from two
     timed probes, the power of two nearest T: its default zsobol sampler renders no other
     counts; many_lights.pbrt_spp_for) and pathspace path --color spectral --time T;
  3. relMSE of each image against the reference (mean over pixels and channels of
     (x - r)^2 / (r^2 + 0.01), as bench/README.md's equal-time figures), mean and spread over
     the seeds, the ratio ours / pbrt-v4 (the goal: at most 1/3), and "at T": each run's relMSE
     times its own whole-process time over T (relMSE falls as 1/time), for runs that missed T.
     --ours-fixed-spp adds ours at a fixed spp chosen from probes as pbrt-v4's is.
Then the load: both renderers on the cloud scene at 1 spp, 16x16 pixels (the film's size
changed in a copy), whole process, against the same scene without the cloud (its medium and
boundary removed): wall time (the best of --load-runs, alternating) and peak resident memory
(/usr/bin/time's maximum resident set size, %M; not wait4's ru_maxrss from Python, which
Linux starts at the forking Python's own 20 MiB), and the differences, the cloud's own cost.

Run from the repository root, under the lock for the whole measurement:

  flock /tmp/ps-build.lock python3 bench/media_vs_pbrt.py [--time 6] [--seeds 3] [--pbrt PBRT] [--load-only]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import many_lights  # noqa: E402
from image_means import mean_and_error, pfm_mean_luminance  # noqa: E402
from many_lights import ROOT, ours, pbrt_spp_for, relmse  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = {"fog": os.path.join(HERE, "scenes", "media-fog.pbrt"), "cloud": os.path.join(HERE, "scenes", "media-cloud.pbrt")}
SPECTRAL = ("--color", "spectral")


def make_nvdb(cache, res):
    path = os.path.join(cache, f"cloud-{res}.nvdb")
    if not os.path.exists(path):
        tool = os.path.join(ROOT, "build", "tests", "make_nvdb")
        if not os.path.exists(tool):
            sys.exit(f"{tool} is missing: cmake --build build --target make_nvdb")
        subprocess.run([tool, path, "cloud", str(res)], check=True, stdout=subprocess.DEVNULL)
    return path


def scene_copy(name, tmp, nvdb, film=None, drop_cloud=False):
    """The scene with the cloud's .nvdb path written in; `film` (w, h) changes its size;
    `drop_cloud` removes the AttributeBegin ... AttributeEnd block holding the medium."""
    text = open(SCENES[name]).read().replace("CLOUD_NVDB", nvdb)
    if film:
        text, n = re.subn(r'"integer xresolution" \[ \d+ \] "integer yresolution" \[ \d+ \]',
                          f'"integer xresolution" [ {film[0]} ] "integer yresolution" [ {film[1]} ]', text)
        assert n == 1
    if drop_cloud:
        text, n = re.subn(r"AttributeBegin\n(?:(?!AttributeEnd).)*MakeNamedMedium.*?AttributeEnd\n", "", text, flags=re.S)
        assert n == 1
    suffix = ("-%dx%d" % film if film else "") + ("-empty" if drop_cloud else "")
    path = os.path.join(tmp, f"media-{name}{suffix}.pbrt")
    with open(path, "w") as f:
        f.write(text)
    return path


def equal_time(name, scene, args, tmp):
    tag = f"-{args.nvdb_res}" if name == "cloud" else ""
    ref = os.path.join(args.cache, f"media-{name}{tag}-ref{args.ref_time:g}s.pfm")
    if not os.path.exists(ref):
        st = os.path.join(tmp, "ref-stats.json")
        t = ours(scene, ref, 1000, args.threads, seconds=args.ref_time, stats=st, extra=SPECTRAL)
        print(f"  reference: pathspace path spectral, {json.load(open(st))['spp_mean']:.0f} spp, {t:.1f} s", flush=True)
    m_ref = pfm_mean_luminance(ref)
    spp, a, b = pbrt_spp_for(scene, args.time, args.threads, tmp)
    print(f"  pbrt-v4 volpath: {a:.2f} s + {b * 1000:.1f} ms/spp -> --spp {spp}", flush=True)
    configs = [("pbrt-v4 volpath", lambda o, sd, st: many_lights.pbrt(scene, o, sd, args.threads, spp)),
               ("ours path", lambda o, sd, st: ours(scene, o, sd, args.threads, seconds=args.time, stats=st,
                                                    extra=SPECTRAL))]
    if args.ours_fixed_spp:
        # Ours at a fixed count too, chosen as pbrt-v4's is (any count: t = a + b spp fitted to
        # probes at 8 and 32 spp), to set the --time renders' sampling apart from the rest.
        out = os.path.join(tmp, "probe.pfm")
        t1 = min(ours(scene, out, 90, args.threads, spp=8, extra=SPECTRAL) for _ in range(2))
        t2 = min(ours(scene, out, 91, args.threads, spp=32, extra=SPECTRAL) for _ in range(2))
        ob = max((t2 - t1) / 24, 1e-6)
        oa = max(t1 - 8 * ob, 0.0)
        ospp = max(1, round((args.time - oa) / ob))
        print(f"  ours fixed: {oa:.2f} s + {ob * 1000:.1f} ms/spp -> --spp {ospp}", flush=True)
        configs.append(("ours path fixed spp", lambda o, sd, st: ours(scene, o, sd, args.threads, spp=ospp, extra=SPECTRAL)))
    runs = {label: [] for label, _ in configs}
    for seed in range(1, args.seeds + 1):
        for label, run in configs:
            out, st = os.path.join(tmp, "run.pfm"), os.path.join(tmp, "stats.json")
            if os.path.exists(st):
                os.remove(st)
            t = run(out, seed, st)
            s = spp if label.startswith("pbrt") else ospp if "fixed" in label else round(json.load(open(st))["spp_mean"], 1)
            runs[label].append({"seed": seed, "seconds": t, "spp": s, "relmse": relmse(out, ref),
                                "mean": pfm_mean_luminance(out)})
            print(f"    seed {seed} {label}: {t:.2f} s, {s} spp, relMSE {runs[label][-1]['relmse']:.4g}", flush=True)
    table = {}
    for label, rs in runs.items():
        e = [r["relmse"] for r in rs]
        m, se, sd = mean_and_error(e) if len(e) > 1 else (e[0], 0.0, 0.0)
        table[label] = {"relmse": m, "relmse_sd": sd, "relmse_at_T": sum(r["relmse"] * r["seconds"] for r in rs) / len(rs) / args.time,
                        "seconds": [r["seconds"] for r in rs], "spp": [r["spp"] for r in rs],
                        "image_mean_over_ref": sum(r["mean"] for r in rs) / len(rs) / m_ref, "runs": rs}
    p, o = table["pbrt-v4 volpath"], table["ours path"]
    if "ours path fixed spp" in table:
        f = table["ours path fixed spp"]
        print(f"  relMSE ours at a fixed spp / pbrt-v4: {f['relmse'] / p['relmse']:.3f} (at T {f['relmse_at_T'] / p['relmse_at_T']:.3f})")
    print(f"  {'':16s} {'relMSE':>10s} {'sd':>9s} {'at T':>10s} {'seconds':>20s} {'spp':>20s} {'mean/ref':>8s}")
    for label, row in table.items():
        print(f"  {label:16s} {row['relmse']:10.4g} {row['relmse_sd']:9.2g} {row['relmse_at_T']:10.4g} "
              f"{' '.join(f'{x:.2f}' for x in row['seconds']):>20s} {' '.join(str(x) for x in row['spp']):>20s} "
              f"{row['image_mean_over_ref']:8.4f}")
    ratio, ratio_t = o["relmse"] / p["relmse"], o["relmse_at_T"] / p["relmse_at_T"]
    print(f"  relMSE ours / pbrt-v4: {ratio:.3f} (at T {ratio_t:.3f}); goal <= 0.333: "
          f"{'met' if ratio_t <= 1 / 3 else 'not met'}", flush=True)
    return {"pbrt_spp": spp, "pbrt_probe": [a, b], "table": table, "ratio": ratio, "ratio_at_T": ratio_t}


def run_measured(cmd, cwd):
    """(wall seconds, peak RSS in MiB, exit status, output tail) of one process, through
    /usr/bin/time (its %M, KiB)."""
    t0 = time.perf_counter()
    p = subprocess.run(["/usr/bin/time", "-f", "maxrss %M", *cmd], cwd=cwd, stdout=subprocess.DEVNULL,
                       stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - t0
    lines = p.stderr.splitlines()
    rss = next((int(l.split()[1]) / 1024.0 for l in reversed(lines) if l.startswith("maxrss ")), float("nan"))
    return wall, rss, p.returncode, lines[-5:]


def load(args, tmp, nvdb, pbrt):
    out = os.path.join(tmp, "load.exr")
    scenes = {"cloud": scene_copy("cloud", tmp, nvdb, film=(16, 16)),
              "no cloud": scene_copy("cloud", tmp, nvdb, film=(16, 16), drop_cloud=True)}
    best = {}
    for _ in range(args.load_runs):
        for which, scene in scenes.items():
            cmds = {"pathspace": [many_lights.PATHSPACE, "render", scene, "--spp", "1", "--threads", str(args.threads),
                                  "--quiet", "-o", out, *SPECTRAL],
                    "pbrt-v4": [pbrt, "--nthreads", str(args.threads), "--spp", "1", "--quiet", "--outfile", out, scene]}
            for prog, cmd in cmds.items():
                wall, rss, code, tail = run_measured(cmd, tmp)
                if code != 0:
                    sys.exit(f"{prog} exited with {code}:\n  " + "\n  ".join(tail))
                w0, r0 = best.get((prog, which), (float("inf"), 0.0))
                best[(prog, which)] = (min(w0, wall), max(r0, rss))
    print(f"  {'':10s} {'with cloud s':>12s} {'MiB':>6s} {'without s':>10s} {'MiB':>6s} {'cloud s':>8s} {'cloud MiB':>9s}")
    res = {}
    for prog in ("pathspace", "pbrt-v4"):
        (w1, r1), (w0, r0) = best[(prog, "cloud")], best[(prog, "no cloud")]
        res[prog] = {"wall": w1, "rss_mib": r1, "wall_without": w0, "rss_without_mib": r0}
        print(f"  {prog:10s} {w1:12.3f} {r1:6.0f} {w0:10.3f} {r0:6.0f} {w1 - w0:8.3f} {r1 - r0:9.0f}", flush=True)
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="*", default=list(SCENES))
    ap.add_argument("--time", type=float, default=6.0, help="whole-process wall time of each run, seconds")
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--ref-time", type=float, default=180, help="pathspace reference, seconds")
    ap.add_argument("--nvdb-res", type=int, default=128, help="the cloud grid's voxels per side (8 to 128)")
    ap.add_argument("--load-runs", type=int, default=3)
    ap.add_argument("--load-only", action="store_true", help="only the load time and memory")
    ap.add_argument("--ours-fixed-spp", action="store_true",
                    help="also ours at a fixed spp chosen from timed probes, as pbrt-v4's (not --time)")
    ap.add_argument("--pbrt", default=many_lights.PBRT)
    ap.add_argument("--cache", default=os.path.join(ROOT, "build", "bench-cache"))
    ap.add_argument("--json", help="write every figure here")
    args = ap.parse_args()
    many_lights.PBRT = args.pbrt
    os.makedirs(args.cache, exist_ok=True)
    nvdb = make_nvdb(args.cache, args.nvdb_res)
    results = {"nvdb": {"file": os.path.basename(nvdb), "bytes": os.path.getsize(nvdb)}}
    with tempfile.TemporaryDirectory() as tmp:
        for name in [] if args.load_only else args.scenes:
            print(f"== {name}", flush=True)
            results[name] = equal_time(name, scene_copy(name, tmp, nvdb), args, tmp)
        print(f"== load: {os.path.basename(nvdb)}, {os.path.getsize(nvdb) / 2**20:.1f} MiB", flush=True)
        results["load"] = load(args, tmp, nvdb, args.pbrt)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
