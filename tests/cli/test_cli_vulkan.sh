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

for cls in info lists modes usage data outputs; do echo "class $cls: ${tried[$cls]:-0} cases"; done
echo "cli vulkan: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
