#!/usr/bin/env python3
"""compare.py A.npy B.npy [BLOCK]: A against the reference B (linear RGB arrays of one size, as
render.py saves them): the ratio of the image means (luminance), the largest relative
difference of BLOCK x BLOCK block means among blocks brighter than 5% of the image mean, and
relMSE (squared error over the reference's squared value plus 0.01, averaged). NumPy
(/usr/bin/python3)."""
import sys

import numpy as np

LUM = np.array([0.2126, 0.7152, 0.0722])


def blocks(img, n):
    h, w = (img.shape[0] // n) * n, (img.shape[1] // n) * n
    return img[:h, :w].reshape(h // n, n, w // n, n).mean(axis=(1, 3))


a, b = (np.load(p).astype(np.float64) for p in sys.argv[1:3])
n = int(sys.argv[3]) if len(sys.argv) > 3 else 16
la, lb = a @ LUM, b @ LUM
ba, bb = blocks(la, n), blocks(lb, n)
lit = bb > 0.05 * lb.mean()
block = np.abs(ba[lit] / bb[lit] - 1).max() if lit.any() else 0.0
rel = ((a - b) ** 2 / (b ** 2 + 1e-2)).mean()
print(f"mean_ratio {la.mean() / lb.mean():.4f} block_max {block:.4f} relmse {rel:.6f}")
