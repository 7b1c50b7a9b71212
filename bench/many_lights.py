#!/usr/bin/env python3
"""Many lights at equal time against pbrt-v4 (issue 40, section 2).

For each scene of bench/scenes/many-lights (or the scenes given):
  1. a long reference: pathspace, path tracer, lightsampler bvh, --ref-spp samples (cached in
     build/bench-cache/), checked against a long pbrt-v4 render's image mean (--pbrt-ref-spp);
  2. equal-time runs of the same whole-process wall time T (--time), 2 threads, --seeds seeds
     each: pbrt-v4 path with lightsampler bvh and power, pathspace path bvh and power,
     pathspace bdpt. pathspace stops at `--time T`; pbrt-v4 has no time budget, so its --spp
     comes from two timed probes (whole process, a + b spp fitted): the power of two (its
     zsobol sampler renders no other counts) whose time is nearest T;
  3. relMSE of each image against the reference (mean over pixels and channels of
     (x - r)^2 / (r^2 + 0.01), as bench/README.md's equal-time figures), mean and spread over
     the seeds, and the ratios to pbrt-v4's bvh; also "at T", each run's relMSE times its own
     whole-process time over T (relMSE falls as 1/time), for runs that missed T.

The lightsampler is the scene's Integrator parameter: the power runs read a copy of the scene
with "bvh" replaced by "power" (a temporary file). Run from the repository root, under the
lock for the whole measurement:

  flock /tmp/ps-build.lock python3 bench/many_lights.py [--time 3] [--seeds 3] [--pbrt PBRT] [SCENE...]
"""
import argparse
import json
import math
import os
import re
import resource
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from image_means import mean_and_error, pfm_mean_luminance, read_pfm  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
PATHSPACE = os.environ.get("PATHSPACE", os.path.join(ROOT, "build", "pathspace"))
PBRT = os.path.join(os.environ.get("PEERS", os.path.expanduser("~/peers")), "pbrt-v4", "build", "pbrt")
SCENES = [os.path.join(HERE, "scenes", "many-lights", n + ".pbrt") for n in ("corridor", "street", "emissive-mesh")]


def relmse(image, reference, variance=None):
    """Mean over pixels and channels of (x - r)^2 / (r^2 + 0.01). With the reference's
    variance image (--aov variance, PFM), its per-pixel variance is subtracted from each
    squared difference, as equal_time_bench does: E[(x - r)^2] = MSE(x) + Var(r)."""
    w, h, x = read_pfm(image)
    rw, rh, r = read_pfm(reference)
    assert (w, h) == (rw, rh), f"{image}: {w}x{h}, reference {rw}x{rh}"
    v = read_pfm(variance)[2] if variance else [0.0] * len(r)
    return sum(((a - b) ** 2 - s) / (b * b + 0.01) for a, b, s in zip(x, r, v)) / len(r)


def timed(cmd, cwd=None, stdout=None):
    """Runs cmd; returns its whole-process wall time in seconds. Fails on any error output.
    stdout: a list that receives the command's standard output (discarded otherwise)."""
    start = time.perf_counter()
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE if stdout is not None else subprocess.DEVNULL,
                       stderr=subprocess.PIPE, text=True)
    elapsed = time.perf_counter() - start
    if stdout is not None:
        stdout.append(p.stdout or "")
    if p.returncode != 0:
        sys.exit(f"failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr}")
    noise = [l for l in p.stderr.splitlines() if ("Warning" in l or "warning" in l)
             and "Output filename supplied on command line" not in l]
    if noise:
        print(f"  warnings from {' '.join(cmd)}:\n    " + "\n    ".join(noise[:5]), flush=True)
    return elapsed


