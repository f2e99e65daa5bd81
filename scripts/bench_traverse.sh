#!/usr/bin/env bash
# Reproduces the traversal tables of docs/BENCHMARKS.md: every tracer on the
# near-field ray population (1M surface-sampled cosine rays, seed 1, start
# offset 1 voxel diagonal) of the Cornell box and Sibenik at 128³, 256³, 512³,
# for rays of 0.1 × the scene diagonal and unbounded rays; CPU on all cores,
# GLSL on the GL device at 256³. Usage: scripts/bench_traverse.sh [out-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/script_args.sh
[ $# -le 1 ] || sa_usage "[out-dir]"
out=${1:-out/bench_traverse}
sa_vgi vgi build/apps/vgi
sa_out out-dir "$out"
for s in builtin:cornell scenes/sibenik.json; do
  name=$(basename "${s#builtin:}" .json)
  for n in 128 256 512; do
    for d in 0.1 inf; do
      gl=--no-gl
      [ "$n" = 256 ] && gl=
      build/apps/vgi bench traverse --scene "$s" --voxels $n --max-dist $d --rays 1000000 --repeat 3 $gl \
        --stats "$out/${name}_${n}_${d}.json"
    done
  done
done
python3 - "$out" <<'PY'
import json, sys, glob, os
print("| scene | grid | max-dist | tracer | CPU Mrays/s | GL Mrays/s | mean steps | hit rate | agree dda | agree embree hit | dist err mean / p95 (voxels) |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for f in sorted(glob.glob(os.path.join(sys.argv[1], "*.json"))):
    d = json.load(open(f))
    for t in ["hierarchical", "dda", "march", "embree"]:
        j = d["tracers"][t]
        gl = "%.2f" % j["gl_mrays_per_s"] if "gl_mrays_per_s" in j else "-"
        if "gl_equals_cpu" in j and not j["gl_equals_cpu"]: gl += " (≠ CPU!)"
        print("| %s | %d³ | %s | %s | %.2f | %s | %.1f | %.3f | %.5f | %.4f | %.2f / %.2f |" % (
            os.path.basename(d["scene"]).replace(".json", ""), d["resolution"][0], d["max_dist"], t,
            j["mrays_per_s"], gl, j["mean_steps"], j["hit_rate"], j["agree_dda"], j["agree_embree_hit"],
            j["dist_err_mean_voxels"], j["dist_err_p95_voxels"]))
PY
