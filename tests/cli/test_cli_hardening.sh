#!/usr/bin/env bash
# Careless use of the CLI, one section per class of harm (issues 9 and 10): inputs
# overwritten or outputs shared, losses unreported, values that silently
# become others, endless or binary input, GL losing what the CPU keeps, and
# long work without a sign of life. Each case checks the exit code, that
# stderr is one short printable line naming what was wrong, and that no
# input changed.
set -u
bin=$1
dir=$2
# shellcheck source=cli_common.sh
source "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/cli_common.sh"  # enters a fresh $dir

printf 'x,y,depth,rgba\n0,0,0.5,0xFF0000FF\n1,0,0.25,255\n1,1,0.75,0x00FF0080\n' >in.csv
printf 'ox,oy\n0,0\n1,0\n0,1\n1,1\n2,0\n2,1\n2,2\n0,2\n1,2\n3,0\n3,1\n3,2\n3,3\n0,3\n1,3\n' >off.csv
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0.5\nf 1 2 3\nf 2 4 3\n' >mesh.obj
mkdir -p sub
ln -f in.csv hard.csv
ln -sf in.csv soft.csv
sum_in=$(md5sum <in.csv)
sum_off=$(md5sum <off.csv)
sum_mesh=$(md5sum <mesh.obj)

# --- 1. Inputs are never overwritten; outputs never share a file -----------
B=(build-lists --screen 4x4 --table 4x4 --age-bits 4)
for out_opt in --out --stats --dump-table --dump-max-age; do
  for spelling in in.csv ./in.csv sub/../in.csv "$PWD/in.csv" hard.csv soft.csv; do
    others=()
    for o in --out --stats --dump-table --dump-max-age; do
      [[ $o == "$out_opt" ]] || others+=("$o" "x$o.csv")
    done
    expect files 2 "is the same file as --in" -- "${B[@]}" --in in.csv "${others[@]}" "$out_opt" "$spelling"
    unchanged files in.csv "$sum_in"
  done
  expect files 2 "is the same file as --offsets" -- "${B[@]}" --in in.csv --offsets off.csv \
    $( [[ $out_opt == --out ]] || echo --out l.csv ) "$out_opt" off.csv
  unchanged files off.csv "$sum_off"
done
outs=(--out --stats --dump-table --dump-max-age)
for ((i = 0; i < 4; ++i)); do
  for ((j = i + 1; j < 4; ++j)); do
    args=(--in in.csv)
    for ((k = 0; k < 4; ++k)); do
      if [[ $k -eq $i || $k -eq $j ]]; then args+=("${outs[k]}" same.csv); else args+=("${outs[k]}" "o$k.csv"); fi
    done
    expect files 2 "(two outputs)" -- "${B[@]}" "${args[@]}"
  done
done
for out_opt in --out --stats --reference "--heatmap depth:"; do
  if [[ $out_opt == "--heatmap depth:" ]]; then target=(--heatmap depth:mesh.obj); else target=("$out_opt" mesh.obj); fi
  extra=(); [[ $out_opt == --out ]] || extra=(--out r.png)
  expect files 2 "is the same file as --scene" -- render --scene mesh.obj --size 16x16 "${extra[@]}" "${target[@]}"
  unchanged files mesh.obj "$sum_mesh"
