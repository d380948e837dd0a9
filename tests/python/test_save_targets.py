# Frame.save goes through the CLI's output code: a symlink is written through, a file keeps its
# mode, a FIFO gets the bytes as a stream and stays a FIFO, a folder is refused untouched (as it
# was before).
import os
import stat
import threading

import pytest


def test_save_writes_through_a_symlink_and_keeps_the_mode(luz, tmp_path):
    frame = luz.render("demo:primitives", width=16, height=12)
    (tmp_path / "real.png").write_bytes(b"old")
    os.chmod(tmp_path / "real.png", 0o600)
    os.symlink("real.png", tmp_path / "link.png")
    frame.save(tmp_path / "link.png")
    assert (tmp_path / "link.png").is_symlink()
    assert (tmp_path / "real.png").read_bytes()[1:4] == b"PNG"
    assert stat.S_IMODE(os.stat(tmp_path / "real.png").st_mode) == 0o600
    assert sorted(os.listdir(tmp_path)) == ["link.png", "real.png"]


def test_save_streams_to_a_fifo(luz, tmp_path):
    frame = luz.render("demo:primitives", width=16, height=12)
    fifo = tmp_path / "out.ppm"
    os.mkfifo(fifo)
    got = []
    # a daemon: a save that replaced the FIFO would leave it waiting for ever
    reader = threading.Thread(target=lambda: got.append(open(fifo, "rb").read()), daemon=True)
    reader.start()
    frame.save(fifo)
    reader.join(timeout=10)
    assert got and got[0].startswith(b"P6\n16 12\n255\n")
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)


def test_save_to_a_folder_is_refused(luz, tmp_path):
    frame = luz.render("demo:primitives", width=16, height=12)
    (tmp_path / "x.png").mkdir()
    with pytest.raises(ValueError, match="is a folder"):
        frame.save(tmp_path / "x.png")
    assert list((tmp_path / "x.png").iterdir()) == []
