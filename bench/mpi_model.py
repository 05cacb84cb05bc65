#!/usr/bin/env python3
"""A model of glint-mpi's speedup on N nodes, from figures measured on one machine.

Reads two `glint-mpi --timings` files of one frame rendered at two sample counts A < B with fine
tiles (bench/mpi_scaling.sh makes them: the path-traced Cornell box at 3840x2160, 16-pixel
tiles). From them, per 16-pixel tile i: a fixed cost c (setting up a render of a tile, the same
for every tile: fitted on the sums) and a cost per sample s_i (the smaller of the two runs'
estimates: a descheduled thread only ever slows a tile), so that the tile takes
c + s_i * spp seconds on one thread while every thread of the node is busy. Larger tiles are
unions of 16-pixel ones (one fixed cost each).

The frame on N nodes of T threads each (rank 0 renders too) is then simulated as glint-mpi runs
it: tiles are handed out in rows from the top, each to the first thread that is free (every
rank holds one tile more than it has threads, so a thread never waits for rank 0's answer);
each tile's pixels (24 bytes a pixel, plus a 56-byte header) cross the network to rank 0 at
BANDWIDTH after LATENCY, and rank 0 handles one result in HANDLE seconds (measured: the time its
MPI thread spends receiving a result and placing its pixels). The job also pays, once: mpirun's start (STARTUP), loading the scene
and building its BVH (every rank at once: the slowest), and writing the image (rank 0, after the
last tile). One node is glint itself: no start, no messages.

Usage: bench/mpi_model.py TIMINGS_A.json TIMINGS_B.json [--spp 1024] [--threads 2,32]
       [--tiles 16,32,64] [--startup S] [--handle S] [--bandwidth B/s] [--latency S]
       [--load S] [--build S]
Prints a Markdown table (docs/scale-out.md).
"""

import argparse
import heapq
import json


def load(path):
    with open(path) as f:
        return json.load(f)


def fit(a, b):
    """Per 16-pixel tile (x0, y0) -> samples cost s_i, and the fixed cost c per tile."""
    if a["tile_side"] != b["tile_side"] or (a["width"], a["height"]) != (b["width"], b["height"]):
        raise SystemExit("mpi_model.py: the two timings must be one frame with the same tiles")
    spp_a, spp_b = a["spp"], b["spp"]
    ta = {(t[0], t[1]): t[5] for t in a["tiles"]}
    tb = {(t[0], t[1]): t[5] for t in b["tiles"]}
    n = len(ta)
    # Sums over the frame: sum t(spp) = n c + spp sum s_i, at two spp.
    sa, sb = sum(ta.values()), sum(tb.values())
    c = max((spp_b * sa - spp_a * sb) / ((spp_b - spp_a) * n), 0.0)
    # A tile's cost per sample from each run; the smaller of the two, since a thread that was
    # descheduled for a while (a busy machine) makes a tile slower, never faster.
    s = {k: max(min((ta[k] - c) / spp_a, (tb[k] - c) / spp_b), 0.0) for k in tb}
    return s, c, a["tile_side"]


def tiles_of(s, fine, side, width, height):
    """Per-sample costs of tiles `side` pixels square, in rows from the top (as frameTiles)."""
    out = []
    for y0 in range(0, height, side):
        for x0 in range(0, width, side):
            total = 0.0
            for y in range(y0, min(y0 + side, height), fine):
                for x in range(x0, min(x0 + side, width), fine):
                    total += s[(x, y)]
            px = (min(x0 + side, width) - x0) * (min(y0 + side, height) - y0)
            out.append((total, px))
    return out


