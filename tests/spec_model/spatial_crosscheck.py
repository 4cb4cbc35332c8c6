#!/usr/bin/env python3
"""Cross-check `habuffer hash` against an independent Python model of the
spatial hash (docs/spec-notes.md, "The spatial hash").

usage: python3 spatial_crosscheck.py --habuffer PATH/TO/habuffer [--cases N]
                                     [--seed S] [--workdir DIR]

For every case a seeded random domain (2D or 3D), key multiset (with repeats
and values), rule, age bits and load are written as a key CSV; `habuffer
hash build` builds the table with 2 threads; the table file is read here and
compared slot for slot and cell for cell with the model's, built serially
from the same offsets (`habuffer offsets`) at the table's size; `habuffer
hash query` over the keys and as many absent keys must answer as the
model's dictionary does. The model shares no code with the C++: it is
written from the spec notes (record layout, fold, probe, Robin Hood insert
with one record per key, max-age cells). Standard library only. The last
line is `spatial crosscheck: N passed, M failed`.
"""

import argparse
import math
import os
import random
import shutil
import struct
import subprocess
import sys
import tempfile

MAGIC = b"HASPATL1"
RULES = ["max", "min", "first", "last"]


class SpatialModel:
    """Serial model: distinct keys inserted by SPEC 6's loop, records
    | age | quotient | live | value |, key bits = the high word >> 1."""

    def __init__(self, domain, table, age_bits, block, offsets):
        self.dx, self.dy, self.dz = domain
        # G slices interleaved along x, then F groups per row (spec notes).
        self.g = 4 if self.dz >= 4 else 2 if self.dz >= 2 else 1  # a power of two up to min(Dz, 4)
        groups = -(-self.dz // self.g)
        f = math.sqrt(groups * self.dy / (self.dx * self.g))
        self.per_row = min(max(int(math.floor(f + 0.5)), 1), groups)
        self.du = self.dx * self.g * self.per_row
        self.dv = self.dy * -(-groups // self.per_row)
        self.hx, self.hy = table
        self.qx = -(-self.du // self.hx)
        self.a_bits = age_bits
        self.amax = (1 << age_bits) - 1
        self.block = block
        self.cells_x = -(-self.hx // block)
        self.offsets = offsets
        self.slots = [0] * (self.hx * self.hy)
        self.max_age = [0] * (self.cells_x * -(-self.hy // block))

    def fold(self, k):
        x, y, z = k
        group, piece = divmod(z, self.g)
        return (x * self.g + piece + self.dx * self.g * (group % self.per_row), y + self.dy * (group // self.per_row))

    def split(self, u, v):
        return (u % self.hx, v % self.hy), u // self.hx + self.qx * (v // self.hy)

    def probe(self, p, a):
        o = self.offsets[(a - 1) % len(self.offsets)]
        return ((p[0] + o[0]) % self.hx, (p[1] + o[1]) % self.hy)

    def owner(self, h, a):
        o = self.offsets[(a - 1) % len(self.offsets)]
        return ((h[0] - o[0]) % self.hx, (h[1] - o[1]) % self.hy)

    def record(self, a, q, value):
        return ((a << (32 - self.a_bits) | q << 1 | 1) << 32) | value

    def insert(self, key, value):
        """Inserts a key not yet in the table; returns False on a failure."""
        p, q = self.split(*self.fold(key))
        a, r = 1, self.record(1, q, value)
        while True:
            if a > self.amax:
                return False
            h = self.probe(p, a)
            s = h[0] + h[1] * self.hx
            old = self.slots[s]
            if r > old:
                self.slots[s] = r
                c = p[0] // self.block + (p[1] // self.block) * self.cells_x
                self.max_age[c] = max(self.max_age[c], a)
                if old == 0:
                    return True
                a = old >> (64 - self.a_bits)
                r = old
                p = self.owner(h, a)
            a += 1
            r = (r & ((1 << (64 - self.a_bits)) - 1)) | (a << (64 - self.a_bits))


def distinct(keys, values, rule):
    d = {}
    for k, v in zip(keys, values):
        if k not in d:
            d[k] = v
        elif rule == "max":
            d[k] = max(d[k], v)
        elif rule == "min":
            d[k] = min(d[k], v)
        elif rule == "last":
            d[k] = v
    return d


def read_table(path):
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == MAGIC, "not a table file"
    fields = struct.unpack_from("<10I", data, 8)
    (dx, dy, dz, rule, age_bits, block, generator, iter_limit, hx, hy) = fields
    seed = struct.unpack_from("<Q", data, 48)[0]
    n = hx * hy
    slots = list(struct.unpack_from("<%dQ" % n, data, 56))
    cells = (-(-hx // block)) * (-(-hy // block))
    max_age = list(struct.unpack_from("<%dI" % cells, data, 56 + 8 * n))
    return dict(domain=(dx, dy, dz), rule=rule, age_bits=age_bits, block=block, generator=generator, seed=seed,
                table=(hx, hy), slots=slots, max_age=max_age)


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("%s -> %d: %s" % (" ".join(cmd), r.returncode, r.stderr.strip()))
    return r.stdout


def one_case(habuffer, rng, work, index):
    three_d = rng.random() < 0.4
    domain = (rng.randint(1, 90), rng.randint(1, 90), rng.randint(2, 12) if three_d else 1)
    cells = domain[0] * domain[1] * domain[2]
    n = rng.randint(1, max(1, cells * 3 // 5))
    rule = rng.choice(RULES)
    age_bits = rng.choice([4, 5, 6, 8])
    load = rng.choice([0.5, 0.8, 0.9, 0.95, 0.99])
    pool = [(rng.randrange(domain[0]), rng.randrange(domain[1]), rng.randrange(domain[2])) for _ in range(n)]
    keys = pool + [rng.choice(pool) for _ in range(n // 4)]  # repeats
    rng.shuffle(keys)
    values = [rng.randrange(1 << 32) for _ in keys]
    keyfile = os.path.join(work, "keys%d.csv" % index)
    with open(keyfile, "w") as f:
        f.write("x,y,z,value\n" if three_d else "x,y,value\n")
        for k, v in zip(keys, values):
            f.write(("%d,%d,%d,%d\n" % (k[0], k[1], k[2], v)) if three_d else ("%d,%d,%d\n" % (k[0], k[1], v)))
    table = os.path.join(work, "t%d.tab" % index)
    seed = rng.randrange(1 << 20)
    run([habuffer, "hash", "build", "--keys", keyfile, "--out", table, "--rule", rule, "--age-bits", str(age_bits),
         "--load", str(load), "--fixed", "--seed", str(seed), "--threads", "2", "--domain",
         "%dx%dx%d" % domain if three_d else "%dx%d" % domain[:2], "--quiet"])
    t = read_table(table)
    offsets_csv = os.path.join(work, "o%d.csv" % index)
    run([habuffer, "offsets", "--table", "%dx%d" % t["table"], "--generator", "random", "--seed", str(seed),
         "--age-bits", str(age_bits), "--out", offsets_csv])
    with open(offsets_csv) as f:
        lines = f.read().split("\n")[1:]
    offsets = [tuple(int(c) for c in line.split(",")) for line in lines if line]
    model = SpatialModel(domain, t["table"], age_bits, t["block"], offsets)
    want = distinct(keys, values, rule)
    for k, v in want.items():
        if not model.insert(k, (~v & 0xFFFFFFFF) if rule == "min" else v):
            raise RuntimeError("the model failed to place key %s at table %s: the C++ grew past it" % (k, t["table"]))
    if model.slots != t["slots"]:
        bad = next(i for i in range(len(model.slots)) if model.slots[i] != t["slots"][i])
        raise RuntimeError("slot %d: model %#x, habuffer %#x" % (bad, model.slots[bad], t["slots"][bad]))
    if model.max_age != t["max_age"]:
        raise RuntimeError("max-age cells differ")
    # Queries: every key, and absent ones.
    absent = []
    for _ in range(len(want) + 5):
        k = (rng.randrange(domain[0]), rng.randrange(domain[1]), rng.randrange(domain[2]))
        if k not in want:
            absent.append(k)
    qfile, rfile = os.path.join(work, "q%d.csv" % index), os.path.join(work, "r%d.csv" % index)
    queries = list(want.keys()) + absent
    with open(qfile, "w") as f:
        f.write("x,y,z\n" if three_d else "x,y\n")
        for k in queries:
            f.write(("%d,%d,%d\n" % k) if three_d else ("%d,%d\n" % k[:2]))
    run([habuffer, "hash", "query", "--table", table, "--keys", qfile, "--out", rfile, "--quiet"])
    with open(rfile) as f:
        rows = f.read().split("\n")[1:]
    for k, row in zip(queries, rows):
        cols = [int(c) for c in row.split(",")]
        found, value = cols[-2], cols[-1]
        expect = (1, want[k]) if k in want else (0, 0)
        if (found, value) != expect:
            raise RuntimeError("query %s: habuffer %s, model %s" % (k, (found, value), expect))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--habuffer", required=True)
    ap.add_argument("--cases", type=int, default=40)
    ap.add_argument("--seed", type=int, default=22)
    ap.add_argument("--workdir")
    a = ap.parse_args()
    work = a.workdir or tempfile.mkdtemp(prefix="spatial_crosscheck_")
    os.makedirs(work, exist_ok=True)
    passed = failed = 0
    for i in range(a.cases):
        rng = random.Random(a.seed * 100003 + i)
        try:
            one_case(a.habuffer, rng, work, i)
            passed += 1
        except (RuntimeError, AssertionError) as e:
            failed += 1
            print("case %d (--seed %d): %s" % (i, a.seed, e))
    if not a.workdir and failed == 0:
        shutil.rmtree(work, ignore_errors=True)
    print("spatial crosscheck: %d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
