#!/usr/bin/env python3
"""Independent serial reference model of the HA-buffer specification.

Written from the specification alone (docs/specification.md, then the
project's founding brief of the same text; plus the paper, seed 000, for
the early-cull details the spec defers to); it shares no code with the C++ implementation.
Standard library only.

Sections of the specification implemented here:
  2  records L64 / L32, depth code with t rounded to float32 first
  3  probing h_a(p) = ((p.x + O[a-1].x) mod Hx, (p.y + O[a-1].y) mod Hy)
  5  max-age table M
  6  insertion (serial: atomicMax = read old, store max), LIMIT, early cull
  7  traversal (per-pixel front-to-back lists)
  11 counters: fragments, invalid, duplicates, culled, failed_age,
     failed_iter, stored

Run `python3 ha_model.py` to execute the self-test.
"""

import math
import random
import struct

__all__ = [
    "f32", "depth_code", "HAModel", "random_offsets", "self_test",
]

DEFAULT_LIMIT = 65536


def f32(v):
    """Round a Python float to float32 (round to nearest even).

    Values whose magnitude overflows float32 become +-inf; NaN stays NaN.
    """
    try:
        return struct.unpack("<f", struct.pack("<f", v))[0]
    except OverflowError:
        return math.copysign(math.inf, v)


def depth_code(t, age_bits):
    """SPEC section 2. Returns the depth code, or None for an invalid depth.

    t is first rounded to float32; NaN or t outside [0, 1] (after rounding)
    is invalid. -0.0 compares equal to 0.0 and is valid.
    """
    D = 32 - age_bits
    t = f32(float(t))
    if t != t or t < 0.0 or t > 1.0:
        return None
    full = (1 << D) - 1
    # t is a float32 and 2^D a power of two: the product is exact in double.
    q = math.floor(t * float(1 << D))
    return full - min(full, q)


