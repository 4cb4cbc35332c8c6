#!/usr/bin/env bash
# Runs a GoogleTest binary as N shard processes at once (GTEST_TOTAL_SHARDS,
# GTEST_SHARD_INDEX), each shard's output after the others'; exit 1 when any
# shard failed. Shaders compile on the CPU, so on a GPU machine with many
# cores the GL tests finish several times sooner (scripts/gpu_checks.sh).
# Usage: scripts/gtest_shards.sh N COMMAND [ARGS...]
set -uo pipefail
n=${1:?usage: scripts/gtest_shards.sh N COMMAND [ARGS...]}
shift
logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT
pids=()
for ((i = 0; i < n; ++i)); do
  GTEST_TOTAL_SHARDS=$n GTEST_SHARD_INDEX=$i "$@" >"$logs/$i.log" 2>&1 &
  pids+=($!)
done
rc=0
for p in "${pids[@]}"; do wait "$p" || rc=1; done
for ((i = 0; i < n; ++i)); do
  echo "-- shard $i of $n"
  cat "$logs/$i.log"
done
exit $rc
