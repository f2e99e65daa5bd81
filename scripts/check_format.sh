#!/usr/bin/env bash
# The tree's C++ is clang-formatted (.clang-format; Debian 12's clang-format 14).
# Run by CTest (Format.TreeIsClangFormatted); `clang-format -i FILE` fixes a file.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || { echo "clang-format not found (scripts/setup.sh installs it)"; exit 1; }
bad=()
while IFS= read -r -d '' f; do
  clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done < <(find core illum experiments voxelize traverse apps tests shaders -type f \( -name '*.cpp' -o -name '*.h' \) -print0)
if [ ${#bad[@]} -gt 0 ]; then
  echo "not clang-formatted (fix: clang-format -i FILE):"
  printf '  %s\n' "${bad[@]}"
  exit 1
fi
echo "format: all files clang-formatted"
