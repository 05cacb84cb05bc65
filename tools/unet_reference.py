#!/usr/bin/python3
"""A reference of Open Image Denoise's U-Net in NumPy, written independently of Glint's C++
inference (src/glint/denoise/unet/) from the same description, to check it against:

    unet_reference.py WEIGHTS.tza COLOR.pfm [ALBEDO.pfm [NORMAL.pfm]] OUT.pfm [--raw]

as tools/unet_denoise.cpp takes them. Also a module: `read_tza`, `unet`, `denoise`.
"""

import struct
import sys

import numpy as np

ALIGN = 16
PU = dict(a=1.41283765e+03, b=1.64593172e+00, c=4.31384981e-01, d=-2.94139609e-03,
          e=1.92653254e-01, f=6.26026094e-03, g=9.98620152e-01, y0=1.57945760e-06,
          y1=3.22087631e-02, x0=2.23151711e-03, x1=3.70974749e-01)


def read_tza(path):
    """{name: float32 array shaped as stored}."""
    data = open(path, "rb").read()
    magic, major, _minor, table = struct.unpack_from("<HBBQ", data, 0)
    assert magic == 0x41D7 and major == 2, "not a version 2 tensor archive"
    (count,) = struct.unpack_from("<I", data, table)
    at = table + 4
    out = {}
    for _ in range(count):
        (length,) = struct.unpack_from("<H", data, at)
        name = data[at + 2:at + 2 + length].decode()
        at += 2 + length
        ndims = data[at]
        dims = struct.unpack_from(f"<{ndims}I", data, at + 1)
        at += 1 + 4 * ndims + ndims
        kind = chr(data[at])
        (offset,) = struct.unpack_from("<Q", data, at + 1)
        at += 9
        dtype = np.float16 if kind == "h" else np.float32
        n = int(np.prod(dims))
        out[name] = np.frombuffer(data, dtype, n, offset).astype(np.float32).reshape(dims)
    return out


def conv_relu(w, b, x):
    """3x3 convolution, zero-padded, with bias and ReLU: x is C x H x W."""
    c, h, wd = x.shape
    padded = np.zeros((c, h + 2, wd + 2), np.float32)
    padded[:, 1:-1, 1:-1] = x
    out = np.broadcast_to(b[:, None, None], (w.shape[0], h, wd)).astype(np.float32).copy()
    for ky in range(3):
        for kx in range(3):
            patch = padded[:, ky:ky + h, kx:kx + wd]
            out += np.tensordot(w[:, :, ky, kx], patch, axes=([1], [0]))
    return np.maximum(out, 0)


def pool(x):
    c, h, w = x.shape
    return x.reshape(c, h // 2, 2, w // 2, 2).max(axis=(2, 4))


def upsample(x):
    return x.repeat(2, axis=1).repeat(2, axis=2)


def unet(t, x):
    """The network of weights `t` on input planes `x` (sides multiples of 16)."""
    def run(names, y):
        for n in names:
            y = conv_relu(t[n + ".weight"], t[n + ".bias"], y)
        return y

    large = "enc_conv1a.weight" in t
    levels = ([[f"enc_conv{n}a", f"enc_conv{n}b"] for n in range(1, 5)] if large else
              [["enc_conv0", "enc_conv1"], ["enc_conv2"], ["enc_conv3"], ["enc_conv4"]])
    pools = []
    y = x
    for names in levels:
        y = pool(run(names, y))
        pools.append(y)
    y = upsample(run(["enc_conv5a", "enc_conv5b"], y))
    for level in (4, 3, 2):
        y = np.concatenate([y, pools[level - 2]])
        y = upsample(run([f"dec_conv{level}a", f"dec_conv{level}b"], y))
    y = np.concatenate([y, x])
    return run(["dec_conv1a", "dec_conv1b", "dec_conv1c" if large else "dec_conv0"], y)


def pu(y):
    p = PU
    return np.where(y <= p["y0"], p["a"] * y,
                    np.where(y <= p["y1"], p["b"] * np.power(np.maximum(y, 1e-30), p["c"]) + p["d"],
                             p["e"] * np.log(y + p["f"]) + p["g"]))


def pu_inverse(x):
    p = PU
    return np.where(x <= p["x0"], x / p["a"],
                    np.where(x <= p["x1"], np.power(np.maximum((x - p["d"]) / p["b"], 0), 1 / p["c"]),
                             np.exp((x - p["g"]) / p["e"]) - p["f"]))


NORM = 1 / pu(np.float64(65504.0))


def exposure(color):
    h, w, _ = color.shape
    lum = (0.212671 * color[..., 0] + 0.715160 * color[..., 1] + 0.072169 * color[..., 2])
    bh, bw = -(-h // 16), -(-w // 16)
    logs = []
    for i in range(bh):
        for j in range(bw):
            block = lum[i * h // bh:(i + 1) * h // bh, j * w // bw:(j + 1) * w // bw]
            m = block.mean()
            if m > 1e-8:
                logs.append(np.log2(m))
    return 0.18 / 2 ** np.mean(logs) if logs else 1.0


def denoise(t, color, albedo=None, normal=None):
    """OIDN's HDR filter on H x W x 3 images."""
    h, w, _ = color.shape
    color = np.clip(np.nan_to_num(color), 0, None)
    scale = exposure(color)
    planes = [pu(color * scale) * NORM]
    if albedo is not None:
        planes.append(np.clip(albedo, 0, 1))
    if normal is not None:
        planes.append(np.clip(normal, -1, 1) * 0.5 + 0.5)
    return run_padded(t, np.concatenate(planes, axis=2), lambda y: pu_inverse(np.maximum(y, 0) / NORM) / scale)


def run_padded(t, image, finish=lambda y: y):
    h, w, c = image.shape
    ph, pw = -(-h // ALIGN) * ALIGN, -(-w // ALIGN) * ALIGN
    x = np.zeros((c, ph, pw), np.float32)
    x[:, :h, :w] = image.transpose(2, 0, 1)
    y = unet(t, x)[:, :h, :w]
    return finish(y).transpose(1, 2, 0)


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), "<f4" if scale < 0 else ">f4")
    return data.reshape(h, w, 3 if kind == b"PF" else 1)[::-1].astype(np.float64)


def write_pfm(path, image):
    h, w, _ = image.shape
    with open(path, "wb") as f:
        f.write(f"PF\n{w} {h}\n-1\n".encode())
        f.write(np.ascontiguousarray(image[::-1], "<f4").tobytes())


def main(argv):
    raw = argv and argv[-1] == "--raw"
    if raw:
        argv = argv[:-1]
    t = read_tza(argv[0])
    images = [read_pfm(p) for p in argv[1:-1]]
    if raw:
        out = run_padded(t, np.concatenate(images, axis=2).astype(np.float32))
    else:
        out = denoise(t, *images)
    write_pfm(argv[-1], out)


if __name__ == "__main__":
    main(sys.argv[1:])
