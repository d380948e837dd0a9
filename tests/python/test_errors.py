# Bad input through the module: a bad scene (file or dict) raises luz.SceneError, a ValueError,
# with the command line's one-line message; a wrong argument type raises TypeError and a bad
# value ValueError, naming the argument. The malformed-input corpus and the fuzzers' findings
# are replayed: each loads or raises SceneError, and nothing crashes.
import json
import shutil
import warnings

import pytest

from conftest import CORPUS, run_luz


def cli_error(tmp_path, scene, args=()):
    status, _, err = run_luz(["render", str(scene), *args, "-o", "o.png", "-q"], tmp_path)
    assert status == 2, err
    return err.rstrip("\n")


def test_scene_error_is_a_value_error(luz):
    assert issubclass(luz.SceneError, ValueError)
    assert luz.SceneError.__module__ == "luz"
    assert issubclass(luz.SceneWarning, UserWarning)


def test_missing_file(luz, tmp_path):
    with pytest.raises(luz.SceneError) as e:
        luz.load(str(tmp_path / "nope.json"))
    assert str(e.value) == cli_error(tmp_path, tmp_path / "nope.json")
    assert "nope.json: cannot read" in str(e.value)


def test_folder_and_unknown_demo(luz, tmp_path):
    with pytest.raises(luz.SceneError, match="is a directory"):
        luz.load(tmp_path)
    with pytest.raises(luz.SceneError) as e:
        luz.render("demo:nothing")
    assert str(e.value) == cli_error(tmp_path, "demo:nothing")


def test_broken_json(luz, tmp_path):
    (tmp_path / "b.json").write_text('{"objects": [\n  {"type": "sphere",}\n]}')
    with pytest.raises(luz.SceneError) as e:
        luz.load(str(tmp_path / "b.json"))
    assert str(e.value) == cli_error(tmp_path, tmp_path / "b.json")
    assert ":2:" in str(e.value) and "JSON syntax error" in str(e.value)


def test_unknown_key_in_a_dict(luz):
    with pytest.raises(luz.SceneError) as e:
        luz.load({"objetcs": []})
    assert str(e.value).startswith("<dict>: objetcs: unknown key")


def test_negative_radius_in_a_dict(luz):
    with pytest.raises(luz.SceneError) as e:
        luz.load({"objects": [{"type": "sphere", "radius": -1}]})
    assert str(e.value) == "<dict>: objects.0.radius: must be > 0, got -1"


def test_bad_values_name_the_option_as_the_cli_does(luz, tmp_path):
    cases = [({"width": -1}, ["--width=-1"]),
             ({"height": 0}, ["--height", "0"]),
             ({"pipeline": "rasterize"}, ["--pipeline", "rasterize"]),
             ({"model": "blinn"}, ["--model", "blinn"]),
             ({"aa": "fxaa"}, ["--aa", "fxaa"]),
             ({"samples": 3}, ["--samples", "3"]),
             ({"threshold": -0.5}, ["--threshold=-0.5"]),
             ({"max_depth": 1000}, ["--max-depth", "1000"]),
             ({"width": 10 ** 30}, ["--width", str(10 ** 30)]),
             ({"set": {"objects.0.radius": -2}}, ["--set=objects.0.radius=-2"]),
             ({"set": {"objects.0.nope": 1}}, ["--set", "objects.0.nope=1"]),
             ({"set": {"": 1}}, ["--set", "=1"])]
    for kwargs, args in cases:
        with pytest.raises(luz.SceneError) as e:
            luz.render("demo:whitted", **kwargs)
        assert isinstance(e.value, ValueError)
        assert str(e.value) == cli_error(tmp_path, "demo:whitted", args), kwargs
    with pytest.raises(ValueError, match="width"):
        luz.render("demo:whitted", width=-1)


