#!/usr/bin/env python3
"""Writes the test textures of this directory (PNG, 8-bit RGB) with the standard library only.

Run from this directory; the images are committed, this script only documents how they were made.
"""
import struct
import zlib


def png(path, width, height, pixel):
    """pixel(x, y) -> (r, g, b) bytes; row 0 is the top of the image."""
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    rows = b"".join(
        b"\x00" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(rows, 9)))
        f.write(chunk(b"IEND", b""))


# quadrants.png: 2 x 2 texels, red and green on top, blue and white below.
QUADRANTS = [[(255, 0, 0), (0, 255, 0)], [(0, 0, 255), (255, 255, 255)]]
png("quadrants.png", 2, 2, lambda x, y: QUADRANTS[y][x])

# grid.png: 16 x 16, a checker of 4 x 4 texel squares in orange and dark blue, with a white
# 1-texel border: shows filtering, orientation (the top-left square is orange) and wrapping.
def grid(x, y):
    if x in (0, 15) or y in (0, 15):
        return (255, 255, 255)
    return (240, 140, 20) if ((x // 4) + (y // 4)) % 2 == 0 else (20, 40, 120)


png("grid.png", 16, 16, grid)