done
expect files 2 "is the same file as --fragments" -- render --fragments in.csv --size 4x4 --out r.png --stats ./in.csv
unchanged files in.csv "$sum_in"
expect files 2 "(two outputs)" -- render --scene quads --size 16x16 --out q.png --reference q.png
expect files 2 "(two outputs)" -- render --scene quads --size 16x16 --out q.png --heatmap depth:q.png
expect files 2 "(two outputs)" -- render --scene quads --size 16x16 --out q.png --heatmap depth:h.png,age:h.png
expect files 2 "(two outputs)" -- render --scene quads --size 16x16 --out q.png --stats s.json --heatmap culled:s.json
expect files 2 "option --heatmap: empty list" -- render --scene quads --size 16x16 --out q.png --heatmap ""
expect files 2 "is a directory" -- render --scene quads --size 16x16 --out sub
expect files 2 "is a directory" -- build-lists --in in.csv --screen 4x4 --out sub
expect files 2 "(two outputs)" -- demo --screen 16x16 --lists F --stats F
expect files 2 "is the same file as --offsets" -- demo --screen 4x4 --table 4x4 --age-bits 4 --offsets off.csv --stats off.csv
expect files 2 "(two outputs)" -- offsets --table 8x8 --out o.csv --quality o.csv
expect files 2 "cannot be created: directory" -- "${B[@]}" --in in.csv --out l.csv --stats nodir/s.json
expect files 2 "cannot be created: directory" -- render --scene quads --size 8x8 --out q.png --stats nodir/s.json
expect files 2 "is not a directory" -- render --scene quads --size 8x8 --out in.csv/q.png
expect files 0 "" -- render --scene quads --size 8x8 --out newdir/deeper/q.png --quiet
[[ -s newdir/deeper/q.png ]] && ok files || bad files "render did not create the image's directories"
expect files 0 "" -- "${B[@]}" --in in.csv --out /dev/null --stats /dev/null
unchanged files in.csv "$sum_in"

# --- 2. Losses are always reported ------------------------------------------
python3 -c "
import random
random.seed(7)
print('x,y,depth,rgba')
for i in range(20000): print('0,0,%.7f,%d' % (random.random(), random.getrandbits(32)))" >deep.csv
expect losses 0 "warning: 19984 of 20000 fragments not stored: failed_age 19984" -- build-lists --in deep.csv --out l.csv --screen 4x4
[[ $(wc -l <err.txt) -eq 1 ]] && ok losses || bad losses "one warning line expected"
expect losses 0 "warning: 19984 of 20000 fragments not stored" -- build-lists --in deep.csv --out l.csv --screen 4x4 --path gl
# A pixel deeper than AMAX fails at any table size: no growth, the pixel named.
expect losses 1 "lossless mode: 19984 of 20000 fragments not stored: failed_age 19984 after 1 attempt: pixel (0, 0) has 20000 distinct fragments" -- build-lists --in deep.csv --out l.csv --screen 4x4 --lossless
expect losses 1 "lossless mode: 19984 of 20000 fragments not stored: failed_age 19984 after 1 attempt: pixel (0, 0) has 20000 distinct" -- build-lists --in deep.csv --out l.csv --screen 4x4 --lossless --path gl
grep -qF "no age bits hold it (at most 12): use another technique, such as lists (or accept the loss); more attempts cannot help (--max-attempts 16)" err.txt &&
  ok losses || bad losses "the lossless failure does not say growing cannot help: $(cat err.txt)"
# A pixel within AMAX that the attempts allowed cannot hold: the attempts, AMAX, the pixel and --max-attempts.
head -n 4001 deep.csv >deep4000.csv
# (Two attempts hold them: the second is sized for what the first counted.)
expect losses 0 "" -- build-lists --in deep4000.csv --out l.csv --screen 4x4 --lossless --age-bits 12 --max-attempts 2
expect losses 1 "after 1 attempt (last table" -- build-lists --in deep4000.csv --out l.csv --screen 4x4 --lossless --age-bits 12 --max-attempts 1
grep -qF "; AMAX = 2^12 - 1 = 4095): pixel (0, 0) lost the most, " err.txt && grep -qF "raise --max-attempts above 1" err.txt &&
  ok losses || bad losses "the lossless failure does not name AMAX, the pixel and --max-attempts: $(cat err.txt)"
