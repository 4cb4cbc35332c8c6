#!/usr/bin/env bash
# The GPU path's checks on a machine with a real GPU (NVIDIA, headless EGL),
# from the bundle of scripts/device_bundle.sh, in one command of under 10
# minutes: what the machine is, the GL tests, issue 22's spatial hash on the GPU
# (BM_GlSpatial beside the CPU's rates), issue 20's translucent shadows
# (Fig. 2 with and without them, the shadow frontier), issue 26's measurements (render's
# gather with and without its per-fragment bookkeeping, the module's
# read-first variants, the captured hairball stream through the compute entry
# in arrival and in pixel order, the compute entry at 2^24 fragments, the
# technique table of `habuffer bench` on engine, hairball and spider at 512
# and 1024, hairball at three loads, BM_Technique beside `habuffer bench`),
# issue 36's GPU traffic model beside the measurement (`bench --model gpu`
# on the GL path, then scripts/gpu_model_check.py: Spearman per scene, HA /
# lists measured and predicted), issue 48's Vulkan tests (the host frame driver's included), lists and renders (vk against cpu, gl's times beside), issue 37's multisampled renders (each technique
# of lists at 1 and 4 samples on engine and hairball), then the older checks as time allows (GL tests in emulated64, the scene
# tests, renders' stats, issue 11's whole technique table).
#
# Usage (repository root): scripts/gpu_checks.sh [--smoke|--dry-run] OUTDIR [STEPS]
#   STEPS    a comma list of the step names below (default: all, in that order)
#   --smoke  every step at toy sizes (64x64, 256-pixel benchmarks, 2^18
#            fragments, 1 repeat, a few tests), to try the script on llvmpipe
#   --dry-run  print each step's command and time limit, run nothing
# Each step has its own time limit and all of them share one deadline
# (GPU_CHECKS_BUDGET_S, 540 s): a step that would start with less than 20 s
# left is skipped, so a slow step cannot eat the rest, and the script ends in
# time. Everything goes on after a failure. OUTDIR holds two files (the
# device machine returns few): gpu.log, the commands, their output (every
# benchmark repetition as it ends), exit codes and times; results.tar.gz,
# every result file (*.json, *.csv), repacked after each step so a run cut
# short still returns what it finished. A benchmark writes its JSON only when
# it ends, so the long ones are split (one per side).
set -uo pipefail
mode=run
case "${1:-}" in
  --smoke) mode=smoke; shift ;;
  --dry-run) mode=dry; shift ;;
esac
out=${1:?usage: scripts/gpu_checks.sh [--smoke|--dry-run] OUTDIR [STEPS]}
all_steps=info,adaptive,gl-tests,vk,spatial,shadows,gather,harness,model,msaa,captured,insert,loads,technique,gl-tests-emulated64,render-tests,render,techniques-all
steps=${2:-$all_steps}
budget=${GPU_CHECKS_BUDGET_S:-540}
mkdir -p "$out"
out=$(cd "$out" && pwd)
repo=$PWD
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [[ -f .dev/run.sh ]]; then
  # shellcheck disable=SC1091
  source .dev/run.sh
else
  export PATH="$PWD/build/bin:$PATH"  # a local build (the smoke run)
fi
log="$out/gpu.log"
: >"$log"
deadline=$((SECONDS + budget))
want() { [[ ",$steps," == *",$1,"* ]]; }
pack() { tar czf "$out/results.tar.gz" -C "$work" . 2>>"$log"; }
# step LIMIT_S NAME COMMAND...: runs COMMAND in the results folder, within
# LIMIT_S and the shared deadline.
step() {
  local limit=$1 name=$2; shift 2
  local left=$((deadline - SECONDS))
  ((limit > left)) && limit=$left
  if [[ $mode == dry ]]; then
    echo "== $name (limit ${limit} s): $*"
    return
  fi
  if ((limit < 20)); then
    echo "== $name: skipped, ${left} s left of the ${budget} s budget" | tee -a "$log"
    return
  fi
  echo "== $name (limit ${limit} s): $*" | tee -a "$log"
  local t0=$SECONDS
  (cd "$work" && timeout "$limit" "$@") >>"$log" 2>&1
  local rc=$?
  echo "== $name: rc=$rc after $((SECONDS - t0)) s" | tee -a "$log"
  pack
}
# sharded N LIMIT_S NAME COMMAND...: a test binary as N shard processes at
# once (scripts/gtest_shards.sh).
sharded() {
  local n=$1 limit=$2 name=$3; shift 3
  step "$limit" "$name" "$repo/scripts/gtest_shards.sh" "$n" "$@"
}

