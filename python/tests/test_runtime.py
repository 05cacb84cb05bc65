"""Ctrl-C, threads of Python and long loops: what a notebook or a pipeline does to a renderer."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import glint
from conftest import SOURCE, data


def long_scene() -> glint.Scene:
    # A path-traced Cornell box at the most samples there are: hours, and seconds for each
    # block of 4 x 2 pixels, which the render must not finish before it stops.
    return glint.load(SOURCE / "scenes" / "cornell.test", size=(256, 256), integrator="path",
                      spp=65536)


def test_ctrl_c_stops_a_render_within_a_second_and_leaves_python_usable():
    scene = long_scene()
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        scene.render(threads=2)
    stopped = time.monotonic() - start - 0.5
    timer.join()
    assert stopped < 1.0, f"the render went on {stopped:.2f} s after Ctrl-C"
    # The interpreter and the scene both work on.
    assert scene.render(spp=1).shape == (256, 256, 3)


def test_two_python_threads_render_at_once_and_get_what_each_gets_alone():
    a = glint.load(data("cse167x", "scene6.test"), size=(64, 48))
    b = glint.load(SOURCE / "scenes" / "cornell.test", size=(32, 32), integrator="path", spp=4)
    alone = [a.render(threads=1), b.render(threads=1)]
    results = [None, None, None]

    def run(i, scene):
        results[i] = scene.render(threads=1)

    threads = [threading.Thread(target=run, args=(0, a)), threading.Thread(target=run, args=(1, b)),
               threading.Thread(target=run, args=(2, a))]  # and one scene from two threads
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert np.array_equal(results[0], alone[0])
    assert np.array_equal(results[1], alone[1])
    assert np.array_equal(results[2], alone[0])


def resident_bytes() -> int:
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_memory_does_not_grow_over_a_hundred_renders():
    scene = glint.load(data("gltf", "blender-monkey.gltf"), size=(64, 48))
    for _ in range(10):  # the allocator's pools settle first
        glint.encode(scene.render(spp=1), "png")
    before = resident_bytes()
    for _ in range(100):
        image = scene.render(spp=1)
        glint.encode(image, "png")
        del image
    grown = resident_bytes() - before
    # An image here is 64 x 48 x (12 + 24) bytes (the array and its film): 100 of them kept
    # would be 11 MB; allow a few pages of allocator slack.
    assert grown < 2_000_000, f"resident memory grew by {grown} bytes over 100 renders"