expect losses 1 "lossless mode:" -- render --scene planes --count 40 --size 16x16 --age-bits 4 --out p.png --lossless --quiet
expect losses 1 "lossless mode:" -- render --scene planes --count 40 --size 16x16 --age-bits 4 --out p.png --lossless --quiet --path cpu
expect losses 1 "lossless mode:" -- render --fragments deep.csv --size 4x4 --out p.png --lossless --quiet
expect losses 0 "failed_age" -- render --scene planes --count 40 --size 16x16 --age-bits 4 --table 16x16 --out p.png --quiet
expect losses 0 "culled (early cull)" -- render --scene planes --size 16x16 --early-cull 0.5 --out p.png --quiet
expect losses 0 "culled (early cull)" -- build-lists --in deep.csv --out l.csv --screen 4x4 --table 64x64 --early-cull 0.9
printf 'x,y,depth,rgba\n0,0,nan,1\n0,0,1.5,1\n0,0,0.5,1\n' >invalid.csv
expect losses 0 "2 of 3 fragments not stored: invalid (depth NaN or outside [0, 1], or a coverage mask naming none of the samples) 2" -- build-lists --in invalid.csv --out l.csv --screen 1x1
expect losses 0 "failed_age" -- demo --screen 8x8 --fragments 3000 --table 8x8 --age-bits 4 --stream random
printf 'v 0 0 0\nv 1e20 0 0\nv 0 1e20 0\nf 1 2 3\n' >far.obj
expect losses 1 "leaves no usable depth range in float32" -- render --scene far.obj --size 16x16 --out f.png
printf 'v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n' >flat.obj
expect losses 0 "no transparent fragment reached the screen" -- render --scene flat.obj --size 16x16 --out f.png --quiet
expect losses 0 "" -- build-lists --in in.csv --out l.csv --screen 4x4
[[ ! -s err.txt ]] && ok losses || bad losses "a lossless build printed: $(cat err.txt)"

# --- 3. No value silently becomes another -------------------------------------
for tau in 1e-300 1e-39 0 -0.5 1.0000001 2 nan inf 0x1p-10; do
  expect values 2 "option --early-cull" -- build-lists --in in.csv --out l.csv --screen 4x4 --early-cull "$tau"
  expect values 2 "option --early-cull" -- render --scene quads --size 8x8 --out q.png --early-cull "$tau"
done
expect values 2 "smallest normal float32 is 1.1754944e-38" -- build-lists --in in.csv --out l.csv --screen 4x4 --early-cull 1e-300
expect values 0 "" -- build-lists --in in.csv --out l.csv --screen 4x4 --early-cull 1.2e-38
for opacity in 0.001 1e-45 0 1.5; do
  expect values 2 "option --opacity" -- render --scene quads --size 8x8 --out q.png --opacity "$opacity"
done
for opt in loads probing policy offsets; do
  expect values 2 "option --$opt: empty list" -- stats --$opt ""
  expect values 2 "option --$opt: empty item" -- stats --$opt ","
done
expect values 2 "option --loads: empty item in '0.5,,0.9'" -- stats --loads 0.5,,0.9
expect values 2 "option --opaque-meshes: empty" -- render --scene planes --size 8x8 --out q.png --opaque-meshes ""
expect values 2 "is too large (accepted: 0..18446744073709551615)" -- build-lists --in in.csv --out l.csv --screen 4x4 --seed 18446744073709551616
expect values 2 "'-1' is not a non-negative integer" -- build-lists --in in.csv --out l.csv --screen 4x4 --seed -1
expect values 2 "option --threads has no effect with --path gl" -- build-lists --in in.csv --out l.csv --screen 4x4 --path gl --threads 2
expect values 2 "option --insert-mode has no effect with --path gl" -- build-lists --in in.csv --out l.csv --screen 4x4 --path gl --insert-mode owner
expect values 2 "option --seed has no effect with an offsets file" -- build-lists --in in.csv --out l.csv --screen 4x4 --table 4x4 --age-bits 4 --offsets off.csv --seed 2
expect values 2 "option --table has no effect without --load" -- generate --screen 4x4 --fragments 9 --table 8x8 --out g.csv
expect values 2 "option --min-side has no effect" -- generate --screen 4x4 --fragments 9 --stream random --min-side 2 --out g.csv
expect values 2 "option --spread has no effect" -- stats --stream random --spread 0.5
expect values 2 "option --count has no effect on scene 'mesh.obj'" -- render --scene mesh.obj --size 8x8 --out q.png --count 3
expect values 2 "option --order has no effect on scene 'quads'" -- render --scene quads --size 8x8 --out q.png --order front
expect values 2 "option --spread has no effect on scene 'planes'" -- render --scene planes --size 8x8 --out q.png --spread 0.5
expect values 2 "option --threads has no effect with --path gl" -- render --scene quads --size 8x8 --out q.png --threads 2
expect values 0 "" -- demo --screen 32x32 --path gl --stats d.json
grep -q '"path":"gl"' d.json && grep -q '"gl_atomic_mode"' d.json && grep -q "gl emulated64 on" out.txt && ok values ||
  bad values "demo --path gl did not run on GL: $(cat out.txt)"
