#!/usr/bin/env bash
# Draws docs/architecture.svg from the build's own CMake targets: the
# libraries, their parts (habuffer_add_part) and what each declares it uses
# (cmake --graphviz, then Graphviz's dot; Debian graphviz). External
# packages, the compile-flag target and the tools are left out.
# Usage: scripts/draw_architecture.sh [OUT.svg]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-docs/architecture.svg}
command -v dot >/dev/null || { echo "draw_architecture: needs Graphviz's dot (apt-get install graphviz)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat >"$work/CMakeGraphVizOptions.cmake" <<'CMAKE'
set(GRAPHVIZ_GRAPH_NAME "habuffer")
set(GRAPHVIZ_EXTERNAL_LIBS FALSE)
set(GRAPHVIZ_GENERATE_PER_TARGET FALSE)
set(GRAPHVIZ_GENERATE_DEPENDERS FALSE)
set(GRAPHVIZ_IGNORE_TARGETS "^habuffer_build_flags$;^habuffer_write_glsl$;^habuffer_glsl_dump$;_tests$;^habuffer_bench;^habuffer_adaptive_jumps$;^habuffer_csg_peers$;^fuzz_")
CMAKE
cmake -S . -B "$work" -G Ninja -DHABUFFER_BUILD_TESTS=OFF -DHABUFFER_BUILD_BENCHMARKS=OFF -DHABUFFER_INSTALL=OFF \
      -DHABUFFER_WITH_PYTHON=OFF --graphviz="$work/habuffer.dot" >"$work/configure.log" ||
  { cat "$work/configure.log" >&2; exit 1; }
# Top to bottom as docs/architecture.md's order runs: users above what they use.
sed -i 's/^digraph "habuffer" {/digraph "habuffer" {\n  rankdir = BT; node [fontsize = 10]; ranksep = 0.35;/' "$work/habuffer.dot"
dot -Tsvg "$work/habuffer.dot" -o "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out ($(grep -c '<g id="node' "$out") targets)"
