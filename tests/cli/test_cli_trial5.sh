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

for cls in files vdb; do echo "class $cls: ${tried[$cls]:-0} cases"; done
echo "cli trial 5: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
