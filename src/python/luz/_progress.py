"""The bar luz.render(progress=True) draws: tqdm's when tqdm imports, else a line on
sys.stderr. Called from the thread that called render(), never from the render's threads.
Its words are `luz render`'s: "0.04%  ETA 3h05m" (decimals below 10 %, time left from the
first pixel on; luz._luz._progress_status).

tqdm's text bar, in a terminal and in a notebook alike: its notebook widget (tqdm.auto) needs
ipywidgets 7 or later, and Debian 12 ships ipywidgets 6."""

import sys
import time

from ._luz import _progress_status


class Bar:
    """Call with the fraction done (0..1); close() when the render ends."""

    def __init__(self):
        self._status = None
        self._drawn = False
        self._start = time.monotonic()
        try:
            from tqdm import tqdm
        except ImportError:
            self._tqdm = None
        else:
            # the share and the time left are luz's words (desc), not tqdm's whole percents
            self._tqdm = tqdm(total=1.0, leave=True, bar_format="luz |{bar}| {desc}")

    @property
    def status(self):
        """The words last shown, e.g. "4.2%  ETA 1m05s" (None before the first call)."""
        return self._status

    def __call__(self, fraction):
        fraction = max(0.0, min(1.0, float(fraction)))
        status = _progress_status(fraction, time.monotonic() - self._start)
        if status == self._status:
            return
        self._status = status
        if self._tqdm is not None:
            self._tqdm.n = fraction
            self._tqdm.set_description_str(status, refresh=False)
            self._tqdm.refresh()
            return
        self._drawn = True
        width = 30
        filled = int(width * fraction)
        sys.stderr.write("\rluz [%s%s] %s\033[K" % ("#" * filled, "-" * (width - filled), status))
        sys.stderr.flush()

    def close(self):
        if self._tqdm is not None:
            self._tqdm.close()
            self._tqdm = None
        elif self._drawn:
            sys.stderr.write("\n")
            sys.stderr.flush()
            self._drawn = False
