#!/usr/bin/env python3
"""The noise of a pbrt-v4 reference image's 16x16-pixel block means, measured.

pbrt-v4 renders the reference's scene RUNS more times at SPP samples per pixel with other seeds
(2, 3, ...); each block's mean varies between those renders, and its variance scaled from SPP
to the reference's REF_SPP samples (variance proportional to 1/spp: exact for independent
samples, an upper bound for pbrt-v4's stratified and low-discrepancy ones) is the variance of
the reference's block mean. Written as a PFM with one pixel per block: R, G, B standard errors.

    python3 make_reference_noise.py PBRT IMGTOOL SCENE REF_SPP SPP RUNS OUT.pfm
"""
import array
import math
import os
import subprocess
import sys
import tempfile

BLOCK = 16


def read_pfm(path):
    with open(path, "rb") as f:
        if f.readline().strip() != b"PF":
            raise SystemExit(path + ": not an RGB PFM")
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = array.array("f")
        data.frombytes(f.read(width * height * 3 * 4))
    if (scale < 0) != (sys.byteorder == "little"):
        data.byteswap()
    return width, height, data  # rows bottom to top


def write_pfm(path, width, height, data):
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n%s\n" % (width, height, b"-1" if sys.byteorder == "little" else b"1"))
        f.write(array.array("f", data).tobytes())


def block_means(width, height, data):
    bw, bh = width // BLOCK, height // BLOCK
    means = [0.0] * (bw * bh * 3)
    for row in range(bh * BLOCK):
        y = height - 1 - row  # image row from the top
        by = y // BLOCK
        if by >= bh:
            continue
        for x in range(bw * BLOCK):
            i = (row * width + x) * 3
            b = (by * bw + x // BLOCK) * 3
            for c in range(3):
                means[b + c] += data[i + c] / (BLOCK * BLOCK)
    return bw, bh, means


def main():
    pbrt, imgtool, scene, ref_spp, spp, runs, out = sys.argv[1:8]
    ref_spp, spp, runs = int(ref_spp), int(spp), int(runs)
    renders = []
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(runs):
            exr, pfm = os.path.join(tmp, "r.exr"), os.path.join(tmp, "r.pfm")
            subprocess.run([pbrt, "--nthreads", "2", "--quiet", "--spp", str(spp), "--seed", str(2 + k),
                            "--outfile", exr, scene], check=True)
            subprocess.run([imgtool, "convert", "--outfile", pfm, exr], check=True)
            bw, bh, means = block_means(*read_pfm(pfm))
            renders.append(means)
            print("render %d of %d done" % (k + 1, runs), flush=True)
    sigma = []
    for i in range(len(renders[0])):
        m = sum(r[i] for r in renders) / runs
        var = sum((r[i] - m) ** 2 for r in renders) / (runs - 1)
        sigma.append(math.sqrt(var * spp / ref_spp))
    # PFM rows go bottom to top: block row bh - 1 first.
    rows = [sigma[(by * bw) * 3:(by * bw + bw) * 3] for by in range(bh)]
    write_pfm(out, bw, bh, [v for row in reversed(rows) for v in row])


if __name__ == "__main__":
    main()
