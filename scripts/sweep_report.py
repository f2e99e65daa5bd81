#!/usr/bin/python3
"""The plots, Pareto tables and HTML report of a `vgi sweep` output folder.

Usage: sweep_report.py DIR   (vgi sweep runs it after writing DIR/results.json)

Writes into DIR:
  convergence_<scene>.png/.pdf  log-log error (rel. MAE, relMSE with the relative ε and, where the
                                sweep measured it, HDR-FLIP, of the image and of each AOV) against time, one line per point, a marker
                                per checkpoint; the exact counterparts' own curves dashed; a point rendered
                                with several seeds ("seeds") is one line, their mean, in a band of ±1
                                standard deviation
  seeds.md                      with "seeds": per point and sample count the mean ± standard deviation
                                over its seeds of every error metric and of the equal-error time ratio
  passes_<scene>.png/.pdf       per-pass time of each point's final render (one frame)
  pareto.md, pareto.tex         per scene, the points on the error-vs-time Pareto front
                                (Markdown and LaTeX booktabs), with FLIP beside relMSE and each point's equal-error time
                                ratio to its counterpart where the experiment has its curve
  report.html                   the tables, the plots and, per point, its image, the
                                reference, the error map and the FLIP map with an A/B slider and a crop; in an
                                animation experiment ("frames"), per point a strip of its frames
                                above the reference's and the error maps, with its temporal error
Needs Debian's python3-matplotlib (scripts/setup.sh installs it).
"""
import html
import json
import math
import os
import re
import sys

import script_args as sa

plt = None  # matplotlib.pyplot, imported by main() once its argument is checked


def import_pyplot():
    global plt
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as pyplot
    except ImportError as e:
        print(f"{sa.PROG}: error: {e} (install python3-matplotlib, scripts/setup.sh does, and run this with "
              f"Debian's /usr/bin/python3)", file=sys.stderr)
        sys.exit(2)
    plt = pyplot


num = sa.number


def fmt(x, spec):
    return sa.fmt(x, spec, missing="undefined")


def slug(s):
    return re.sub(r"[^A-Za-z0-9]+", "_", s).strip("_") or "scene"


def is_curve(row):
    return row.get("role") == "counterpart"


def render_dir(row):
    return ("curves/" if is_curve(row) else "points/") + row["point"]


def point_name(row):
    params = ", ".join(f"{k}={v}" for k, v in sorted(row["params"].items()))
    return row["label"] + (f" ({params})" if params else "")


def seed_groups(order):
    """The points grouped by name (one group per point rendered with several seeds), in order."""
    groups = {}
    for pid, p in order:
        groups.setdefault((is_curve(p[0]), point_name(p[0])), []).append((pid, p))
    return list(groups.values())


def seed_table(rows, chans, flip_key):
    """seeds.md's lines for one scene: per point and sample count, mean ± sd over the seeds."""
    groups = {}
    for r in rows:
        if not is_curve(r):
            groups.setdefault((point_name(r), r["spp"]), []).append(r)
    metrics = [("rel_mae", "rel. MAE"), ("relmse", "relMSE"), ("relmse_trimmed", "relMSE (top 0.1 % out)")]
    if flip_key:
        metrics.append((flip_key, "HDR-FLIP" if flip_key == "flip_hdr" else "LDR-FLIP"))
    metrics.append(("equal_error_time_ratio", "equal-error time ratio"))
    if any(c in r and "total_relmse" in r[c] for r in rows for c in chans):  # "split"
        metrics += [("total_relmse", "total relMSE"), ("model_relmse", "model relMSE")]
    lines = ["| point | spp | seeds | time ms | " + " | ".join(f"{c} {n}" for c in chans for _, n in metrics) + " |",
             "|" + "---|" * (4 + len(chans) * len(metrics))]
    for (name, spp), g in sorted(groups.items()):
        if len(g) < 2:
            continue
        t, ts = sa.mean_sd([r["time_ms"] for r in g])
        cells = []
        for c in chans:
            for k, _ in metrics:
                m, s = sa.mean_sd([num(r[c].get(k)) if c in r else None for r in g])
                cells.append("" if m is None else f"{m:.4g} ± {s:.2g}")
        lines.append(f"| {name} | {spp} | {len(g)} | {t:.0f} ± {ts:.0f} | " + " | ".join(cells) + " |")
    return lines if len(lines) > 2 else []


