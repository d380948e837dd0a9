"""Local against global models and Whitted ray tracing (lecture: "Modelos locais x modelos
globais", "Ray Tracing": sombra, reflexão, transparência e lei de Snell, a árvore de raios, a
profundidade máxima e a atenuação de cada nó pela distância ao pai)."""

import json
import os
import shutil
import subprocess

import numpy as np
import matplotlib.pyplot as plt

from .common import Figure, render, save, to8, panels

WHITTED = "demo:whitted"
TREE_PIXEL = (100, 110)  # a pixel of snell.json through the glass box: refraction and TIR


def rays(stats):
    """(primary, shadow, reflection, refraction) ray counts of a --stats JSON."""
    r = stats["rays"]
    return r["primary"], r["shadow"], r["reflection"], r["refraction"]


def make(ctx):
    """The five figures of this group."""
    local_global(ctx)
    depths(ctx)
    attenuation(ctx)
    snell(ctx)
    ray_tree(ctx)


def local_global(ctx):
    """raycast against raytrace, with the shadow, reflected and refracted terms."""
    cast = render(ctx, WHITTED, "whitted_raycast", ["--pipeline", "raycast"])
    trace = render(ctx, WHITTED, "whitted_raytrace", [],
                   aov=["shadow", "reflected", "refracted"])
    a = trace["aov"]
    fig = panels([to8(cast["image"]), to8(trace["image"]), to8(a["shadow"]),
                  to8(a["reflected"]), to8(a["refracted"])],
                 ["local: raycast", "global: raytrace", "sombra / shadow term",
                  "refletido / reflected term", "refratado / refracted term"], cols=5, scale=0.95)
    path = save(ctx, fig, "local_global")
    p, s, rl, rr = rays(trace["stats"])
    ctx.add(Figure(
        "local_global", "Modelos locais × globais; sombra, reflexão, refração",
        "Local against global models; shadows, reflection, refraction",
        "Modelos locais consideram apenas os raios vindos das fontes de luz (raycast: só o "
        "primeiro raio); modelos globais também os raios refletidos e transmitidos pelos demais "
        "objetos (raytrace). Os termos do luz mostram o que cada raio secundário trouxe: a luz "
        "que os raios de sombra retiraram, a reflexão do espelho e a refração (lei de Snell).",
        "Local models consider only the rays coming from the lights (raycast: the first ray "
        "only); global models also the rays reflected and transmitted by the other objects "
        "(raytrace). luz's terms show what each kind of secondary ray brought: the light the "
        "shadow rays took away, the mirror reflection and the refraction (Snell's law).",
        [path], [WHITTED], [cast["command"], trace["command"]],
        [("raycast rays: primary, shadow, reflection, refraction",
          ", ".join(str(x) for x in rays(cast["stats"]))),
         ("raytrace rays: primary, shadow, reflection, refraction", f"{p}, {s}, {rl}, {rr}"),
         ("raytrace / raycast time (render seconds from --stats)",
          f"{trace['stats']['seconds'] / cast['stats']['seconds']:.1f}× "
          f"({trace['stats']['seconds']:.3f} s / {cast['stats']['seconds']:.3f} s)")]))


def depths(ctx):
    """demo:whitted at max depth 0 … 5, secondary rays counted."""
    runs = [render(ctx, WHITTED, f"whitted_depth{d}", ["--max-depth", str(d)]) for d in range(6)]
    fig = panels([to8(r["image"]) for r in runs],
                 [f"profundidade máxima / max depth {d}" for d in range(6)], cols=3)
    path = save(ctx, fig, "max_depth")
    numbers = []
    for d, r in enumerate(runs):
        p, s, rl, rr = rays(r["stats"])
        numbers.append((f"max depth {d}: secondary rays (reflection + refraction), shadow rays",
                        f"{rl + rr}, {s}"))
    diffs = [float(np.max(np.abs(runs[d]["image"] - runs[d - 1]["image"]))) for d in range(1, 6)]
    numbers.append(("largest pixel change from depth d−1 to d, d = 1 … 5",
                    ", ".join(f"{x:.3f}" for x in diffs)))
    ctx.add(Figure(
        "max_depth", "Profundidade máxima da árvore: 0 a 5", "Maximum tree depth: 0 to 5",
        "O trajeto de um raio termina ao atingir a profundidade máxima da árvore, uma fonte de "
        "luz ou nenhum objeto. Com profundidade 0 não há raios secundários (só sombras); cada "
        "nível a mais acrescenta reflexões dentro de reflexões e a luz que atravessa o vidro.",
        "A ray's path ends when it reaches the tree's maximum depth, a light, or nothing. At "
        "depth 0 there are no secondary rays (shadows only); each further level adds "
        "reflections of reflections and the light that passes through the glass.",
        [path], [WHITTED], [runs[d]["command"] for d in range(6)], numbers))


