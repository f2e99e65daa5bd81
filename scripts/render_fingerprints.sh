#!/usr/bin/env bash
# Renders a fixed set of method configurations at small sizes and prints one
# SHA-1 of the pixels of each written image (EXR, AOVs included; `iinfo
# --hash` of openimageio-tools: the files' headers carry the time): run it before and after a
# refactor that must not change any image, and diff the two lists.
#   bash scripts/render_fingerprints.sh OUT_DIR [VGI]   (> fingerprints.txt)
# The scenes of ../shared/scenes are used where present (the rows that need
# them are left out otherwise, and say so on stderr).
set -euo pipefail
. "$(dirname "$0")/script_args.sh"
[ $# -ge 1 ] && [ $# -le 2 ] || sa_usage "OUT_DIR [VGI]"
out=$1
vgi=${2:-build/apps/vgi}
root="$(cd "$(dirname "$0")/.." && pwd)"
sa_vgi VGI "$vgi"
command -v iinfo > /dev/null || { echo "$sa_prog: iinfo is missing: install openimageio-tools (scripts/setup.sh does)" >&2; exit 2; }
sa_out OUT_DIR "$out"
n=0
row() {  # row SCENE METHOD [ARGS...]
  local scene=$1 method=$2
  shift 2
  case $scene in builtin:*) ;; *)
    if [ ! -e "$scene" ]; then echo "render_fingerprints: $scene absent, row left out" >&2; return; fi ;;
  esac
  n=$((n + 1))
  local o="$out/r$(printf %02d $n)_$method.exr"
  sa_run "$out/r$(printf %02d $n).log" "$vgi" render --scene "$scene" --method "$method" --size 64x48 --spp 2 \
    --quiet -o "$o" "$@"
  for f in "${o%.exr}"*.exr; do
    echo "$(iinfo --hash "$f" | sed -n 's/.*SHA-1: //p' | cut -c1-16)  $(basename "$f")  ${scene#"$root"/} $method $*"
  done
}
C=builtin:cornell
O=$root/scenes/cornell-original.json
B=$root/scenes/cornell-bunny.json
G=$root/scenes/cornell-glossy.json
row $C direct
row $O direct
row $C nearfield --aov indirect
row $C nearfield --aov indirect --set blur_visibility=false --set fixup=false
row $O nearfield --aov indirect
row $B nearfield --frames 2
row $C nearfield --set tracer=dda
row $C voxel_ao
row $C voxelpath --aov indirect
row $G voxelpath
row $O voxelpath
row $C vpl
row $C vpl --set visibility=exact
row $O vpl --set visibility=exact
row $C vpl --set bounces=1
row $C avg
row $C avg --set visibility=exact
row $C avg --set vpl_shadow_triangles=0
row $C vct --aov indirect,ao,specular
row $C vct --set radiance=atlas
row $C vct --set anisotropic=false
row $O vct
row $B vct --frames 2
row $C vct_ao
row $B vct_ao --frames 2
row $C voxels
row $C reference --set integrator=path
row $O reference --set integrator=path
row $C reference --set integrator=nearfield
row $C reference --set integrator=nearfield --set visibility=voxels
row $C reference --set integrator=ao
row $C reference --set integrator=direct
row $root/scenes/leak-rooms-lit.json vct
row $C reference_gl --aov direct,indirect
row $O reference_gl --set integrator=path
row $O reference_gl --set integrator=path --set emitter_sampling=light
row $C reference_gl --set integrator=nearfield
row $C reference_gl --set integrator=ao
row $C reference_gl --set integrator=direct
row $C vct --aov indirect --set directional=none
row $C vct --aov indirect --set directional=level1 --set blur_visibility=true --set fixup=true --set max_level=3