def simulate(tiles, c, spp, nodes, threads, net):
    """Seconds from the first tile handed out to the last one in at rank 0."""
    slots = [(0.0, n) for n in range(nodes) for _ in range(threads)]
    heapq.heapify(slots)
    arrivals = []
    for s_i, px in tiles:
        start, node = heapq.heappop(slots)
        done = start + c + s_i * spp
        heapq.heappush(slots, (done, node))
        if node != 0:  # rank 0's own tiles do not cross the network
            done += net["latency"] + (24 * px + 56) / net["bandwidth"]
        arrivals.append(done)
    if nodes == 1:
        return max(arrivals)
    # Rank 0's MPI thread takes the results as they arrive, one at a time.
    root_free = 0.0
    for t in sorted(arrivals):
        root_free = max(root_free, t) + net["handle"]
    return root_free


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("timings_a")
    p.add_argument("timings_b")
    p.add_argument("--spp", type=int, default=1024)
    p.add_argument("--threads", default="2,32", help="threads per node, comma-separated")
    p.add_argument("--tiles", default="16,32,64", help="tile sides, comma-separated")
    p.add_argument("--nodes", default="1,4,16,64")
    p.add_argument("--startup", type=float, default=2.0, help="mpirun's start on N nodes, s")
    p.add_argument("--handle", type=float, default=None,
                   help="rank 0's time per message, s (default: measured, in timings B)")
    p.add_argument("--bandwidth", type=float, default=1.25e9, help="into rank 0, bytes/s")
    p.add_argument("--latency", type=float, default=50e-6, help="per message, s")
    p.add_argument("--load", type=float, default=None, help="scene load, s (default: measured)")
    p.add_argument("--build", type=float, default=None, help="BVH build, s (default: measured)")
    p.add_argument("--write", type=float, default=None, help="image write, s (default: measured)")
    args = p.parse_args()

    a, b = load(args.timings_a), load(args.timings_b)
    s, c, fine = fit(a, b)
    width, height = b["width"], b["height"]
    handle = args.handle
    if handle is None:
        # Rank 0's MPI thread receiving a message and placing its pixels (the other ranks' tiles).
        remote = sum(1 for t in b["tiles"] if t[4] != 0)
        handle = b["receive_seconds"] / max(remote, 1)
    net = {"latency": args.latency, "bandwidth": args.bandwidth, "handle": handle}
    load_s = args.load if args.load is not None else max(b["parse_seconds"])
    build_s = args.build if args.build is not None else max(b["build_seconds"])
    write_s = args.write if args.write is not None else b["write_seconds"]
    serial = load_s + build_s + write_s
    thread_seconds = sum(c + v * args.spp for v in s.values())
    print(f"Frame {width}x{height} at {args.spp} spp: {thread_seconds / 3600:.2f} thread-hours "
          f"(per 16-pixel tile: {c * 1e3:.2f} ms fixed, {sum(s.values()) / len(s) * 1e6:.1f} us "
          f"per sample); load {load_s:.3f} s, build {build_s:.3f} s, write {write_s:.2f} s, "
          f"mpirun start {args.startup:.1f} s; rank 0 handles a tile in {handle * 1e6:.0f} us; "
          f"{args.bandwidth / 1e9:.2f} GB/s and {args.latency * 1e6:.0f} us into rank 0.\n")
    nodes = [int(n) for n in args.nodes.split(",")]
    print("| threads per node | tile | " + " | ".join(f"{n} node{'s' if n > 1 else ''}"
                                                      for n in nodes) + " | limits at the most nodes |")
    print("|---|---|" + "---|" * len(nodes) + "---|")
    for threads in [int(t) for t in args.threads.split(",")]:
        for side in [int(t) for t in args.tiles.split(",")]:
            tiles = tiles_of(s, fine, side, width, height)
            one = serial + simulate(tiles, c, args.spp, 1, threads, net)
            cells = []
            for n in nodes:
                render = simulate(tiles, c, args.spp, n, threads, net)
                total = serial + render + (args.startup if n > 1 else 0)
                speedup = one / total
                cells.append(f"{speedup:.1f}x ({100 * speedup / n:.0f}%)")
            # What the largest job loses against a perfect split of the work.
            n = nodes[-1]
            ideal = sum(c + v * args.spp for v, _ in tiles) / (n * threads)
            render = simulate(tiles, c, args.spp, n, threads, net)
            fixed = serial + args.startup
            print(f"| {threads} | {side} | " + " | ".join(cells) +
                  f" | load, build, write, start {fixed:.1f} s; tail {render - ideal:.1f} s; "
                  f"render {render:.1f} s, {len(tiles)} tiles |")
    print("\n(speedup against one node, and the parallel efficiency: speedup / nodes)")


if __name__ == "__main__":
    main()
