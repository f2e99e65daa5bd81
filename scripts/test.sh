#!/usr/bin/env bash
# The README's test command: set up (with the suite's own packages: scripts/setup.sh --tests), build,
# run the whole suite (CTest + gtest).
# GL tests run headless on Mesa llvmpipe (EGL surfaceless and OSMesa).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --tests
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"
