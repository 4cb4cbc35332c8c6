#!/usr/bin/env bash
# Issue 25: outputs appear whole or not at all (a signal, a full disk, a
# file-size limit or a second run never leaves a partial or mixed file, and
# an earlier file of the name survives every failure), and the harness's
# commands hold to the CLI's rules for files, words and resources.
set -u
bin=$1
dir=$2
# shellcheck source=cli_common.sh
source "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/cli_common.sh"  # enters a fresh $dir

no_temporaries() {  # CLASS: no staging file left in this directory
  local left
  left=$(find . -maxdepth 2 -name '.*.tmp*' | head -3)
  [[ -z $left ]] && ok "$1" || bad "$1" "temporary files left: $left"
}

# --- 1. A signal mid-write leaves the earlier file and no temporary ---------
"$bin" generate --screen 64x64 --fragments 1000 --out big.csv >/dev/null 2>&1
sum_big=$(md5sum <big.csv)
for sig in TERM INT HUP; do
  "$bin" generate --screen 2048x2048 --fragments 6000000 --seed 7 --out big.csv >/dev/null 2>err.txt &
  pid=$!
  # Wait until the staging file holds data, so the signal lands mid-write.
  for _ in $(seq 600); do
    staged=$(find . -maxdepth 1 -name '.big.*.tmp.csv' -size +100k | head -1)
    [[ -n $staged ]] && break
    kill -0 $pid 2>/dev/null || break
    sleep 0.05
  done
  kill -s $sig $pid 2>/dev/null
  wait $pid
  code=$?
  want=$((128 + $(kill -l $sig)))
  [[ -n $staged && $code -eq $want ]] && ok signal ||
    bad signal "SIG$sig mid-write: exit $code (want $want), staged '${staged:-none}'"
  unchanged signal big.csv "$sum_big"
  no_temporaries signal
done

# --- 2. Write errors name the reason and keep the earlier file --------------
( ulimit -f 64; exec "$bin" generate --screen 512x512 --fragments 200000 --out big.csv ) >/dev/null 2>err.txt
code=$?
[[ $code -eq 1 ]] && grep -q 'File too large' err.txt && ok write ||
  bad write "file-size limit: exit $code, $(head -c 200 err.txt)"
unchanged write big.csv "$sum_big"
no_temporaries write
if [[ -w /dev/full ]]; then
  expect write 1 "No space left on device" -- generate --screen 64x64 --fragments 50000 --out /dev/full
  ln -sf /dev/full full.png  # an image through a link to the device
  expect write 1 "No space left on device" -- render --scene quads --size 8x8 --path cpu --out full.png
fi
expect write 0 "" -- generate --screen 64x64 --fragments 5000 --out /dev/null
lines=$("$bin" generate --screen 64x64 --fragments 5000 --out /dev/stdout 2>err.txt | wc -l)
[[ $lines -eq 5001 ]] && ok write || bad write "--out /dev/stdout gave $lines lines: $(cat err.txt)"

# --- 3. Two runs to one output leave one run's whole file -------------------
"$bin" generate --screen 256x256 --fragments 300000 --seed 1 --out a.csv >/dev/null 2>&1
"$bin" generate --screen 256x256 --fragments 300000 --seed 2 --out b.csv >/dev/null 2>&1
for _ in 1 2 3; do
  "$bin" generate --screen 256x256 --fragments 300000 --seed 1 --out race.csv >/dev/null 2>&1 &
  p1=$!
  "$bin" generate --screen 256x256 --fragments 300000 --seed 2 --out race.csv >/dev/null 2>&1 &
  p2=$!
  wait $p1 && wait $p2 && { cmp -s race.csv a.csv || cmp -s race.csv b.csv; } && ok race ||
    bad race "two runs to one --out left a file equal to neither run's"
done
no_temporaries race

