"""The bar luz.render(progress=True) draws: tqdm's when tqdm imports, else a line on
sys.stderr. Called from the thread that called render(), never from the render's threads.

tqdm's text bar, in a terminal and in a notebook alike: its notebook widget (tqdm.auto) needs
ipywidgets 7 or later, and Debian 12 ships ipywidgets 6."""

import sys
import time


class Bar:
    """Call with the fraction done (0..1); close() when the render ends."""

    def __init__(self):
        self._done = 0
        self._drawn = False
        self._start = time.monotonic()
        try:
            from tqdm import tqdm
        except ImportError:
            self._tqdm = None
        else:
            self._tqdm = tqdm(total=100, desc="luz", unit="%", leave=True,
                              bar_format="{l_bar}{bar}| {n:.0f}% [{elapsed}<{remaining}]")

    def __call__(self, fraction):
        percent = max(0, min(100, int(fraction * 100)))
        if self._tqdm is not None:
            if percent > self._done:
                self._tqdm.update(percent - self._done)
                self._done = percent
            return
        if percent == self._done and percent != 0:
            return
        self._done = percent
        self._drawn = True
        width = 30
        filled = width * percent // 100
        elapsed = time.monotonic() - self._start
        sys.stderr.write("\rluz [%s%s] %3d%%  %.1fs" % ("#" * filled, "-" * (width - filled),
                                                       percent, elapsed))
        sys.stderr.flush()

    def close(self):
        if self._tqdm is not None:
            self._tqdm.close()
            self._tqdm = None
        elif self._drawn:
            sys.stderr.write("\n")
            sys.stderr.flush()
            self._drawn = False
