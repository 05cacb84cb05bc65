"""Checks that two renders of the Cornell box see its light in the same pixels.

    blender -b --factory-startup --python bench/cycles/light_pixels.py -- A.exr B.exr

The light's radiance, (17, 12, 4), is some 60 times that of the ceiling around it, so the
pixels it covers tell where a renderer put the camera and the light, whatever it computes for
the rest: the pixels wholly inside it read exactly Ke in both renders if the camera (eye, look-at,
field of view), the axis conversion, the image's orientation and the pixel filter agree, and
the pixels along its edges hold the same fraction of it. Needs no path tracer: Glint's Whitted
integrator shows a quadLight's radiance to camera rays as well.

Prints the pixels that read Ke in each (and in both), the summed green channel over the pixels
brighter than 1 in either, and exits 1 if the sets differ or the sums by more than 1%.
"""

import os
import sys

import bpy

KE = (17.0, 12.0, 4.0)


def load(path):
    """Rows top first, each a list of (r, g, b)."""
    img = bpy.data.images.load(path)
    w, h = img.size
    px = img.pixels[:]  # bottom row first, RGBA
    rows = [[tuple(px[4 * ((h - 1 - y) * w + x):4 * ((h - 1 - y) * w + x) + 3])
             for x in range(w)] for y in range(h)]
    return w, h, rows


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 2:
        print("usage: blender -b --python light_pixels.py -- A.exr B.exr", file=sys.stderr)
        os._exit(2)
    (wa, ha, a), (wb, hb, b) = load(args[0]), load(args[1])
    if (wa, ha) != (wb, hb):
        print(f"light_pixels: sizes differ: {wa}x{ha} and {wb}x{hb}", file=sys.stderr)
        os._exit(1)

    def is_ke(c):
        return all(abs(c[i] - KE[i]) < 1e-3 for i in range(3))

    full_a = {(x, y) for y in range(ha) for x in range(wa) if is_ke(a[y][x])}
    full_b = {(x, y) for y in range(ha) for x in range(wa) if is_ke(b[y][x])}
    lit = [(x, y) for y in range(ha) for x in range(wa) if a[y][x][1] > 1 or b[y][x][1] > 1]
    sum_a = sum(a[y][x][1] for x, y in lit)
    sum_b = sum(b[y][x][1] for x, y in lit)
    rel = abs(sum_a - sum_b) / sum_b if sum_b else float("inf")
    print(f"pixels reading Ke: A {len(full_a)}, B {len(full_b)}, both {len(full_a & full_b)}")
    if lit:
        xs, ys = [p[0] for p in lit], [p[1] for p in lit]
        print(f"pixels brighter than 1 in either: {len(lit)}, x {min(xs)}-{max(xs)}, "
              f"y {min(ys)}-{max(ys)} (row 0 at the top)")
    print(f"their green channel summed: A {sum_a:.3f}, B {sum_b:.3f}, relative difference "
          f"{rel:.5f}")
    ok = full_a == full_b and bool(full_a) and rel <= 0.01
    print("PASSED" if ok else "FAILED", flush=True)
    os._exit(0 if ok else 1)


if __name__ == "__main__":
    try:
        main()
    except Exception:  # noqa: BLE001
        import traceback
        traceback.print_exc()
        os._exit(2)
