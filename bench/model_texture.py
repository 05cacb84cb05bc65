#!/usr/bin/env python3
"""Writes the texture of bench/model_mode.sh's 15k-triangle model: a 512 x 512 PNG (8-bit RGB,
standard library only) of hue bands along u broken by off-white squares, so that the texture's
colours, their orientation and the texel size show on the knot.

Usage: bench/model_texture.py OUT.png
"""
import math
import struct
import sys
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


def pixel(x, y):
    u, v = x / 512, y / 512
    if (int(u * 16) + int(v * 4)) % 2 == 0:
        return (235, 235, 225)
    return tuple(int(127 + 127 * math.cos(2 * math.pi * (u - k / 3))) for k in range(3))


png(sys.argv[1], 512, 512, pixel)
