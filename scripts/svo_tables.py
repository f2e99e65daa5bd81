#!/usr/bin/python3
"""The dense-against-sparse tables of docs/BENCHMARKS.md ("Sparse voxel octree cone tracing") from
one run of scenes/experiments/svo.json (`vgi sweep scenes/experiments/svo.json -o DIR`).

Usage: scripts/svo_tables.py DIR   (prints Markdown; every number is a field of DIR/results.json or of
a point's own stats, DIR/points/<point>/render.json)

Per scene, method and storage at each resolution: the error against the exact counterpart (vct: the
indirect channel's rel. MAE, the storage's only effect; vct_ao: the AO image's), the svo's error over
the dense one's at the same resolution, the volume's bytes (what each storage allocates, its injection
sums included) and the process's peak RSS, and the time per pass (ms per render: the volume's build,
injection, filtering; the cones per sample).
"""
import json
import os
import sys

import script_args as sa

PASSES = {
    "build": ["svo_build"],
    "inject": ["vct_inject_max", "vct_inject"],
    "filter": ["svo_resolve", "svo_filter", "svo_borders", "value_resolve", "value_mips"],
    "cones": ["diffuse_cones", "cones_full", "ao_cones"],
}


def fmt(x, digits=4):
    return sa.fmt(x, f".{digits}f")


def mib(b):
    """Bytes as MiB, or "undefined" / "—" as fmt has it."""
    v = sa.number(b)
    return sa.fmt(b if v is None else v / 2**20, ".1f")


def main(out):
    res = sa.sweep_results("DIR", out, "svo")
    rows = [r for r in res["rows"] if r.get("role") == "point"]
    first = rows[0]
    print(f"Run: {res['experiment']}, {res['size'][0]}×{res['size'][1]}, {res['spp']} spp per point, "
          f"revision {first['git_revision']}, {first['machine']}, `{first['gl_renderer']}`.\n")
    stats = {}
    for r in rows:
        path = os.path.join(out, "points", r["point"], "render.json")
        try:
            with open(path) as f:
                stats[r["point"]] = json.load(f)
        except ValueError as e:
            sa.fail("DIR", out, f"its {path} does not parse ({e})")
        if not isinstance(stats[r["point"]], dict):
            sa.fail("DIR", out, f"its {path} is not a render's stats")
    dense = {}
    for r in rows:
        if r["label"].endswith(" dense"):
            dense[(r["scene"], r["method"], str(r["params"]["voxels"]))] = r
    for scene in dict.fromkeys(r["scene"] for r in rows):
        print(f"**{scene}**\n")
        print("| point | voxels | error | svo / dense | volume MiB | peak RSS MiB | nodes | build ms | "
              "inject ms | filter ms | cones ms/sample | total ms |")
        print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        for r in rows:
            if r["scene"] != scene:
                continue
            s = stats[r["point"]]
            channel = "indirect" if r["method"] == "vct" else "image"
            err = r.get(channel, {}).get("rel_mae")
            v = str(r["params"]["voxels"])
            d = dense.get((scene, r["method"], v))
            ratio = None
            if d is not None and d is not r and sa.number(err) is not None:
                de = sa.number(d.get(channel, {}).get("rel_mae"))
                ratio = sa.number(err) / de if de else None
            vol = (s.get("extra") or {}).get("volume", {})
            t = s.get("timings_ms", {})
            spp = max(sa.number(s.get("spp_completed", s.get("spp", 1))) or 1, 1)
            ms = {k: sum(sa.number(t.get(n, 0.0)) or 0.0 for n in names) for k, names in PASSES.items()}
            print(f"| {r['label']} | {v}³ | {fmt(err)} | {fmt(ratio, 3)} | "
                  f"{mib(vol.get('bytes', 0))} | {mib((s.get('memory') or {}).get('peak_rss_bytes'))} | "
                  f"{vol.get('nodes', '—')} | {ms['build']:.0f} | {ms['inject']:.0f} | {ms['filter']:.0f} | "
                  f"{ms['cones'] / spp:.0f} | {fmt(r.get('time_ms'), 0)} |")
        print()


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print("usage: svo_tables.py DIR   (DIR: the output folder of `vgi sweep scenes/experiments/svo.json -o DIR`)", file=sys.stderr)
        sys.exit(2)
    sa.run_main(lambda: main(sys.argv[1]))
