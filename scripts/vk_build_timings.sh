#!/usr/bin/env bash
# Issue 48's interleaved build-lists timings (docs/performance.md, "Issue 48,
# second part"): one 512x512 stream at load 0.8, each round sorted-lists and
# the k-buffer (K 4, occupancy map) in L64 and L32 on gl then vk, then ha and
# the k-buffer (K 4) in L64 on vk native64, vk emulated64 and gl emulated64.
# Prints one line a run: technique layout path mode build_ms [vk_deferred].
# Usage (repository root, after a release build): scripts/vk_build_timings.sh [ROUNDS]
set -euo pipefail
bin=$PWD/build/bin/habuffer
rounds=${1:-4}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
"$bin" generate --screen 512x512 --out f.csv --load 0.8 --seed 21 2>/dev/null
ms() { grep -o '"build_ms":[0-9.]*' s.json | cut -d: -f2; }
for _ in $(seq 1 "$rounds"); do
  for t in sorted-lists kbuffer; do
    extra=()
    [[ $t == kbuffer ]] && extra=(--layers 4 --occupancy on)
    for layout in 64 32; do
      for p in gl vk; do
        "$bin" build-lists --in f.csv --out o.csv --screen 512x512 --technique $t --layout $layout "${extra[@]}" \
          --path $p --stats s.json 2>/dev/null
        echo "$t $layout $p default $(ms)"
      done
    done
  done
  for t in ha kbuffer; do
    extra=()
    [[ $t == kbuffer ]] && extra=(--layers 4)
    for m in native64 emulated64; do
      HABUFFER_ATOMIC_MODE=$m "$bin" build-lists --in f.csv --out o.csv --screen 512x512 --technique $t "${extra[@]}" \
        --path vk --stats s.json 2>/dev/null
      echo "$t 64 vk $m $(ms) $(grep -o '"vk_deferred":[0-9]*' s.json)"
    done
    HABUFFER_ATOMIC_MODE=emulated64 "$bin" build-lists --in f.csv --out o.csv --screen 512x512 --technique $t \
      "${extra[@]}" --path gl --stats s.json 2>/dev/null
    echo "$t 64 gl emulated64 $(ms)"
  done
done
