#!/usr/bin/python3
"""The equal-time table with the error split and error bars (docs/BENCHMARKS.md, "What a paper
reports: the error split and error bars") from one run of scenes/experiments/equal-time-split.json
(`vgi sweep scenes/experiments/equal-time-split.json -o DIR`).

Usage: scripts/split_tables.py DIR   (prints Markdown; every number is a field of DIR/results.json)

One row per scene and method: each point's last image (its time budget's), mean ± standard deviation
over the experiment's seeds of the samples reached, the approximation error (the point against its
model-matched counterpart: relMSE with the relative ε — the one the equal-error time ratio is read
with —, the same with the top 0.1 % of the pixels' errors dropped, HDR-FLIP), the total error
(against the full reference) and the model's (the counterpart against the full reference, one value:
both render once), per channel (image, indirect), and the equal-error time ratio against the
counterpart's curve on the same device. Metrics: core/image_metrics.h; the split: experiments/compare.h.
"""
import sys

import script_args as sa


def cell(rows, channel, key, spec=".3g"):
    m, s = sa.mean_sd([sa.number(r.get(channel, {}).get(key)) for r in rows])
    if m is None:
        return ""
    return f"{m:{spec}}" + ("" if s == 0 else f" ± {s:.2g}")


def main(out):
    res = sa.sweep_results("DIR", out, "equal-time-split")
    finals = {}  # (scene, method) -> each seed's last row
    for r in res["rows"]:
        if r.get("role") != "point":
            continue
        key = (r["scene"], r["method"])
        best = finals.setdefault(key, {})
        if r["point"] not in best or r["spp"] > best[r["point"]]["spp"]:
            best[r["point"]] = r
    some = next(iter(res["rows"]))
    print(f"{res['size'][0]}×{res['size'][1]}, {res.get('time_budget_s')} s per point, relMSE with ε = "
          f"({res.get('relative_epsilon')} × mean)², "
          f"{res.get('seeds', 1)} seeds, `{some.get('gl_renderer', '')}`, {some.get('machine', '')}, "
          f"revision {some.get('git_revision', '')}\n")
    chans = [("image", "image"), ("indirect", "indirect")]
    head = ["scene", "method", "samples", "set-up ms"]
    for _, name in chans:
        head += [f"{name} relMSE approx", f"{name} trimmed", f"{name} total", f"{name} model",
                 f"{name} HDR-FLIP approx / model", f"{name} ratio"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for (scene, method), by in sorted(finals.items(), key=lambda kv: (kv[0][0] != "builtin:cornell", kv[0])):
        rows = list(by.values())
        spp, sps = sa.mean_sd([r["spp"] for r in rows])
        setup, _ = sa.mean_sd([r["setup_ms"] for r in rows])
        cells = [scene.split("/")[-1], f"`{method}`", f"{spp:.0f}" + ("" if sps == 0 else f" ± {sps:.1f}"),
                 f"{setup:.0f}"]
        for ch, _ in chans:
            if not any(ch in r for r in rows):
                cells += [""] * 6
                continue
            flip = cell(rows, ch, "flip_hdr", ".3f")
            model_flip = cell(rows, ch, "model_flip_hdr", ".3f")
            cells += [cell(rows, ch, "relmse_relative"), cell(rows, ch, "relmse_relative_trimmed"),
                      cell(rows, ch, "total_relmse_relative"), cell(rows, ch, "model_relmse_relative"),
                      f"{flip} / {model_flip}", cell(rows, ch, "equal_error_time_ratio")]
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print("usage: split_tables.py DIR   (DIR: the output folder of `vgi sweep "
              "scenes/experiments/equal-time-split.json -o DIR`)", file=sys.stderr)
        sys.exit(2)
    sa.run_main(lambda: main(sys.argv[1]))
