#!/usr/bin/env bash
# CLI contract: bad usage exits 2, bad data exits 1, each with one clear line
# on stderr naming what was wrong; good input exits 0 and writes its files.
set -u
bin=$1
dir=$2
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir" || exit 1
pass=0
fail=0

# expect CODE NEEDLE -- ARGS...
expect() {
  local code=$1 needle=$2
  shift 3
  "$bin" "$@" >out.txt 2>err.txt
  local got=$?
  local lines
  lines=$(wc -l <err.txt)
  local bad=0
  if [[ $code -eq 0 ]]; then
    [[ $got -eq 0 ]] || bad=1
  elif [[ $got -ne $code || $lines -ne 1 ]] || ! grep -qF -- "$needle" err.txt; then
    bad=1
  fi
  if [[ $bad -ne 0 ]]; then
    echo "FAIL: habuffer $* -> exit $got (want $code), stderr:"
    cat err.txt
    echo "  (wanted one line containing: $needle)"
    fail=$((fail + 1))
  else
    pass=$((pass + 1))
  fi
}

printf 'x,y,depth,rgba\n0,0,0.5,0xFF0000FF\n1,0,0.25,255\n1,0,0.75,0x00FF0080\n' >good.csv
printf 'x,y,depth,rgba\n0,0,0.5,1\n0,5,0.5,1\n' >offscreen.csv
printf 'x,y,depth,rgba\n0,0,half,1\n' >baddepth.csv
printf 'ox,oy\n0,0\n1,0\n' >short_offsets.csv
printf 'ox,oy\n0,0\n0,0\n1,0\n1,1\n2,0\n2,1\n2,2\n0,2\n1,2\n3,0\n3,1\n3,2\n3,3\n0,3\n1,3\n' >dup_offsets.csv

expect 0 "" -- build-lists --in good.csv --out lists.csv --screen 2x2 --stats s.json --dump-table t.csv --dump-max-age m.csv
expect 2 "unknown command 'frobnicate'" -- frobnicate
expect 2 "option --out is required" -- build-lists --in good.csv --screen 2x2
expect 2 "option --screen: '2by2' is not a size WxH" -- build-lists --in good.csv --out l.csv --screen 2by2
expect 2 "table 2x1 is smaller than screen 2x2" -- build-lists --in good.csv --out l.csv --screen 2x2 --table 2x1
expect 2 "option --age-bits: 13 outside 4..12" -- build-lists --in good.csv --out l.csv --screen 2x2 --age-bits 13
expect 2 "option --layout: '48' is not 64 or 32" -- build-lists --in good.csv --out l.csv --screen 2x2 --layout 48
expect 2 "unknown option '--bogus'" -- build-lists --in good.csv --out l.csv --screen 2x2 --bogus 1
expect 2 "threshold must be in (0, 1]" -- build-lists --in good.csv --out l.csv --screen 2x2 --early-cull 1.5
expect 2 "early cull needs the L64 layout" -- build-lists --in good.csv --out l.csv --screen 2x2 --layout 32 --early-cull 0.5
expect 1 "is a directory, not a CSV file" -- build-lists --in . --out l.csv --screen 2x2
expect 1 "missing.csv: cannot open for reading" -- build-lists --in missing.csv --out l.csv --screen 2x2
expect 1 "offscreen.csv:3: field y: 5 outside screen 2x2" -- build-lists --in offscreen.csv --out l.csv --screen 2x2
expect 1 "baddepth.csv:2: field depth: 'half' is not a number" -- build-lists --in baddepth.csv --out l.csv --screen 2x2
expect 1 "short_offsets.csv: offsets: 2 rows given, 15 needed" -- build-lists --in good.csv --out l.csv --screen 2x2 --table 4x4 --age-bits 4 --offsets short_offsets.csv
expect 1 "dup_offsets.csv: offsets row 2 (age 2): duplicate offset (0,0)" -- build-lists --in good.csv --out l.csv --screen 2x2 --table 4x4 --age-bits 4 --offsets dup_offsets.csv
expect 2 "--out: /nonexistent/dir/l.csv cannot be created: directory /nonexistent/dir does not exist" -- build-lists --in good.csv --out /nonexistent/dir/l.csv --screen 2x2
expect 2 "give exactly one of --fragments and --load" -- generate --screen 4x4 --out f.csv
expect 2 "more than 2^28 slots" -- offsets --table 20000x20000 --generator farthest

