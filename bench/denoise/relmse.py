#!/usr/bin/env python3
"""Errors of a PFM image against a reference PFM, per channel over all pixels:
  relMSE       mean of (x - ref)^2 / (ref^2 + 0.01), as bench/denoise_eval computes it;
  relMSE-trim  the same without the 0.1% of pixels of largest error (so that a handful of
               fireflies cannot decide it), and how many pixels are off by more than 4x
               (|x - ref| > 4 (ref + 0.01) in some channel: the fireflies, counted apart);
  MARE         mean absolute relative error, |x - ref| / (ref + 0.01).
Plain Python (no NumPy).
Usage: relmse.py IMAGE.pfm REFERENCE.pfm [--all]   (without --all: relMSE alone)"""
import array
import sys


def read_pfm(path):
    with open(path, 'rb') as f:
        data = f.read()
    kind, size, scale, pixels = data.split(b'\n', 3)
    if kind != b'PF':
        sys.exit(f'{path}: not a colour PFM')
    width, height = map(int, size.split())
    values = array.array('f')
    values.frombytes(pixels[:width * height * 12])
    if float(scale) > 0:  # big-endian
        values.byteswap()
    return width, height, values


def main():
    w, h, image = read_pfm(sys.argv[1])
    rw, rh, ref = read_pfm(sys.argv[2])
    if (w, h) != (rw, rh):
        sys.exit('the images differ in size')
    n = w * h
    per_pixel, absolute, fireflies = [], 0.0, 0
    for i in range(n):
        e, off = 0.0, False
        for c in range(3):
            x, r = image[3 * i + c], ref[3 * i + c]
            e += (x - r) ** 2 / (r * r + 0.01)
            absolute += abs(x - r) / (r + 0.01)
            off = off or abs(x - r) > 4 * (r + 0.01)
        per_pixel.append(e)
        fireflies += off
    relmse = sum(per_pixel) / (3 * n)
    if '--all' not in sys.argv[3:]:
        print(f'{relmse:.5f}')
        return
    per_pixel.sort()
    kept = per_pixel[:n - n // 1000]
    trimmed = sum(kept) / (3 * len(kept))
    print(f'relMSE {relmse:.6f} relMSE-trim {trimmed:.6f} MARE {absolute / (3 * n):.6f} '
          f'fireflies {fireflies}')


if __name__ == '__main__':
    main()
