"""The specular term (lecture: "Componente especular", Il·Ks·cos(α)^n): spheres at n = 1, 4,
20, 100 beside the curves cos(α)^n with the slide's example (α = 30°: 0.86 at n = 1, 0.56 at
n = 4) measured back from luz's specular term; and the slide's values Ia = Ip = 1.0,
Ka = 0.1, Kd = 0.45 with Ks varied."""

import numpy as np
import matplotlib.pyplot as plt

from .common import Figure, render, save, to8, load_scene, hit_points

AOVS = ["specular", "depth", "normal"]


def geometry(ctx, name, res):
    """Per pixel: sphere index, cosα, Il/(d + K) (far light), and the materials' Ks and n."""
    desc = load_scene(ctx, name)
    light = desc["lights"][0]
    lp = np.array(light["position"], float)
    P, S = hit_points(desc["camera"], res["aov"]["depth"])
    L = lp - P
    d = np.linalg.norm(L, axis=2)
    L /= d[..., None]
    N = res["aov"]["normal"]
    ndl = np.sum(N * L, axis=2)
    R = 2 * ndl[..., None] * N - L
    cos_a = np.clip(np.sum(R * S, axis=2), 0, None)
    factor = light["intensity"] / (d + desc.get("attenuation_k", 1.0))
    xs = np.array([o["center"][0] for o in desc["objects"]])
    hit = np.isfinite(res["aov"]["depth"])
    idx = np.where(hit, np.argmin(np.abs(np.nan_to_num(P[..., 0])[..., None] - xs), axis=2), -1)
    mats = [desc["materials"][o["material"]] for o in desc["objects"]]
    return idx, cos_a, factor, ndl, mats


def make(ctx):
    """The n figure, then the Ks figure."""
    make_n(ctx)
    make_ks(ctx)


def make_n(ctx):
    """The n figure: four spheres and the cos(α)^n curves, the slide's example measured."""
    res = render(ctx, "specular_n", "specular_n", [], aov=AOVS, size=(480, 160))
    idx, cos_a, factor, ndl, mats = geometry(ctx, "specular_n", res)
    spec = res["aov"]["specular"][..., 0]
    alpha = np.degrees(np.arccos(np.clip(cos_a, 0, 1)))
    fig, axes = plt.subplots(1, 2, figsize=(14, 4.6), gridspec_kw={"width_ratios": [1.5, 1]})
    axes[0].imshow(to8(res["image"]))
    axes[0].set_title("n = 1, 4, 20, 100 (Ks = 0.5, Kd = 0.45, Ka = 0.1)", fontsize=10)
    axes[0].axis("off")
    ax = axes[1]
    a = np.linspace(0, 90, 361)
    numbers = []
    for k, m in enumerate(mats):
        n = m["n"]
        ax.plot(a, np.cos(np.radians(a)) ** n, f"C{k}-", lw=1.2, label=f"cos(α)^{n}")
        sel = (idx == k) & (ndl > 0) & (cos_a > 0)
        measured = spec[sel] / (factor[sel] * m["ks"])  # = cos(α)^n as luz computed it
        pick = np.random.default_rng(k).choice(measured.size, min(400, measured.size), False)
        ax.plot(alpha[sel][pick], measured[pick], f"C{k}.", ms=2, alpha=0.6)
        k30 = np.argmin(np.abs(alpha[sel] - 30))
        err = np.max(np.abs(measured - cos_a[sel] ** n))
        numbers.append((f"n = {n}: luz's pixel nearest α = 30° (α = {alpha[sel][k30]:.2f}°)",
                        f"specular/(Ks·Il/(d+K)) = {measured[k30]:.3f}; "
                        f"largest |… − cos(α)^{n}| = {err:.1e}"))
    for n, v in ((1, 0.86), (4, 0.56)):
        ax.plot([30], [np.cos(np.radians(30)) ** n], "ko")
        ax.annotate(f"α = 30°, n = {n}: {v}", (30, np.cos(np.radians(30)) ** n),
                    xytext=(42, v + 0.08), arrowprops={"arrowstyle": "->"}, fontsize=9)
    ax.axvline(30, color="gray", ls=":", lw=1)
    ax.set_xlabel("α (°), entre R e S / between R and S")
    ax.set_ylabel("cos(α)^n")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    img = save(ctx, fig, "specular_n")
    ctx.add(Figure(
        "specular_n", "n pequeno × n grande", "Small n against large n",
        "A potência n aproxima a distribuição espacial da luz refletida especularmente: n "
        "pequeno espalha o brilho (não metais), n grande o concentra (metais polidos). Exemplo "
        "do slide, α = 30°: cos(30°)^1 = 0.86 e cos(30°)^4 = 0.56. Os pontos são pixels das "
        "esferas: o termo especular do luz dividido por Ks·Il/(d + K), contra α calculado da "
        "normal e da profundidade de cada pixel. Il/(d + K) = 1.0 (luz distante).",
        "The power n approximates how specularly reflected light spreads: small n spreads the "
        "highlight (non-metals), large n concentrates it (polished metals). The slide's example, "
        "α = 30°: cos(30°)^1 = 0.86 and cos(30°)^4 = 0.56. Dots are pixels of the spheres: "
        "luz's specular term divided by Ks·Il/(d + K), against α computed from each pixel's "
        "normal and depth. Il/(d + K) = 1.0 (a far light).",
        [img], ["scenes/figures/specular_n.json"], [res["command"]], numbers))