def attenuation(ctx):
    """render.tree_attenuation off and on."""
    off = render(ctx, WHITTED, "whitted_att_off", [])
    on = render(ctx, WHITTED, "whitted_att_on", ["--set", "render.tree_attenuation=true"],
                aov=["reflected", "refracted"])
    off_t = render(ctx, WHITTED, "whitted_att_off_terms", [], aov=["reflected", "refracted"])
    fig = panels([to8(off["image"]), to8(on["image"]),
                  to8(np.abs(off["image"] - on["image"]) * 2)],
                 ["tree_attenuation = false (A = 1)", "tree_attenuation = true (A = 1/(d + K))",
                  "|diferença / difference| × 2"], scale=1.2)
    path = save(ctx, fig, "tree_attenuation")

    def share(r):
        """Share of the image's sum that came through reflected and refracted rays."""
        a = r["aov"]
        return float((a["reflected"] + a["refracted"]).sum() / max(r["image"].sum(), 1e-9))

    ctx.add(Figure(
        "tree_attenuation", "Atenuação na árvore de raios", "Ray-tree attenuation",
        "A intensidade do objeto, em cada nó da árvore, é atenuada pela distância do objeto "
        "pai e adicionada à intensidade deste: com a atenuação ligada, cada raio secundário é "
        "multiplicado por 1/(d + K), d o comprimento do segmento até o pai.",
        "Each node of the ray tree is attenuated by its distance to its parent and added to the "
        "parent's intensity: with attenuation on, every secondary ray is weighted by "
        "1/(d + K), d the length of its segment from the parent.",
        [path], [WHITTED], [off["command"], on["command"]],
        [("share of the image from reflected + refracted terms, off → on",
          f"{share(off_t):.3f} → {share(on):.3f}"),
         ("mean pixel value, off → on",
          f"{off['image'].mean():.3f} → {on['image'].mean():.3f}")]))


