"""What every figure group shares: running the luz binary, reading its PFM and stats outputs,
rebuilding each pixel's camera ray, saving matplotlib figures, and the Figure record the page
shows (captions in Portuguese and English, scene files, commands, measured numbers)."""

import json
import os
import shlex
import shutil
import subprocess
import time
import urllib.parse
from dataclasses import dataclass, field

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

W, H = 320, 240  # every render's size: the whole `luz figures` stays under 2 minutes


@dataclass
class Figure:
    """One figure of the page: an id, titles and captions in both languages, the images it
    shows (paths relative to the output folder), the scene files and the commands that
    reproduce it, and the numbers it measured (label → text)."""
    id: str
    title_pt: str
    title_en: str
    caption_pt: str
    caption_en: str
    images: list = field(default_factory=list)
    scenes: list = field(default_factory=list)
    commands: list = field(default_factory=list)
    numbers: list = field(default_factory=list)


class Context:
    """The run: the luz binary, the scenes root (holding figures/*.json and bunny.obj), the
    output folder, and the figures made so far."""

    def __init__(self, luz, scenes, out):
        self.luz = luz
        self.scenes = scenes
        self.out = out
        self.figures = []
        self.renders = 0
        self.web = False  # luz.html written beside the page (write_web_page)
        os.makedirs(os.path.join(out, "img"), exist_ok=True)
        os.makedirs(os.path.join(out, "work"), exist_ok=True)

    def scene(self, name):
        """The path of scenes/figures/NAME.json, and its path as the page shows it."""
        return os.path.join(self.scenes, "figures", name + ".json"), f"scenes/figures/{name}.json"

    def add(self, fig):
        """Adds a Figure to the page."""
        self.figures.append(fig)


def _shown(arg):
    """An argument quoted for a shell, as the page prints it."""
    return shlex.quote(arg)


def render(ctx, scene, out_name, opts=(), aov=None, fmt="pfm", stats=True, aa_mask=None,
           size=(W, H)):
    """Runs `luz render SCENE -o work/OUT_NAME.FMT OPTS` (SCENE: a figures scene name,
    demo:NAME or an NFF file under the scenes root) and returns {"image", "aov", "stats", "command", "seconds"}: float arrays read
    back from the PFM files (row 0 on top), the --stats JSON, and the command as the page shows
    it (run from the output folder)."""
    if scene.startswith("demo:"):
        path, shown = scene, scene
    elif scene.endswith(".nff"):  # a scene file under the scenes root, e.g. spd/balls.nff
        path, shown = os.path.join(ctx.scenes, scene), f"scenes/{scene}"
    else:
        path, shown = ctx.scene(scene)
    work = os.path.join(ctx.out, "work")
    out = os.path.join(work, f"{out_name}.{fmt}")
    args = ["render", path, "-o", out, "-q"]
    shown_args = ["luz", "render", shown, "-o", f"{out_name}.{fmt}"]
    if size:
        args += ["--width", str(size[0]), "--height", str(size[1])]
        shown_args += ["--width", str(size[0]), "--height", str(size[1])]
    args += list(opts)
    shown_args += list(opts)
    if aov:
        args += ["--aov", ",".join(aov)]
        shown_args += ["--aov", ",".join(aov)]
    if stats:
        sp = os.path.join(work, f"{out_name}.stats.json")
        args += ["--stats", sp]
        shown_args += ["--stats", f"{out_name}.stats.json"]
    if aa_mask:
        mp = os.path.join(work, f"{out_name}.mask.{fmt}")
        args += ["--aa-mask", mp]
        shown_args += ["--aa-mask", f"{out_name}.mask.{fmt}"]
    t0 = time.perf_counter()
    r = subprocess.run([ctx.luz] + args, capture_output=True, text=True)
    seconds = time.perf_counter() - t0
    ctx.renders += 1
    if r.returncode != 0:
        raise RuntimeError(f"luz {' '.join(args)} failed ({r.returncode}): {r.stderr.strip()}")
    result = {"command": " ".join(_shown(a) for a in shown_args), "seconds": seconds}
    if fmt == "pfm":
        result["image"] = read_pfm(out)
        result["aov"] = {}
        for n in aov or ():
            a = read_pfm(os.path.join(work, f"{out_name}.{n}.pfm"))
            result["aov"][n] = a[..., 0] if n in ("depth", "tests") and a.ndim == 3 else a
        if aa_mask:
            result["mask"] = read_pfm(mp)
    if stats:
        with open(sp) as f:
            result["stats"] = json.load(f)
    return result


def read_pfm(path):
    """A PFM file as a float32 array (height, width, 3) or (height, width), row 0 on top."""
    with open(path, "rb") as f:
        kind = f.readline().strip()
        w, h = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    shape = (h, w, 3) if kind == b"PF" else (h, w)
    return np.flipud(data.reshape(shape)).astype(np.float32)


def to8(img):
    """luz's linear 8-bit encoding, round(255·clamp(I, 0, 1)), as floats in [0, 1] for
    imshow (so a shown render has the very values `luz render -o X.png` writes)."""
    return np.round(255 * np.clip(img, 0, 1)) / 255


