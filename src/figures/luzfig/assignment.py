"""The practical assignment (lecture: "Trabalho prático": the five objects lit with
I = Ia·Ka + Il·Kd·cosθ and with the full model, through the orthographic Z-buffer) and the
material presets sheet (demo:materials with the names and constants of `luz materials`)."""

import subprocess

import matplotlib.pyplot as plt

from .common import Figure, render, save, to8, panels, load_scene


def make(ctx):
    """Both figures."""
    primitives(ctx)
    materials(ctx)


def primitives(ctx):
    """demo:primitives through the orthographic Z-buffer with both models."""
    # demo:primitives' lights (Il = 10 and 4) are exposed for 1/(d + K): lambert, which has no
    # distance term, gets what they deliver at the objects, Il/(d + K) ≈ 10/11 and 4/12
    lambert = ["--model", "lambert", "--set", "lights.0.intensity=0.9", "--set",
               "lights.1.intensity=0.33"]
    runs = [render(ctx, "demo:primitives", "primitives_lambert", lambert),
            render(ctx, "demo:primitives", "primitives_phong", ["--model", "phong"])]
    fig = panels([to8(r["image"]) for r in runs],
                 ["I = Ia·Ka + Il·Kd·cos(θ)  (lambert)",
                  "I = Ia·Ka + Σ Il/(d+K)·(Kd·cos(θ) + Ks·cos(α)^n)  (phong)"], scale=1.4)
    path = save(ctx, fig, "primitives")
    ctx.add(Figure(
        "primitives", "Trabalho prático: os cinco objetos", "The practical assignment",
        "Esfera, cubo, cilindro, cone e toro sobre um piso, iluminados em cada ponto pelos dois "
        "modelos, pelo Z-buffer com projeção ortográfica; as constantes são as padrão do luz "
        "(valores previamente testados), que o usuário muda com --set ou no visualizador. "
        "Lambert não tem o termo de distância: suas luzes recebem o que as da cena entregam "
        "aos objetos com 1/(d + K), Il = 0.9 e 0.33.",
        "Sphere, cube, cylinder, cone and torus on a floor, lit at every point by both models "
        "through the orthographic Z-buffer; the constants are luz's defaults (previously tested "
        "values), which the user changes with --set or in the viewer. Lambert has no distance "
        "term: its lights get what the scene's deliver at the objects through 1/(d + K), "
        "Il = 0.9 and 0.33.",
        [path], ["demo:primitives"], [r["command"] for r in runs],
        [(f"{r['stats']['pipeline']} {m}: triangles rasterized, seconds",
          f"{r['stats']['triangles']:,}, {r['stats']['seconds']:.3f} s")
         for r, m in zip(runs, ("lambert", "phong"))]))


def materials(ctx):
    """The presets as labelled spheres, demo:materials, and `luz materials`' constants."""
    demo = render(ctx, "demo:materials", "materials_demo", [], size=(480, 240))
    sheet = render(ctx, "materials_sheet", "materials_sheet", [], size=None)
    listing = subprocess.run([ctx.luz, "materials"], capture_output=True, text=True,
                             check=True).stdout.strip().splitlines()
    header = listing[0].split()
    rows = [line.split() for line in listing[1:]]
    alias = {r[0]: r[1] for r in rows if len(r) > 1}
    desc = load_scene(ctx, "materials_sheet")
    cam = desc["camera"]
    h, w = sheet["image"].shape[:2]
    vh = cam["view_height"]
    vw = vh * w / h
    fig, axes = plt.subplots(1, 2, figsize=(15, 5.6), gridspec_kw={"width_ratios": [1.33, 1]})
    axes[0].imshow(to8(sheet["image"]))
    for o in desc["objects"]:
        if o["type"] != "sphere":
            continue
        name = o.get("material", "padrão / default")
        x, y = o["center"][0], o["center"][1] - o["radius"] - 0.15
        px, py = (x / (vw / 2) + 1) * w / 2, (1 - y / (vh / 2)) * h / 2
        label = f"{name}\n({alias[name]})" if name in alias else name
        axes[0].text(px, py, label, ha="center", va="top", fontsize=7, color="white",
                     bbox={"fc": "black", "alpha": 0.55, "pad": 1, "lw": 0})
    axes[0].set_title("scenes/figures/materials_sheet.json", fontsize=9)
    axes[1].imshow(to8(demo["image"]))
    axes[1].set_title("demo:materials", fontsize=9)
    for ax in axes:
        ax.axis("off")
    fig.tight_layout()
    path = save(ctx, fig, "materials")
    numbers = [(r[0] + (f" ({r[1]})" if len(r) > 1 else ""),
                ", ".join(f"{hd} {v}" for hd, v in zip(header[2:], r[2:]))) for r in rows]
    ctx.add(Figure(
        "materials", "Os materiais pré-definidos", "The material presets",
        "Materiais diferentes refletem de modo diferente: os presets do luz com os nomes da "
        "aula (gesso, madeira, concreto, cortiça, plástico, metal polido, água, vidro) e os "
        "metais com a curva de Schlick (ouro, prata, cobre), com as constantes que "
        "`luz materials` lista; o último é o material padrão (Ka = 0.1, Kd = 0.45).",
        "Different materials reflect differently: luz's presets with the lecture's names and "
        "the metals with Schlick's curve, with the constants `luz materials` lists; the last "
        "sphere is the default material (Ka = 0.1, Kd = 0.45).",
        [path], ["scenes/figures/materials_sheet.json", "demo:materials"],
        [sheet["command"], demo["command"], "luz materials"], numbers))
