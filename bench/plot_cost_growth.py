#!/usr/bin/python3
"""Plots "How cost grows" (docs/BENCHMARKS.md) from the CSVs bench/cost_growth.sh writes:

  cost_build.png   BVH build time against triangle count, luz and Embree (log-log, n log n line)
  cost_memory.png  bytes per triangle against triangle count
  cost_rays.png    Mrays/s against triangle count, perspective and incoherent rays (log n guide)
  cost_render.png  luz render time of demo:whitted against resolution and against max depth

    /usr/bin/python3 bench/plot_cost_growth.py --bvh build/native/cost_growth_bvh.csv \\
        --resolution build/native/cost_growth_resolution.csv \\
        --depth build/native/cost_growth_depth.csv --out docs
"""
import argparse
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter, NullFormatter  # noqa: E402

LUZ, EMBREE = "tab:blue", "tab:orange"
STYLE = {1: ":", 2: "-"}  # line style per thread count (others: dashed)


def read_csv(path):
    if not path or not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(row, key):
    v = row.get(key, "")
    return float(v) if v not in ("", None) else math.nan


def by_threads(rows):
    out = {}
    for r in rows:
        out.setdefault(int(r["threads"]), []).append(r)
    for t in out:
        out[t].sort(key=lambda r: int(r["triangles"]))
    return dict(sorted(out.items()))


def series(rows, key):
    pts = [(int(r["triangles"]), num(r, key)) for r in rows]
    pts = [(n, y) for n, y in pts if not math.isnan(y)]
    return [n for n, _ in pts], [y for _, y in pts]


def count_label(n, _pos=None):
    for div, suffix in ((1e6, "M"), (1e3, "k")):
        if n >= div:
            v = n / div
            return f"{v:.0f}{suffix}" if abs(v - round(v)) < 1e-9 else f"{v:g}{suffix}"
    return f"{n:g}"


def triangle_axis(ax):
    ax.set_xscale("log")
    ax.set_xlabel("triangles (bumpy sphere, bvh_vs_embree --sphere)")
    ax.xaxis.set_major_formatter(FuncFormatter(count_label))
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.grid(True, which="both", alpha=0.3)


def caption(fig, rows):
    if rows:
        r = rows[0]
        reps = sorted({int(x["build_reps"]) for x in rows})
        sizes = "/".join(sorted({x["size"] for x in rows}, key=int))
        fig.text(0.01, 0.005, f"{sizes}² primary rays, median of {r['reps']} "
                 f"passes; builds: median of {'/'.join(map(str, reps))} (build_scene: of at "
                 f"most 3); bench/cost_growth.sh", fontsize=7, color="0.4")


def plot_build(rows, out):
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.8))
    groups = by_threads(rows)
    lines = [("luz_build_ms", "luz Bvh8", LUZ, "o"),
             ("luz_scene_build_ms", "luz build_scene (mesh + BVH)", "tab:green", "s"),
             ("embree_build_ms", "Embree medium", EMBREE, "^"),
             ("embree_high_build_ms", "Embree high", "tab:red", "v")]
    for t, rs in groups.items():
        for key, label, colour, marker in lines:
            n, y = series(rs, key)
            if not n:
                continue
            kw = dict(color=colour, marker=marker, ls=STYLE.get(t, "--"), ms=4,
                      label=f"{label}, {t} thread{'s' if t > 1 else ''}")
            ax.plot(n, y, **kw)
            if key != "embree_high_build_ms":  # it would squash the others
                ax2.plot(n, [1e6 * v / m for v, m in zip(y, n)], **kw)  # ns per triangle
    # reference: n log n through luz's largest build on the most threads
    if groups:
        n, y = series(groups[max(groups)], "luz_build_ms")
        if n:
            ref = [y[-1] * (m * math.log(m)) / (n[-1] * math.log(n[-1])) for m in n]
            ax.plot(n, ref, color="0.5", lw=1, ls="-.", label="∝ n log n (reference)")
            ax2.plot(n, [1e6 * v / m for v, m in zip(ref, n)], color="0.5", lw=1, ls="-.",
                     label="∝ log n (n log n per triangle)")
    ax.set_yscale("log")
    ax.set_ylabel("build time (ms)")
    ax.set_title("BVH build time against triangle count")
    ax2.set_ylabel("build time per triangle (ns)")
    ax2.set_title("per triangle (flat = linear growth; Embree high left out)")
    ax2.set_ylim(bottom=0)
    for a in (ax, ax2):
        triangle_axis(a)
    ax.legend(fontsize=7)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    caption(fig, rows)
    fig.savefig(out, dpi=110)
    plt.close(fig)


def plot_memory(rows, out):
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    groups = by_threads(rows)
    rs = groups[max(groups)] if groups else []
    for key, label, colour, marker in [
            ("luz_bytes_per_tri", "luz scene (mesh + BVH with vertex copies)", LUZ, "o"),
            ("luz_bvh8_bytes_per_tri", "luz Bvh8 (mesh + nodes + order)", "tab:cyan", "s"),
            ("embree_bytes_per_tri", "Embree medium (all it allocates)", EMBREE, "^"),
            ("embree_high_bytes_per_tri", "Embree high", "tab:red", "v")]:
        n, y = series(rs, key)
        if n:
            ax.plot(n, y, color=colour, marker=marker, ms=4, label=label)
    triangle_axis(ax)
    ax.set_ylim(bottom=0)
    ax.set_ylabel("memory per triangle (bytes)")
    ax.set_title("Memory per triangle against triangle count")
    ax.legend(fontsize=8)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    caption(fig, rows)
    fig.savefig(out, dpi=110)
    plt.close(fig)