# Good runs write what they promise.
if [[ "$(head -1 lists.csv)" != "x,y,rank,code,rgba" || $(wc -l <lists.csv) -ne 4 ]]; then
  echo "FAIL: lists.csv"; cat lists.csv; fail=$((fail + 1)); else pass=$((pass + 1)); fi
for key in fragments stored duplicates culled invalid failed_age failed_iter load_factor max_age mean_age \
  age_histogram memory_bytes build_ms threads path layout age_bits table screen; do
  if ! grep -q "\"$key\":" s.json; then echo "FAIL: stats key $key missing"; fail=$((fail + 1)); else pass=$((pass + 1)); fi
done
expect 0 "" -- build-lists --in good.csv --out l2.csv --screen 2x2 --table 3x3 --lossless --threads 2 --offsets farthest
expect 0 "" -- build-lists --in good.csv --out l3.csv --screen 2x2 --threads 2 --insert-mode owner
cmp -s lists.csv l3.csv && pass=$((pass + 1)) || { echo "FAIL: owner-computes lists differ"; fail=$((fail + 1)); }
expect 2 "option --insert-mode: 'magic' is not auto" -- build-lists --in good.csv --out l.csv --screen 2x2 --insert-mode magic
expect 0 "" -- generate --screen 32x32 --load 0.5 --out gen.csv --stream random
expect 0 "" -- offsets --table 64x64 --generator farthest --out o.csv --quality q.csv
# info opens a GL context: Mesa leaves allocations LeakSanitizer cannot attribute.
ASAN_OPTIONS=detect_leaks=0 expect 0 "" -- info
grep -q "gl: available through" out.txt && pass=$((pass + 1)) || { echo "FAIL: info has no GL path"; cat out.txt; fail=$((fail + 1)); }
grep -q "techniques: ha, lists, arrays" out.txt && pass=$((pass + 1)) || { echo "FAIL: info lists no techniques"; fail=$((fail + 1)); }
# --path gl and --path cpu write identical lists, table and max-age dumps
# (L32, native32), on streams of several shapes and table sizes.
for cfg in "48x32 48x32 4 coherent 0.8 32" "40x40 61x47 8 random 0.7 32" "64x16 64x16 6 random 0.9 32" \
  "48x32 48x32 4 coherent 0.8 64" "40x40 61x47 8 random 0.7 64"; do
  read -r screen table bits kind load layout <<<"$cfg"
  "$bin" generate --screen "$screen" --table "$table" --load "$load" --stream "$kind" --seed 3 --out gen_$screen.csv
  for path in cpu gl; do
    threads=(); [[ $path == cpu ]] && threads=(--threads 2)
    ASAN_OPTIONS=detect_leaks=0 expect 0 "" -- build-lists --in gen_$screen.csv --out l_$path.csv --screen "$screen" \
      --table "$table" --layout "$layout" --age-bits "$bits" --seed 5 "${threads[@]}" --path $path \
      --dump-table t_$path.csv --dump-max-age m_$path.csv --stats s_$path.json
  done
  if cmp -s l_cpu.csv l_gl.csv && cmp -s t_cpu.csv t_gl.csv && cmp -s m_cpu.csv m_gl.csv && [[ $(wc -l <t_gl.csv) -gt 10 ]]; then
    pass=$((pass + 1))
  else
    echo "FAIL: --path gl and --path cpu differ for $cfg"; fail=$((fail + 1))
  fi
done
# Lossless mode regathers on the GPU into the same grown tables as on the CPU.
"$bin" generate --screen 32x32 --load 1.2 --stream random --seed 4 --out gen_lossless.csv
for path in cpu gl; do
  ASAN_OPTIONS=detect_leaks=0 expect 0 "" -- build-lists --in gen_lossless.csv --out ll_$path.csv --screen 32x32 \
    --age-bits 4 --lossless --path $path --dump-table tl_$path.csv --stats sl_$path.json
