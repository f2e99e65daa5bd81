#!/usr/bin/env python3
"""One Markdown row of an error-split table (scripts/bench_*_split.sh,
bench_vpl.sh, bench_avg.sh): image relMSE, then the indirect AOV's relMSE,
rel. MAE and energy (green) of render A against render B (stems: A.exr,
A.indirect.exr), and optionally the per-sample time of the timed passes
named after --passes, from A.json.
   split_row.py VGI LABEL A B [--passes P1,P2,...]"""
import json
import subprocess
import sys

vgi, label, a, b = sys.argv[1:5]
passes = sys.argv[6].split(",") if len(sys.argv) > 6 and sys.argv[5] == "--passes" else []


def diff(x, y):
    out = subprocess.run([vgi, "diff", x, y, "--json"], capture_output=True, text=True, check=True).stdout
    return json.loads(out)


i, m = diff(a + ".indirect.exr", b + ".indirect.exr"), diff(a + ".exr", b + ".exr")
cells = [label, f"{m['relmse']:.4f}", f"{i['relmse']:.4f}", f"{i['rel_mae']:.3f}", f"{i['energy_rgb'][1]:.3f}"]
if passes:
    s = json.load(open(a + ".json"))
    t, c = s["timings_ms"], s["pass_calls"]
    cells.append(f"{sum(t.get(p, 0) / max(1, c.get(p, 1)) for p in passes):.0f}")
print("| " + " | ".join(cells) + " |")