def random_offsets(Hx, Hy, age_bits, rng):
    """Offsets per SPEC section 3 (random generator, our own seeding).

    Pairwise-distinct cells when Hx*Hy >= AMAX, otherwise a permutation of
    all cells repeated cyclically.
    """
    amax = (1 << age_bits) - 1
    n = Hx * Hy
    if n >= amax:
        cells = rng.sample(range(n), amax)
    else:
        perm = list(range(n))
        rng.shuffle(perm)
        cells = [perm[i % n] for i in range(amax)]
    return [(c % Hx, c // Hx) for c in cells]


class HAModel(object):
    """Serial model of one HA-buffer frame."""

    COUNTERS = ("fragments", "stored", "duplicates", "culled", "invalid",
                "failed_age", "failed_iter")

    def __init__(self, screen, table, layout=64, age_bits=8, offsets=None,
                 block=8, limit=DEFAULT_LIMIT, tau=None, rng=None):
        Vx, Vy = screen
        Hx, Hy = table
        if Vx < 1 or Vy < 1 or Hx < 1 or Hy < 1:
            raise ValueError("sizes must be positive")
        if Hx < Vx or Hy < Vy:
            raise ValueError("geometry rule violated: table %dx%d smaller "
                             "than screen %dx%d" % (Hx, Hy, Vx, Vy))
        if layout not in (64, 32):
            raise ValueError("layout must be 64 or 32")
        if not 4 <= age_bits <= 12:
            raise ValueError("age bits must be in 4..12")
        if block < 1:
            raise ValueError("block must be >= 1")
        if tau is not None:
            if layout != 64:
                raise ValueError("early cull needs L64")
            if not (0.0 < tau <= 1.0):
                raise ValueError("tau must be in (0, 1]")
        self.Vx, self.Vy, self.Hx, self.Hy = Vx, Vy, Hx, Hy
        self.layout = layout
        self.A = age_bits
        self.D = 32 - age_bits
        self.AMAX = (1 << age_bits) - 1
        self.block = block
        self.limit = limit
        self.tau = tau
        if offsets is None:
            offsets = random_offsets(Hx, Hy, age_bits,
                                     rng or random.Random(0))
        offsets = [(int(ox), int(oy)) for ox, oy in offsets]
        if len(offsets) < self.AMAX:
            raise ValueError("need %d offsets, got %d"
                             % (self.AMAX, len(offsets)))
        for ox, oy in offsets:
            if not (0 <= ox < Hx and 0 <= oy < Hy):
                raise ValueError("offset (%d,%d) outside the table" % (ox, oy))
        self.O = offsets[:self.AMAX]
        self.age_shift = layout - age_bits
        self.low_mask = (1 << self.age_shift) - 1
        self.Mx = -(-Vx // block)
        self.My = -(-Vy // block)
        self.clear()

    # -- state ----------------------------------------------------------
    def clear(self):
        self.T = [0] * (self.Hx * self.Hy)
        self.M = [0] * (self.Mx * self.My)
        self.counters = dict((k, 0) for k in self.COUNTERS)

    # -- records --------------------------------------------------------
    def pack(self, age, code, data):
        if self.layout == 64:
            return (age << self.age_shift) | (code << 32) | (data & 0xFFFFFFFF)
        return (age << self.age_shift) | code

    def age(self, r):
        return r >> self.age_shift

    def code(self, r):
        if self.layout == 64:
            return (r >> 32) & ((1 << self.D) - 1)
        return r & ((1 << self.D) - 1)

    def data(self, r):
        return (r & 0xFFFFFFFF) if self.layout == 64 else 0

    def probe(self, x, y, a):
        ox, oy = self.O[a - 1]
        return (x + ox) % self.Hx + ((y + oy) % self.Hy) * self.Hx

    def cell(self, x, y):
        return (x // self.block) + (y // self.block) * self.Mx

    # -- insertion (SPEC section 6) --------------------------------------
    def add_fragment(self, x, y, t, data=0):
        """Count and insert one fragment. Returns the outcome string:
        'invalid', 'stored', 'duplicate', 'culled', 'failed_age',
        'failed_iter'."""
        if not (0 <= x < self.Vx and 0 <= y < self.Vy):
            raise ValueError("pixel (%d,%d) outside the screen" % (x, y))
        c = self.counters
        c["fragments"] += 1
        code = depth_code(t, self.A)
        if code is None:
            c["invalid"] += 1
            return "invalid"
        if self.layout == 32:
            data = 0
        out = self._insert(x, y, code, data & 0xFFFFFFFF)
        c[out if out != "duplicate" else "duplicates"] += 1
        return out

    def _insert(self, px, py, code, data):
        T, M, O = self.T, self.M, self.O
        Hx, Hy = self.Hx, self.Hy
        B, Mx = self.block, self.Mx
        AMAX, limit = self.AMAX, self.limit
        sh, low = self.age_shift, self.low_mask
        cull = self.tau is not None
        tau = self.tau
        a = 1
        r = self.pack(1, code, data)
        it = 0
        acc = 0.0
        front = None  # the last record counted into acc, without its age
        while True:
            if a > AMAX:
                return "failed_age"
            if it >= limit:
                return "failed_iter"
            it += 1
            ox, oy = O[a - 1]
            sx = (px + ox) % Hx
            sy = (py + oy) % Hy
            s = sx + sy * Hx
            old = T[s]                   # atomicMax(T[s], r)
            if r > old:
                T[s] = r
            if old == r:
                return "duplicate"
            if old < r:                  # placed r
                m = px // B + (py // B) * Mx
                if M[m] < a:             # atomicMax(M[cell(p)], a)
                    M[m] = a
                if old == 0:
                    return "stored"
                oa = old >> sh
                if cull and oa == a:
                    # same pixel: keep acc and a, the evicted record is tried
                    # once more at the same slot.
                    r = old
                    continue
                acc = 0.0
                front = None
                a = oa
                r = old
                ox, oy = O[a - 1]
                px = (sx - ox) % Hx
                py = (sy - oy) % Hy
            elif cull and (old >> sh) == a:
                # One call alone meets its pixel's front records in strictly
                # decreasing order, so the kernels' rule against counting a
                # record twice under concurrency (ha_front_is_new) never
                # leaves one out here.
                assert front is None or (old & low) < front, (px, py, old, front)
                front = old & low
                alpha = f32((old & 255) / 255.0)
                acc = f32(acc + f32(f32(1.0 - acc) * alpha))
                if acc > tau:
                    return "culled"
            a += 1
            r = (r & low) | (a << sh)

    # -- traversal (SPEC section 7) --------------------------------------
    def traverse(self, x, y):
        """Records of pixel (x, y), in traversal (front-to-back) order."""
        out = []
        amax = self.M[self.cell(x, y)]
        sh = self.age_shift
        for a in range(1, amax + 1):
            r = self.T[self.probe(x, y, a)]
            ra = r >> sh
            if ra == a:
                out.append(r)
            elif ra < a:
                break
        return out

    def lists(self):
        """Rows (x, y, rank, code, rgba) of the list CSV, row-major."""
        rows = []
        for y in range(self.Vy):
            for x in range(self.Vx):
                for k, r in enumerate(self.traverse(x, y)):
                    rows.append((x, y, k, self.code(r), self.data(r)))
        return rows

    def table_rows(self):
        return [(s, r) for s, r in enumerate(self.T) if r != 0]

    def maxage_rows(self):
        return [(cx, cy, self.M[cx + cy * self.Mx])
                for cy in range(self.My) for cx in range(self.Mx)]

    def stats(self):
        return dict(self.counters)

    # -- file text, in the interchange formats ---------------------------
    def lists_csv(self):
        return "x,y,rank,code,rgba\n" + "".join(
            "%d,%d,%d,%d,%d\n" % row for row in self.lists())

    def table_csv(self):
        w = 16 if self.layout == 64 else 8
        return "slot,record\n" + "".join(
            "%d,0x%0*x\n" % (s, w, r) for s, r in self.table_rows())

    def maxage_csv(self):
        return "cx,cy,max_age\n" + "".join(
            "%d,%d,%d\n" % row for row in self.maxage_rows())


# ---------------------------------------------------------------------------
# Self-test
# ---------------------------------------------------------------------------

def _random_stream(rng, Vx, Vy, n, with_bad=True):
    frags = []
    levels = [rng.random() for _ in range(rng.randint(1, 6))]
    for _ in range(n):
        x, y = rng.randrange(Vx), rng.randrange(Vy)
        u = rng.random()
        if u < 0.3:
            t = rng.choice(levels)
        else:
            t = rng.random()
        frags.append((x, y, t, rng.getrandbits(32)))
    # exact duplicates and equal-depth / different-colour copies
    for _ in range(n // 10 + 1):
        if frags:
            frags.append(rng.choice(frags))
            x, y, t, d = rng.choice(frags)
            frags.append((x, y, t, rng.getrandbits(32)))
    if with_bad:
        for t in (float("nan"), -0.5, 1.5, 1e-40, 0.0, 1.0, -0.0,
                  1.0000000001, 1.0000001, -1e-50):
            frags.append((rng.randrange(Vx), rng.randrange(Vy), t,
                          rng.getrandbits(32)))
    rng.shuffle(frags)
    return frags


def _check_model(m, frags, label):
    """Invariants of SPEC section 11 on a finished model. Returns failure
    flags (any_failure, failed_iter)."""
    c = m.counters
    assert c["fragments"] == len(frags), label
    nonempty = sum(1 for v in m.T if v)
    assert c["stored"] == nonempty, (label, c, nonempty)
    assert c["stored"] == (c["fragments"] - c["invalid"] - c["duplicates"]
                           - c["culled"] - c["failed_age"]
                           - c["failed_iter"]), (label, c)
    # invariant 2: every stored record found by traversal of its own pixel,
    # exactly once; invariant 3 (sorted) always.
    seen = {}
    for y in range(m.Vy):
        for x in range(m.Vx):
            lst = m.traverse(x, y)
            keys = [r & m.low_mask for r in lst]
            assert all(keys[i] > keys[i + 1] for i in range(len(keys) - 1)), \
                (label, "unsorted", x, y, keys)
            for r in lst:
                a = r >> m.age_shift
                s = m.probe(x, y, a)
                assert m.T[s] == r
                assert s not in seen, (label, "found twice", s)
                seen[s] = (x, y)
    assert len(seen) == nonempty, (label, "traversal missed records",
                                   len(seen), nonempty)
    failures = c["failed_age"] + c["failed_iter"]
    if failures == 0 and c["culled"] == 0:
        # invariant 3: lists equal the de-duplicated quantized multiset
        want = {}
        for x, y, t, d in frags:
            code = depth_code(t, m.A)
            if code is None:
                continue
            dd = d if m.layout == 64 else 0
            want.setdefault((x, y), set()).add((code, dd))
        got = {}
        for x, y, k, code, dd in m.lists():
            got.setdefault((x, y), []).append((code, dd))
        for key, vals in want.items():
            exp = sorted(vals, reverse=True)
            assert got.get(key) == exp, (label, key, got.get(key), exp)
        assert set(got) == set(want), label
        assert c["duplicates"] == len(frags) - c["invalid"] - nonempty
    return failures > 0, c["failed_iter"] > 0


def self_test(cases=300, seed=12345, verbose=False):
    rng = random.Random(seed)
    stats = {"cases": 0, "with_failures": 0, "cull": 0, "failed_iter": 0}
    # depth code spot checks (SPEC section 2)
    assert depth_code(0.0, 8) == (1 << 24) - 1
    assert depth_code(-0.0, 8) == (1 << 24) - 1
    assert depth_code(1.0, 8) == 0
    assert depth_code(0.5, 8) == (1 << 23) - 1
    assert depth_code(float("nan"), 8) is None
    assert depth_code(-0.5, 8) is None
    assert depth_code(1.5, 8) is None
    assert depth_code(1.0000000001, 8) == 0          # rounds to 1.0f
    assert depth_code(1.0000001, 8) is None          # rounds above 1.0f
    assert depth_code(-1e-50, 8) == (1 << 24) - 1    # rounds to -0.0f
    assert depth_code(1e-40, 12) == (1 << 20) - 1
    assert depth_code(1e300, 8) is None
    # t = 0.1 as float32 = 0.100000001490116..., * 2^24 = 1677721.625
    assert depth_code(0.1, 8) == (1 << 24) - 1 - 1677721
    # a small hand-traced insertion: 2x1 screen, 2x1 table, 3 ages
    off = [(0, 0), (1, 0), (0, 0)] + [(0, 0)] * 12
    m = HAModel((2, 1), (2, 1), 64, 4, off, block=1)
    m.add_fragment(0, 0, 0.5, 7)      # -> slot 0 age 1
    m.add_fragment(0, 0, 0.25, 9)     # nearer: evicts, old goes age 2 slot 1
    assert m.T[0] >> 60 == 1 and m.code(m.T[0]) == depth_code(0.25, 4)
    assert m.T[1] >> 60 == 2 and m.data(m.T[1]) == 7
    assert m.M == [2, 0]
    assert [r & m.low_mask for r in m.traverse(0, 0)] == \
        [m.T[0] & m.low_mask, m.T[1] & m.low_mask]
    m.add_fragment(0, 0, 0.25, 9)
    assert m.counters["duplicates"] == 1
    # 1x1 table: every age probes the single slot
    m = HAModel((1, 1), (1, 1), 32, 4, [(0, 0)] * 15, block=1)
    for t in (0.1, 0.2, 0.3):
        m.add_fragment(0, 0, t)
    assert m.counters["stored"] == 1 and m.counters["failed_age"] == 2

    for i in range(cases):
        Vx = rng.randint(1, 24)
        Vy = rng.randint(1, 24)
        if rng.random() < 0.15:
            Vx = 1
        elif rng.random() < 0.15:
            Vy = 1
        Hx = rng.randint(Vx, 2 * Vx)
        Hy = rng.randint(Vy, 2 * Vy)
        layout = rng.choice((64, 32))
        A = rng.randint(4, 9)
        B = rng.choice((1, 2, 3, 8))
        limit = rng.choice((DEFAULT_LIMIT, DEFAULT_LIMIT, 50, 8))
        load = rng.uniform(0.05, 1.1)
        n = max(1, int(load * Hx * Hy))
        frags = _random_stream(rng, Vx, Vy, n, with_bad=rng.random() < 0.5)
        offsets = random_offsets(Hx, Hy, A, rng)
        tau = None
        if layout == 64 and rng.random() < 0.25:
            tau = rng.choice((1.0, 0.99, 0.9, 0.5, 0.1))
        label = "case %d V=%dx%d H=%dx%d L%d A=%d B=%d limit=%d tau=%s" % (
            i, Vx, Vy, Hx, Hy, layout, A, B, limit, tau)

        def run(order):
            mm = HAModel((Vx, Vy), (Hx, Hy), layout, A, offsets, B, limit,
                         tau)
            for x, y, t, d in order:
                mm.add_fragment(x, y, t, d)
            return mm

        m1 = run(frags)
        anyfail, fiter = _check_model(m1, frags, label)
        stats["cases"] += 1
        stats["with_failures"] += anyfail
        stats["failed_iter"] += fiter
        if tau is not None:
            stats["cull"] += 1
            continue                 # cull is order dependent
        for _ in range(2):
            sh = frags[:]
            rng.shuffle(sh)
            m2 = run(sh)
            any2, fiter2 = _check_model(m2, sh, label + " (shuffled)")
            if not fiter and not fiter2:
                assert m1.T == m2.T, label + ": table depends on order"
                assert m1.counters["stored"] == m2.counters["stored"]
                assert m1.table_csv() == m2.table_csv()
            if not anyfail and not any2:
                assert m1.M == m2.M, label + ": M depends on order"
                assert m1.lists_csv() == m2.lists_csv()
                assert m1.counters == m2.counters, label
            if not anyfail and not fiter:
                # failed_age alone never changes the table
                pass
        if verbose:
            print(label, m1.counters)
    _check_cull_conservative(rng)
    return stats


def _check_cull_conservative(rng):
    """Invariant 5 flavour: with cull, each pixel's kept list is a superset
    of what is needed: compositing the kept list differs from compositing
    the full list (no cull) by at most (1 - tau) per channel (plus float
    slack), and culled fragments are never in front of kept opacity <= tau.
    """
    for i in range(60):
        Vx, Vy = rng.randint(1, 8), rng.randint(1, 8)
        Hx, Hy = rng.randint(Vx, 2 * Vx), rng.randint(Vy, 2 * Vy)
        A = 8
        offsets = random_offsets(Hx, Hy, A, rng)
        tau = rng.choice((1.0, 0.95, 0.8, 0.5))
        n = int(rng.uniform(0.1, 0.7) * Hx * Hy) + 1
        frags = []
        for _ in range(n):
            a = rng.choice((0, 64, 128, 200, 255, rng.randrange(256)))
            frags.append((rng.randrange(Vx), rng.randrange(Vy), rng.random(),
                          (rng.getrandbits(24) << 8) | a))
        full = HAModel((Vx, Vy), (Hx, Hy), 64, A, offsets, 1)
        cul = HAModel((Vx, Vy), (Hx, Hy), 64, A, offsets, 1, tau=tau)
        for f in frags:
            full.add_fragment(*f)
            cul.add_fragment(*f)
        if full.counters["failed_age"] or cul.counters["failed_age"]:
            continue
        if tau == 1.0:
            assert cul.counters["culled"] == 0
        for y in range(Vy):
            for x in range(Vx):
                kept = [r & cul.low_mask for r in cul.traverse(x, y)]
                allr = [r & full.low_mask for r in full.traverse(x, y)]
                assert set(kept) <= set(allr)
                # all fragments in front of a culled one are kept: kept list
                # is a prefix-closed subset of the full sorted list up to
                # where opacity exceeds tau.
                acc = 0.0
                for r in allr:
                    if r not in kept:
                        assert acc > tau - 1e-6, (x, y, acc, tau)
                    acc = acc + (1 - acc) * ((r & 255) / 255.0)


if __name__ == "__main__":
    import sys
    st = self_test(cases=int(sys.argv[1]) if len(sys.argv) > 1 else 300,
                   verbose="-v" in sys.argv)
    print("ha_model self-test passed: %s" % st)
