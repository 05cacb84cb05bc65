"""Silhouettes of Glint's and Cycles' renders of the same animated frames, compared by
intersection over union (issue 24; bench/cycles/animation/README.md). Blender's Python (it has
NumPy; the system python3 has not):

    blender -b --factory-startup --python bench/cycles/animation/silhouettes.py -- \
        --out OUT --png sheet.png [--draw MODEL:LABEL,...] MODEL:LABEL ...

For each MODEL:LABEL (LABEL a frame number, or a variant such as `40nlerp`) it reads, in OUT:
  cycles_MODEL_LABEL.exr     Cycles' RGBA render (anim_cycles.py): its silhouette is alpha > 0.5
                             (alpha is the pixel's covered fraction: a box filter 1 pixel wide)
  mask_MODEL_LABEL.exr       Glint at K times the size, 1 sample per pixel through its centre,
                             with `--aov depth`: depth.Z > 0 where the ray met the model. Each
                             K x K block's share of hits is the pixel's covered fraction; the
                             silhouette is that > 0.5, as Cycles'
  glint_MODEL_LABEL.exr      Glint's render (only for the picture)
and prints IoU (|A and B| / |A or B|) of Glint against Cycles for each, how many of the pixels
that disagree lie on an edge (within one pixel of either silhouette's boundary), and the
covered areas without a threshold: the sums of Glint's covered fractions and of Cycles'
alpha. Then, between each two frames of a model (numeric labels), the same IoU (Glint against
Glint, Cycles against Cycles, Glint at one frame against Cycles at the other): what a different
pose scores.

--png writes a picture: a row per model, a tile per view (those --draw names), each tile
Glint's render, Cycles' render (both over black, sRGB, clamped) and the silhouettes overlaid
(white both, orange Glint only, blue Cycles only), cropped to the model's silhouettes.

OpenEXR is read by a small reader of its own (single-part scanline files, NONE, ZIPS or ZIP
compression, HALF or FLOAT channels): Blender's Python cannot read the pixels of a multilayer
file such as Glint's with its depth layer. The reader is checked against Blender's own loader
on every Cycles file.
"""

import argparse
import os
import struct
import sys
import zlib

import numpy as np


def fail(message):
    print(f"silhouettes.py: error: {message}", file=sys.stderr, flush=True)
    os._exit(1)


def read_exr(path):
    """{channel name: float32 array (height, width)}, top row first."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"\x76\x2f\x31\x01":
        fail(f"{path}: not an OpenEXR file")
    flags = struct.unpack_from("<I", data, 4)[0] >> 8
    if flags & (0x2 | 0x8 | 0x10):
        fail(f"{path}: tiled, deep or multi-part OpenEXR is not read here")
    pos, header = 8, {}
    while data[pos] != 0:
        end = data.index(b"\0", pos)
        name = data[pos:end].decode()
        tend = data.index(b"\0", end + 1)
        kind = data[end + 1:tend].decode()
        size = struct.unpack_from("<i", data, tend + 1)[0]
        header[name] = (kind, data[tend + 5:tend + 5 + size])
        pos = tend + 5 + size
    pos += 1
    channels, raw, p = [], header["channels"][1], 0
    while raw[p] != 0:
        end = raw.index(b"\0", p)
        # name, int pixel type, uchar pLinear, 3 reserved bytes, int x and y sampling
        pixel_type = struct.unpack_from("<i", raw, end + 1)[0]
        xs, ys = struct.unpack_from("<ii", raw, end + 9)
        if (xs, ys) != (1, 1) or pixel_type not in (1, 2):
            fail(f"{path}: channel sampling or type not read here")
        channels.append((raw[p:end].decode(), pixel_type))
        p = end + 17
    compression = header["compression"][1][0]
    lines = {0: 1, 2: 1, 3: 16}.get(compression)
    if lines is None:
        fail(f"{path}: compression {compression} is not read here (NONE, ZIPS, ZIP are)")
    x0, y0, x1, y1 = struct.unpack("<iiii", header["dataWindow"][1])
    w, h = x1 - x0 + 1, y1 - y0 + 1
    chunks = (h + lines - 1) // lines
    offsets = struct.unpack_from(f"<{chunks}Q", data, pos)
    out = {name: np.zeros((h, w), np.float32) for name, _ in channels}
    bytes_per_line = sum(w * (2 if t == 1 else 4) for _, t in channels)
    for offset in offsets:
        y, size = struct.unpack_from("<ii", data, offset)
        block = data[offset + 8:offset + 8 + size]
        n = min(lines, y1 + 1 - y)
        if size < n * bytes_per_line:  # stored compressed
            t = np.frombuffer(zlib.decompress(block), np.uint8).astype(np.int64)
            t[1:] -= 128
            t = (np.cumsum(t) & 0xFF).astype(np.uint8)  # undo the predictor
            half = (len(t) + 1) // 2
            u = np.empty_like(t)
            u[0::2], u[1::2] = t[:half], t[half:]  # undo the interleaving
            block = u.tobytes()
        at = 0
        for row in range(n):
            for name, t in channels:
                kind, step = (np.float16, 2) if t == 1 else (np.float32, 4)
                out[name][y - y0 + row] = np.frombuffer(block, kind, w, at)
                at += w * step
    return out


def blender_pixels(path):
    """RGBA (height, width, 4), top row first, through Blender's own loader."""
    import bpy
    image = bpy.data.images.load(path)
    w, h = image.size
    a = np.empty(w * h * 4, np.float32)
    image.pixels.foreach_get(a)
    bpy.data.images.remove(image)
    return a.reshape(h, w, 4)[::-1]


