#!/usr/bin/env python3
"""Writes the grid values of media-uniformgrid.pbrt ("density" and "Lescale", 8x8x8) and
media-rgbgrid.pbrt ("sigma_a" and "sigma_s", 4x4x4 RGB) into those files, in place, in
pbrt-v4's order (x fastest, then y, then z). Run in this folder: python3 make_media_grids.py
"""
import math
import re


def fmt(values, per):
    return "\n      ".join(" ".join(str(v) for v in values[i:i + per]) for i in range(0, len(values), per))


def fmt3(triples, per=5):
    return "\n      ".join("  ".join(" ".join(str(c) for c in t) for t in triples[i:i + per])
                           for i in range(0, len(triples), per))


def uniformgrid(n=8):
    density, lescale = [], []
    for z in range(n):
        for y in range(n):
            for x in range(n):
                u, v, w = (x + 0.5) / n, (y + 0.5) / n, (z + 0.5) / n
                r2 = (u - 0.45) ** 2 + (v - 0.4) ** 2 * 1.5 + (w - 0.55) ** 2
                density.append(round(max(0.0, 1.6 * math.exp(-r2 * 8) * (0.75 + 0.25 * math.sin(9 * u + 5 * w)) - 0.05), 3))
                lescale.append(round(max(0.0, 1 - ((u - 0.6) ** 2 + (v - 0.3) ** 2 + (w - 0.4) ** 2) * 6), 3))
    return {"float density": fmt(density, 16), "float Lescale": fmt(lescale, 16)}


def rgbgrid(m=4):
    sa, ss = [], []
    for z in range(m):
        for y in range(m):
            for x in range(m):
                u, v, w = x / (m - 1), y / (m - 1), z / (m - 1)
                sa.append((round(0.1 + 0.5 * u, 3), round(0.1 + 0.4 * w, 3), round(0.1 + 0.3 * (1 - v), 3)))
                ss.append((round(0.5 + 1.5 * (1 - u) * v, 3), round(0.4 + 1.2 * u * w, 3), round(0.6 + 1.0 * (1 - w), 3)))
    return {"rgb sigma_a": fmt3(sa), "rgb sigma_s": fmt3(ss)}


def write(path, blocks):
    text = open(path).read()
    for name, values in blocks.items():
        text, n = re.subn(r'("%s" \[\n      )[^\]]*( \])' % name, lambda m: m.group(1) + values + m.group(2), text)
        assert n == 1, (path, name)
    open(path, "w").write(text)


write("media-uniformgrid.pbrt", uniformgrid())
write("media-rgbgrid.pbrt", rgbgrid())
