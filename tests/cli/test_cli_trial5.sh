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

for cls in files; do echo "class $cls: ${tried[$cls]:-0} cases"; done
echo "cli trial 5: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
