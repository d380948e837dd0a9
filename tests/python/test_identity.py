# luz.render gives the same pixels, bit for bit, as `luz render` with the same scene and options
# (docs/PYTHON.md): every pipeline, antialiasing mode, --set, dict scenes, meshes; and the same PNG
# bytes from Frame._repr_png_ and Frame.save as from the command line.
import json

import numpy as np
import pytest

from conftest import cli_image, run_luz, same_bits

SMALL = ["--width", "96", "--height", "72"]

# (scene, CLI options, the same as keywords)
CASES = [
    ("demo:primitives", [], {}),
    ("demo:primitives", ["--pipeline", "raycast"], {"pipeline": "raycast"}),
    ("demo:primitives", ["--pipeline", "raytrace", "--model", "lambert"],
     {"pipeline": "raytrace", "model": "lambert"}),
    ("demo:whitted", [], {}),
    ("demo:whitted", ["--max-depth", "1"], {"max_depth": 1}),
    ("demo:whitted", ["--aa", "grid", "--samples", "4"], {"aa": "grid", "samples": 4}),
    ("demo:whitted", ["--aa", "adaptive", "--threshold", "0.05"],
     {"aa": "adaptive", "threshold": 0.05}),
    ("demo:primitives", ["--aa", "grid", "--samples", "9"], {"aa": "grid", "samples": 9}),
    ("demo:primitives", ["--aa", "adaptive", "--threshold", "0.02"],
     {"aa": "adaptive", "threshold": 0.02}),
    ("demo:materials", ["--set", "materials.floor.kd=0.3", "--set", "ambient=[0.5,0.6,0.7]"],
     {"set": {"materials.floor.kd": 0.3, "ambient": [0.5, 0.6, 0.7]}}),
    ("demo:whitted", ["--set", "objects.1.radius=0.5", "--set", "render.pipeline=raycast"],
     {"set": {"objects.1.radius": 0.5, "render.pipeline": "raycast"}}),
    ("demo:bunny", [], {}),
]


@pytest.mark.parametrize("scene,args,kwargs", CASES,
                         ids=[f"{s}{' '.join(a)}" for s, a, _ in CASES])
def test_render_matches_cli_bit_for_bit(luz, tmp_path, scene, args, kwargs):
    expected = cli_image(tmp_path, scene, SMALL + args)
    # from the source directly, and from a loaded Scene: the same bits
    direct = luz.render(scene, width=96, height=72, **kwargs)
    assert same_bits(direct.image, expected)
    loaded = luz.load(scene)
    again = luz.render(loaded, width=96, height=72, **kwargs)
    assert same_bits(again.image, expected)


def test_load_set_equals_render_set_equals_cli(luz, tmp_path):
    expected = cli_image(tmp_path, "demo:primitives",
                         SMALL + ["--set", "materials.blue.n=4", "--set", "attenuation_k=2"])
    s = luz.load("demo:primitives", set={"materials.blue.n": 4, "attenuation_k": 2})
    assert same_bits(luz.render(s, width=96, height=72).image, expected)
    s2 = luz.load(luz.load("demo:primitives"), set={"materials.blue.n": 4, "attenuation_k": 2})
    assert same_bits(luz.render(s2, width=96, height=72).image, expected)


def test_none_keeps_the_scene_value(luz, tmp_path):
    s = luz.load("demo:whitted", set={"image.width": 64, "image.height": 48})
    expected = cli_image(tmp_path, "demo:whitted", ["--width", "64", "--height", "48"])
    frame = luz.render(s, pipeline=None, width=None, aa=None)
    assert frame.image.shape == (48, 64, 3)
    assert same_bits(frame.image, expected)


