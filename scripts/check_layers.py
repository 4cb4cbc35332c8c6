#!/usr/bin/env python3
"""No include runs up the library order of docs/architecture.md (issue 47).

docs/architecture.md's table "The order" lists every folder that holds a
library or a part of one, one row each, lowest first:

    | 3 | `core/record` | habuffer::core | ... |

A source or header in a folder may include a file of its own folder or of a
folder in an earlier row, never one of a later row. Includes are resolved as
the compiler would find them: beside the including file, then under every
listed folder's include/ and internal/ (and the including folder's src/).
Files that resolve nowhere (the standard library, glm, epoxy, generated
headers) are not checked. A source file under a library folder that no row
covers is an error too, so a new folder has to take its place in the order.

usage: check_layers.py [SOURCE_DIR]
"""

import os
import re
import sys

ROW = re.compile(r"^\|\s*(\d+)\s*\|\s*`([^`]+)`\s*\|")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
SOURCES = (".h", ".hpp", ".cpp", ".glsl")
# Folders holding consumers only (anything may be included from them).
CONSUMERS = ("tests", "benchmarks", "examples", "build", ".git", "docs", "scripts", "cmake", "out")


def read_order(root):
    path = os.path.join(root, "docs", "architecture.md")
    rows = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            m = ROW.match(line)
            if m:
                rows.append((int(m.group(1)), m.group(2).rstrip("/")))
    if not rows:
        raise SystemExit("check_layers: no order table (| n | `folder` | ...) in " + path)
    numbers = [n for n, _ in rows]
    if numbers != list(range(1, len(rows) + 1)):
        raise SystemExit("check_layers: the order table's rows must be numbered 1..%d in order" % len(rows))
    return [folder for _, folder in rows]


def owner(rel, folders):
    """The listed folder holding `rel` (the longest that is a prefix), or None."""
    best = None
    for i, folder in enumerate(folders):
        if rel == folder or rel.startswith(folder + "/"):
            if best is None or len(folder) > len(folders[best]):
                best = i
    return best


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    folders = read_order(root)
    for folder in folders:
        if not os.path.isdir(os.path.join(root, folder)):
            raise SystemExit("check_layers: docs/architecture.md lists `%s`, which is not a folder" % folder)
    roots = []
    for folder in folders:
        if os.path.basename(folder) == "include":  # an umbrella's own headers
            roots.append(os.path.join(root, folder))
        for sub in ("include", "internal"):
            d = os.path.join(root, folder, sub)
            if os.path.isdir(d):
                roots.append(d)
    files = []
    for top in sorted(os.listdir(root)):
        if top.startswith(".") or top.startswith("build") or top in CONSUMERS or not os.path.isdir(os.path.join(root, top)):
            continue
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, top)):
            dirnames[:] = sorted(d for d in dirnames if d not in ("__pycache__",))
            for name in sorted(filenames):
                if name.endswith(SOURCES):
                    files.append(os.path.relpath(os.path.join(dirpath, name), root))
    problems, checked = [], 0
    for rel in files:
        mine = owner(rel, folders)
        if mine is None:
            if rel.startswith(("python/tests", "python/habuffer")):
                continue
            problems.append("%s: in no folder of docs/architecture.md's order" % rel)
            continue
        text = open(os.path.join(root, rel), encoding="utf-8", errors="replace").read()
        here = os.path.dirname(os.path.join(root, rel))
        own_src = os.path.join(root, folders[mine], "src")
        for m in INCLUDE.finditer(text):
            name = m.group(1)
            candidates = [os.path.join(here, name), os.path.join(own_src, name)] + [os.path.join(r, name) for r in roots]
            target = next((c for c in candidates if os.path.isfile(c)), None)
            if target is None:
                continue
            checked += 1
            theirs = owner(os.path.relpath(target, root), folders)
            if theirs is None or theirs <= mine:
                continue
            line = text.count("\n", 0, m.start()) + 1
            problems.append("%s:%d includes %s: `%s` (row %d) may not include `%s` (row %d, later in the order)" %
                            (rel, line, os.path.relpath(target, root), folders[mine], mine + 1, folders[theirs],
                             theirs + 1))
    for p in problems:
        print(p)
    print("%d files, %d includes resolved, %d running up the order or outside it" % (len(files), checked, len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
