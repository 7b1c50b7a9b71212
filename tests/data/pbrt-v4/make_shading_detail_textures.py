#!/usr/bin/env python3
# Writes the textures of shading-detail.pbrt (standard library only):
#   textures/waves.pfm      64x64 RGB float, d = 0.5 + 0.5 sin(8 pi s) sin(8 pi t), the bump map
#   textures/normals.png    64x64 8-bit RGB, (n + 1) / 2 of n = normalize(0.4 sin(6 pi s), 0.3 cos(4 pi t), 1)
# s, t are texel centres with t = 0 at the bottom row, as the renderers look textures up.
import math, os, struct, zlib

N = 64
here = os.path.dirname(os.path.abspath(__file__))
os.makedirs(os.path.join(here, "textures"), exist_ok=True)

def centre(i):
    return (i + 0.5) / N

# PFM stores rows bottom to top.
with open(os.path.join(here, "textures", "waves.pfm"), "wb") as f:
    f.write(b"PF\n%d %d\n-1.0\n" % (N, N))
    for row in range(N):
        t = centre(row)
        for col in range(N):
            s = centre(col)
            d = 0.5 + 0.5 * math.sin(8 * math.pi * s) * math.sin(8 * math.pi * t)
            f.write(struct.pack("<3f", d, d, d))

# PNG stores rows top to bottom.
raw = bytearray()
for row in range(N):
    t = centre(N - 1 - row)
    raw.append(0)
    for col in range(N):
        s = centre(col)
        n = (0.4 * math.sin(6 * math.pi * s), 0.3 * math.cos(4 * math.pi * t), 1.0)
        l = math.sqrt(sum(c * c for c in n))
        raw.extend(round(255 * (c / l + 1) / 2) for c in n)

def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

with open(os.path.join(here, "textures", "normals.png"), "wb") as f:
    f.write(b"\x89PNG\r\n\x1a\n")
    f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", N, N, 8, 2, 0, 0, 0)))
    f.write(chunk(b"IDAT", zlib.compress(bytes(raw), 9)))
    f.write(chunk(b"IEND", b""))
