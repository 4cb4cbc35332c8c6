#!/usr/bin/env bash
# Sets everything up, builds into build/ and runs the test suite: every test
# but the pip install test (label pip: a second whole build through setup.py,
# six minutes on two cores), which CI runs after this (`ctest -L pip`).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh release
ctest --preset release -j "$(nproc)" -LE pip