def test_wrong_types_raise_type_error_naming_the_argument(luz):
    cases = [dict(width="800"), dict(width=320.0), dict(width=True), dict(height=[1]),
             dict(max_depth=1.5), dict(samples="4"), dict(pipeline=3), dict(model=1),
             dict(aa=b"grid"), dict(threshold="0.1"), dict(threshold=True), dict(threads=1.0),
             dict(threads="2"), dict(aov=3), dict(aov=[1, 2]), dict(set=["a=1"]),
             dict(set={1: 2}), dict(set={"ambient": 1j}), dict(progress="yes")]
    for kwargs in cases:
        (name,) = kwargs
        with pytest.raises(TypeError, match=name):
            luz.render("demo:primitives", **kwargs)
    for bad in [42, None, 1.5, ["demo:whitted"], object()]:
        with pytest.raises(TypeError, match="scene"):
            luz.load(bad)
        with pytest.raises(TypeError, match="scene"):
            luz.render(bad)
    with pytest.raises(TypeError, match="keys must be str"):
        luz.load({"objects": [{1: "sphere"}]})
    with pytest.raises(TypeError, match="objects.0.radius"):
        luz.load({"objects": [{"type": "sphere", "radius": object()}]})
    with pytest.raises(TypeError):
        luz.render("demo:primitives", 320)  # keywords only
    with pytest.raises(TypeError):
        luz.render("demo:primitives", colour="red")
    with pytest.raises(TypeError, match="px"):
        luz.ray_tree("demo:primitives", 1.5, 2)
    with pytest.raises(TypeError, match="path"):
        luz.render("demo:primitives", width=8, height=8).save(3)


def test_bad_argument_values(luz, tmp_path):
    with pytest.raises(ValueError, match=r"threads: must be in \[0, 4096\], got -1"):
        luz.render("demo:primitives", width=8, height=8, threads=-1)
    with pytest.raises(ValueError) as e:
        luz.render("demo:primitives", width=8, height=8, aov=["diffuse", "difuse"])
    assert 'aov: unknown term "difuse"; valid: ambient, diffuse, specular' in str(e.value)
    assert "tests, all" in str(e.value)
    with pytest.raises(ValueError, match="aov"):
        luz.render("demo:primitives", width=8, height=8, aov="bogus")
    with pytest.raises(ValueError, match=r"region \(0, 0, 9, 4\): outside the 8x8 image"):
        luz.render("demo:primitives", width=8, height=8, region=(0, 0, 9, 4))
    with pytest.raises(ValueError, match=r"region \(4, 0, 4, 4\): the region is empty"):
        luz.render("demo:primitives", width=8, height=8, region=[4, 0, 4, 4])
    for bad in ["0,0,4,4", (0, 0, 4), (0, 0, 4.0, 4), 7, (0, 0, True, 4)]:
        with pytest.raises(TypeError, match="region: expected a sequence of four ints"):
            luz.render("demo:primitives", width=8, height=8, region=bad)
    with pytest.raises(ValueError, match="px"):
        luz.ray_tree("demo:primitives", 800, 10)
    with pytest.raises(ValueError, match="py"):
        luz.ray_tree("demo:primitives", 0, -1)
    frame = luz.render("demo:primitives", width=8, height=8)
    with pytest.raises(luz.SceneError, match="unknown image format"):
        frame.save(tmp_path / "x.bmp")
    with pytest.raises(luz.SceneError, match="does not exist"):
        frame.save(tmp_path / "no" / "x.png")
    assert list(tmp_path.iterdir()) == []


def test_numbers_json_cannot_hold(luz):
    with pytest.raises(luz.SceneError, match=r"<dict>: objects.0.radius: not a JSON number: nan"):
        luz.load({"objects": [{"type": "sphere", "radius": float("nan")}]})
    with pytest.raises(luz.SceneError, match="--set ambient: not a JSON number: inf"):
        luz.load("demo:primitives", set={"ambient": float("inf")})
    with pytest.raises(ValueError, match="threshold"):
        luz.render("demo:whitted", threshold=float("nan"))


def test_self_containing_and_deep_dicts_end(luz):
    d = {"objects": []}
    d["objects"].append(d)
    with pytest.raises(luz.SceneError, match="nested deeper than 64 levels"):
        luz.load(d)
    deep = {"objects": [{"type": "sphere"}]}
    node = deep
    for _ in range(100):
        node["x"] = {}
        node = node["x"]
    with pytest.raises(luz.SceneError, match="nested deeper"):
        luz.load(deep)


def test_paths_and_keys_with_a_nul_are_bad_input(luz, tmp_path):
    # the operating system would stop at the NUL: "d/a\0b.png" would write "d/a"
    (tmp_path / "d").mkdir()
    frame = luz.render("demo:primitives", width=8, height=6)
    with pytest.raises(ValueError, match="path: the path contains a NUL character"):
        frame.save(str(tmp_path / "d" / "a\0b.png"))
    assert list((tmp_path / "d").iterdir()) == []
    (tmp_path / "a").write_text('{"objects": [{"type": "sphere"}]}')
    with pytest.raises(ValueError, match="cannot read: the path contains a NUL character"):
        luz.load(str(tmp_path / "a\0b"))
    # in a dict: the key and the reason, at its line:column
    with pytest.raises(luz.SceneError, match=r'<dict>:1:2: key "objects\\u0000": a NUL'):
        luz.load({"objects\0": []})
    with pytest.raises(luz.SceneError, match=r'string "bunny.obj\\u0000x": a NUL'):
        luz.load({"objects": [{"type": "mesh", "file": "bunny.obj\0x"}]})