done
if cmp -s ll_cpu.csv ll_gl.csv && cmp -s tl_cpu.csv tl_gl.csv && grep -q '"attempts":\[{' sl_gl.json &&
  [[ $(grep -o '"table":' sl_gl.json | wc -l) -gt 2 ]]; then
  pass=$((pass + 1))
else
  echo "FAIL: --path gl --lossless differs from cpu"; fail=$((fail + 1))
fi
expect 2 "option --iter-limit" -- build-lists --in good.csv --out l.csv --screen 2x2 --iter-limit 300000000
grep -q '"path":"gl"' s_gl.json && pass=$((pass + 1)) || { echo "FAIL: gl stats path"; fail=$((fail + 1)); }
expect 2 "option --path: 'gpu' is not cpu" -- build-lists --in good.csv --out l.csv --screen 2x2 --path gpu
# render: a real scene's image, stats and heat maps; one clear line for bad input.
ASAN_OPTIONS=detect_leaks=0 expect 0 "" -- render --scene engine --size 96x64 --out r_engine.png --stats r_engine.json \
  --heatmap depth:r_depth.png,age:r_age.png,culled:r_culled.png --reference r_ref.png --frames 2
for key in '"gather_ms"' '"resolve_ms"' '"frame_ms"' '"memory_bytes"' '"load_factor"' '"table"' '"max_age"' \
  '"max_depth_complexity"' '"frames":\[{' '"psnr"'; do
  grep -q "$key" r_engine.json && pass=$((pass + 1)) || { echo "FAIL: render stats lack $key"; fail=$((fail + 1)); }
done
for f in r_engine.png r_depth.png r_age.png r_culled.png r_ref.png; do
  [[ -s $f ]] && pass=$((pass + 1)) || { echo "FAIL: render did not write $f"; fail=$((fail + 1)); }
done
ASAN_OPTIONS=detect_leaks=0 expect 0 "" -- render --scene engine --size 96x64 --path cpu --out r_cpu.png --frames 2
expect 0 "" -- compare r_engine.png r_cpu.png
grep -q "psnr inf" out.txt && pass=$((pass + 1)) || { echo "FAIL: gl and cpu render images differ"; cat out.txt; fail=$((fail + 1)); }
"$bin" generate --screen 40x30 --load 0.5 --stream random --out r_frags.csv
expect 0 "" -- render --fragments r_frags.csv --size 40x30 --out r_frags.png --stats r_frags.json
ASAN_OPTIONS=detect_leaks=0 expect 0 "" -- render --scene planes --count 6 --opaque-meshes 3 --size 32x32 --out r_planes.exr \
  --stats r_planes.json
grep -q '"opaque_rejected":3072' r_planes.json && pass=$((pass + 1)) || { echo "FAIL: opaque plane rejects 3 planes"; fail=$((fail + 1)); }
expect 0 "" -- compare r_planes.exr r_planes.exr
expect 2 "option --opaque-meshes: mesh 9 does not exist (the scene has 6 meshes)" -- render --scene planes --count 6 \
  --opaque-meshes 9 --out x.png
expect 1 "unknown scene 'teapotx'" -- render --scene teapotx --out x.png
expect 1 "mesh file 'nowhere/teapot.obj' does not exist" -- render --scene nowhere/teapot.obj --out x.png
printf 'not a mesh\n' >garbage.obj
expect 1 "mesh file 'garbage.obj'" -- render --scene garbage.obj --out x.png
expect 2 "option --size: '0x64'" -- render --scene quads --size 0x64 --out x.png
ASAN_OPTIONS=detect_leaks=0 expect 1 "exceeds this OpenGL's largest viewport" -- render --scene quads --size 40000x64 --out x.png
expect 2 "option --heatmap: 'depth'" -- render --scene quads --heatmap depth --out x.png
expect 2 "give exactly one of --scene and --fragments" -- render --out x.png
# voxelize: a solid's grid, stats and reference; bad input refused.
ASAN_OPTIONS=detect_leaks=0 expect 0 "" -- voxelize --mesh torus --grid 24 --out v_torus.vox --stats v_torus.json \
  --reference --quiet
