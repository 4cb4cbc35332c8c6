#!/usr/bin/env bash
# Every assembled shader (each atomic mode and stage, native64 included,
# which llvmpipe cannot run) compiled by the reference compiler,
# glslangValidator, for OpenGL: the modes this machine cannot execute are at
# least compiled on every change.
set -u
dump=$1
validator=$2
dir=$3
rm -rf "$dir" && mkdir -p "$dir" || exit 1
"$dump" "$dir" || exit 1
pass=0
fail=0
for f in "$dir"/*.*; do
  if "$validator" "$f" >"$f.log" 2>&1; then
    pass=$((pass + 1))
  else
    echo "FAIL: $(basename "$f") does not compile:"
    grep -E "ERROR|error" "$f.log" | head -5
    fail=$((fail + 1))
  fi
done
echo "glslangValidator: $pass compiled, $fail failed"
[[ $pass -gt 0 && $fail -eq 0 ]]
