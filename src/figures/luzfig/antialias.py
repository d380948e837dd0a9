"""Antialiasing (lecture: "Realismo e antialiasing": more rays per pixel averaged, or only the
pixels whose neighbourhood changes colour strongly): none, grid 4, grid 16 and adaptive with
its refined-pixel mask, zoomed crops, and the samples counted by --stats."""

import matplotlib.pyplot as plt

from .common import Figure, render, save, to8

SCENE = "demo:whitted"
CROP = (slice(140, 185), slice(60, 120))  # rows, columns: a sphere edge over the checker

MODES = [("none", ["--aa", "none"]), ("grid 4", ["--aa", "grid", "--samples", "4"]),
         ("grid 16", ["--aa", "grid", "--samples", "16"]), ("adaptive", ["--aa", "adaptive"])]


def make(ctx):
    """Renders the four modes and lays out full images, crops ×4 and the adaptive mask."""
    runs = []
    for name, opts in MODES:
        runs.append(render(ctx, SCENE, "aa_" + name.replace(" ", ""), opts,
                           aa_mask=(name == "adaptive")))
    fig, axes = plt.subplots(3, 4, figsize=(14, 9.6))
    for k, ((name, _), r) in enumerate(zip(MODES, runs)):
        st = r["stats"]
        axes[0, k].imshow(to8(r["image"]), interpolation="nearest")
        axes[0, k].add_patch(plt.Rectangle((CROP[1].start, CROP[0].start),
                                           CROP[1].stop - CROP[1].start,
                                           CROP[0].stop - CROP[0].start, fill=False, ec="cyan"))
        axes[0, k].set_title(f"{name}: {st['samples']} amostras / samples "
                             f"({st['samples'] / (st['width'] * st['height']):.2f}/pixel)",
                             fontsize=9)
        axes[1, k].imshow(to8(r["image"][CROP]), interpolation="nearest")
        axes[1, k].set_title(f"{name}: recorte ampliado / enlarged crop", fontsize=9)
    mask = runs[-1]["mask"]
    axes[2, 0].imshow(to8(mask), interpolation="nearest")
    axes[2, 0].set_title(f"adaptive: {runs[-1]['stats']['pixels_refined']} pixels refinados / "
                         "refined", fontsize=9)
    axes[2, 1].imshow(to8(mask[CROP]), interpolation="nearest")
    axes[2, 1].set_title("máscara, recorte / mask, crop", fontsize=9)
    for ax in axes.flat:
        ax.axis("off")
    ax = fig.add_subplot(3, 2, 6)
    names = [m for m, _ in MODES]
    ax.bar(names, [r["stats"]["samples"] for r in runs], color="C0")
    ax.set_ylabel("amostras / samples")
    ax2 = ax.twinx()
    ax2.plot(names, [r["stats"]["seconds"] for r in runs], "C3o-")
    ax2.set_ylabel("segundos / seconds", color="C3")
    fig.tight_layout()
    path = save(ctx, fig, "antialias")
    base = runs[0]["stats"]
    numbers = []
    for (name, _), r in zip(MODES, runs):
        st = r["stats"]
        numbers.append((f"{name}: samples, pixels refined, render seconds (× none)",
                        f"{st['samples']}, {st['pixels_refined']}, {st['seconds']:.3f} s "
                        f"({st['seconds'] / base['seconds']:.1f}×)"))
    total = base["width"] * base["height"]
    numbers.append(("adaptive: share of pixels refined",
                    f"{100 * runs[-1]['stats']['pixels_refined'] / total:.1f} %"))
    ctx.add(Figure(
        "antialias", "Antialiasing: nenhum, grade 4, grade 16, adaptativo",
        "Antialiasing: none, grid 4, grid 16, adaptive",
        "Lançar mais raios por pixel e tirar a média (grade de 4 e de 16 amostras), ou "
        "selecionar os pixels que precisam ser melhor calculados, aqueles em cuja vizinhança "
        "ocorre uma grande mudança de cor (adaptativo; a máscara mostra os pixels refinados, "
        "cor = nível). O adaptativo se aproxima da grade com muito menos amostras.",
        "Cast more rays per pixel and average them (grids of 4 and 16 samples), or pick the "
        "pixels that need more work, those whose neighbourhood changes colour strongly "
        "(adaptive; the mask shows the refined pixels, colour = level). Adaptive comes close to "
        "the grid with far fewer samples.",
        [path], [SCENE], [r["command"] for r in runs], numbers))
