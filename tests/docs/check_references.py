#!/usr/bin/env python3
"""The repository cites only itself (issue 47, part 1).

- No file points outside the repository: to the founding brief beside it or
  to the source papers' text files.
- Every "SPEC n" (also "SPEC n-m", "SPEC n, m and k") names a section of
  docs/specification.md, and every "SPEC invariant n" an item of its
  section 11.
- Every "seed 0NN" has a row in the specification's References.

usage: check_references.py REPOSITORY
"""

import os
import re
import subprocess
import sys

# Spelled in pieces, so this file does not match itself.
OUTSIDE = [re.compile(p) for p in (r"\.\./" + "shared", r"/work/" + "shared", "SPEC" + r"\.md",
                                   r"[0-9]{3}_[0-9a-f]{16}" + r"\.txt")]
TEXT = (".h", ".hpp", ".cpp", ".glsl", ".py", ".pyi", ".md", ".sh", ".txt", ".cmake", ".toml", ".ipynb", ".json",
        ".in", ".cfg")


def tracked_files(root):
    out = subprocess.run(["git", "-C", root, "ls-files"], capture_output=True, text=True)
    if out.returncode != 0:  # not a git checkout (an exported tree): walk it
        names = []
        for d, dirs, files in os.walk(root):
            dirs[:] = [x for x in dirs if not x.startswith(".") and not x.startswith("build")]
            names += [os.path.relpath(os.path.join(d, f), root) for f in files]
        return names
    return out.stdout.split()


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    spec_path = os.path.join(root, "docs", "specification.md")
    with open(spec_path) as f:
        spec = f.read()
    sections = {int(m) for m in re.findall(r"^## ([0-9]+)\. ", spec, re.M)}
    invariants_text = spec.split("## 11.", 1)[1].split("\n## ", 1)[0] if "## 11." in spec else ""
    invariants = {int(m) for m in re.findall(r"^([0-9]+)\. ", invariants_text, re.M)}
    references = {m for m in re.findall(r"^\| (0[0-9]{2}) \|", spec, re.M)}
    problems = []
    cited = 0
    for name in tracked_files(root):
        if not name.endswith(TEXT) and name != "CMakeLists.txt" and not name.endswith("CMakeLists.txt"):
            continue
        try:
            with open(os.path.join(root, name), encoding="utf-8") as f:
                lines = f.read().splitlines()
        except (UnicodeDecodeError, FileNotFoundError):
            continue
        for number, line in enumerate(lines, 1):
            where = "%s:%d" % (name, number)
            for p in OUTSIDE:
                if p.search(line) and name != "tests/docs/check_references.py":
                    problems.append("%s points outside the repository (%s)" % (where, p.pattern))
            for m in re.finditer(r"SPEC invariants? ([0-9]+)", line):
                cited += 1
                if int(m.group(1)) not in invariants:
                    problems.append("%s cites SPEC invariant %s, which section 11 lacks" % (where, m.group(1)))
            for m in re.finditer(r"SPEC ([0-9]+(?:(?:-|, | and )[0-9]+)*)", line):
                for n in re.findall(r"[0-9]+", m.group(1)):
                    cited += 1
                    if int(n) not in sections:
                        problems.append("%s cites SPEC %s, which docs/specification.md lacks" % (where, n))
            for m in re.finditer(r"\b[Ss]eed (0[0-9]{2})\b", line):
                cited += 1
                if m.group(1) not in references:
                    problems.append("%s cites seed %s, which the specification's References lack" % (where, m.group(1)))
    if not sections or not invariants or not references:
        problems.append("docs/specification.md: no numbered sections, invariants or references found")
    for p in problems[:40]:
        print(p)
    print("%d citations checked against %d sections, %d invariants, %d references: %d problems"
          % (cited, len(sections), len(invariants), len(references), len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
