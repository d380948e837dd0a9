# Ctrl-C and the interpreter's exit while luz works: KeyboardInterrupt within a second while a
# scene loads, while its BVH builds and while a big frame is saved (nothing left behind); the
# interpreter exiting while a load or a render runs in another thread cancels and joins it, with
# no abort ("terminate called without an active exception") and its usual exit status.
import json
import os
import signal
import subprocess
import textwrap
import threading
import time

import pytest

from conftest import SOURCE_DIR

PYTHON = "/usr/bin/python3"  # Debian's, as CTest runs these tests


def seconds_to_interrupt(call, delay):
    """Runs call(), sending this process SIGINT `delay` seconds in; the seconds from the signal
    to the KeyboardInterrupt, or None when call() returned first."""
    sent = []

    def fire():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(delay, fire)
    timer.start()
    try:
        call()
    except KeyboardInterrupt:
        return time.monotonic() - sent[0]
    finally:
        timer.cancel()
        timer.join()
    if sent:  # the call ended just before the signal: let its KeyboardInterrupt pass here
        try:
            time.sleep(0.5)
        except KeyboardInterrupt:
            pass
    return None


def write_many_faces(path, faces):
    """An OBJ file of one triangle given `faces` times: seconds of reading for a few MB."""
    path.write_bytes(b"v 0 0 0\nv 1 0 0\nv 0 1 0\n" + b"f 1 2 3\n" * faces)


def scene_with(tmp_path, objects, pipeline="zbuffer"):
    scene = {"image": {"width": 32, "height": 24}, "render": {"pipeline": pipeline},
             "lights": [{"position": [0, 3, 3]}], "objects": objects}
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    return path


def test_ctrl_c_stops_a_long_load(luz, tmp_path):
    # 5 million faces: ~3 s of reading, checking and triangle building on this VM
    write_many_faces(tmp_path / "many.obj", 5_000_000)
    path = scene_with(tmp_path, [{"type": "mesh", "file": "many.obj"}])
    latency = seconds_to_interrupt(lambda: luz.load(path), 0.4)
    assert latency is not None, "the load ended before the interrupt"
    assert latency < 1.0, latency
    # and the module still works
    assert luz.load("demo:primitives").width > 0


def test_ctrl_c_stops_a_bvh_build(luz, tmp_path):
    # 300 bunnies, 1.1 million triangles: the first ray-traced render builds their BVH (seconds)
    bunny = str(SOURCE_DIR / "scenes" / "bunny.obj")
    objects = [{"type": "mesh", "file": bunny, "smooth": False,
                "transform": {"translate": [i % 20, (i // 20) % 20, i // 400]}}
               for i in range(300)]
    scene = luz.load(scene_with(tmp_path, objects, pipeline="raycast"))
    latency = seconds_to_interrupt(lambda: luz.render(scene), 0.3)
    assert latency is not None, "the BVH build ended before the interrupt"
    assert latency < 1.0, latency


def test_ctrl_c_stops_saving_a_big_frame_and_leaves_nothing(luz, tmp_path):
    # a plane over 2560² pixels: a fast render, then seconds of EXR compression
    frame = luz.render({"camera": {"projection": "perspective", "position": [0, 3, 0.5],
                                   "look_at": [0, 0, 0]},
                        "render": {"pipeline": "zbuffer"},
                        "lights": [{"position": [0.3, 0.5, 0.2], "intensity": 3}],
                        "objects": [{"type": "plane",
                                     "material": {"kd": 0.7, "ks": 0.4, "n": 7}}]},
                       width=2560, height=2560)
    out = tmp_path / "out"
    out.mkdir()
    latency = seconds_to_interrupt(lambda: frame.save(out / "big.exr"), 0.3)
    assert latency is not None, "the file was written before the interrupt"
    assert latency < 1.0, latency
    assert os.listdir(out) == []


# slow_teardown() keeps the interpreter finalizing for a while after its exit hooks, as a large
# program's teardown does: a cycle of an object whose __del__ sleeps, left to the collector,
# which runs once the interpreter is finalizing. A thread that wakes then and takes the GIL is
# ended by pthread_exit(), which aborts a C++ frame waiting for its worker.
SLOW_TEARDOWN = """
import os, sys, threading, time
import luz
class SlowTeardown:
    def __del__(self, sleep=time.sleep):
        sleep(0.3)
def slow_teardown():
    a = SlowTeardown()
    a.cycle = a
"""


def run_script(body):
    """Runs Debian's python3 on `body` (with this process's PYTHONPATH: the module under
    test); (exit status, stderr, seconds)."""
    start = time.monotonic()
    r = subprocess.run([PYTHON, "-c", textwrap.dedent(body)], capture_output=True, text=True,
                       timeout=120)
    return r.returncode, r.stderr, time.monotonic() - start


RENDER = 'luz.render("demo:whitted", width=1600, height=1200, aa="grid", samples=64)'


@pytest.mark.parametrize("work", ["render", "load"])
def test_interpreter_exit_cancels_and_joins_work_in_a_daemon_thread(tmp_path, work):
    write_many_faces(tmp_path / "many.obj", 5_000_000)
    path = scene_with(tmp_path, [{"type": "mesh", "file": "many.obj"}])
    call = RENDER if work == "render" else f"luz.load({str(path)!r})"
    status, err, seconds = run_script(SLOW_TEARDOWN + textwrap.dedent(f"""
        threading.Thread(target=lambda: {call}, daemon=True).start()
        time.sleep(0.5)
        slow_teardown()
        sys.exit(3)
    """))
    assert "terminate called" not in err, err
    assert status == 3, err
    assert err == ""
    assert seconds < 5, seconds


@pytest.mark.parametrize("daemon", [False, True])
def test_ctrl_c_while_the_main_thread_joins_a_rendering_thread(daemon):
    status, err, seconds = run_script(SLOW_TEARDOWN + textwrap.dedent(f"""
        import signal
        t = threading.Thread(target=lambda: {RENDER}, daemon={daemon})
        t.start()
        threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
        slow_teardown()
        t.join()
    """))
    assert "terminate called" not in err, err
    # KeyboardInterrupt in the main thread: Python ends by SIGINT, as for any script
    assert status == -signal.SIGINT, err
    assert err.rstrip().endswith("KeyboardInterrupt"), err
    assert seconds < 10, seconds


def test_work_asked_for_after_the_exit_hook_is_refused():
    # exit hooks run last registered first: this one, registered before luz's, runs after it
    status, err, _ = run_script("""
        import atexit, sys
        def late():
            import luz
            try:
                luz.render("demo:primitives", width=8, height=8)
                print("rendered", file=sys.stderr)
            except RuntimeError as e:
                print("refused:", e, file=sys.stderr)
        atexit.register(late)
        import luz
    """)
    assert status == 0, err
    assert err == "refused: luz: the interpreter is exiting\n", err
