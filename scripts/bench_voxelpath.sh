#!/usr/bin/env bash
# voxelpath against its exact counterpart (reference integrator=path, same
# maxdepth and rr_depth): `vgi compare` per scene and grid resolution, and the
# error split by stage for the first scene. Writes OUT/<scene>_<voxels>.* and
# prints one table row per run (docs/BENCHMARKS.md, "Voxel path tracing").
#   scripts/bench_voxelpath.sh OUT [SIZE] [SPP] [REF_SPP] [VOXELS...]
set -euo pipefail
OUT=${1:?usage: bench_voxelpath.sh OUT [SIZE] [SPP] [REF_SPP] [VOXELS...]}
SIZE=${2:-256x256}
SPP=${3:-64}
REF=${4:-1024}
shift $(( $# < 4 ? $# : 4 ))
VOXELS=(128 256)
[ $# -gt 0 ] && VOXELS=("$@")
VGI=${VGI:-build/apps/vgi}
mkdir -p "$OUT"
SCENES=(builtin:cornell scenes/cornell-original.json scenes/cornell-glossy.json scenes/sibenik.json)
row() {  # scene voxels extra-args…
  local scene=$1 vox=$2
  shift 2
  local name
  name=$(basename "$scene" .json | tr ':' '_')_${vox}${TAG:-}
  "$VGI" compare --scene "$scene" --method voxelpath --set voxels="$vox" "$@" --size "$SIZE" --spp "$SPP" \
    --ref-spp "$REF" --quiet -o "$OUT/$name.exr" > "$OUT/$name.txt"
  python3 - "$OUT/$name.json" "$scene" "$vox" "${TAG:-}" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
e = c["error"]
t = c["time"]
def g(ch, k):
    return e[ch][k] if ch in e else float("nan")
print(f"| {sys.argv[2]} | {sys.argv[3]} {sys.argv[4]} | {g('image','relmse'):.4f} | {g('image','rel_mae'):.3f} | "
      f"{g('indirect','relmse'):.4f} | {g('indirect','rel_mae'):.3f} | {e['indirect']['energy_rgb'][1]:.3f} | "
      f"{t['method_ms_per_frame']:.0f} | {t['method_setup_ms']:.0f} | {t['exact_wall_ms'] / 1000:.1f} |")
PY
}
echo "| scene | voxels | relMSE | rel. MAE | indirect relMSE | indirect rel. MAE | indirect energy | ms/sample | set-up ms | exact s (REF spp) |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for scene in "${SCENES[@]}"; do
  for vox in "${VOXELS[@]}"; do row "$scene" "$vox"; done
done
