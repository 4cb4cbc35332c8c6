#!/usr/bin/env python3
"""`pip install --no-build-isolation .` from a clean copy of the source tree,
into a virtual environment that sees the system's site packages (Debian's
numpy), offline (--no-index); then `import habuffer` from the environment and
the notebook, then `pip uninstall`. The copy holds what a fresh clone holds
(git's tracked and not-ignored files), so nothing of a build tree can help.

usage: pip_install.py SOURCE_DIR --workdir DIR [--python PYTHON3]
Exit 0 when every step passed; a failing step names itself and its output.
"""

import argparse
import os
import shutil
import subprocess
import sys
import time


def step(what, cmd, env, cwd=None, timeout=3600):
    print("pip_install: %s: %s" % (what, " ".join(cmd)), flush=True)
    t0 = time.monotonic()
    r = subprocess.run(cmd, env=env, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       timeout=timeout)
    if r.returncode != 0:
        print(r.stdout[-8000:])
        raise SystemExit("pip_install: %s failed (exit %d)" % (what, r.returncode))
    print("pip_install: %s: done in %.0f s" % (what, time.monotonic() - t0), flush=True)
    return r.stdout


def clean_copy(source, dest):
    """The files a fresh clone would have: tracked plus untracked-not-ignored."""
    r = subprocess.run(["git", "-C", source, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                       stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    if r.returncode != 0:  # not a git checkout (an unpacked archive): everything but build folders
        shutil.copytree(source, dest, ignore=shutil.ignore_patterns("build*", "out", "__pycache__", "*.egg-info"))
        return sum(len(f) for _, _, f in os.walk(dest))
    files = [f for f in r.stdout.decode().split("\0") if f]
    for f in files:
        src = os.path.join(source, f)
        if not os.path.lexists(src):  # deleted in the work tree, not yet in git
            continue
        os.makedirs(os.path.dirname(os.path.join(dest, f)), exist_ok=True)
        shutil.copy2(src, os.path.join(dest, f), follow_symlinks=False)
    return len(files)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("source")
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--python", default="/usr/bin/python3", help="the interpreter the environment is made from")
    a = ap.parse_args()
    work = os.path.abspath(a.workdir)
    shutil.rmtree(work, ignore_errors=True)
    src, venv = os.path.join(work, "src"), os.path.join(work, "venv")
    n = clean_copy(os.path.abspath(a.source), src)
    print("pip_install: copied %d files to %s" % (n, src))

    env = {k: v for k, v in os.environ.items() if not k.startswith("PYTHON") and k != "VIRTUAL_ENV"}
    env.update(MPLBACKEND="Agg", PIP_DISABLE_PIP_VERSION_CHECK="1", PYTHONDONTWRITEBYTECODE="1")
    step("venv", [a.python, "-m", "venv", "--system-site-packages", venv], env)
    py = os.path.join(venv, "bin", "python")
    step("pip install", [py, "-m", "pip", "install", "--no-build-isolation", "--no-index", "-v", "."], env, cwd=src)

    out = step("import", [py, "-c", "import habuffer, sys; print(habuffer.__file__); print(habuffer.__version__);"
                          "print(len(habuffer.techniques()))"], env, cwd=work)
    where, version = out.splitlines()[0], out.splitlines()[1]
    if not os.path.realpath(where).startswith(os.path.realpath(venv) + os.sep):
        raise SystemExit("pip_install: habuffer was imported from %s, not from the environment %s" % (where, venv))
    with open(os.path.join(src, "CMakeLists.txt")) as f:
        if "VERSION %s " % version not in f.read():
            raise SystemExit("pip_install: the installed module says version %s, CMakeLists.txt does not" % version)
    files = step("pip show", [py, "-m", "pip", "show", "-f", "habuffer"], env, cwd=work)
    for f in ("habuffer/__init__.py", "habuffer/__init__.pyi", "habuffer/py.typed", "habuffer/_habuffer"):
        if f not in files:
            raise SystemExit("pip_install: the installed package lacks %s:\n%s" % (f, files))

    notebook = os.path.join(src, "docs", "notebooks", "age_vs_load.ipynb")
    step("notebook", [py, os.path.join(src, "python", "tests", "run_notebook.py"), notebook,
                      "--workdir", os.path.join(work, "notebook")], env, cwd=work)

    step("pip uninstall", [py, "-m", "pip", "uninstall", "-y", "habuffer"], env, cwd=work)
    # A habuffer the system has (cmake --install into dist-packages) may
    # still import through the system site packages: only the environment's must be gone.
    r = subprocess.run([py, "-c", "import habuffer; print(habuffer.__file__)"], env=env, cwd=work, capture_output=True,
                       text=True)
    if r.returncode == 0 and os.path.realpath(r.stdout.strip()).startswith(os.path.realpath(venv) + os.sep):
        raise SystemExit("pip_install: habuffer still imports from the environment after pip uninstall")
    print("pip_install: install, import, notebook and uninstall passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
