#!/usr/bin/env python3
"""Writes the brick image of scenes/pbrt/textured.pbrt: 64x64 8-bit sRGB PNG,
four courses of bricks (each its own shade of red) in light mortar, with a
darker top-left brick so that the image's orientation shows in renders.
Power-of-two sides, so that pbrt-v4's MIP pyramid keeps it unresampled.

usage: scripts/make_texture_png.py [OUTPUT=scenes/pbrt/textured-bricks.png]
"""
import struct
import sys
import zlib

SIZE = 64
COURSE, BRICK, MORTAR = 16, 32, 2


def brick_colour(x, y):
    course = y // COURSE
    shift = (course % 2) * BRICK // 2
    column = ((x + shift) % SIZE) // BRICK
    if y % COURSE < MORTAR or (x + shift) % BRICK < MORTAR:
        return (200, 196, 188)
    if course == 0 and column == 0 and shift == 0:
        return (60, 40, 40)
    tone = (course * 37 + column * 53) % 40
    return (150 + tone, 60 + tone // 2, 45 + tone // 3)


def png(width, height, pixel):
    rows = b"".join(
        b"\x00" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height)
    )

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) +
            chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/pbrt/textured-bricks.png"
    with open(out, "wb") as f:
        f.write(png(SIZE, SIZE, brick_colour))


if __name__ == "__main__":
    main()
