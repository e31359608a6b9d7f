#!/usr/bin/env python3
"""Writes the two maps of scenes/pbrt/bump-normal.pbrt, 64x64 8-bit PNGs
read with the linear encoding:

  bump-normal-heights.png  heights for "displacement": ripples
                           0.5 + 0.5 sin(2 pi 2 x/64) sin(2 pi 2 y/64), grey
  bump-normal-dimples.png  a tangent-space normal map, c = (n + 1)/2: a 4x4
                           grid of spherical domes (radius 7 texels, flat
                           between them), the normal tilting towards +x on
                           each dome's right

usage: scripts/make_bump_maps.py [OUTDIR=scenes/pbrt]
"""
import math
import os
import sys

from make_texture_png import png  # the same 8-bit RGB PNG writer

SIZE = 64
CELL, RADIUS = 16, 7.0


def code(v):
    return max(0, min(255, int(round(v * 255))))


def height(x, y):
    s, t = (x + 0.5) / SIZE, (y + 0.5) / SIZE
    h = 0.5 + 0.5 * math.sin(2 * math.pi * 2 * s) * math.sin(2 * math.pi * 2 * t)
    return (code(h),) * 3


def dimple_normal(x, y):
    # Texel centre relative to its cell's centre; image rows run down, the
    # map's +y (towards +v) runs up.
    dx = (x % CELL) + 0.5 - CELL / 2
    dy = -((y % CELL) + 0.5 - CELL / 2)
    r2 = dx * dx + dy * dy
    if r2 >= RADIUS * RADIUS:
        n = (0.0, 0.0, 1.0)
    else:
        n = (dx / RADIUS, dy / RADIUS, math.sqrt(1 - r2 / (RADIUS * RADIUS)))
    return tuple(code((c + 1) / 2) for c in n)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/pbrt"
    with open(os.path.join(out, "bump-normal-heights.png"), "wb") as f:
        f.write(png(SIZE, SIZE, height))
    with open(os.path.join(out, "bump-normal-dimples.png"), "wb") as f:
        f.write(png(SIZE, SIZE, dimple_normal))


if __name__ == "__main__":
    main()
