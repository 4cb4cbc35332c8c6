#!/usr/bin/env bash
# Issue 48's bar through the CLI: `habuffer info` names the Vulkan device,
# `build-lists --path vk` writes the CPU's lists byte for byte on streams of
# several shapes, layouts and sizes (lossless regathers included), with the
# validation layer on; misuse is one line. Exits 77 (ctest's skip) where the
# build or the machine has no Vulkan.
set -u
bin=$1
dir=$2
# shellcheck source=cli_common.sh
source "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/cli_common.sh"  # enters a fresh $dir
# The validation layer where it is installed (scripts/setup.sh installs it).
for d in /usr/share/vulkan/explicit_layer.d /etc/vulkan/explicit_layer.d; do
  [[ -e $d/VkLayer_khronos_validation.json ]] && export HABUFFER_VK_VALIDATION=1
done

"$bin" info >info.txt 2>&1
if grep -q "^  vk: not built\|^  vk: unavailable" info.txt; then
  echo "SKIP: $(grep '^  vk:' info.txt)"
  exit 77
fi
grep -q "^  vk: device [0-9]* used" info.txt && grep -q "\[used\]" info.txt && ok info ||
  bad info "info names no Vulkan device: $(grep -A3 '^  vk:' info.txt)"

# --- The CPU's lists, byte for byte -------------------------------------------
same() {  # SCREEN GENERATE-ARGS -- BUILD-ARGS
  local screen=$1 gen=$2
  shift 3
  "$bin" generate --screen "$screen" --out f.csv $gen 2>/dev/null || { bad lists "generate $gen failed"; return; }
  "$bin" build-lists --in f.csv --out cpu.csv --screen "$screen" "$@" 2>cpu.err
  local c=$?
  "$bin" build-lists --in f.csv --out vk.csv --screen "$screen" --path vk --stats vk.json "$@" 2>vk.err
  local v=$?
  if [[ $c -ne 0 || $v -ne 0 ]]; then
    bad lists "$screen $gen $*: exit cpu $c, vk $v: $(head -c 300 vk.err)"
  elif ! cmp -s cpu.csv vk.csv; then
    bad lists "$screen $gen $*: the lists differ"
  elif ! grep -q '"path":"vk"' vk.json; then
    bad lists "$screen $gen $*: the stats do not say path vk"
  else
    ok lists
  fi
}
same 96x64 "--load 0.8 --seed 11" --
same 96x64 "--load 0.8 --seed 11" -- --layout 32
same 131x77 "--load 0.6 --stream random --seed 12" -- --table 160x90 --age-bits 6
same 50x40 "--load 2.5 --seed 13" -- --lossless --max-attempts 6
same 50x40 "--load 2.5 --seed 13" -- --lossless --max-attempts 6 --layout 32
same 64x64 "--fragments 3000 --seed 14 --min-side 1 --max-side 3" -- --block 4 --offsets farthest
same 96x64 "--load 1.7 --seed 15" -- --technique lists
same 96x64 "--load 1.7 --seed 15" -- --technique lists --layout 32
same 96x64 "--load 1.7 --seed 15" -- --technique lists --pool 3000 --lossless --max-attempts 4
same 70x50 "--load 2 --stream random --seed 17" -- --technique sorted-lists --layout 32
same 96x64 "--load 2 --seed 21" -- --technique kbuffer --layers 4
same 96x64 "--load 2 --seed 21" -- --technique kbuffer --layers 4 --occupancy on --occupancy-words 1 --layout 32
same 80x60 "--load 2.5 --seed 22" -- --technique kbuffer --layers 2 --occupancy on --lossless --max-attempts 5
same 96x64 "--load 3 --seed 16" -- --technique sorted-lists
same 96x64 "--load 2 --seed 23" -- --technique arrays --layers 24
same 80x60 "--load 2.5 --seed 24" -- --technique arrays --layers 2 --lossless --max-attempts 4
same 96x64 "--load 2 --seed 25" -- --technique paged-lists
same 96x64 "--load 2 --seed 26" -- --technique paged-lists --pool 2000 --lossless --max-attempts 4
# The last build was L64: native64 where the device has 64-bit buffer atomics (lavapipe does).
if grep -q "shaderBufferInt64Atomics: yes" info.txt; then
  grep -q '"vk_atomic_mode":"native64"' vk.json && ok modes || bad modes "L64 did not run native64: $(cat vk.json)"
fi

# emulated64 (HABUFFER_ATOMIC_MODE forces it): the per-slot locks, the calls
# they cut short resumed round by round (a hot random stream at load 3 has
# lanes of one SIMD group meet at one lock on lavapipe), the CPU's lists.
export HABUFFER_ATOMIC_MODE=emulated64
same 128x128 "--load 3 --stream random --seed 31" -- --lossless --max-attempts 8
grep -q '"vk_atomic_mode":"emulated64"' vk.json && ok modes || bad modes "emulated64 did not run: $(head -c 300 vk.json)"
if grep -q '"software":true\|llvmpipe' vk.json; then
  grep -q '"vk_deferred":[1-9]' vk.json && ok modes || bad modes "no call was deferred and resumed: $(grep -o '"vk_[a-z_]*":[^,]*' vk.json)"
fi
same 96x64 "--load 2 --seed 21" -- --technique kbuffer --layers 4 --occupancy on
same 96x64 "--load 1.7 --seed 15" -- --technique sorted-lists
unset HABUFFER_ATOMIC_MODE

