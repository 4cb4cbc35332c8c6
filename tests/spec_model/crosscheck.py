#!/usr/bin/env python3
"""Cross-check `habuffer build-lists` against the independent Python model.

usage: python3 crosscheck.py --habuffer PATH/TO/habuffer [--cases N]
                             [--seed S] [--workdir DIR] [--case K] [--keep]
                             [--gl-every N]

For every case a seeded random configuration and fragment stream are written
to the work directory, `habuffer build-lists` is run twice (file order, and
shuffled rows with 2 threads) and the outputs are compared with each other and
with ha_model.HAModel. When the model loses nothing, a third run builds the
shuffled stream with linked lists or fixed arrays (alternating; from a pool
of 3 nodes or 2 layers, grown by --lossless) on the shuffled run's path, and
its lists and counters must be the model's too. A failing case prints one line with the command that
reproduces it; its files stay in the work directory. The last line is
`crosscheck: N passed, M failed`; the exit status is non-zero on any failure.
"""

import argparse
import json
import math
import os
import random
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ha_model  # noqa: E402
from ha_model import HAModel, f32  # noqa: E402

STAT_KEYS = ("fragments", "stored", "duplicates", "culled", "invalid",
             "failed_age", "failed_iter")


class CaseFailure(Exception):
    pass


# ---------------------------------------------------------------------------
# Case generation
# ---------------------------------------------------------------------------

def _is_f32_midpoint(d):
    """True if the double d lies exactly halfway between two float32 values.

    Only then can 'decimal -> double -> float32' differ from a direct
    'decimal -> float32' conversion of repr(d); such depths are avoided so the
    test does not depend on how the C++ parses the text."""
    if d != d or math.isinf(d):
        return False
    f = f32(d)
    if f == d or math.isinf(f):
        return False
    g = f32(math.nextafter(f, d))
    if g == f:  # d beyond the float32 range on this side
        return False
    # float32 neighbours f and g; their midpoint is exact in double
    return (f + g) / 2.0 == d


def _clean_depth(t):
    while _is_f32_midpoint(t):
        t = math.nextafter(t, 2.0)
    return t


def _colour(rng):
    a = rng.choice((255, 255, 0, 128, rng.randrange(256)))
    return (rng.getrandbits(24) << 8) | a


def _uniform_stream(rng, Vx, Vy, n):
    levels = [rng.random() for _ in range(rng.randint(1, 5))]
    frags = []
    for _ in range(n):
        u = rng.random()
        if u < 0.25:
            t = rng.choice(levels)
        elif u < 0.30:
            t = rng.choice(levels) + rng.uniform(-1e-9, 1e-9)  # same code
            t = min(1.0, max(0.0, t))
        else:
            t = rng.random()
        frags.append((rng.randrange(Vx), rng.randrange(Vy), t, _colour(rng)))
    return frags


def _coherent_stream(rng, Vx, Vy, n):
    frags = []
    while len(frags) < n:
        w = rng.randint(1, Vx)
        h = rng.randint(1, Vy)
        x0 = rng.randint(0, Vx - w)
        y0 = rng.randint(0, Vy - h)
        tri = rng.random() < 0.4
        corner = rng.randrange(4)
        t0 = rng.random()
        if rng.random() < 0.3:
            gx = gy = 0.0                       # constant-depth primitive
        else:
            gx = rng.uniform(-0.02, 0.02)
            gy = rng.uniform(-0.02, 0.02)
        col = _colour(rng)
        for y in range(y0, y0 + h):
            for x in range(x0, x0 + w):
                if tri:
                    u = (x - x0 + 0.5) / w
                    v = (y - y0 + 0.5) / h
                    if corner & 1:
                        u = 1.0 - u
                    if corner & 2:
                        v = 1.0 - v
                    if u + v > 1.0:
                        continue
                t = t0 + gx * (x - x0) + gy * (y - y0)
                t = min(1.0, max(0.0, t))
                frags.append((x, y, t, col))
                if len(frags) >= n:
                    return frags
    return frags