def cpu_timed(cmd):
    """Runs cmd (failing on an error); returns the process's user + system CPU seconds."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def with_lightsampler(scene, sampler, tmp):
    text = open(scene).read()
    new, n = re.subn(r'"string lightsampler" \[ "bvh" \]', f'"string lightsampler" [ "{sampler}" ]', text)
    assert n == 1, f"{scene}: no lightsampler bvh to replace"
    path = os.path.join(tmp, os.path.basename(scene).replace(".pbrt", f"-{sampler}.pbrt"))
    with open(path, "w") as f:
        f.write(new)
    return path


def ours(scene, out, seed, threads, spp=None, seconds=None, integrator="path", stats=None, extra=()):
    """Renders with pathspace; returns the whole-process wall time. `stats`: a file that
    receives {"spp_mean": ...} from the render's closing summary. Not from --stats, which
    would change what is measured: it renders a QMC sampler's samples as 8 independently
    scrambled sets (noisier than one) and tallies every technique's figures."""
    cmd = [PATHSPACE, "render", scene, "--integrator", integrator, "--threads", str(threads), "--seed", str(seed),
           "-o", out, *extra]
    cmd += ["--spp", str(spp)] if spp else ["--spp", "100000000", "--time", str(seconds)]
    if not stats:
        return timed(cmd + ["--quiet"])
    text = []
    elapsed = timed(cmd, stdout=text)
    with open(stats, "w") as f:
        json.dump({"spp_mean": summary(text[0], cmd)[1]}, f)
    return elapsed


def summary(text, cmd):
    """(the render's own seconds, samples or mutations per pixel) from pathspace's closing
    summary line ("time T s | N spp ..."), or exit naming the command."""
    m = re.search(r"time ([0-9.]+) s \| ([0-9.]+) spp", text)
    if not m:
        sys.exit(f"no summary from {' '.join(cmd)}:\n{text[-500:]}")
    return float(m.group(1)), float(m.group(2))


def pbrt(scene, out, seed, threads, spp):
    return timed([PBRT, "--nthreads", str(threads), "--seed", str(seed), "--spp", str(spp), "--outfile", out, scene],
                 cwd=os.path.dirname(scene))


def pbrt_spp_for(scene, seconds, threads, tmp):
    """pbrt-v4's spp for a whole process of about `seconds`. Its zsobol sampler (these scenes')
    renders 2^floor(log2 spp) samples per pixel whatever --spp says, so the count is the power
    of two whose time, t = a + b spp fitted to probes at 4 and 16 spp, is nearest; the runs'
    own times then scale their relMSE to T ("at T")."""
    out = os.path.join(tmp, "probe.pfm")
    t1 = min(pbrt(scene, out, 90, threads, 4) for _ in range(2))
    t2 = min(pbrt(scene, out, 91, threads, 16) for _ in range(2))
    b = max((t2 - t1) / 12, 1e-6)
    a = min(max(t1 - 4 * b, 0.0), 0.5 * seconds)
    spp = min((2 ** k for k in range(16)), key=lambda n: abs(a + b * n - seconds))
    return spp, a, b


