#!/usr/bin/env bash
# Every GPU figure of the project in one command (issue "Beyond one machine"): run it on a GPU
# node from the bundle (scripts/bundle.sh) or a build, and it writes OUT/gpu_bench.json and
# OUT/gpu_bench.md:
#   voxelizers   each GL voxelizer on Sibenik and the dragon at 128³, 256³ and 512³ (pass times,
#                recall / precision against the exact voxelizer)
#   traverse     `vgi bench traverse` rows (GLSL Mrays/s per tracer, GLSL = C++, and the loads per ray
#                the C++ build counts) at 0.01 … ∞ × the diagonal: Sibenik 256³ (10⁷ rays), Sibenik
#                512³ and the Cornell box 256³ (2·10⁶ rays)
#   methods      every GL method's per-pass time per sample at 1920×1080 and 1024×768 on the Cornell
#                box and Sibenik at its defaults, and the papers' settings (VGI: nearfield at ¼
#                resolution, 1024×768; voxelpath 64 spp with two bounces; SSDO: ssdo at 1600×1200), set-up passes apart, and the
#                bytes each resource reports (light maps, grid, pyramid, value textures, cone volume,
#                BVH) beside what the process measurably uses (peak resident memory; on NVIDIA the
#                driver's used dedicated memory, GL_NVX_gpu_memory_info)
#   svo          vct's dense cone volume against the sparse voxel octree (volume=svo) at 1024×768 on
#                Sibenik, 256³–1024³ (dense to 512³): build / inject / filter / cone passes, bytes
#   equal error  the same-device experiments (scenes/experiments/same-device-ao.json and
#                same-device-gi.json): each method against reference_gl on the same GPU, the
#                equal-error time ratio, twice into one fresh set-up cache (cold: every voxelization
#                paid; warm: the cached grids read)
#   parity       the driver parity set (scripts/driver_parity.py: every GL method and GPU-code choice,
#                every voxelizer's grid, every tracer's hits) on this GPU against the llvmpipe images
#                the bundle carries (share/vgi/parity-llvmpipe, or --parity-ref DIR): "same image" or
#                the list of differences, in OUT/parity.json and gpu_bench.md
# --quick runs the same code at tiny sizes on the Cornell box only (the suite runs it on llvmpipe, so
# the script never rots). Scenes from ../shared/scenes (or $VGI_SCENES) are used where present.
# The NVIDIA EGL device path needs glvnd to find the driver's vendor file; where
# /usr/share/glvnd/egl_vendor.d has none, the script looks for one and exports
# __EGL_VENDOR_LIBRARY_FILENAMES (and says so).
# Usage: scripts/gpu_bench.sh [--quick] [--vgi PATH] [--parity-ref DIR] OUT
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/.." && pwd)
. "$here/script_args.sh"
quick=0
vgi=""
out=""
parity_ref=""
while [ $# -gt 0 ]; do
  case $1 in
    --quick) quick=1 ;;
    --vgi|--parity-ref) [ $# -ge 2 ] || sa_usage "[--quick] [--vgi PATH] [--parity-ref DIR] OUT   ($1 needs a value)" ;;&
    --vgi) vgi=$2; shift ;;
    --parity-ref) parity_ref=$2; shift ;;
    -*) echo "gpu_bench: unknown option '$1' (usage: gpu_bench.sh [--quick] [--vgi PATH] OUT)" >&2; exit 2 ;;
    *) out=$1 ;;
  esac
  shift
done
[ -n "$out" ] || { echo "usage: gpu_bench.sh [--quick] [--vgi PATH] OUT" >&2; exit 2; }
if [ -z "$vgi" ]; then
  for c in "$repo/bin/vgi" "$repo/build/apps/vgi" "$(command -v vgi || true)"; do
    [ -n "$c" ] && [ -x "$c" ] && { vgi=$c; break; }
  done
fi
[ -n "$vgi" ] || { echo "gpu_bench: no vgi binary found (give --vgi PATH)" >&2; exit 2; }
sa_vgi --vgi "$vgi"
# A VGI_SCENES that is not a folder would leave every scene's rows out, each with a note that it is absent.
if [ -n "${VGI_SCENES+set}" ] && [ ! -d "$VGI_SCENES" ]; then
  sa_fail VGI_SCENES "$VGI_SCENES" "is not a folder (the test scenes' folder, ../shared/scenes by default)"
