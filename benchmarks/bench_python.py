#!/usr/bin/env python3
"""The Python binding's cost: an HA-buffer insert of N fragments from numpy
arrays (three arrays, copied into fragments; and one FRAGMENT_DTYPE array,
read in place) against the library's own call inside it
(Buffer.last_insert_ms), and 2 threads against 1 (the GIL is released).
Rounds interleave the variants; medians are printed.

usage: PYTHONPATH=build/python /usr/bin/python3 benchmarks/bench_python.py [--fragments N] [--rounds R]
"""

import argparse
import statistics
import time

import numpy as np

import habuffer as hb


def stream(n, side, seed=1):
    """Coherent-ish: fragments of 16x16 tiles in scanline order, as a rasterizer emits them."""
    rng = np.random.default_rng(seed)
    tiles = side // 16
    tile = rng.integers(0, tiles * tiles, n // 256 + 1)
    within = np.arange(256)
    xs = ((tile[:, None] % tiles) * 16 + within[None, :] % 16).ravel()[:n]
    ys = ((tile[:, None] // tiles) * 16 + within[None, :] // 16).ravel()[:n]
    xy = np.stack([xs, ys], axis=1).astype(np.uint32)
    depth = rng.random(n, dtype=np.float32)
    rgba = rng.integers(0, 2**32, n, dtype=np.uint32)
    return xy, depth, rgba


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--fragments", type=int, default=10_000_000)
    ap.add_argument("--side", type=int, default=2048)
    ap.add_argument("--rounds", type=int, default=3)
    a = ap.parse_args()
    xy, depth, rgba = stream(a.fragments, a.side)
    frags = np.zeros(a.fragments, hb.FRAGMENT_DTYPE)
    frags["x"], frags["y"], frags["depth"], frags["rgba"] = xy[:, 0], xy[:, 1], depth, rgba
    screen = (a.side, a.side)
    slots = int(a.fragments / 0.8)
    side = int(np.ceil(np.sqrt(slots)))
    table = (max(side, a.side), max(side, a.side))
    buf = hb.HaBuffer(screen, table=table)
    results = {}

    def run(name, call, threads):
        buf.clear()
        t0 = time.perf_counter()
        call(threads)
        wall = (time.perf_counter() - t0) * 1e3
        results.setdefault(name, []).append((wall, buf.last_insert_ms))

    variants = [
        ("arrays, 1 thread", lambda t: buf.insert(xy, depth, rgba, threads=t, order="arrival"), 1),
        ("in place, 1 thread", lambda t: buf.insert_fragments(frags, threads=t, order="arrival"), 1),
        ("arrays, 2 threads", lambda t: buf.insert(xy, depth, rgba, threads=t, order="arrival"), 2),
    ]
    for _ in range(a.rounds):
        for name, call, threads in variants:
            run(name, call, threads)
    print("%d fragments, screen %dx%d, table %dx%d, %d rounds (medians)" % (a.fragments, a.side, a.side, *table,
                                                                           a.rounds))
    for name, _, _ in variants:
        wall = statistics.median(w for w, _ in results[name])
        lib = statistics.median(l for _, l in results[name])
        print("%-20s wall %8.1f ms, library %8.1f ms, binding overhead %5.1f %%" % (name, wall, lib,
                                                                                  100.0 * (wall - lib) / lib))
    one = statistics.median(w for w, _ in results["arrays, 1 thread"])
    two = statistics.median(w for w, _ in results["arrays, 2 threads"])
    print("2 threads / 1 thread (wall, from Python): %.2f" % (two / one))


if __name__ == "__main__":
    main()
