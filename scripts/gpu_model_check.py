#!/usr/bin/env python3
"""The GPU traffic model against measurements (issue 36, part 7).

Usage: scripts/gpu_model_check.py MODEL.json [MEASURED.json ...] [--fit SIZE]

MODEL.json: a `habuffer bench --model gpu` table (its model_* columns).
MEASURED.json: tables of measured times (e.g. docs/results/techniques-h100-*.json),
matched by (technique, scene, size); none given: MODEL.json's own total_ms
(a bench run with --path gl --model gpu on a GPU).
--fit SIZE: refit the model's constants on the rows of SIZE (non-negative
least squares on relative error; the sector cost stays HBM3's a priori
3.35 TB/s) and evaluate every row with them (rows of other sizes held out);
without it the model_total_ms the bench wrote (GpuCostModel::h100()).

Prints, per scene and size, the model's and the measured time of each
technique, Spearman's rank correlation between them, and the HA-buffer's
ratio to lists, measured and predicted, with the prediction's error.
"""
import json
import math
import sys

SECTOR_NS = 32.0 / 3350.0  # 32 bytes at 3.35 TB/s (H100 SXM HBM3)
PASSES = ("gather", "sort", "resolve")


def rows_of(path):
    with open(path) as f:
        return json.load(f)["rows"]


def features(r):
    """Per row: gathered fragments, then sectors, atomics, conflicts and chain links over the three passes."""
    s = lambda k: sum(float(r.get(f"model_{p}_{k}", 0) or 0) for p in PASSES)
    return [float(r["fragments"]), s("sectors"), s("atomics"), s("conflicts"), s("chain")]


def fit(rows, measured):
    """Non-negative fragment, atomic, conflict and chain costs (ns) minimising relative error, sectors a priori."""
    import numpy as np  # only the fit needs numpy and scipy (a GPU machine may lack them)
    from scipy.optimize import nnls
    a = np.array([features(r) for r in rows])
    y = np.array(measured) * 1e6  # ns
    base = a[:, 1] * SECTOR_NS
    w = 1.0 / y
    x, _ = nnls((a[:, [0, 2, 3, 4]] * w[:, None]), (y - base) * w)
    return {"fragment_ns": x[0], "sector_ns": SECTOR_NS, "atomic_ns": x[1], "conflict_ns": x[2], "chain_ns": x[3]}


def predict(r, c):
    f = features(r)
    return (c["fragment_ns"] * f[0] + c["sector_ns"] * f[1] + c["atomic_ns"] * f[2] + c["conflict_ns"] * f[3] +
            c["chain_ns"] * f[4]) * 1e-6


def ranks(v):
    order = sorted(range(len(v)), key=lambda i: v[i])
    r = [0.0] * len(v)
    i = 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and v[order[j + 1]] == v[order[i]]:
            j += 1
        for k in range(i, j + 1):
            r[order[k]] = (i + j) / 2.0 + 1
        i = j + 1
    return r


def spearman(a, b):
    """Pearson's correlation of the ranks (ties averaged); nan for fewer than two distinct values."""
    ra, rb = ranks(a), ranks(b)
    ma, mb = sum(ra) / len(ra), sum(rb) / len(rb)
    sab = sum((x - ma) * (y - mb) for x, y in zip(ra, rb))
    saa = sum((x - ma) ** 2 for x in ra)
    sbb = sum((y - mb) ** 2 for y in rb)
    return sab / math.sqrt(saa * sbb) if saa > 0 and sbb > 0 else float("nan")


def main(argv):
    fit_size = None
    if "--fit" in argv:
        i = argv.index("--fit")
        fit_size = argv[i + 1]
        argv = argv[:i] + argv[i + 2:]
    if not argv:
        sys.exit(__doc__)
    model = [r for r in rows_of(argv[0]) if "model_gather_sectors" in r]
    if not model:
        sys.exit(f"gpu_model_check: {argv[0]} has no model_* columns (run bench with --model gpu)")
    measured = {}
    for path in argv[1:] or [argv[0]]:
        for r in rows_of(path):
            measured[(r["technique"], r["scene"], r["size"])] = r["total_ms"]
    pairs = [(r, measured[(r["technique"], r["scene"], r["size"])]) for r in model
             if (r["technique"], r["scene"], r["size"]) in measured]
    if not pairs:
        sys.exit("gpu_model_check: no row of the model matches a measured row (technique, scene, size)")
    if fit_size:
        train = [(r, m) for r, m in pairs if r["size"] == fit_size]
        if len(train) < 5:
            sys.exit(f"gpu_model_check: {len(train)} rows of size {fit_size} to fit 4 constants: too few")
        c = fit([r for r, _ in train], [m for _, m in train])
        print(f"constants fitted on {len(train)} rows of {fit_size} (other sizes held out): " +
              ", ".join(f"{k} {v:.4g}" for k, v in c.items()))
        model_ms = lambda r: predict(r, c)
    else:
        print("constants: the bench's model_total_ms (GpuCostModel::h100())")
        model_ms = lambda r: r["model_total_ms"]
    groups = {}
    for r, m in pairs:
        groups.setdefault((r["size"], r["scene"]), []).append((r["technique"], model_ms(r), m))
    print("| size | scene | techniques | Spearman | HA / lists measured | model | error |")
    print("|---|---|---|---|---|---|---|")
    rhos, errors = [], []
    for (size, scene), g in sorted(groups.items()):
        rho = spearman([x[1] for x in g], [x[2] for x in g])
        rhos.append(rho)
        t = {x[0]: x for x in g}
        ratio = ""
        if "ha" in t and "lists" in t:
            mr, pr = t["ha"][2] / t["lists"][2], t["ha"][1] / t["lists"][1]
            errors.append(pr / mr - 1)
            ratio = f"{mr:.2f} | {pr:.2f} | {100 * (pr / mr - 1):+.0f} %"
        else:
            ratio = "| |"
        print(f"| {size} | {scene} | {len(g)} | {rho:.2f} | {ratio} |")
    finite = [x for x in rhos if not math.isnan(x)]
    print(f"mean Spearman {sum(finite) / max(len(finite), 1):.2f} over {len(finite)} scene-size groups")
    print("| size | scene | technique | model ms | measured ms |")
    print("|---|---|---|---|---|")
    for (size, scene), g in sorted(groups.items()):
        for tech, p, m in g:
            print(f"| {size} | {scene} | {tech} | {p:.2f} | {m:.2f} |")


if __name__ == "__main__":
    main(sys.argv[1:])
