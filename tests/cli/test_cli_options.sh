#!/usr/bin/env bash
# Issue 34: every declared option is read. Each option of every command and
# subcommand (as its --help lists it) is run by some CLI test, and every run
# of these scripts has HABUFFER_CHECK_OPTIONS=1 (cli_common.sh): a command
# that returns without reading an option it was given exits 70 naming it.
# This script runs the options no other script runs (each either changes
# the run or is refused in context), then checks that no option of any
# command is left without a run: a new option without one fails here.
set -u
bin=$1
dir=$2
tests=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=cli_common.sh
source "$tests/cli_common.sh"  # enters a fresh $dir

"$bin" generate --screen 16x16 --fragments 300 --out f.csv >/dev/null 2>&1
"$bin" render --scene quads --count 4 --size 8x8 --out img.png --quiet >/dev/null 2>&1

# --- Options read (exit 0), or refused in context (exit 2, naming why) -----
expect read 0 "" -- build-lists --in f.csv --out l.csv --screen 16x16 --technique kbuffer --layers 4 --occupancy on --occupancy-words 2 --depth-range 0,1
expect read 0 "" -- build-lists --in f.csv --out l.csv --screen 16x16 --early-cull 0.9 --saturation on --block 4 --insert-order pixel
expect read 0 "" -- generate --screen 16x16 --fragments 100 --stream coherent --max-side 8 --out g.csv
expect read 0 "" -- offsets --table 16x16 --count 10 --out o.csv
expect read 0 "" -- demo --screen 16x16 --layout 32 --seed 3 --block 4 --iter-limit 1000 --insert-order arrival
expect read 0 "" -- demo --screen 16x16 --early-cull 0.9
expect read 2 "demo does not take --lossless" -- demo --screen 16x16 --lossless --max-attempts 2
expect read 0 "" -- stats --screen 16x16 --loads 0.5 --trials 1 --seed 2 --block 4 --out s.csv --quiet
expect read 0 "" -- stats --keys sparse-image --domain 16x16 --coverage 0.5 --loads 0.5 --trials 1 --misses 10 --out k.csv
expect read 0 "" -- stats --keys random --domain 16x16 --count 20 --loads 0.5 --trials 1 --out k2.csv
expect read 0 "" -- plan --scene quads:count=4 --size 16x16 --loads 0.5,0.9 --trials 1 --seed 2 --out p.json --quiet
expect read 0 "" -- plan --scene quads:count=4 --size 16x16 --loads 0.5 --trials 1 --memory-budget 20 --out pb.json --quiet
expect read 0 "" -- csg --solids "A=box:0,0,0,1,1,1;B=sphere:0.5,0.5,0.5,0.6" --expr "A-B" --size 32x24 --yaw 10 --pitch 5 --fov 50 --path cpu --reference --quiet --stats c.json
expect read 0 "" -- hash build --key-set sparse-image --domain 32x32 --coverage 0.3 --seed 2 --offsets farthest --threads 2 --out t.tab --quiet
expect read 0 "" -- hash build --key-set random --domain 32x32 --count 100 --out t2.tab --quiet
expect read 0 "" -- hash build --image img.png --background 0,0,0 --out ti.tab --quiet
expect read 0 "" -- hash image --table ti.tab --out back.png --background 0.5,0.5,0.5
expect read 0 "" -- render --scene hairball --count 4 --size 16x16 --out r.png --yaw 10 --pitch 5 --fov 50 --background 0,0,0 --error --scene-seed 3 --quiet
expect read 0 "" -- render --scene quads --count 4 --size 16x16 --out r.png --technique kbuffer --layers 4 --occupancy on --occupancy-words 2 --depth-range 0.1,0.9 --quiet
expect read 0 "" -- render --scene quads --count 4 --size 16x16 --out r.png --technique lists --pool 10000 --quiet
expect read 0 "" -- render --scene quads --count 4 --size 16x16 --out r.png --path cpu --block 4 --iter-limit 1000 --offsets farthest --seed 3 --max-attempts 2 --insert-order pixel --quiet
expect read 0 "" -- render --scene quads --count 4 --size 16x16 --out r.png --shadows --light-pos 3,10,3 --light-table auto --shadow-error 10 --light-size 32x32 --quiet
expect read 0 "" -- sweep --scene quads:count=4 --size 16x16 --loads 0.2 --repeats 1 --path cpu --seed 3 --insert-order pixel --out sw.json --quiet
expect read 0 "" -- bench --scenes quads:count=4 --techniques ha --size 16x16 --repeats 1 --path cpu --seed 3 --insert-order pixel --out b.json --quiet
expect read 0 "" -- techniques --markdown
expect read 0 "" -- render --scene quads --count 4 --size 16x16 --out r.png --slot-writes --quiet
# Issue 37: multisampled records on both paths, and the refusals in context.
expect read 0 "" -- render --scene quads --count 4 --size 16x16 --out r.png --samples 4 --path cpu --error --quiet
expect read 0 "" -- render --scene quads --count 4 --size 16x16 --out r.png --samples 4 --technique lists --quiet
expect read 0 "" -- build-lists --in f.csv --out ls.csv --screen 16x16 --samples 4 --technique sorted-lists
expect read 2 "option --samples: 3 is not a power of two in 1..8" -- build-lists --in f.csv --out l.csv --screen 16x16 --samples 3
expect read 2 "wboit stores none" -- render --scene quads --count 4 --size 16x16 --out r.png --samples 4 --technique wboit --quiet
expect read 2 "translucent shadows are not drawn on a multisampled screen" -- render --scene quads --count 4 --size 16x16 --out r.png --samples 4 --shadows --quiet
expect read 0 "" -- bench --scenes quads:count=4 --techniques ha --size 16x16 --repeats 1 --no-floors --out b2.json --quiet
expect read 0 "" -- bench --scenes quads:count=4 --techniques ha,lists --size 16x16 --repeats 1 --no-floors --model gpu --out b3.json --quiet
expect read 0 "" -- hash build --key-set random --domain 32x32 --count 100 --age-bits 6 --out t3.tab --quiet
expect read 0 "" -- hash build --key-set random --domain 32x32 --count 100 --miss-filter-bits 8 --out t4.tab --quiet
expect read 2 "option --miss-filter-bits: 4 is not 0, 8 or 16" -- hash build --key-set random --domain 32x32 --count 100 --miss-filter-bits 4 --out t5.tab --quiet
expect read 0 "" -- figure fig2 --scene quads:count=4 --opacities 0.5,1 --size 8x8 --repeats 1 --path cpu --threads 1 --tau 0.9 --out f2.json --quiet
expect read 0 "" -- figure fig8 --scene quads:count=64 --frames 2 --load 0.64 --size 16x16 --repeats 1 --path cpu --threads 1 --tau 0.9 --out f8.json --quiet
expect read 0 "" -- figure fig10 --planes 4 --size 8x8 --repeats 1 --tau 0.9 --out f10.json --quiet
expect read 0 "" -- figure table1 --size 64x64 --fragments 1000 --loads 0.5 --no-allocate --out t1.json --quiet
expect read 2 "no effect on table1" -- figure table1 --size 64x64 --path cpu --repeats 2 --threads 1 --tau 0.9 --out t1.json
expect read 0 "" -- figure frontier --scenes quads:count=64 --size 16x16 --repeats 1 --path cpu --threads 1 --tau 0.9 --picks pk.json --targets 30 --memory-budgets 16,32 --out fr.json --quiet
expect read 0 "" -- figure shadows --scene quads:count=4 --size 8x8 --light-size 16x16 --receivers 10 --threads 1 --repeats 1 --out sh.json --quiet
expect read 2 "no effect on figure shadows" -- figure shadows --scene quads:count=4 --tau 0.9 --out sh.json
expect read 2 "no effect on figure shadows" -- figure shadows --scene quads:count=4 --path cpu --out sh.json
expect read 0 "" -- figure voxels --meshes sphere --grids 8 --axis x --path cpu --repeats 1 --threads 1 --out vx.json --quiet
expect read 2 "--grids sets the sizes" -- figure voxels --meshes sphere --grids 8 --size 8x8 --out vx.json
expect read 2 "nothing is culled" -- figure voxels --meshes sphere --grids 8 --tau 0.9 --out vx.json
expect read 0 "" -- figure csg --cylinders 1,2 --size 16x16 --path cpu --repeats 1 --threads 1 --out cs.json --quiet
expect read 2 "nothing is culled" -- figure csg --cylinders 1 --tau 0.9 --out cs.json

