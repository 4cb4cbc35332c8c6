#!/usr/bin/env bash
# Configures and builds one CMake preset (default: release) after setup:
# every target, or only the targets named after the preset.
# Usage: scripts/build.sh [release|debug|asan|tsan|fuzz] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
preset=${1:-release}
shift || true
./scripts/setup.sh
export HABUFFER_WERROR=${HABUFFER_WERROR:-ON}
cmake --preset "$preset" >/dev/null
if [ "$#" -gt 0 ]; then
  cmake --build --preset "$preset" --target "$@"
else
  cmake --build --preset "$preset"
fi
