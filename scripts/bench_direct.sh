#!/usr/bin/env bash
# Reproduces the `direct` rows of docs/BENCHMARKS.md: the GL direct module against
# its exact Embree counterpart (reference integrator=direct), per shadow-map
# setting, plus the timings. Usage: scripts/bench_direct.sh [scene] [WxH] [out-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-builtin:cornell}
size=${2:-256x256}
out=${3:-out/bench_direct}
mkdir -p "$out"
vgi=build/apps/vgi
$vgi render --quiet --scene "$scene" --method reference --set integrator=direct --spp 64 --size "$size" -o "$out/ref.exr" 2>/dev/null
ms() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print('%.1f' % d['total_ms'], d['gl_renderer'])" "$1"; }
echo "reference direct (64 spp): $(ms "$out/ref.json") ms"
for res in 256 1024 2048; do
  for setting in "0 0" "1 0" "0 1" "1 0.25" "1 1" "4 4"; do
    set -- $setting
    name="$out/gl_r${res}_b$1_n$2"
    $vgi render --quiet --scene "$scene" --method direct --set shadow_res=$res --set shadow_bias=$1 \
      --set normal_offset=$2 --spp 64 --size "$size" -o "$name.exr" 2>/dev/null
    rel=$($vgi diff --json "$name.exr" "$out/ref.exr" | python3 -c "import json,sys; d=json.load(sys.stdin); print('relMSE %.5f  SSIM %.4f' % (d['relmse'], d['ssim']))")
    echo "direct shadow_res=$res shadow_bias=$1 normal_offset=$2: $rel  $(ms "$name.json") ms (64 frames)"
  done
done