def test_dict_scene_matches_the_same_file(luz, tmp_path):
    scene = {
        "image": {"width": 80, "height": 60},
        "render": {"pipeline": "raytrace"},
        "materials": {"red": {"ka": [0.1, 0.02, 0.02], "kd": [0.8, 0.1, 0.1], "ks": 0.5,
                              "n": 30}},
        "lights": [{"position": [5, 8, 6], "intensity": [1, 1, 1]}],
        "objects": [{"type": "sphere", "center": [0, 1, 0], "material": "red"},
                    {"type": "plane"}],
    }
    (tmp_path / "s.json").write_text(json.dumps(scene))
    expected = cli_image(tmp_path, tmp_path / "s.json", ["--set", "materials.red.n=4"])
    assert same_bits(luz.render(scene, set={"materials.red.n": 4}).image, expected)
    assert same_bits(luz.render(luz.load(scene), set={"materials.red.n": 4}).image, expected)
    # numpy values in a dict are numbers as well
    scene["lights"][0]["position"] = np.array([5.0, 8.0, 6.0])
    assert same_bits(luz.render(scene, set={"materials.red.n": np.int64(4)}).image, expected)
    # the smallest scene of docs/SCENES.md#scene-files
    small = luz.render({"objects": [{"type": "sphere"}]}, width=32, height=24)
    assert small.image.shape == (24, 32, 3)


def test_scene_file_with_mesh_relative_to_it(luz, tmp_path):
    (tmp_path / "m.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\n")
    (tmp_path / "m.json").write_text(json.dumps(
        {"image": {"width": 40, "height": 30}, "render": {"pipeline": "raytrace"},
         "objects": [{"type": "mesh", "file": "m.obj"}]}))
    expected = cli_image(tmp_path, tmp_path / "m.json")
    scene = luz.load(tmp_path / "m.json")  # a pathlib.Path
    assert same_bits(luz.render(scene).image, expected)
    # a settings-only change reuses the loaded mesh and built geometry: still the same bits
    assert same_bits(luz.render(scene, width=40).image, expected)


def test_threads_give_the_same_bits(luz):
    a = luz.render("demo:whitted", width=64, height=48, threads=1)
    b = luz.render("demo:whitted", width=64, height=48, threads=2)
    c = luz.render("demo:whitted", width=64, height=48, threads=0)
    assert same_bits(a.image, b.image) and same_bits(a.image, c.image)
    assert a.stats["threads"] == 1 and b.stats["threads"] == 2


def test_repr_png_and_save_are_the_cli_bytes(luz, tmp_path):
    status, _, err = run_luz(["render", "demo:whitted", *SMALL, "-o", "cli.png", "-q"], tmp_path)
    assert status == 0, err
    cli_png = (tmp_path / "cli.png").read_bytes()
    frame = luz.render("demo:whitted", width=96, height=72)
    assert frame._repr_png_() == cli_png
    frame.save(tmp_path / "py.png")
    assert (tmp_path / "py.png").read_bytes() == cli_png
    frame.save(str(tmp_path / "py.pfm"))
    status, _, err = run_luz(["render", "demo:whitted", *SMALL, "-o", "cli.pfm", "-q"], tmp_path)
    assert (tmp_path / "py.pfm").read_bytes() == (tmp_path / "cli.pfm").read_bytes()
    # no temporary file left behind
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cli.pfm", "cli.png", "py.pfm",
                                                          "py.png"]


def test_srgb_encoding_in_png(luz, tmp_path):
    args = [*SMALL, "--set", "image.encoding=srgb"]
    status, _, err = run_luz(["render", "demo:primitives", *args, "-o", "c.png", "-q"], tmp_path)
    assert status == 0, err
    frame = luz.render("demo:primitives", width=96, height=72, set={"image.encoding": "srgb"})
    assert frame._repr_png_() == (tmp_path / "c.png").read_bytes()


def test_stats_are_the_cli_stats(luz, tmp_path):
    status, _, err = run_luz(["render", "demo:whitted", *SMALL, "--aa", "adaptive", "-o",
                              "c.png", "--stats", "s.json", "-q"], tmp_path)
    assert status == 0, err
    cli = json.loads((tmp_path / "s.json").read_text())
    stats = luz.render("demo:whitted", width=96, height=72, aa="adaptive").stats
    assert isinstance(stats, dict)
    assert stats.keys() == cli.keys()
    for key in ["scene", "width", "height", "pipeline", "model", "antialias", "rays",
                "intersection_tests", "pixels_refined", "samples", "triangles", "bvh_nodes",
                "accel", "bvh_bytes"]:
        assert stats[key] == cli[key], key
    assert stats["seconds"] > 0 and stats["peak_memory_bytes"] > 0


