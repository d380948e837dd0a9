"""Intensity and distance (lecture: "Intensidade / Distância", I = Ia·Ka + Il·Kd·cosθ/(d + K)):
five receding spheres rendered without the distance term (`attenuation: none`), with 1/(d + K)
for several K and with the inverse square the slide calls less practical
(`attenuation: inverse_square`), plotted beside the measured peaks."""

import numpy as np
import matplotlib.pyplot as plt

from .common import Figure, render, save, to8, fmt, load_scene

KS = [1, 5, 20]


def make(ctx):
    """Renders phong without the distance term, with K = 1, 5, 20 and with 1/d²; measures each
    sphere's peak."""
    desc = load_scene(ctx, "distance")
    cam = np.array(desc["camera"]["position"], float)
    lp = np.array(desc["lights"][0]["position"], float)
    centres = [np.array(o["center"], float) for o in desc["objects"]]
    r = desc["objects"][0]["radius"]
    d_light = np.array([np.linalg.norm(c - lp) - r for c in centres])  # nearest point's d
    d_cam = [np.linalg.norm(c - cam) for c in centres]

    def peaks(res):
        """Each sphere's brightest diffuse value (its pixels found by depth)."""
        depth, diff = res["aov"]["depth"], res["aov"]["diffuse"][..., 0]
        return np.array([diff[(depth > dc - r - 0.2) & (depth < dc + r)].max() for dc in d_cam])

    # Il chosen so that the nearest sphere gets the same Il/divisor = 1 under every law
    runs = [("sem distância / no distance: Il·Kd·cosθ", None,
             render(ctx, "distance", "distance_none", ["--set", "attenuation=none"],
                    aov=["diffuse", "depth"]))]
    for K in KS:
        il = d_light[0] + K  # Il/(d + K) = 1 on the nearest sphere: the same exposure there
        runs.append((f"1/(d + K), K = {K}", K, render(
            ctx, "distance", f"distance_k{K}",
            ["--set", f"attenuation_k={K}", "--set", f"lights.0.intensity={il:.4f}"],
            aov=["diffuse", "depth"])))
    runs.append(("1/d² (inverse_square)", "square", render(
        ctx, "distance", "distance_square",
        ["--set", "attenuation=inverse_square", "--set",
         f"lights.0.intensity={d_light[0] ** 2:.4f}"], aov=["diffuse", "depth"])))
    fig = plt.figure(figsize=(17, 6.4))
    g = fig.add_gridspec(2, 5)
    for k, (title, K, res) in enumerate(runs):
        ax = fig.add_subplot(g[k // 3, k % 3])
        ax.imshow(to8(res["image"]))
        ax.set_title(title, fontsize=9)
        ax.axis("off")
    ax = fig.add_subplot(g[:, 3:])
    d = np.linspace(d_light[0], d_light[-1] * 1.05, 200)
    numbers = []
    for k, (title, K, res) in enumerate(runs):
        p = peaks(res)
        rel = p / p[0]
        col = f"C{k}"
        ax.plot(d_light, rel, "o", color=col, label=f"luz: {title.split(':')[0]}")
        if K == "square":
            numbers.append(("1/d²: farthest/nearest peak, measured (predicted)",
                            f"{rel[-1]:.3f} ({(d_light[0] / d_light[-1]) ** 2:.3f})"))
        elif K is not None:
            ax.plot(d, (d_light[0] + K) / (d + K), "-", color=col, lw=1,
                    label=f"(d₀ + K)/(d + K), K = {K}")
            pred = (d_light[0] + K) / (d_light + K)
            numbers.append((f"K = {K}: farthest/nearest peak, measured (predicted)",
                            f"{rel[-1]:.3f} ({pred[-1]:.3f})"))
        else:
            numbers.append(("no distance term: farthest/nearest peak", fmt(rel[-1], 3)))
    ax.plot(d, (d_light[0] / d) ** 2, "k--", lw=1.5, label="1/d² (inverso do quadrado / inverse "
            "square), d₀²/d²")
    numbers.append(("distances d from the light to each sphere's nearest point",
                    ", ".join(fmt(x, 1) for x in d_light)))
    ax.set_xlabel("d, distância da luz / distance from the light")
    ax.set_ylabel("pico relativo à esfera mais próxima / peak relative to the nearest sphere")
    ax.set_ylim(0, 1.1)
    ax.legend(fontsize=8, loc="lower left")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    img = save(ctx, fig, "distance")
    ctx.add(Figure(
        "distance", "Intensidade e distância", "Intensity and distance",
        "Cinco esferas iguais se afastando da luz, sem considerar a distância (attenuation: "
        "none) e considerando a distância: com a atenuação linear 1/(d + K) para K = 1, 5 e 20 "
        "e com o inverso do quadrado 1/d² (attenuation: inverse_square), Il escolhido para a "
        "esfera mais próxima ter o mesmo brilho. A intensidade da luz decresce com o quadrado "
        "da distância, mas na prática a atenuação linear dá resultados melhores: 1/d² escurece "
        "as esferas distantes muito mais depressa. Quanto maior K, menor a diferença.",
        "Five equal spheres receding from the light, without the distance term (attenuation: "
        "none) and with it: the linear attenuation 1/(d + K) for K = 1, 5 and 20 and the "
        "inverse square 1/d² (attenuation: inverse_square), Il chosen so the nearest sphere "
        "keeps the same brightness. Light falls with the square of the distance, but in "
        "practice the linear attenuation looks better: 1/d² darkens far spheres much faster "
        "(its dots on the dashed curve). The larger K, the smaller the difference. Dots: each "
        "sphere's brightest diffuse pixel, from luz's diffuse term.",
        [img], ["scenes/figures/distance.json"], [res["command"] for _, _, res in runs], numbers))
