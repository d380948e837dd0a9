# luz.render(progress=True)'s bar says what `luz render`'s says: the share with decimals below
# 10 % and the time left as soon as a pixel is done, with tqdm and without; on a scene whose
# pixels take seconds it shows three different lines within the first 6 seconds.
import _thread
import sys
import threading
import time

import pytest

from conftest import SOURCE_DIR


@pytest.mark.parametrize("kind", ["tqdm", "plain"])
def test_decimals_below_ten_percent_and_time_left_from_the_first_pixel(luz, kind, monkeypatch,
                                                                      capsys):
    if kind == "plain":
        monkeypatch.setitem(sys.modules, "tqdm", None)  # `from tqdm import tqdm` fails
    from luz._progress import Bar
    bar = Bar()  # made here, not in a fixture: tqdm keeps the sys.stderr it finds
    bar(1 / 76800)  # one pixel of 320×240
    assert bar.status.startswith("0.00%  ETA ") and "--" not in bar.status, bar.status
    bar(0.004)
    assert bar.status.startswith("0.40%  ETA "), bar.status
    bar(0.042)
    assert bar.status.startswith("4.2%  ETA "), bar.status
    bar(0.42)
    assert bar.status.startswith(" 42%  ETA "), bar.status
    bar(1.0)
    assert bar.status.startswith("100%  done in "), bar.status
    bar.close()
    err = capsys.readouterr().err
    for words in ["0.40%  ETA ", "4.2%  ETA ", " 42%  ETA ", "100%  done in "]:
        assert words in err, err


def test_the_words_are_luz_renders(luz):
    from luz._luz import _progress_status
    assert _progress_status(0.004, 1.0) == "0.40%  ETA 4m09s"
    assert _progress_status(0.0, 5.0) == "0.00%  ETA --"


def test_a_heavy_scene_shows_three_lines_within_six_seconds(luz):
    from luz._progress import Bar
    bar = Bar()
    seen = []
    start = time.monotonic()

    class Enough(Exception):
        pass

    def progress(fraction):
        bar(fraction)
        if fraction > 0 and time.monotonic() - start <= 6 and bar.status not in seen:
            seen.append(bar.status)
        if len(seen) >= 3 or time.monotonic() - start > 6:
            raise Enough

    # progress is called only when it moves: a render that never moves is interrupted
    timer = threading.Timer(10, _thread.interrupt_main)
    timer.start()
    try:
        with pytest.raises(Enough):
            luz.render(str(SOURCE_DIR / "scenes" / "exploding_glass.json"), progress=progress)
    except KeyboardInterrupt:
        pass  # reported below: fewer than three lines
    finally:
        timer.cancel()
        bar.close()
    assert len(seen) >= 3, seen
    assert not any("ETA --" in s for s in seen), seen  # the time left once a pixel is done
