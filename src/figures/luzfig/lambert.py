"""Lambert's cosine law (lecture: "Modelo de Lambert", I = Il·Kd·cosθ, then I = Ia·Ka + …): a
sphere of the default material (Ka = 0.1, Kd = 0.45) lit by one far light, the diffuse term
measured per pixel against θ computed from luz's own depth and normal terms."""

import numpy as np
import matplotlib.pyplot as plt

from .common import Figure, render, save, to8, fmt, load_scene, hit_points

KD, KA, IL = 0.45, 0.1, 1.0


def make(ctx):
    """Renders the sphere without and with ambient light and plots I against θ."""
    desc = load_scene(ctx, "lambert")
    lp = np.array(desc["lights"][0]["position"], float)
    dark = render(ctx, "lambert", "lambert_no_ambient", ["--set", "ambient=0"],
                  aov=["diffuse", "depth", "normal"])
    lit = render(ctx, "lambert", "lambert_ambient", [], aov=["ambient", "diffuse"])
    P, _ = hit_points(desc["camera"], dark["aov"]["depth"])
    L = lp - P
    L /= np.linalg.norm(L, axis=2, keepdims=True)
    cos_t = np.sum(dark["aov"]["normal"] * L, axis=2)
    hit = np.isfinite(dark["aov"]["depth"])
    theta = np.degrees(np.arccos(np.clip(cos_t[hit], -1, 1)))
    measured = dark["aov"]["diffuse"][hit][:, 0] / (IL * KD)   # I / (Il·Kd)
    with_ambient = lit["image"][hit][:, 0]

    def at(angle):
        """(θ, I/(Il·Kd), I with ambient) of the sphere pixel nearest `angle`."""
        k = np.argmin(np.abs(theta - angle))
        return theta[k], measured[k], with_ambient[k]

    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2), gridspec_kw={"width_ratios": [1, 1, 1.6]})
    axes[0].imshow(to8(dark["image"]))
    axes[0].set_title("I = Il·Kd·cosθ (Ia = 0)", fontsize=10)
    axes[1].imshow(to8(lit["image"]))
    axes[1].set_title("I = Ia·Ka + Il·Kd·cosθ (Ia = 1)", fontsize=10)
    for ax in axes[:2]:
        ax.axis("off")
    ax = axes[2]
    sel = np.random.default_rng(1).choice(len(theta), size=min(3000, len(theta)), replace=False)
    ax.plot(theta[sel], (measured * IL * KD)[sel], ".", ms=2, alpha=0.5,
            label="luz: termo difuso por pixel / diffuse term per pixel")
    ax.plot(theta[sel], with_ambient[sel], ".", ms=2, alpha=0.5,
            label="luz: com ambiente / with ambient")
    t = np.linspace(0, 180, 361)
    ax.plot(t, IL * KD * np.clip(np.cos(np.radians(t)), 0, None), "k-", lw=1,
            label="Il·Kd·max(0, cosθ)")
    ax.plot(t, KA + IL * KD * np.clip(np.cos(np.radians(t)), 0, None), "k--", lw=1,
            label="Ia·Ka + Il·Kd·max(0, cosθ)")
    t45, m45, _ = at(45)
    ax.plot([t45], [m45 * IL * KD], "ro")
    ax.annotate(f"θ = {t45:.1f}°: I/(Il·Kd) = {m45:.3f}", (t45, m45 * IL * KD),
                xytext=(60, 0.42), arrowprops={"arrowstyle": "->"})
    ax.set_xlabel("θ (°), ângulo entre N e L / angle between N and L")
    ax.set_ylabel("I")
    ax.set_xlim(0, 180)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    img = save(ctx, fig, "lambert")
    err = np.max(np.abs(measured - np.clip(cos_t[hit], 0, None)))
    numbers = [(f"I/(Il·Kd) at θ = {at(a)[0]:.1f}° "
                f"(max(0, cosθ) = {max(0.0, np.cos(np.radians(at(a)[0]))):.3f})",
                fmt(at(a)[1], 3)) for a in (0, 30, 45, 60, 90)]
    numbers.append(("largest |I/(Il·Kd) − max(0, cosθ)| over the sphere's "
                    f"{int(hit.sum())} pixels", f"{err:.1e}"))
    numbers.append(("dark side with ambient: I = Ia·Ka", fmt(at(150)[2], 3)))
    ctx.add(Figure(
        "lambert", "Lei do cosseno de Lambert", "Lambert's cosine law",
        "Uma esfera do material padrão (Ka = 0.1, Kd = 0.45) sob uma fonte pontual distante, "
        "modelo de Lambert. A intensidade refletida é proporcional ao cosseno do ângulo θ entre "
        "a luz incidente e a normal: cada ponto do gráfico é um pixel da imagem, θ calculado "
        "das imagens de profundidade e normal do próprio luz. Com a luz ambiente (Ia = 1) o "
        "lado escuro fica com Ia·Ka = 0.1: é possível enxergar debaixo da mesa.",
        "A sphere of the default material (Ka = 0.1, Kd = 0.45) under one far point light, "
        "Lambert's model. The reflected intensity is proportional to the cosine of the angle θ "
        "between the incident light and the normal: every dot is one pixel of the render, θ "
        "computed from luz's own depth and normal terms. With ambient light (Ia = 1) the dark "
        "side keeps Ia·Ka = 0.1.",
        [img], ["scenes/figures/lambert.json"], [dark["command"], lit["command"]], numbers))
