#!/usr/bin/env python3
"""Turns habuffer_bench JSON (--benchmark_out) into the markdown tables of
docs/performance.md: fragments/s vs load for 1 and 2 threads, the ratio of
2 to 1 thread, and the ratio to the atomic-add floor, all from one run."""
import json
import re
import sys


def medians(path):
    data = json.load(open(path))
    out = {}
    for b in data["benchmarks"]:
        if b.get("aggregate_name", "median") != "median":
            continue
        name = re.sub(r"/real_time(_median)?$", "", b["run_name"] if "run_name" in b else b["name"])
        out[name] = b
    return out


def main(path):
    m = medians(path)
    floor = {t: m.get(f"BM_CountFloor/threads:{t}", {}).get("items_per_second") for t in (1, 2)}
    for family in ("BM_InsertCoherent", "BM_InsertCoherentAtomic", "BM_InsertRandom", "BM_InsertRandomAtomic",
                   "BM_InsertCoherentL32"):
        rows = []
        for load in (10, 30, 50, 70, 80, 90, 95):
            one = m.get(f"{family}/load:{load}/threads:1")
            two = m.get(f"{family}/load:{load}/threads:2")
            if not one or not two:
                continue
            a, b = one["items_per_second"], two["items_per_second"]
            rows.append(f"| {load} | {a / 1e6:.1f} | {b / 1e6:.1f} | {b / a:.2f} | "
                        f"{a / floor[1]:.3f} | {b / floor[2]:.3f} |" if floor[1] and floor[2] else
                        f"| {load} | {a / 1e6:.1f} | {b / 1e6:.1f} | {b / a:.2f} | | |")
        if rows:
            print(f"\n{family} (M fragments/s, median of repetitions)\n")
            print("| load % | 1 thread | 2 threads | 2/1 | 1 thread / floor | 2 threads / floor |")
            print("|---|---|---|---|---|---|")
            print("\n".join(rows))
    if floor[1]:
        print(f"\nfloor (one atomic add per fragment): 1 thread {floor[1] / 1e6:.1f} M/s, "
              f"2 threads {floor[2] / 1e6:.1f} M/s, 2/1 = {floor[2] / floor[1]:.2f}")
    for name, b in sorted(m.items()):
        if "Offsets" in name or "Composite" in name:
            unit = b.get("time_unit", "ns")
            print(f"{name}: {b['real_time']:.3g} {unit}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "bench.json")