# --- render --path vk: the CPU path's image, float for float ------------------
# GL rasterizes and captures for both; the technique is built and resolved
# on the Vulkan device against the CPU's build and composite.
render_same() {  # SCENE TECHNIQUE RENDER-ARGS...
  local scene=$1 technique=$2
  shift 2
  "$bin" render --scene "$scene" --technique "$technique" --path cpu --out cpu.exr "$@" 2>r_cpu.err
  local c=$?
  "$bin" render --scene "$scene" --technique "$technique" --path vk --out vk.exr --stats vk_render.json "$@" 2>r_vk.err
  local v=$?
  if [[ $c -ne 0 || $v -ne 0 ]]; then
    bad render "$scene $technique $*: exit cpu $c, vk $v: $(head -c 300 r_vk.err)"
  elif ! "$bin" compare cpu.exr vk.exr 2>&1 | grep -q "psnr inf"; then
    bad render "$scene $technique $*: $("$bin" compare cpu.exr vk.exr 2>&1 | head -1)"
  elif ! grep -q '"path":"vk"' vk_render.json || ! grep -q '"device":"vk ' vk_render.json; then
    bad render "$scene $technique $*: the stats do not say path vk and its device"
  else
    ok render
  fi
}
render_same wuson ha --size 96x72 --frames 2
render_same wuson lists --size 96x72 --frames 2
render_same spider sorted-lists --size 80x64 --layout 32
render_same spider kbuffer --size 80x64 --layers 4 --occupancy on
render_same hairball ha --size 64x48 --table 64x48 --lossless --max-attempts 6
render_same quads lists --size 64x48 --samples 4
render_same wuson arrays --size 80x64 --layers 4 --lossless --max-attempts 4  # K grown: no pixel keeps an arrival-order subset
render_same quads paged-lists --size 64x48 --samples 4
HABUFFER_ATOMIC_MODE=emulated64 render_same spider ha --size 80x64 --frames 2
grep -q '"device":"vk emulated64' vk_render.json && ok modes || bad modes "render did not run emulated64"

# --- bench and figure frontier on vk ------------------------------------------
# The same rows as the CPU path's where they do not time: stored, failures,
# the image's psnr against the reference; frontier leaves out what vk does
# not run.
cols() {  # FILE: technique,stored,failures,psnr per row
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
           { print $c["technique"] "," $c["stored"] "," $c["failures"] "," $c["psnr"] }' "$1"
}
if "$bin" bench --scenes quads,wuson --techniques ha,lists,sorted-lists,kbuffer:k=4:occ --size 48x40 --repeats 1 \
     --path vk --no-floors --quiet --out bench_vk.csv 2>b.err &&
   "$bin" bench --scenes quads,wuson --techniques ha,lists,sorted-lists,kbuffer:k=4:occ --size 48x40 --repeats 1 \
     --path cpu --no-floors --quiet --out bench_cpu.csv 2>>b.err; then
  if [[ "$(cols bench_vk.csv)" == "$(cols bench_cpu.csv)" ]] && [[ $(grep -c ',vk,' bench_vk.csv) -eq 8 ]]; then
    ok harness
  else
    bad harness "bench --path vk differs from --path cpu: $(diff <(cols bench_vk.csv) <(cols bench_cpu.csv) | head -4)"
  fi
else
  bad harness "bench failed: $(head -c 300 b.err)"
fi
if "$bin" figure frontier --scenes quads --size 32x32 --repeats 1 --path vk --quiet --out frontier_vk.csv 2>f.err; then
  if grep -qE '^(wboit|blend)' frontier_vk.csv || ! grep -q '^sorted-lists,quads,32x32,vk' frontier_vk.csv ||
     ! grep -q '^arrays:k=4,quads,32x32,vk' frontier_vk.csv; then
    bad harness "figure frontier --path vk: rows $(cut -d, -f1 frontier_vk.csv | tr '\n' ' ')"
  else
    ok harness
  fi
else
  bad harness "figure frontier --path vk failed: $(head -c 300 f.err)"
fi

# --- Misuse, one line each ---------------------------------------------------
expect usage 2 "option --threads has no effect with --path vk" -- build-lists --in f.csv --out x.csv --screen 96x64 \
  --path vk --threads 2
expect usage 2 "option --path: 'metal' is not cpu, gl or vk" -- build-lists --in f.csv --out x.csv --screen 96x64 \
  --path metal
expect usage 2 "option --path: 'vk' is not cpu or gl" -- demo --path vk
HABUFFER_VK_DEVICE=97 expect data 1 "device 97 (HABUFFER_VK_DEVICE) is not among the Vulkan devices" -- \
  build-lists --in f.csv --out x.csv --screen 96x64 --path vk
HABUFFER_ATOMIC_MODE=native128 expect data 1 "HABUFFER_ATOMIC_MODE='native128' is not native32, native64" -- \
  build-lists --in f.csv --out x.csv --screen 96x64 --path vk
[[ ! -e x.csv ]] && ok outputs || bad outputs "a refused build left x.csv"
expect usage 2 "option --threads has no effect with --path vk" -- render --scene quads --size 32x32 --out y.png \
  --path vk --threads 2
expect usage 2 "--fragments renders on the CPU path: drop --path vk" -- render --fragments f.csv --size 96x64 \
  --out y.png --path vk
expect data 1 "does not run blend yet (it runs ha, lists, sorted-lists, arrays, kbuffer, paged-lists)" -- \
  render --scene quads --size 32x32 --out y.png --path vk --technique blend
[[ ! -e y.png ]] && ok outputs || bad outputs "a refused render left y.png"
expect usage 2 "option --path vk: figure fig10 runs on gl or cpu" -- figure fig10 --path vk --out z.csv

for cls in info lists modes render harness usage data outputs; do echo "class $cls: ${tried[$cls]:-0} cases"; done
echo "cli vulkan: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
