"""luz: the classic illumination models (ambient, Lambert, Phong, Whitted ray tracing,
z-buffer) as a Python module; the contract is docs/PYTHON.md.

    import luz
    scene = luz.load("demo:whitted")              # a path, "demo:NAME" or a dict
    frame = luz.render(scene, width=320, height=240, aov=["diffuse", "depth"])
    frame.image          # numpy float32 (240, 320, 3), linear, unclamped, row 0 on top
    frame.aov["depth"]   # numpy float32 (240, 320)
    frame.stats          # dict: the `luz render --stats` JSON
    frame.save("out.png")
    luz.ray_tree(scene, 160, 120)                 # the viewer's ray tree as a dict

The same pixels, bit for bit, as `luz render` with the same scene and options.
"""

from ._luz import (
    Frame,
    Scene,
    SceneError,
    SceneWarning,
    __version__,
    load,
    materials,
    ray_tree,
    render,
    scenes,
)

__all__ = [
    "Frame",
    "Scene",
    "SceneError",
    "SceneWarning",
    "load",
    "materials",
    "ray_tree",
    "render",
    "scenes",
]

# Show the public names as luz.X (they are defined in the extension module luz._luz).
for _name in __all__:
    try:
        globals()[_name].__module__ = "luz"
    except (AttributeError, TypeError):
        pass
del _name
