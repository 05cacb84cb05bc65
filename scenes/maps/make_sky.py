#!/usr/bin/env python3
"""Writes sky.hdr beside this script: a small equirectangular HDR sky for the examples of the
README and the docs (`--environment scenes/maps/sky.hdr`), made here, not photographed: a blue
gradient above the horizon, a warm sun 35 degrees up, a dim brownish ground below. 128 x 64
texels of Radiance RGBE, uncompressed. Python's standard library only; it remakes the file
byte for byte:

    python3 scenes/maps/make_sky.py
"""

import math
import os

WIDTH, HEIGHT = 128, 64
SUN_ELEVATION, SUN_AZIMUTH = math.radians(35), math.radians(60)
SUN_RADIUS = math.radians(3)  # wider than the real sun's 0.27 degrees: 128 texels cannot show it


def radiance(x: float, y: float) -> tuple:
    """Linear RGB radiance towards texel centre (x, y) of the map (row 0 is straight up)."""
    theta = math.pi * (y + 0.5) / HEIGHT  # from +y
    phi = 2 * math.pi * (x + 0.5) / WIDTH
    elevation = math.pi / 2 - theta
    if elevation < 0:  # the ground: dim, a little brighter towards the horizon
        k = 0.18 + 0.1 * math.exp(8 * elevation)
        return (0.35 * k, 0.3 * k, 0.25 * k)
    t = 1 - elevation / (math.pi / 2)  # 0 straight up, 1 at the horizon
    sky = (0.25 + 0.45 * t, 0.45 + 0.35 * t, 0.9 + 0.05 * t)
    # The angle to the sun, by the cosine of the great circle.
    cos_angle = (math.sin(elevation) * math.sin(SUN_ELEVATION) +
                 math.cos(elevation) * math.cos(SUN_ELEVATION) * math.cos(phi - SUN_AZIMUTH))
    angle = math.acos(max(-1.0, min(1.0, cos_angle)))
    if angle < SUN_RADIUS:
        return (900.0, 800.0, 650.0)
    glow = 2.0 * math.exp(-angle / math.radians(8))
    return (sky[0] + glow, sky[1] + 0.85 * glow, sky[2] + 0.6 * glow)


def rgbe(r: float, g: float, b: float) -> bytes:
    """Radiance's shared-exponent encoding of a colour."""
    m = max(r, g, b)
    if m < 1e-32:
        return bytes(4)
    mantissa, exponent = math.frexp(m)
    scale = mantissa * 256.0 / m
    return bytes([int(r * scale), int(g * scale), int(b * scale), exponent + 128])


def main() -> None:
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "sky.hdr")
    head = f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {HEIGHT} +X {WIDTH}\n".encode()
    body = b"".join(rgbe(*radiance(x, y)) for y in range(HEIGHT) for x in range(WIDTH))
    with open(path, "wb") as out:
        out.write(head + body)
    print(f"wrote {path} ({WIDTH} x {HEIGHT})")


if __name__ == "__main__":
    main()
