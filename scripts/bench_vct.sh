#!/bin/bash
# vct and vct_ao against their exact counterparts (docs/BENCHMARKS.md,
# "Voxel cone tracing"): the Cornell box at 256x256, references rendered once.
#   vct:    reference integrator=path maxdepth=2 (512 spp); vct at 4 spp per grid /
#           chain / radiance source; indirect rel. MAE, energy, relMSE.
#   AO:     reference integrator=ao, radius 0.3 x diagonal (256 spp) against
#           voxel_ao (voxel rays, 16 spp) and vct_ao (3 / 5 / 8 cones, each chain).
# Usage: scripts/bench_vct.sh [OUT_DIR]
set -euo pipefail
V=${VGI:-build/apps/vgi}
OUT=${1:-/tmp/bench_vct}
mkdir -p "$OUT"
S=256x256
row() {  # row LABEL A B
  "$V" diff "$2" "$3" --json | python3 -c "import json,sys; d=json.load(sys.stdin); e=d['energy_rgb']; \
print('| $1 | %.4f | %.3f | %.3f %.3f %.3f |' % (d['relmse'], d['rel_mae'], e[0], e[1], e[2]))"
}
"$V" render --method reference --set integrator=path --set maxdepth=2 --spp 512 --size $S -o "$OUT/ref.exr" \
  --aov direct,indirect --quiet >/dev/null
echo "| vct setting | indirect relMSE | indirect rel. MAE | indirect energy r g b |"
for s in "voxels=128" "voxels=256" "voxels=128 anisotropic=false" "voxels=128 radiance=atlas voxelizer=atlas" \
  "voxels=128 plane_guard=false" "voxels=128 diffuse_cones=9 aperture=45"; do
  sets=()
  for x in $s; do sets+=(--set "$x"); done
  "$V" render --method vct "${sets[@]}" --spp 4 --size $S -o "$OUT/vct.exr" --aov direct,indirect --quiet >/dev/null
  row "$s" "$OUT/vct.indirect.exr" "$OUT/ref.indirect.exr"
done
R=$("$V" render --method vct_ao --spp 1 --size 16x16 -o "$OUT/r.exr" --quiet 2>/dev/null >/dev/null; python3 -c \
  "import json; print(json.load(open('$OUT/r.json'))['extra']['radius'])")
"$V" render --method reference --set integrator=ao --set radius=$R --spp 256 --size $S -o "$OUT/refao.exr" --quiet >/dev/null
echo "| AO (radius $R) | relMSE | rel. MAE | energy |"
"$V" render --method voxel_ao --set radius=$R --spp 16 --size $S -o "$OUT/vao.exr" --quiet >/dev/null
row "voxel_ao (rays)" "$OUT/vao.exr" "$OUT/refao.exr"
for s in "cones=3" "cones=5" "cones=8" "cones=8 anisotropic=false" "cones=8 plane_guard=false" "cones=8 overlap=1.3" \
  "cones=8 jitter=false" "cones=8 voxels=256"; do
  sets=()
  for x in $s; do sets+=(--set "$x"); done
  "$V" render --method vct_ao "${sets[@]}" --spp 1 --size $S -o "$OUT/ao.exr" --quiet >/dev/null
  row "vct_ao $s" "$OUT/ao.exr" "$OUT/refao.exr"
done
