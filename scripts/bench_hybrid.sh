#!/bin/bash
# The hybrid voxelizer (Rauwendaal & Bailey 2013; Basgier 2015 §3.4) against
# conservative, atlas and exact (docs/BENCHMARKS.md, "Voxel cone tracing"):
# recall / precision against the exact voxelizer and the pass time (min of 3
# runs, GL; the atlas: atlas_render + insert), per scene and resolution.
# Usage: scripts/bench_hybrid.sh
set -euo pipefail
. "$(dirname "$0")/script_args.sh"
[ $# = 0 ] || sa_usage "   (no arguments; VGI=path/to/vgi)"
V=${VGI:-build/apps/vgi}
sa_vgi VGI "$V"
T=$(mktemp)
L=$(mktemp)
echo "| scene | grid | voxelizer | voxels | recall | precision | pass ms (min of 3) | triangle-parallel / all |"
echo "|---|---|---|---|---|---|---|---|"
for scene in builtin:cornell scenes/bunny.json scenes/dragon.json scenes/sibenik.json; do
  for n in 256 512; do
    for v in conservative "hybrid 1" "hybrid 4" "hybrid 16" atlas; do
      set -- $v
      extra=()
      [ $# -gt 1 ] && extra=(--hybrid-cutoff "$2")
      best=""
      for i in 1 2 3; do
        sa_run "$L" "$V" voxelize --scene "$scene" --voxels $n --voxelizer $1 "${extra[@]}" --stats "$T"
        ms=$(python3 -c "import json; t=json.load(open('$T'))['timings_ms']; \
print(sum(v for k, v in t.items() if k not in ('upload', 'readback', 'atlas_setup', 'atlas_cache')))")
        best=$(python3 -c "print(min(float(x) for x in '$best $ms'.split()))")
      done
      python3 -c "import json; d=json.load(open('$T')); \
tp = '%d / %d' % (d['triangles_parallel'], d['triangles_parallel'] + d['fragment_parallel']) if 'triangles_parallel' in d else ''; \
print('| %s | %d³ | %s | %d | %.5f | %.5f | %.1f | %s |' % ('$scene'.split('/')[-1], $n, '$v', d['voxels_set'], d['recall'], d['precision'], $best, tp))"
    done
  done
done
rm -f "$T" "$L"
