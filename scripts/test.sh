#!/usr/bin/env bash
# Sets everything up, builds into build/ and runs the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh release
ctest --preset release -j "$(nproc)"
