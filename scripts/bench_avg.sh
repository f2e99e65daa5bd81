#!/usr/bin/env bash
# avg's error split by stage on one scene (docs/BENCHMARKS.md, "Approximate
# visibility grids"): the exact counterpart E (reference integrator=path,
# maxdepth = bounces + 1, rendered once; shared with bench_vpl.sh's when OUT
# is the same), and per VPL count N:
#   A  avg (rays marched through the AVG, per-VPL shadow maps, clamp);
#      MAP=paraboloid for the paper's maps (each map draws the occluders,
#      the scene simplified to vpl_shadow_triangles, illum/resources/occluders.h)
#   P  avg shadow_map=paraboloid (when MAP is cube)
#   S  A with vpl_shadow_triangles=0 (the maps draw the whole scene, not the
#      simplified occluders; the same image where the scene is within the budget)
#   T  avg visibility=exact (the same VPLs, Embree occlusion rays)
#   X  avg visibility=exact tracing=exact (the same rays through the triangles)
#   U  X with clamp=0
# A vs S is the occluders' simplification, S vs T the shadow maps of the
# scene itself (P vs T the paraboloids), T vs X the AVG's
# tracing, X vs U the clamp, U vs E the many-light estimate and noise.
# Indirect AOV: relMSE, rel. MAE, energy (green); per-sample time of the
# VPL passes (vpls + vpl_shadow_maps + gather).
#   scripts/bench_avg.sh OUT [SCENE] [SIZE] [SPP] [REF_SPP] [BOUNCES] [COUNTS…]
set -euo pipefail
OUT=${1:?usage: bench_avg.sh OUT [SCENE] [SIZE] [SPP] [REF_SPP] [BOUNCES] [COUNTS...]}
SCENE=${2:-builtin:cornell}
SIZE=${3:-256x256}
SPP=${4:-16}
REF=${5:-1024}
B=${6:-3}
shift $(( $# < 6 ? $# : 6 ))
COUNTS=${*:-256 1024 4096}
VGI=${VGI:-build/apps/vgi}
MAP=${MAP:-cube}
mkdir -p "$OUT"
r() { "$VGI" render --scene "$SCENE" --size "$SIZE" --aov direct,indirect --quiet "$@" > /dev/null; }
E="$OUT/E_maxdepth$((B + 1))"
[ -f "$E.exr" ] || r --method reference --set integrator=path --set maxdepth=$((B + 1)) --spp "$REF" -o "$E.exr"
for n in $COUNTS; do
  a() { r --method avg --set bounces=$B --set vpls=$n --spp "$SPP" "$@"; }
  a --set shadow_map=$MAP -o "$OUT/A$n.exr"
  [ "$MAP" != cube ] || a --set shadow_map=paraboloid -o "$OUT/P$n.exr"
  a --set shadow_map=$MAP --set vpl_shadow_triangles=0 -o "$OUT/S$n.exr"
  a --set visibility=exact -o "$OUT/T$n.exr"
  a --set visibility=exact --set tracing=exact -o "$OUT/X$n.exr"
  a --set visibility=exact --set tracing=exact --set clamp=0 -o "$OUT/U$n.exr"
done
row() { python3 scripts/split_row.py "$VGI" "$@" --passes vpls,vpl_shadow_maps,gather; }  # label A B
echo "| N: comparison | image relMSE | indirect relMSE | indirect rel. MAE | indirect energy | VPL passes ms/sample |"
echo "|---|---|---|---|---|---|"
for n in $COUNTS; do
  row "$n: all, avg vs exact path" "$OUT/A$n" "$E"
  row "$n: $MAP shadow maps, avg vs visibility=exact" "$OUT/A$n" "$OUT/T$n"
  row "$n: occluders, avg vs vpl_shadow_triangles=0" "$OUT/A$n" "$OUT/S$n"
  row "$n: $MAP maps of the whole scene vs visibility=exact" "$OUT/S$n" "$OUT/T$n"
  [ "$MAP" != cube ] || row "$n: paraboloid shadow maps vs visibility=exact" "$OUT/P$n" "$OUT/T$n"
  row "$n: AVG tracing, visibility=exact vs + tracing=exact" "$OUT/T$n" "$OUT/X$n"
  row "$n: clamp, exact stages vs + clamp=0" "$OUT/X$n" "$OUT/U$n"
  row "$n: many-light estimate, exact stages + clamp=0 vs exact path" "$OUT/U$n" "$E"
done