for key in '"voxels":' '"merged":' '"odd_columns":' '"dense_bytes":' '"mismatches":0'; do
  grep -q "$key" v_torus.json && pass=$((pass + 1)) || { echo "FAIL: voxelize stats lack $key"; fail=$((fail + 1)); }
done
[[ $(stat -c %s v_torus.vox) -eq $((40 + (24 * 24 * 24 + 63) / 64 * 8)) ]] && pass=$((pass + 1)) ||
  { echo "FAIL: voxelize grid file size"; fail=$((fail + 1)); }
ASAN_OPTIONS=detect_leaks=0 expect 0 "" -- voxelize --mesh torus --grid 24 --path cpu --threads 2 --out v_cpu.vox --quiet
cmp -s v_torus.vox v_cpu.vox && pass=$((pass + 1)) || { echo "FAIL: voxelize gl and cpu grids differ"; fail=$((fail + 1)); }
expect 2 "option --axis: 'w' is not x, y, z or all" -- voxelize --mesh sphere --axis w --out v.vox
expect 2 "option --threads has no effect with --path gl" -- voxelize --mesh sphere --threads 2 --out v.vox
expect 2 "option --grid" -- voxelize --mesh sphere --grid 0 --out v.vox
expect 2 "is the same file as --nrrd (two outputs)" -- voxelize --mesh sphere --out v.vox --nrrd v.vox
ASAN_OPTIONS=detect_leaks=0 expect 0 "" -- voxelize --mesh torus --grid 16 --axis all --reference --out v.vox \
  --nrrd v.nrrd --stats v_all.json --quiet
grep -q '"mismatches":0' v_all.json && pass=$((pass + 1)) || { echo "FAIL: voxelize --axis all --reference"; fail=$((fail + 1)); }
[[ $(head -c 8 v.nrrd) == NRRD0004 ]] && pass=$((pass + 1)) || { echo "FAIL: voxelize --nrrd magic"; fail=$((fail + 1)); }
expect 1 "unknown scene 'teapotx'" -- voxelize --mesh teapotx --out v.vox
# voxelize --vdb: the same grid as OpenVDB; hash build takes either file and builds the same table.
if ASAN_OPTIONS=detect_leaks=0 "$bin" info | grep -q "OpenVDB: OpenVDB"; then
  ASAN_OPTIONS=detect_leaks=0 expect 0 "" -- voxelize --mesh torus --grid 24 --out v_t.vox --vdb v_t.vdb --quiet
  expect 0 "" -- hash build --voxels v_t.vox --out h_vox.tab
  expect 0 "" -- hash build --voxels v_t.vdb --out h_vdb.tab
  cmp -s h_vox.tab h_vdb.tab && pass=$((pass + 1)) || { echo "FAIL: hash build from .vox and .vdb differ"; fail=$((fail + 1)); }
  printf ' BDV and then nothing an OpenVDB reader takes' >bad.vdb
  expect 1 "bad.vdb" -- hash build --voxels bad.vdb --out h_bad.tab
else
  ASAN_OPTIONS=detect_leaks=0 expect 2 "option --vdb: this habuffer was built without OpenVDB" -- voxelize --mesh torus --out v.vox --vdb v.vdb
fi
# csg: an expression over named solids, its image and stats, the ray caster; bad solids and expressions refused.
ASAN_OPTIONS=detect_leaks=0 expect 0 "" -- csg --solids "cube=box:-1,-1,-1,1,1,1; hole=cylinder:0,0,-2,0,0,1,4,0.5" \
  --expr "cube - hole" --size 48x48 --out c.png --stats c.json --reference --quiet
for key in '"expression":"(cube - hole)"' '"mismatches":0' '"covered_pixels":'; do
  grep -q "$key" c.json && pass=$((pass + 1)) || { echo "FAIL: csg stats lack $key"; fail=$((fail + 1)); }
done
expect 2 "option --expr: csg expression, column 8: unknown primitive 'hol'" -- csg --solids "cube=box:0,0,0,1,1,1" \
  --expr "cube - hol" --out c.png
