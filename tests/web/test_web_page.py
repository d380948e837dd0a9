"""luz.html in headless Chromium from file:// (docs/WEB.md): it loads without a console error, gives
the pixels `luz render` gives, an edit changes the image as --set does, a bad scene shows the
CLI's message and keeps the last image, a click returns that pixel's ray tree.

Run by CTest (tests/CMakeLists.txt) with LUZ_WEB_HTML (the page) and LUZ_BINARY; skipped, saying
why, only when the page was not built (no emcc) or Chromium is absent.
"""
import base64
import io
import json
import os
import subprocess

import pytest

import browser

HTML = os.environ.get("LUZ_WEB_HTML", "")
LUZ = os.environ.get("LUZ_BINARY", "")

if not browser.chromium():
    pytest.skip("chromium is not installed (apt-get install chromium)", allow_module_level=True)
if not os.path.isfile(HTML):
    pytest.skip(f"luz.html was not built ({HTML or 'LUZ_WEB_HTML unset'}): needs Emscripten "
                "(apt-get install emscripten node-acorn)", allow_module_level=True)

from PIL import Image  # noqa: E402  (after the skips: only needed when the page runs)

SMALL = "&set=image.width=320&set=image.height=240"


@pytest.fixture
def page(request):
    fragment = getattr(request, "param", "scene=demo:whitted" + SMALL)
    b = browser.Browser("file://" + os.path.abspath(HTML) + "#" + fragment)
    b.wait_for("typeof luzPage === 'object'")
    b.evaluate("luzPage.idle()", timeout=120)
    yield b
    b.close()


def canvas(b):
    p = b.evaluate("luzPage.pixels()")
    rgba = base64.b64decode(p["rgba"])
    return Image.frombytes("RGBA", (p["width"], p["height"]), rgba).convert("RGB")


def luz_render(tmp_path, *args):
    out = tmp_path / "cli.png"
    subprocess.run([LUZ, "render", *args, "-o", str(out)], check=True)
    return Image.open(out).convert("RGB")


def differing(a, b):
    """(pixels that differ, largest difference of a channel)."""
    assert a.size == b.size
    pa, pb = a.tobytes(), b.tobytes()
    diff = [abs(x - y) for x, y in zip(pa, pb)]
    return sum(1 for i in range(0, len(diff), 3) if any(diff[i:i + 3])), max(diff)


def test_page_loads_without_console_error(page, tmp_path):
    assert page.evaluate("luzPage.error()") == ""
    assert page.errors() == []
    page.screenshot(str(tmp_path / "page.png"))


def test_whitted_same_pixels_as_luz_render(page, tmp_path):
    web = canvas(page)
    cli = luz_render(tmp_path, "demo:whitted", "--width", "320", "--height", "240")
    assert differing(web, cli) == (0, 0)


def test_edit_changes_image_as_set_does(page, tmp_path):
    before = canvas(page)
    page.evaluate("luzPage.set('lights.0.intensity', '[2, 0.5, 0.5]')")
    page.evaluate("luzPage.idle()", timeout=120)
    after = canvas(page)
    assert differing(before, after)[0] > 1000
    cli = luz_render(tmp_path, "demo:whitted", "--width", "320", "--height", "240",
                     "--set", "lights.0.intensity=[2, 0.5, 0.5]")
    assert differing(after, cli) == (0, 0)


def test_bad_scene_shows_the_cli_message_and_keeps_the_image(page, tmp_path):
    before = canvas(page)
    text = '{\n  "objects": [ {"type": "sphere", "radius": -1} ]\n}\n'
    page.evaluate(f"luzPage.files([{{name: 'bad.json', text: {json.dumps(text)}}}])")
    page.wait_for("luzPage.error() !== ''")
    (tmp_path / "bad.json").write_text(text)
    cli = subprocess.run([LUZ, "render", "bad.json", "-o", "x.png"], cwd=tmp_path,
                         capture_output=True, text=True)
    assert cli.returncode == 2
    message = page.evaluate("luzPage.error()")
    assert message.startswith("bad.json:")
    assert message in cli.stderr
    assert differing(before, canvas(page)) == (0, 0)
    assert not (tmp_path / "x.png").exists()
    # The menu names the scene still shown, and an edit goes on with that scene.
    assert page.evaluate("document.getElementById('scenes').value") == "demo:whitted"
    page.evaluate("luzPage.set('lights.0.intensity', '[2, 0.5, 0.5]')")
    page.evaluate("luzPage.idle()", timeout=120)
    assert page.evaluate("luzPage.error()") == ""
    assert differing(before, canvas(page))[0] > 1000


def test_click_returns_that_pixels_ray_tree(page):
    tree = json.loads(page.evaluate("luzPage.tree(210, 120)"))
    assert tree["pixel"] == [210, 120]
    nodes = tree["nodes"]
    assert nodes[0]["kind"] == "primary"
    # The glass sphere at the image's right: the ray tree goes on past the primary hit.
    assert any(n["kind"] in ("reflection", "refraction") for n in nodes)
