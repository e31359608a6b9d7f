#!/usr/bin/env python3
"""Writes the environment map of scenes/pbrt/envmap-sun.pbrt: a sky gradient
over a dark ground with a small bright sun (2 degrees across, about 3000 times
the sky's radiance), as a 256x256 PFM in pbrt-v4's equal-area octahedral
layout (Clarberg 2008; +z up in the light's frame).

usage: scripts/make_sky_sun.py [OUTPUT=scenes/pbrt/sky-sun.pfm]
"""
import math
import sys

import numpy as np

SIZE = 256
SUN_ELEVATION, SUN_AZIMUTH = math.radians(35), math.radians(40)
SUN_RADIUS = math.radians(1.0)
SUN_RADIANCE = np.array([3000.0, 2800.0, 2400.0])


def square_to_sphere(u, v):
    """pbrt-v4's EqualAreaSquareToSphere on arrays of points of [0,1]^2."""
    u, v = 2 * u - 1, 2 * v - 1
    au, av = np.abs(u), np.abs(v)
    signed = 1 - (au + av)
    r = 1 - np.abs(signed)
    phi = np.where(r == 0, 1.0, (av - au) / np.where(r == 0, 1, r) + 1) * math.pi / 4
    z = np.copysign(1 - r * r, signed)
    s = r * np.sqrt(np.maximum(0, 2 - r * r))
    return np.copysign(np.cos(phi), u) * s, np.copysign(np.sin(phi), v) * s, z


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/pbrt/sky-sun.pfm"
    centres = (np.arange(SIZE) + 0.5) / SIZE
    u, v = np.meshgrid(centres, centres)  # row y = v, top row first
    x, y, z = square_to_sphere(u, v)
    zenith, horizon = np.array([0.15, 0.3, 0.8]), np.array([0.7, 0.8, 1.0])
    t = np.clip(z, 0, 1)[..., None]
    sky = horizon * (1 - t) ** 3 + zenith * (1 - (1 - t) ** 3)
    ground = np.array([0.12, 0.1, 0.08])
    img = np.where((z > 0)[..., None], sky, ground)
    sun = np.array([math.cos(SUN_ELEVATION) * math.cos(SUN_AZIMUTH),
                    math.cos(SUN_ELEVATION) * math.sin(SUN_AZIMUTH), math.sin(SUN_ELEVATION)])
    cos_to_sun = x * sun[0] + y * sun[1] + z * sun[2]
    img[cos_to_sun > math.cos(SUN_RADIUS)] = SUN_RADIANCE
    with open(out, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (SIZE, SIZE))
        # PFM rows run bottom to top.
        f.write(np.ascontiguousarray(img[::-1], dtype="<f4").tobytes())
    print(f"{out}: {SIZE}x{SIZE}, sun texels: {int((cos_to_sun > math.cos(SUN_RADIUS)).sum())}")


if __name__ == "__main__":
    main()
