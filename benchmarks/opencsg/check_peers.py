#!/usr/bin/env python3
"""habuffer_csg_peers on a small curve: it runs, writes its table, and the
two exact methods (habuffer's HA-buffer, OpenCSG's Goldfeather with
occlusion queries) match the ray caster outside the edge band on every row.

usage: check_peers.py PEERS_EXE --workdir DIR
"""
import csv
import os
import subprocess
import sys


def main():
    exe, work = sys.argv[1], sys.argv[sys.argv.index("--workdir") + 1]
    os.makedirs(work, exist_ok=True)
    out = os.path.join(work, "peers.csv")
    r = subprocess.run([exe, "--cylinders", "1,4,16", "--size", "64x64", "--repeats", "1", "--out", out],
                       capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        raise SystemExit("habuffer_csg_peers failed (%d): %s" % (r.returncode, r.stderr))
    with open(out) as f:
        rows = list(csv.DictReader(f))
    methods = {row["method"] for row in rows}
    want = {"habuffer-ha", "opencsg-goldfeather+occlusion", "opencsg-goldfeather+convexity", "opencsg-scs+occlusion"}
    if methods != want or len(rows) != 4 * 4:
        raise SystemExit("the table has methods %s and %d rows, not %s x 4 workloads" % (sorted(methods), len(rows), sorted(want)))
    for row in rows:
        if row["method"] in ("habuffer-ha", "opencsg-goldfeather+occlusion") and int(row["mismatches"]) != 0:
            raise SystemExit("%s on %s: %s mismatching pixels" % (row["method"], row["workload"], row["mismatches"]))
        if not float(row["ms"]) > 0:
            raise SystemExit("%s on %s: no time" % (row["method"], row["workload"]))
    bad = usage_refused(exe)
    if bad:
        raise SystemExit(bad)
    print("csg peers: %d rows, the exact methods match the ray caster" % len(rows))


def usage_refused(exe):
    for args, named in ((["--cylinders", "0"], "--cylinders"), (["--size", "9x"], "--size"), (["--frobnicate", "1"], "--frobnicate")):
        r = subprocess.run([exe, *args], capture_output=True, text=True, timeout=60)
        if r.returncode != 2 or named not in r.stderr.splitlines()[0]:
            return "%s: exit %d, %r (want 2 naming %s)" % (" ".join(args), r.returncode, r.stderr, named)
    return ""


if __name__ == "__main__":
    main()
