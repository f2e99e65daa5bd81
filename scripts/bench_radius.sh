#!/usr/bin/env bash
# Reproduces the near-field radius table of docs/BENCHMARKS.md: for radii r =
# f × the scene diagonal, the share of the exact one-bounce indirect light
# that the near field captures, and what r costs per frame in `nearfield`.
#   captured(r) = mean(reference nearfield r, indirect AOV) /
#                 (mean(reference path maxdepth=2) − mean(reference direct))
# (per colour channel, then averaged; env=false, so rays leaving r add nothing),
# and the `nearfield` module's indirect pass per frame at that radius (GPU
# timer; default rays, ¼ resolution, 128³), plus its captured share against
# the same exact one-bounce light.
# Usage: scripts/bench_radius.sh [out-dir] [ref-spp]
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/script_args.sh
[ $# -le 2 ] || sa_usage "[out-dir] [ref-spp]   (VGI=path/to/vgi)"
out=${1:-out/bench_radius}
spp=${2:-256}
vgi=${VGI:-build/apps/vgi}
sa_vgi VGI "$vgi"
sa_int ref-spp "$spp"
sa_out out-dir "$out"
fractions="0.05 0.1 0.2 0.3 0.5 1.0"
for s in builtin:cornell scenes/sibenik.json; do
  name=$(basename "${s#builtin:}" .json)
  size=256x256
  [ "$name" = sibenik ] && size=384x256
  common=(--scene "$s" --size "$size" --quiet)
  $vgi render "${common[@]}" --method reference --set integrator=path --set maxdepth=2 --spp "$spp" -o "$out/${name}_path2.exr"
  $vgi render "${common[@]}" --method reference --set integrator=direct --spp "$spp" -o "$out/${name}_direct.exr"
  diag=$($vgi info --json --scene "$s" | python3 -c "import json,sys; print(json.load(sys.stdin)['bounds']['diagonal'])")
  for f in $fractions; do
    r=$(python3 -c "print('%.6g' % ($f * $diag))")
    $vgi render "${common[@]}" --method reference --set integrator=nearfield --set env=false --set radius=$r \
      --spp "$spp" --aov indirect -o "$out/${name}_ref_$f.exr"
    $vgi render "${common[@]}" --method nearfield --set env=false --set radius=$r --spp 16 --aov indirect \
      -o "$out/${name}_nf_$f.exr"
  done
done
python3 - "$out" "$vgi" "$fractions" <<'PY'
import json, subprocess, sys, os
out, vgi, fractions = sys.argv[1], sys.argv[2], sys.argv[3].split()
def means(a, b):
    r = subprocess.run([vgi, "diff", "--json", os.path.join(out, a), os.path.join(out, b)],
                       check=True, capture_output=True, text=True)
    d = json.loads(r.stdout)
    return d["mean_a_rgb"], d["mean_b_rgb"]
print("| scene | r / diagonal | r | captured (exact near field) | captured by `nearfield` | indirect pass ms/frame | frame ms (all passes) |")
print("|---|---|---|---|---|---|---|")
for name in ["cornell", "sibenik"]:
    if not os.path.exists(os.path.join(out, name + "_path2.exr")): continue
    direct, path2 = means(name + "_direct.exr", name + "_path2.exr")
    bounce = [p - d for p, d in zip(path2, direct)]
    for f in fractions:
        ref, _ = means(name + "_ref_%s.indirect.exr" % f, name + "_path2.exr")
        nf, _ = means(name + "_nf_%s.indirect.exr" % f, name + "_path2.exr")
        share = lambda m: sum(x / b for x, b in zip(m, bounce)) / 3
        st = json.load(open(os.path.join(out, name + "_nf_%s.json" % f)))
        t, calls = st["timings_ms"], st["pass_calls"]
        frame = sum(t[p] for p in st["sample_passes"]) / st["spp_completed"]
        print("| %s | %s | %.4g | %.3f | %.3f | %.1f | %.1f |" % (name, f, st["params"]["radius"], share(ref), share(nf),
              t["indirect"] / calls["indirect"], frame))
PY
