"""Puts images side by side (Blender's Python: it reads the Khronos thumbnails' WebP).

    blender -b --factory-startup --python bench/fidelity/compose.py -- \
        --out OUT.png --height 256 [--background 0.5] IMAGE...

Each IMAGE (PNG, JPEG or WebP) is scaled to --height pixels high (box filter, keeping its
aspect ratio) and composited over the grey --background (sRGB value in [0, 1]) by its alpha, so
that the Render Fidelity thumbnails, transparent where the model is not, sit on the same grey
as Glint's studio; the panels go left to right with a 4-pixel gap. Pixel values are treated as
the 8-bit encoded values they are (no colour conversion): the composite of an opaque image is
its own pixels, resampled.
"""

import argparse
import array
import sys

import bpy


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="compose.py")
    p.add_argument("--out", required=True)
    p.add_argument("--height", type=int, default=256)
    p.add_argument("--background", type=float, default=0.5)
    p.add_argument("images", nargs="+")
    return p.parse_args(argv)


def load(path):
    """(width, height, rows of RGBA floats, top row first)."""
    img = bpy.data.images.load(path)
    img.colorspace_settings.name = "Non-Color"  # the stored values, not linearised
    w, h = img.size
    px = array.array("f", [0.0]) * (w * h * 4)
    img.pixels.foreach_get(px)
    rows = [px[(h - 1 - y) * w * 4:(h - y) * w * 4] for y in range(h)]  # Blender's rows go up
    return w, h, rows


def scaled(w, h, rows, height, background):
    """Box-filtered to `height` rows, composited over the background grey: RGB rows."""
    width = max(1, round(w * height / h))
    out = []
    for y in range(height):
        y0, y1 = y * h / height, (y + 1) * h / height
        row = []
        for x in range(width):
            x0, x1 = x * w / width, (x + 1) * w / width
            acc = [0.0, 0.0, 0.0]
            total = 0.0
            for sy in range(int(y0), min(h, int(y1 + 0.999999))):
                wy = min(y1, sy + 1) - max(y0, sy)
                if wy <= 0:
                    continue
                src = rows[sy]
                for sx in range(int(x0), min(w, int(x1 + 0.999999))):
                    wx = min(x1, sx + 1) - max(x0, sx)
                    if wx <= 0:
                        continue
                    k = sx * 4
                    a = src[k + 3]
                    for c in range(3):
                        acc[c] += wx * wy * (src[k + c] * a + background * (1 - a))
                    total += wx * wy
            row.extend(v / total for v in acc)
        out.append(row)
    return width, out


def main():
    a = parse_args()
    gap = 4
    panels = [scaled(*load(path), a.height, a.background) for path in a.images]
    width = sum(w for w, _ in panels) + gap * (len(panels) - 1)
    px = array.array("f", [1.0]) * (width * a.height * 4)
    x0 = 0
    for w, rows in panels:
        for y, row in enumerate(rows):
            base = ((a.height - 1 - y) * width + x0) * 4
            for x in range(w):
                px[base + 4 * x:base + 4 * x + 3] = array.array("f", row[3 * x:3 * x + 3])
        x0 += w + gap
    img = bpy.data.images.new("composite", width, a.height, alpha=False)
    img.colorspace_settings.name = "Non-Color"
    img.pixels.foreach_set(px)
    img.filepath_raw = a.out
    img.file_format = "PNG"
    img.save()
    print(f"compose.py: wrote {a.out} ({width}x{a.height})")


main()
