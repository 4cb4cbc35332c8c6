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
  # Crash, leak and timeout inputs go to fuzz-artifacts/TARGET/ (the run's
  # status is the grep's: an input that ended the run fails the script below).
  mkdir -p fuzz-artifacts/"$target"
  ./build-fuzz/bin/fuzz_"$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
    -artifact_prefix=fuzz-artifacts/"$target"/ "$work" 2>&1 |
    grep -E "stat::number_of_executed_units|stat::new_units_added|ERROR|SUMMARY|Done" || true
  rm -rf "$work"
  if [[ -n $(ls -A fuzz-artifacts/"$target") ]]; then
    echo "fuzz_$target: inputs that ended the run, kept in fuzz-artifacts/$target/: $(ls fuzz-artifacts/"$target" | tr '\n' ' ')"
    exit 1
  fi
  rmdir fuzz-artifacts/"$target"
done
rmdir fuzz-artifacts 2>/dev/null || true
