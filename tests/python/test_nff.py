# NFF scenes through the module (docs/SCENES.md#nff, §5): luz.load("x.nff") reads the file as `luz render`
# does — the same description and the same pixels, --set on its materials f1… — and bad NFF
# raises luz.SceneError with the CLI's FILE:LINE message.
import pytest

from conftest import SOURCE_DIR, cli_image, run_luz, same_bits

SMALL_NFF = SOURCE_DIR / "tests" / "scenes" / "nff" / "small.nff"


def test_load_reads_the_nff_description(luz):
    s = luz.load(str(SMALL_NFF))
    assert (s.width, s.height) == (48, 32)
    assert s.pipeline == "raytrace"
    d = s.to_dict()
    assert d["render"]["max_depth"] == 4
    assert d["camera"]["projection"] == "perspective"
    assert [m for m in d["materials"]][-3:] == ["f1", "f2", "f3"]
    assert d["materials"]["f1"]["kd"] == pytest.approx([0.72, 0.16, 0.16])
    assert len(d["lights"]) == 2
    assert d["lights"][0]["intensity"] == pytest.approx([2 ** -0.5] * 3)


def test_render_equals_cli_bit_for_bit(luz, tmp_path):
    expected = cli_image(tmp_path, SMALL_NFF, ["--set", "materials.f1.kd=[0,0,1]"])
    direct = luz.render(str(SMALL_NFF), set={"materials.f1.kd": [0, 0, 1]})
    assert same_bits(direct.image, expected)
    loaded = luz.load(str(SMALL_NFF), set={"materials.f1.kd": [0, 0, 1]})
    assert same_bits(luz.render(loaded).image, expected)


def test_bad_nff_raises_the_cli_message(luz, tmp_path):
    bad = tmp_path / "bad.nff"
    bad.write_text("v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 8 8\n"
                   "p 2\n0 0 0\n1 0 0\n")
    with pytest.raises(luz.SceneError) as e:
        luz.load(str(bad))
    status, _, err = run_luz(["render", str(bad)], tmp_path)
    assert status == 2
    assert str(e.value) in err
    assert "bad.nff:8: p: a polygon needs at least 3 vertices, got 2" in str(e.value)