expect values 2 "option --threads has no effect with --path gl" -- demo --screen 32x32 --path gl --threads 2
# hash query reads --threads as every command does (the batched find's threads).
printf 'x,y,value\n1,1,5\n2,3,7\n' >hk.csv
expect values 0 "" -- hash build --keys hk.csv --out hk.tab --quiet
expect values 2 "option --threads: '-1' is not a non-negative integer" -- hash query --table hk.tab --keys hk.csv --threads -1
expect values 2 "option --threads: 'abc' is not a non-negative integer" -- hash query --table hk.tab --keys hk.csv --threads abc
expect values 2 "option --threads: 100000 outside 0..1024" -- hash query --table hk.tab --keys hk.csv --threads 100000
expect values 0 "" -- hash query --table hk.tab --keys hk.csv --out hq.csv --threads 2 --quiet
[[ "$(tr '\n' ' ' <hq.csv)" == "x,y,found,value 1,1,1,5 2,3,1,7 " ]] && ok values || bad values "hash query --threads 2: $(cat hq.csv)"
# One key far from the origin: the domain of its bounds would need a table of
# 2 GiB for its quotients; refused at once naming the sizes and the options.
printf 'x,y\n50000000,50000000\n' >far.csv
expect values 2 "for 1 key in the domain 50000001x50000001 (the keys' bounds)" -- hash build --keys far.csv --out far.tab
for needle in "for its quotients to fit 23 bits (--age-bits 8)" "give a smaller --domain (keys nearer 0) or fewer --age-bits (--age-bits 4: "; do
  grep -qF -- "$needle" err.txt && ok values || bad values "hash build of a far key: stderr lacks '$needle': $(cat err.txt)"
done
expect values 2 "in the domain 60000000x60000000 (--domain)" -- hash build --keys far.csv --out far.tab --domain 60000000x60000000
[[ ! -e far.tab ]] && ok values || bad values "a refused hash build wrote its table"
for psnr in -1 0 -0 -1e-300; do
  expect values 2 "option --target-psnr: $psnr is not a PSNR above 0 dB" -- plan --scene quads --size 8x8 --out p.json --target-psnr "$psnr"
done
for budget in -1 -1e-300 nan; do
  expect values 2 "option --memory-budget: " -- plan --scene quads --size 8x8 --out p.json --memory-budget "$budget"
done

# --- 4. Bounded input: devices, binary data, endless lines --------------------
{ printf '\001'; head -c 3000000 /dev/urandom; } >binary.csv  # never an empty first line
(printf 'x,y,depth,rgba\n'; head -c 2000000 /dev/zero | tr '\0' '7') >longline.csv
printf 'x,y,depth,rgba\n0,0,0.5,1\0\n' >nul.csv
printf 'x,y,depth,rgba\n0,0,0.5,1,2\n' >extra.csv
printf 'ox,oy\n0,0,0\n' >extra_off.csv
printf '\xef\xbb\xbfx,y,depth,rgba\n0,0,0.5,1\n' >bom.csv
head -c 5000 /dev/urandom >junk.png
for f in /dev/zero /dev/urandom .; do
  expect input 1 "$f: is a" -- build-lists --in $f --out l.csv --screen 4x4
  expect input 1 "$f: is a" -- render --fragments $f --size 4x4 --out r.png
  expect input 1 "$f: is a" -- build-lists --in in.csv --out l.csv --screen 4x4 --table 4x4 --age-bits 4 --offsets $f
