#!/usr/bin/env bash
# Sets everything up, builds, and runs the main job. Until the render issue
# lands, that is the CPU path on a generated, rasterization-like stream of
# 2^20 fragments on a 1024x1024 screen: it builds the sorted lists with one
# thread and with every thread, checks both tables are bit-identical, and
# writes its stats to out/demo-stats.json.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh release >/dev/null
mkdir -p out
./build/bin/habuffer demo --screen 1024x1024 --load 0.5 --stats out/demo-stats.json "$@"
echo "stats: out/demo-stats.json"
