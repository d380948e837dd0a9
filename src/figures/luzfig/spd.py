"""The Standard Procedural Databases (issue 39: the classic benchmark of Whitted ray tracers):
the seven SPD scenes read as NFF (scenes/spd/), each with its render time, its rays by kind and
its intersection tests per ray, from --stats."""

import matplotlib.pyplot as plt

from .common import Figure, render, save, to8

SCENES = ["balls", "gears", "mount", "rings", "teapot", "tetra", "tree"]
SIZE = (256, 256)


def rays(st):
    """Primary, reflected, refracted and shadow rays of a --stats JSON."""
    r = st["rays"]
    return r["primary"], r["reflection"], r["refraction"], r["shadow"]


def tests_per_ray(st):
    """Ray–primitive plus ray–bounds tests per ray traced."""
    t = st["intersection_tests"]
    return (t["primitive"] + t["bounds"]) / max(sum(rays(st)), 1)


def make(ctx):
    """Renders the seven scenes (256², their own settings) and shows each with its numbers."""
    runs = {s: render(ctx, f"spd/{s}.nff", f"spd_{s}", size=SIZE) for s in SCENES}
    fig, axes = plt.subplots(2, 4, figsize=(15, 8.6))
    numbers = []
    for ax, s in zip(axes.flat, SCENES):
        st = runs[s]["stats"]
        primary, reflected, refracted, shadow = rays(st)
        ax.imshow(to8(runs[s]["image"]), interpolation="nearest")
        ax.set_title(f"{s}: {st['seconds'] * 1000:.0f} ms\n"
                     f"{primary:,} primários / primary, {shadow:,} sombra / shadow\n"
                     f"{reflected:,} refletidos / reflected, {refracted:,} refratados / "
                     f"refracted\n{tests_per_ray(st):.1f} testes por raio / tests per ray",
                     fontsize=8)
        ax.axis("off")
        numbers.append((f"{s}: seconds; rays primary / reflected / refracted / shadow; "
                        "tests per ray",
                        f"{st['seconds']:.3f} s; {primary:,} / {reflected:,} / {refracted:,} / "
                        f"{shadow:,}; {tests_per_ray(st):.1f}"))
    per_ray = [tests_per_ray(runs[s]["stats"]) for s in SCENES]
    ax = axes.flat[-1]
    ax.barh(SCENES[::-1], per_ray[::-1], color="C0")
    ax.set_xlabel("testes por raio / intersection tests per ray")
    for k, v in enumerate(per_ray[::-1]):
        ax.text(v, k, f" {v:.1f}", va="center", fontsize=8)
    fig.tight_layout()
    path = save(ctx, fig, "spd")
    threads = runs[SCENES[0]]["stats"]["threads"]
    ctx.add(Figure(
        "spd", "As Standard Procedural Databases", "The Standard Procedural Databases",
        "As sete cenas de teste clássicas de Eric Haines (SPD 3.14), lidas em NFF, cujo "
        "material é o modelo da aula: cada uma com o tempo de renderização, os raios por tipo "
        f"e os testes de interseção por raio ({SIZE[0]}×{SIZE[1]}, {threads} threads).",
        "Eric Haines' seven classic test scenes (SPD 3.14), read as NFF, whose material line is "
        "the lecture's model: each with its render time, its rays by kind and its "
        f"intersection tests per ray ({SIZE[0]}×{SIZE[1]}, {threads} threads).",
        [path], [f"scenes/spd/{s}.nff" for s in SCENES],
        [runs[s]["command"] for s in SCENES], numbers))
