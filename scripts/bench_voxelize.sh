#!/usr/bin/env bash
# Reproduces the voxelization rows of docs/BENCHMARKS.md: each voxelizer against
# the exact one (recall, precision), points and time, per scene and resolution.
# Usage: scripts/bench_voxelize.sh [out-dir]   (scenes from ../shared/scenes are skipped when absent)
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/script_args.sh
[ $# -le 1 ] || sa_usage "[out-dir]"
out=${1:-out/bench_voxelize}
vgi=build/apps/vgi
sa_vgi vgi "$vgi"
sa_out out-dir "$out"
scenes=(builtin:cornell)
[ -f ../shared/scenes/stanford-bunny/bun_zipper.ply ] && scenes+=(../shared/scenes/stanford-bunny/bun_zipper.ply)
[ -f ../shared/scenes/sibenik/sibenik.obj ] && scenes+=(scenes/sibenik.json)
row() { python3 - "$1" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
t = d["timings_ms"]
pts = d["points"] if d["points"] is not None else "-"
atl = d["atlas_resolution"] if d["atlas_resolution"] is not None else "-"
passes = ", ".join("%s %.1f" % (k, v) for k, v in t.items())
print("| %s | %s | %s | %.5f | %.5f | %.5f | %s | %s | %s |" % (d["scene"].split("/")[-1], "x".join(map(str, d["resolution"])),
      d["voxelizer"] + (" tpv=%g fp=%g" % (d["texels_per_voxel"], d["atlas_footprint_texels"]) if "texels_per_voxel" in d else ""),
      d["recall"], d["recall_interior"], d["precision"], pts, atl, passes))
PY
}
echo "| scene | grid | voxelizer | recall | recall (interior) | precision | points | atlas (largest) | ms per pass |"
echo "|---|---|---|---|---|---|---|---|---|"
for s in "${scenes[@]}"; do
  for n in 128 256; do
    for v in exact slicemap conservative; do
      $vgi voxelize --scene "$s" --voxels $n --voxelizer $v --stats "$out/s.json" > /dev/null && row "$out/s.json"
    done
    # (texels per voxel, footprint in texels): the default (2√2, 1), sparser atlases with
    # footprints, and the paper's single points at growing densities
    for cfg in "1 1" "2 1" "2.8284271 1" "2.8284271 0" "4 0" "8 0"; do
      set -- $cfg
      # build (or fetch) the atlas once, then time a run that reads it from the cache;
      # a run that does not fit (atlas too large) prints its error and the table goes on
      if $vgi voxelize --scene "$s" --voxels $n --voxelizer atlas --texels-per-voxel $1 --atlas-footprint $2 --stats "$out/s.json" > /dev/null; then
        $vgi voxelize --scene "$s" --voxels $n --voxelizer atlas --texels-per-voxel $1 --atlas-footprint $2 --stats "$out/s.json" > /dev/null && row "$out/s.json"
      fi
    done
  done
done
