#!/usr/bin/env bash
# Issue 25: outputs appear whole or not at all (a signal, a full disk, a
# file-size limit or a second run never leaves a partial or mixed file, and
# an earlier file of the name survives every failure), and the harness's
# commands hold to the CLI's rules for files, words and resources.
set -u
bin=$1
dir=$2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir" || exit 1
export ASAN_OPTIONS=${ASAN_OPTIONS:-}:detect_leaks=0  # GL runs: Mesa's allocations
# shellcheck source=cli_common.sh
source "$here/cli_common.sh"

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

for cls in signal write race replace; do echo "class $cls: ${tried[$cls]:-0} cases"; done
echo "cli outputs: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
