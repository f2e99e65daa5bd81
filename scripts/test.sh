#!/usr/bin/env bash
# The README's test command: set up, build, run the whole suite (CTest + gtest).
# GL tests run headless on Mesa llvmpipe (EGL surfaceless and OSMesa).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"
