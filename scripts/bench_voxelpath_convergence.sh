#!/usr/bin/env bash
# The equal-error time ratio of voxelpath (VGI §5.2's "2.2 s vs 28 minutes"
# claim, measured with the voxel method's bias): error curves over
# --checkpoints of voxelpath and of its exact counterpart (reference
# integrator=path, same maxdepth/rr_depth) against a high-spp reference, both
# timed on this machine (wall time from the start of the render, set-up
# included). Prints the two curves and the ratio (docs/BENCHMARKS.md).
#   scripts/bench_voxelpath_convergence.sh OUT [SCENE] [SIZE] [VP_SPP] [REF_SPP] [TRUTH_SPP] [VOXELS]
set -euo pipefail
OUT=${1:?usage: bench_voxelpath_convergence.sh OUT [SCENE] [SIZE] [VP_SPP] [REF_SPP] [TRUTH_SPP] [VOXELS]}
SCENE=${2:-builtin:cornell}
SIZE=${3:-256x256}
VP=${4:-512}
REF=${5:-1024}
TRUTH=${6:-4096}
VOX=${7:-256}
VGI=${VGI:-build/apps/vgi}
mkdir -p "$OUT"
list() {  # 1,2,4,… below $1
  local n=1 s=""
  while [ $n -lt "$1" ]; do s="$s${s:+,}$n"; n=$((n * 2)); done
  echo "$s"
}
"$VGI" render --scene "$SCENE" --method reference --set integrator=path --set maxdepth=3 --size "$SIZE" \
  --spp "$TRUTH" --seed 7 --quiet -o "$OUT/truth.exr" > /dev/null
"$VGI" render --scene "$SCENE" --method voxelpath --set voxels="$VOX" --size "$SIZE" --spp "$VP" \
  --checkpoints "$(list "$VP")" --quiet -o "$OUT/vp.exr" > /dev/null
"$VGI" render --scene "$SCENE" --method reference --set integrator=path --set maxdepth=3 --size "$SIZE" \
  --spp "$REF" --checkpoints "$(list "$REF")" --quiet -o "$OUT/ref.exr" > /dev/null
python3 - "$OUT" "$VGI" "$VP" "$REF" <<'PY'
import json, subprocess, sys, math
out, vgi, vp, ref = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
def curve(stem, last):
    rows, n = [], 1
    while True:
        spp = min(n, last)
        base = f"{out}/{stem}" if spp == last else f"{out}/{stem}.spp{spp:05d}"
        d = json.loads(subprocess.run([vgi, "diff", base + ".exr", f"{out}/truth.exr", "--json"],
                                      capture_output=True, text=True, check=True).stdout)
        rows.append((spp, json.load(open(base + ".json"))["wall_ms"] / 1000.0, d["relmse"]))
        if spp == last: return rows
        n *= 2
v, r = curve("vp", vp), curve("ref", ref)
print("| spp | voxelpath s | voxelpath relMSE | reference s | reference relMSE |")
print("|---|---|---|---|---|")
for i in range(max(len(v), len(r))):
    a = v[i] if i < len(v) else None
    b = r[i] if i < len(r) else None
    spp = (a or b)[0]
    print(f"| {spp} | {a[1]:.1f} | {a[2]:.5f} |" if a else f"| {spp} | | |", end="")
    print(f" {b[1]:.1f} | {b[2]:.5f} |" if b else " | |")
target = v[-1][2]
# voxelpath reaches its converged error at the first checkpoint within 10 % of it.
tv = next(t for _, t, e in v if e <= 1.1 * target)
# The reference's time to that error: log-log interpolation along its curve.
tr = None
for (s0, t0, e0), (s1, t1, e1) in zip(r, r[1:]):
    if e0 >= target >= e1:
        f = (math.log(e0) - math.log(target)) / (math.log(e0) - math.log(e1)) if e0 != e1 else 0.0
        tr = math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
        break
if tr is None and r[0][2] <= target: tr = r[0][1]
print(f"\nvoxelpath converged relMSE {target:.5f} (at {vp} spp), reached in {tv:.1f} s")
if tr is None:
    print(f"reference does not reach it within {ref} spp (its last relMSE {r[-1][2]:.5f})")
else:
    print(f"reference reaches it in {tr:.1f} s: equal-error time ratio {tr / tv:.2f}")
PY
