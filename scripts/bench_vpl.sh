#!/usr/bin/env bash
# vpl's error split by stage on one scene (docs/BENCHMARKS.md, "VPL instant
# radiosity"): the exact counterpart E (reference integrator=path,
# maxdepth = bounces + 1, rendered once), and per VPL count N:
#   V  vpl (voxel two-point visibility, default clamp)
#   X  vpl visibility=exact (the same VPLs, Embree occlusion rays)
#   U  vpl visibility=exact clamp=0 (nothing clamped)
# V vs X is the voxel visibility, X vs U the clamp, U vs E the many-light
# estimate itself (RSM texels as VPLs, bounce VPLs placed through the voxel
# grid, interleaving, blur, upsampling) plus noise at SPP samples.
# Indirect AOV: relMSE, rel. MAE, energy (green); per-sample gather time.
#   scripts/bench_vpl.sh OUT [SCENE] [SIZE] [SPP] [REF_SPP] [BOUNCES] [COUNTS…]
set -euo pipefail
OUT=${1:?usage: bench_vpl.sh OUT [SCENE] [SIZE] [SPP] [REF_SPP] [BOUNCES] [COUNTS...]}
SCENE=${2:-builtin:cornell}
SIZE=${3:-256x256}
SPP=${4:-16}
REF=${5:-1024}
B=${6:-2}
shift $(( $# < 6 ? $# : 6 ))
COUNTS=${*:-256 1024 4096}
VGI=${VGI:-build/apps/vgi}
mkdir -p "$OUT"
r() { "$VGI" render --scene "$SCENE" --size "$SIZE" --aov direct,indirect --quiet "$@" > /dev/null; }
[ -f "$OUT/E.exr" ] || r --method reference --set integrator=path --set maxdepth=$((B + 1)) --spp "$REF" -o "$OUT/E.exr"
for n in $COUNTS; do
  r --method vpl --set bounces=$B --set vpls=$n --spp "$SPP" -o "$OUT/V$n.exr"
  r --method vpl --set bounces=$B --set vpls=$n --set visibility=exact --spp "$SPP" -o "$OUT/X$n.exr"
  r --method vpl --set bounces=$B --set vpls=$n --set visibility=exact --set clamp=0 --spp "$SPP" -o "$OUT/U$n.exr"
done
row() { python3 scripts/split_row.py "$VGI" "$@" --passes gather; }  # label A B
echo "| N: comparison | image relMSE | indirect relMSE | indirect rel. MAE | indirect energy | gather ms/sample |"
echo "|---|---|---|---|---|---|"
for n in $COUNTS; do
  row "$n: all, vpl vs exact path" "$OUT/V$n" "$OUT/E"
  row "$n: voxel visibility, vpl vs visibility=exact" "$OUT/V$n" "$OUT/X$n"
  row "$n: clamp, visibility=exact vs + clamp=0" "$OUT/X$n" "$OUT/U$n"
  row "$n: many-light estimate, clamp=0 exact visibility vs exact path" "$OUT/U$n" "$OUT/E"
done
