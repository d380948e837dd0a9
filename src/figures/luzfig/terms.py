"""Combining the components (lecture: "Combinação das componentes: ambiente + difusa +
especular"): luz's per-term images (`--aov`) of one render, and their sum checked in float
against the image itself."""

import numpy as np

from .common import Figure, render, save, to8, panels

TERMS = ["ambient", "diffuse", "specular", "emitted"]


def make(ctx):
    """Renders with --aov ambient,diffuse,specular,emitted (PFM) and checks the sum."""
    res = render(ctx, "terms", "terms", [], aov=TERMS)
    a = res["aov"]
    total = a["ambient"] + a["diffuse"] + a["specular"] + a["emitted"]
    err = float(np.max(np.abs(total - res["image"])))
    rel = float(np.max(np.abs(total - res["image"]) / (1 + np.abs(res["image"]))))
    fig = panels([to8(a["ambient"] * 4), to8(a["diffuse"]), to8(a["specular"]),
                  to8(a["ambient"] + a["diffuse"] + a["specular"]), to8(res["image"])],
                 ["ambiente / ambient Ia·Ka (×4)", "difusa / diffuse Σ Il/(d+K)·Kd·cosθ",
                  "especular / specular Σ Il/(d+K)·Ks·cos(α)^n",
                  "ambiente + difusa + especular", "a imagem / the image"], cols=5, scale=0.95)
    img = save(ctx, fig, "terms")
    ctx.add(Figure(
        "terms", "Ambiente + difusa + especular", "Ambient + diffuse + specular",
        "As componentes do modelo como imagens do próprio luz (--aov): a ambiente (mostrada ×4 "
        "para ser visível), a difusa e a especular, somadas pixel a pixel, dão a imagem. O fundo "
        "é o termo emitido (emitted), que entra na soma conferida.",
        "The model's components as luz's own per-term images (--aov): ambient (shown ×4 to be "
        "visible), diffuse and specular add up, pixel by pixel, to the image. The background is "
        "the emitted term, included in the checked sum.",
        [img], ["scenes/figures/terms.json"], [res["command"]],
        [("largest |ambient + diffuse + specular + emitted − image| (float, PFM)", f"{err:.2e}"),
         ("largest relative difference |Σ − I|/(1 + |I|)", f"{rel:.2e}"),
         ("pixels compared", str(res["image"].shape[0] * res["image"].shape[1]))]))
