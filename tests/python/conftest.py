# Shared helpers of the Python module's tests: the `luz` binary to compare with (LUZ_BINARY, set
# by CTest), running it, and reading the PFM files it writes (raw float pixels).
import os
import pathlib
import subprocess

import numpy as np
import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("LUZ_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))
LUZ_BINARY = os.environ.get("LUZ_BINARY", str(SOURCE_DIR / "build" / "release" / "luz"))
CORPUS = SOURCE_DIR / "tests" / "corpus"


def run_luz(args, cwd):
    """Runs `luz ARGS` in `cwd`; returns (exit status, stdout, stderr)."""
    r = subprocess.run([LUZ_BINARY, *args], cwd=cwd, capture_output=True, timeout=300)
    return r.returncode, r.stdout.decode(errors="replace"), r.stderr.decode(errors="replace")


def read_pfm(path):
    """A colour PFM file (luz writes PF, little-endian, rows bottom-up) as (h, w, 3) float32,
    row 0 on top."""
    data = pathlib.Path(path).read_bytes()
    fields = []
    pos = 0
    while len(fields) < 4:
        # the header: "PF", width, height, scale, separated by whitespace
        while data[pos:pos + 1].isspace():
            pos += 1
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end].decode())
        pos = end
    pos += 1  # the one whitespace byte before the pixels
    assert fields[0] == "PF"
    w, h, scale = int(fields[1]), int(fields[2]), float(fields[3])
    dtype = "<f4" if scale < 0 else ">f4"
    pixels = np.frombuffer(data, dtype=dtype, count=w * h * 3, offset=pos).reshape(h, w, 3)
    return pixels[::-1].astype(np.float32)


def cli_image(tmp_path, scene, args=()):
    """The float image `luz render SCENE ARGS -o out.pfm` writes."""
    out = tmp_path / "cli.pfm"
    status, _, err = run_luz(["render", str(scene), *args, "-o", str(out), "--quiet"], tmp_path)
    assert status == 0, err
    return read_pfm(out)


def same_bits(a, b):
    """True when the two float arrays hold the very same bits (so -0 ≠ 0, NaN = NaN)."""
    a = np.ascontiguousarray(a, dtype=np.float32)
    b = np.ascontiguousarray(b, dtype=np.float32)
    return a.shape == b.shape and np.array_equal(a.view(np.uint32), b.view(np.uint32))


@pytest.fixture(scope="session")
def luz():
    import luz as module
    return module