# --- 4. A replaced file keeps its link and its permissions ------------------
cp a.csv real.csv
ln -sf real.csv link.csv
chmod 640 real.csv
"$bin" generate --screen 256x256 --fragments 300000 --seed 2 --out link.csv >/dev/null 2>&1
[[ -L link.csv ]] && cmp -s real.csv b.csv && ok replace || bad replace "the link or its target was not kept"
[[ $(stat -c %a real.csv) == 640 ]] && ok replace || bad replace "permissions $(stat -c %a real.csv), want 640"
mkdir -p locked && cp a.csv locked/kept.csv && chmod 555 locked
if [[ ! -w locked ]]; then  # not as root
  expect write 2 "directory" -- generate --screen 64x64 --fragments 10 --out locked/kept.csv
fi
chmod 755 locked

# --- 5. The harness holds to the CLI's file rules --------------------------
"$bin" generate --screen 16x16 --fragments 600 --seed 3 --out scene.csv >/dev/null 2>&1
sum_scene=$(md5sum <scene.csv)
ln -sf scene.csv scene_link.csv
F=(figure frontier --path cpu --size 16x16 --repeats 1 --scenes scene.csv)
expect files 2 "the same file as --scenes" -- "${F[@]}" --out scene.csv
expect files 2 "the same file as --scenes" -- "${F[@]}" --out scene_link.csv
expect files 2 "(two outputs)" -- "${F[@]}" --out f.json --picks f.json
expect files 2 "the same file as --scenes" -- "${F[@]}" --out f.json --picks scene.csv
expect files 2 "--picks" -- "${F[@]}" --out f.json --picks missing_dir/p.json
expect values 2 "--targets has no effect without --picks" -- "${F[@]}" --out f.json --targets 30
expect values 2 "--memory-budgets has no effect without --picks" -- "${F[@]}" --out f.json --memory-budgets 16
expect values 2 "--memory-budgets: '-1' is not a number in [0, " -- "${F[@]}" --out f.json --picks p.json --memory-budgets -1
expect files 2 "the same file as --scenes" -- bench --path cpu --size 16x16 --scenes scene.csv --techniques ha --out scene.csv
expect files 2 "the same file as --fragments" -- sweep --size 16x16 --fragments scene.csv --out scene.csv
expect files 2 "the same file as --fragments" -- plan --size 16x16 --fragments scene.csv --out scene.csv
unchanged files scene.csv "$sum_scene"

# --- 6. Harness words and options obey render's rules -----------------------
expect values 2 "count=0: 0 outside 1..1048576" -- bench --scenes quads:count=0 --techniques ha --out b.json
expect values 2 "outside 1..1048576" -- bench --scenes planes:count=1000000000 --techniques ha --out b.json
expect values 2 "above 1/510" -- bench --scenes quads:opacity=0.001 --techniques ha --out b.json
expect values 2 "does not take count" -- bench --scenes engine:count=3 --techniques ha --out b.json
expect values 2 "does not take order" -- bench --scenes quads:order=front --techniques ha --out b.json
expect values 2 "a fragment file takes no options" -- bench --path cpu --scenes scene.csv:count=3 --techniques ha --out b.json
expect values 2 "count given twice" -- bench --scenes quads:count=3:count=4 --techniques ha --out b.json
expect values 2 "cull given twice" -- bench --scenes quads --techniques ha:cull=0.5:cull=0.6 --out b.json
expect values 2 "smallest normal float32" -- bench --scenes quads --techniques ha:cull=1e-40 --out b.json
expect values 2 "--model must be gpu, not 'cpu'" -- bench --scenes quads --techniques ha --model cpu --out b.json
expect values 2 "sweep sets the load" -- sweep --scene quads --technique ha:load=0.5 --out s.json
expect values 2 "sweep sets the layers" -- sweep --scene quads --technique arrays:k=4 --out s.json
expect values 2 "--offsets has no effect with --technique lists" -- sweep --scene quads --technique lists --offsets random --out s.json
expect values 2 "--threads: 70000 outside 0..1024" -- bench --path cpu --scenes quads --techniques ha --threads 70000 --out b.json
expect values 2 "--threads has no effect with --path gl" -- sweep --scene quads --threads 2 --out s.json
expect values 2 "--threads has no effect with --path gl" -- figure fig10 --threads 2 --out f.json
expect values 2 "fragment file" -- figure fig2 --scene scene.csv --path cpu --out f.json
expect values 2 "has none (quads takes it)" -- figure fig8 --scene planes --out f.json
expect values 2 "option --loads: load must be in (0, 1]" -- figure table1 --loads 0 --out t.json
expect values 2 "option --loads: load must be in (0, 1]" -- figure table1 --loads 1.5 --out t.json
expect values 2 "outside 1..2147483648" -- figure table1 --fragments 1000000000000 --out t.json
expect values 2 "has no effect on table1" -- figure table1 --threads 2 --out t.json
expect values 2 "--saturation has no effect with --technique lists" -- render --scene quads --size 8x8 --out q.png --technique lists --saturation on
expect values 2 "--lossless has no effect with --technique blend" -- render --scene quads --size 8x8 --out q.png --technique blend --lossless
expect values 2 "--lossless has no effect with --technique wboit" -- render --scene quads --size 8x8 --out q.png --technique wboit --lossless
expect values 2 "needs" -- stats --screen 100000x100000
expect values 2 "option --loads: 1e-300 of table 128x128 gives no fragment" -- stats --loads 1e-300
expect values 2 "option --load: 1e-300 of table 4x4 gives no fragment" -- generate --screen 4x4 --load 1e-300 --out g.csv
expect values 2 "more than 2^32 - 1: raise the load" -- demo --screen 4x4 --load 1e-300
expect values 2 "more than this machine's" -- render --scene quads --size 65535x65535 --out q.png
expect values 2 "--size 65535x65535 needs" -- sweep --scene quads --size 65535x65535 --out s.json

