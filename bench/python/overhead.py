#!/usr/bin/python3
"""What rendering from Python costs beside the glint program (docs/performance.md, "Python").

For a tiny scene (the course's scene6 at 160 x 120, one sample: milliseconds) and a large one
(the path-traced Cornell box at 256 x 256, 64 samples: seconds), each rendered to a PNG:
  cli        `glint SCENE ... -o out.png`, a process per render (what a script calling the
             program pays);
  python     in one interpreter, glint.load + Scene.render + glint.write to the same PNG
             (what a notebook pays per render after the first import);
  render     Scene.render alone on a loaded scene (the BVH built already);
  wrapper    what of that is not the renderer's own time (image.info's seconds, build_seconds
             and denoise_seconds): the options, the GIL, the progress calls, the float32 array.
Runs are interleaved, and the medians of --runs of each are printed with the ratio to the
program's. Run from the repository root after building:

    PYTHONPATH=build/python /usr/bin/python3 bench/python/overhead.py [--runs 7] [--threads 2]
"""

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import glint

ROOT = Path(__file__).resolve().parents[2]
SCENES = {
    "tiny: scene6, 160x120, 1 spp": (
        ROOT / "tests" / "data" / "cse167x" / "scene6.test", dict(size=(160, 120))),
    "large: Cornell box, path, 256x256, 64 spp": (
        ROOT / "scenes" / "cornell.test",
        dict(size=(256, 256), integrator="path", spp=64, seed=1, srgb=True)),
}


def cli_args(options: dict) -> list:
    args = []
    for key, value in options.items():
        flag = "--" + key.replace("_", "-")
        if value is True:
            args.append(flag)
        elif key == "size":
            args += [flag, f"{value[0]}x{value[1]}"]
        else:
            args += [flag, str(value)]
    return args


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--threads", type=int, default=os.cpu_count())
    parser.add_argument("--glint", default=str(ROOT / "build" / "glint"))
    a = parser.parse_args()
    out = Path(tempfile.mkdtemp(prefix="glint-py-bench-"))
    print(f"{a.runs} runs each, {a.threads} threads, medians (s)")
    print(f"{'scene':44} {'cli':>8} {'python':>8} {'ratio':>7} {'render':>8} {'wrapper':>8}")
    for name, (path, options) in SCENES.items():
        command = [a.glint, str(path), *cli_args(options), "-t", str(a.threads), "-q",
                   "-o", str(out / "cli.png")]
        times = {"cli": [], "python": [], "render": [], "wrapper": []}
        for _ in range(a.runs):
            t = time.perf_counter()
            subprocess.run(command, check=True)
            times["cli"].append(time.perf_counter() - t)

            t = time.perf_counter()
            scene = glint.load(path, **options)
            image = scene.render(threads=a.threads)
            glint.write(out / "py.png", image)
            times["python"].append(time.perf_counter() - t)

            t = time.perf_counter()
            image = scene.render(threads=a.threads)
            times["render"].append(time.perf_counter() - t)
            inner = image.info["seconds"] + image.info["build_seconds"] + image.info[
                "denoise_seconds"]
            times["wrapper"].append(times["render"][-1] - inner)
            if (out / "py.png").read_bytes() != (out / "cli.png").read_bytes():
                sys.exit(f"{name}: the PNGs differ")
        m = {k: statistics.median(v) for k, v in times.items()}
        print(f"{name:44} {m['cli']:8.4f} {m['python']:8.4f} {m['python'] / m['cli']:7.3f} "
              f"{m['render']:8.4f} {m['wrapper']:8.4f}")


if __name__ == "__main__":
    main()
