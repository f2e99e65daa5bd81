#!/usr/bin/python3
"""The "Artefacts users report" tables of docs/BENCHMARKS.md from one run of
scenes/experiments/artefacts.json (`vgi sweep scenes/experiments/artefacts.json -o DIR`).

Usage: scripts/artefacts_tables.py DIR   (prints Markdown; every number is a field of DIR/results.json)

Tables: the leak through walls and through a closed mesh (indirect, the combined image's in
brackets), the indirect energy against the exact one across grid resolutions, the temporal error of
the two animations (the rotating bunny, the Sibenik walk) with the reference's own noise floor, and
the remedies (the parameters the papers name against leaks and flicker) side by side. Metrics:
core/image_metrics.h.
"""
import json
import os
import sys

import script_args as sa

WALLS = ["0.25", "0.5", "1", "2"]
BUNNY, WALK = "scenes/cornell-bunny.json", "scenes/sibenik-walk.json"
REMEDIES = ["vct isotropic", "vct thin voxels", "vct offset 0.5", "vct full-rate gather",
            "nearfield full-rate gather"]


def grid_of(row):
    p = row["params"]
    if "voxels" in p:
        return f"{p['voxels']}³"
    if "grid" in p:
        return f"grid {p['grid']}"
    return ""


def name_of(row):
    g = grid_of(row)
    return f"`{row['label']}`" + (f" {g}" if g else "")


def fmt(x, digits=4):
    """"—" where there is no such row or metric, "undefined" where vgi wrote one without a value."""
    return sa.fmt(x, f".{digits}f")


def metric(row, channel, key):
    """The metric as vgi wrote it (a number or "undefined"), None where the row or the field is missing."""
    value = row.get(channel, {}) if isinstance(row, dict) else None
    return value.get(key) if isinstance(value, dict) else None


def method_table(order, by, headers, scenes, cell):
    """One row per method setting (the remedies left out), one column per scene: cell(row or None)."""
    print("| method | " + " | ".join(headers) + " |")
    print("|---|" + "---:|" * len(headers))
    for k in order:
        if k[0] in REMEDIES:
            continue
        some = by[k][next(iter(by[k]))]
        print(f"| {name_of(some)} | " + " | ".join(cell(by[k].get(s)) for s in scenes) + " |")
    print()


def main(out):
    res = sa.sweep_results("DIR", out, "artefacts")
    rows = [r for r in res["rows"] if r.get("role") == "point"]
    # One key per method setting, in the experiment's order.
    order, by = [], {}
    for r in rows:
        k = (r["label"], grid_of(r))
        if k not in by:
            by[k] = {}
            order.append(k)
        by[k][r["scene"]] = r
    first = next(iter(by[order[0]].values()))
    print(f"Run: {res['experiment']}, {res['size'][0]}×{res['size'][1]}, {res['spp']} spp per method, "
          f"revision {first['git_revision']}, {first['machine']}, `{first['gl_renderer']}`.\n")

    for family, title in (("leak-walls/wall", "Leak through a wall k voxels thick at 128³ (two rooms)"),
                          ("leak-closed/closed", "Leak into a sealed box, walls k voxels thick at 128³")):
        print(f"**{title}** — indirect leak (combined image's in brackets):\n")
        def leak(r):
            value, img = metric(r, "indirect", "leak"), metric(r, "image", "leak")
            return "—" if value is None and img is None else f"{fmt(value)} ({fmt(img)})"

        method_table(order, by, [f"{w} voxel{'s' if w == '2' else ''}" for w in WALLS],
                     [f"scenes/{family}-{w}v.json" for w in WALLS], leak)

    print("**Indirect energy / exact across grid resolutions** (AO methods: their AO channel is not in "
          "`indirect`; the combined image's energy in brackets):\n")
    scenes = ["scenes/leak-walls/wall-1v.json", "scenes/leak-closed/closed-1v.json", BUNNY, WALK]
    method_table(order, by, [os.path.basename(s)[:-5] for s in scenes], scenes,
                 lambda r: f"{fmt(metric(r, 'indirect', 'energy'), 3)} ({fmt(metric(r, 'image', 'energy'), 3)})")

    print("**Temporal error** (6 frames; indirect: temporal error, the method's change, the exact change):\n")
    print("| method | bunny: temporal error | change | exact change | Sibenik walk: temporal error | change | "
          "exact change | Sibenik indirect rel. MAE |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for k in order:
        rb, rw = by[k].get(BUNNY), by[k].get(WALK)
        some = rb or rw
        if not some:
            continue
        # The AO methods write no indirect channel: their image (the AO) stands in, marked.
        ch = "indirect" if "indirect" in some else "image"
        cells = [fmt(metric(rb, ch, x)) for x in ("temporal_error", "change", "change_reference")]
        cells += [fmt(metric(rw, ch, x)) for x in ("temporal_error", "change", "change_reference")]
        cells.append(fmt(metric(rw, ch, "rel_mae")))
        mark = "" if ch == "indirect" else " (image)"
        print(f"| {name_of(some)}{mark} | " + " | ".join(cells) + " |")
    print()

    print("**Remedies** (128³; indirect):\n")
    print("| setting | wall 0.5 voxel leak | closed 0.5 voxel leak | bunny temporal error | "
          "Sibenik temporal error | Sibenik rel. MAE | Sibenik ms per frame |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for label in ["vct"] + REMEDIES[:4] + ["nearfield", REMEDIES[4]]:
        for k in order:
            if k[0] != label or (grid_of(by[k][next(iter(by[k]))]) not in ("", "128³")):
                continue
            r = by[k]
            w, c = r.get("scenes/leak-walls/wall-0.5v.json"), r.get("scenes/leak-closed/closed-0.5v.json")
            rw = r.get(WALK)
            print(f"| {name_of(r[next(iter(r))])} | {fmt(metric(w, 'indirect', 'leak'))} | "
                  f"{fmt(metric(c, 'indirect', 'leak'))} | {fmt(metric(r.get(BUNNY), 'indirect', 'temporal_error'))} | "
                  f"{fmt(metric(rw, 'indirect', 'temporal_error'))} | {fmt(metric(rw, 'indirect', 'rel_mae'))} | "
                  f"{fmt(rw.get('time_ms') if rw else None, 0)} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print("usage: artefacts_tables.py DIR   (DIR: the output folder of `vgi sweep scenes/experiments/artefacts.json -o DIR`)", file=sys.stderr)
        sys.exit(2)
    sa.run_main(lambda: main(sys.argv[1]))