def save(ctx, fig, name):
    """Saves a matplotlib figure as img/NAME.png and returns its path relative to the page."""
    rel = f"img/{name}.png"
    fig.savefig(os.path.join(ctx.out, rel), dpi=100)
    plt.close(fig)
    return rel


def panels(images, titles, cols=None, scale=1.0, suptitle=None):
    """A row (or grid) of renders with titles, axes off: a matplotlib figure."""
    n = len(images)
    cols = cols or n
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(cols * 3.3 * scale, rows * 2.8 * scale),
                             squeeze=False)
    for k, ax in enumerate(axes.flat):
        ax.axis("off")
        if k < n:
            img = images[k]
            ax.imshow(img if img.ndim == 3 else img, cmap=None if img.ndim == 3 else "gray",
                      interpolation="nearest")
            ax.set_title(titles[k], fontsize=9)
    if suptitle:
        fig.suptitle(suptitle, fontsize=10)
    fig.tight_layout()
    return fig


def load_scene(ctx, name):
    """The JSON of scenes/figures/NAME.json."""
    with open(ctx.scene(name)[0]) as f:
        return json.load(f)


def camera_rays(camera, w, h):
    """Each pixel centre's camera ray (docs/SCENES.md#geometry): origins and unit directions (h, w, 3)."""
    pos = np.array(camera.get("position", [0, 0, 5]), float)
    look = np.array(camera.get("look_at", [0, 0, 0]), float)
    up = np.array(camera.get("up", [0, 1, 0]), float)
    wv = pos - look
    wv /= np.linalg.norm(wv)
    u = np.cross(up, wv)
    u /= np.linalg.norm(u)
    v = np.cross(wv, u)
    px = np.arange(w) + 0.5
    py = np.arange(h) + 0.5
    x = (2 * px / w - 1)[None, :, None]
    y = (1 - 2 * py / h)[:, None, None]
    if camera.get("projection", "orthographic") == "orthographic":
        vh = camera.get("view_height", 6.0)
        origin = pos + x * (vh * w / h / 2) * u + y * (vh / 2) * v
        direction = np.broadcast_to(-wv, origin.shape)
    else:
        t = np.tan(np.radians(camera.get("fov_y", 40)) / 2)
        d = -wv + x * t * (w / h) * u + y * t * v
        direction = d / np.linalg.norm(d, axis=2, keepdims=True)
        origin = np.broadcast_to(pos, direction.shape)
    return np.array(origin), np.array(direction)


def hit_points(camera, depth):
    """World hit points (h, w, 3) from the depth term (NaN where the ray met nothing)."""
    h, w = depth.shape
    o, d = camera_rays(camera, w, h)
    t = np.where(np.isfinite(depth), depth, np.nan)
    return o + t[..., None] * d, -d


def copy_scene_files(ctx):
    """Copies scenes/figures/*.json, scenes/bunny.obj and scenes/spd/*.nff into the output
    folder, so that the page's commands run from it."""
    dst = os.path.join(ctx.out, "scenes", "figures")
    os.makedirs(dst, exist_ok=True)
    for n in sorted(os.listdir(os.path.join(ctx.scenes, "figures"))):
        if n.endswith(".json"):
            shutil.copy(os.path.join(ctx.scenes, "figures", n), dst)
    shutil.copy(os.path.join(ctx.scenes, "bunny.obj"), os.path.join(ctx.out, "scenes"))
    spd = os.path.join(ctx.scenes, "spd")
    if os.path.isdir(spd):  # the SPD figure's NFF scenes
        os.makedirs(os.path.join(ctx.out, "scenes", "spd"), exist_ok=True)
        for n in sorted(os.listdir(spd)):
            if n.endswith(".nff"):
                shutil.copy(os.path.join(spd, n), os.path.join(ctx.out, "scenes", "spd"))


def write_web_page(ctx):
    """Writes luz.html (`luz web`, docs/WEB.md) into the output folder, so that each figure's scene
    opens live in it; False when this luz was built without the page (the links are left out)."""
    r = subprocess.run([ctx.luz, "web", "-o", ctx.out], capture_output=True, text=True)
    return r.returncode == 0


def has_web_link(scene):
    """Whether the page's URL can carry `scene`: a built-in scene or a JSON file (docs/WEB.md#url;
    an NFF file, the SPD figure's, opens from disk in the page instead)."""
    return scene.startswith("demo:") or scene.endswith(".json")


def web_link(ctx, scene):
    """luz.html opened on `scene` (has_web_link(): demo:NAME, or a JSON scene file of the page,
    inlined)."""
    assert has_web_link(scene), scene
    if scene.startswith("demo:"):
        return "luz.html#scene=" + urllib.parse.quote(scene, safe=":")
    with open(os.path.join(ctx.out, scene), encoding="utf-8") as f:
        return "luz.html#scene=" + urllib.parse.quote(f.read(), safe="")


def fmt(x, digits=2):
    """A number as the page prints it."""
    return f"{x:.{digits}f}"
