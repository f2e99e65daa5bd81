#!/usr/bin/env python3
"""One image on every OpenGL driver: renders the parity set with one driver and compares two drivers.

  driver_parity.py render --vgi VGI --gl BACKEND OUT  the parity set with one driver into OUT
                         [--only NAME,…]              (only these renders, no voxelizer or tracer rows)
                         [--size WxH] [--spp N]       (another size or sample count: the driver table of
                                                      docs/BENCHMARKS.md is --size 128x128 --spp 16)
  driver_parity.py compare A B [--json F] [--markdown] two such folders: exit 0 when equal, 1 with the list
                                                      (--markdown: each pass's ms per sample on both)
  driver_parity.py run --vgi VGI OUT                  render with llvmpipe (--gl egl) and zink (--gl zink)
                                                      into OUT/llvmpipe and OUT/zink, then compare them

The parity set is every GL method at its defaults and every parameter choice that changes GPU code —
the tracers, the voxelizers, `volume`, `radiance`, `visibility`, the exact GL integrators, `--accumulate
plain` — on the built-in Cornell box and on a scene this script writes (a textured quad, a triangle
that moves between two frames, an environment map; spot, point and directional lights: every GPU input
path), at 32×32 pixels and two samples; every voxelizer's grid (`vgi voxelize`'s `grid_digest`: integers, so
equal) and every tracer's GLSL hits (`vgi bench traverse`: GLSL equals the C++ tracer bit for bit, so
equal across drivers, hit rates and step counts too).

Images are equal when `vgi diff`'s rel. MAE is at most 1e-6 (float rounding of a different compiler).
Declared nondeterminism: the sparse voxel octree allocates tiles with an atomic counter, so its bricks'
places differ between runs and its images by ~1e-7 (docs/ARCHITECTURE.md) — inside the tolerance.
Each folder keeps every render's stats JSON; `compare` prints per-method time per sample on both.
"""
import argparse
import concurrent.futures
import json
import os
import struct
import subprocess
import sys
import zlib

import script_args as sa

TOLERANCE = 1e-6
SIZE = "32x32"
SPP = "2"
GRID = "voxels=32x32x128"

