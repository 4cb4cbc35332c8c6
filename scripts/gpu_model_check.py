#!/usr/bin/env python3
"""The GPU traffic model against measurements (issue 36, part 7).

Usage: scripts/gpu_model_check.py MODEL.json[,MODEL.json...] [MEASURED.json ...] [--fit SIZE] [--alias MODEL_SCENE SCENE ...]

MODEL.json: `habuffer bench --model gpu` tables (their model_* columns).
MEASURED.json: tables of measured times (e.g. docs/results/techniques-h100-*.json),
matched by (technique, scene, size); none given: MODEL.json's own total_ms
(a bench run with --path gl --model gpu on a GPU).
--fit SIZE: refit the model's fitted constants (per pass, gather and
resolve apart: a pass, a warp memory instruction) on the rows of SIZE
(non-negative least squares on relative error of gather_ms and resolve_ms;
the sector cost stays HBM3's a priori 3.35 TB/s) and evaluate every row
with them (rows of other sizes held out);
without it the model_total_ms the bench wrote (GpuCostModel::h100()).
--alias: a model row of scene MODEL_SCENE stands for the measured SCENE
(the planes of 32 layers at 512x512 exceed llvmpipe's capture, so the model
replays 31).

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


def counts(r, passes, key):
    return sum(float(r.get(f"model_{p}_{key}", 0) or 0) for p in passes)


GATHER, RESOLVE = ("gather",), ("sort", "resolve")


def fit_pass(rows, measured, passes):
    """Non-negative (ms per pass, ns per warp memory instruction) minimising relative error, sectors a priori."""
    import numpy as np  # only the fit needs numpy and scipy (a GPU machine may lack them)
    from scipy.optimize import nnls
    a = np.array([[1.0, counts(r, passes, "instructions")] for r in rows])
    y = np.array(measured) * 1e6  # ns
    sectors = np.array([counts(r, passes, "sectors") for r in rows])
    w = 1.0 / y
    x, _ = nnls(a * w[:, None], (y - sectors * SECTOR_NS) * w)
    return x[0] * 1e-6, x[1]


def fit(pairs):
    """The cost model's four fitted constants: gather_ms and resolve_ms fitted apart."""
    g = fit_pass([r for r, _ in pairs], [m["gather_ms"] for _, m in pairs], GATHER)
    v = fit_pass([r for r, _ in pairs], [m["resolve_ms"] for _, m in pairs], RESOLVE)
    return {"gather_frame_ms": g[0], "gather_instruction_ns": g[1], "resolve_frame_ms": v[0],
            "resolve_instruction_ns": v[1], "sector_ns": SECTOR_NS}


def predict(r, c):
    gather = c["gather_frame_ms"] + (c["gather_instruction_ns"] * counts(r, GATHER, "instructions") +
                                     c["sector_ns"] * counts(r, GATHER, "sectors")) * 1e-6
    resolve = c["resolve_frame_ms"] + (c["resolve_instruction_ns"] * counts(r, RESOLVE, "instructions") +
                                       c["sector_ns"] * counts(r, RESOLVE, "sectors")) * 1e-6
    return gather + resolve


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
    alias = {}
    while "--alias" in argv:
        i = argv.index("--alias")
        if i + 2 >= len(argv):
            sys.exit("gpu_model_check: --alias takes two scenes: MODEL_SCENE SCENE")
        alias[argv[i + 1]] = argv[i + 2]
        argv = argv[:i] + argv[i + 3:]
    if not argv:
        sys.exit(__doc__)
    model = [dict(r, scene=alias.get(r["scene"], r["scene"])) for path in argv[0].split(",") for r in rows_of(path)
             if "model_gather_sectors" in r]
    if not model:
        sys.exit(f"gpu_model_check: {argv[0]} has no model_* columns (run bench with --model gpu)")
    measured = {}
    for path in argv[1:] or argv[0].split(","):
        for r in rows_of(path):
            measured[(r["technique"], r["scene"], r["size"])] = r
    pairs = [(r, measured[(r["technique"], r["scene"], r["size"])]) for r in model
             if (r["technique"], r["scene"], r["size"]) in measured]
    if not pairs:
        sys.exit("gpu_model_check: no row of the model matches a measured row (technique, scene, size)")
    if fit_size:
        train = [(r, m) for r, m in pairs if r["size"] == fit_size]
        if len(train) < 4:
            sys.exit(f"gpu_model_check: {len(train)} rows of size {fit_size} to fit 2 constants a pass: too few")
        c = fit(train)
        print(f"constants fitted on {len(train)} rows of {fit_size} (other sizes held out): " +
              ", ".join(f"{k} {v:.4g}" for k, v in c.items()))
        model_ms = lambda r: predict(r, c)
    else:
        print("constants: the bench's model_total_ms (GpuCostModel::h100())")
        model_ms = lambda r: r["model_total_ms"]
    groups = {}
    for r, m in pairs:
        groups.setdefault((r["size"], r["scene"]), []).append((r["technique"], model_ms(r), m["total_ms"]))
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
