#!/usr/bin/env bash
# One declaration per command (issue 24, item 6): each command's --help is
# written from the options it accepts, so every option its help lists is
# accepted (a following unknown option is the one refused), its help starts
# with its usage line, and build-lists' help lists every option a technique
# descriptor names (`habuffer techniques`).
set -u
bin=$1
dir=$2
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir" || exit 1
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL: $1"; fail=$((fail + 1)); }

# accepted CMD... -- FLAG: "CMD... --FLAG 1 --zz-not-an-option" is refused for
# --zz-not-an-option alone (Args reads every option before any work).
accepted() {
  local flag=${*: -1}
  local cmd=("${@:1:$#-2}")
  "$bin" "${cmd[@]}" "--$flag" 1 --zz-not-an-option >out.txt 2>err.txt </dev/null
  local got=$?
  if [[ $got -eq 2 ]] && grep -qF -- "unknown option '--zz-not-an-option'" err.txt; then
    ok
  elif [[ $got -eq 2 ]] && grep -qF -- "unexpected argument '1'" err.txt; then
    ok  # a switch: its "value" 1 is the next argument, refused before the unknown option
  else
    bad "habuffer ${cmd[*]} --$flag: $(head -c 300 err.txt)"
  fi
}

# The flags of help text lines "  --NAME ...".
flags_of() { grep -oE '^  --[a-z0-9-]+' | sed 's/^  --//'; }

for cmd in build-lists render demo stats offsets generate sweep bench plan techniques info; do
  "$bin" $cmd --help >help.txt 2>err.txt
  if [[ $? -ne 0 ]] || ! head -1 help.txt | grep -qF "usage: habuffer $cmd"; then
    bad "$cmd --help: $(head -c 200 help.txt err.txt)"
    continue
  fi
  ok
  for flag in $(flags_of <help.txt); do accepted $cmd -- "$flag"; done
done

# figure: the common options before the first figure's section, each
# figure's own in its section; another figure's option is refused by name.
"$bin" figure --help >help.txt || bad "figure --help"
common=$(sed '/^[a-z0-9]*:$/,$d' help.txt | flags_of)
for fig in fig2 fig8 fig10 table1 frontier shadows voxels csg; do
  own=$(sed -n "/^$fig:\$/,/^[a-z0-9]*:\$/p" help.txt | sed '1d' | flags_of)
  [[ -n $own ]] && ok || bad "figure $fig lists no options of its own"
  for flag in $common $own; do accepted figure $fig -- "$flag"; done
done
"$bin" figure fig2 --planes 3 --out f.json >out.txt 2>err.txt
[[ $? -eq 2 ]] && grep -qF "option --planes does not apply to figure fig2" err.txt && ok ||
  bad "figure fig2 --planes: $(cat err.txt)"

# Every option a technique descriptor names is one of build-lists'.
"$bin" build-lists --help >help.txt
for flag in $("$bin" techniques | grep -oE 'options: .*' | grep -oE -- '--[a-z0-9-]+' | sed 's/^--//' | sort -u); do
  grep -qE "^  --$flag( |\$)" help.txt && ok || bad "build-lists --help lacks --$flag (a descriptor's option)"
done
# The technique options' help shows TechniqueConfig's defaults.
default_of() { grep -A2 -E "^  --$1 " help.txt | tr '\n' ' ' | grep -oE '[(]default [^)]*[)]' | head -1; }
[[ "$(default_of layers)" == "(default 16)" ]] && ok || bad "build-lists --help: --layers $(default_of layers)"
[[ "$(default_of pool)" == "(default auto)" ]] && ok || bad "build-lists --help: --pool $(default_of pool)"

echo "cli help: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