def make_ks(ctx):
    """The Ks figure: the slide's Ia, Ip, Ka, Kd with Ks from 0 to 0.9, and a profile."""
    res = render(ctx, "specular_ks", "specular_ks", [], aov=AOVS, size=(480, 160))
    idx, cos_a, factor, ndl, mats = geometry(ctx, "specular_ks", res)
    spec = res["aov"]["specular"][..., 0]
    img = res["image"][..., 0]
    fig, axes = plt.subplots(1, 2, figsize=(14, 4.4), gridspec_kw={"width_ratios": [1.5, 1]})
    axes[0].imshow(to8(res["image"]))
    axes[0].set_title("Ia = Ip = 1.0, Ka = 0.1, Kd = 0.45, n = 20; Ks = 0, 0.3, 0.6, 0.9",
                      fontsize=10)
    axes[0].axis("off")
    ax = axes[1]
    numbers = []
    row = int(np.unravel_index(np.argmax(spec), spec.shape)[0])  # through the highlights
    for k, m in enumerate(mats):
        sel = idx == k
        peak, speak = img[sel].max(), spec[sel].max()
        numbers.append((f"Ks = {m['ks']}: brightest pixel I (its specular term)",
                        f"{peak:.3f} ({speak:.3f})"))
    ax.plot(img[row], "k-", lw=1, label="I")
    ax.plot(spec[row], "C1-", lw=1, label="termo especular / specular term")
    ax.set_xlabel(f"coluna / column (linha / row {row})")
    ax.set_ylabel("I")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    path = save(ctx, fig, "specular_ks")
    ctx.add(Figure(
        "specular_ks", "Componente especular: os valores do slide",
        "The specular term: the slide's values",
        "Os valores testados do slide, Ia = Ip = 1.0, Ka = 0.1, Kd = 0.45 (o material padrão "
        "do luz), com Ks variando de 0 a 0.9 (n = 20). Ip/(d + K) = 1.0: luz distante com "
        "Il = d + K. O perfil à direita corta as quatro esferas na linha dos brilhos.",
        "The slide's tested values, Ia = Ip = 1.0, Ka = 0.1, Kd = 0.45 (luz's default "
        "material), with Ks from 0 to 0.9 (n = 20). Ip/(d + K) = 1.0: a far light with "
        "Il = d + K. The profile on the right cuts the four spheres through their highlights.",
        [path], ["scenes/figures/specular_ks.json"], [res["command"]], numbers))