done
expect input 1 "is not a regular file" -- compare /dev/zero junk.png
expect input 1 "cannot be read" -- compare junk.png junk.png
expect input 1 "binary.csv:1: header is '" -- build-lists --in binary.csv --out l.csv --screen 4x4
expect input 1 "longline.csv:2: line longer than 1048576 bytes" -- build-lists --in longline.csv --out l.csv --screen 4x4
expect input 1 "nul.csv:2: field rgba: '1\\x00'" -- build-lists --in nul.csv --out l.csv --screen 4x4
expect input 1 "extra.csv:2: 5 fields, expected 4" -- build-lists --in extra.csv --out l.csv --screen 4x4
expect input 1 "extra_off.csv:2: 3 fields, expected 2" -- build-lists --in in.csv --out l.csv --screen 4x4 --offsets extra_off.csv
expect input 0 "" -- build-lists --in bom.csv --out l.csv --screen 4x4
expect input 1 "is not a regular file" -- render --scene /dev/zero --size 8x8 --out q.png
expect input 2 "unknown option '--\\xff\\x01'" -- build-lists --in in.csv $'--\xff\x01' 1
"$bin" build-lists --in /dev/stdin --out piped.csv --screen 4x4 <in.csv >/dev/null 2>&1 && "$bin" build-lists --in in.csv \
  --out direct.csv --screen 4x4 >/dev/null 2>&1 && cmp -s piped.csv direct.csv && ok input || bad input "a pipe reads differently"

# --- 5. GL keeps what the CPU keeps, under contention -------------------------
# 10^5 fragments on one pixel, two busy threads beside the GL run.
python3 -c "
import random
random.seed(5)
print('x,y,depth,rgba')
for i in range(100000): print('3,2,%.7f,%d' % (random.random(), random.getrandbits(32)))" >onepixel.csv
busy=()
for _ in 1 2; do (while :; do :; done) & busy+=($!); done
"$bin" build-lists --in onepixel.csv --out gl.csv --screen 64x64 --path gl --stats gl.json >/dev/null 2>gl_err.txt
kill "${busy[@]}" 2>/dev/null; wait "${busy[@]}" 2>/dev/null
"$bin" build-lists --in onepixel.csv --out cpu.csv --screen 64x64 --stats cpu.json >/dev/null 2>/dev/null
counters() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print([d[k] for k in
  ('fragments','stored','duplicates','culled','invalid','failed_age','failed_iter')])" "$1"; }
if cmp -s gl.csv cpu.csv && [[ "$(counters gl.json)" == "$(counters cpu.json)" ]] &&
  grep -q '"failed_iter":0' gl.json; then ok gl; else
  bad gl "GL differs from CPU under contention: $(counters gl.json) vs $(counters cpu.json); $(cat gl_err.txt)"; fi

# --- 6. Long work shows progress on a terminal, and only there ---------------
if command -v script >/dev/null; then
  script -qec "$bin stats --screen 64x64 --trials 40 --loads 0.5,0.9" /dev/null >tty.txt 2>&1
  grep -q 'habuffer stats \[' tty.txt && grep -q '% ' tty.txt && grep -q 'trials' tty.txt && ok progress ||
    bad progress "no progress bar on a terminal"
  script -qec "$bin stats --screen 64x64 --trials 40 --loads 0.5,0.9 --quiet" /dev/null >tty_quiet.txt 2>&1
  grep -q 'habuffer stats \[' tty_quiet.txt && bad progress "--quiet still drew a bar" || ok progress
  script -qec "$bin render --scene quads --size 32x32 --frames 12 --out q.png" /dev/null >tty_render.txt 2>&1
  grep -q 'habuffer render \[' tty_render.txt && grep -q 'frames' tty_render.txt && ok progress ||
    bad progress "no progress bar for render frames"
fi
"$bin" stats --screen 64x64 --trials 40 --loads 0.5,0.9 >/dev/null 2>notty.txt
[[ ! -s notty.txt ]] && ok progress || bad progress "progress written to a non-terminal: $(head -c 200 notty.txt)"

