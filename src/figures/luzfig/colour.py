"""Coloured objects (lecture: "Tratamento de objetos coloridos": Ia, Il, Ka, Kd, Ks as RGB
triples): a white sphere and a yellow box under a red, a green and a blue light, ray traced,
so each shadow takes the colour of the lights that still reach it."""

import numpy as np

from .common import Figure, render, save, to8, panels


def make(ctx):
    """Renders the scene with its image and shadow term; names the colour in each shadow."""
    res = render(ctx, "coloured_lights", "coloured_lights", [], aov=["shadow", "depth"])
    img, sh = res["image"], res["aov"]["shadow"]
    numbers = []
    for c, (pt, en) in enumerate([("vermelha", "red"), ("verde", "green"), ("azul", "blue")]):
        others = [k for k in range(3) if k != c]
        # the floor pixel that lost most of this light and none of the others
        score = sh[..., c] - sh[..., others].sum(axis=2) * 4
        y, x = np.unravel_index(np.argmax(score), score.shape)
        v = img[y, x]
        numbers.append((f"in the {en} light's shadow (pixel {x}, {y}): RGB",
                        f"({v[0]:.2f}, {v[1]:.2f}, {v[2]:.2f})"))
    fig = panels([to8(img), to8(sh)], ["raytrace: luzes R, G, B / red, green, blue lights",
                                      "termo sombra / shadow term (luz retirada / light removed)"],
                 scale=1.4)
    path = save(ctx, fig, "coloured_lights")
    ctx.add(Figure(
        "coloured_lights", "Objetos coloridos sob luzes coloridas",
        "Coloured objects under coloured lights",
        "Os parâmetros das fontes e dos materiais são tuplas RGB. Uma esfera branca e uma caixa "
        "amarela sob uma luz vermelha, uma verde e uma azul: onde o raio de sombra encontra um "
        "objeto, falta só aquela luz, e a sombra fica com a cor das outras duas (a sombra da "
        "luz vermelha é ciano). À direita, o termo sombra: a luz que os raios de sombra "
        "retiraram.",
        "Light and material parameters are RGB triples. A white sphere and a yellow box under a "
        "red, a green and a blue light: where a shadow ray meets an object only that light is "
        "missing, and the shadow takes the colour of the other two (the red light's shadow is "
        "cyan). Right: the shadow term, the light the shadow rays took away.",
        [path], ["scenes/figures/coloured_lights.json"], [res["command"]], numbers))
