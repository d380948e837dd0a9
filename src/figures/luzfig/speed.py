"""Ray casting's speed (lecture: "Ray Casting": only the first ray, so fast enough for
real-time games): zbuffer, raycast and raytrace timed on one scene (best of three runs)."""

import matplotlib.pyplot as plt

from .common import Figure, render, save, to8

SCENE = "demo:whitted"
PIPELINES = ["zbuffer", "raycast", "raytrace"]


def make(ctx):
    """Times the three pipelines (render seconds from --stats, best of 3)."""
    best = {}
    for p in PIPELINES:
        runs = [render(ctx, SCENE, f"speed_{p}_{k}", ["--pipeline", p]) for k in range(3)]
        best[p] = min(runs, key=lambda r: r["stats"]["seconds"])
    fig, axes = plt.subplots(1, 4, figsize=(15, 3.4), gridspec_kw={"width_ratios": [1, 1, 1, 1.2]})
    for ax, p in zip(axes, PIPELINES):
        st = best[p]["stats"]
        ax.imshow(to8(best[p]["image"]))
        ax.set_title(f"{p}: {st['seconds'] * 1000:.0f} ms", fontsize=10)
        ax.axis("off")
    secs = [best[p]["stats"]["seconds"] * 1000 for p in PIPELINES]
    axes[3].bar(PIPELINES, secs, color=["C2", "C0", "C3"])
    axes[3].set_ylabel("ms (melhor de 3 / best of 3)")
    for k, v in enumerate(secs):
        axes[3].text(k, v, f"{v:.0f}", ha="center", va="bottom")
    fig.tight_layout()
    path = save(ctx, fig, "speed")
    base = best["raycast"]["stats"]["seconds"]
    numbers = []
    for p in PIPELINES:
        st = best[p]["stats"]
        r = st["rays"]
        numbers.append((f"{p}: seconds (× raycast), rays primary + shadow + secondary",
                        f"{st['seconds']:.4f} s ({st['seconds'] / base:.2f}×), "
                        f"{r['primary'] + r['shadow'] + r['reflection'] + r['refraction']:,}"))
    ctx.add(Figure(
        "speed", "A velocidade do ray casting", "Ray casting's speed",
        "O ray casting limita-se ao traçado do primeiro raio, ignorando os raios secundários; "
        "por sua grande velocidade é indicado para jogos 3D em tempo real. A mesma cena pelos "
        f"três pipelines do luz, {best['raycast']['stats']['threads']} threads, melhor de três.",
        "Ray casting traces only the first ray and ignores secondary rays; its speed suits "
        "real-time 3D games. The same scene through luz's three pipelines, "
        f"{best['raycast']['stats']['threads']} threads, best of three runs.",
        [path], [SCENE], [best[p]["command"] for p in PIPELINES], numbers))