def iou(a, b):
    union = np.logical_or(a, b).sum()
    return float(np.logical_and(a, b).sum() / union) if union else 1.0


def edge(mask):
    """Pixels within one pixel (8-neighbourhood) of the mask's boundary, on either side."""
    p = np.pad(mask, 1, mode="edge")
    h, w = mask.shape
    near = np.zeros_like(mask)
    for dy in (0, 1, 2):
        for dx in (0, 1, 2):
            near |= p[dy:dy + h, dx:dx + w] != mask
    return near


def srgb8(linear):
    c = np.clip(linear, 0.0, 1.0)
    c = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)
    return (c * 255 + 0.5).astype(np.uint8)


def write_png(path, rgb):
    h, w, _ = rgb.shape
    raw = b"".join(b"\0" + rgb[y].tobytes() for y in range(h))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(png)
    os.replace(tmp, path)


def tile(glint_rgb, cycles_rgb, g, c, box):
    """Glint | Cycles | overlay, cropped to box (y0, y1, x0, x1), 3-pixel white gaps."""
    y0, y1, x0, x1 = box
    overlay = np.zeros(g.shape + (3,), np.uint8)
    overlay[g & c] = (235, 235, 235)
    overlay[g & ~c] = (255, 140, 0)
    overlay[~g & c] = (40, 140, 255)
    gap = np.full((y1 - y0, 3, 3), 255, np.uint8)
    return np.concatenate([glint_rgb[y0:y1, x0:x1], gap, cycles_rgb[y0:y1, x0:x1], gap,
                           overlay[y0:y1, x0:x1]], axis=1)


