#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan+UBSan) and runs each for a bounded
# time over a scratch copy of its corpus in tests/fuzz/corpus/.
# Usage: scripts/fuzz.sh [seconds per target, default 30]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
targets=(csv insert ply spatial_table voxel_file)
# Only the fuzz targets and the libraries they link (not the CLI, viewer or
# Python module): the clang build is a whole second build otherwise.
./scripts/build.sh fuzz "${targets[@]/#/fuzz_}"
for target in "${targets[@]}"; do
  work=$(mktemp -d)
  cp tests/fuzz/corpus/"$target"/* "$work"/
  echo "fuzz_$target: ${seconds}s"
  ./build-fuzz/bin/fuzz_"$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
    "$work" 2>&1 | grep -E "stat::number_of_executed_units|stat::new_units_added|ERROR|SUMMARY|Done" || true
  # libFuzzer exits non-zero on a crash; rerun the corpus once to turn that into this script's status.
  ./build-fuzz/bin/fuzz_"$target" -runs=0 "$work" >/dev/null 2>&1
  rm -rf "$work"
done
