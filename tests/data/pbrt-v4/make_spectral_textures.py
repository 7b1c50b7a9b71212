#!/usr/bin/env python3
# Writes the coloured slide of spectral-lights.pbrt (standard library only), PFM float RGB:
#   textures/slide-colour.pfm  8x6 projected slide: a checker whose light squares run from
#                              red (left) to blue (right) and whose dark squares are green,
#                              so a flip in either axis or a swapped channel shows
# s, t are texel centres with t = 0 at the bottom row, as the renderers look textures up.
import os, struct

here = os.path.dirname(os.path.abspath(__file__))
os.makedirs(os.path.join(here, "textures"), exist_ok=True)

w, h = 8, 6
with open(os.path.join(here, "textures", "slide-colour.pfm"), "wb") as f:
    f.write(b"PF\n%d %d\n-1.0\n" % (w, h))
    for row in range(h):  # PFM stores rows bottom to top
        t = (row + 0.5) / h
        for col in range(w):
            s = (col + 0.5) / w
            if (col + row) % 2 == 0:
                rgb = (1.0 - 0.8 * s, 0.2 + 0.3 * t, 0.2 + 0.8 * s)
            else:
                rgb = (0.05, 0.5, 0.1)
            f.write(struct.pack("<3f", *rgb))
