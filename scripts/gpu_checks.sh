#!/usr/bin/env bash
# The GPU path's checks on a machine with a real GPU, from the bundle of
# scripts/device_bundle.sh: what the machine is, `habuffer info`, the GL
# tests (every runnable atomic mode), the scene tests without image files,
# the GL benchmarks, the technique table of `habuffer bench` and renders'
# stats. Usage (repository root): scripts/gpu_checks.sh OUTDIR [STEPS]
# STEPS: a comma list of info,tests,render-tests,bench,harness,render (all).
# Every step has its own time limit and goes on after a failure; the log is
# OUTDIR/gpu.log, results OUTDIR/*.json and *.csv.
set -uo pipefail
out=${1:?usage: scripts/gpu_checks.sh OUTDIR [STEPS]}
steps=${2:-info,tests,render-tests,bench,harness,render}
mkdir -p "$out"
# shellcheck disable=SC1091
source .dev/run.sh
log="$out/gpu.log"
want() { [[ ",$steps," == *",$1,"* ]]; }
step() {  # step LIMIT_S NAME COMMAND...
  local limit=$1 name=$2; shift 2
  echo "== $name: $*" | tee -a "$log"
  local t0=$SECONDS
  timeout "$limit" "$@" >>"$log" 2>&1
  local rc=$?
  echo "== $name: rc=$rc after $((SECONDS - t0)) s" | tee -a "$log"
}
if want info; then
  step 30 nvidia-smi nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv
  step 60 info habuffer info
fi
if want tests; then  # every runnable mode: the default (native64 on NVIDIA) and emulated64 forced
  step 240 gl-tests habuffer_gl_tests --gtest_brief=1
  step 240 gl-tests-emulated64 env HABUFFER_ATOMIC_MODE=emulated64 habuffer_gl_tests --gtest_brief=1
fi
want render-tests && step 240 render-tests habuffer_render_tests --gtest_brief=1
if want bench; then
  step 300 gl-bench habuffer_bench --benchmark_filter='BM_GlInsert|BM_Render|BM_Technique/[a-z-]+/gl/' \
    --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
    --benchmark_out="$out/gl-bench.json" --benchmark_out_format=json
fi
if want harness; then
  step 300 harness habuffer bench --path gl --quiet --repeats 5 --size 512x512,1024x1024 \
    --scenes engine,hairball,planes:order=front:count=32,planes:order=back:count=32 \
    --techniques ha,ha:cull=0.99,sorted-lists,sorted-lists:cull=0.99,lists,arrays:k=16,kbuffer:k=4,kbuffer:k=8,kbuffer:k=8:occ,kbuffer:k=16,wboit,blend \
    --out "$out/techniques.json,$out/techniques.csv"
fi
if want render; then
  for scene in engine hairball; do
    step 120 "render-$scene" habuffer render --scene "$scene" --size 2048x2048 --path gl --quiet --stats "$out/render-$scene.json"
  done
fi
exit 0
