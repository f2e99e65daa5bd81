#!/usr/bin/python3
"""The before/after tables of "Artefacts users report" (docs/BENCHMARKS.md) from one run of
scenes/experiments/artefacts-remedies.json and, optionally, of artefacts-remedies-avg.json (`avg`
on the same scenes but the Sibenik walk):

  vgi sweep scenes/experiments/artefacts-remedies.json -o DIR
  vgi sweep scenes/experiments/artefacts-remedies-avg.json -o AVG_DIR
  scripts/artefacts_remedies_tables.py DIR [AVG_DIR]   (prints Markdown; every number is a field of
                                                        the results.json files)

Every method twice at 128³ (labels "M before": its remedies off — the wall kit, `directional=none`,
`temporal=false` — and "M after": its defaults), plus the settings the remedies sections name; the
tables: the leak through the open wall and into the sealed box per wall thickness, the temporal error
of the two animations with the static error beside it, the indirect energy, the time per frame.
Metrics: core/image_metrics.h.
"""
import os
import sys

import artefacts_tables as at
import script_args as sa

BUNNY, WALK = at.BUNNY, at.WALK


def rows_by_label(res):
    order, by = [], {}
    for r in res["rows"]:
        if r.get("role") != "point":
            continue
        if r["label"] not in by:
            by[r["label"]] = {}
            order.append(r["label"])
        by[r["label"]][r["scene"]] = r
    return order, by


def channel(r):
    """The AO methods write no indirect channel: their image (the AO) stands in."""
    return "indirect" if r and "indirect" in r else "image"


def main(out, avg):
    res = sa.sweep_results("DIR", out, "artefacts-remedies")
    order, by = rows_by_label(res)
    if avg:
        res_avg = sa.sweep_results("AVG_DIR", avg, "artefacts-remedies-avg")
        o2, b2 = rows_by_label(res_avg)
        exact = order.index("exact, seed 2") if "exact, seed 2" in order else len(order)
        order[exact:exact] = o2
        by.update(b2)
    first = next(iter(by[order[0]].values()))
    print(f"Run: {res['experiment']}, {res['size'][0]}×{res['size'][1]}, {res['spp']} spp per method, "
          f"revision {first['git_revision']}, {first['machine']}, `{first['gl_renderer']}`.\n")

    for family, title in (("leak-walls/wall", "Leak through a wall k voxels thick at 128³ (two rooms)"),
                          ("leak-closed/closed", "Leak into a sealed box, walls k voxels thick at 128³")):
        print(f"**{title}** — indirect leak (the AO methods have no indirect channel: left out):\n")
        print("| setting | " + " | ".join(f"{w} voxel{'s' if w == '2' else ''}" for w in at.WALLS) + " |")
        print("|---|" + "---:|" * len(at.WALLS))
        for label in order:
            cells = []
            for w in at.WALLS:
                r = by[label].get(f"scenes/{family}-{w}v.json")
                cells.append(at.fmt(at.metric(r, "indirect", "leak")) if r and "indirect" in r else "—")
            if any(c != "—" for c in cells):
                print(f"| `{label}` | " + " | ".join(cells) + " |")
        print()

    floor = by.get("exact, seed 2", {}).get(BUNNY)
    floor_te = at.metric(floor, "indirect", "temporal_error")
    print("**Temporal and static error** (6 frames; indirect, the AO methods' image marked; × floor: the "
          "bunny's temporal error over the exact sequence's own with another seed):\n")
    print("| setting | bunny: temporal error | × floor | change (exact) | relMSE | Sibenik walk: temporal "
          "error | change (exact) | relMSE |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for label in order:
        rb, rw = by[label].get(BUNNY), by[label].get(WALK)
        ch = channel(rb or rw)
        te = at.metric(rb, ch, "temporal_error")
        te_value, floor_value = sa.number(te), sa.number(floor_te)
        ratio = at.fmt(te_value / floor_value, 2) if te_value is not None and floor_value else "—"
        mark = "" if ch == "indirect" else " (image)"

        def change(r):
            a, b = at.metric(r, ch, "change"), at.metric(r, ch, "change_reference")
            return "—" if a is None else f"{at.fmt(a)} ({at.fmt(b)})"

        print(f"| `{label}`{mark} | {at.fmt(te)} | {ratio} | {change(rb)} | {at.fmt(at.metric(rb, ch, 'relmse'))} | "
              f"{at.fmt(at.metric(rw, ch, 'temporal_error'))} | {change(rw)} | "
              f"{at.fmt(at.metric(rw, ch, 'relmse'))} |")
    print()

    scenes = ["scenes/leak-walls/wall-1v.json", "scenes/leak-closed/closed-1v.json", BUNNY, WALK]
    # (No time column: an error run, the renders shared the machine; time is `vgi bench motion`'s.)
    print("**Energy / exact** (indirect; the AO methods' image marked):\n")
    print("| setting | " + " | ".join(os.path.basename(s)[:-5] for s in scenes) + " |")
    print("|---|" + "---:|" * len(scenes))
    for label in order:
        some = next(iter(by[label].values()))
        ch = channel(some)
        cells = [at.fmt(at.metric(by[label].get(s), ch, "energy"), 3) for s in scenes]
        mark = "" if ch == "indirect" else " (image)"
        print(f"| `{label}`{mark} | " + " | ".join(cells) + " |")
    print()


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        print("usage: artefacts_remedies_tables.py DIR [AVG_DIR]   (DIR: `vgi sweep "
              "scenes/experiments/artefacts-remedies.json -o DIR`; AVG_DIR: the same of "
              "artefacts-remedies-avg.json)", file=sys.stderr)
        sys.exit(2)
    sa.run_main(lambda: main(sys.argv[1], sys.argv[2] if len(sys.argv) == 3 else None))
