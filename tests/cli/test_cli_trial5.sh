#!/usr/bin/env bash
# Issue 46 (careless use, fifth round): the files a value or a scene name
# resolves to are inputs, third-party readers cannot take the process down,
# pipes are read once, losses and sample limits are said in one line.
set -u
bin=$1
dir=$2
# shellcheck source=cli_common.sh
source "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/cli_common.sh"  # enters a fresh $dir

printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' >tet.obj

# --- 1. A file name with commas is one file; a catalog name is its model ------
cp tet.obj 'a,b.obj'
sum=$(md5sum <'a,b.obj')
for out in --out --stats --nrrd --vdb; do
  other=(--out g.bin)
  [[ $out == --out ]] && other=()
  expect files 2 "is the same file as --mesh" -- voxelize --mesh 'a,b.obj' --grid 4 "${other[@]}" $out 'a,b.obj'
  unchanged files 'a,b.obj' "$sum"
done
expect files 0 "" -- voxelize --mesh 'a,b.obj' --grid 4 --out g.bin --quiet
expect files 2 "is the same file as --scenes" -- bench --scenes 'a\,b.obj' --techniques ha --out 'a\,b.obj'
unchanged files 'a,b.obj' "$sum"
mkdir -p models/OBJ && cp tet.obj models/OBJ/spider.obj && ln -s models/OBJ/spider.obj link-to-model
sum=$(md5sum <models/OBJ/spider.obj)
export HABUFFER_ASSIMP_MODELS=models
expect files 2 "is the same file as --scene" -- render --scene spider --stats models/OBJ/spider.obj
expect files 2 "is the same file as --mesh" -- voxelize --mesh spider --out g.bin --stats link-to-model
expect files 2 "is the same file as --scenes" -- bench --scenes engine,spider:opacity=0.5 --techniques ha --out link-to-model
expect files 2 "is the same file as --meshes" -- figure voxels --meshes sphere,spider --out models/OBJ/spider.obj
unset HABUFFER_ASSIMP_MODELS
unchanged files models/OBJ/spider.obj "$sum"

# --- 2. Voxel files: corrupt VDB files fenced, FIFOs and pipes read once -------
if "$bin" info 2>/dev/null | grep -q "OpenVDB [0-9]"; then
  expect vdb 0 "" -- voxelize --mesh sphere --grid 12 --out s.grid --vdb s.vdb --quiet
  for i in $(seq 0 24); do
    /usr/bin/python3 - "$i" <<'PY'
import random, sys
rng = random.Random(int(sys.argv[1]))
b = bytearray(open("s.vdb", "rb").read())
for _ in range(rng.randint(1, 4)):
    b[rng.randrange(len(b))] = rng.randrange(256)
open("c.vdb", "wb").write(b)
PY
    "$bin" hash build --voxels c.vdb --out c.tab --quiet >out.txt 2>err.txt
    code=$?
    if [[ $code -gt 1 || $(wc -l <err.txt) -gt 1 ]] || { [[ $code -eq 1 ]] && ! grep -q "c.vdb" err.txt; }; then
      bad vdb "corrupt file $i: exit $code: $(head -c 300 err.txt)"
    else
      ok vdb
    fi
  done
  for f in s.vdb s.grid; do
    rm -f fifo && mkfifo fifo
    (cat $f >fifo &)
    timeout 60 "$bin" hash build --voxels fifo --out fifo.tab --quiet 2>err.txt
    code=$?
    "$bin" hash build --voxels $f --out file.tab --quiet
    [[ $code -eq 0 ]] && cmp -s fifo.tab file.tab && ok vdb || bad vdb "$f through a FIFO: exit $code $(cat err.txt)"
    cat $f | "$bin" hash build --voxels /dev/stdin --out pipe.tab --quiet 2>err.txt
    cmp -s pipe.tab file.tab && ok vdb || bad vdb "$f through a pipe: $(cat err.txt)"
  done
fi

# A flat mesh encloses nothing: refused before any file is written.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n' >flat.obj
expect vdb 1 "is flat along z" -- voxelize --mesh flat.obj --out flat.grid --vdb flat.vdb --nrrd flat.nrrd --stats flat.json
[[ -z $(ls flat.grid flat.vdb flat.nrrd flat.json 2>/dev/null) ]] && ok vdb || bad vdb "a refused flat mesh left outputs"

