#!/usr/bin/env python3
"""Plots the harness's tables and writes docs/results.md.

Usage: plot_results.py RESULTS_DIR MARKDOWN MODE

RESULTS_DIR holds the JSON tables `scripts/reproduce.sh` wrote (sweep-*.json,
bench.json, fig2.json, fig8.json, fig10.json, table1.json, frontier.json,
frontier-picks.json, plan.json; csg-peers.json from habuffer_csg_peers where
OpenCSG is built); the PNG figures are written beside them and
MARKDOWN links them, each captioned with the machine, the renderer and the
command that produced it. Findings are computed from the tables, never typed.
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(directory, name):
    path = os.path.join(directory, name)
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def num(v):
    return float("inf") if v is None else float(v)


def caption(table):
    p = table["provenance"]
    return f"Machine: {p['machine']}. Renderer: {p['renderer']}. Command: `{p['command']}`."


def save(fig, directory, name):
    fig.tight_layout()
    fig.savefig(os.path.join(directory, name), dpi=110)
    plt.close(fig)
    return name


def plot_sweeps(directory, sweeps, rel):
    out = []
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4))
    gather_only = False
    for label, t in sweeps:
        rows = t["rows"]
        loads = [r["load"] for r in rows]
        # Like for like: each technique's cost to sorted lists (its sort pass in);
        # a table from before that column has only the gather, and says so.
        col = "sorted_mfrag_per_s" if "sorted_mfrag_per_s" in rows[0] else "mfrag_per_s"
        if col == "mfrag_per_s":
            gather_only = True
            label += " (gather only)"
        med = [r[col] for r in rows]
        lo = [r[col] - r[col + "_min"] for r in rows]
        hi = [r[col + "_max"] - r[col] for r in rows]
        ax1.errorbar(loads, med, yerr=[lo, hi], marker="o", capsize=3, label=label)
        if "mean_age" in rows[0]:
            ax2.plot(loads, [r["mean_age"] for r in rows], marker="o", label=label + " mean")
            ax2.plot(loads, [r["max_age"] for r in rows], marker="x", linestyle="--", label=label + " max")
    ax1.set_xlabel("load factor")
    ax1.set_ylabel("M fragments / s (median, min-max)" if gather_only else "M fragments to sorted lists / s (median, min-max)")
    ax1.set_title("Throughput to sorted lists vs load (seed 000 Fig. 5)" if not gather_only
                  else "Throughput vs load (seed 000 Fig. 5; some curves gather only)")
    ax1.legend(fontsize=7)
    ax2.set_xlabel("load factor")
    ax2.set_ylabel("age")
    ax2.set_title("HA-buffer ages vs load")
    ax2.legend(fontsize=7)
    name = save(fig, directory, "sweep.png")
    out.append(f"![throughput and age vs load]({rel}/{name})")
    out.append("")
    out.append("Throughput counts each technique's whole cost to sorted lists: the gather plus a separate sort pass "
               "where it has one (lists and arrays on the GPU path; the CPU containers sort in their gather). "
               "Curves marked \"gather only\" leave that sort pass out.")
    out.append("")
    for label, t in sweeps:
        out.append(f"- {label}: {caption(t)}")
    return out


def throughput_drop(t):
    rows = t["rows"]
    best = None
    for a, b in zip(rows, rows[1:]):
        if a["mfrag_per_s"] > 0:
            drop = 1.0 - b["mfrag_per_s"] / a["mfrag_per_s"]
            if best is None or drop > best[0]:
                best = (drop, a["load"], b["load"], a["mfrag_per_s"], b["mfrag_per_s"])
    return best


def plot_fig2(directory, t, rel):
    rows = t["rows"]
    opac = sorted({r["opacity"] for r in rows})
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4))
    width = 0.35
    for i, cull in enumerate(["off", next((r["early_cull"] for r in rows if r["early_cull"] != "off"), "off")]):
        sel = [next(r for r in rows if r["opacity"] == o and r["early_cull"] == cull) for o in opac]
        xs = [j + (i - 0.5) * width for j in range(len(opac))]
        ax1.bar(xs, [r["stored"] for r in sel], width, label=f"cull {cull}")
        ax2.plot(range(len(opac)), [r["gather_ms"] for r in sel], marker="o", label=f"gather ms, cull {cull}")
        ax2.plot(range(len(opac)), [r["fill_rate_mfrag_per_s"] for r in sel], marker="x", linestyle="--",
                 label=f"fill rate Mfrag/s, cull {cull}")
    for ax in (ax1, ax2):
        ax.set_xticks(range(len(opac)))
        ax.set_xticklabels([str(o) for o in opac])
        ax.set_xlabel("opacity")
        ax.legend(fontsize=7)
    ax1.set_ylabel("stored fragments")
    ax1.set_title("Early cull vs opacity (seed 000 Fig. 2)")
    ax2.set_title("Time and fill rate")
    name = save(fig, directory, "fig2.png")
    return [f"![Fig. 2]({rel}/{name})", "", caption(t)]


def plot_fig8(directory, t, rel):
    rows = t["rows"]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4))
    for cull in sorted({r["early_cull"] for r in rows}):
        sel = [r for r in rows if r["early_cull"] == cull]
        ax1.plot([r["frame"] for r in sel], [r["gather_ms"] for r in sel], marker="o", label=f"cull {cull}")
        ax2.plot([r["frame"] for r in sel], [r["max_age"] for r in sel], marker="o", label=f"cull {cull}")
    ax1.set_xlabel("frame (spread 1 to 0)")
    ax1.set_ylabel("gather ms")
    ax1.set_title("Stress test (seed 000 Fig. 8): time")
    ax2.set_xlabel("frame (spread 1 to 0)")
    ax2.set_ylabel("max age")
    ax2.set_title("max age per frame")
    ax1.legend()
    ax2.legend()
    name = save(fig, directory, "fig8.png")
    return [f"![Fig. 8]({rel}/{name})", "", caption(t)]


def plot_fig10(directory, t, rel):
    rows = t["rows"]
    techs = list(dict.fromkeys(r["technique"] for r in rows))
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4))
    width = 0.8 / len(scenes)
    for i, s in enumerate(scenes):
        sel = [next(r for r in rows if r["scene"] == s and r["technique"] == tech) for tech in techs]
        xs = [j + i * width for j in range(len(techs))]
        ax1.bar(xs, [r["gather_ms"] for r in sel], width, label=s)
        ax2.bar(xs, [r["stored"] for r in sel], width, label=s)
    for ax in (ax1, ax2):
        ax.set_xticks([j + width * (len(scenes) - 1) / 2 for j in range(len(techs))])
        ax.set_xticklabels(techs, rotation=30, ha="right", fontsize=7)
        ax.legend(fontsize=7)
    ax1.set_ylabel("gather ms")
    ax1.set_title("Planes front vs back (seed 001 Fig. 10)")
    ax2.set_ylabel("stored fragments")
    name = save(fig, directory, "fig10.png")
    return [f"![Fig. 10]({rel}/{name})", "", caption(t)]


def memory_table(t):
    out = ["| technique | fragments | paper formula MiB | paper's Table 1 MiB | our model MiB | allocated MiB |",
           "|---|---|---|---|---|---|"]
    for r in t["rows"]:
        def f(k):
            v = r.get(k)
            return "" if v is None else f"{v:.1f}"
        out.append(f"| {r['technique']} | {r['fragments']} | {f('paper_formula_mib')} | {f('paper_table_mib')} | "
                   f"{f('model_mib')} | {f('allocated_mib')} |")
    out += ["", caption(t)]
    return out


def plot_frontier(directory, t, rel):
    rows = t["rows"]
    groups = list(dict.fromkeys((r["scene"], r["size"]) for r in rows))
    fig, axes = plt.subplots(len(groups), 2, figsize=(12, 4 * len(groups)), squeeze=False)
    for gi, (scene, size) in enumerate(groups):
        sel = [r for r in rows if r["scene"] == scene and r["size"] == size]
        finite = [num(r["psnr"]) for r in sel if math.isfinite(num(r["psnr"]))]
        exact_at = (max(finite) if finite else 60.0) + 10.0
        for col, (cost, mark, label) in enumerate([("total_ms", "pareto_time", "total ms"),
                                                   ("memory_bytes", "pareto_memory", "memory MiB")]):
            ax = axes[gi][col]
            for r in sel:
                x = r[cost] / (1 << 20) if cost == "memory_bytes" else r[cost]
                y = num(r["psnr"]) if math.isfinite(num(r["psnr"])) else exact_at
                on = r.get(mark)
                on3 = r.get("pareto_3d")  # on the (time, memory, psnr) front though not on this one
                ax.scatter([x], [y], c="tab:red" if on else "tab:orange" if on3 else "tab:gray", s=40 if on or on3 else 15)
                if on:
                    ax.annotate(r["technique"], (x, y), fontsize=6, xytext=(3, 3), textcoords="offset points")
            ax.axhline(exact_at, color="k", linewidth=0.5, linestyle=":")
            ax.set_xscale("log")
            ax.set_xlabel(label + " (log)")
            ax.set_ylabel(f"PSNR dB (exact drawn at {exact_at:.0f})")
            ax.set_title(f"{scene} {size}: Pareto-optimal in red (orange: in time, memory and psnr)", fontsize=9)
    name = save(fig, directory, "frontier.png")
    return [f"![frontier]({rel}/{name})", "", caption(t)]


def csg_peers_section(directory, t, rel, findings):
    """The CSG curve: habuffer beside OpenCSG (habuffer_csg_peers), time and
    pixels wrong against the ray caster, per cylinder count and method."""
    rows = t["rows"]
    methods = []
    for r in rows:
        if r["method"] not in methods:
            methods.append(r["method"])
    workloads = []
    for r in rows:
        if r["workload"] not in workloads:
            workloads.append(r["workload"])
    cell = {(r["workload"], r["method"]): r for r in rows}
    out = ["Each cell: median ms of one render (to glFinish) / pixels whose visible primitive differs from the ray "
           "caster outside its edge band (of " + str(rows[0]["pixels"]) + "). Every primitive is convex; OpenCSG "
           "renders the expression's sum of products on the same EGL context (compatibility profile).", "",
           "| workload | " + " | ".join(methods) + " |", "|---|" + "---|" * len(methods)]
    for w in workloads:
        out.append(f"| {w} | " + " | ".join(
            f"{cell[(w, m)]['ms']:.1f} / {cell[(w, m)]['mismatches']}" if (w, m) in cell else "" for m in methods) + " |")
    fig, ax = plt.subplots(figsize=(6.5, 4))
    for m in methods:
        pts = [(r["cylinders"], r["ms"], r["mismatches"]) for r in rows if r["method"] == m and r["cylinders"] > 0]
        pts.sort()
        ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", label=m,
                linestyle="-" if all(p[2] == 0 for p in pts) else "--")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("cylinders subtracted from the cube")
    ax.set_ylabel("ms per render (median)")
    ax.set_title("CSG: habuffer vs OpenCSG (dashed: pixels wrong)")
    ax.legend(fontsize=7)
    name = save(fig, directory, "csg-peers.png")
    out += ["", f"![CSG peers]({rel}/{name})", "", caption(t)]
    exact = "opencsg-goldfeather+occlusion"
    curve = sorted({r["cylinders"] for r in rows if r["cylinders"] > 0})
    faster = [n for n in curve if (f"cube - {n} cylinders", exact) in cell
              and cell[(f"cube - {n} cylinders", "habuffer-ha")]["ms"] < cell[(f"cube - {n} cylinders", exact)]["ms"]]
    if faster:
        top = curve[-1]
        ratio = cell[(f"cube - {top} cylinders", exact)]["ms"] / cell[(f"cube - {top} cylinders", "habuffer-ha")]["ms"]
        findings.append(f"csg: habuffer's CSG is faster than OpenCSG's exact method ({exact}) from {faster[0]} "
                        f"cylinders on ({ratio:.1f}x at {top}); below that OpenCSG is faster.")
    for m in methods:
        wrong = [n for n in curve if cell.get((f"cube - {n} cylinders", m), {}).get("mismatches", 0) > 0]
        if wrong:
            findings.append(f"csg: {m} draws pixels the ray caster disagrees with from {wrong[0]} cylinders on "
                            f"(up to {max(cell[(f'cube - {n} cylinders', m)]['mismatches'] for n in wrong)}).")
    return out


def plan_errors(plan, frontier):
    scene, size = plan["notes"].get("scene"), plan["notes"].get("size")
    measured = {r["technique"]: r for r in frontier["rows"] if r["scene"] == scene and r["size"] == size}
    out = []
    for p in plan["rows"]:
        m = measured.get(p["technique"])
        if not m:
            continue
        if p.get("predicted_max_age") is not None and m.get("max_age") is not None:
            out.append((p["technique"], "max age", p["predicted_max_age"], m["max_age"]))
        if p.get("predicted_psnr") is not None and m.get("psnr") is not None and math.isfinite(num(p["predicted_psnr"])):
            out.append((p["technique"], "psnr dB", p["predicted_psnr"], m["psnr"]))
        out.append((p["technique"], "memory MiB", p["memory_bytes"] / (1 << 20), m["memory_model_bytes"] / (1 << 20)))
    return out


def main():
    directory, markdown, mode = sys.argv[1], sys.argv[2], sys.argv[3]
    rel = os.path.relpath(directory, os.path.dirname(os.path.abspath(markdown)))
    md = ["# Results", "",
          f"Regenerated by `scripts/reproduce.sh{' --quick' if mode == 'quick' else ''}` ({mode} sizes); the tables "
          f"(JSON and CSV) and figures are in `{os.path.relpath(directory, os.path.dirname(os.path.abspath(markdown)) + '/..')}`. "
          "Every number below is read from those tables. Timings come from one run on the machine named under each "
          "figure; compare only within a figure (this VM drifts 20-40% between runs).", ""]
    findings = []
    sweeps = []
    for name in sorted(os.listdir(directory)):
        if name.startswith("sweep-") and name.endswith(".json"):
            sweeps.append((name[len("sweep-"):-len(".json")], load(directory, name)))
    if sweeps:
        md += ["## Throughput and age vs load", ""] + plot_sweeps(directory, sweeps, rel) + [""]
        for label, t in sweeps:
            d = throughput_drop(t)
            if d:
                findings.append(f"{label}: the largest throughput drop between consecutive loads is "
                                f"{100 * d[0]:.0f}% from load {d[1]} ({d[3]:.2f} Mfrag/s) to {d[2]} ({d[4]:.2f} Mfrag/s).")
    for key, title, fn in [("fig2.json", "Early cull vs opacity (Fig. 2)", plot_fig2),
                           ("fig8.json", "Stress test (Fig. 8)", plot_fig8),
                           ("fig10.json", "Planes front vs back, saturation (seed 001 Fig. 10)", plot_fig10)]:
        t = load(directory, key)
        if t:
            md += [f"## {title}", ""] + fn(directory, t, rel) + [""]
    t1 = load(directory, "table1.json")
    if t1:
        md += ["## Memory (Table 1)", ""] + memory_table(t1) + [""]
    bench = load(directory, "bench.json")
    if bench:
        md += ["## Techniques x scenes (bench)", "",
               "| technique | scene | path | gather ms | resolve ms | MiB | B/frag | dropped | psnr | x atomic floor | x blend floor |",
               "|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in bench["rows"]:
            psnr = "exact" if r["psnr"] is None else f"{r['psnr']:.1f}"
            md.append(f"| {r['technique']} | {r['scene']} {r['size']} | {r['path']} | {r['gather_ms']:.2f} | "
                      f"{r['resolve_ms']:.2f} | {r['memory_bytes'] / (1 << 20):.2f} | {r['bytes_per_fragment']:.1f} | "
                      f"{r['failures']} | {psnr} | {r.get('gather_vs_atomic_floor', 0):.1f} | "
                      f"{r.get('total_vs_blend_floor', 0):.1f} |")
        md += ["", caption(bench), ""]
    frontier = load(directory, "frontier.json")
    if frontier:
        md += ["## Speed-accuracy frontier", ""] + plot_frontier(directory, frontier, rel) + [""]
        picks = load(directory, "frontier-picks.json")
        if picks:
            md += ["| scene | target dB | budget B/frag | fastest reaching it within the budget | total ms | MiB | B/frag | psnr |",
                   "|---|---|---|---|---|---|---|---|"]
            for r in picks["rows"]:
                budget = r.get("memory_budget")
                budget = "none" if budget is None or not math.isfinite(num(budget)) else f"{budget:g}"
                tech = r.get("technique", "none")
                if tech == "none":
                    md.append(f"| {r['scene']} {r['size']} | {r['target_psnr']:.0f} | {budget} | none | | | | |")
                    continue
                psnr = "exact" if r.get("psnr", 0) is None else f"{r.get('psnr', float('nan')):.1f}"
                md.append(f"| {r['scene']} {r['size']} | {r['target_psnr']:.0f} | {budget} | {tech} | "
                          f"{r['total_ms']:.2f} | {r['memory_bytes'] / (1 << 20):.2f} | "
                          f"{r.get('bytes_per_fragment', float('nan')):.1f} | {psnr} |")
                findings.append(f"{r['scene']} {r['size']}: the fastest configuration reaching {r['target_psnr']:.0f} dB "
                                + (f"within {budget} bytes per fragment " if budget != "none" else "")
                                + f"is {tech} ({r['total_ms']:.2f} ms).")
            md += [""]
    peers = load(directory, "csg-peers.json")
    if peers:
        md += ["## CSG beside OpenCSG (a cube minus N cylinders, nested differences)", ""] + \
              csg_peers_section(directory, peers, rel, findings) + [""]
    plan = load(directory, "plan.json")
    if plan:
        md += ["## Plan vs measured", "",
               f"`habuffer plan` recommends **{plan['notes']['recommendation']}** ({plan['notes']['fragments']} fragments, "
               f"depth complexity up to {plan['notes']['max_depth_complexity']}). Model: {plan['notes']['model']}", ""]
        if frontier:
            errs = plan_errors(plan, frontier)
            md += [f"Measured: the frontier's rows of {plan['notes'].get('scene')} at {plan['notes'].get('size')} "
                   "(fixed arrays on several threads keep the first K to arrive in a racy order, which the plan "
                   "models as stream order).", "",
                   "| configuration | quantity | predicted | measured (frontier run) | error |", "|---|---|---|---|---|"]
            worst = {}
            for tech, q, p, m in errs:
                if m is None or p is None:
                    continue
                if q == "psnr dB" and p >= 60 and m >= 60:
                    # Above about 60 dB the measured image differs from the reference by float rounding alone.
                    md.append(f"| {tech} | {q} | {p:.2f} | {m:.2f} | both above 60 dB (float rounding) |")
                    continue
                e = (p - m) / m if m else 0.0
                md.append(f"| {tech} | {q} | {p:.2f} | {m:.2f} | {100 * e:+.1f}% |")
                worst[q] = max(worst.get(q, 0.0), abs(e))
            for q, w in worst.items():
                findings.append(f"plan vs measured: the largest {q} error is {100 * w:.1f}%.")
        md += ["", caption(plan), ""]
    md[4:4] = ["## Findings", ""] + [f"- {f}" for f in findings] + [""]
    with open(markdown, "w") as f:
        f.write("\n".join(md) + "\n")
    print(f"plot_results: wrote {markdown} and the figures in {directory}")


if __name__ == "__main__":
    main()
