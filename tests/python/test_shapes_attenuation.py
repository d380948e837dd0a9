# Truncated cones and the distance law through the module: a cone's apex_radius survives
# Scene.to_dict(), and set={"attenuation": …} changes phong's light term as `--set` does.
import numpy as np
import pytest

FRUSTUM = {"image": {"width": 40, "height": 30},
           "objects": [{"type": "cone", "radius": 1, "apex_radius": 0.4, "height": 1.5}]}


def test_frustum_apex_radius_is_in_the_dict(luz):
    scene = luz.load(FRUSTUM)
    cone = scene.to_dict()["objects"][0]
    assert cone["type"] == "cone" and cone["apex_radius"] == pytest.approx(0.4)
    again = luz.load(scene.to_dict())
    assert np.array_equal(luz.render(again).image, luz.render(scene).image)
    with pytest.raises(luz.SceneError, match="apex_radius: must be < radius"):
        luz.load({"objects": [{"type": "cone", "radius": 1, "apex_radius": 1}]})


def test_attenuation_law_changes_the_image_as_set_does(luz):
    scene = luz.load("demo:primitives")
    assert scene.to_dict()["attenuation"] == "linear"
    images = {law: luz.render(scene, width=48, height=36, set={"attenuation": law}).image
              for law in ["none", "linear", "inverse_square"]}
    assert np.array_equal(images["linear"], luz.render(scene, width=48, height=36).image)
    # demo:primitives' light is several units away: no distance term is brightest
    assert images["none"].mean() > images["linear"].mean() > images["inverse_square"].mean()
    with pytest.raises(luz.SceneError, match=r"attenuation=\"cubic\": unknown value"):
        luz.render(scene, width=8, height=6, set={"attenuation": "cubic"})