expect 2 "option --solids: cube=box takes 6 numbers, not 5" -- csg --solids "cube=box:0,0,0,1,1" --expr cube --out c.png
expect 2 "option --solids: 'cube' is named twice" -- csg --solids "cube=box:0,0,0,1,1,1;cube=sphere:0,0,0,1" \
  --expr cube --out c.png
expect 2 "option --solids: box box: every side must be positive" -- csg --solids "box=box:0,0,0,0,1,1" --expr box \
  --out c.png
# render --shadows: the light's stats, its T heat map, the reference check; bad lights refused by name.
ASAN_OPTIONS=detect_leaks=0 expect 0 "" -- render --scene engine --size 48x48 --shadows --light-size 96x96 \
  --light-ortho --stats r_shadow.json --heatmap shadow:r_shadow_t.png --shadow-error 0 --frames 2
for key in '"light":' '"builds":1' '"bias_codes":' '"lookup_ms":' '"within_fraction":' '"silhouette_band":'; do
  grep -q "$key" r_shadow.json && pass=$((pass + 1)) || { echo "FAIL: shadow stats lack $key"; fail=$((fail + 1)); }
done
[[ -s r_shadow_t.png ]] && pass=$((pass + 1)) || { echo "FAIL: render did not write the shadow heat map"; fail=$((fail + 1)); }
expect 2 "option --light-dir has no effect without --shadows" -- render --scene quads --light-dir 0,-1,0 --out x.png
expect 2 "option --light-size: '0x64'" -- render --scene quads --shadows --light-size 0x64 --out x.png
expect 2 "option --light-dir: '0,1' is not X,Y,Z" -- render --scene quads --shadows --light-dir 0,1 --out x.png
expect 2 "option --light-dir: the zero vector" -- render --scene quads --shadows --light-dir 0,0,0 --out x.png
expect 2 "option --light-cull: threshold must be in (0, 1]" -- render --scene quads --shadows --light-cull 1.5 \
  --out x.png
expect 2 "option --light-fov has no effect with --light-ortho" -- render --scene quads --shadows --light-ortho \
  --light-fov 30 --out x.png
expect 2 "option --shadows needs --layout 64" -- render --scene quads --shadows --layout 32 --out x.png
ASAN_OPTIONS=detect_leaks=0 expect 1 "leaves no usable depth range" -- render --scene quads --shadows \
  --light-pos 1e30,0,0 --out x.png
# The precision rule: at 1e6 float32 rounds the light's depth by ~0.5, over a hundred light pixels' sides.
ASAN_OPTIONS=detect_leaks=0 expect 1 "leaves float32 too coarse a depth for this scene" -- render --scene quads \
  --shadows --light-pos 1e6,0,0 --out x.png
# A slope whose bias exceeds the map's short side (the whole scene's depth) once saturated the bias silently.
expect 2 "--shadow-slope 1e+30 must be below 1024" -- render --scene quads --shadows --shadow-slope 1e30 --out x.png
expect 2 "--shadow-slope 600 must be below 512" -- render --scene quads --shadows --shadow-filter pcf \
  --shadow-slope 600 --out x.png
# Any finite direction but zero is normalisable, however long (1e38 was once "not finite").
for ortho in "" --light-ortho; do
  ASAN_OPTIONS=detect_leaks=0 expect 0 "" -- render --scene quads --size 16x16 --shadows --light-size 32x32 \
    --light-dir 1e38,-1e38,0 $ortho --stats r_dir.json
done
# A bias covering the light's whole depth range (one quad facing the light) is warned about.
ASAN_OPTIONS=detect_leaks=0 "$bin" render --scene quads --count 1 --size 16x16 --shadows --light-size 32x32 \
  --light-ortho --light-dir 0,0,-1 --stats r_flat.json >out.txt 2>err.txt
if [[ $? -eq 0 ]] && grep -qF "covers the light's whole depth range over the scene" err.txt; then
  pass=$((pass + 1))
else
  echo "FAIL: no warning for a shadow bias over the whole depth range:"; cat err.txt; fail=$((fail + 1))
fi
expect 2 "option --shadow-filter: 'box' is not nearest or pcf" -- render --scene quads --shadows --shadow-filter box \
  --out x.png