# Sizes, repeats and filters: the real run, or toys for --smoke.
if [[ $mode == smoke ]]; then
  sizes=64x64 repeats=1 sides='256' model_size=64x64 gtest_filter='GlBookkeeping.*:GlFrame.*:GlAdaptive.*:Render.Planes*'
  adaptive_sides='32'
  render_size=96x96 msaa_size=64x64 bench_time=0.05 bench_reps=1 log2n='18' l64=emulated64  # llvmpipe has no native64
  fig2_size=64x64 light_size=128x128
  spatial_gpu_filter='BM_GlSpatial/image/'
  spatial_cpu_filter='BM_Spatial/image/build/ours-load-0.80/threads-2'
else
  sizes=512x512,1024x1024 repeats=3 sides='512|1024' model_size=1024x1024 gtest_filter='*'
  adaptive_sides='64 256'
  render_size=2048x2048 msaa_size=512x512 bench_time=0.2 bench_reps=3 log2n='18|24' l64=native64
  fig2_size=1024x1024 light_size=2048x2048
  spatial_gpu_filter='BM_GlSpatial/[a-z]+/'
  spatial_cpu_filter='BM_Spatial/(image|shell)/(build|hits-row-major|hits-shuffled|misses)/(ours-load-0.(80|99)|absl)'
fi
bench_flags=(--benchmark_min_time="$bench_time" --benchmark_repetitions="$bench_reps"
             --benchmark_enable_random_interleaving=true --benchmark_out_format=json)

if want info; then
  if [[ $mode != smoke ]]; then
    step 30 nvidia-smi nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv
  fi
  step 30 uptime uptime
  step 60 info habuffer info
fi
# Every GL test in the default mode (native64 on NVIDIA).
# Issue 45: jumps and drops of depth complexity through the frame driver,
# per readback mode (lossy frames, gathers at the jump, the jump frame
# against a normal one, frames to give memory back, a steady frame's cost
# Immediate against Deferred: the CPU-GPU overlap a GPU allows).
if want adaptive; then
  for side in ${adaptive_sides}; do
    step 60 "adaptive-$side" bash -c "habuffer_adaptive_jumps --size $side --repeats $repeats > adaptive-$side.md"
  done
fi
want gl-tests && sharded 4 120 gl-tests habuffer_gl_tests --gtest_brief=1 --gtest_filter="$gtest_filter"
# Issue 48: the Vulkan path on the machine's driver (NVIDIA's ICD, the
# bundle's loader): its tests without the validation layer (not installed
# there), and build-lists at load 0.8 of a 1024x1024 table against the
# CPU's and the GL path's lists.
if want vk && [ -x "$(command -v habuffer_vk_tests)" ]; then
  vk_side=1024
  [ "$mode" = smoke ] && vk_side=64
  step 90 vk-tests env HABUFFER_VK_VALIDATION=0 habuffer_vk_tests --gtest_brief=1
  step 120 vk-lists bash -c "s=${vk_side}x${vk_side}; habuffer generate --screen \$s --out vk-frags.csv --load 0.8 --seed 7 &&
    habuffer build-lists --in vk-frags.csv --out vk-cpu.csv --screen \$s --stats vk-cpu-stats.json &&
    habuffer build-lists --in vk-frags.csv --out vk-gpu.csv --screen \$s --path vk --stats vk-stats.json &&
    habuffer build-lists --in vk-frags.csv --out vk-gl.csv --screen \$s --path gl --stats vk-gl-stats.json &&
    cmp vk-cpu.csv vk-gpu.csv && cmp vk-cpu.csv vk-gl.csv && echo 'vk lists equal the cpu and gl lists' &&
    rm -f vk-frags.csv vk-cpu.csv vk-gpu.csv vk-gl.csv"
  # render --path vk against --path cpu (PSNR inf) and the GL path's times
  # on the engine for the four techniques the Vulkan path runs.
  vk_size=512x512
  [ "$mode" = smoke ] && vk_size=64x64
  step 150 vk-render bash -c "for t in ha lists sorted-lists kbuffer paged-lists; do
      habuffer render --scene engine --size $vk_size --technique \$t --frames 3 --path cpu --out vk-r-cpu.exr --stats vk-render-cpu-\$t.json &&
      habuffer render --scene engine --size $vk_size --technique \$t --frames 3 --path vk --out vk-r-vk.exr --stats vk-render-vk-\$t.json &&
      habuffer render --scene engine --size $vk_size --technique \$t --frames 3 --path gl --out vk-r-gl.exr --stats vk-render-gl-\$t.json &&
      habuffer compare vk-r-cpu.exr vk-r-vk.exr 2>&1 | grep -q 'psnr inf' && echo \"\$t: vk equals cpu\" || exit 1
    done; rm -f vk-r-cpu.exr vk-r-vk.exr vk-r-gl.exr"
