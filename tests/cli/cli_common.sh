# What the CLI test scripts share, sourced after `bin` and `dir` are set: a
# fresh working directory, counters per class of harm, and `expect`, which
# checks one run's exit code and stderr.
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir" || exit 1
export HABUFFER_CHECK_OPTIONS=1  # a given option the command never reads exits 70 (cli_args.h)
export ASAN_OPTIONS=${ASAN_OPTIONS:-}:detect_leaks=0  # GL runs: Mesa's allocations
pass=0
fail=0
declare -A tried

ok() { pass=$((pass + 1)); tried[$1]=$((${tried[$1]:-0} + 1)); }
bad() { echo "FAIL [$1]: $2"; fail=$((fail + 1)); tried[$1]=$((${tried[$1]:-0} + 1)); }

# expect CLASS CODE NEEDLE -- ARGS...: exit CODE, one stderr line of at most
# 400 printable bytes containing NEEDLE (CODE 0: stderr may hold warnings).
expect() {
  local cls=$1 code=$2 needle=$3
  shift 4
  "$bin" "$@" >out.txt 2>err.txt </dev/null
  local got=$? lines bytes
  lines=$(wc -l <err.txt)
  bytes=$(wc -c <err.txt)
  if [[ $got -ne $code ]]; then
    bad "$cls" "habuffer $* -> exit $got, want $code: $(head -c 300 err.txt)"
  elif [[ $code -ne 0 && ($lines -ne 1 || $bytes -gt 400) ]]; then
    bad "$cls" "habuffer $* -> stderr has $lines lines, $bytes bytes"
  elif LC_ALL=C grep -q '[^[:print:][:space:]]' err.txt; then
    bad "$cls" "habuffer $* -> unprintable bytes on stderr"
  elif [[ -n $needle ]] && ! grep -qF -- "$needle" err.txt; then
    bad "$cls" "habuffer $* -> stderr lacks '$needle': $(cat err.txt)"
  else
    ok "$cls"
  fi
}

unchanged() {  # CLASS FILE CHECKSUM
  if [[ "$(md5sum <"$2")" == "$3" ]]; then ok "$1"; else bad "$1" "$2 was changed"; fi
}

