#!/usr/bin/env bash
# Sets everything up, builds, and runs the main job: renders the `engine`
# scene (Debian's assimp-testmodels) headless through the HA-buffer at
# 1024x1024, writing out/engine.png, its stats (out/engine-stats.json) and
# its depth-complexity heat map (out/engine-depth.png), and prints a
# three-line summary. Extra arguments go to `habuffer render`.
set -euo pipefail
cd "$(dirname "$0")/.."
# Only the CLI and the libraries it links: the tests, benchmarks, viewer and
# Python module wait for scripts/test.sh, so the image comes minutes sooner.
./scripts/build.sh release habuffer >/dev/null
mkdir -p out
./build/bin/habuffer render --scene engine --size 1024x1024 --out out/engine.png --stats out/engine-stats.json \
  --heatmap depth:out/engine-depth.png "$@"
