#!/usr/bin/env python3
"""Metropolis on a set of six scenes at equal time (issue 37).

For each scene of bench/scenes/metropolis-set (or the scenes given):
  1. a long BDPT reference with its per-pixel variance (--aov variance), --ref-time seconds,
     cached in build/bench-cache/ under the scene's name, the time and a hash of its text;
  2. equal-time renders of --time T seconds each (pathspace's --time; the Metropolis
     bootstrap and pilot included), 2 threads, seeds 1..--seeds, the integrators alternating
     within each seed: bdpt, mmlt, mlt with their defaults, and pbrt-v4's mlt (its
     multiplexed MLT) when its binary exists, its mutations per pixel fitted to T by two
     timed probes (a note says so when it is missing);
  3. the relative MSE of each image against the reference (per pixel and channel
     (x - r)^2 / (r^2 + 0.01), with the reference's own variance subtracted, as
     equal_time_bench does), its mean over the seeds and its ratio to BDPT's, and the image
     mean over the reference's per seed and its spread (standard deviation) across seeds.

Every render runs under its own hold of the build lock (flock LOCK, one render each), so that
other work on the machine can interleave; do not run the script itself under the lock. Run
from the repository root:

  python3 bench/metropolis_set.py [--time 8] [--seeds 3] [--ref-time 60] [--json OUT.json] [SCENE...]
"""
import hashlib
import json
import os
import re
import statistics
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from image_means import pfm_mean_luminance, read_pfm  # noqa: E402
from many_lights import HERE, PATHSPACE, PBRT, ROOT, equal_time_parser, relmse, summary, timed  # noqa: E402

SET = os.path.join(HERE, "scenes", "metropolis-set")
# The set, and what kind of light each scene has: the goals (mmlt <= 1/3 and mlt <= 1/5 of
# BDPT's relMSE) are for the dark, indirectly lit scenes; the open scene is where BDPT should win.
KINDS = {"door-ajar": "dark-indirect", "door-ajar-glossy": "dark-indirect", "mirror-caustic": "caustic",
         "crack": "dark-indirect", "lantern": "dark-indirect", "open-sky": "open"}
SCENES = [os.path.join(SET, n + ".pbrt") for n in KINDS]
INTEGRATORS = ("bdpt", "mmlt", "mlt")


def inlined(path):
    """The scene's text with its Include directives replaced by the included files' text."""
    out = []
    for line in open(path).read().splitlines():
        m = re.match(r'\s*Include\s+"([^"]+)"', line)
        out.append(inlined(os.path.join(os.path.dirname(path), m.group(1))) if m else line)
    return "\n".join(out)


def ours(scene, out, seed, args, integrator, seconds, extra=()):
    """One pathspace render under its own hold of the lock. Returns (the render's own time,
    samples or mutations per pixel) from its closing summary."""
    cmd = ["flock", args.lock, PATHSPACE, "render", scene, "--integrator", integrator, "--threads", str(args.threads),
           "--seed", str(seed), "--spp", "1000000000", "--time", str(seconds), "-o", out, *extra]
    text = []
    timed(cmd, stdout=text)
    return summary(text[0], cmd)


def pbrt_scene(scene, tmp, mutations):
    """A copy of the scene for pbrt-v4's mlt (its multiplexed MLT): the Integrator line
    replaced, maxdepth kept."""
    text = inlined(scene)
    depth = re.search(r'"integer maxdepth" \[ *([0-9]+) *\]', text).group(1)
    line = f'Integrator "mlt" "integer maxdepth" [ {depth} ] "integer mutationsperpixel" [ {mutations} ]'
    text, n = re.subn(r"^Integrator .*$", line, text, flags=re.M)
    assert n == 1, f"{scene}: one Integrator line expected"
    path = os.path.join(tmp, f"pbrt-{os.path.basename(scene)}")
    with open(path, "w") as f:
        f.write(text)
    return path


def pbrt_run(scene, out, seed, args, tmp, mutations):
    """One pbrt-v4 render under its own hold of the lock; returns its whole-process time,
    measured inside the lock (/usr/bin/time), so that the wait for the lock is not counted."""
    cmd = ["flock", args.lock, "/usr/bin/time", "-f", "wall %e", args.pbrt, "--nthreads", str(args.threads),
           "--seed", str(seed), "--outfile", out, pbrt_scene(scene, tmp, mutations)]
    p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    m = re.search(r"^wall ([0-9.]+)$", p.stderr, flags=re.M)
    if p.returncode != 0 or not m:
        sys.exit(f"failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr[-2000:]}")
    return float(m.group(1))


def pbrt_mutations_for(scene, args, tmp):
    """pbrt-v4's mutations per pixel for a whole process of about T: t = a + b n fitted to two
    probes (each under the lock; a quiet machine assumed, so the wait is small)."""
    out = os.path.join(tmp, "probe.pfm")
    t1 = pbrt_run(scene, out, 90, args, tmp, 16)
    t2 = pbrt_run(scene, out, 91, args, tmp, 64)
    b = max((t2 - t1) / 48, 1e-6)
    a = max(t1 - 16 * b, 0.0)
    return max(1, round((args.time - a) / b))


def channel_scaled(image, reference, tmp):
    """The image with each channel scaled to the reference's channel mean (pbrt-v4 renders
    spectrally through its own sensor: colours differ by 1-3%), written as a PFM."""
    w, h, x = read_pfm(image)
    _, _, r = read_pfm(reference)
    scale = [sum(r[c::3]) / max(sum(x[c::3]), 1e-30) for c in range(3)]
    path = os.path.join(tmp, "scaled.pfm")
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (w, h))
        f.write(struct.pack("<" + "f" * len(x), *(v * scale[i % 3] for i, v in enumerate(x))))
    return path