EDGE_DEPTHS = (float("nan"), -0.5, 1.5, 1e-40, 0.0, 1.0, -0.0)
# valid or invalid only after float32 rounding: 1.0000000001 -> 1.0f (valid),
# 1.0000001 -> 1.00000012f (invalid), -1e-50 -> -0.0f (valid),
# 1e-46 -> 0.0f (valid).
ROUNDING_DEPTHS = (1.0000000001, 1.0000001, -1e-50, 1e-46, 0.99999999999)


def make_case(seed):
    rng = random.Random(seed)
    shape = rng.random()
    if shape < 0.05:
        Vx, Vy = rng.randint(1, 3), rng.randint(1, 3)
    elif shape < 0.1:
        Vx, Vy = 1, rng.randint(1, 40)
    elif shape < 0.2:
        Vx, Vy = rng.randint(1, 40), 1
    else:
        Vx, Vy = rng.randint(1, 40), rng.randint(1, 40)
    if rng.random() < 0.2:
        Hx, Hy = Vx, Vy
    else:
        Hx, Hy = rng.randint(Vx, 2 * Vx), rng.randint(Vy, 2 * Vy)
    layout = rng.choice((64, 32))
    A = rng.randint(4, 8)
    B = rng.choice((1, 2, 3, 8))
    threads = rng.choice((1, 2))
    amax = (1 << A) - 1
    offsets = ha_model.random_offsets(Hx, Hy, A, rng)
    if rng.random() < 0.7:
        load = rng.uniform(0.05, 0.9)
    else:
        load = rng.uniform(0.9, 1.08)   # overfull: failures are expected
    n = max(1, int(round(load * Hx * Hy)))
    coherent = rng.random() < 0.5
    frags = (_coherent_stream if coherent else _uniform_stream)(rng, Vx, Vy, n)
    # exact duplicates, equal depths with other colours
    extra = []
    for _ in range(rng.randint(0, max(1, n // 12))):
        extra.append(rng.choice(frags))
    for _ in range(rng.randint(0, max(1, n // 15))):
        x, y, t, _c = rng.choice(frags)
        extra.append((x, y, t, _colour(rng)))
    edge = []
    if rng.random() < 0.7:
        for _ in range(rng.randint(1, 6)):
            edge.append(rng.choice(EDGE_DEPTHS))
    rounding = rng.random() < 0.3
    if rounding:
        edge.extend(rng.sample(ROUNDING_DEPTHS, rng.randint(1, 3)))
    for t in edge:
        extra.append((rng.randrange(Vx), rng.randrange(Vy), t, _colour(rng)))
    for f in extra:
        frags.insert(rng.randrange(len(frags) + 1), f)
    frags = [(x, y, t if t != t else _clean_depth(t), c)
             for x, y, t, c in frags]
    hexmode = rng.choice(("dec", "hex", "HEX", "mix"))
    fmt = [rng.choice(("dec", "hex", "HEX")) if hexmode == "mix" else hexmode
           for _ in frags]
    perm = list(range(len(frags)))
    rng.shuffle(perm)
    return dict(seed=seed, Vx=Vx, Vy=Vy, Hx=Hx, Hy=Hy, layout=layout, A=A,
                amax=amax, B=B, threads=threads, offsets=offsets,
                frags=frags, fmt=fmt, perm=perm, coherent=coherent,
                rounding=rounding, load=load)


def _fmt_depth(t):
    return "nan" if t != t else repr(t)


def _fmt_rgba(c, mode):
    if mode == "dec":
        return "%d" % c
    if mode == "hex":
        return "0x%x" % c
    return "0x%08X" % c


def write_case(case, d):
    with open(os.path.join(d, "offsets.csv"), "w") as f:
        f.write("ox,oy\n")
        for ox, oy in case["offsets"]:
            f.write("%d,%d\n" % (ox, oy))
    rows = ["%d,%d,%s,%s\n" % (x, y, _fmt_depth(t), _fmt_rgba(c, m))
            for (x, y, t, c), m in zip(case["frags"], case["fmt"])]
    with open(os.path.join(d, "frags.csv"), "w") as f:
        f.write("x,y,depth,rgba\n")
        f.writelines(rows)
    with open(os.path.join(d, "frags_shuffled.csv"), "w") as f:
        f.write("x,y,depth,rgba\n")
        f.writelines(rows[i] for i in case["perm"])


# ---------------------------------------------------------------------------
# Running and parsing
# ---------------------------------------------------------------------------

def habuffer_cmd(exe, case, d, tag, infile, threads, path="cpu"):
    p = lambda name: os.path.join(d, name)  # noqa: E731
    # --threads is the CPU path's; the CLI refuses it with --path gl.
    threads_args = ["--threads", str(threads)] if path == "cpu" else []
    return [exe, "build-lists", "--path", path,
            "--in", p(infile),
            "--out", p("lists%s.csv" % tag),
            "--screen", "%dx%d" % (case["Vx"], case["Vy"]),
            "--table", "%dx%d" % (case["Hx"], case["Hy"]),
            "--layout", str(case["layout"]),
            "--age-bits", str(case["A"]),
            "--offsets", p("offsets.csv"),
            "--block", str(case["B"]),
            *threads_args,
            "--stats", p("stats%s.json" % tag),
            "--dump-table", p("table%s.csv" % tag),
            "--dump-max-age", p("maxage%s.csv" % tag)]


def technique_cmd(exe, case, d, technique, path):
    """A sorted technique (lists, arrays) on the shuffled stream, lossless:
    its lists must be the model's whenever the model lost nothing."""
    p = lambda name: os.path.join(d, name)  # noqa: E731
    return [exe, "build-lists", "--path", path, "--technique", technique,
            "--in", p("frags_shuffled.csv"),
            "--out", p("lists_%s.csv" % technique),
            "--screen", "%dx%d" % (case["Vx"], case["Vy"]),
            "--layout", str(case["layout"]),
            "--age-bits", str(case["A"]),
            *(["--layers", "2"] if technique == "arrays" else ["--pool", "3"]),
            "--lossless", "--max-attempts", "40",
            "--stats", p("stats_%s.json" % technique)]


def check_technique(exe, case, d, timeout, model, technique, path):
    """Errors of the technique run against the model (no HA failure)."""
    cmd = technique_cmd(exe, case, d, technique, path)
    try:
        run_habuffer(cmd, timeout)
        lists = _parse_csv(os.path.join(d, "lists_%s.csv" % technique),
                           "x,y,rank,code,rgba", (int,) * 5)
        st = json.loads(_read(os.path.join(d, "stats_%s.json" % technique)))
    except (CaseFailure, ValueError) as e:
        return ["%s on %s: %s" % (technique, path, e)]
    errs = []
    ms = model.stats()
    dif = _first_diff("lists", lists, model.lists())
    if dif:
        errs.append("%s on %s %s" % (technique, path, dif))
    for k in ("fragments", "invalid", "duplicates", "stored"):
        if st.get(k) != ms[k]:
            errs.append("%s on %s stats %s: habuffer %s, model %s"
                        % (technique, path, k, st.get(k), ms[k]))
    if st.get("dropped_pool", 0) or st.get("dropped_layers", 0):
        errs.append("%s on %s dropped fragments in lossless mode: %s"
                    % (technique, path, st))
    return errs


def run_habuffer(cmd, timeout):
    env = dict(os.environ)
    if "gl" in cmd:
        # Mesa leaves allocations LeakSanitizer cannot attribute (asan builds).
        env["ASAN_OPTIONS"] = ":".join(
            x for x in (env.get("ASAN_OPTIONS", ""), "detect_leaks=0") if x)
    try:
        pr = subprocess.run(cmd, stdout=subprocess.PIPE, env=env,
                            stderr=subprocess.PIPE, timeout=timeout)
    except subprocess.TimeoutExpired:
        raise CaseFailure("timeout after %ds" % timeout)
    except OSError as e:
        raise CaseFailure("cannot run habuffer: %s" % e)
    if pr.returncode != 0:
        err = pr.stderr.decode("utf-8", "replace").strip().splitlines()
        raise CaseFailure("exit code %d: %s" % (
            pr.returncode, err[-1] if err else "(no stderr)"))


def _read(path):
    try:
        with open(path, "rb") as f:
            return f.read()
    except OSError as e:
        raise CaseFailure("missing output %s (%s)" % (path, e.strerror))


def _parse_csv(path, header, conv):
    text = _read(path).decode("ascii", "replace")
    lines = text.splitlines()
    if not lines or lines[0].strip() != header:
        raise CaseFailure("%s: bad header %r, want %r" % (
            os.path.basename(path), lines[0] if lines else "", header))
    rows = []
    for i, ln in enumerate(lines[1:], 2):
        if not ln.strip():
            continue
        parts = ln.strip().split(",")
        if len(parts) != len(conv):
            raise CaseFailure("%s:%d: %d fields" % (
                os.path.basename(path), i, len(parts)))
        try:
            rows.append(tuple(c(v) for c, v in zip(conv, parts)))
        except ValueError:
            raise CaseFailure("%s:%d: unparsable %r" % (
                os.path.basename(path), i, ln))
    return rows


def _hex(v):
    v = v.strip()
    if v[:2].lower() != "0x":
        raise ValueError(v)
    return int(v[2:], 16)


def read_outputs(d, tag):
    out = {}
    out["lists"] = _parse_csv(os.path.join(d, "lists%s.csv" % tag),
                              "x,y,rank,code,rgba", (int,) * 5)
    out["table"] = _parse_csv(os.path.join(d, "table%s.csv" % tag),
                              "slot,record", (int, _hex))
    out["maxage"] = _parse_csv(os.path.join(d, "maxage%s.csv" % tag),
                               "cx,cy,max_age", (int,) * 3)
    try:
        st = json.loads(_read(os.path.join(d, "stats%s.json" % tag)))
    except ValueError as e:
        raise CaseFailure("stats%s.json: bad JSON (%s)" % (tag, e))
    for k in STAT_KEYS:
        if k not in st:
            raise CaseFailure("stats%s.json: missing key %r" % (tag, k))
    out["stats"] = dict((k, st[k]) for k in STAT_KEYS)
    out["raw"] = dict((k, _read(os.path.join(d, "%s%s.%s" % (k, tag, e))))
                      for k, e in (("lists", "csv"), ("table", "csv"),
                                   ("maxage", "csv")))
    return out


def _show(name, row):
    if name == "table":
        return "(%d, 0x%x)" % row
    return "(%s)" % ", ".join(str(v) for v in row)


def _first_diff(name, got, want):
    for i, (g, w) in enumerate(zip(got, want)):
        if g != w:
            return "%s row %d: habuffer %s, model %s" % (
                name, i + 1, _show(name, g), _show(name, w))
    if len(got) != len(want):
        return "%s: habuffer %d rows, model %d rows" % (
            name, len(got), len(want))
    return None


def check_internal(o, tag):
    st = o["stats"]
    s = (st["fragments"] - st["invalid"] - st["duplicates"] - st["culled"]
         - st["failed_age"] - st["failed_iter"])
    errs = []
    if st["stored"] != s:
        errs.append("run%s: stored %d != fragments-invalid-duplicates-culled-"
                    "failed_age-failed_iter = %d" % (tag, st["stored"], s))
    if st["stored"] != len(o["table"]):
        errs.append("run%s: stored %d != non-empty slots in table dump %d"
                    % (tag, st["stored"], len(o["table"])))
    return errs


# ---------------------------------------------------------------------------
# One case
# ---------------------------------------------------------------------------

def run_case(exe, case, d, timeout, gl=False):
    """gl: the second (shuffled) run goes through the GPU path."""
    write_case(case, d)
    cmd1 = habuffer_cmd(exe, case, d, "", "frags.csv", case["threads"])
    cmd2 = habuffer_cmd(exe, case, d, "_shuffled", "frags_shuffled.csv", 2,
                        "gl" if gl else "cpu")
    errs = []
    try:
        run_habuffer(cmd1, timeout)
        o1 = read_outputs(d, "")
    except CaseFailure as e:
        return ["run1: %s" % e], cmd1, None
    try:
        run_habuffer(cmd2, timeout)
        o2 = read_outputs(d, "_shuffled")
    except CaseFailure as e:
        return ["run2 (shuffled): %s" % e], cmd2, None

    m = HAModel((case["Vx"], case["Vy"]), (case["Hx"], case["Hy"]),
                case["layout"], case["A"], case["offsets"], case["B"])
    for x, y, t, c in case["frags"]:
        m.add_fragment(x, y, t, c)
    ms = m.stats()
    m_fail = ms["failed_age"] + ms["failed_iter"]

    errs += check_internal(o1, "1")
    errs += check_internal(o2, "2")
    s1, s2 = o1["stats"], o2["stats"]
    for k in ("fragments", "invalid", "culled"):
        for tag, s in (("1", s1), ("2", s2)):
            if s[k] != ms[k]:
                errs.append("run%s stats %s: habuffer %s, model %s"
                            % (tag, k, s[k], ms[k]))
    fail1 = s1["failed_age"] + s1["failed_iter"]
    fail2 = s2["failed_age"] + s2["failed_iter"]

    # run1 vs run2: byte identity
    if s1["failed_iter"] == 0 and s2["failed_iter"] == 0:
        if o1["raw"]["table"] != o2["raw"]["table"]:
            errs.append("table differs between file-order run and shuffled "
                        "run (" + (_first_diff("table", o2["table"],
                                               o1["table"]) or "bytes") + ")")
        if s1["stored"] != s2["stored"]:
            errs.append("stored differs between runs: %d vs %d"
                        % (s1["stored"], s2["stored"]))
        if (s1["duplicates"] + s1["failed_age"]
                != s2["duplicates"] + s2["failed_age"]):
            errs.append("duplicates+failed_age differs between runs")
    if fail1 == 0 and fail2 == 0:
        for k in ("maxage", "lists"):
            if o1["raw"][k] != o2["raw"][k]:
                errs.append("%s differs between file-order run and shuffled "
                            "run (%s)" % (k, _first_diff(k, o2[k], o1[k])
                                          or "bytes"))
        if s1 != s2:
            errs.append("stats differ between runs: %s vs %s" % (s1, s2))

    # habuffer vs model
    if ms["failed_iter"] == 0:
        for tag, o, s in (("1", o1, s1), ("2", o2, s2)):
            if s["failed_iter"]:
                errs.append("run%s: failed_iter %d but model has none"
                            % (tag, s["failed_iter"]))
                continue
            dif = _first_diff("table", o["table"], m.table_rows())
            if dif:
                errs.append("run%s %s" % (tag, dif))
            if s["stored"] != ms["stored"]:
                errs.append("run%s stats stored: habuffer %d, model %d"
                            % (tag, s["stored"], ms["stored"]))
            if (s["duplicates"] + s["failed_age"]
                    != ms["duplicates"] + ms["failed_age"]):
                errs.append("run%s stats duplicates+failed_age: habuffer "
                            "%d+%d, model %d+%d" % (
                                tag, s["duplicates"], s["failed_age"],
                                ms["duplicates"], ms["failed_age"]))
            if (s["failed_age"] == 0) != (ms["failed_age"] == 0):
                errs.append("run%s stats failed_age: habuffer %d, model %d"
                            % (tag, s["failed_age"], ms["failed_age"]))
    if m_fail == 0:
        for tag, o, s, fl in (("1", o1, s1, fail1), ("2", o2, s2, fail2)):
            if fl:
                continue  # already reported above
            if s != ms:
                errs.append("run%s stats: habuffer %s, model %s"
                            % (tag, s, ms))
            for k, want in (("maxage", m.maxage_rows()),
                            ("lists", m.lists())):
                dif = _first_diff(k, o[k], want)
                if dif:
                    errs.append("run%s %s" % (tag, dif))
        # The other exact techniques, from tiny first sizes grown losslessly,
        # on the path of the shuffled run.
        technique = "lists" if len(case["frags"]) % 2 == 0 else "arrays"
        errs += check_technique(exe, case, d, timeout, m, technique,
                                "gl" if gl else "cpu")
    return errs, cmd1, ms


def describe(case, ms):
    return ("V=%dx%d H=%dx%d L%d A=%d B=%d T=%d n=%d load=%.2f %s%s%s" % (
        case["Vx"], case["Vy"], case["Hx"], case["Hy"], case["layout"],
        case["A"], case["B"], case["threads"], len(case["frags"]),
        case["load"], "coherent" if case["coherent"] else "uniform",
        " rounding-edges" if case["rounding"] else "",
        "" if ms is None else " model:%s" % ",".join(
            "%s=%d" % (k, ms[k]) for k in STAT_KEYS if ms[k])))


def main(argv=None):
    ap = argparse.ArgumentParser(
        description="Cross-check habuffer build-lists against the Python "
                    "model of docs/specification.md.")
    ap.add_argument("--habuffer", required=True,
                    help="path to the habuffer executable")
    ap.add_argument("--cases", type=int, default=60)
    ap.add_argument("--gl-every", type=int, default=0,
                    help="every Nth case runs its shuffled build with "
                         "--path gl (0: never)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--case", type=int, action="append",
                    help="run only this case index (repeatable)")
    ap.add_argument("--workdir", help="directory for case files "
                    "(default: a fresh temporary directory)")
    ap.add_argument("--keep", action="store_true",
                    help="keep the files of passing cases too")
    ap.add_argument("--timeout", type=int, default=120,
                    help="seconds per habuffer run")
    ap.add_argument("-v", "--verbose", action="store_true",
                    help="print every error of a failing case and a line "
                         "per passing case")
    args = ap.parse_args(argv)

    exe = os.path.abspath(args.habuffer)
    if not (os.path.isfile(exe) and os.access(exe, os.X_OK)):
        print("crosscheck: %s is not an executable file" % args.habuffer)
        print("crosscheck: 0 passed, 1 failed")
        return 2
    workdir = args.workdir or tempfile.mkdtemp(prefix="ha_crosscheck_")
    os.makedirs(workdir, exist_ok=True)
    here = os.path.abspath(__file__)

    indices = args.case if args.case else range(args.cases)
    passed = failed = 0
    t0 = time.time()
    for i in indices:
        seed = args.seed * 1000003 + i
        case = make_case(seed)
        d = os.path.join(workdir, "case%04d" % i)
        if os.path.isdir(d):
            shutil.rmtree(d)
        os.makedirs(d)
        gl = args.gl_every > 0 and i % args.gl_every == args.gl_every - 1
        errs, cmd, ms = run_case(exe, case, d, args.timeout, gl)
        if errs:
            failed += 1
            repro = "python3 %s --habuffer %s --seed %d --case %d " \
                    "--workdir %s" % (shlex.quote(here), shlex.quote(exe),
                                      args.seed, i, shlex.quote(workdir))
            print("FAIL case %d [%s] %s%s | repro: %s | habuffer: %s" % (
                i, describe(case, ms), errs[0],
                " (+%d more)" % (len(errs) - 1) if len(errs) > 1 else "",
                repro, " ".join(shlex.quote(c) for c in cmd)))
            with open(os.path.join(d, "errors.txt"), "w") as f:
                f.write("\n".join(errs) + "\n")
            if args.verbose:
                for e in errs[1:]:
                    print("    " + e)
        else:
            passed += 1
            if args.verbose:
                print("ok   case %d [%s]" % (i, describe(case, ms)))
            if not args.keep:
                shutil.rmtree(d, ignore_errors=True)
    if not args.workdir and failed == 0 and not args.keep:
        shutil.rmtree(workdir, ignore_errors=True)
    elif failed:
        print("crosscheck: case files kept in %s (errors.txt per case)"
              % workdir)
    if args.verbose:
        print("crosscheck: %.1fs" % (time.time() - t0))
    print("crosscheck: %d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
