#!/usr/bin/env bash
# Installs the build in BUILD_DIR into a scratch prefix, builds tests/consumer
# against it with find_package(vgi), runs it, and checks that the installed
# `vgi` finds the installed shaders (../share/vgi/shaders beside its binary)
# and that the consumer renders a lit image. The suite runs this as
# Install.ConsumerBuildsAndRuns.
set -euo pipefail
BUILD_DIR=$(cd "${1:?usage: test_consumer.sh BUILD_DIR}" && pwd)
SRC=$(cd "$(dirname "$0")/.." && pwd)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cmake --install "$BUILD_DIR" --prefix "$WORK/prefix" > "$WORK/install.log"
generator=()
command -v ninja > /dev/null && generator=(-G Ninja)
cmake -S "$SRC/tests/consumer" -B "$WORK/build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$WORK/prefix" > "$WORK/configure.log" || { cat "$WORK/configure.log"; exit 1; }
cmake --build "$WORK/build" > "$WORK/build.log" || { cat "$WORK/build.log"; exit 1; }

# The installed tool reads the installed shaders, wherever the prefix was moved.
mv "$WORK/prefix" "$WORK/moved"
version=$(env -u VGI_SHADER_DIR "$WORK/moved/bin/vgi" --version)
echo "$version"
want="shaders $WORK/moved/share/vgi/shaders"
grep -qxF "$want" <<< "$version" || { echo "FAIL: expected '$want'"; exit 1; }

out=$(env -u VGI_SHADER_DIR "$WORK/build/vgi_consumer")
echo "$out"
grep -qx "method direct" <<< "$out" || { echo "FAIL: the registry lacks 'direct'"; exit 1; }
mean=$(sed -n 's/^mean //p' <<< "$out")
awk -v m="$mean" 'BEGIN { exit !(m > 0.01 && m < 10) }' || { echo "FAIL: image mean '$mean'"; exit 1; }
echo "consumer: ok"
