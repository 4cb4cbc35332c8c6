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
# The last build was L64: native64 where the device has 64-bit buffer atomics (lavapipe does).
if grep -q "shaderBufferInt64Atomics: yes" info.txt; then
  grep -q '"vk_atomic_mode":"native64"' vk.json && ok modes || bad modes "L64 did not run native64: $(cat vk.json)"
fi

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

# --- Misuse, one line each ---------------------------------------------------
expect usage 2 "option --threads has no effect with --path vk" -- build-lists --in f.csv --out x.csv --screen 96x64 \
  --path vk --threads 2
expect usage 2 "option --path: 'metal' is not cpu, gl or vk" -- build-lists --in f.csv --out x.csv --screen 96x64 \
  --path metal
expect usage 2 "option --path: 'vk' is not cpu or gl" -- demo --path vk
expect data 1 "does not run arrays yet (it runs ha, lists, sorted-lists, kbuffer)" -- build-lists --in f.csv --out x.csv \
  --screen 96x64 --path vk --technique arrays
HABUFFER_VK_DEVICE=97 expect data 1 "device 97 (HABUFFER_VK_DEVICE) is not among the Vulkan devices" -- \
  build-lists --in f.csv --out x.csv --screen 96x64 --path vk
HABUFFER_ATOMIC_MODE=emulated64 expect data 1 "does not run emulated64 yet" -- \
  build-lists --in f.csv --out x.csv --screen 96x64 --path vk
[[ ! -e x.csv ]] && ok outputs || bad outputs "a refused build left x.csv"
expect usage 2 "option --threads has no effect with --path vk" -- render --scene quads --size 32x32 --out y.png \
  --path vk --threads 2
expect usage 2 "--fragments renders on the CPU path: drop --path vk" -- render --fragments f.csv --size 96x64 \
  --out y.png --path vk
expect data 1 "does not run arrays yet" -- render --scene quads --size 32x32 --out y.png --path vk --technique arrays
[[ ! -e y.png ]] && ok outputs || bad outputs "a refused render left y.png"

for cls in info lists modes render usage data outputs; do echo "class $cls: ${tried[$cls]:-0} cases"; done
echo "cli vulkan: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
