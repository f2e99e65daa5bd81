#!/usr/bin/env bash
# voxelpath's error split by stage, and its hit-point variants, on one scene
# (docs/BENCHMARKS.md, "Voxel path tracing"): reference integrator=path with
# exact visibility (E) and with visibility=voxels (V: the bounce rays' first
# hits through an exact voxelization, shading and direct light exact), and
# voxelpath (G) with each hitpoint. V vs E is the voxel visibility; G vs V the
# voxel shading (hit point, mean normal and BRDF) plus the RSM direct light at
# hits. Indirect AOV: relMSE, rel. MAE, energy (green).
#   scripts/bench_voxelpath_split.sh OUT [SCENE] [SIZE] [SPP] [REF_SPP] [VOXELS]
set -euo pipefail
OUT=${1:?usage: bench_voxelpath_split.sh OUT [SCENE] [SIZE] [SPP] [REF_SPP] [VOXELS]}
SCENE=${2:-builtin:cornell}
SIZE=${3:-256x256}
SPP=${4:-64}
REF=${5:-1024}
VOX=${6:-128}
VGI=${VGI:-build/apps/vgi}
mkdir -p "$OUT"
r() { "$VGI" render --scene "$SCENE" --size "$SIZE" --aov direct,indirect --quiet "$@" > /dev/null; }
r --method reference --set integrator=path --set maxdepth=3 --spp "$REF" -o "$OUT/E.exr"
r --method reference --set integrator=path --set maxdepth=3 --set visibility=voxels --set voxels="$VOX" \
  --set offset=1 --spp "$REF" -o "$OUT/V.exr"
for hp in entry centre plane; do
  r --method voxelpath --set voxels="$VOX" --set hitpoint=$hp --spp "$SPP" -o "$OUT/G_$hp.exr"
done
row() { python3 scripts/split_row.py "$VGI" "$@"; }  # label A B
echo "| comparison | image relMSE | indirect relMSE | indirect rel. MAE | indirect energy |"
echo "|---|---|---|---|---|"
row "voxel visibility: reference visibility=voxels vs exact" "$OUT/V" "$OUT/E"
for hp in entry centre plane; do
  row "voxel shading + RSM at hits: voxelpath hitpoint=$hp vs visibility=voxels" "$OUT/G_$hp" "$OUT/V"
  row "all: voxelpath hitpoint=$hp vs exact" "$OUT/G_$hp" "$OUT/E"
done
