#!/usr/bin/env python3
"""Stand-in for `habuffer build-lists` built on ha_model, used only to test
crosscheck.py itself (python3 crosscheck.py --habuffer ./model_habuffer.py).

Accepts the same options as the C++ tool; --threads is ignored (serial).
Set HA_FAKE_BUG to one of: code, order, maxage, stats, tablecase (the
last is harmless: upper-case hex must still be accepted) to inject a
deliberate defect and check that crosscheck.py catches it.
"""

import argparse
import json
import os
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ha_model  # noqa: E402
from ha_model import HAModel  # noqa: E402


def size(s):
    x, y = s.lower().split("x")
    return int(x), int(y)


def die(msg):
    sys.stderr.write("model_habuffer: %s\n" % msg)
    sys.exit(2)


def read_csv(path, header):
    with open(path) as f:
        lines = f.read().splitlines()
    if not lines or lines[0].strip() != header:
        die("%s:1: bad header" % path)
    return [(i, ln.split(",")) for i, ln in enumerate(lines[1:], 2)
            if ln.strip()]


def parse_rgba(v):
    v = v.strip()
    return int(v[2:], 16) if v[:2].lower() == "0x" else int(v, 10)


def main():
    if len(sys.argv) < 2 or sys.argv[1] != "build-lists":
        die("usage: model_habuffer.py build-lists ...")
    ap = argparse.ArgumentParser()
    for o in ("--in", "--out", "--screen", "--table", "--offsets", "--stats",
              "--dump-table", "--dump-max-age"):
        ap.add_argument(o, required=o in ("--in", "--out", "--screen"))
    ap.add_argument("--layout", type=int, default=64)
    ap.add_argument("--age-bits", type=int, default=8)
    ap.add_argument("--block", type=int, default=8)
    ap.add_argument("--threads", type=int, default=1)
    a = ap.parse_args(sys.argv[2:])
    bug = os.environ.get("HA_FAKE_BUG", "")
    V = size(a.screen)
    H = size(a.table) if a.table else V
    offs = [(int(r[0]), int(r[1])) for _, r in read_csv(a.offsets, "ox,oy")]
    frags = []
    for ln, r in read_csv(getattr(a, "in"), "x,y,depth,rgba"):
        try:
            frags.append((int(r[0]), int(r[1]), float(r[2]),
                          parse_rgba(r[3])))
        except (ValueError, IndexError):
            die("%s:%d: bad field" % (getattr(a, "in"), ln))
    if bug == "code":
        # depth coded from the double instead of the float32 value
        def code64(t, age_bits):
            D = 32 - age_bits
            if t != t or t < 0.0 or t > 1.0:
                return None
            return (1 << D) - 1 - min((1 << D) - 1, int(t * (1 << D)))
        ha_model.depth_code = code64
    m = HAModel(V, H, a.layout, a.age_bits, offs, a.block)
    for x, y, t, c in frags:
        m.add_fragment(x, y, t, c)
    if bug == "order" and a.threads == 2:
        # pretend the parallel run lost a race: swap two stored records
        full = [s for s, v in enumerate(m.T) if v]
        if len(full) >= 2:
            i, j = full[0], full[1]
            m.T[i], m.T[j] = m.T[j], m.T[i]
    st = m.stats()
    if bug == "stats":
        st["duplicates"] += 1
        st["stored"] -= 1
    rows = m.lists()
    with open(a.out, "w") as f:
        f.write("x,y,rank,code,rgba\n")
        f.writelines("%d,%d,%d,%d,%d\n" % r for r in rows)
    if a.dump_table:
        txt = m.table_csv()
        if bug == "tablecase":
            txt = txt.upper().replace("SLOT,RECORD", "slot,record") \
                .replace("0X", "0x")
        with open(a.dump_table, "w") as f:
            f.write(txt)
    if a.dump_max_age:
        if bug == "maxage" and m.M:
            m.M[0] += 1
        with open(a.dump_max_age, "w") as f:
            f.write(m.maxage_csv())
    if a.stats:
        with open(a.stats, "w") as f:
            json.dump(st, f)


if __name__ == "__main__":
    main()