# (name, scene key, vgi render arguments). "cornell" is builtin:cornell, "parity" the written scene.
RENDERS = [
    ("direct", "cornell", ["--method", "direct"]),
    ("direct_parity", "parity", ["--method", "direct"]),
    ("direct_plain", "cornell", ["--method", "direct", "--accumulate", "plain"]),
    ("nearfield", "cornell", ["--method", "nearfield", "--set", GRID]),
    ("nearfield_dda", "cornell", ["--method", "nearfield", "--set", GRID, "--set", "tracer=dda"]),
    ("nearfield_march", "cornell", ["--method", "nearfield", "--set", GRID, "--set", "tracer=march"]),
    ("nearfield_bvh", "cornell", ["--method", "nearfield", "--set", GRID, "--set", "tracer=bvh"]),
    ("nearfield_parity", "parity", ["--method", "nearfield", "--set", GRID, "--frames", "2", "--time-step", "1"]),
    ("ssdo", "cornell", ["--method", "ssdo"]),
    ("ssdo_patch", "cornell", ["--method", "ssdo", "--set", "estimator=patch"]),
    ("ssdo_parity", "parity", ["--method", "ssdo", "--frames", "2", "--time-step", "1"]),
    ("ddgi", "cornell", ["--method", "ddgi", "--set", GRID, "--set", "probes=4", "--set", "rays=32"]),
    ("ddgi_bvh", "cornell", ["--method", "ddgi", "--set", GRID, "--set", "probes=4", "--set", "rays=32",
                             "--set", "tracer=bvh"]),
    ("ddgi_relocate", "cornell", ["--method", "ddgi", "--set", GRID, "--set", "probes=4", "--set", "rays=32",
                                  "--set", "relocate=true"]),
    ("ddgi_parity", "parity", ["--method", "ddgi", "--set", GRID, "--set", "probes=4", "--set", "rays=32",
                               "--frames", "2", "--time-step", "1"]),
    ("voxel_ao", "cornell", ["--method", "voxel_ao", "--set", GRID]),
    ("voxel_ao_parity", "parity", ["--method", "voxel_ao", "--set", GRID]),
    ("voxelpath", "cornell", ["--method", "voxelpath", "--set", GRID]),
    ("voxelpath_centre", "cornell", ["--method", "voxelpath", "--set", GRID, "--set", "hitpoint=centre",
                                     "--set", "backprojection=entry"]),
    ("voxelpath_plane", "cornell", ["--method", "voxelpath", "--set", GRID, "--set", "hitpoint=plane"]),
    ("voxelpath_parity", "parity", ["--method", "voxelpath", "--set", GRID, "--frames", "2", "--time-step", "1"]),
    ("vpl", "cornell", ["--method", "vpl", "--set", GRID]),
    ("vpl_parity", "parity", ["--method", "vpl", "--set", GRID]),
    ("vpl_none", "cornell", ["--method", "vpl", "--set", GRID, "--set", "visibility=none"]),
    ("avg", "cornell", ["--method", "avg"]),
    ("avg_parity", "parity", ["--method", "avg"]),
    ("avg_paraboloid", "cornell", ["--method", "avg", "--set", "shadow_map=paraboloid"]),
    ("avg_none", "cornell", ["--method", "avg", "--set", "visibility=none"]),
    ("vct", "cornell", ["--method", "vct", "--set", GRID]),
    ("vct_parity", "parity", ["--method", "vct", "--set", GRID, "--frames", "2", "--time-step", "1"]),
    # Past its last keyframe the triangle stands; its second frame injects only its cells and its
    # shadow's (the range the same: the region pass, the cleared region, the per-cell maxima's reduction).
    ("vct_parity_region", "parity",
     ["--method", "vct", "--set", GRID, "--time", "1", "--frames", "2", "--time-step", "0.5"]),
    ("vct_svo", "cornell", ["--method", "vct", "--set", GRID, "--set", "volume=svo"]),
    # The injection's triangle-parallel path (the geometry shader's), for every triangle of up to 512 cells.
    ("vct_inject_small", "parity", ["--method", "vct", "--set", GRID, "--set", "inject_small=512"]),
    ("vct_texels", "cornell", ["--method", "vct", "--set", GRID, "--set", "radiance=texels"]),
    ("vct_atlas", "cornell", ["--method", "vct", "--set", GRID, "--set", "radiance=atlas"]),
    ("vct_squared", "cornell", ["--method", "vct", "--set", GRID, "--set", "face_weights=squared"]),
    ("vct_leak_study", "cornell", ["--method", "vct", "--set", GRID, "--set", "directional=level1", "--set",
                                    "blur_visibility=true", "--set", "fixup=true", "--set", "max_level=3"]),
    ("vct_directional_none", "cornell", ["--method", "vct", "--set", GRID, "--set", "directional=none"]),
    ("vct_ao", "cornell", ["--method", "vct_ao", "--set", GRID]),
    ("vct_ao_svo", "cornell", ["--method", "vct_ao", "--set", GRID, "--set", "volume=svo"]),
    ("voxels", "cornell", ["--method", "voxels", "--set", GRID]),
    ("voxels_dda", "cornell", ["--method", "voxels", "--set", GRID, "--set", "tracer=dda"]),
    ("voxels_march", "cornell", ["--method", "voxels", "--set", GRID, "--set", "tracer=march"]),
    ("voxels_parity", "parity", ["--method", "voxels", "--set", GRID]),
    ("reference_gl_path", "cornell", ["--method", "reference_gl"]),
    ("reference_gl_parity", "parity", ["--method", "reference_gl"]),
    ("reference_gl_nearfield", "cornell", ["--method", "reference_gl", "--set", "integrator=nearfield"]),
    ("reference_gl_ao", "cornell", ["--method", "reference_gl", "--set", "integrator=ao"]),
    ("reference_gl_direct", "cornell", ["--method", "reference_gl", "--set", "integrator=direct"]),
    ("reference_gl_light", "cornell", ["--method", "reference_gl", "--set", "emitter_sampling=light"]),
]
VOXELIZERS = ["atlas", "slicemap", "conservative", "hybrid", "exact"]
TRAVERSE = ["--voxels", "64x64x128", "--rays", "20000", "--max-dist", "0.1,inf", "--repeat", "1", "--json"]