# --- 7. Techniques: options that would be ignored are refused; drops are reported
expect values 2 "'listz' is not one of ha, lists, arrays" -- build-lists --in in.csv --out t.csv --screen 4x4 --technique listz
for t in lists arrays; do
  for ha_only in "--table 4x4" "--block 2" "--iter-limit 9" "--early-cull 0.5" "--offsets random" "--seed 3" \
    "--dump-table dt.csv"; do
    # shellcheck disable=SC2086
    expect values 2 "has no effect with --technique $t" -- build-lists --in in.csv --out t.csv --screen 4x4 --technique $t $ha_only
  done
  expect values 2 "has no effect with --technique $t" -- render --scene quads --size 8x8 --out q.png --technique $t --table 8x8
  expect values 2 "the HA-buffer's" -- render --scene quads --size 8x8 --out q.png --technique $t --heatmap age:a.png
done
expect values 2 "--insert-mode owner has no effect with --technique lists" -- build-lists --in in.csv --out t.csv --screen 4x4 --technique lists --insert-mode owner
expect values 0 "" -- demo --screen 16x16 --insert-mode serial
expect values 2 "--layers has no effect with --technique ha" -- build-lists --in in.csv --out t.csv --screen 4x4 --layers 4
expect values 2 "--pool has no effect with --technique arrays" -- build-lists --in in.csv --out t.csv --screen 4x4 --technique arrays --pool 9
expect values 2 "--layers" -- build-lists --in in.csv --out t.csv --screen 4x4 --technique arrays --layers 0
expect values 2 "--pool" -- build-lists --in in.csv --out t.csv --screen 4x4 --technique lists --pool 0
printf 'x,y,depth,rgba\n2,2,0.5,1\n2,2,0.25,2\n2,2,0.75,3\n2,2,0.5,1\n0,1,0.1,4\n' >deep.csv
expect losses 0 "dropped_layers (pixel's layers full) 2" -- build-lists --in deep.csv --out t.csv --screen 4x4 --technique arrays --layers 2
expect losses 0 "dropped_pool (node pool full) 3" -- build-lists --in deep.csv --out t.csv --screen 4x4 --technique lists --pool 2
expect losses 1 "lossless mode" -- build-lists --in deep.csv --out t.csv --screen 4x4 --technique lists --pool 2 --lossless --max-attempts 1
"$bin" build-lists --in deep.csv --out ha.csv --screen 4x4 >/dev/null 2>&1
for path in cpu gl; do
  for t in "lists --pool 2 --lossless" "arrays --layers 1 --lossless" "lists" "arrays"; do
    # shellcheck disable=SC2086
    "$bin" build-lists --in deep.csv --out tech.csv --screen 4x4 --path $path --technique $t >/dev/null 2>err.txt &&
      cmp -s tech.csv ha.csv && ok losses || bad losses "$path $t lists differ from the HA-buffer's: $(cat err.txt)"
  done
done

# --- 8. Issue 34: every reader bounded, image outputs checked, GL limits named -
# Binary loaders: a device (read until memory ran out), a directory
# ("basic_filebuf::underflow"); a key file through a pipe (its header was read twice).
printf 'x,y,value\n1,1,5\n2,3,7\n' >hk.csv
"$bin" hash build --keys hk.csv --out hk.tab --quiet >/dev/null 2>&1
for f in /dev/zero sub; do
  expect input 1 "$f: is a" -- hash query --table $f --keys hk.csv
  expect input 1 "$f: is a" -- hash stats --table $f
  expect input 1 "$f: is a" -- hash image --table $f --out hi.png
  expect input 1 "$f: is a" -- hash build --voxels $f --out hv.tab
done
expect input 1 "image '/dev/zero' is not a regular file" -- hash build --image /dev/zero --out hv.tab
expect input 1 "image 'sub' is a directory" -- hash build --image sub --out hv.tab
rm -f keys.fifo && mkfifo keys.fifo
timeout 60 bash -c "printf 'x,y\n1,1\n2,3\n' >keys.fifo" &
writer=$!
expect input 0 "" -- hash query --table hk.tab --keys keys.fifo --out hq_pipe.csv --quiet
kill "$writer" 2>/dev/null; wait "$writer" 2>/dev/null
[[ "$(tr '\n' ' ' <hq_pipe.csv)" == "x,y,found,value 1,1,1,5 2,3,1,7 " ]] && ok input ||
  bad input "hash query of keys from a pipe: $(cat hq_pipe.csv 2>/dev/null)"