def test_image_is_a_float32_view_that_keeps_the_frame_alive(luz):
    import gc

    frame = luz.render("demo:primitives", width=48, height=36)
    img = frame.image
    assert img.dtype == np.float32 and img.shape == (36, 48, 3)
    assert img.strides == (48 * 12, 12, 4)
    assert not img.flags.owndata  # no copy: the frame's memory
    assert np.shares_memory(img, frame.image)
    copy = img.copy()
    del frame
    gc.collect()
    junk = [luz.render("demo:whitted", width=48, height=36).image.copy() for _ in range(3)]
    assert junk and same_bits(img, copy)


def test_scenes_and_materials_list_what_the_cli_lists(luz, tmp_path):
    _, out, _ = run_luz(["scenes"], tmp_path)
    names = [line.split()[0] for line in out.splitlines() if line.strip()]
    assert list(luz.scenes()) == names
    assert all(isinstance(d, str) and d for d in luz.scenes().values())
    _, out, _ = run_luz(["materials"], tmp_path)
    rows = [line.split() for line in out.splitlines()[1:] if line.strip()]
    mats = luz.materials()
    assert list(mats) == [r[0] for r in rows]
    for r in rows:
        m = mats[r[0]]
        assert m["alias"] == r[1]
        assert float(r[5]) == pytest.approx(m["n"])
        assert float(r[8]) == pytest.approx(m["ior"])
        assert len(m["kd"]) == 3
    for name in names:  # every listed scene loads
        luz.load(name)


def test_ray_tree_is_the_viewer_tree(luz):
    scene = luz.load("demo:whitted", set={"image.width": 320, "image.height": 240})
    tree = luz.ray_tree(scene, 160, 120)
    assert tree["pixel"] == [160, 120]
    assert tree["pipeline"] == "raytrace"
    nodes = tree["nodes"]
    assert nodes[0]["kind"] == "primary" and nodes[0]["parent"] == -1
    assert tree["colour"] == nodes[0]["colour"]
    # the tree's colour is the render's pixel (no antialiasing: the centre sample)
    frame = luz.render(scene)
    assert np.allclose(frame.image[120, 160], tree["colour"], rtol=0, atol=1e-6)
    # a zbuffer scene is traced as raycast
    zb = luz.ray_tree("demo:primitives", 400, 300)
    assert zb["traced_as_raycast"] is True
    # options as for render
    t2 = luz.ray_tree(scene, 10, 10, pipeline="raycast", width=20, height=20)
    assert t2["pipeline"] == "raycast"


def test_scene_object(luz):
    s = luz.load("demo:whitted")
    assert s.source == "demo:whitted" and s.name == "whitted"
    assert s.pipeline == "raytrace" and s.width > 0 and s.height > 0
    assert "demo:whitted" in repr(s)
    d = s.to_dict()
    assert d["render"]["pipeline"] == "raytrace"
    again = luz.load(d)
    assert same_bits(luz.render(again, width=40, height=30).image,
                     luz.render(s, width=40, height=30).image)


@pytest.mark.parametrize("aa", ["none", "grid", "adaptive"])
def test_region_is_the_cli_region_and_the_crop_of_the_whole(luz, tmp_path, aa):
    opts = SMALL + ["--aa", aa, "--set", 'render.antialias.filter="tent"']
    expected = cli_image(tmp_path, "demo:whitted", opts + ["--region", "10,20,70,41"])
    whole = luz.render("demo:whitted", width=96, height=72, aa=aa,
                       set={"render.antialias.filter": "tent"}, aov=["depth"])
    part = luz.render("demo:whitted", width=96, height=72, aa=aa,
                      set={"render.antialias.filter": "tent"}, aov=["depth"],
                      region=(10, 20, 70, 41))
    assert part.image.shape == (21, 60, 3)
    assert same_bits(part.image, expected)
    assert same_bits(part.image, whole.image[20:41, 10:70])
    assert same_bits(part.aov["depth"], whole.aov["depth"][20:41, 10:70])
    assert part.stats["region"] == [10, 20, 70, 41]