# --- 7. Losses in harness runs are said; a pixel deeper than AMAX is named --
printf 'x,y,depth,rgba\n' >deep.csv
for i in $(seq 1 300); do printf '0,0,%s,255\n' "0.$((1000 + i))"; done >>deep.csv
printf '1,1,0.5,255\n' >>deep.csv
expect losses 0 "" -- bench --path cpu --size 4x4 --scenes deep.csv --techniques lists,arrays:k=2 --repeats 1 --out b.json
grep -q "warning: 1 of 2 runs lost fragments" err.txt && grep -q "technique=arrays:k=2" err.txt && ok losses ||
  bad losses "bench did not warn of arrays:k=2's losses: $(cat err.txt)"
expect losses 1 "pixel (0, 0) has 300 distinct fragments, more than AMAX = 2^8 - 1 = 255, at any table size: use --age-bits 9" -- \
  render --fragments deep.csv --size 4x4 --stats r.json --lossless
expect losses 1 "pixel (0, 0) has 300 distinct fragments" -- build-lists --in deep.csv --out l.csv --screen 4x4 --lossless
# The GPU path of render sees the counting pass only: one attempt where
# frames may grow (lossless), the same pixel named where they may not.
expect losses 1 "pixel (0, 0) has 300 fragments (duplicates included), more than AMAX" -- \
  render --scene planes --count 300 --size 8x8 --out p.png --lossless --stats p.json --quiet
python3 -c "import json,sys; sys.exit(json.load(open('p.json'))['frames'][0]['attempts'] != 1)" && ok losses ||
  bad losses "render --lossless grew the table for a pixel deeper than AMAX"
expect losses 0 "" -- render --scene planes --count 300 --size 8x8 --out p.png --table 8x8 --quiet
grep -q "pixel (0, 0) has 300 fragments (duplicates included)" err.txt && ok losses ||
  bad losses "render with a fixed table did not name the pixel deeper than AMAX: $(cat err.txt)"
expect losses 0 "" -- build-lists --in deep.csv --out l.csv --screen 4x4 --lossless --age-bits 9
timeout 60 "$bin" plan --size 4x4 --fragments deep.csv --out p.json >/dev/null 2>err.txt && grep -q "ha_beyond_amax" p.json &&
  ok losses || bad losses "plan on a pixel deeper than AMAX: $(cat err.txt)"
if command -v script >/dev/null; then
  script -qec "$bin plan --size 16x16 --fragments scene.csv --out p2.json" /dev/null >tty_plan.txt 2>&1
  grep -q 'habuffer plan \[' tty_plan.txt && ok progress || bad progress "plan shows no progress on a terminal"
fi