def png(path, w, h, pixel):
    """An 8-bit RGB PNG from pixel(x, y) -> (r, g, b)."""
    rows = b"".join(b"\0" + bytes(c for x in range(w) for c in pixel(x, y)) for y in range(h))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def write_scene(folder):
    """The Cornell box with a textured quad, a moving triangle, an environment map, a spot, a point light
    and a sun through the open side."""
    os.makedirs(folder, exist_ok=True)
    png(os.path.join(folder, "checker.png"), 8, 8,
        lambda x, y: (230, 200, 40) if (x + y) % 2 else (40, 90, 220))
    png(os.path.join(folder, "sky.png"), 16, 8, lambda x, y: (60 + 10 * x, 120, 255 - 25 * y))
    with open(os.path.join(folder, "quad.obj"), "w") as f:
        f.write("v 0.1 0.02 0.1\nv 0.45 0.02 0.1\nv 0.45 0.3 0.1\nv 0.1 0.3 0.1\n"
                "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 -1\n"
                "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n")
    with open(os.path.join(folder, "triangle.obj"), "w") as f:
        f.write("v 0 0 0\nv 0.15 0 0\nv 0 0.15 0\nf 1 2 3\n")
    scene = {
        "meshes": [
            {"path": "builtin:cornell"},
            {"path": "quad.obj", "material": "checker"},
            {"path": "triangle.obj", "dynamic": True, "transform": {"translate": [0.15, 0.25, 0.2]},
             "keyframes": [{"time": 0, "translate": [0, 0, 0]}, {"time": 1, "translate": [0.15, 0.05, 0]}]},
        ],
        "materials": {"checker": {"albedo": [1, 1, 1], "texture": "checker.png"}},
        "lights": [
            {"type": "spot", "position": [0.278, 0.54, 0.28], "direction": [0, -1, 0], "intensity": [0.2, 0.15, 0.05],
             "cone_deg": 60, "falloff": 1},
            {"type": "point", "position": [0.45, 0.12, 0.15], "intensity": [0.01, 0.02, 0.03]},
            {"type": "directional", "direction": [0.3, -0.5, 1], "irradiance": [0.4, 0.4, 0.35]},
        ],
        "environment": {"map": "sky.png", "scale": 0.5},
    }
    path = os.path.join(folder, "parity.json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    return path


# LeakSanitizer's own failure (its stop-the-world tracer crashing, "Tracer caught signal 11"), not a
# finding: seen once in 90 sanitized renders. Such a render runs once more; a leak report never does.
LSAN_FATAL = "LeakSanitizer has encountered a fatal error"


def run(cmd, log):
    for attempt in range(2):
        with open(log, "w") as f:
            rc = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT).returncode
        if rc == 0 or attempt == 1:
            return rc
        with open(log, errors="replace") as f:
            if LSAN_FATAL not in f.read():
                return rc
    return rc


def render(args):
    check_render_args(args)
    out = os.path.abspath(args.out)
    scenes = {"cornell": "builtin:cornell", "parity": write_scene(os.path.join(out, "scene"))}
    jobs = []
    only = set(args.only.split(",")) if args.only else None
    renders = [r for r in RENDERS if only is None or r[0] in only]
    if only is not None and len(renders) != len(only):
        sa.fail("--only", args.only, f"unknown render(s) {', '.join(sorted(only - {r[0] for r in RENDERS}))} "
                f"(known: {', '.join(r[0] for r in RENDERS)})")
    voxelizers = VOXELIZERS if only is None else []
    for name, scene, extra in renders:
        cmd = [args.vgi, "render", "--gl", args.gl, "--scene", scenes[scene], "--size", args.size, "--spp", args.spp,
               "--seed", "3", "--quiet", "-o", os.path.join(out, name + ".exr")] + extra
        jobs.append((name, cmd))
    for v in voxelizers:
        jobs.append(("voxelize_" + v, [args.vgi, "voxelize", "--gl", args.gl, "--voxels", "128",
                                       "--voxelizer", v, "--stats", os.path.join(out, "voxelize_" + v + ".json")]))
    if only is None:
        jobs.append(("traverse", [args.vgi, "bench", "traverse", "--gl", args.gl, "--stats",
                                  os.path.join(out, "traverse.json")] + TRAVERSE))
    failed = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=int(args.jobs)) as pool:
        codes = pool.map(lambda j: run(j[1], os.path.join(out, j[0] + ".log")), jobs)
        for (name, _), rc in zip(jobs, codes):
            if rc != 0:
                failed.append(name)
                with open(os.path.join(out, name + ".log"), errors="replace") as log:
                    print(f"FAILED {name} (exit {rc}): {sa.vgi_reason(log.read())} (see {out}/{name}.log)")
    with open(os.path.join(out, "manifest.json"), "w") as f:
        json.dump({"gl": args.gl, "renders": [n for n, _, _ in renders], "voxelizers": voxelizers,
                   "failed": failed}, f, indent=1)
    print(f"rendered the parity set with --gl {args.gl} into {out}: {len(jobs) - len(failed)} of {len(jobs)} ran")
    return 1 if failed else 0