def channels_of(rows):
    chans = []
    for r in rows:
        for c in r:
            if isinstance(r[c], dict) and "rel_mae" in r[c] and c not in chans:
                chans.append(c)
    return sorted(chans, key=lambda c: (c != "image", c))


def pareto(rows, channel):
    """Rows not dominated in (time, error): nothing is both faster and more accurate."""
    pts = [r for r in rows if channel in r and num(r[channel].get("rel_mae")) is not None]
    pts.sort(key=lambda r: (r["time_ms"], num(r[channel]["rel_mae"])))
    front, best = [], math.inf
    for r in pts:
        if num(r[channel]["rel_mae"]) < best:
            front.append(r)
            best = num(r[channel]["rel_mae"])
    return front


def flip_metric(rows, chans):
    """The FLIP the rows carry: HDR-FLIP where measured, else LDR-FLIP, else None (a sweep run with
    "flip": "off", or one from before FLIP)."""
    for key in ("flip_hdr", "flip_ldr"):
        if any(num(r[c].get(key)) is not None for r in rows for c in chans if c in r):
            return key
    return None


def main(out):
    res = sa.sweep_results("DIR", out)
    import_pyplot()
    rows = res["rows"]
    scenes = []
    for r in rows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])
    md = [f"# {res['experiment']}: error against time\n"]
    seeds_md = [f"# {res['experiment']}: mean ± standard deviation over {res.get('seeds', 1)} seeds\n"]
    tex = ["% vgi sweep " + res["experiment"] + " (booktabs)"]
    sections = []
    for scene in scenes:
        srows = [r for r in rows if r["scene"] == scene]
        chans = channels_of(srows)
        points = {}
        for r in srows:
            points.setdefault(r["point"], []).append(r)
        for p in points.values():
            p.sort(key=lambda r: r["spp"])
        # Convergence: error vs time, one line per point (the counterparts' own curves dashed).
        metrics = [("rel_mae", "rel. MAE"), ("relmse_relative", f"relMSE (ε {res['relative_epsilon']} × mean)")]
        # FLIP against time where the sweep measured it (core/flip.h: HDR-FLIP of the EXRs).
        flip_key = flip_metric(srows, chans)
        if flip_key:
            metrics.append((flip_key, "HDR-FLIP" if flip_key == "flip_hdr" else "LDR-FLIP"))
        fig, axes = plt.subplots(len(metrics), len(chans), figsize=(5.5 * len(chans), 4.0 * len(metrics)),
                                 squeeze=False)
        # One style per point in every panel (a point missing from a channel keeps its colour elsewhere).
        order = sorted(points.items(), key=lambda kv: (is_curve(kv[1][0]), point_name(kv[1][0])))
        cmap = plt.get_cmap("tab10" if sum(not is_curve(p[0]) for _, p in order) <= 10 else "tab20")
        dashes = [("--", "x"), (":", "+"), ("-.", "1"), ((0, (5, 1, 1, 1)), "2"), ((0, (1, 3)), "3")]
        styles, ncolor, ncurve = {}, 0, 0
        for pid, p in order:
            if is_curve(p[0]):
                ls, mk = dashes[ncurve % len(dashes)]
                shade = 0.45 * (ncurve // len(dashes)) / max(1, len(order) // len(dashes))
                styles[pid] = dict(color=(shade, shade, shade), ls=ls, marker=mk)
                ncurve += 1
            else:
                styles[pid] = dict(color=cmap(ncolor % cmap.N), marker="o")
                ncolor += 1
        handles = {}
        groups = seed_groups(order)
        for mi, (metric, mname) in enumerate(metrics):
            for ax, ch in zip(axes[mi], chans):
                for group in groups:
                    pid, p = group[0]
                    # Per checkpoint: the mean over the group's seeds (one seed: the point itself);
                    # the seeds' last images (a time budget stops each at its own count) as one.
                    by_spp = {}
                    for _, q in group:
                        for r in q:
                            if ch in r and num(r[ch].get(metric)) is not None:
                                last = len(group) > 1 and r is q[-1] and r["spp"] not in res["checkpoints"]
                                by_spp.setdefault(math.inf if last else r["spp"], []).append(r)
                    xs, ys, lo, hi = [], [], [], []
                    for spp in sorted(by_spp):
                        t, _ = sa.mean_sd([r["time_ms"] for r in by_spp[spp]])
                        m, s = sa.mean_sd([num(r[ch][metric]) for r in by_spp[spp]])
                        xs.append(t)
                        ys.append(max(m, 1e-9))
                        lo.append(max(m - s, 1e-9))
                        hi.append(max(m + s, 1e-9))
                    if xs:
                        label = point_name(p[0]) + (f" ({len(group)} seeds, ±1 sd)" if len(group) > 1 else "")
                        (line,) = ax.plot(xs, ys, ms=3, label=label, **styles[pid])
                        if len(group) > 1:
                            ax.fill_between(xs, lo, hi, color=styles[pid]["color"], alpha=0.2, lw=0)
                        handles.setdefault(pid, (line, label))
                ax.set_xscale("log")
                ax.set_yscale("log")
                ax.set_xlabel("time (ms, set-up + samples)")
                ax.set_ylabel(f"{mname} ({ch})")
                ax.set_title(f"{scene}: {ch}")
                ax.grid(True, which="both", alpha=0.3)
        legend = [handles[pid] for pid, p in order if pid in handles]
        ncol = 2 if len(chans) > 1 else 1
        rows_legend = (len(legend) + ncol - 1) // ncol
        fig.legend([h for h, _ in legend], [n for _, n in legend], loc="lower center", ncol=ncol, fontsize=7,
                   frameon=False)
        fig.tight_layout(rect=(0, min(0.5, 0.017 * rows_legend + 0.005), 1, 1))
        conv = f"convergence_{slug(scene)}"
        for ext in ("png", "pdf"):
            fig.savefig(os.path.join(out, f"{conv}.{ext}"), dpi=110)
        plt.close(fig)
        # Per-pass time of each point's final render.
        finals = [max(p, key=lambda r: r["spp"]) for p in points.values()]
        images = [r for r in finals if not is_curve(r)]
        passes = []
        timings = []
        for r in finals:
            t = {}
            path = os.path.join(out, render_dir(r), "render.json")
            try:  # a render killed while writing it, or another run's half-written file: no bar
                with open(path) as f:
                    stats = json.load(f)
                t = stats.get("timings_ms", {}) if isinstance(stats, dict) else {}
            except (OSError, ValueError):
                pass
            if not isinstance(t, dict):
                t = {}
            timings.append(t)
            for k, v in t.items():
                if k not in passes and (num(v) or 0.0) >= 0.5:
                    passes.append(k)
        fig, ax = plt.subplots(figsize=(10, 0.45 * len(finals) + 1.8))
        left = [0.0] * len(finals)
        cmap = plt.get_cmap("tab20")
        for i, k in enumerate(passes):
            vals = [num(t.get(k)) or 0.0 for t in timings]
            ax.barh(range(len(finals)), vals, left=left, color=cmap(i % 20), label=k)
            left = [a + b for a, b in zip(left, vals)]
        ax.set_yticks(range(len(finals)))
        ax.set_yticklabels([point_name(r) for r in finals], fontsize=7)
        ax.set_xlabel("ms (all passes of the final render)")
        ax.set_title(f"{scene}: per-pass time")
        ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.01, 1.0))
        fig.tight_layout()
        bars = f"passes_{slug(scene)}"
        for ext in ("png", "pdf"):
            fig.savefig(os.path.join(out, f"{bars}.{ext}"), dpi=110)
        plt.close(fig)
        # Pareto tables: per reference (the points that estimate the same integral).
        # Each point's final render and every row on its reference's Pareto front (marked).
        listed = []
        for ref in sorted({r["reference"] for r in srows}):
            group = [r for r in srows if r["reference"] == ref]
            front = {id(r) for r in pareto(group, "image")}
            finals_here = {id(r) for r in finals if r["reference"] == ref}
            listed += sorted(((r, id(r) in front) for r in group if id(r) in front or id(r) in finals_here),
                             key=lambda x: x[0]["time_ms"])
        ratio = any("equal_error_time_ratio" in r.get(c, {}) for r in srows for c in chans)
        md.append(f"\n## {scene}: each point's final render and the Pareto front (*: no row is both faster and more accurate in image rel. MAE; per reference)\n")
        if ratio:
            md.append("Equal-error time ratio: the exact counterpart's time to the same relMSE (relative ε) "
                      "over the point's time (> 1: the method is faster; ~ extrapolated at 1/samples).\n")
        cols = []
        flip_name = {"flip_hdr": "HDR-FLIP", "flip_ldr": "LDR-FLIP"}.get(flip_key)
        for c in chans:
            cols += [f"{c} rel. MAE", f"{c} relMSE"] + ([f"{c} {flip_name}"] if flip_key else []) + \
                ([f"{c} equal-error time ratio"] if ratio else [])
        cols = ["Pareto"] + cols
        md.append("| point | spp | time ms | " + " | ".join(cols) + " |")
        md.append("|" + "---|" * (3 + len(cols)))
        tex.append("\\begin{tabular}{l r r c " + "r " * (len(cols) - 1) + "}\n\\toprule")
        tex.append("point & spp & time (ms) & " + " & ".join(x.replace(". ", ".\\ ") for x in cols)
                   + " \\\\\n\\midrule")
        table = []
        for r, on_front in listed:
            cells = ["*" if on_front else ""]
            for c in chans:
                if c in r:
                    cells += [fmt(r[c].get("rel_mae"), ".4f"), fmt(r[c].get("relmse"), ".5f")]
                    if flip_key:
                        cells.append(fmt(r[c].get(flip_key), ".4f"))
                    if ratio:
                        q = r[c].get("equal_error_time_ratio")
                        cells.append("" if q is None else
                                     ("~" if r[c].get("equal_error_extrapolated") else "") + fmt(q, ".3g"))
                else:
                    cells += ["", ""] + ([""] if flip_key else []) + ([""] if ratio else [])
            tcells = [x.replace("~", "$\\sim$").replace("*", "$\\bullet$") for x in cells]
            md.append(f"| {point_name(r)} | {r['spp']} | {r['time_ms']:.0f} | " + " | ".join(cells) + " |")
            name = point_name(r).replace("_", "\\_").replace("&", "\\&").replace("%", "\\%")
            tex.append(f"{name} & {r['spp']} & {r['time_ms']:.0f} & " + " & ".join(tcells) + " \\\\")
            table.append((point_name(r), r["spp"], r["time_ms"], cells))
        tex.append("\\bottomrule\n\\end{tabular}\n")
        sections.append((scene, conv, bars, (cols, table), images))
        seeds_md += [f"\n## {scene}\n"] + seed_table(srows, chans, flip_key) if res.get("seeds", 1) > 1 else []
    with open(os.path.join(out, "pareto.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    with open(os.path.join(out, "pareto.tex"), "w") as f:
        f.write("\n".join(tex) + "\n")
    if res.get("seeds", 1) > 1:
        with open(os.path.join(out, "seeds.md"), "w") as f:
            f.write("\n".join(seeds_md) + "\n")
    write_html(out, res, sections)


SLIDER_JS = """
// After loading: how many images failed (body data-broken), and whether moving the first
// slider moves its image's clip (body data-slider) — what a headless browser test reads.
window.addEventListener('load', function () {
  var broken = 0, imgs = document.images;
  for (var i = 0; i < imgs.length; ++i) if (!imgs[i].complete || imgs[i].naturalWidth === 0) ++broken;
  document.body.dataset.images = imgs.length;
  document.body.dataset.broken = broken;
  var s = document.querySelector("input[type=range]");
  if (s) {
    var top = document.getElementById(s.id.slice(0, -1) + 't'), before = top.style.clipPath;
    s.value = 80;
    s.dispatchEvent(new Event('input'));
    document.body.dataset.slider = top.style.clipPath !== before ? 'moved' : 'stuck';
  }
});
function slide(id, v) {
  document.getElementById(id).style.clipPath = 'inset(0 ' + (100 - v) + '% 0 0)';
}
function pick(id, which, src) {
  document.getElementById(id + which).src = src;
}
"""


def frame_strip(r, frames, step, t0):
    """An animation point's frames (at most 8, evenly spaced) above the reference's and the error
    maps, with its temporal error per channel (core/image_metrics.h)."""
    shown = sorted({round(i * (frames - 1) / max(1, min(frames, 8) - 1)) for i in range(min(frames, 8))})
    temporal = "; ".join(
        f"{html.escape(ch)}: temporal error {fmt(r[ch]['temporal_error'], '.4f')}, "
        f"change {fmt(r[ch].get('change'), '.4f')} (reference {fmt(r[ch].get('change_reference'), '.4f')})"
        for ch in sorted(r, key=lambda c: (c != "image", c)) if isinstance(r[ch], dict) and "temporal_error" in r[ch])
    rows = [("method", f"points/{r['point']}/render_{{:04d}}.png"),
            ("reference", f"references/{r['reference']}/ref_{{:04d}}.png"),
            ("error", f"points/{r['point']}/error_{{:04d}}.png")]
    h = [f"<p>Frames ({temporal}):</p><table class='strip'><tr><th></th>"
         + "".join(f"<th>{f} (t = {t0 + f * step:g})</th>" for f in shown) + "</tr>"]
    for name, pattern in rows:
        h.append(f"<tr><th>{name}</th>" + "".join(
            f"<td><img src='{pattern.format(f)}' alt='{name} frame {f}'></td>" for f in shown) + "</tr>")
    return "".join(h) + "</table>"


def write_html(out, res, sections):
    h = ["<!DOCTYPE html><html><head><meta charset='utf-8'>",
         f"<title>vgi sweep: {html.escape(res['experiment'])}</title>",
         "<style>body{font:14px sans-serif;margin:24px;max-width:1200px}"
         ".plot{max-width:100%}table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:2px 6px;font-size:12px}"
         ".ab{position:relative;display:inline-block;image-rendering:pixelated}"
         ".ab img{display:block;width:384px}.ab .top{position:absolute;left:0;top:0}"
         ".crop{width:192px;height:192px;overflow:hidden;display:inline-block;margin-left:8px}"
         ".crop img{width:768px;margin:-192px 0 0 -192px;image-rendering:pixelated}"
         ".strip img{width:160px;image-rendering:pixelated;display:block}</style>",
         f"<script>{SLIDER_JS}</script></head><body>",
         f"<h1>{html.escape(res['experiment'])}</h1>",
         f"<p>{res['points']} points, {res['size'][0]}×{res['size'][1]}, {res['spp']} spp "
         f"(checkpoints {res['checkpoints']}), relMSE ε {res['epsilon']}, relative ε {res['relative_epsilon']}. "
         "Rows, parameters and every metric: <a href='results.csv'>results.csv</a>, "
         "<a href='results.json'>results.json</a>; tables: <a href='pareto.md'>pareto.md</a>, "
         "<a href='pareto.tex'>pareto.tex</a>.</p>"]
    n = 0
    for scene, conv, bars, pareto_table, finals in sections:
        h.append(f"<h2>{html.escape(scene)}</h2>")
        h.append(f"<img class='plot' src='{conv}.png' alt='convergence'><br>")
        h.append(f"<img class='plot' src='{bars}.png' alt='per-pass time'>")
        cols, table = pareto_table
        h.append("<h3>Each point's final render and the Pareto front (*), image rel. MAE against time, per reference</h3>"
                 "<table><tr><th>point</th>"
                 "<th>spp</th><th>time ms</th>" + "".join(f"<th>{html.escape(c)}</th>" for c in cols) + "</tr>")
        for name, spp, ms, cells in table:
            h.append(f"<tr><td>{html.escape(name)}</td><td>{spp}</td><td>{ms:.0f}</td>"
                     + "".join(f"<td>{html.escape(x)}</td>" for x in cells) + "</tr>")
        h.append("</table><h3>Images</h3><p>Drag the slider: left of it the first image, right of it the "
                 "second; choose either from the method, the reference, the error map (red = too bright, "
                 "blue = too dark) and the FLIP map (magma: black = no visible difference, bright = large). "
                 "Right: a 4× crop of the centre.</p>")
        anim = res.get("animations", {}).get(scene, {})
        frames = anim.get("frames", 1)
        for r in finals:
            n += 1
            pid = f"ab{n}"
            first = "_0000" if frames > 1 else ""
            img = f"points/{r['point']}/render{first}.png"
            ref = f"references/{r['reference']}/ref{first}.png"
            err = f"points/{r['point']}/error.png"
            opts = [("method", img), ("reference", ref), ("error", err)]
            flip = f"points/{r['point']}/flip.png"  # the FLIP map, where the sweep computed FLIP
            if os.path.exists(os.path.join(out, flip)):
                opts.append(("FLIP", flip))
            sel = lambda which, default: (  # noqa: E731
                f"<select onchange=\"pick('{pid}','{which}',this.value)\">"
                + "".join(f"<option value='{src}'{' selected' if name == default else ''}>{name}</option>"
                          for name, src in opts) + "</select>")
            h.append(f"<h4>{html.escape(point_name(r))} — {r['spp']} spp, image rel. MAE "
                     f"{fmt(r['image'].get('rel_mae'), '.4f')}</h4>" if "image" in r else f"<h4>{html.escape(point_name(r))}</h4>")
            h.append(f"<div>{sel('b', 'method')} | {sel('t', 'reference')} "
                     f"<input type='range' min='0' max='100' value='50' id='{pid}s' "
                     f"oninput=\"slide('{pid}t', this.value)\"></div>")
            h.append(f"<div class='ab'><img id='{pid}b' src='{img}' alt='A'>"
                     f"<img id='{pid}t' class='top' src='{ref}' alt='B' style='clip-path:inset(0 50% 0 0)'></div>"
                     f"<div class='crop'><img src='{img}' alt='crop'></div>"
                     f"<div class='crop'><img src='{ref}' alt='crop of the reference'></div>")
            if frames > 1:
                h.append(frame_strip(r, frames, anim["time_step"], anim["time"]))
    h.append("</body></html>")
    with open(os.path.join(out, "report.html"), "w") as f:
        f.write("\n".join(h) + "\n")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print("usage: sweep_report.py DIR   (DIR: the output folder of `vgi sweep EXPERIMENT -o DIR`)", file=sys.stderr)
        sys.exit(2)
    sa.run_main(lambda: main(sys.argv[1]))