def click_tree(ctx, scene, x, y):
    """The ray tree of pixel (x, y) as luz's viewer records it (`luz view --click X,Y
    --screenshot`, under xvfb-run), or None when the viewer or xvfb-run is not there."""
    work = os.path.join(ctx.out, "work")
    shot = os.path.join(work, "tree.png")
    xvfb = shutil.which("xvfb-run")
    if not xvfb:
        return None, ""
    cmd = [xvfb, "-a", ctx.luz, "view", scene, "--screenshot", shot, "--click", f"{x},{y}"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0 or not os.path.exists(os.path.join(work, "tree.json")):
        return None, r.stderr.strip()
    with open(os.path.join(work, "tree.json")) as f:
        return json.load(f), ""


def snell(ctx):
    """The glass box and sphere, the refracted term, Snell's law with its critical angle."""
    res = render(ctx, "snell", "snell", [], aov=["refracted", "reflected"])
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    axes[0].imshow(to8(res["image"]))
    axes[0].set_title("vidro / glass (ior 1.5): raytrace; + pixel da árvore / tree's pixel",
                      fontsize=10)
    axes[0].plot([TREE_PIXEL[0]], [TREE_PIXEL[1]], "c+", ms=14, mew=2)
    axes[1].imshow(to8(res["aov"]["refracted"]))
    axes[1].set_title("termo refratado / refracted term", fontsize=10)
    for ax in axes[:2]:
        ax.axis("off")
    ax = axes[2]
    i = np.linspace(0, 90, 901)
    s = np.sin(np.radians(i))
    for n1, n2, col in ((1.0, 1.5, "C0"), (1.5, 1.0, "C1"), (1.0, 1.33, "C2")):
        arg = n1 * s / n2
        r = np.where(arg <= 1, np.degrees(np.arcsin(np.clip(arg, -1, 1))), np.nan)
        ax.plot(i, r, col, label=f"n1 = {n1}, n2 = {n2}")
    crit = np.degrees(np.arcsin(1 / 1.5))
    ax.axvline(crit, color="C1", ls="--", lw=1)
    ax.annotate(f"reflexão total / total internal\nreflection: i > {crit:.1f}°", (crit, 60),
                xytext=(50, 30), arrowprops={"arrowstyle": "->"}, fontsize=9)
    ax.set_xlabel("i (°)")
    ax.set_ylabel("r (°): n1·sen i = n2·sen r")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    path = save(ctx, fig, "snell")
    ctx.add(Figure(
        "snell", "Transparência: lei de Snell e reflexão total",
        "Transparency: Snell's law and total internal reflection",
        "A luz transmitida é governada pela lei de Snell, n1·sen i = n2·sen r (curvas à "
        "direita). Saindo do vidro (n1 = 1.5, n2 = 1) acima do ângulo crítico não há raio "
        "refratado: a parte transmitida segue o raio refletido (reflexão total), o que dá às "
        "faces laterais da caixa de vidro o aspecto de espelho.",
        "Transmitted light follows Snell's law, n1·sin i = n2·sin r (curves, right). Leaving "
        "glass (n1 = 1.5, n2 = 1) beyond the critical angle there is no refracted ray: the "
        "transmitted share follows the reflected ray (total internal reflection), which makes "
        "the glass box's side faces look like mirrors.",
        [path], ["scenes/figures/snell.json"], [res["command"]],
        [("critical angle for glass, arcsin(1/1.5)", f"{crit:.1f}°")]))


def ray_tree(ctx):
    """One pixel's ray tree (luz's viewer inspector) drawn as a diagram with its numbers."""
    scene, shown = ctx.scene("snell")
    x, y = TREE_PIXEL
    tree, why = click_tree(ctx, scene, x, y)
    cmd = f"xvfb-run -a luz view {shown} --screenshot tree.png --click {x},{y}   # writes tree.json"
    if tree is None:
        ctx.add(Figure("ray_tree", "A árvore de um pixel", "One pixel's ray tree",
                       "Indisponível: precisa do visualizador do luz e do xvfb-run.",
                       f"Not available: needs luz's viewer and xvfb-run ({why}).",
                       [], [shown], [cmd], []))
        return
    nodes = tree["nodes"]
    # layout: depth → x; leaves in order → y
    ys, next_y = {}, [0]

    def place(k):
        """Lays out node k's subtree: leaves one row apart, parents between children."""
        kids = [c for c in (nodes[k].get("reflection_child", -1),
                            nodes[k].get("refraction_child", -1)) if c is not None and c >= 0]
        if not kids:
            ys[k] = next_y[0]
            next_y[0] += 1
        else:
            for c in kids:
                place(c)
            ys[k] = np.mean([ys[c] for c in kids])
    place(0)
    fig, ax = plt.subplots(figsize=(15, 1.1 * max(next_y[0], 4)))
    for k, n in enumerate(nodes):
        if n.get("parent", -1) >= 0:
            p = n["parent"]
            ax.annotate("", (n["depth"], -ys[k]), (nodes[p]["depth"], -ys[p]),
                        arrowprops={"arrowstyle": "->", "color": "C0" if n["kind"] == "reflection"
                                    else "C1"})
    tir = 0
    for k, n in enumerate(nodes):
        col = n.get("colour", [0, 0, 0])
        txt = [f"{k}: {n['kind']} → " + (n.get("object_label") or n["hit"])]
        if n["hit"] == "object":
            loc = n.get("local", [0, 0, 0])
            txt.append(f"t = {n['t']:.2f}, local = {loc[0]:.3f}")
        if n.get("parent", -1) >= 0:
            txt.append(f"×{n.get('coefficient', 1):.2f} → +{n.get('contribution', [0])[0]:.3f}")
        txt.append(f"cor / colour R = {col[0]:.3f}")
        if n.get("total_internal_reflection"):
            tir += 1
            txt.append("reflexão total / TIR")
        ax.text(n["depth"], -ys[k], "\n".join(txt), fontsize=7, ha="center", va="center",
                bbox={"boxstyle": "round", "fc": "#fff8e0" if n.get("total_internal_reflection")
                      else "white", "ec": "gray"})
    ax.set_xlim(-0.6, max(n["depth"] for n in nodes) + 0.6)
    ax.set_ylim(-next_y[0] + 0.3, 0.7)
    ax.set_xlabel("profundidade / depth  (azul: reflexão / blue: reflection; "
                  "laranja: refração / orange: refraction)")
    ax.set_yticks([])
    fig.tight_layout()
    path = save(ctx, fig, "ray_tree")
    root = nodes[0]
    kids = [nodes[c]["contribution"][0] for c in (root.get("reflection_child", -1),
                                                  root.get("refraction_child", -1)) if c >= 0]
    ctx.add(Figure(
        "ray_tree", f"A árvore de raios do pixel ({x}, {y})", f"The ray tree of pixel ({x}, {y})",
        "A intensidade atribuída ao pixel é calculada pelo acúmulo das contribuições, "
        "iniciando pelos objetos nas folhas da árvore: cada nó soma o seu modelo local às "
        "contribuições dos filhos (coeficiente × cor devolvida). Os números são os que o "
        "traçador do luz usou (o inspetor do visualizador), pixel da caixa de vidro da figura "
        "anterior; canal R.",
        "The pixel's intensity is the sum of the contributions, starting from the leaves: each "
        "node adds its local model to its children's contributions (coefficient × returned "
        "colour). The numbers are those luz's tracer used (the viewer's inspector), for a pixel "
        "of the previous figure's glass box; red channel.",
        [path], [shown], [cmd],
        [("nodes, total internal reflections", f"{len(nodes)}, {tir}"),
         ("root: local + Σ children's contributions = colour (R)",
          f"{root['local'][0]:.4f} + {sum(kids):.4f} = {root['local'][0] + sum(kids):.4f} "
          f"(luz: {root['colour'][0]:.4f}, pixel value {tree['pixel_value'][0]:.4f})")]))