# --- No option without a run ------------------------------------------------
# Every (command, option) of the help texts must appear on one line of a CLI
# test script with the command's words (the line runs it, under the check).
commands=$("$bin" --help | sed -n 's/^  \([a-z-]*\)  .*/\1/p')
missing=()
for c in $commands; do
  subs=("$c")
  [[ $c == hash ]] && subs=("hash build" "hash query" "hash stats" "hash image")
  [[ $c == figure ]] && subs=("figure fig2" "figure fig8" "figure fig10" "figure table1" "figure frontier" "figure shadows" "figure voxels" "figure csg")
  for s in "${subs[@]}"; do
    if [[ $s == figure* ]]; then
      # figure's help: the common options, then each figure's own under "NAME:"
      name=${s#figure }
      opts=$("$bin" figure --help | awk -v f="$name:" '/^[a-z0-9]+:$/ {section = $0; next} (section == "" || section == f) && /^  --/ {print $1}' | sort -u)
    else
      opts=$("$bin" $s --help | grep -oE '^  --[a-z0-9-]+' | sort -u)
    fi
    [[ -n $opts ]] || continue
    for o in $opts; do
      found=0
      while IFS= read -r line; do
        ok_line=1
        for w in $s; do [[ $line == *"$w"* ]] || ok_line=0; done
        if [[ $ok_line -eq 1 && $line == *"$o"* ]]; then found=1; break; fi
      done < <(grep -h -- "$o" "$tests"/*.sh)
      [[ $found -eq 1 ]] || missing+=("$s $o")
    done
  done
done
if [[ ${#missing[@]} -eq 0 ]]; then ok coverage; else bad coverage "options no CLI test runs: ${missing[*]}"; fi

for cls in read coverage; do echo "class $cls: ${tried[$cls]:-0} cases"; done
echo "cli options: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
