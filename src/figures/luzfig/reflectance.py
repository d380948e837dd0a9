"""The reflectance curve w(i, λ) (lecture: "w(i, λ) é uma função muito complexa … na prática,
é comum substituir w(i, λ) por uma constante Ks"; docs/SCENES.md#reflectance): Schlick's curves of the metal
presets and of glass and water, and gold, silver and copper rendered with constant Ks beside
Schlick's curve, the ratio of their specular terms checked against the formula."""

import subprocess

import numpy as np
import matplotlib.pyplot as plt

from .common import Figure, render, save, to8, load_scene, hit_points

PRESETS = [("ouro", "gold"), ("prata", "silver"), ("cobre", "copper"), ("vidro", "glass"),
           ("agua", "still_water")]


def preset_ks(ctx):
    """Ks (RGB) of each preset of PRESETS, read from `luz materials`."""
    lines = subprocess.run([ctx.luz, "materials"], capture_output=True, text=True,
                           check=True).stdout.splitlines()
    col = lines[0].split().index("ks")
    out = {}
    for line in lines[1:]:
        f = line.split()
        if f and f[0] in dict(PRESETS):
            v = [float(x) for x in f[col].split(",")]
            out[f[0]] = np.array(v * 3 if len(v) == 1 else v)
    missing = [p for p, _ in PRESETS if p not in out]
    if missing:
        raise RuntimeError(f"luz materials lists no {', '.join(missing)}")
    return out


def schlick(ks, cos_t):
    """Schlick's w(θ) = Ks + (1 − Ks)(1 − cosθ)^5 (docs/SCENES.md#reflectance)."""
    return ks + (1 - ks) * (1 - cos_t) ** 5


def fresnel(n, cos_i):
    """Unpolarised Fresnel reflectance from air into index n (for comparison)."""
    sin_t = np.sqrt(np.clip(1 - cos_i ** 2, 0, 1)) / n
    cos_t = np.sqrt(1 - sin_t ** 2)
    rs = ((cos_i - n * cos_t) / (cos_i + n * cos_t)) ** 2
    rp = ((n * cos_i - cos_t) / (n * cos_i + cos_t)) ** 2
    return (rs + rp) / 2


