#!/usr/bin/python3
"""Issue 37's second reference: a multisampled render against a supersampled one.

Renders each scene with `habuffer render --samples S` at WxH and with one
sample at (kW)x(kH), k*k = S (a k x k ordered grid of samples per pixel),
box-filters the large image down, and reports how far each of the
multisampled and the single-sampled render lies from it: the share of
pixels within 1/255 over all pixels and outside the edge band (pixels whose
k x k supersampled block is not uniform, dilated by one pixel: there the
multisampled render's rotated-grid samples and the supersampled ordered
grid cover different points), the largest error outside the band, and the
RMSE over all pixels. The renders use the lists technique on the CPU path
(the single-sampled large one on the GL path when its capture would exceed
this OpenGL's shader-storage limit); both paths give the same image.

Usage: scripts/msaa_supersampled.py HABUFFER OUTDIR [--scenes engine,hairball]
       [--size 512x512] [--samples 4]
"""
import argparse
import math
import os
import subprocess
import sys

import matplotlib.image as mpimg
import numpy as np


def render(habuffer, scene, size, samples, out, path="cpu"):
    cmd = [habuffer, "render", "--scene", scene, "--size", size, "--samples", str(samples), "--technique", "lists",
           "--path", path, "--quiet", "--out", out]
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        if path == "cpu" and "shader-storage buffer" in result.stderr:
            return render(habuffer, scene, size, samples, out, "gl")
        sys.exit(f"{' '.join(cmd)}: {result.stderr.strip()}")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("habuffer")
    p.add_argument("outdir")
    p.add_argument("--scenes", default="engine,hairball")
    p.add_argument("--size", default="512x512")
    p.add_argument("--samples", type=int, default=4)
    a = p.parse_args()
    k = int(round(math.sqrt(a.samples)))
    if k * k != a.samples or a.samples < 4:
        sys.exit(f"--samples {a.samples}: a square sample count of at least 4 (4: 2x2 supersampling)")
    w, h = (int(v) for v in a.size.split("x"))
    os.makedirs(a.outdir, exist_ok=True)
    print(f"| scene | edge band | within 1/255 outside the band, {a.samples}x | the same, 1x | "
          f"max outside the band, {a.samples}x | RMSE, {a.samples}x | RMSE, 1x |")
    print("|---|---|---|---|---|---|---|")
    for scene in a.scenes.split(","):
        images = {}
        for name, size, samples in (("msaa", a.size, a.samples), ("one", a.size, 1), ("super", f"{k * w}x{k * h}", 1)):
            out = os.path.join(a.outdir, f"{scene}-{name}.png")
            render(a.habuffer, scene, size, samples, out)
            images[name] = mpimg.imread(out)[..., :3].astype(np.float64)
        block = images["super"].reshape(h, k, w, k, 3)
        box = block.mean(axis=(1, 3))
        edge = (block.max(axis=(1, 3)) - block.min(axis=(1, 3))).max(axis=2) > 2.0 / 255.0
        band = edge.copy()
        for dy in (-1, 0, 1):
            for dx in (-1, 0, 1):
                band |= np.roll(np.roll(edge, dy, 0), dx, 1)
        inside = ~band
        err = {n: np.abs(images[n] - box).max(axis=2) for n in ("msaa", "one")}
        within = {n: 100.0 * np.mean(err[n][inside] <= 1.0 / 255.0 + 1e-6) for n in err}
        rmse = {n: 255.0 * math.sqrt(float(np.mean(err[n] ** 2))) for n in err}
        print(f"| {scene} | {100.0 * band.mean():.1f} % of pixels | {within['msaa']:.2f} % | {within['one']:.2f} % | "
              f"{255.0 * err['msaa'][inside].max():.1f}/255 | {rmse['msaa']:.2f}/255 | {rmse['one']:.2f}/255 |")


if __name__ == "__main__":
    main()