fi
# Issue 22: the spatial hash on the GPU (build, hits and misses per second at
# loads 0.8 and 0.99 on the sparse image and the voxel shell, GPU time of the
# passes), beside the CPU's rates on the same keys.
# One step a pass (a benchmark writes its JSON only at its end): on the H200
# (2026-12-04) the first case reported in 1 s and the next ran out the old
# single step's 150 s, so each pass now has its own limit and output.
if want spatial; then
  for pass in build hits misses; do
    step 60 "spatial-gpu-$pass" habuffer_bench --benchmark_filter="$spatial_gpu_filter$pass" --benchmark_repetitions=3 \
      --benchmark_report_aggregates_only=true --benchmark_out="spatial-gpu-$pass.json"
  done
  step 60 spatial-cpu habuffer_bench --benchmark_filter="$spatial_cpu_filter" --benchmark_out=spatial-cpu.json
fi
# Issue 20: seed 000's Fig. 2 with and without translucent shadows (hairball,
# the four opacities, cull 0.99 in the culled rows: the paper's frame ratio
# 0.63-0.71 on a GTX 680), a render with shadows' stats, and the shadow
# frontier (light buffers scored against the ray-traced reference).
if want shadows; then
  # One repeat: three at 1024 ran past 150 s on the H200.
  step 150 fig2-shadows habuffer figure fig2 --quiet --size "$fig2_size" --repeats 1 \
    --out fig2-shadows.json,fig2-shadows.csv
  step 60 render-shadows habuffer render --scene hairball --size "$fig2_size" --shadows --light-size "$light_size" \
    --quiet --stats render-shadows.json
  step 120 shadow-frontier habuffer figure shadows --quiet --scene hairball --size 512x512 \
    --light-size "$light_size" --receivers 200000 --repeats 1 --out shadow-frontier.json,shadow-frontier.csv
