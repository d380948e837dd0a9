# Per-term images (docs/SCENES.md#terms) through the module: Frame.aov holds the terms asked for as numpy
# views over the frame's memory — colour terms and normal (h, w, 3), depth and tests (h, w) —
# and the colour terms add up to the image. (These need the render core to fill Frame::aovs.)
import numpy as np
import pytest

COLOUR_TERMS = ["ambient", "diffuse", "specular", "reflected", "refracted", "emitted"]


def test_asked_terms_are_arrays_of_the_right_shape(luz):
    frame = luz.render("demo:whitted", width=64, height=48, aov=["diffuse", "depth"])
    assert list(frame.aov) == ["diffuse", "depth"]
    diffuse, depth = frame.aov["diffuse"], frame.aov["depth"]
    assert diffuse.dtype == np.float32 and diffuse.shape == (48, 64, 3)
    assert depth.dtype == np.float32 and depth.shape == (48, 64)
    assert depth.strides == (64 * 12, 12)  # one channel of the RGB plane: no copy
    assert not depth.flags.owndata and not diffuse.flags.owndata
    assert (depth[np.isfinite(depth)] > 0).all()


def test_colour_terms_add_up_to_the_image(luz):
    for pipeline in ["zbuffer", "raycast", "raytrace"]:
        frame = luz.render("demo:whitted", width=64, height=48, pipeline=pipeline, aov="all")
        assert set(frame.aov) == set(COLOUR_TERMS + ["shadow", "depth", "normal", "tests"])
        total = sum(frame.aov[t].astype(np.float64) for t in COLOUR_TERMS)
        assert np.allclose(total, frame.image, rtol=1e-5, atol=1e-5), pipeline
        assert frame.aov["tests"].shape == (48, 64)


def test_no_terms_unless_asked(luz):
    assert luz.render("demo:primitives", width=16, height=12).aov == {}
    assert luz.render("demo:primitives", width=16, height=12, aov=[]).aov == {}


def test_terms_are_saved_next_to_the_image(luz, tmp_path):
    frame = luz.render("demo:primitives", width=32, height=24, aov=["diffuse", "depth"])
    frame.save(tmp_path / "x.png")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.depth.png", "x.diffuse.png",
                                                          "x.png"]
