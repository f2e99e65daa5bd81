#!/usr/bin/env bash
# Reproduces the near-field accuracy table of docs/BENCHMARKS.md: the
# `nearfield` module against its exact counterpart (`reference --set
# integrator=nearfield`, same radius), on the Cornell box and Sibenik at
# 64x64x128, 128³ and 256³, with each approximation measured on its own:
#   R    exact reference (Embree)                                   REF_SPP samples
#   R2   the same with another seed: the reference's own noise floor
#   RV   reference with voxel visibility (exact voxelization, hierarchical
#        tracer, VGI's start offset of one diagonal), exact shading at the hit
#   NF   nearfield at full resolution, no interleaving, no blur, 64 frames ×
#        16 rays: converged, so NF − RV is RSM back-projection + shadow maps
#   NQ   nearfield as shipped (½ resolution, 4×4 interleaving, blur,
#        upsampling), 64 frames: NQ − NF is reduced resolution + upsampling
# Usage: scripts/bench_nearfield.sh [out-dir] [size] [ref-spp]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/bench_nearfield}
size=${2:-256x256}
spp=${3:-1024}
mkdir -p "$out"
vgi=${VGI:-build/apps/vgi}
for s in builtin:cornell scenes/sibenik.json; do
  name=$(basename "${s#builtin:}" .json)
  common=(--scene "$s" --size "$size" --quiet)
  $vgi render "${common[@]}" --method reference --set integrator=nearfield --spp "$spp" --aov indirect \
    -o "$out/${name}_R.exr"
  $vgi render "${common[@]}" --method reference --set integrator=nearfield --spp "$spp" --seed 2 --aov indirect \
    -o "$out/${name}_R2.exr"
  for n in 64x64x128 128 256; do
    $vgi render "${common[@]}" --method reference --set integrator=nearfield --set visibility=voxels \
      --set voxels=$n --spp "$spp" --aov indirect -o "$out/${name}_${n}_RV.exr"
    $vgi render "${common[@]}" --method nearfield --set voxels=$n --set resolution=1 --set interleave=1 \
      --set blur=false --spp 64 --aov indirect -o "$out/${name}_${n}_NF.exr"
    $vgi render "${common[@]}" --method nearfield --set voxels=$n --spp 64 --aov indirect \
      -o "$out/${name}_${n}_NQ.exr"
  done
done
python3 - "$out" "$vgi" <<'PY'
import json, subprocess, sys, os
out, vgi = sys.argv[1], sys.argv[2]
def diff(a, b):
    r = subprocess.run([vgi, "diff", "--json", os.path.join(out, a), os.path.join(out, b)],
                       check=True, capture_output=True, text=True)
    return json.loads(r.stdout)
print("| scene | grid | relMSE NF vs R | relMSE NQ vs R | indirect rel. MAE: NF vs R (total) | RV vs R (voxel visibility) | NF vs RV (RSM + shadow maps) | NQ vs NF (reduced res + blur + upsampling) | NQ vs R |")
print("|---|---|---|---|---|---|---|---|---|")
for name in ["cornell", "sibenik"]:
    if not os.path.exists(os.path.join(out, name + "_R.exr")): continue
    noise = diff(name + "_R2.indirect.exr", name + "_R.indirect.exr")["rel_mae"]
    print("| %s | reference noise (R2 vs R) | | | %.4f | | | | |" % (name, noise))
    for n in ["64x64x128", "128", "256"]:
        p = "%s_%s_" % (name, n)
        c = lambda a, b: diff(a, b)
        row = [c(p + "NF.exr", name + "_R.exr")["relmse"], c(p + "NQ.exr", name + "_R.exr")["relmse"],
               c(p + "NF.indirect.exr", name + "_R.indirect.exr")["rel_mae"],
               c(p + "RV.indirect.exr", name + "_R.indirect.exr")["rel_mae"],
               c(p + "NF.indirect.exr", p + "RV.indirect.exr")["rel_mae"],
               c(p + "NQ.indirect.exr", p + "NF.indirect.exr")["rel_mae"],
               c(p + "NQ.indirect.exr", name + "_R.indirect.exr")["rel_mae"]]
        print("| %s | %s | %.5f | %.5f | %.4f | %.4f | %.4f | %.4f | %.4f |" % ((name, n) + tuple(row)))
PY