def images(folder, name):
    """The EXR files one render wrote: NAME.exr, or NAME_0000.exr … for an animation."""
    single = os.path.join(folder, name + ".exr")
    if os.path.exists(single):
        return [name + ".exr"]
    return sorted(f for f in os.listdir(folder) if f.startswith(name + "_") and f.endswith(".exr")
                  and f[len(name) + 1:-4].isdigit())


def renderer(folder, name):
    try:
        with open(os.path.join(folder, name + ".json")) as f:
            return json.load(f).get("gl_renderer", "?")
    except (OSError, ValueError):
        return "?"


def pass_ms(folder, name):
    """Set-up excluded: each per-sample pass's time over the samples (ms per sample), and the set-up's."""
    with open(os.path.join(folder, name + ".json")) as f:
        s = json.load(f)
    frames = s.get("frames") or [s]
    passes = s.get("sample_passes") or frames[0].get("sample_passes", [])
    timings = s.get("timings_ms", {})
    spp = max(1, int(s.get("spp_completed", s.get("spp", 1)) or 1)) * max(1, len(frames))
    per = {p: float(timings.get(p, 0.0)) / spp for p in passes}
    setup = sum(float(v) for k, v in timings.items() if k not in passes)
    return per, setup


def per_sample_ms(folder, name):
    return sum(pass_ms(folder, name)[0].values())


def check_render_args(args):
    sa.vgi_binary("--vgi", args.vgi)
    if args.gl not in ("auto", "egl", "osmesa", "zink"):
        sa.fail("--gl", args.gl, "expected auto, egl, osmesa or zink")
    sa.positive_int("--jobs", args.jobs)
    sa.size("--size", args.size)
    sa.positive_int("--spp", args.spp)
    sa.out_folder("OUT", args.out)


def read_manifest(arg, folder):
    """A folder `render` wrote: its manifest.json, checked."""
    sa.folder_with(arg, folder, "manifest.json")
    try:
        with open(os.path.join(folder, "manifest.json")) as f:
            m = json.load(f)
        if not isinstance(m.get("renders"), list) or not isinstance(m.get("voxelizers"), list) or not m["renders"]:
            raise ValueError("no renders listed")
    except ValueError as e:
        sa.fail(arg, folder, f"its manifest.json is not one `driver_parity.py render` wrote ({e})")
    return m