# An image header claiming 10^12 pixels: refused from its size before the pixels are allocated.
printf 'P6\n1000000 1000000\n255\n' >huge.ppm
expect input 1 "more than this machine's" -- compare huge.ppm huge.ppm
expect input 1 "more than this machine's" -- hash build --image huge.ppm --out hv.tab
# Image outputs: an extension no writer takes is bad usage before any work; a
# full device says so ("OpenImageIO gave no reason" before).
expect files 2 "option --out: 'x.txt': '.txt' is not an image format OpenImageIO can write (png" -- \
  render --scene quads --size 8x8 --out x.txt
expect files 2 "option --reference: 'r.txt': '.txt' is not an image format" -- \
  render --scene quads --size 8x8 --out q.png --reference r.txt
expect files 2 "option --heatmap shadow: 'h.txt': '.txt' is not an image format" -- \
  render --scene quads --size 8x8 --shadows --heatmap shadow:h.txt --out q.png
expect files 2 "option --out: 'x.txt': '.txt' is not an image format" -- hash image --table hk.tab --out x.txt
expect files 2 "option --out: 'x.txt': '.txt' is not an image format" -- \
  csg --solids "cube=box:-1,-1,-1,1,1,1" --expr cube --size 16x16 --out x.txt
[[ ! -e x.txt && ! -e r.txt && ! -e h.txt ]] && ok files || bad files "a refused image output was written"
expect files 1 "No space left on device" -- render --scene quads --size 8x8 --out /dev/full
expect files 1 "No space left on device" -- render --scene quads --size 8x8 --out q.png --shadows --heatmap shadow:/dev/full
expect files 1 "No space left on device" -- hash image --table hk.tab --out /dev/full
expect files 1 "No space left on device" -- csg --solids "cube=box:-1,-1,-1,1,1,1" --expr cube --size 16x16 --out /dev/full
# A size beyond this OpenGL's framebuffer: one line naming --size and the limit (the driver's GL_INVALID_VALUE lines before).
for path in gl cpu; do
  expect gl 1 "csg: --size 65535x1 exceeds this OpenGL's largest" -- \
    csg --solids "cube=box:-1,-1,-1,1,1,1" --expr cube --size 65535x1 --out c.png --path $path
done
# A scene without a transparent fragment: bench warns naming it (its rows time an empty pass); sweep refuses it.
expect losses 0 "habuffer bench: warning: scene 'planes:opacity=1' puts no transparent fragment on the screen at 16x16" -- \
  bench --scenes planes:opacity=1,quads --techniques ha --size 16x16 --repeats 1 --no-floors --out b.csv --quiet
[[ $(grep -c "planes:opacity=1" err.txt) -eq 1 ]] && ok losses || bad losses "bench: not one warning line: $(cat err.txt)"
expect losses 1 "scene 'planes:opacity=1' puts no transparent fragment on the screen at 16x16" -- \
  sweep --scene planes:opacity=1 --size 16x16 --repeats 1 --out s.json --quiet
# Sweep's counters sum the repeats: the table says so.
expect values 0 "" -- sweep --scene quads --size 16x16 --repeats 2 --loads 0.5 --path cpu --out s.json --quiet
grep -q '"counters": *"fragments, stored, failures, every counter column and age_histogram are sums over the row' s.json &&
  ok values || bad values "sweep's notes do not say the counters sum the repeats: $(head -c 600 s.json)"
# A forced atomic mode the layout cannot run is refused (L64), or said (L32), never replaced quietly.
HABUFFER_ATOMIC_MODE=native32 expect values 1 "HABUFFER_ATOMIC_MODE=native32 does not fit layout L64" -- \
  render --scene quads --size 8x8 --layout 64 --out q.png
HABUFFER_ATOMIC_MODE=emulated64 expect values 0 "HABUFFER_ATOMIC_MODE=emulated64 does not apply to layout L32" -- \
  render --scene quads --size 8x8 --layout 32 --out q.png --quiet

for cls in files losses values input gl progress; do echo "class $cls: ${tried[$cls]:-0} cases"; done
echo "cli hardening: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