def equal_time_parser(doc, scenes, seconds, time_help):
    """The command line the equal-time benches share: scenes, --time, --seeds, --threads."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="*", default=scenes)
    ap.add_argument("--time", type=float, default=seconds, help=time_help)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    return ap


def main():
    global PBRT
    ap = equal_time_parser(__doc__, SCENES, 3.0, "whole-process wall time of each run, seconds")
    ap.add_argument("--ref-spp", type=int, default=2048, help="pathspace reference, samples per pixel")
    ap.add_argument("--pbrt-ref-spp", type=int, default=256, help="pbrt-v4's long render for the image-mean check")
    ap.add_argument("--pbrt", default=PBRT)
    ap.add_argument("--cache", default=os.path.join(ROOT, "build", "bench-cache"))
    ap.add_argument("--json", help="write every figure here")
    args = ap.parse_args()
    PBRT = args.pbrt
    os.makedirs(args.cache, exist_ok=True)
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        for scene in args.scenes:
            scene = os.path.abspath(scene)
            name = os.path.basename(scene)[:-5]
            print(f"== {name}", flush=True)
            power = with_lightsampler(scene, "power", tmp)
            ref = os.path.join(args.cache, f"many-lights-{name}-ref{args.ref_spp}.pfm")
            if not os.path.exists(ref):
                t = ours(scene, ref, 1000, args.threads, spp=args.ref_spp)
                print(f"  reference: pathspace path bvh, {args.ref_spp} spp, {t:.1f} s", flush=True)
            pref = os.path.join(args.cache, f"many-lights-{name}-pbrt-ref{args.pbrt_ref_spp}.pfm")
            if not os.path.exists(pref):
                t = pbrt(scene, pref, 1000, args.threads, args.pbrt_ref_spp)
                print(f"  pbrt-v4 path bvh, {args.pbrt_ref_spp} spp, {t:.1f} s", flush=True)
            m_ours, m_pbrt = pfm_mean_luminance(ref), pfm_mean_luminance(pref)
            check = {"ours_mean": m_ours, "pbrt_mean": m_pbrt, "ratio": m_ours / m_pbrt,
                     "relmse_pbrt_vs_ref": relmse(pref, ref)}
            print(f"  image mean: pathspace {m_ours:.6g}, pbrt-v4 {m_pbrt:.6g}, ratio {m_ours / m_pbrt:.4f}; "
                  f"relMSE of pbrt-v4's long render against the reference {check['relmse_pbrt_vs_ref']:.4g}", flush=True)
            spp = {}
            for label, s in (("pbrt-v4 path bvh", scene), ("pbrt-v4 path power", power)):
                spp[label], a, b = pbrt_spp_for(s, args.time, args.threads, tmp)
                print(f"  {label}: {a:.2f} s + {b * 1000:.1f} ms/spp -> --spp {spp[label]}", flush=True)
            configs = [("pbrt-v4 path bvh", lambda o, sd, st: pbrt(scene, o, sd, args.threads, spp["pbrt-v4 path bvh"])),
                       ("pbrt-v4 path power", lambda o, sd, st: pbrt(power, o, sd, args.threads, spp["pbrt-v4 path power"])),
                       ("ours path bvh", lambda o, sd, st: ours(scene, o, sd, args.threads, seconds=args.time, stats=st)),
                       ("ours path power", lambda o, sd, st: ours(power, o, sd, args.threads, seconds=args.time, stats=st)),
                       ("ours bdpt", lambda o, sd, st: ours(scene, o, sd, args.threads, seconds=args.time,
                                                            integrator="bdpt", stats=st))]
            runs = {label: [] for label, _ in configs}
            for seed in range(1, args.seeds + 1):  # alternate the configurations within each seed
                for label, run in configs:
                    out, st = os.path.join(tmp, "run.pfm"), os.path.join(tmp, "stats.json")
                    if os.path.exists(st):
                        os.remove(st)
                    t = run(out, seed, st)
                    s = spp.get(label)
                    if s is None and os.path.exists(st):
                        stats = json.load(open(st))
                        s = round(stats["spp_mean"], 1)
                        if stats.get("warnings"):
                            print(f"  {label} seed {seed}: {stats['warnings']} warnings", flush=True)
                    runs[label].append({"seed": seed, "seconds": t, "spp": s, "relmse": relmse(out, ref),
                                        "mean": pfm_mean_luminance(out)})
            table = {}
            for label, rs in runs.items():
                e = [r["relmse"] for r in rs]
                m, se, sd = mean_and_error(e) if len(e) > 1 else (e[0], 0.0, 0.0)
                # relMSE falls as 1/time: scaled to the budget T by each run's own whole-process time
                scaled = sum(r["relmse"] * r["seconds"] for r in rs) / len(rs) / args.time
                table[label] = {"relmse": m, "relmse_sd": sd, "relmse_at_T": scaled, "relmse_min": min(e), "relmse_max": max(e),
                                "seconds": [r["seconds"] for r in rs], "spp": [r["spp"] for r in rs],
                                "image_mean_over_ref": sum(r["mean"] for r in rs) / len(rs) / m_ours, "runs": rs}
            base = table["pbrt-v4 path bvh"]["relmse"]
            base_t = table["pbrt-v4 path bvh"]["relmse_at_T"]
            print(f"  {'configuration':20s} {'relMSE':>10s} {'sd':>9s} {'min-max':>19s} {'/pbrt bvh':>9s} "
                  f"{'at T':>10s} {'/pbrt bvh':>9s} {'seconds':>17s} {'spp':>17s} {'mean/ref':>8s}")
            for label, row in table.items():
                row["over_pbrt_bvh"] = row["relmse"] / base
                row["at_T_over_pbrt_bvh"] = row["relmse_at_T"] / base_t
                secs = " ".join(f"{x:.2f}" for x in row["seconds"])
                spps = " ".join(str(x) for x in row["spp"])
                print(f"  {label:20s} {row['relmse']:10.4g} {row['relmse_sd']:9.2g} "
                      f"{row['relmse_min']:9.3g}-{row['relmse_max']:<9.3g} {row['over_pbrt_bvh']:9.3f} "
                      f"{row['relmse_at_T']:10.4g} {row['at_T_over_pbrt_bvh']:9.3f} {secs:>17s} "
                      f"{spps:>17s} {row['image_mean_over_ref']:8.4f}", flush=True)
            results[name] = {"reference_check": check, "pbrt_spp": spp, "table": table}
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