# --- 3. Shading at any scale: a mesh scaled by a power of two renders the
# unit mesh's image exactly (float scales exactly), and by powers of ten
# within a rounding of it; the faces keep their shades (not one flat grey).
/usr/bin/python3 - <<'PY'
import math
def sphere(scale, path):
    rings, segs = 8, 12
    v = [(0.0, 0.0, 1.0)]
    for i in range(1, rings):
        th = math.pi * i / rings
        for j in range(segs):
            ph = 2 * math.pi * j / segs
            v.append((math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th)))
    v.append((0.0, 0.0, -1.0))
    f = []
    for j in range(segs):
        f.append((1, 2 + j, 2 + (j + 1) % segs))
    for i in range(rings - 2):
        for j in range(segs):
            a, b = 2 + i * segs + j, 2 + i * segs + (j + 1) % segs
            f += [(a, a + segs, b), (b, a + segs, b + segs)]
    last = len(v)
    base = 2 + (rings - 2) * segs
    for j in range(segs):
        f.append((base + j, last, base + (j + 1) % segs))
    with open(path, "w") as out:
        for p in v:
            out.write("v %r %r %r\n" % tuple(float(c) * scale for c in p))
        for t in f:
            out.write("f %d %d %d\n" % t)
for name, scale in [("unit", 1.0), ("p56", 2.0 ** 56), ("m56", 2.0 ** -56), ("e17", 1e17), ("e14", 1e14),
                    ("em9", 1e-9), ("em17", 1e-17)]:
    sphere(scale, "scaled_%s.obj" % name)
PY
expect scale 0 "" -- render --scene scaled_unit.obj --size 64x64 --out scaled_unit.png --quiet
for name in p56 m56 e17 e14 em9 em17; do
  expect scale 0 "" -- render --scene scaled_$name.obj --size 64x64 --out scaled_$name.png --quiet
  psnr=$("$bin" compare scaled_unit.png scaled_$name.png 2>&1 | sed -n 's/.*psnr \([^ ]*\).*/\1/p')
  case $name in
    p56 | m56) [[ $psnr == inf ]] && ok scale || bad scale "a mesh scaled 2^$name: PSNR $psnr against the unit mesh, not inf" ;;
    *) /usr/bin/python3 -c "import sys; sys.exit(0 if '$psnr' == 'inf' or float('$psnr') >= 40 else 1)" 2>/dev/null &&
      ok scale || bad scale "a mesh scaled $name: PSNR $psnr against the unit mesh (want >= 40 dB)" ;;
  esac
done

# --- 4. A sample count this OpenGL cannot make exactly: one line naming --samples.
held=$("$bin" info 2>/dev/null | sed -n 's/.*multisampling (--samples): \([0-9, ]*\) (.*/\1/p')
for s in 2 8; do
  [[ ", $held," == *", $s,"* ]] && continue
  expect samples 1 "--samples $s" -- render --scene quads --count 4 --size 16x16 --out ms.png --samples $s --technique lists
  [[ ! -e ms.png ]] && ok samples || bad samples "a refused --samples $s wrote its image"
done

# --- 5. Unclear messages made short: a fragment file named by --fragments is
# one whatever its extension; a 300-byte name and a field padded with 500
# spaces give one line that quotes neither whole.
expect plan 0 "" -- generate --out frags.txt --screen 16x12 --fragments 300
expect plan 0 "" -- plan --fragments frags.txt --size 16x12 --out plan.json --quiet
long=$(printf 'n%.0s' $(seq 1 300))
"$bin" render --scene quads --count 2 --size 16x16 --out "$long/x.png" --quiet 2>err.txt
code=$?
[[ $code -ne 0 && $(wc -l <err.txt) -eq 1 && $(wc -c <err.txt) -lt 400 ]] && ok plan ||
  bad plan "a 300-byte output name: exit $code, $(wc -c <err.txt) bytes: $(head -c 300 err.txt)"
printf 'x,y,depth,rgba\n1,%500szz,0.5,0\n' "" >padded.csv
"$bin" build-lists --in padded.csv --out l.csv --screen 4x4 2>err.txt
code=$?
[[ $code -ne 0 && $(wc -c <err.txt) -lt 300 ]] && ! grep -q '   ' err.txt && ok plan ||
  bad plan "a field padded with 500 spaces: exit $code, $(wc -c <err.txt) bytes"

for cls in files vdb scale samples plan; do echo "class $cls: ${tried[$cls]:-0} cases"; done
echo "cli trial 5: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
