#!/usr/bin/env bash
# Reproduces the atlas rows of docs/BENCHMARKS.md: per scene and grid, the atlases
# the automatic rule builds (uncached): charts, LSCM charts, largest resolution,
# utilization (chart area / atlas area, area-weighted over meshes), max stretch,
# triangles without texels, and the CPU build time. Usage: scripts/bench_atlas.sh [out-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/script_args.sh
[ $# -le 1 ] || sa_usage "[out-dir]"
out=${1:-out/bench_atlas}
sa_vgi vgi build/apps/vgi
sa_out out-dir "$out"
echo "| scene | grid | meshes | triangles | charts (LSCM) | largest atlas | utilization | max stretch | triangles without texels | sampled by neighbours | build ms |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for s in ../shared/scenes/stanford-bunny/bun_zipper.ply ../shared/scenes/stanford-dragon/dragon_vrip_res2.ply scenes/sibenik.json; do
  [ -f "$s" ] || continue
  for n in 128 256; do
    sa_run "$out/a.log" build/apps/vgi voxelize --scene "$s" --voxels $n --voxelizer atlas --no-cache --stats "$out/a.json"
    python3 - "$out/a.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
a = d["atlases"]
texels = sum(x["resolution"] ** 2 for x in a)
used = sum(x["utilization"] * x["resolution"] ** 2 for x in a)
print("| %s | %s | %d | %d | %d (%d) | %d | %.3f | %.3f | %d | %d | %.0f |" % (
    d["scene"].split("/")[-1], "x".join(map(str, d["resolution"])), len(a), sum(x["triangles"] for x in a),
    sum(x["charts"] for x in a), sum(x["lscm_charts"] for x in a), d["atlas_resolution"], used / texels,
    max(x["max_stretch"] for x in a), d["triangles_without_texels"], d["triangles_sampled_by_neighbours"],
    sum(x["ms"] for x in a)))
PY
  done
done
