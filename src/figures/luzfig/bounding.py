"""Bounding volumes (lecture: "Melhorias no processamento": 75–95 % of the time goes to
intersections; bounding boxes cut the tests, a small gain for simple objects and a large one
for a complex object): render.accel none against bvh, the tests term as heat maps, measured
time, test ratios and the intersection share from --stats."""

import numpy as np
import matplotlib.pyplot as plt
from matplotlib.colors import LogNorm

from .common import Figure, render, save

SCENES = [("bvh_simple", "objetos simples / simple objects (4 + plano)"),
          ("bvh_bunny", "objeto complexo / complex object (coelho, 3674 triângulos)")]


def tests(st):
    """Ray–primitive plus ray–bounds tests of a --stats JSON."""
    t = st["intersection_tests"]
    return t["primitive"] + t["bounds"]


def make(ctx):
    """Renders both scenes with accel none and bvh (tests term), plots heat maps and ratios."""
    runs = {}
    for s, _ in SCENES:
        for accel in ("none", "bvh"):
            runs[s, accel] = render(ctx, s, f"{s}_{accel}", ["--set", f'render.accel="{accel}"'],
                                    aov=["tests"], size=None)
    vmax = max(float(r["aov"]["tests"].max()) for r in runs.values())
    fig, axes = plt.subplots(2, 4, figsize=(15, 7.4),
                             gridspec_kw={"width_ratios": [1, 1, 0.05, 1.1], "wspace": 0.3})
    numbers = []
    for row, (s, label) in enumerate(SCENES):
        none, bvh = runs[s, "none"], runs[s, "bvh"]
        for col, (accel, r) in enumerate((("none", none), ("bvh", bvh))):
            ax = axes[row, col]
            im = ax.imshow(np.maximum(r["aov"]["tests"], 1), cmap="viridis",
                           norm=LogNorm(1, vmax), interpolation="nearest")
            st = r["stats"]
            ax.set_title(f"{label.split(' (')[0]}\naccel = {accel}: {tests(st):,} testes / tests, "
                         f"{st['seconds'] * 1000:.0f} ms", fontsize=8)
            ax.axis("off")
        fig.colorbar(im, cax=axes[row, 2], label="testes por pixel / tests per pixel")
        ax = axes[row, 3]
        t_ratio = none["stats"]["seconds"] / bvh["stats"]["seconds"]
        n_ratio = tests(none["stats"]) / tests(bvh["stats"])
        ax.bar(["tempo / time", "testes / tests"], [t_ratio, n_ratio], color=["C3", "C0"])
        ax.set_yscale("log")
        ax.set_ylim(0.5, max(1000, n_ratio * 2))
        ax.axhline(1, color="gray", lw=1)
        for k, v in enumerate((t_ratio, n_ratio)):
            ax.text(k, v * 1.15, f"{v:.1f}×", ha="center", fontsize=10)
        ax.set_title(f"none / bvh: {label}", fontsize=9)
        sh_none = none["stats"]["intersection_time"]["share"]
        sh_bvh = bvh["stats"]["intersection_time"]["share"]
        numbers += [
            (f"{s}: time none / bvh", f"{t_ratio:.1f}× ({none['stats']['seconds']:.3f} s / "
             f"{bvh['stats']['seconds']:.3f} s)"),
            (f"{s}: intersection tests none / bvh (primitive + bounds)",
             f"{n_ratio:.1f}× ({tests(none['stats']):,} / {tests(bvh['stats']):,})"),
            (f"{s}: share of time in intersection (intersection_time.share), none; bvh",
             f"{100 * sh_none:.0f} %; {100 * sh_bvh:.0f} %")]
    fig.subplots_adjust(left=0.01, right=0.99, top=0.9, bottom=0.06, hspace=0.35)
    path = save(ctx, fig, "bounding_volumes")
    ctx.add(Figure(
        "bounding_volumes", "Volumes envolventes (bounding boxes)", "Bounding volumes",
        "Estima-se que o ray tracing gasta entre 75 % e 95 % do seu tempo nas interseções. "
        "Como muitos objetos não são interceptados pelos raios, caixas envolventes (a BVH do "
        "luz) diminuem os testes: objetos simples levam a ganhos pequenos, um objeto complexo "
        "(o coelho) a um ganho grande. Mapas de calor: o termo tests, testes por pixel, na "
        "mesma escala logarítmica. A fração medida do tempo em interseções está na tabela.",
        "Ray tracing is estimated to spend 75 % to 95 % of its time on intersections. As most "
        "objects are not hit by a given ray, bounding boxes (luz's BVH) cut the tests: simple "
        "objects gain little, a complex object (the bunny) gains a lot. Heat maps: the tests "
        "term, tests per pixel, on one logarithmic scale. The measured share of time spent "
        "in intersections is in the table.",
        [path], ["scenes/figures/bvh_simple.json", "scenes/figures/bvh_bunny.json"],
        [r["command"] for r in runs.values()], numbers))
