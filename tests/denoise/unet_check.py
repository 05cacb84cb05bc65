#!/usr/bin/python3
"""Glint's U-Net inference against the NumPy reference (tools/unet_reference.py), both Glint's
own, on the same weights and images: outputs equal to float rounding. CTest runs it as
denoise.unet_matches_numpy:

    unet_check.py GLINT_UNET_DENOISE_BINARY [WEIGHTS.tza ...] [--kernels NAME,...|all]

Random weights of each of OIDN's three shapes (its base, small-level names and large one, with
few channels, so that it runs in seconds) on a random image of a size no multiple of 16 (the
padding), colour of a wide range with albedo and normal; and any real weights named, on a small
image. Both the network's raw output and the whole filter (exposure, transfer function) are
compared, for each set of kernels named (default: the best this machine runs; all: every one it
runs)."""

import itertools
import os
import struct
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tools"))
import unet_reference as ref  # noqa: E402


def write_tza(path, tensors):
    """A version 2 archive of float16 tensors, as OIDN's weights are stored."""
    header = 16
    blobs, table = b"", b""
    offset = header
    for name, array in tensors.items():
        data = array.astype("<f2").tobytes()
        pad = (-offset) % 64
        blobs += b"\0" * pad
        offset += pad
        layout = "oihw" if array.ndim == 4 else "x"
        table += struct.pack("<H", len(name)) + name.encode() + bytes([array.ndim])
        table += struct.pack(f"<{array.ndim}I", *array.shape) + layout.encode() + b"h"
        table += struct.pack("<Q", offset)
        blobs += data
        offset += len(data)
    table_offset = header + len(blobs)
    with open(path, "wb") as f:
        f.write(struct.pack("<HBBQ", 0x41D7, 2, 0, table_offset) + b"\0\0\0\0")
        f.write(blobs + struct.pack("<I", len(tensors)) + table)


def random_weights(rng, shape, inputs=9):
    """The layers of a U-Net of `shape` (base, small or large) with a few channels each."""
    t = {}
    def conv(name, i, o):
        t[name + ".weight"] = rng.normal(0, (2 / (9 * i)) ** 0.5, (o, i, 3, 3)).astype(np.float32)
        t[name + ".bias"] = rng.normal(0, 0.05, o).astype(np.float32)
        return o
    c = inputs
    pools = []
    names = ([[f"enc_conv{n}a", f"enc_conv{n}b"] for n in range(1, 5)] if shape == "large" else
             [["enc_conv0", "enc_conv1"], ["enc_conv2"], ["enc_conv3"], ["enc_conv4"]])
    width = {"base": [8, 12, 12, 16], "small": [8, 8, 8, 8], "large": [8, 12, 16, 16]}[shape]
    for level, layer_names in enumerate(names):
        for n in layer_names:
            c = conv(n, c, width[level])
        pools.append(c)
    c = conv("enc_conv5b", conv("enc_conv5a", c, 16), 16)
    for level in (4, 3, 2):
        c = conv(f"dec_conv{level}a", c + pools[level - 2], 12)
        c = conv(f"dec_conv{level}b", c, 12)
    c = conv("dec_conv1a", c + inputs, 8)
    c = conv("dec_conv1b", c, 8)
    conv("dec_conv1c" if shape == "large" else "dec_conv0", c, 3)
    return t


def worst(a, b, floor):
    """The largest difference relative to the larger value (at least `floor`)."""
    return float(np.max(np.abs(a - b) / np.maximum(np.maximum(np.abs(a), np.abs(b)), floor)))


def worst_of_scale(a, b):
    """The largest difference relative to the image's largest value. The raw planes come
    straight from ReLUs, where values near zero carry the rounding of sums of thousands of
    terms taken in another order, so a per-pixel ratio there measures nothing."""
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-30))


def main():
    binary = sys.argv[1]
    args = sys.argv[2:]
    kernels = [None]
    if "--kernels" in args:
        at = args.index("--kernels")
        kernels = args[at + 1].split(",")
        del args[at:at + 2]
        if kernels == ["all"]:
            kernels = subprocess.run([binary, "--list-kernels"], check=True, capture_output=True,
                                     text=True).stdout.split()
    rng = np.random.default_rng(2026)
    failures = 0
    with tempfile.TemporaryDirectory() as d:
        h, w = 37, 53
        color = np.exp(rng.normal(-1, 2, (h, w, 3)))  # radiance over many stops
        albedo = rng.uniform(0, 1, (h, w, 3))
        normal = rng.normal(0, 1, (h, w, 3))
        normal /= np.linalg.norm(normal, axis=2, keepdims=True)
        files = []
        for name, image in (("color", color), ("albedo", albedo), ("normal", normal)):
            ref.write_pfm(os.path.join(d, name + ".pfm"), image)
            files.append(os.path.join(d, name + ".pfm"))
        cases = []
        for shape in ("base", "small", "large"):
            path = os.path.join(d, shape + ".tza")
            write_tza(path, random_weights(rng, shape))
            cases.append((shape, path))
        cases += [(os.path.basename(p), p) for p in args]
        for (name, weights), kernel, mode in itertools.product(cases, kernels, ("raw", "filter")):
            t = ref.read_tza(weights)
            out = os.path.join(d, f"{name}-{mode}.pfm")
            command = [binary, weights, *files, out] + (["--raw"] if mode == "raw" else [])
            command += ["--kernels", kernel] if kernel else []
            subprocess.run(command, check=True)
            glint = ref.read_pfm(out)
            images = [ref.read_pfm(f) for f in files]
            if mode == "raw":
                expected = ref.run_padded(t, np.concatenate(images, 2).astype(np.float32))
            else:
                expected = ref.denoise(t, *images)
            error = (worst_of_scale(glint, expected) if mode == "raw" else
                     worst(glint, expected, 1e-3))
            ok = error < 2e-3
            failures += not ok
            print(f"{name:24s} {kernel or 'best':10s} {mode:7s} largest difference {error:.2e} "
                  f"{'ok' if ok else 'TOO LARGE'}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
