#!/usr/bin/env python3
# Writes the grey images of lights.pbrt (standard library only), PFM float RGB, r = g = b:
#   textures/gonio.pfm   32x32 equal-area goniometric map, 0.1 + 1.9 s (1 - t)^2 + 0.3 sin(6 pi t)^2
#   textures/slide.pfm   8x8 projected slide: a checker of 1 and 0.15 whose light squares fade
#                        from left (1) to right (0.4), so a flip in either axis shows
#   textures/panel.pfm   16x16 emission image of the area light, 0.2 + 1.6 s + 0.6 t^2
# s, t are texel centres with t = 0 at the bottom row, as the renderers look textures up.
import math, os, struct

here = os.path.dirname(os.path.abspath(__file__))
os.makedirs(os.path.join(here, "textures"), exist_ok=True)

def write_pfm(name, n, value):
    # PFM stores rows bottom to top.
    with open(os.path.join(here, "textures", name), "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (n, n))
        for row in range(n):
            t = (row + 0.5) / n
            for col in range(n):
                v = value((col + 0.5) / n, t, col, row)
                f.write(struct.pack("<3f", v, v, v))

write_pfm("gonio.pfm", 32, lambda s, t, c, r: 0.1 + 1.9 * s * (1 - t) ** 2 + 0.3 * math.sin(6 * math.pi * t) ** 2)
write_pfm("slide.pfm", 8, lambda s, t, c, r: (1 - 0.6 * c / 7) if (c + r) % 2 == 0 else 0.15)
write_pfm("panel.pfm", 16, lambda s, t, c, r: 0.2 + 1.6 * s + 0.6 * t * t)
