#!/usr/bin/python3
"""Random course-format scenes for the denoiser's training data (make_data.sh):

    gen_scenes.py OUT_DIR COUNT [SEED]

writes OUT_DIR/rand000.test ... Each scene is path traced: a floor (plain or checkered), 3 to
14 primitives (spheres, boxes, cylinders, cones, some turned) of random materials (matte,
plastic, glossy or mirror metal, glass, an occasional emitter), lit one of three ways: a sun
and a sky gradient, area lights in the dark, or a closed room lit through a window or by a
ceiling lamp (mostly indirect light); now and then a thin lens. Reproducible from SEED."""

import math
import os
import random
import sys


def colour(rng, low=0.05, high=0.9):
    return [rng.uniform(low, high) for _ in range(3)]


def fmt(values):
    return " ".join(f"{v:.4g}" for v in values)


def material(rng, lines):
    """Sets a random material (every property, so none leaks from the one before)."""
    kind = rng.choices(["matte", "plastic", "metal", "mirror", "glass", "emitter"],
                       [4, 3, 3, 1, 2, 0.5])[0]
    diffuse, specular, rough, trans, emission = colour(rng), [0, 0, 0], 0.0, [0, 0, 0], [0, 0, 0]
    if kind == "plastic":
        specular, rough = [0.04] * 3, rng.uniform(0.02, 0.4)
    elif kind in ("metal", "mirror"):
        diffuse = [0, 0, 0]
        specular = colour(rng, 0.5, 0.95)
        rough = rng.uniform(0.05, 0.5) if kind == "metal" else 0.0
    elif kind == "glass":
        diffuse, trans = [0, 0, 0], colour(rng, 0.7, 1.0)
        rough = rng.choice([0.0, 0.0, rng.uniform(0.02, 0.2)])
    elif kind == "emitter":
        diffuse = [0, 0, 0]
        emission = [c * rng.uniform(2, 20) for c in colour(rng, 0.3, 1.0)]
    lines += [f"diffuse {fmt(diffuse)}", f"specular {fmt(specular)}", f"roughness {rough:.3g}",
              f"transmission {fmt(trans)}", f"ior {rng.uniform(1.3, 1.8):.3g}",
              f"emission {fmt(emission)}"]


def primitive(rng, lines, x, z, size):
    """One shape standing on the floor (y = 0) at (x, z), about `size` across."""
    kind = rng.choice(["sphere", "sphere", "box", "cylinder", "cone"])
    if kind == "sphere":
        r = size / 2
        lines.append(f"sphere {x:.3f} {r:.3f} {z:.3f} {r:.3f}")
        return
    h = size * rng.uniform(0.5, 2.0)
    lines.append("pushTransform")
    lines.append(f"translate {x:.3f} 0 {z:.3f}")
    lines.append(f"rotate 0 1 0 {rng.uniform(0, 360):.1f}")
    if kind == "box":
        w, d = size * rng.uniform(0.4, 0.6), size * rng.uniform(0.4, 0.6)
        lines.append(f"box {-w:.3f} 0 {-d:.3f} {w:.3f} {h:.3f} {d:.3f}")
    elif kind == "cylinder":
        lines.append(f"cylinder 0 0 0 0 {h:.3f} 0 {size / 2:.3f}")
    else:
        lines.append(f"cone 0 0 0 {size / 2:.3f} 0 {h:.3f} 0 {size * rng.uniform(0, 0.3):.3f}")
    lines.append("popTransform")


