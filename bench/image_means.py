#!/usr/bin/env python3
"""Image means and Metropolis b across seeds: renders SCENE once per seed in [FIRST, LAST) with
the given pathspace options, and prints the mean luminance of each image and, for Metropolis
renders, b and its claimed relative error (--stats); then their means, standard errors, and
how b's spread across seeds compares with the error its bootstrap claims.

  bench/image_means.py SCENE FIRST LAST [pathspace render options...]
"""
import json
import math
import os
import struct
import subprocess
import sys
import tempfile

PATHSPACE = os.environ.get("PATHSPACE", os.path.join(os.path.dirname(__file__), "..", "build", "pathspace"))


def read_pfm(path):
    """(width, height, values): an RGB PFM's floats, 3 per pixel, in the file's row order."""
    with open(path, "rb") as f:
        kind, size, scale, body = f.read().split(b"\n", 3)
    w, h = map(int, size.split())
    return w, h, struct.unpack(("<" if float(scale) < 0 else ">") + "f" * (3 * w * h), body[: 12 * w * h])


def pfm_mean_luminance(path):
    w, h, values = read_pfm(path)
    return sum(0.2126 * values[i] + 0.7152 * values[i + 1] + 0.0722 * values[i + 2]
               for i in range(0, len(values), 3)) / (w * h)


def mean_and_error(xs):
    m = sum(xs) / len(xs)
    sd = math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1))
    return m, sd / math.sqrt(len(xs)), sd


def main():
    scene, first, last, options = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
    means, bs, claimed = [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        image, stats = os.path.join(tmp, "image.pfm"), os.path.join(tmp, "stats.json")
        for seed in range(first, last):
            subprocess.run([PATHSPACE, "render", scene, "--seed", str(seed), "--quiet", "-o", image, "--stats", stats]
                           + options, check=True, stdout=subprocess.DEVNULL)
            means.append(pfm_mean_luminance(image))
            metropolis = json.load(open(stats)).get("metropolis")
            line = f"seed {seed}: image mean {means[-1]:.6f}"
            if metropolis:
                bs.append(metropolis["b"])
                claimed.append(metropolis["b_relative_error"])
                line += f", b {bs[-1]:.6f} (relative error {claimed[-1]:.5f})"
            print(line, flush=True)
    m, se, sd = mean_and_error(means)
    print(f"image mean {m:.6f} +- {se:.6f} (sd {sd:.6f}, {len(means)} seeds)")
    if bs:
        m, se, sd = mean_and_error(bs)
        c = sum(claimed) / len(claimed)
        print(f"b {m:.6f} +- {se:.6f}; relative spread across seeds {sd / m:.5f}, claimed {c:.5f} (ratio {sd / m / c:.2f})")


if __name__ == "__main__":
    main()