def plot_rays(rows, out):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8), sharey=False)
    groups = by_threads(rows)
    for ax, kind in zip(axes, ("perspective", "incoherent")):
        for t, rs in groups.items():
            for key, label, colour, marker in [
                    (f"luz_{kind}_mrays", "luz scene query", LUZ, "o"),
                    (f"embree_{kind}_mrays", "Embree rtcIntersect1", EMBREE, "^")]:
                n, y = series(rs, key)
                if n:
                    ax.plot(n, y, color=colour, marker=marker, ms=4, ls=STYLE.get(t, "--"),
                            label=f"{label}, {t} thread{'s' if t > 1 else ''}")
        # guide: rays/s ∝ 1 / log n (traversal cost ∝ log n), through luz's smallest mesh on
        # the most threads
        if groups:
            n, y = series(groups[max(groups)], f"luz_{kind}_mrays")
            if n:
                ax.plot(n, [y[0] * math.log(n[0]) / math.log(m) for m in n], color="0.5",
                        lw=1, ls="-.", label="∝ 1 / log n (traversal ∝ log n)")
        triangle_axis(ax)
        ax.set_yscale("log")
        ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _p: f"{v:g}"))
        ax.yaxis.set_minor_formatter(FuncFormatter(lambda v, _p: f"{v:g}"))
        ax.tick_params(axis="y", which="minor", labelsize=7)
        ax.set_ylabel("million rays per second (log)")
        what = "primary (perspective)" if kind == "perspective" else \
            "incoherent (a cosine ray per primary hit)"
        ax.set_title(f"Rays/s against triangle count: {what}", fontsize=10)
        ax.legend(fontsize=7)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    caption(fig, rows)
    fig.savefig(out, dpi=110)
    plt.close(fig)


def plot_render(res, depth, out):
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.8))
    if res:
        px = [int(r["pixels"]) for r in res]
        sec = [float(r["render_s"]) for r in res]
        lo = [s - float(r["render_s_min"]) for s, r in zip(sec, res)]
        hi = [float(r["render_s_max"]) - s for s, r in zip(sec, res)]
        ax.errorbar(px, sec, yerr=[lo, hi], color=LUZ, marker="o", ms=4, capsize=2,
                    label="luz render (--stats seconds; bars: min–max)")
        ax.plot(px, [float(r["wall_s"]) for r in res], color="tab:green", marker="s", ms=3,
                ls="--", label="whole process (wall)")
        ax.plot(px, [sec[-1] * p / px[-1] for p in px], color="0.5", lw=1, ls="-.",
                label="∝ pixels (reference)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xticks(px)
        ax.set_xticklabels([f"{r['width']}×\n{r['height']}" for r in res], fontsize=7)
        ax.minorticks_off()
        t, d = res[0]["threads"], res[0]["max_depth"]
        ax.set_title(f"luz demo:whitted: render time against resolution (max depth {d}, "
                     f"{t} threads)", fontsize=10)
    ax.set_xlabel("image size (pixels, log)")
    ax.set_ylabel("time (s)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    if depth:
        d = [int(r["max_depth"]) for r in depth]
        sec = [float(r["render_s"]) for r in depth]
        lo = [s - float(r["render_s_min"]) for s, r in zip(sec, depth)]
        hi = [float(r["render_s_max"]) - s for s, r in zip(sec, depth)]
        ax2.errorbar(d, sec, yerr=[lo, hi], color=LUZ, marker="o", ms=4, capsize=2,
                     label="render time (--stats seconds)")
        ax2.set_ylim(bottom=0)
        ax2r = ax2.twinx()
        ax2r.plot(d, [int(r["rays"]) / 1e6 for r in depth], color="tab:purple", marker="s",
                  ms=3, ls="--", label="rays traced (all kinds)")
        ax2r.set_ylim(bottom=0)
        ax2r.set_ylabel("rays traced (millions)")
        h1, l1 = ax2.get_legend_handles_labels()
        h2, l2 = ax2r.get_legend_handles_labels()
        ax2.legend(h1 + h2, l1 + l2, fontsize=7, loc="lower right")
        ax2.set_xticks(d)
        w, h, t = depth[0]["width"], depth[0]["height"], depth[0]["threads"]
        ax2.set_title(f"luz demo:whitted: render time against max depth ({w}×{h}, {t} threads)",
                      fontsize=10)
    ax2.set_xlabel("render.max_depth (--max-depth)")
    ax2.set_ylabel("time (s)")
    ax2.grid(True, alpha=0.3)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    if res or depth:
        fig.text(0.01, 0.005, f"median of {(res or depth)[0]['runs']} runs "
                 "(bench/cost_growth.sh)", fontsize=7, color="0.4")
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--bvh", help="bvh_vs_embree --csv file (cost_growth_bvh.csv)")
    p.add_argument("--resolution", help="cost_growth_resolution.csv")
    p.add_argument("--depth", help="cost_growth_depth.csv")
    p.add_argument("--out", default="docs", help="directory for the PNGs (default docs)")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    written = []
    bvh = read_csv(a.bvh)
    if bvh:
        for name, f in (("cost_build.png", plot_build), ("cost_memory.png", plot_memory),
                        ("cost_rays.png", plot_rays)):
            f(bvh, os.path.join(a.out, name))
            written.append(name)
    res, depth = read_csv(a.resolution), read_csv(a.depth)
    if res or depth:
        plot_render(res, depth, os.path.join(a.out, "cost_render.png"))
        written.append("cost_render.png")
    if not written:
        raise SystemExit("plot_cost_growth.py: no data (give --bvh, --resolution or --depth)")
    print(f"plots: {', '.join(os.path.join(a.out, w) for w in written)}")


if __name__ == "__main__":
    main()