def test_long_values_are_shortened_in_messages(luz):
    with pytest.raises(luz.SceneError) as e:
        luz.load({"objects": [{"type": "a" * 10485760}]})
    assert '"' + "a" * 40 + '\u2026" (10485760 characters)' in str(e.value)
    assert len(str(e.value)) < 300


def test_warnings_are_scene_warnings(luz, tmp_path):
    (tmp_path / "w.obj").write_text("mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    (tmp_path / "w.json").write_text(json.dumps(
        {"image": {"width": 16, "height": 12}, "objects": [{"type": "mesh", "file": "w.obj"}]}))
    with pytest.warns(luz.SceneWarning, match="missing.mtl"):
        scene = luz.load(tmp_path / "w.json")
    assert any("missing.mtl" in w for w in scene.warnings)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        luz.render(scene, width=16)  # a derived scene repeats no warning


def corpus_cases():
    cases = []
    for line in (CORPUS / "expected.tsv").read_text().splitlines():
        if not line or line.startswith("#"):
            continue
        file, status, fragment = line.split("\t", 2)
        cases.append((file, int(status), fragment))
    return cases


@pytest.mark.parametrize("file,status,fragment", corpus_cases(),
                         ids=[c[0] for c in corpus_cases()])
def test_corpus_gives_the_cli_message(luz, tmp_path, file, status, fragment):
    source = CORPUS / file
    shutil.copy(source, tmp_path / source.name)
    scene = source.name
    if source.suffix == ".obj":
        for mtl in source.parent.glob("*.mtl"):
            shutil.copy(mtl, tmp_path / mtl.name)
        scene = "s.json"
        (tmp_path / scene).write_text(json.dumps(
            {"image": {"width": 64, "height": 48},
             "objects": [{"type": "mesh", "file": source.name}]}))
    code, _, err = run_luz(["render", scene, "-o", "out.png", "--quiet"], tmp_path)
    assert code == status
    import os
    cwd = os.getcwd()
    os.chdir(tmp_path)  # the CLI ran there: relative names in messages are the same
    try:
        if status == 2:
            with pytest.raises(luz.SceneError) as e:
                luz.render(scene, width=None)
            assert str(e.value) == err.rstrip("\n")
            assert fragment in str(e.value)
        else:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                luz.render(scene)
            messages = [str(w.message) for w in caught
                        if issubclass(w.category, luz.SceneWarning)]
            assert messages and "luz: warning: " + messages[0] == err.splitlines()[0]
    finally:
        os.chdir(cwd)


def test_fuzz_findings_load_or_raise_scene_error(luz, tmp_path):
    found = 0
    for f in sorted((CORPUS / "fuzz").glob("*/*")):
        found += 1
        data = f.read_bytes()
        if f.parent.name == "obj":
            # fuzz/fuzz_obj_loader.cpp: OBJ text, then optionally "\n#MTL\n" and what every
            # mtllib file reads as
            obj, sep, mtl = data.partition(b"\n#MTL\n")
            (tmp_path / "fuzz.obj").write_bytes(obj + (b"\n" if sep else b""))
            for line in obj.splitlines():
                words = line.split()
                if len(words) >= 2 and words[0] == b"mtllib" and sep:
                    for name in words[1:]:
                        safe = name.replace(b"/", b"_").replace(b"\0", b"_") or b"x"
                        if safe not in (b".", b".."):
                            (tmp_path / safe.decode(errors="replace")).write_bytes(mtl)
            scene = {"image": {"width": 16, "height": 12},
                     "objects": [{"type": "mesh", "file": str(tmp_path / "fuzz.obj")}]}
        else:
            (tmp_path / "fuzz.json").write_bytes(data)
            scene = str(tmp_path / "fuzz.json")
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                s = luz.load(scene)
                luz.render(s, width=16, height=12, pipeline="raytrace")
        except luz.SceneError as e:
            assert str(e)
    assert found >= 1