def sheet(rows, gap):
    """Tiles left to right in rows, rows top to bottom, white between, black padding."""
    lines = []
    for tiles in rows:
        parts = []
        for t in tiles:
            if parts:
                parts.append(np.full((t.shape[0], gap, 3), 255, np.uint8))
            parts.append(t)
        lines.append(np.concatenate(parts, axis=1))
    width = max(line.shape[1] for line in lines)
    out = []
    for line in lines:
        if out:
            out.append(np.full((gap, width, 3), 255, np.uint8))
        pad = np.zeros((line.shape[0], width - line.shape[1], 3), np.uint8)
        out.append(np.concatenate([line, pad], axis=1))
    return np.concatenate(out, axis=0)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    p = argparse.ArgumentParser(prog="silhouettes.py")
    p.add_argument("--out", required=True, help="the folder with the renders")
    p.add_argument("--png", help="write the picture here")
    p.add_argument("--draw", help="MODEL:LABEL,... the views the picture shows [all]")
    p.add_argument("views", nargs="+", metavar="MODEL:LABEL")
    a = p.parse_args(argv)
    views = [tuple(v.split(":", 1)) for v in a.views]
    draw = [tuple(v.split(":", 1)) for v in a.draw.split(",")] if a.draw else views
    masks, images = {}, {}
    for model, label in views:
        stem = f"{model}_{label}"
        cyc = read_exr(os.path.join(a.out, f"cycles_{stem}.exr"))
        ref = blender_pixels(os.path.join(a.out, f"cycles_{stem}.exr"))
        mine = np.stack([cyc[c] for c in "RGBA"], axis=-1)
        if not np.array_equal(mine, ref):
            fail(f"cycles_{stem}.exr: this reader and Blender's disagree "
                 f"(largest difference {np.abs(mine - ref).max():g})")
        h, w = cyc["A"].shape
        depth = read_exr(os.path.join(a.out, f"mask_{stem}.exr"))["depth.Z"]
        k = depth.shape[0] // h
        if depth.shape != (h * k, w * k):
            fail(f"mask_{stem}.exr is {depth.shape[1]}x{depth.shape[0]}, not a multiple of "
                 f"{w}x{h}")
        covered = (depth > 0).reshape(h, k, w, k).mean(axis=(1, 3))
        g = covered > 0.5
        c = cyc["A"] > 0.5
        masks[(model, label)] = (g, c)
        xor = g != c
        on_edge = (xor & (edge(g) | edge(c))).sum()
        area_g, area_c = float(covered.sum()), float(cyc["A"].sum())
        print(f"SILHOUETTE {model} {label}: IoU {iou(g, c):.4f}; pixels Glint {g.sum()}, "
              f"Cycles {c.sum()}, both {np.logical_and(g, c).sum()}, differing {xor.sum()} "
              f"({on_edge} of them on an edge); covered area (summed coverage, no threshold) "
              f"Glint {area_g:.1f}, Cycles {area_c:.1f}, relative difference "
              f"{area_g / area_c - 1:+.5f}; supersampling {k}x{k}", flush=True)
        if a.png and (model, label) in draw:
            beauty = read_exr(os.path.join(a.out, f"glint_{stem}.exr"))
            images[(model, label)] = (srgb8(np.stack([beauty[ch] for ch in "RGB"], axis=-1)),
                                      srgb8(np.stack([cyc[ch] for ch in "RGB"], axis=-1)))
    by_model = {}
    for model, label in views:
        if label.isdigit():  # frames; other labels are variants of a frame
            by_model.setdefault(model, []).append(label)
    for model, labels in by_model.items():
        for i, f1 in enumerate(labels):
            for f2 in labels[i + 1:]:
                (g1, c1), (g2, c2) = masks[(model, f1)], masks[(model, f2)]
                print(f"BETWEEN {model} frames {f1} and {f2}: IoU Glint-Glint {iou(g1, g2):.4f}, "
                      f"Cycles-Cycles {iou(c1, c2):.4f}, Glint {f1}-Cycles {f2} {iou(g1, c2):.4f}, "
                      f"Glint {f2}-Cycles {f1} {iou(g2, c1):.4f}", flush=True)
    if a.png:
        rows = {}
        for model, label in draw:  # one row per model, cropped to all its drawn silhouettes
            rows.setdefault(model, []).append(label)
        tiles = []
        for model, labels in rows.items():
            union = np.zeros_like(masks[(model, labels[0])][0])
            for label in labels:
                union |= masks[(model, label)][0] | masks[(model, label)][1]
            ys, xs = np.nonzero(union)
            m = 8
            box = (max(ys.min() - m, 0), min(ys.max() + m + 1, union.shape[0]),
                   max(xs.min() - m, 0), min(xs.max() + m + 1, union.shape[1]))
            tiles.append([tile(*images[(model, label)], *masks[(model, label)], box)
                          for label in labels])
        picture = sheet(tiles, 8)
        write_png(a.png, picture)
        print(f"silhouettes.py: wrote {a.png} ({picture.shape[1]}x{picture.shape[0]})", flush=True)


if __name__ == "__main__":
    try:
        main()
    except SystemExit as e:
        os._exit(e.code if isinstance(e.code, int) else 1)
    except Exception:  # noqa: BLE001 - report and exit non-zero instead of Blender's 0
        import traceback
        traceback.print_exc()
        os._exit(1)
    sys.stdout.flush()
    os._exit(0)
