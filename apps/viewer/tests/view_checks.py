#!/usr/bin/env python3
"""habuffer-view's checks, each a ctest test, run under Xvfb (xvfb-run; GLX on
Mesa's llvmpipe). A check that needs a window exits 77 (ctest's skip) with
the reason when xvfb-run is missing or no OpenGL 4.5 window can be made.

usage: view_checks.py CHECK --view EXE --habuffer EXE --workdir DIR
checks:
  screenshot   the scene image equals `habuffer render` of the same view (PSNR inf),
               translucent shadows included
  resize       a window resized mid-run renders the new size, equal to render's
  switches     100 technique switches and 20 resizes: no GL error, no GL object
               left behind (per technique), resident memory flat (the highest of 16 frames
               grows under 16 MiB)
  usage        bad command lines: one line naming the option, exit 2; a bad scene exit 1
  losses       render's loss rules: a pixel deeper than AMAX grows no table (a warning naming
               --age-bits; --lossless exits 1), a lossy fixed table warned about on stderr,
               a file-size limit on --screenshot a write error with no temporary left
"""

import argparse
import json
import os
import shutil
import subprocess
import sys

SKIP = 77


def run(cmd, timeout=900):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)


class Checks:
    def __init__(self, a):
        self.view, self.cli, self.work = a.view, a.habuffer, os.path.abspath(a.workdir)
        os.makedirs(self.work, exist_ok=True)

    def path(self, name):
        return os.path.join(self.work, name)

    def windowed(self, *args, want=0, limit_bytes=None):
        """habuffer-view under a fresh Xvfb server; skips when there is no window.
        With limit_bytes, the run's file-size limit (RLIMIT_FSIZE)."""
        if shutil.which("xvfb-run") is None:
            print("SKIP: xvfb-run not found (Debian xvfb; scripts/setup.sh installs it)")
            sys.exit(SKIP)
        limit = [] if limit_bytes is None else ["prlimit", "--fsize=%d" % limit_bytes, "--"]  # the viewer's alone
        cmd = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", *limit, self.view, *map(str, args)]
        r = run(cmd)
        if r.returncode != 0 and "Xvfb failed to start" in r.stderr:
            r = run(cmd)  # another server took the display number xvfb-run chose: once more
        if r.returncode == 5 and "problem while cleaning up temporary directory" in r.stderr:
            r = run(cmd)  # xvfb-run's own clean-up failed, hiding the viewer's exit status: once more
        if r.returncode != 0 and ("no window system" in r.stderr or "no OpenGL 4.5 core window" in r.stderr):
            print("SKIP: " + r.stderr.strip())
            sys.exit(SKIP)
        if r.returncode != want:
            raise SystemExit("habuffer-view %s exited %d (want %d): %s"
                             % (" ".join(map(str, args)), r.returncode, want, r.stderr))
        return r

    def render(self, out, *args):
        r = run([self.cli, "render", "--out", out, "--quiet", *map(str, args)])
        if r.returncode != 0:
            raise SystemExit("habuffer render failed (%d): %s" % (r.returncode, r.stderr))

    def psnr(self, a, b):
        r = run([self.cli, "compare", a, b])
        if r.returncode != 0:
            raise SystemExit("habuffer compare failed: " + r.stderr)
        return r.stdout.split("psnr ")[1].split()[0]

    def expect_equal(self, what, shot, image):
        p = self.psnr(shot, image)
        print("%s: PSNR %s against habuffer render" % (what, p))
        if p != "inf":
            raise SystemExit("%s: the viewer's image differs from habuffer render's (PSNR %s)" % (what, p))

    def screenshot(self):
        views = [("engine", ["--technique", "ha", "--yaw", "40", "--pitch", "15"], "200x150"),
                 ("hairball", ["--technique", "sorted-lists", "--samples", "4"], "160x128"),
                 ("quads", ["--technique", "kbuffer", "--layers", "4"], "96x96"),
                 ("engine", ["--technique", "lists", "--shadows", "--light-size", "256x256"], "200x150"),
                 ("engine", ["--technique", "ha", "--pitch", "90", "--fov", "150"], "96x72")]
        for k, (scene, options, size) in enumerate(views):
            shot, image = self.path("%d_%s_view.png" % (k, scene)), self.path("%d_%s_render.png" % (k, scene))
            self.windowed("--scene", scene, "--size", size, "--frames", 2, "--screenshot", shot, *options)
            self.render(image, "--scene", scene, "--size", size, *options)
            self.expect_equal(scene + " " + " ".join(options), shot, image)

    def resize(self):
        shot, report = self.path("resized.png"), self.path("resized.json")
        self.windowed("--scene", "engine", "--size", "160x120", "--resize", "2:224x168,3:200x136", "--frames", 5,
                      "--screenshot", shot, "--report", report)
        with open(report) as f:
            r = json.load(f)
        screens = [f["screen"] for f in r["per_frame"]]
        if screens != ["160x120", "160x120", "224x168", "200x136", "200x136"] or r["resizes"] != 2:
            raise SystemExit("resize: the frames ran at %s (%d resizes), not 160x120 x2, 224x168, 200x136 x2"
                             % (screens, r["resizes"]))
        image = self.path("resized_render.png")
        self.render(image, "--scene", "engine", "--size", "200x136")
        self.expect_equal("engine after two resizes", shot, image)
        # A window beyond this OpenGL's viewport: refused, the refusal said in full.
        r = self.windowed("--scene", "engine", "--size", "64x48", "--frames", 3, "--resize", "1:17000x48", "--no-gui",
                          want=1)
        if "1 scripted change refused; the first: window 17000x48: " not in r.stderr:
            raise SystemExit("resize: a refused window size said %r" % r.stderr)

    def switches(self):
        report = self.path("switches.json")
        resizes = ",".join("%d:%dx%d" % (3 + 5 * i, 96 + 8 * (i % 4), 72 + 8 * (i % 3)) for i in range(20))
        self.windowed("--scene", "engine", "--size", "128x96", "--frames", 101, "--cycle", 100, "--resize", resizes,
                      "--report", report)
        with open(report) as f:
            r = json.load(f)
        problems = []
        if r["technique_switches"] != 100 or r["switches_refused"] != 0:
            problems.append("%d switches, %d refused" % (r["technique_switches"], r["switches_refused"]))
        if r["resizes"] != 20:
            problems.append("%d resizes, not 20" % r["resizes"])
        if r["gl_errors"] != 0:
            problems.append("%d GL errors" % r["gl_errors"])
        if len(r["gl_objects"]) < 8:
            problems.append("only %s ran after the warm-up" % sorted(r["gl_objects"]))
        for technique, seen in r["gl_objects"].items():
            if seen["first"] != seen["last"]:
                problems.append("%s: live GL objects %s, later %s" % (technique, seen["first"], seen["last"]))
        # Resident memory is two-level from frame to frame (a technique's buffers are host
        # memory on llvmpipe, freed at each switch; whether the allocator gives them back
        # to the system depends on timing), so neither one frame nor the lowest of several
        # says anything: under load the lowest was 24 MiB apart with no leak. The highest
        # of 16 frames (two rounds of the eight techniques, every technique's buffers live
        # once) is steady, and a leak raises it with every switch: compared after the
        # warm-up and at the end.
        rss = [row["rss_kib"] for row in r["per_frame"]]
        if len(rss) != 101:  # the warm-up ends at frame 20 (view_run.cpp: frames / 5)
            raise SystemExit("switches: %d frames reported, not 101" % len(rss))
        warm, end = rss[20:36], rss[-16:]
        peak = max(end) - max(warm)
        print("switches: resident memory at most %d KiB after the warm-up, %d at the end (%+d; lowest %d, %d)"
              % (max(warm), max(end), peak, min(warm), min(end)))
        if peak > 16 * 1024:
            problems.append("resident memory grew by %d KiB (the highest of 16 frames)" % peak)
        if problems:
            raise SystemExit("switches: " + "; ".join(problems))

    def losses(self):
        deep = ["--scene", "planes", "--count", "260", "--size", "32x24", "--frames", "2", "--no-gui"]
        report = self.path("deep.json")
        r = self.windowed(*deep, "--report", report)
        with open(report) as f:
            frames = json.load(f)["per_frame"]
        if "warning" not in r.stderr or "--age-bits 9" not in r.stderr:
            raise SystemExit("losses: a pixel of 260 fragments (AMAX 255) was not warned about: %r" % r.stderr)
        if frames[1]["attempts"] != 1 or frames[0]["table"] != frames[1]["table"]:
            raise SystemExit("losses: tables %s grew for a pixel no table holds (attempts %s)"
                             % ([f["table"] for f in frames], [f["attempts"] for f in frames]))
        print("losses: deeper than AMAX: " + r.stderr.strip().splitlines()[-1])
        r = self.windowed(*deep, "--lossless", want=1)
        if "lossless mode" not in r.stderr or "--age-bits 9" not in r.stderr:
            raise SystemExit("losses: --lossless with a pixel deeper than AMAX said %r" % r.stderr)
        r = self.windowed("--scene", "hairball", "--size", "64x64", "--table", "64x64", "--frames", "1", "--no-gui")
        if "warning" not in r.stderr or "not stored" not in r.stderr:
            raise SystemExit("losses: a lossy fixed table was not warned about: %r" % r.stderr)
        print("losses: fixed table: " + r.stderr.strip().splitlines()[-1])
        shot = self.path("limited.png")
        if os.path.exists(shot):
            os.remove(shot)  # an earlier run's
        r = self.windowed("--scene", "engine", "--size", "96x72", "--frames", "1", "--no-gui", "--screenshot", shot,
                          want=1, limit_bytes=256)
        left = [n for n in os.listdir(self.work) if n.startswith(".limited")]
        if "File too large" not in r.stderr or os.path.exists(shot) or left:
            raise SystemExit("losses: a file-size limit on --screenshot: %r, temporaries %s" % (r.stderr, left))
        print("losses: file-size limit: " + r.stderr.strip().splitlines()[-1])

    def usage(self):
        cases = [(["--scene", "engine", "--screenshot", self.path("x.png")], 2, "--screenshot"),
                 (["--scene", "engine", "--frames", "2", "--resize", "1:0x5"], 2, "--resize"),
                 (["--scene", "engine", "--frames", "3", "--resize", "2:64x64,1:32x32"], 2, "--resize"),
                 (["--scene", "engine", "--technique", "nope"], 2, "--technique"),
                 (["--scene", "engine", "--overlay", "heat"], 2, "--overlay"),
                 (["--scene", "engine", "--size", "0x4"], 2, "--size"),
                 (["--scene", "engine", "--layers", "4"], 2, "--layers"),
                 (["--scene", "engine", "--light-dir", "1,0,0"], 2, "--light-dir"),
                 (["--scene", "engine", "--overlay", "shadow"], 2, "--overlay shadow"),
                 (["--scene", "engine", "--shadows", "--samples", "4"], 2, "--samples"),
                 (["--scene", "engine", "--shadows", "--light-dir", "0,0,0"], 2, "--light-dir"),
                 (["--scene", "engine", "--technique", "lists", "--overlay", "age"], 2, "--overlay age"),
                 (["--scene", "engine", "--pitch", "91"], 2, "--pitch"),
                 (["--scene", "engine", "--fov", "179"], 2, "--fov"),
                 (["--scene", self.path("missing.obj"), "--frames", "1"], 1, "missing.obj")]
        for args, code, named in cases:
            r = run([self.view, *args])
            lines = r.stderr.strip().splitlines()
            if r.returncode != code or len(lines) != 1 or named not in lines[0]:
                raise SystemExit("usage: %s exited %d (want %d) saying %r (want one line naming %s)"
                                 % (" ".join(args), r.returncode, code, r.stderr, named))
            print("usage: %s -> %d: %s" % (" ".join(args), code, lines[0]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("check", choices=["screenshot", "resize", "switches", "usage", "losses"])
    ap.add_argument("--view", required=True)
    ap.add_argument("--habuffer", required=True)
    ap.add_argument("--workdir", required=True)
    a = ap.parse_args()
    getattr(Checks(a), a.check)()
    print("%s: passed" % a.check)
    return 0


if __name__ == "__main__":
    sys.exit(main())