def make(ctx):
    """Plots the curves; renders the metals with constant and Schlick reflectance."""
    ks = preset_ks(ctx)
    sch = render(ctx, "reflectance", "reflectance_schlick", [],
                 aov=["specular", "depth", "normal"], size=None)
    const_opts = []
    for m in ("gold", "silver", "copper"):
        const_opts += ["--set", f'materials.{m}.reflectance="constant"']
    con = render(ctx, "reflectance", "reflectance_constant", const_opts, aov=["specular"],
                 size=None)
    # per pixel: w/Ks measured (schlick specular / constant specular) against the formula,
    # for the first light (the rim light behind the spheres dominates the grazing pixels)
    desc = load_scene(ctx, "reflectance")
    P, _ = hit_points(desc["camera"], sch["aov"]["depth"])
    N = sch["aov"]["normal"]
    xs = np.array([o["center"][0] for o in desc["objects"]])
    names = [desc["materials"][o["material"]]["preset"] for o in desc["objects"]]
    idx = np.argmin(np.abs(np.nan_to_num(P[..., 0])[..., None] - xs), axis=2)
    a_s, a_c = sch["aov"]["specular"], con["aov"]["specular"]
    grazing = None
    for k, name in enumerate(names):
        sel = (idx == k) & np.isfinite(sch["aov"]["depth"]) & (a_c[..., 0] > 1e-4)
        # a pixel whose measured w/Ks matches the formula at one light's θ: that light gives
        # (almost) all of its specular term
        for lj in desc["lights"]:
            L = np.array(lj["position"], float) - P
            L /= np.linalg.norm(L, axis=2, keepdims=True)
            cos_t = np.clip(np.sum(N * L, axis=2), 0, 1)
            pred = schlick(ks[name], cos_t[..., None]) / ks[name]
            meas = a_s / np.maximum(a_c, 1e-12)
            err = np.abs(meas - pred).max(axis=2)
            good = sel & (err < 1e-3)
            if good.any():
                g = np.argmax(np.where(good, 1 - cos_t, -1))
                y, x = np.unravel_index(g, cos_t.shape)
                if grazing is None or 1 - cos_t[y, x] > grazing[0]:
                    grazing = (1 - cos_t[y, x], name, np.degrees(np.arccos(cos_t[y, x])),
                               meas[y, x], pred[y, x])
    fig = plt.figure(figsize=(15, 7.6))
    g = fig.add_gridspec(2, 3)
    ax = fig.add_subplot(g[:, 0])
    th = np.linspace(0, 90, 361)
    c = np.cos(np.radians(th))
    for name, en in PRESETS[:3]:
        for ch, col in enumerate(("r", "g", "b")):
            ax.plot(th, schlick(ks[name][ch], c), col, lw=1.2,
                    ls={"ouro": "-", "prata": "--", "cobre": ":"}[name],
                    label=f"{name} ({en}) {col.upper()}: Ks = {ks[name][ch]:.2f}")
    for name, en in PRESETS[3:]:
        ax.plot(th, schlick(ks[name][0], c), "k" if name == "vidro" else "c", lw=1.5,
                label=f"{name} ({en}): Ks = {ks[name][0]:.2f}")
    for n, lab in ((1.5, "vidro"), (1.33, "água")):
        ax.plot(th, fresnel(n, c), "k" if n == 1.5 else "c", lw=0.8, ls="-.",
                label=f"Fresnel, {lab} n = {n} (referência)")
    ax.set_xlabel("ângulo de incidência θ (°) / angle of incidence")
    ax.set_ylabel("w(θ, λ) = Ks + (1 − Ks)(1 − cosθ)^5")
    ax.set_ylim(0, 1.02)
    ax.legend(fontsize=7, loc="lower left")
    ax.grid(alpha=0.3)
    for row, (r, label) in enumerate(((con, "w = Ks (reflectance: constant)"),
                                      (sch, "w = Schlick (reflectance: schlick)"))):
        ax = fig.add_subplot(g[row, 1])
        ax.imshow(to8(r["image"]))
        ax.set_title(f"{label}: imagem / image", fontsize=9)
        ax.axis("off")
        ax = fig.add_subplot(g[row, 2])
        ax.imshow(to8(r["aov"]["specular"]))
        ax.set_title(f"{label}: termo especular / specular", fontsize=9)
        ax.axis("off")
    fig.tight_layout()
    path = save(ctx, fig, "reflectance")
    ratio = float(a_s.sum() / max(a_c.sum(), 1e-12))
    numbers = [(f"{n} ({en}) Ks = F0 (from luz materials)",
                ", ".join(f"{v:.3f}" for v in ks[n])) for n, en in PRESETS]
    numbers.append(("Σ specular, schlick / constant (all three spheres)", f"{ratio:.2f}"))
    if grazing:
        _, name, deg, meas, pred = grazing
        numbers.append((f"most grazing checked pixel ({name}, θ = {deg:.1f}°): w/Ks measured "
                        "(schlick ÷ constant specular term) vs formula, R G B",
                        " ".join(f"{m:.3f}" for m in meas) + " vs " +
                        " ".join(f"{p:.3f}" for p in pred)))
    ctx.add(Figure(
        "reflectance", "A curva de reflectância w(i, λ)", "The reflectance curve w(i, λ)",
        "w(i, λ) é a razão entre a luz refletida especularmente e a incidente, em função do "
        "ângulo de incidência e do comprimento de onda (equação de Fresnel); na prática é "
        "substituída por uma constante Ks. Aqui a aproximação de Schlick, um valor por canal "
        "RGB (λ): ouro, prata e cobre com Ks medido em incidência normal, e vidro e água com o "
        "Ks dos seus presets (a curva de Fresnel física, tracejada, parte de 0.04 e 0.02). À "
        "direita os metais com Ks constante e com a curva de Schlick: perto do ângulo rasante "
        "o brilho cresce e perde a cor.",
        "w(i, λ) is the ratio of specularly reflected to incident light as a function of the "
        "angle of incidence and the wavelength (Fresnel's equation); in practice it is replaced "
        "by a constant Ks. Here Schlick's approximation, one value per RGB channel (λ): gold, "
        "silver and copper with measured normal-incidence Ks, glass and water with their "
        "presets' Ks (the physical Fresnel curve, dash-dotted, starts at 0.04 and 0.02). Right: "
        "the metals with constant Ks and with Schlick's curve: towards grazing angles the "
        "highlight grows and loses its colour.",
        [path], ["scenes/figures/reflectance.json"], [con["command"], sch["command"]], numbers))