def scene(rng):
    lines = ["size 256 192", "integrator path", f"maxdepth {rng.choice([6, 8, 10])}",
             "ambient 0 0 0"]
    lighting = rng.choices(["sun", "lamps", "room"], [3, 2, 2])[0]
    spread = rng.uniform(2.5, 5)
    # Camera: above the floor, looking at the middle of the objects.
    angle, dist = rng.uniform(0, 6.283), rng.uniform(1.2, 2.2) * spread
    eye = [dist * math.sin(angle), rng.uniform(0.4, 2.5) * spread / 2, dist * math.cos(angle)]
    target = [rng.uniform(-0.3, 0.3), rng.uniform(0.2, 0.8), rng.uniform(-0.3, 0.3)]
    if lighting == "room":  # inside the room, near a wall, looking in
        r = rng.uniform(0.5, 0.85) * spread
        eye = [r * math.sin(angle), rng.uniform(0.6, 1.8), r * math.cos(angle)]
    lines.append(f"camera {fmt(eye)} {fmt(target)} 0 1 0 {rng.uniform(30, 60):.1f}")
    if rng.random() < 0.2:
        lines.append(f"lens {rng.uniform(0.02, 0.12):.3f}")
    if lighting == "sun":
        sky = colour(rng, 0.1, 0.5) + colour(rng, 0.3, 1.2)
        lines.append(f"background {fmt(sky)}")
        sun = [rng.uniform(-1, 1), rng.uniform(0.15, 1), rng.uniform(-1, 1)]
        light = [c * rng.uniform(1, 4) for c in colour(rng, 0.6, 1)]
        lines.append(f"directional {fmt(sun)} {fmt(light)}")
    elif lighting == "lamps":
        lines.append(f"background {fmt(colour(rng, 0, 0.03))}")
        for _ in range(rng.randint(1, 3)):
            w, d = rng.uniform(0.2, 1.5), rng.uniform(0.2, 1.5)
            corner = [rng.uniform(-spread, spread), rng.uniform(2, 5), rng.uniform(-spread, spread)]
            power = rng.uniform(5, 40) / (w * d) ** 0.5
            lines.append(f"quadLight {fmt(corner)} {w:.3f} 0 0 0 0 {d:.3f} "
                         f"{fmt([c * power for c in colour(rng, 0.5, 1)])}")
    # The floor.
    lines += ["diffuse 0.6 0.6 0.6", "specular 0 0 0", "roughness 0", "transmission 0 0 0",
              "emission 0 0 0", f"diffuse {fmt(colour(rng, 0.2, 0.8))}"]
    if rng.random() < 0.5:
        lines.append(f"checker {fmt(colour(rng, 0.5, 0.9))} {fmt(colour(rng, 0.05, 0.4))} "
                     f"{rng.uniform(0.2, 1.5):.3f}")
    lines += ["plane 0 0 0 0 1 0", "texture none"]
    if lighting == "room":
        lines.append(f"background {fmt(colour(rng, 0.2, 0.5) + colour(rng, 0.4, 1.2))}")
        s, top = spread, rng.uniform(2.5, 4)
        lines.append(f"diffuse {fmt(colour(rng, 0.4, 0.85))}")
        lines += [f"box {-s - 0.2:.3f} {top:.3f} {-s - 0.2:.3f} "
                  f"{s + 0.2:.3f} {top + 0.2:.3f} {s + 0.2:.3f}",
                  f"box {-s - 0.2:.3f} 0 {-s - 0.2:.3f} {s + 0.2:.3f} {top:.3f} {-s:.3f}",
                  f"box {s:.3f} 0 {-s:.3f} {s + 0.2:.3f} {top:.3f} {s:.3f}",
                  f"box {-s - 0.2:.3f} 0 {s:.3f} {s + 0.2:.3f} {top:.3f} {s + 0.2:.3f}"]
        if rng.random() < 0.6:  # the left wall with a window, a sun outside
            w0, w1 = rng.uniform(-s, 0), rng.uniform(0.3, s)
            y0, y1 = rng.uniform(0.5, 1.2), rng.uniform(1.6, top - 0.2)
            x0, x1 = -s - 0.2, -s
            lines += [f"box {x0:.3f} 0 {-s:.3f} {x1:.3f} {y0:.3f} {s:.3f}",
                      f"box {x0:.3f} {y1:.3f} {-s:.3f} {x1:.3f} {top:.3f} {s:.3f}",
                      f"box {x0:.3f} {y0:.3f} {-s:.3f} {x1:.3f} {y1:.3f} {w0:.3f}",
                      f"box {x0:.3f} {y0:.3f} {w1:.3f} {x1:.3f} {y1:.3f} {s:.3f}"]
            sun = [-1, rng.uniform(0.3, 1.2), rng.uniform(-0.6, 0.6)]
            light = [c * rng.uniform(3, 8) for c in colour(rng, 0.7, 1)]
            lines.append(f"directional {fmt(sun)} {fmt(light)}")
        else:
            lines.append(f"box {-s - 0.2:.3f} 0 {-s:.3f} {-s:.3f} {top:.3f} {s:.3f}")
            w = rng.uniform(0.3, 1.2)
            lines.append(f"quadLight {-w:.3f} {top - 0.01:.3f} {-w:.3f} "
                         f"{2 * w:.3f} 0 0 0 0 {2 * w:.3f} "
                         f"{fmt([c * rng.uniform(4, 15) for c in colour(rng, 0.6, 1)])}")
    # The objects, spread over the floor without much overlap.
    placed = []
    for _ in range(rng.randint(3, 14)):
        for _try in range(20):
            size = rng.uniform(0.3, 1.4)
            x, z = rng.uniform(-spread, spread) * 0.7, rng.uniform(-spread, spread) * 0.7
            if all((x - px) ** 2 + (z - pz) ** 2 > ((size + ps) / 2) ** 2 for px, pz, ps in placed):
                break
        placed.append((x, z, size))
        material(rng, lines)
        primitive(rng, lines, x, z, size)
    return "\n".join(lines) + "\n"


def main(argv):
    out, count = argv[0], int(argv[1])
    seed = int(argv[2]) if len(argv) > 2 else 1
    os.makedirs(out, exist_ok=True)
    for i in range(count):
        rng = random.Random(seed * 100003 + i)
        path = os.path.join(out, f"rand{i:03d}.test")
        if not os.path.exists(path):
            with open(path, "w") as f:
                f.write(f"# gen_scenes.py seed {seed}, scene {i}\n" + scene(rng))


if __name__ == "__main__":
    main(sys.argv[1:])
