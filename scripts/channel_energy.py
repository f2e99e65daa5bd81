#!/usr/bin/env python3
"""The same integral on both sides: each lighting method against its exact counterpart (same GL
device), per channel, as the energy ratio method / counterpart (the mean of the RGB ratios).

  channel_energy.py --vgi VGI OUT [--scenes scenes/dragon.json,scenes/bunny.json] [--spp 16]
                    [--ref-spp 256] [--size 96x96]

Runs `vgi compare` per (scene, method) into OUT/<scene>_<method>/ and prints a markdown table with the
counterpart's parameters and note (docs/BENCHMARKS.md "The same integral on both sides").
"""
import json
import os

import script_args as sa

METHODS = ["direct", "nearfield", "voxelpath", "vpl", "avg", "vct"]


def main():
    ap = sa.ArgumentParser(description=__doc__, formatter_class=sa.argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--vgi", required=True)
    ap.add_argument("--scenes", default="scenes/dragon.json,scenes/bunny.json")
    ap.add_argument("--methods", default=",".join(METHODS))
    ap.add_argument("--spp", default="16")
    ap.add_argument("--ref-spp", default="256")
    ap.add_argument("--size", default="96x96")
    ap.add_argument("out")
    a = ap.parse_args()
    sa.vgi_binary("--vgi", a.vgi)
    for scene in a.scenes.split(","):
        if not scene.startswith("builtin:") and not os.path.isfile(scene):
            sa.fail("--scenes", a.scenes, f"'{scene}' is not a file")
    if not [m for m in a.methods.split(",") if m]:
        sa.fail("--methods", a.methods, "is empty")
    sa.positive_int("--spp", a.spp)
    sa.positive_int("--ref-spp", a.ref_spp)
    sa.size("--size", a.size)
    sa.out_folder("OUT", a.out)
    rows = []
    for scene in a.scenes.split(","):
        for m in a.methods.split(","):
            stem = os.path.join(a.out, f"{os.path.splitext(os.path.basename(scene))[0]}_{m}", "c")
            os.makedirs(os.path.dirname(stem), exist_ok=True)
            cmd = [a.vgi, "compare", "--scene", scene, "--method", m, "--spp", a.spp, "--ref-spp", a.ref_spp,
                   "--size", a.size, "-o", stem + ".exr"]
            sa.run_vgi(cmd, log=stem + ".log")  # a failure names vgi's reason (an unknown method, …)
            s = json.load(open(stem + ".json"))
            # A channel's energy without a value ("undefined" against a black reference) stays so.
            ratio = {}
            for ch, e in s["error"].items():
                rgb = [sa.number(x) for x in e.get("energy_rgb", [])]
                ratio[ch] = sum(rgb) / 3.0 if len(rgb) == 3 and None not in rgb else "undefined"
            rows.append((os.path.basename(scene), m, " ".join(s["exact"]["set"]), ratio, s["exact"].get("note", "")))
    print(f"| scene | method | counterpart (reference_gl) | image | direct | indirect |\n|---|---|---|---|---|---|")
    for scene, m, cp, r, note in rows:
        cell = lambda ch: sa.fmt(r.get(ch), ".3f", missing="–")
        print(f"| {scene} | {m} | {cp} | {cell('image')} | {cell('direct')} | {cell('indirect')} |")
    return 0


if __name__ == "__main__":
    sa.run_main(main)
