#!/bin/bash
# vct and vct_ao against their exact counterparts (docs/BENCHMARKS.md,
# "Voxel cone tracing"), references rendered once per scene:
#   1. Cornell box 256²: vct (4 spp) per setting against reference path
#      maxdepth=2 (512 spp): indirect relMSE, rel. MAE, energy.
#   2. AO: reference ao (radius 0.3 × diagonal, 256 spp) against voxel_ao
#      (16 spp) and vct_ao (1 spp) per constellation / setting.
#   3. Grid sweep 128³ / 256³ / 512³ (Cornell): image and indirect error and
#      the per-pass times of one frame (4 spp).
#   4. CornellBox-Glossy and Sibenik: vct against path maxdepth=2, specular
#      on/off, empty-space skipping on/off (its time and its image change).
#   5. The light-leaking rooms (scenes/leak-rooms*.json): indirect light in
#      the closed dark room (exact 0) against the lit room's.
# Usage: scripts/bench_vct.sh [OUT_DIR] [SECTIONS, e.g. 1,2,3,4,5]
set -euo pipefail
. "$(dirname "$0")/script_args.sh"
[ $# -le 2 ] || sa_usage "[OUT_DIR] [SECTIONS, e.g. 1,2,3,4,5]   (VGI=path/to/vgi)"
V=${VGI:-build/apps/vgi}
OUT=${1:-/tmp/bench_vct}
SECTIONS=${2:-1,2,3,4,5}
sa_vgi VGI "$V"
[[ "$SECTIONS" =~ ^[1-5](,[1-5])*$ ]] || sa_fail SECTIONS "$SECTIONS" "expected a comma-separated list of 1 … 5"
sa_out OUT_DIR "$OUT"
S=256x256
has() { [[ ",$SECTIONS," == *",$1,"* ]]; }
metrics() {  # metrics A B -> "relMSE relMAE energy_g"
  "$V" diff "$1" "$2" --json | python3 -c "import json,sys; d=json.load(sys.stdin); \
print('%.4f | %.3f | %.3f' % (d['relmse'], d['rel_mae'], d['energy_rgb'][1]))"
}
sets() { for x in $1; do printf -- '--set %s ' "$x"; done; }
mean() { "$V" diff "$1" "$1" --json | python3 -c "import json,sys; print('%.4f' % json.load(sys.stdin)['mean_a_rgb'][1])"; }
passes() {  # the per-pass ms of a render's JSON, one frame
  python3 -c "import json; t=json.load(open('$1'))['timings_ms']; \
print(', '.join('%s %.0f' % (k, v) for k, v in sorted(t.items(), key=lambda kv: -kv[1]) if v >= 1))"
}
reference() {  # reference SCENE STEM SPP [SIZE]
  [ -f "$2.json" ] || sa_run "$OUT/vgi.log" "$V" render --scene "$1" --method reference --set integrator=path --set maxdepth=2 \
    --spp "$3" --size "${4:-$S}" -o "$2.exr" --aov direct,indirect --quiet
}
if has 1; then
  reference builtin:cornell "$OUT/ref" 512
  echo "| vct setting | indirect relMSE | indirect rel. MAE | indirect energy |"
  echo "|---|---|---|---|"
  for s in "voxels=128" "voxels=256" "anisotropic=false" "radiance=atlas voxelizer=atlas" "voxelizer=hybrid" \
    "plane_guard=false" "face_weights=squared" "diffuse_cones=9 aperture=45" "diffuse_cones=1 aperture=120" \
    "resolution=1 interleave=1" "step=0.5" "offset=2"; do
    sa_run "$OUT/vgi.log" "$V" render --method vct $(sets "$s") --spp 4 --size $S -o "$OUT/vct.exr" --aov indirect --quiet
    echo "| $s | $(metrics "$OUT/vct.indirect.exr" "$OUT/ref.indirect.exr") |"
  done
  echo "| soft shadows (direct AOV) | direct relMSE | direct rel. MAE | direct energy |"
  echo "|---|---|---|---|"
  for s in "shadows=false" "shadows=true" "shadows=true shadow_stop=1" "shadows=true shadow_aperture=1" \
    "shadows=true shadow_aperture=8"; do
    sa_run "$OUT/vgi.log" "$V" render --method vct $(sets "$s") --spp 4 --size $S -o "$OUT/vct.exr" --aov direct --quiet
    echo "| $s (cones_full $(python3 -c "import json; print('%.0f' % json.load(open('$OUT/vct.json'))['timings_ms']['cones_full'])") ms) | $(metrics "$OUT/vct.direct.exr" "$OUT/ref.direct.exr") |"
  done
fi
if has 2; then
  sa_run "$OUT/vgi.log" "$V" render --method vct_ao --spp 1 --size 16x16 -o "$OUT/r.exr" --quiet
  R=$(python3 -c "import json; print(json.load(open('$OUT/r.json'))['extra']['radius'])")
  [ -f "$OUT/refao.json" ] || sa_run "$OUT/vgi.log" "$V" render --method reference --set integrator=ao --set radius=$R --spp 256 --size $S \
    -o "$OUT/refao.exr" --quiet
  echo "| AO, radius $R | relMSE | rel. MAE | energy |"
  echo "|---|---|---|---|"
  sa_run "$OUT/vgi.log" "$V" render --method voxel_ao --set radius=$R --spp 16 --size $S -o "$OUT/vao.exr" --quiet
  echo "| voxel_ao (voxel rays) | $(metrics "$OUT/vao.exr" "$OUT/refao.exr") |"
  for s in "cones=3" "cones=5" "cones=8" "cones=8 step=1" "cones=8 anisotropic=false" "cones=8 face_weights=abs" \
    "cones=8 plane_guard=false" "cones=8 overlap=1.3" "cones=8 jitter=false" "cones=8 voxels=256" \
    "cones=5 voxels=256" "cones=8 voxelizer=hybrid"; do
    sa_run "$OUT/vgi.log" "$V" render --method vct_ao $(sets "$s") --spp 1 --size $S -o "$OUT/ao.exr" --quiet
    echo "| vct_ao $s | $(metrics "$OUT/ao.exr" "$OUT/refao.exr") |"
  done
fi
if has 3; then
  reference builtin:cornell "$OUT/ref" 512
  echo "| grid | image relMSE | indirect relMSE | indirect rel. MAE | indirect energy | volume MiB | passes of one frame (ms) |"
  echo "|---|---|---|---|---|---|---|"
  for n in 128 256 512; do
    sa_run "$OUT/vgi.log" "$V" render --method vct --set voxels=$n --spp 4 --size $S -o "$OUT/g$n.exr" --aov indirect --quiet
    mib=$(python3 -c "import json; print('%.0f' % (json.load(open('$OUT/g$n.json'))['extra']['volume']['bytes'] / 2**20))")
    img=$("$V" diff "$OUT/g$n.exr" "$OUT/ref.exr" --json | python3 -c "import json,sys; print('%.4f' % json.load(sys.stdin)['relmse'])")
    echo "| $n³ | $img | $(metrics "$OUT/g$n.indirect.exr" "$OUT/ref.indirect.exr") | $mib | $(passes "$OUT/g$n.json") |"
  done
fi
if has 4; then
  echo "| scene | setting | image relMSE | indirect relMSE | indirect rel. MAE | indirect energy | ms / frame (4 spp) |"
  echo "|---|---|---|---|---|---|---|"
  for sc in cornell-glossy sibenik; do
    spp=512
    reference scenes/$sc.json "$OUT/ref_$sc" $spp
    for s in "voxels=128" "voxels=256" "voxels=128 skip_empty=false" "voxels=128 specular=false" \
      "voxels=128 anisotropic=false"; do
      sa_run "$OUT/vgi.log" "$V" render --scene scenes/$sc.json --method vct $(sets "$s") --spp 4 --size $S -o "$OUT/s.exr" --aov indirect \
        --quiet
      ms=$(python3 -c "import json; t=json.load(open('$OUT/s.json'))['timings_ms']; print('%.0f (cones_full %.0f)' % (sum(t.values()), t.get('cones_full', 0)))")
      img=$("$V" diff "$OUT/s.exr" "$OUT/ref_$sc.exr" --json | python3 -c "import json,sys; print('%.4f' % json.load(sys.stdin)['relmse'])")
      echo "| $sc | $s | $img | $(metrics "$OUT/s.indirect.exr" "$OUT/ref_$sc.indirect.exr") | $ms |"
      [ "$s" = "voxels=128" ] && cp "$OUT/s.exr" "$OUT/skip_$sc.exr"
      [ "$s" = "voxels=128 skip_empty=false" ] && echo "|  | skipping's image change (skip vs no skip) | $("$V" diff "$OUT/skip_$sc.exr" "$OUT/s.exr" --json | python3 -c "import json,sys; d=json.load(sys.stdin); print('relMSE %.5f, rel. MAE %.4f' % (d['relmse'], d['rel_mae']))") | | | | |"
    done
  done
fi
if has 5; then
  echo "| leak-rooms setting | dark room indirect (exact 0) | lit room indirect (exact $( [ -f "$OUT/leak_ref.json" ] || sa_run "$OUT/vgi.log" "$V" render --scene scenes/leak-rooms-lit.json --method reference --set integrator=path --set maxdepth=2 --spp 64 --size 128x128 -o "$OUT/leak_ref.exr" --aov indirect --quiet; mean "$OUT/leak_ref.indirect.exr")) | leaked share |"
  echo "|---|---|---|---|"
  for s in "voxels=128" "voxels=256" "anisotropic=false" "face_weights=squared" "plane_guard=false"; do
    sa_run "$OUT/vgi.log" "$V" render --scene scenes/leak-rooms.json --method vct $(sets "$s") --spp 1 --size 128x128 -o "$OUT/dark.exr" \
      --aov indirect --quiet
    sa_run "$OUT/vgi.log" "$V" render --scene scenes/leak-rooms-lit.json --method vct $(sets "$s") --spp 1 --size 128x128 -o "$OUT/lit.exr" \
      --aov indirect --quiet
    d=$(mean "$OUT/dark.indirect.exr"); l=$(mean "$OUT/lit.indirect.exr")
    echo "| $s | $d | $l | $(python3 -c "print('%.3f' % ($d / $l))") |"
  done
fi
