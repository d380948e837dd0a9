"""Diffuse against specular reflection (lecture: "Reflexão difusa", "Reflexão especular"): a
tile of gesso, cortiça, metal polido and água seen from a sweep of camera angles; diffuse tiles
look the same from everywhere, specular ones only near the mirror direction (45° here)."""

import numpy as np
import matplotlib.pyplot as plt

from .common import Figure, render, save, to8, fmt

MATERIALS = [("gesso", "gesso"), ("cortica", "cortiça"), ("metal_polido", "metal polido"),
             ("agua", "água")]
ANGLES = [10, 20, 30, 40, 45, 50, 60, 75, 90]  # camera elevation above the tile, degrees
SHOWN = [20, 45, 75]


def make(ctx):
    """Renders the sweep, plots the tiles' mean brightness against the camera angle."""
    scene, shown = ctx.scene("diffuse_specular")
    means = {m: [] for m, _ in MATERIALS}
    thumbs, titles, commands = [], [], []
    for m, label in MATERIALS:
        for a in ANGLES:
            r = 10.0
            pos = [0, round(r * np.sin(np.radians(a)), 4), round(r * np.cos(np.radians(a)), 4)]
            opts = ["--set", f'objects.0.material="{m}"', "--set",
                    f'objects.1.material="{m}"', "--set",
                    f"camera.position=[{pos[0]},{pos[1]},{pos[2]}]"]
            res = render(ctx, "diffuse_specular", f"ds_{m}_{a}", opts, aov=["depth"],
                         size=(128, 96))
            hit = np.isfinite(res["aov"]["depth"])
            means[m].append(float(res["image"][hit].mean()))
            if a in SHOWN:
                thumbs.append(to8(res["image"]))
                titles.append(f"{label}, {a}°")
            if a == 45:
                commands.append(res["command"])
    fig = plt.figure(figsize=(12, 7.5))
    grid = fig.add_gridspec(len(MATERIALS), len(SHOWN) + 4)
    for k, img in enumerate(thumbs):
        ax = fig.add_subplot(grid[k // len(SHOWN), k % len(SHOWN)])
        ax.imshow(img[16:80, 24:104], interpolation="nearest")
        ax.set_title(titles[k], fontsize=9)
        ax.axis("off")
    ax = fig.add_subplot(grid[:, len(SHOWN):])
    for m, label in MATERIALS:
        ax.plot(ANGLES, means[m], "o-", label=label)
    ax.axvline(45, color="gray", ls="--", lw=1)
    ax.text(46, 0.55, "direção do espelho /\nmirror direction", fontsize=8,
            transform=ax.get_xaxis_transform())
    ax.set_xlabel("ângulo da câmera acima do ladrilho / camera elevation (°)")
    ax.set_ylabel("brilho médio do ladrilho / mean tile brightness")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    img = save(ctx, fig, "diffuse_specular")

    def spread(m):
        """Brightest over dimmest mean along the sweep."""
        v = np.array(means[m])
        return v.max() / max(v.min(), 1e-6)

    numbers = [(f"{label}: brilho médio / mean brightness at 10°, 45°, 90°",
                ", ".join(fmt(means[m][ANGLES.index(a)], 3) for a in (10, 45, 90)))
               for m, label in MATERIALS]
    numbers.append(("max/min over the sweep (gesso, cortiça, metal polido, água)",
                    ", ".join(fmt(spread(m), 1) for m, _ in MATERIALS)))
    ctx.add(Figure(
        "diffuse_specular", "Reflexão difusa × especular", "Diffuse against specular reflection",
        "Um ladrilho de gesso, cortiça, metal polido e água, luz a 45° de um lado, câmera "
        "percorrendo de 10° a 90° do outro. A reflexão difusa é vista de todas as direções "
        "(brilho quase constante); a especular só perto da direção do raio refletido (45°).",
        "A tile of plaster, cork, polished metal and still water lit at 45° from one side, the "
        "camera sweeping from 10° to 90° on the other. Diffuse reflection is seen from every "
        "direction (nearly constant brightness); specular reflection only near the mirror "
        "direction (45°). Local model (raycast): the tile's own light only.",
        [img], [shown], commands[:1] + ["(the other frames: --set camera.position=[0, "
                                        "10·sin a, 10·cos a], a = 10° … 90°, and "
                                        "--set objects.0.material=\"NAME\", the same for objects.1)"], numbers))
