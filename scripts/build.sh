#!/usr/bin/env bash
# Installs the dependencies (scripts/setup.sh) and builds into build/ (Release): the given targets
# (README command 1: `vgi`, the program alone), or everything (the suite, the viewer's tests).
#   scripts/build.sh [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release > build.log 2>&1 || { cat build.log; exit 1; }
if [ $# -gt 0 ]; then
  cmake --build build --target "$@"
else
  cmake --build build
fi