def main():
    ap = equal_time_parser(__doc__, SCENES, 8.0, "seconds per render (pathspace's --time)")
    ap.add_argument("--ref-time", type=float, default=60.0, help="seconds of the BDPT reference")
    ap.add_argument("--integrators", nargs="+", default=list(INTEGRATORS),
                    help="pathspace integrators; NAME:OPTION=VALUE,... adds --OPTION VALUE (e.g. mmlt:two-stage=0)")
    ap.add_argument("--pbrt", default=PBRT, help="pbrt-v4's binary (skipped with a note when missing)")
    ap.add_argument("--lock", default="/tmp/ps-build.lock")
    ap.add_argument("--cache", default=os.path.join(ROOT, "build", "bench-cache"))
    ap.add_argument("--json", help="write every figure here")
    args = ap.parse_args()
    os.makedirs(args.cache, exist_ok=True)
    have_pbrt = os.path.exists(args.pbrt)
    if not have_pbrt:
        print(f"note: no pbrt-v4 binary at {args.pbrt}: its mlt is skipped", flush=True)
    results = {"time": args.time, "seeds": args.seeds, "ref_time": args.ref_time, "threads": args.threads,
               "pbrt": args.pbrt if have_pbrt else None, "scenes": {}}
    with tempfile.TemporaryDirectory() as tmp:
        for scene in args.scenes:
            scene = os.path.abspath(scene)
            name = os.path.basename(scene)[:-5]
            digest = hashlib.sha1(inlined(scene).encode()).hexdigest()[:10]
            ref = os.path.join(args.cache, f"metroset-{name}-{digest}-bdpt{args.ref_time:g}s.pfm")
            var = ref[:-4] + ".variance.pfm"
            print(f"== {name} ({KINDS.get(name, 'other')})", flush=True)
            if not (os.path.exists(ref) and os.path.exists(var)):
                t, spp = ours(scene, ref, 1000, args, "bdpt", args.ref_time, ["--aov", "variance"])
                print(f"  reference: bdpt {t:.1f} s, {spp:.0f} spp", flush=True)
            ref_mean = pfm_mean_luminance(ref)
            configs = []
            for spec in args.integrators:
                integ, _, opts = spec.partition(":")
                extra = []
                for kv in filter(None, opts.split(",")):
                    k, v = kv.split("=")
                    extra += [f"--{k}", v]
                configs.append((spec, lambda o, s, i=integ, e=extra: ours(scene, o, s, args, i, args.time, e)))
            if have_pbrt:
                n = pbrt_mutations_for(scene, args, tmp)
                print(f"  pbrt-v4 mlt: {n} mutations per pixel for {args.time:g} s", flush=True)
                configs.append(("pbrt-v4 mlt", lambda o, s: (pbrt_run(scene, o, s, args, tmp, n), float(n))))
            runs = {label: [] for label, _ in configs}
            for seed in range(1, args.seeds + 1):
                for label, run in configs:
                    out = os.path.join(tmp, "run.pfm")
                    seconds, spp = run(out, seed)
                    if label.startswith("pbrt"):
                        out = channel_scaled(out, ref, tmp)
                    e = relmse(out, ref, var)
                    runs[label].append({"seed": seed, "seconds": seconds, "spp": spp, "relmse": e,
                                        "mean_over_ref": pfm_mean_luminance(out) / ref_mean})
                    print(f"  {label} seed {seed}: relMSE {e:.4g}, {spp:.0f} spp in {seconds:.1f} s, "
                          f"mean/ref {runs[label][-1]['mean_over_ref']:.4f}", flush=True)
            table = {}
            for label, rs in runs.items():
                e = [r["relmse"] for r in rs]
                means = [r["mean_over_ref"] for r in rs]
                table[label] = {"relmse": statistics.mean(e), "relmse_per_seed": e,
                                "mean_over_ref": means,
                                "mean_spread": statistics.stdev(means) if len(means) > 1 else 0.0,
                                "spp": [r["spp"] for r in rs], "seconds": [r["seconds"] for r in rs]}
            base = table[args.integrators[0]]["relmse"]
            print(f"  {'integrator':24s} {'relMSE':>10s} {'/' + args.integrators[0]:>8s} {'mean spread':>11s} "
                  f"{'per seed':>32s} {'spp':>16s}")
            for label, row in table.items():
                row["over_first"] = row["relmse"] / base
                per = " ".join(f"{x:.3g}" for x in row["relmse_per_seed"])
                spps = " ".join(f"{x:.0f}" for x in row["spp"])
                print(f"  {label:24s} {row['relmse']:10.4g} {row['over_first']:8.3f} {100 * row['mean_spread']:10.2f}% "
                      f"{per:>32s} {spps:>16s}", flush=True)
            goals = {}
            if KINDS.get(name) == "dark-indirect":
                for integ, bound in (("mmlt", 1 / 3), ("mlt", 1 / 5)):
                    if integ in table:
                        goals[integ] = table[integ]["over_first"] <= bound
                print("  goals (mmlt <= 1/3, mlt <= 1/5 of bdpt): " +
                      ", ".join(f"{k} {'met' if v else 'missed'}" for k, v in goals.items()), flush=True)
            results["scenes"][name] = {"kind": KINDS.get(name, "other"), "reference": os.path.basename(ref),
                                       "reference_mean": ref_mean, "table": table, "goals": goals}
            if args.json:  # after every scene, so that an interrupted run keeps what it measured
                with open(args.json, "w") as f:
                    json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
