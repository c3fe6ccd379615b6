"""The one progress bar of the package and of the ``arcus`` command: tqdm on stderr.

Every long job shows its stage, done/total and an ETA on a terminal, and nothing when
stderr is not one (a log, a pipe, CI) or when ``quiet`` is set.  The library reports a
job's progress as a fraction; tables and sweeps count tasks.
"""

import sys

from tqdm import tqdm

# Fractions are shown in per mille steps: fine enough for an ETA, coarse enough that a
# callback per batch does not redraw for nothing.
_STEPS = 1000


class Progress:
    """A bar for one stage: ``Progress("rendering double_bow")`` counts a fraction,
    ``Progress("phase tables", total=12, unit="table")`` counts items.

    As a library progress callback (``progress=bar``) it takes the fraction done and
    returns False (go on).  Use it as a context manager, or call :meth:`close`.
    """

    def __init__(self, stage, total=None, unit="", quiet=False):
        self._fraction = total is None
        fmt = ("{desc}: {percentage:3.0f}%|{bar}| [{elapsed}<{remaining}]" if self._fraction
               else "{desc}: {n_fmt}/{total_fmt} {unit}|{bar}| [{elapsed}<{remaining}]")
        # disable=None: shown on a terminal only.
        self._bar = tqdm(total=_STEPS if self._fraction else total, desc=stage, unit=unit, file=sys.stderr,
                         disable=True if quiet else None, bar_format=fmt, leave=False, dynamic_ncols=True)

    @property
    def shown(self):
        return not self._bar.disable

    def set_stage(self, stage):
        self._bar.set_description_str(stage, refresh=True)

    def fraction(self, done):
        """Moves a fraction bar to ``done`` in [0, 1]."""
        target = int(min(max(done, 0.0), 1.0) * _STEPS)
        if target > self._bar.n:
            self._bar.update(target - self._bar.n)

    def advance(self, count=1):
        """Counts ``count`` more items done."""
        self._bar.update(count)

    def __call__(self, done):
        self.fraction(done)
        return False

    def close(self):
        self._bar.close()

    def __enter__(self):
        return self

    def __exit__(self, *_):
        self.close()