fi
# render's gather in steady state, with and without the bookkeeping of issue
# 26 part 5 (bookkeeping:1 = the slot-write tally and the per-pixel counts
# render paid in every frame before), and native64 with and without the
# read-first slot load (slot_rf) and max-age read (age_rf).
if want gather; then
  for side in ${sides//|/ }; do
    step $((side > 512 ? 120 : 90)) "gather-$side" habuffer_bench \
      --benchmark_filter="BM_GlGather/(engine|hairball|spider)/[a-z0-9-]+/side:$side/" "${bench_flags[@]}" \
      --benchmark_out="gl-gather-$side.json"
  done
fi
# The technique table (first frame of a fresh renderer each round: the harness's own timing).
want harness && step 150 harness habuffer bench --path gl --quiet --repeats "$repeats" --size "$sizes" \
  --scenes engine,hairball,spider --techniques ha,ha:cull=0.99,lists,sorted-lists,sorted-lists:cull=0.99 \
  --out techniques.json,techniques.csv
# Issue 36 part 7: the GPU traffic model beside the GPU's own times (one
# repeat; the replays run one row a task on the host's cores: hairball's six
# at 1024 took 73 s on this project's 2-vCPU VM), then model against
# measurement: Spearman per scene and HA / lists.
if want model; then
  step 150 model habuffer bench --path gl --quiet --repeats 1 --no-floors --model gpu --size "$model_size" \
    --scenes engine,hairball --techniques ha,ha:cull=0.99,sorted-lists,sorted-lists:cull=0.99,lists,arrays:k=16 \
    --out model.json,model.csv
  step 20 model-check python3 "$repo/scripts/gpu_model_check.py" model.json
fi
# Issue 37: multisampled transparency on the GPU, each technique of lists at
# 1 and 4 samples per pixel on engine and hairball (render's GL path: its
# gather into a 4x framebuffer, the per-pixel resolve), three frames each;
# the stats' gather_ms and resolve_ms give the GPU's 4x / 1x.
if want msaa; then
  for scene in engine hairball; do
    step 60 "msaa-$scene" bash -c 'for t in ha lists sorted-lists paged-lists arrays kbuffer; do for s in 1 4; do
        extra=; [ $t = arrays ] && extra=--lossless
        habuffer render --scene '"$scene"' --size '"$msaa_size"' --path gl --technique $t --samples $s $extra --frames 3 \
          --quiet --stats msaa-'"$scene"'-$t-$s.json || echo "msaa '"$scene"' $t $s: rc=$?"; done; done'
  done
fi
# The captured hairball stream through the compute entry, arrival and pixel
# order, loads 0.3/0.55/0.8 and the variants, in the L64 mode the GPU runs.
# One step a side: both in one ran past 120 s on the H200 and wrote no JSON.
if want captured; then
  for side in ${sides//|/ }; do
    step 75 "captured-$side" habuffer_bench --benchmark_filter="BM_GlCaptured/hairball/(arrival|pixel)/$l64/side:$side/" \
      "${bench_flags[@]}" --benchmark_out="gl-captured-$side.json"
  done
fi
# The compute entry on synthetic coherent streams, 2^18 (dispatch-bound on a
# GPU) and 2^24 fragments, native32 (the L32 goal: 4.4 G frag/s at load 0.5) and native64.
want insert && step 90 insert habuffer_bench --benchmark_filter="BM_GlInsertNative(32|64)/load:[0-9]+/log2n:($log2n)/" \
  "${bench_flags[@]}" --benchmark_out=gl-insert.json
want loads && step 90 loads habuffer bench --path gl --quiet --no-floors --repeats "$repeats" --size "$sizes" \
  --scenes hairball --techniques ha:load=0.3,ha:load=0.55,ha:load=0.8 --out loads.json,loads.csv
# Issue 26 part 6: BM_Technique beside the harness on the same scene and machine.
# Every repetition kept: its H100 median (35.9 ms) hid one repetition of 88 ms.
want technique && step 90 technique habuffer_bench --benchmark_filter='BM_Technique/hairball/gl/(ha|lists)/' \
  --benchmark_repetitions="$bench_reps" --benchmark_out=gl-technique.json --benchmark_out_format=json
# Older checks, as time allows.
want gl-tests-emulated64 && sharded 4 120 gl-tests-emulated64 env HABUFFER_ATOMIC_MODE=emulated64 \
  habuffer_gl_tests --gtest_brief=1 --gtest_filter="$gtest_filter"
want render-tests && sharded 4 120 render-tests habuffer_render_tests --gtest_brief=1 --gtest_filter="$gtest_filter"
if want render; then
  for scene in engine hairball; do
    step 60 "render-$scene" habuffer render --scene "$scene" --size "$render_size" --path gl --quiet --slot-writes \
      --stats "render-$scene.json"
  done
fi
want techniques-all && step 240 techniques-all habuffer bench --path gl --quiet --repeats 1 --size "$sizes" \
  --scenes engine,hairball,planes:order=front:count=32,planes:order=back:count=32 \
  --techniques ha,ha:cull=0.99,sorted-lists,sorted-lists:cull=0.99,lists,arrays:k=16,kbuffer:k=4,kbuffer:k=8,kbuffer:k=8:occ,kbuffer:k=16,wboit,blend \
  --out techniques-all.json,techniques-all.csv
[[ $mode == dry ]] || echo "== done after $SECONDS s; results: $out/results.tar.gz" | tee -a "$log"
exit 0
