#!/usr/bin/env python3
"""Puts 8-bit binary PPM images (P6, maxval 255, as `imgdiff --preview X.ppm` and
`imgdiff --ssim --diff X.ppm` write them) side by side, left to right, into one PNG, with a
gap of GAP white pixels between them. Python's standard library only.

    side_by_side.py OUT.png A.ppm B.ppm [C.ppm ...] [--gap 4] [--half]

--half averages each image's 2 x 2 blocks first (for the docs, where a noisy render's PNG
would be too large).
"""

import argparse
import struct
import sys
import zlib


def read_ppm(path):
    with open(path, "rb") as f:
        data = f.read()
    fields, pos = [], 0
    while len(fields) < 4:  # magic, width, height, maxval; '#' comments allowed between
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos) + 1
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    pos += 1  # the single whitespace before the pixels
    if fields[0] != b"P6" or int(fields[3]) != 255:
        sys.exit(f"side_by_side.py: error: {path}: not an 8-bit binary PPM (P6, maxval 255)")
    w, h = int(fields[1]), int(fields[2])
    pixels = data[pos:pos + 3 * w * h]
    if len(pixels) != 3 * w * h:
        sys.exit(f"side_by_side.py: error: {path}: truncated")
    return w, h, pixels


def write_png(path, w, h, rows):
    raw = b"".join(b"\x00" + r for r in rows)

    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body +
                struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def halved(w, h, data):
    """The image at half its width and height, each pixel the mean of a 2 x 2 block."""
    hw, hh = w // 2, h // 2
    out = bytearray(3 * hw * hh)
    for y in range(hh):
        r0, r1 = 3 * w * 2 * y, 3 * w * (2 * y + 1)
        for x in range(hw):
            for c in range(3):
                i = 6 * x + c
                out[3 * (y * hw + x) + c] = (data[r0 + i] + data[r0 + i + 3] + data[r1 + i] +
                                             data[r1 + i + 3] + 2) // 4
    return hw, hh, bytes(out)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("out")
    p.add_argument("images", nargs="+")
    p.add_argument("--gap", type=int, default=4)
    p.add_argument("--half", action="store_true", help="average 2 x 2 blocks first")
    a = p.parse_args()
    imgs = [read_ppm(x) for x in a.images]
    if a.half:
        imgs = [halved(*i) for i in imgs]
    h = imgs[0][1]
    if any(i[1] != h for i in imgs):
        sys.exit("side_by_side.py: error: the images differ in height")
    w = sum(i[0] for i in imgs) + a.gap * (len(imgs) - 1)
    gap = b"\xff" * (3 * a.gap)
    rows = [gap.join(i[2][3 * i[0] * y:3 * i[0] * (y + 1)] for i in imgs) for y in range(h)]
    write_png(a.out, w, h, rows)


if __name__ == "__main__":
    main()
