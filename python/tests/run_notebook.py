#!/usr/bin/env python3
"""Runs a notebook's code cells in order, as one script, in a work directory,
so CI executes docs/notebooks without Jupyter (executing with nbconvert needs
a kernel package, ipykernel). A failing cell names its number and the error.

usage: run_notebook.py NOTEBOOK.ipynb [--workdir DIR]
"""

import argparse
import json
import os
import sys
import traceback


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("notebook")
    ap.add_argument("--workdir", default=".")
    a = ap.parse_args()
    with open(a.notebook) as f:
        nb = json.load(f)
    os.makedirs(a.workdir, exist_ok=True)
    os.chdir(a.workdir)
    os.environ.setdefault("MPLBACKEND", "Agg")
    scope = {"__name__": "__main__"}
    cells = [c for c in nb["cells"] if c["cell_type"] == "code"]
    for n, cell in enumerate(cells, 1):
        source = "".join(cell["source"])
        try:
            exec(compile(source, "%s[cell %d]" % (os.path.basename(a.notebook), n), "exec"), scope)
        except Exception:
            traceback.print_exc()
            print("run_notebook: cell %d of %d failed" % (n, len(cells)), file=sys.stderr)
            return 1
    print("run_notebook: %d cells ran" % len(cells))
    return 0


if __name__ == "__main__":
    sys.exit(main())
