#!/usr/bin/env bash
# Regenerates docs/results.md and its figures from scratch: sets up, builds,
# runs every harness command (sweeps on both paths, bench, seed 000's Fig. 2,
# Fig. 8 and Table 1, seed 001's Fig. 10, the speed-accuracy frontier and the
# plan) into docs/results/ as JSON and CSV, then plots them.
#   --quick   small sizes, a few minutes on a 2-core machine (under 10)
#   default   the full sizes (512x512, more repetitions; about an hour here)
set -euo pipefail
cd "$(dirname "$0")/.."
mode=full
[[ "${1:-}" == "--quick" ]] && mode=quick
[[ $# -gt 0 && "$1" != "--quick" ]] && { echo "usage: scripts/reproduce.sh [--quick]" >&2; exit 2; }
./scripts/build.sh release >/dev/null
H=./build/bin/habuffer
R=docs/results
mkdir -p "$R"
# Only what this script writes: docs/results also keeps tables made elsewhere
# (the H100 runs, issue 11's technique tables), which it must not delete.
for t in sweep-ha-cpu sweep-ha-gl sweep-lists-cpu sweep-arrays-cpu sweep-kbuffer-cpu bench fig2 fig8 fig10 table1 \
         frontier frontier-picks plan csg-peers; do
  rm -f "$R/$t.json" "$R/$t.csv"
done
rm -f "$R"/sweep.png "$R"/fig2.png "$R"/fig8.png "$R"/fig10.png "$R"/frontier.png "$R"/csg-peers.png
if [[ $mode == quick ]]; then
  size=128x128; reps=3; gl_reps=2; hair=hairball:count=600; quads=quads:count=64; frames=12; planes=16
  loads=0.3,0.5,0.7,0.8,0.9,0.95
else
  size=512x512; reps=5; gl_reps=3; hair=hairball; quads=quads:count=256; frames=24; planes=32
  loads=0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,0.95,0.99
fi
start=$SECONDS
step() { echo "reproduce ($mode, $((SECONDS - start)) s): $*"; }

step "sweeps: the HA-buffer on both paths, lists, arrays and the k-buffer on the CPU path"
$H sweep --scene engine --size $size --loads $loads --repeats $reps --path cpu --out $R/sweep-ha-cpu.json,$R/sweep-ha-cpu.csv --quiet
$H sweep --scene engine --size $size --loads $loads --repeats $gl_reps --path gl --out $R/sweep-ha-gl.json,$R/sweep-ha-gl.csv --quiet
for t in lists arrays kbuffer; do
  $H sweep --scene engine --size $size --loads $loads --repeats $reps --path cpu --technique $t \
    --out $R/sweep-$t-cpu.json,$R/sweep-$t-cpu.csv --quiet
done
step "bench: techniques x scenes, interleaved, with floors"
$H bench --scenes engine,$hair,planes:order=front:count=$planes,planes:order=back:count=$planes \
  --techniques ha,ha:cull=0.99,lists,sorted-lists:cull=0.99,arrays:k=16,kbuffer:k=8,kbuffer:k=8:occ,wboit,blend \
  --size $size --repeats $reps --path cpu --out $R/bench.json,$R/bench.csv --quiet
step "Fig. 2"
$H figure fig2 --scene $hair --size $size --repeats $reps --path cpu --out $R/fig2.json,$R/fig2.csv --quiet
step "Fig. 8"
$H figure fig8 --scene $quads --frames $frames --size $size --path cpu --out $R/fig8.json,$R/fig8.csv --quiet
step "Fig. 10"
$H figure fig10 --planes $planes --size $size --repeats $reps --path cpu --out $R/fig10.json,$R/fig10.csv --quiet
step "Table 1"
$H figure table1 --out $R/table1.json,$R/table1.csv --quiet
step "frontier"
$H figure frontier --scenes engine,$hair --size $size --repeats $reps --path cpu --out $R/frontier.json,$R/frontier.csv \
  --picks $R/frontier-picks.json,$R/frontier-picks.csv --quiet
step "plan"
$H plan --scene engine --size $size --out $R/plan.json,$R/plan.csv
if [[ -x ./build/bin/habuffer_csg_peers ]]; then
  step "CSG beside OpenCSG (GPL-2+, a benchmark binary; built where libopencsg-dev is found)"
  csg_size=128x128; [[ $mode == full ]] && csg_size=256x256
  ./build/bin/habuffer_csg_peers --size $csg_size --repeats $reps --out $R/csg-peers.json,$R/csg-peers.csv >/dev/null
fi
step "plots and docs/results.md"
py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3  # Debian's, with python3-matplotlib
$py scripts/plot_results.py $R docs/results.md $mode
step "done"