def compare(args):
    a, b = args.a, args.b
    sa.vgi_binary("--vgi", args.vgi)
    diffs, rows = [], []
    manifest = read_manifest("A", a)
    read_manifest("B", b)
    for name in manifest["renders"]:
        ia, ib = images(a, name), images(b, name)
        if not ia or ia != ib:
            diffs.append(f"{name}: images differ in number ({len(ia)} against {len(ib)})")
            continue
        worst = 0.0
        for img in ia:
            p = subprocess.run([args.vgi, "diff", os.path.join(a, img), os.path.join(b, img), "--json"],
                               capture_output=True, text=True)
            if p.returncode != 0:
                diffs.append(f"{img}: vgi diff failed: {p.stderr.strip()}")
                worst = float("inf")
                continue
            d = json.loads(p.stdout)
            r = d.get("rel_mae")
            r = float("inf") if not isinstance(r, (int, float)) else float(r)
            worst = max(worst, r)
        if worst > TOLERANCE:
            diffs.append(f"{name}: rel. MAE {worst:.3g} > {TOLERANCE:g}")
        try:
            ta, tb = per_sample_ms(a, name), per_sample_ms(b, name)
        except (OSError, ValueError, KeyError):
            ta = tb = float("nan")
        row = {"render": name, "rel_mae": worst, "ms_per_sample_a": ta, "ms_per_sample_b": tb}
        try:
            (row["passes_a"], row["setup_ms_a"]), (row["passes_b"], row["setup_ms_b"]) = pass_ms(a, name), pass_ms(b, name)
        except (OSError, ValueError, KeyError):
            pass
        rows.append(row)
    for v in manifest["voxelizers"]:
        ga = json.load(open(os.path.join(a, f"voxelize_{v}.json")))
        gb = json.load(open(os.path.join(b, f"voxelize_{v}.json")))
        if ga["grid_digest"] != gb["grid_digest"] or ga["voxels_set"] != gb["voxels_set"]:
            diffs.append(f"voxelizer {v}: grids differ ({ga['voxels_set']} cells, {ga['grid_digest']} against "
                         f"{gb['voxels_set']}, {gb['grid_digest']})")
        rows.append({"render": "voxelize_" + v, "grid_digest": ga["grid_digest"], "equal":
                     ga["grid_digest"] == gb["grid_digest"]})
    has_traverse = os.path.exists(os.path.join(a, "traverse.json"))
    ta = json.load(open(os.path.join(a, "traverse.json"))) if has_traverse else {"lengths": []}
    tb = json.load(open(os.path.join(b, "traverse.json"))) if has_traverse else {"lengths": []}
    for la, lb in zip(ta["lengths"], tb["lengths"]):
        for tracer, ra in la["tracers"].items():
            rb = lb["tracers"].get(tracer, {})
            for side, r in (("A", ra), ("B", rb)):
                if r.get("gl_equals_cpu") is False:
                    diffs.append(f"tracer {tracer} (max_dist {la['max_dist']:g}): GLSL differs from C++ on {side}")
            for key in ("hit_rate", "mean_steps", "agree_dda"):
                if ra.get(key) != rb.get(key):
                    diffs.append(f"tracer {tracer} (max_dist {la['max_dist']:g}): {key} {ra.get(key)} against "
                                 f"{rb.get(key)}")
    name_a = renderer(a, manifest["renders"][0])
    name_b = renderer(b, manifest["renders"][0])
    print(f"A: {a} ({name_a})\nB: {b} ({name_b})")
    print(f"{'render':28} {'rel. MAE':>10} {'A ms/spp':>10} {'B ms/spp':>10}")
    for r in rows:
        if "rel_mae" in r:
            print(f"{r['render']:28} {r['rel_mae']:10.2g} {r['ms_per_sample_a']:10.1f} {r['ms_per_sample_b']:10.1f}")
    if args.markdown:
        print(f"\n| render | pass | A ms/sample | B ms/sample | B / A |\n|---|---|---|---|---|")
        for r in rows:
            if "passes_a" not in r:
                continue
            for p, va in sorted(r["passes_a"].items(), key=lambda x: -x[1]):
                vb = r["passes_b"].get(p, float("nan"))
                print(f"| {r['render']} | {p} | {va:.2f} | {vb:.2f} | {vb / va if va > 0 else float('nan'):.1f} |")
            print(f"| {r['render']} | set-up (once) | {r['setup_ms_a']:.0f} | {r['setup_ms_b']:.0f} | "
                  f"{r['setup_ms_b'] / r['setup_ms_a'] if r['setup_ms_a'] > 0 else float('nan'):.1f} |")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"a": {"folder": a, "renderer": name_a}, "b": {"folder": b, "renderer": name_b},
                       "tolerance": TOLERANCE, "rows": rows, "differences": diffs}, f, indent=1)
    if diffs:
        print(f"{len(diffs)} difference(s) between the drivers:")
        for d in diffs:
            print("  " + d)
        return 1
    print(f"same image on both drivers: {len(manifest['renders'])} renders (rel. MAE <= {TOLERANCE:g}), "
          f"{len(manifest['voxelizers'])} voxelizer grids equal" + (", every tracer's hits equal" if has_traverse else ""))
    return 0


def main():
    ap = sa.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("render")
    r.add_argument("--vgi", required=True)
    r.add_argument("--gl", default="auto")
    r.add_argument("--jobs", default=os.cpu_count() or 1)
    r.add_argument("--only", default="")
    r.add_argument("--size", default=SIZE)
    r.add_argument("--spp", default=SPP)
    r.add_argument("out")
    c = sub.add_parser("compare")
    c.add_argument("--vgi", required=True)
    c.add_argument("--json")
    c.add_argument("--markdown", action="store_true", help="also print every pass's time per sample on both")
    c.add_argument("a")
    c.add_argument("b")
    b = sub.add_parser("run")
    b.add_argument("--vgi", required=True)
    b.add_argument("--jobs", default=os.cpu_count() or 1)
    b.add_argument("out")
    args = ap.parse_args()
    if args.cmd == "render":
        return render(args)
    if args.cmd == "compare":
        return compare(args)
    sa.vgi_binary("--vgi", args.vgi)
    sa.positive_int("--jobs", args.jobs)
    sa.out_folder("OUT", args.out)
    rc = 0
    for gl, folder in (("egl", "llvmpipe"), ("zink", "zink")):
        rc |= render(argparse.Namespace(vgi=args.vgi, gl=gl, jobs=args.jobs, only="", size=SIZE, spp=SPP,
                                        out=os.path.join(args.out, folder)))
    if rc:
        return rc
    return compare(argparse.Namespace(vgi=args.vgi, json=os.path.join(args.out, "parity.json"), markdown=False,
                                      a=os.path.join(args.out, "llvmpipe"), b=os.path.join(args.out, "zink")))


if __name__ == "__main__":
    sa.run_main(main)
