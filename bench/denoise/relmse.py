#!/usr/bin/env python3
"""relMSE of a PFM image against a reference PFM: the mean over pixels and channels of
(x - ref)^2 / (ref^2 + 0.01), as bench/denoise_eval computes it. Plain Python (no NumPy).
Usage: relmse.py IMAGE.pfm REFERENCE.pfm"""
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
    total = sum((x - r) ** 2 / (r * r + 0.01) for x, r in zip(image, ref))
    print(f'{total / len(image):.5f}')


if __name__ == '__main__':
    main()
