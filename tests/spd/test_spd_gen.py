# bench/spd_gen.py against the SPD's own output: at the default size factor its NFF is byte for
# byte scenes/spd/NAME.nff (the SPD generator's), and other sizes give the SPD's object counts.
import collections
import os
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(os.environ.get("LUZ_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
GEN = ROOT / "bench" / "spd_gen.py"


def generate(tmp_path, scene, size=None):
    args = [sys.executable, str(GEN), scene] + ([str(size)] if size is not None else [])
    subprocess.run(args + ["--out", str(tmp_path)], check=True)
    return (tmp_path / f"{scene}.nff").read_text(), (tmp_path / f"{scene}.pov").read_text()


@pytest.mark.parametrize("scene", ["balls", "rings", "tree"])
def test_default_size_is_the_spd_file(tmp_path, scene):
    nff, pov = generate(tmp_path, scene)
    assert nff == (ROOT / "scenes" / "spd" / f"{scene}.nff").read_text()
    # the SPD's .pov files: ../shared/spd beside the repository (as bench/spd.sh looks)
    for spd in (ROOT.parent / "shared" / "spd", pathlib.Path("/work/shared/spd")):
        if (spd / f"{scene}.pov").exists():
            assert pov == (spd / f"{scene}.pov").read_text()
            break


def kinds(nff):
    return collections.Counter(line.split()[0] for line in nff.splitlines() if line[:2] in
                               ("s ", "c ", "p "))


@pytest.mark.parametrize("scene,size,spheres,cylinders", [
    ("balls", 3, 820, 0), ("balls", 5, 66430, 0),  # sum of 9^n, n = 0..SF
    ("rings", 5, 1650, 1650), ("rings", 10, 11550, 11550),  # 5·SF·(SF+1)·(2·SF+1)
    ("tree", 12, 8191, 8191), ("tree", 14, 32767, 32767),  # 2^(SF+1) − 1
])
def test_sizes_give_the_spd_counts(tmp_path, scene, size, spheres, cylinders):
    nff, pov = generate(tmp_path, scene, size)
    k = kinds(nff)
    assert (k["s"], k["c"], k["p"]) == (spheres, cylinders, 1)
    assert pov.count("\nsphere {") == spheres and pov.count("\ncone {") == cylinders