expect 2 "option --heatmap shadow: the light's transmittance needs --shadows" -- render --scene quads \
  --heatmap shadow:x.png --out y.png
ASAN_OPTIONS=detect_leaks=0 expect 1 "inside the scene's bounding sphere" -- render --scene quads --shadows \
  --light-pos 0,0,0 --out x.png
expect 1 "images differ in size" -- compare r_engine.png r_frags.png
expect 0 "" -- stats --screen 32x32 --trials 2 --loads 0.5,0.9 --probing all --policy all --out st.csv
if [[ "$(head -1 st.csv | cut -d, -f1-6)" != "variant,load,stored_load,trials,mean_age,mean_age_ci95" || $(wc -l <st.csv) -ne 9 ]]; then
  echo "FAIL: stats csv"; head -3 st.csv; fail=$((fail + 1)); else pass=$((pass + 1)); fi
expect 2 "option --loads: 'x' is not a load in (0, 4]" -- stats --loads 0.5,x
expect 2 "option --probing: unknown value 'linear'" -- stats --probing linear
expect 2 "table 16x16 is smaller than screen 32x32" -- stats --screen 32x32 --table 16x16

# hash: a spatial hash built from a CSV, a key set and a voxel grid, queried, its stats; bad input refused.
printf 'x,y,value\n1,1,5\n1,1,9\n2,3,0x10\n7,0,4\n' >hk.csv
expect 0 "" -- hash build --keys hk.csv --out hk.tab --rule max --stats hk.json --quiet
for key in '"duplicates":1' '"keys":3' '"lost":0'; do
  grep -q "$key" hk.json && pass=$((pass + 1)) || { echo "FAIL: hash build stats lack $key"; fail=$((fail + 1)); }
done
expect 0 "" -- hash query --table hk.tab --keys hk.csv --out hq.csv --quiet
[[ "$(cat hq.csv | tr '\n' ' ')" == "x,y,found,value 1,1,1,9 1,1,1,9 2,3,1,16 7,0,1,4 " ]] && pass=$((pass + 1)) ||
  { echo "FAIL: hash query results"; cat hq.csv; fail=$((fail + 1)); }
expect 0 "" -- hash build --key-set voxel-shell --domain 24x24x24 --out hv.tab --load 0.95 --fixed --quiet
expect 0 "keys, 0 tombstones" -- hash stats --table hv.tab --out hv.json
printf 'x,y\n1,1\n1,zz\n' >hb.csv
expect 1 "hb.csv:3: field y: 'zz' is not an unsigned integer" -- hash build --keys hb.csv --out hb.tab
printf 'x,y\n9,9\n' >hq2.csv
expect 1 "hq2.csv: data row 1: key (9, 9, 0) is outside the domain 8x4" -- hash query --table hk.tab --keys hq2.csv
head -c 60 hk.tab >trunc.tab
expect 1 "trunc.tab: " -- hash stats --table trunc.tab
expect 2 "give exactly one of --keys, --key-set, --voxels and --image" -- hash build --out x.tab
expect 2 "option --rule: 'newest' is not max, min, first or last" -- hash build --keys hk.csv --out x.tab --rule newest
expect 2 "option --domain: '0x5' is not XxY" -- hash build --key-set random --domain 0x5 --out x.tab
expect 2 "unknown subcommand 'drop'" -- hash drop

expect 0 "" -- stats --keys sparse-image --domain 64x64 --loads 0.5,0.95 --trials 2 --policy all --quiet --out ks.csv
[[ "$(head -1 ks.csv | cut -d, -f1-5)" == "variant,load,stored_load,trials,keys" && $(wc -l <ks.csv) -eq 9 ]] &&
  pass=$((pass + 1)) || { echo "FAIL: stats --keys csv"; head -3 ks.csv; fail=$((fail + 1)); }
expect 2 "option --screen has no effect with --keys" -- stats --keys random --domain 64x64 --screen 8x8
expect 2 "option --domain has no effect without --keys" -- stats --domain 64x64
expect 2 "option --loads: '1.5' is not a load in (0, 1] (with --keys)" -- stats --keys random --domain 64x64 --count 100 --loads 1.5
echo "cli: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