# --- Issue 34: files named inside values, output sets, links, solids -------
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n' >cube.obj
printf 'f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n' >>cube.obj
sum_cube=$(md5sum <cube.obj)
ln -sf cube.obj cube_link.obj
expect files 2 "the same file as --solids" -- csg --solids "A=cube.obj" --expr A --stats cube.obj
expect files 2 "the same file as --solids" -- csg --solids "B=sphere:0,0,0,1; A=cube.obj" --expr A --out cube_link.obj
expect files 2 "the same file as --meshes" -- figure voxels --meshes sphere,cube.obj --grids 8 --out cube.obj
expect files 2 "the same file as --mesh" -- voxelize --mesh cube.obj --grid 4 --out g.bin --stats cube_link.obj
unchanged files cube.obj "$sum_cube"
# A set of slices replaces an earlier, larger set whole; other folders and files inside are refused.
expect files 0 "" -- voxelize --mesh cube.obj --grid 6 --out g.bin --slices sl --quiet
expect files 0 "" -- voxelize --mesh cube.obj --grid 3 --out g.bin --slices sl/ --quiet
[[ $(find sl -type f | wc -l) -eq 3 && -f sl/slice_0002.png && ! -e sl/slice_0003.png ]] && ok files ||
  bad files "--slices left $(find sl -type f | wc -l) files after a smaller set (want 3)"
no_temporaries files
expect files 2 "inside --slices" -- voxelize --mesh cube.obj --grid 3 --out sl/g.bin --slices sl
cp cube.obj sl/slice_0000.png 2>/dev/null
expect files 2 "inside --slices" -- voxelize --mesh sl/slice_0000.png --grid 3 --out g.bin --slices sl
mkdir -p mine && echo keep >mine/notes.txt
expect files 2 "notes.txt" -- voxelize --mesh cube.obj --grid 3 --out g.bin --slices mine
[[ $(cat mine/notes.txt) == keep ]] && ok files || bad files "--slices over a folder of other files changed it"
# SIGTERM while a set is written: the earlier set whole, no temporary folder.
expect files 0 "" -- voxelize --mesh cube.obj --grid 5 --out g.bin --slices big --quiet
sum_set=$(cat big/*.png | md5sum)
"$bin" voxelize --mesh cube.obj --grid 400 --out g2.bin --slices big --quiet >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1200); do
  [[ -n $(find . -maxdepth 1 -name '.big.*.tmp' | head -1) ]] && break
  kill -0 $pid 2>/dev/null || break
  sleep 0.05
done
kill -s TERM $pid 2>/dev/null
wait $pid
[[ $(cat big/*.png | md5sum) == "$sum_set" && $(find big -type f | wc -l) -eq 5 ]] && ok signal ||
  bad signal "SIGTERM during --slices changed the earlier set"
[[ -z $(find . -maxdepth 1 -name '.big.*' | head -1) ]] && ok signal || bad signal "SIGTERM left a temporary set"
# An output through a dangling link writes the link's target and keeps the link.
ln -sf made.json dangling.json
expect files 0 "" -- voxelize --mesh cube.obj --grid 3 --out g.bin --stats dangling.json --quiet
[[ -L dangling.json && -s made.json ]] && ok files || bad files "--stats through a dangling link replaced the link"
# Solids csg cannot draw, names --expr cannot read, an open mesh.
expect values 2 "solid name 'A-B'" -- csg --solids "A-B=sphere:0,0,0,1" --expr A --stats s.json
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >tri.obj
expect values 1 "is not closed" -- csg --solids "A=tri.obj" --expr A --stats s.json
expect values 1 "float32 cannot hold" -- csg --solids "A=sphere:1e17,0,0,1" --expr A --stats s.json
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n' >open.obj
expect values 0 "not watertight" -- voxelize --mesh open.obj --grid 4 --out g.bin --quiet
expect values 1 "encloses no volume" -- voxelize --mesh tri.obj --grid 4 --out flat.bin --quiet
[[ ! -e flat.bin ]] && ok values || bad values "voxelize of a flat mesh wrote its grid"

for cls in signal write race replace files values losses progress; do echo "class $cls: ${tried[$cls]:-0} cases"; done
echo "cli outputs: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