fi
[ -z "$parity_ref" ] || [ -d "$parity_ref" ] || [ ! -e "$parity_ref" ] ||
  sa_fail --parity-ref "$parity_ref" "exists and is not a folder"
sa_out OUT "$out"
mkdir -p "$out/raw"
log=$out/gpu_bench.log
: > "$log"
note() { echo "gpu_bench: $*" | tee -a "$log" >&2; }

# The NVIDIA driver's EGL vendor file, where glvnd's default folder lacks one.
if [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ] && ! ls /usr/share/glvnd/egl_vendor.d/*nvidia* > /dev/null 2>&1; then
  for f in /etc/glvnd/egl_vendor.d/10_nvidia.json /usr/local/share/glvnd/egl_vendor.d/10_nvidia.json \
           /usr/lib/x86_64-linux-gnu/nvidia/10_nvidia.json /usr/share/nvidia/10_nvidia.json; do
    if [ -f "$f" ]; then
      export __EGL_VENDOR_LIBRARY_FILENAMES=$f
      note "EGL vendor file: $f (exported as __EGL_VENDOR_LIBRARY_FILENAMES)"
      break
    fi
  done
fi

scenes_dir=${VGI_SCENES:-$repo/../shared/scenes}
scene() {  # scene NAME → its path, or nothing (and a note) when absent
  case $1 in
    cornell) echo builtin:cornell ;;
    sibenik) [ -f "$scenes_dir/sibenik/sibenik.obj" ] && echo "$repo/scenes/sibenik.json" || note "Sibenik absent: its rows are left out" ;;
    dragon) [ -d "$scenes_dir/stanford-dragon" ] && echo "$repo/scenes/dragon.json" || note "the dragon absent: its rows are left out" ;;
  esac
}

if [ $quick -eq 1 ]; then
  vox_scenes=(cornell); vox_res=(128); trav_runs=("cornell 128 20000"); trav_dist=0.1,inf
  sizes=(64x48); method_scenes=(cornell); spp=2; paper_spp=2; equal_error=(smoke)
  svo_scenes=(cornell); svo_res=(128); svo_dense_max=128; svo_size=64x48
else
  vox_scenes=(sibenik dragon); vox_res=(128 256 512)
  trav_runs=("sibenik 256 10000000" "sibenik 512 2000000" "cornell 256 2000000"); trav_dist=0.01,0.03,0.1,0.3,1,inf
  sizes=(1920x1080 1024x768); method_scenes=(cornell sibenik); spp=16; paper_spp=64
  equal_error=(same-device-ao same-device-gi)
  svo_scenes=(sibenik); svo_res=(256 512 1024); svo_dense_max=512; svo_size=1024x768
fi
run() {  # run NAME ARGS… : vgi ARGS, its output in raw/NAME.log; a failure is noted, not fatal
  local name=$1
  shift
  if ! (cd "$repo" && "$vgi" "$@") > "$out/raw/$name.log" 2>&1; then
    # vgi's reason; else a sanitizer's lines (a report, or the checker's own crash at exit)
    local why
    why=$(grep 'vgi: error:' "$out/raw/$name.log" | tail -1 || true)
    [ -n "$why" ] || why=$(grep -E 'ERROR: [A-Za-z]+Sanitizer|runtime error:|Tracer caught signal|Sanitizer has encountered' \
      "$out/raw/$name.log" | head -3 | tr '\n' ' ' || true)
    note "FAILED: vgi $*: $why (raw/$name.log)"
    return 1
  fi
}
start=$(date +%s)

note "voxelizers"
for s in "${vox_scenes[@]}"; do
  path=$(scene "$s")
  [ -n "$path" ] || continue
  for r in "${vox_res[@]}"; do
    for v in atlas conservative hybrid slicemap; do
      run "vox_${s}_${r}_$v" voxelize --scene "$path" --voxels "$r" --voxelizer "$v" --stats "$out/raw/vox_${s}_${r}_$v.json" || true
    done
  done
done

note "traverse"
for t in "${trav_runs[@]}"; do
  read -r s r n <<< "$t"
  path=$(scene "$s")
  [ -n "$path" ] || continue
  run "traverse_${s}_$r" bench traverse --scene "$path" --voxels "$r" --rays "$n" --repeat 1 --max-dist "$trav_dist" \
    --tracers hierarchical,dda,bvh,bricks --json --stats "$out/raw/traverse_${s}_$r.json" || true
done

note "methods"
# The registry's methods (its error message lists them), but the CPU one (reference: Embree, not a GPU figure).
methods=$("$vgi" render --help-module '?' 2>&1 | sed -n 's/.*(known: \(.*\))$/\1/p' | tr -d ',' |
  tr ' ' '\n' | grep -vx reference | tr '\n' ' ' || true)
[ -n "$methods" ] || { note "cannot list the methods (vgi render --help-module)"; exit 1; }
for s in "${method_scenes[@]}"; do
  path=$(scene "$s")
  [ -n "$path" ] || continue
  for size in "${sizes[@]}"; do
    for m in $methods; do
      run "method_${s}_${size}_$m" render --scene "$path" --method "$m" --size "$size" --spp "$spp" --quiet \
        -o "$out/raw/method_${s}_${size}_$m.exr" || true
    done
  done
  # The papers' settings: VGI's near field at 1/4 resolution and its 64-sample, two-bounce path tracing.
  psize=1024x768
  [ $quick -eq 1 ] && psize=${sizes[0]}
  run "paper_${s}_nearfield" render --scene "$path" --method nearfield --set resolution=0.25 --size "$psize" \
    --spp "$spp" --quiet -o "$out/raw/paper_${s}_nearfield.exr" || true
  run "paper_${s}_voxelpath" render --scene "$path" --method voxelpath --set maxdepth=3 --size "$psize" \
    --spp "$paper_spp" --quiet -o "$out/raw/paper_${s}_voxelpath.exr" || true
  # SSDO's own figure (Ritschel et al. 2009: 20 fps at 1600×1200, 537 k polygons, on 2009 hardware).
  ssize=1600x1200
  [ $quick -eq 1 ] && ssize=${sizes[0]}
  run "paper_${s}_ssdo" render --scene "$path" --method ssdo --size "$ssize" --spp "$spp" --quiet \
    -o "$out/raw/paper_${s}_ssdo.exr" || true
done

note "svo"
for s in "${svo_scenes[@]}"; do
  path=$(scene "$s")
  [ -n "$path" ] || continue
  for r in "${svo_res[@]}"; do
    for v in dense svo; do
      [ "$v" = dense ] && [ "$r" -gt "$svo_dense_max" ] && continue
      run "svo_${s}_${r}_$v" render --scene "$path" --method vct --set volume=$v --set voxels=$r --size "$svo_size" \
        --spp "$spp" --quiet -o "$out/raw/svo_${s}_${r}_$v.exr" || true
    done
  done
done

note "equal error on one device (${equal_error[*]}), cold then warm"
# One fresh set-up cache for both passes: the first pays every voxelization, the second reads the grids.
rm -rf "$out/raw/setup_cache"
for pass in cold warm; do
  for e in "${equal_error[@]}"; do
    VGI_CACHE_DIR=$out/raw/setup_cache run "equal_error_${e}_$pass" sweep "scenes/experiments/$e.json" \
      -o "$out/raw/sweep_${e}_$pass" || true
  done
done

note "parity"
# Against the llvmpipe images the bundle carries; --quick (the suite, on llvmpipe itself) renders two of
# the set on llvmpipe as the reference, so the section's code runs without a bundle.
[ -n "$parity_ref" ] || parity_ref=$(cd "$(dirname "$vgi")/.." && pwd)/share/vgi/parity-llvmpipe
only=()
if [ $quick -eq 1 ]; then
  only=(--only direct,vpl)
  parity_ref=$out/raw/parity_llvmpipe
  python3 "$here/driver_parity.py" render --vgi "$vgi" --gl egl "${only[@]}" "$parity_ref" >> "$log" 2>&1 ||
    note "FAILED: the llvmpipe parity renders"
fi
if [ -f "$parity_ref/manifest.json" ]; then
  python3 "$here/driver_parity.py" render --vgi "$vgi" --gl auto "${only[@]}" "$out/raw/parity" >> "$log" 2>&1 ||
    note "FAILED: the parity renders on this device"
  if python3 "$here/driver_parity.py" compare --vgi "$vgi" --json "$out/parity.json" "$parity_ref" "$out/raw/parity" \
      > "$out/raw/parity.log" 2>&1; then
    note "parity: same image as llvmpipe ($(tail -1 "$out/raw/parity.log"))"
  else
    note "parity: DIFFERENCES from llvmpipe (raw/parity.log):"
    tail -n 40 "$out/raw/parity.log" | tee -a "$log" >&2
  fi
else
  note "no llvmpipe parity images at $parity_ref (give --parity-ref DIR): parity left out"
fi

python3 - "$out" "$vgi" "$(( $(date +%s) - start ))" "$quick" <<'PY'
import glob, json, os, sys
out, vgi, seconds, quick = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4] == "1"
raw = os.path.join(out, "raw")
def load(p):
    try:
        return json.load(open(p))
    except Exception:
        return None
report = {"vgi": vgi, "quick": quick, "seconds": seconds, "voxelizers": [], "traverse": [], "methods": [],
          "equal_error": [], "parity": load(os.path.join(out, "parity.json"))}
md = []
renderer = None
for p in sorted(glob.glob(os.path.join(raw, "vox_*.json"))):
    s = load(p)
    if not s: continue
    renderer = renderer or s.get("gl_renderer")
    report["voxelizers"].append({k: s.get(k) for k in ("scene", "voxelizer", "resolution", "total_ms", "timings_ms",
                                                         "recall", "precision", "voxels_set", "gl_renderer")})
for p in sorted(glob.glob(os.path.join(raw, "traverse_*.json"))):
    t = load(p) or {}
    grid = os.path.basename(p)[len("traverse_"):-len(".json")]
    for length in t.get("lengths", []):
        for name, r in sorted(length["tracers"].items()):
            if "gl_mrays_per_s" in r or "counts" in r:
                loads = r.get("counts", {}).get("fetches", {})
                report["traverse"].append({"grid": grid, "tracer": name, "max_dist": length["max_dist"],
                                           "rays": length["rays"], "gl_mrays_per_s": r.get("gl_mrays_per_s"),
                                           "gl_equals_cpu": r.get("gl_equals_cpu"),
                                           "agree_embree_hit": r.get("agree_embree_hit"),
                                           "loads_mean": loads.get("mean"), "loads_p99": loads.get("p99")})
def bytes_of(extra, prefix=""):
    found = {}
    if isinstance(extra, dict):
        for k, v in extra.items():
            if k == "bytes" and isinstance(v, (int, float)): found[prefix.rstrip(".")] = v
            else: found.update(bytes_of(v, prefix + k + "."))
    return found
for p in sorted(glob.glob(os.path.join(raw, "method_*.json")) + glob.glob(os.path.join(raw, "paper_*.json")) +
               glob.glob(os.path.join(raw, "svo_*.json"))):
    s = load(p)
    if not s or "timings_ms" not in s: continue
    renderer = renderer or s.get("gl_renderer")
    n = max(1, s.get("spp_completed", 1))
    sample = set(s.get("sample_passes", []))
    per_sample = {k: v / n for k, v in s["timings_ms"].items() if k in sample}
    setup = {k: v for k, v in s["timings_ms"].items() if k not in sample}
    report["methods"].append({"run": os.path.basename(p)[:-5], "method": s["method"], "scene": s["scene"],
                              "size": f'{s["width"]}x{s["height"]}', "spp": n, "params": s.get("params"),
                              "ms_per_sample": sum(per_sample.values()), "per_sample_ms": per_sample,
                              "setup_ms": setup, "resource_bytes": bytes_of(s.get("extra", {})),
                              "measured_memory": s.get("memory", {}),
                              "gl_renderer": s.get("gl_renderer")})
for p in sorted(glob.glob(os.path.join(raw, "sweep_*", "results.json"))):
    run = os.path.basename(os.path.dirname(p))[len("sweep_"):]
    for r in (load(p) or {}).get("rows", []):
        for ch, m in r.items():
            if isinstance(m, dict) and "equal_error_time_ratio" in m:
                report["equal_error"].append({"run": run, "scene": r["scene"], "method": r["method"],
                                              "label": r["label"], "spp": r["spp"], "channel": ch,
                                              "relmse": m["relmse"], "time_ms": r["time_ms"],
                                              "setup_ms": r.get("setup_ms"), "ratio": m["equal_error_time_ratio"],
                                              "extrapolated": m.get("equal_error_extrapolated")})
report["gl_renderer"] = renderer
json.dump(report, open(os.path.join(out, "gpu_bench.json"), "w"), indent=1)
md.append(f"GL_RENDERER: {renderer}; vgi: {vgi}; {seconds} s{' (--quick)' if quick else ''}\n")
md.append("| voxelizer | scene | resolution | ms | recall | precision |\n|---|---|---|---|---|---|")
for v in report["voxelizers"]:
    md.append(f'| {v["voxelizer"]} | {v["scene"]} | {"x".join(map(str, v["resolution"] or []))} | '
              f'{v["total_ms"]:.1f} | {v["recall"]:.4f} | {v["precision"]:.4f} |')
md.append("\n| grid | tracer | max dist | rays | GLSL Mrays/s | GLSL = C++ | loads per ray (mean / p99) |"
          "\n|---|---|---|---|---|---|---|")
def num(v, f):
    return "-" if v is None else format(v, f)
for r in report["traverse"]:
    md.append(f'| {r["grid"]} | {r["tracer"]} | {r["max_dist"] if isinstance(r["max_dist"], str) else format(r["max_dist"], ".3g")} '
              f'| {r["rays"]} | {num(r["gl_mrays_per_s"], ".1f")} | {"-" if r["gl_equals_cpu"] is None else r["gl_equals_cpu"]} '
              f'| {num(r["loads_mean"], ".1f")} / {num(r["loads_p99"], "")} |')
md.append("\n| run | method | size | ms / sample | per-sample passes (ms) | set-up ms | resource MiB | measured MiB |"
          "\n|---|---|---|---|---|---|---|---|")
for m in report["methods"]:
    passes = ", ".join(f"{k} {v:.2f}" for k, v in sorted(m["per_sample_ms"].items(), key=lambda x: -x[1]))
    mib = ", ".join(f"{k} {v / 2**20:.1f}" for k, v in m["resource_bytes"].items())
    mem = m["measured_memory"]
    measured = f'peak RSS {mem.get("peak_rss_bytes", 0) / 2**20:.0f}'
    if "gpu_used_bytes" in mem: measured += f', GPU used {mem["gpu_used_bytes"] / 2**20:.0f}'
    md.append(f'| {m["run"]} | {m["method"]} | {m["size"]} | {m["ms_per_sample"]:.2f} | {passes} | '
              f'{sum(m["setup_ms"].values()):.1f} | {mib} | {measured} |')
md.append("\n| run | scene | method | spp | channel | relMSE | ms | set-up ms | equal-error time ratio (exact / method) |"
          "\n|---|---|---|---|---|---|---|---|---|")
for r in report["equal_error"]:
    md.append(f'| {r["run"]} | {r["scene"]} | {r["label"]} | {r["spp"]} | {r["channel"]} | {r["relmse"]:.4f} | '
              f'{r["time_ms"]:.0f} | {num(r["setup_ms"], ".0f")} | '
              f'{r["ratio"]:.2f}{" (extrapolated)" if r["extrapolated"] else ""} |')
par = report["parity"]
if par:
    md.append(f'\nParity against {par["a"]["renderer"]} (rel. MAE <= {par["tolerance"]:g}): '
              + ("same image" if not par["differences"] else f'{len(par["differences"])} difference(s)'))
    md.append("\n| render | rel. MAE | llvmpipe ms/spp | this device ms/spp |\n|---|---|---|---|")
    for r in par["rows"]:
        if "rel_mae" in r:
            md.append(f'| {r["render"]} | {r["rel_mae"]:.2g} | {r["ms_per_sample_a"]:.1f} | {r["ms_per_sample_b"]:.1f} |')
    for d in par["differences"]:
        md.append(f"- {d}")
open(os.path.join(out, "gpu_bench.md"), "w").write("\n".join(md) + "\n")
print(f"gpu_bench: wrote {out}/gpu_bench.json and gpu_bench.md ({len(report['voxelizers'])} voxelizer, "
      f"{len(report['traverse'])} tracer, {len(report['methods'])} method rows; {seconds} s)")
PY
