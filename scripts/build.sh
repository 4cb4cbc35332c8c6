#!/usr/bin/env bash
# Configures and builds one CMake preset (default: release) after setup.
# Usage: scripts/build.sh [release|debug|asan|tsan]
set -euo pipefail
cd "$(dirname "$0")/.."
preset=${1:-release}
./scripts/setup.sh
export HABUFFER_WERROR=${HABUFFER_WERROR:-ON}
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset"
