"""The one progress bar of gearkit: on stderr, for work that can take over a second.

A loop that may be long wraps itself in a :class:`Progress` and reports how far it is::

    with Progress("contact", steps, unit="steps") as bar:
        for k in range(steps):
            ...
            bar.update(k + 1)

Whether a bar is drawn is decided once, by the command line (:attr:`Progress.mode`): ``"off"`` (the
library's default: a program that calls gearkit sees nothing on its stderr), ``"auto"`` (the ``gearkit``
command: a bar when stderr is a terminal) or ``"on"`` (``gearkit --progress``: also to a pipe or file).
A bar appears only once its work has run :attr:`Progress.delay` seconds (quick runs stay quiet), redraws
at most ten times a second, ends with its final state (complete, unless the work raised) and a newline, and only the outermost of nested
bars draws: a bar opened inside it moves it within its current step (a scene's bar of meshes advances
while one mesh's contact runs). When off, ``update`` is one attribute test: nothing worth measuring per step. Standard
library only (the gear and check paths import nothing for it).

Examples
--------
>>> import io
>>> out = io.StringIO()
>>> with Progress("cells", 4, unit="cells", enabled=True, stream=out, delay=0.0) as bar:
...     for k in range(4):
...         bar.update(k + 1)
>>> out.getvalue().rsplit("\\r", 1)[-1].split(",")[0]
'cells [##############################] 4/4 cells'
>>> out.getvalue().endswith("\\n")
True
>>> with Progress("quiet", 4) as bar:  # the library default: off
...     bar.update(4)
>>> bar.enabled, bar.done
(False, 4)
"""
from __future__ import annotations

import sys
import time

__all__ = ["Progress", "line_break"]


class Progress:
    """A progress bar ``label [#####     ] done/total unit, elapsed s, eta s`` on stderr.

    Parameters
    ----------
    label : str
        What is running (e.g. ``"contact"``, ``"atlas"``).
    total : int
        Steps of the whole work (at least 1).
    unit : str
        Name of a step shown after the count (``"cells"``, ``"steps"``); empty: a percentage.
    enabled : bool or None
        Draw or not; None: as :attr:`mode` says.
    stream : file or None
        Where to draw (default ``sys.stderr``, looked up when the bar starts).
    delay : float or None
        Seconds of work before the first draw (default :attr:`Progress.delay`).
    """

    #: "off" (library default), "auto" (a terminal only: the gearkit command) or "on" (--progress)
    mode = "off"
    #: seconds of work before a bar appears
    delay = 0.5
    #: redraw interval, seconds
    interval = 0.1
    #: characters of the bar
    width = 30
    _depth = 0  # bars open in this process: only the outermost draws
    _drawing = None  # the outermost bar, while it is open and enabled
    _closed = None  # the stream whose line the last bar drawn has ended (its cursor is at a line's start)

    def __init__(self, label: str, total: int, *, unit: str = "", enabled: bool | None = None, stream=None,
                 delay: float | None = None):
        self.label, self.total, self.unit, self.done = label, max(int(total), 1), unit, 0
        self.note = ""  # shown after the bar: what runs now (e.g. the bench's section)
        self.stream = sys.stderr if stream is None else stream
        if enabled is None:
            enabled = self.mode == "on" or (self.mode == "auto" and _is_terminal(self.stream))
        self.enabled = bool(enabled) and Progress._depth == 0
        # a bar right inside a drawn one moves that one within its step (deeper bars are not seen)
        self._outer = Progress._drawing if Progress._depth == 1 else None
        self._within = 0.0  # the part of the current step a bar inside this one has done
        self.delay = Progress.delay if delay is None else float(delay)
        self.drawn, self._tty, self._shown = False, False, None
        self._t0 = self._next = 0.0

    def __enter__(self) -> "Progress":
        Progress._depth += 1
        if self.enabled:
            Progress._drawing = self
        self._t0 = time.monotonic()
        self._next = self._t0 + self.delay
        self._tty = self.enabled and _is_terminal(self.stream)
        return self

    def __exit__(self, *exc) -> bool:
        Progress._depth -= 1
        if Progress._drawing is self:
            Progress._drawing = None
        if self.drawn:
            if exc[0] is None:  # the work is done: the last line says so
                self.done = max(self.done, self.total)
                if self._shown != self.done:
                    self._draw(time.monotonic())
            self.stream.write("\n")
            self.stream.flush()
            Progress._closed = self.stream
        return False

    @classmethod
    def forget(cls) -> None:
        """For a worker process forked while a bar was open: that bar (copied into the worker) is the
        parent's, so bars opened here neither move it nor draw their own (the parent draws the work's
        one bar)."""
        cls.mode, cls._depth, cls._drawing = "off", 0, None

    def update(self, done: int) -> None:
        """``done`` of the ``total`` steps are finished (redraws when due)."""
        self.done = done
        if self.enabled:
            self._within = 0.0
            now = time.monotonic()
            if now >= self._next:
                self._draw(now)
        elif self._outer is not None:
            self._outer._inner(done / self.total)

    def _inner(self, fraction: float) -> None:
        """A bar inside this one has done ``fraction`` of its work (of this bar's current step)."""
        self._within = min(max(fraction, 0.0), 1.0)
        now = time.monotonic()
        if now >= self._next:
            self._draw(now)

    def step(self, n: int = 1) -> None:
        """``n`` more steps are finished."""
        self.update(self.done + n)

    def _draw(self, now: float) -> None:
        self._next = now + self.interval
        self.drawn, self._shown = True, self.done
        Progress._closed = None
        frac = min(max((self.done + self._within) / self.total, 0.0), 1.0)
        k = int(self.width * frac)
        count = f"{self.done}/{self.total} {self.unit}" if self.unit else f"{100 * frac:3.0f}%"
        elapsed = now - self._t0
        eta = f", eta {elapsed * (1 - frac) / frac:.0f} s" if 0 < frac < 1 else ""
        note = f": {self.note}" if self.note else ""
        clear = "\x1b[K" if self._tty else ""  # a terminal: erase what a longer line left
        self.stream.write(f"\r{self.label} [{'#' * k}{' ' * (self.width - k)}] {count}, {elapsed:.1f} s{eta}{note}"
                          f"{clear}")
        self.stream.flush()


def line_break(stream=None) -> str:
    """What a last message on ``stream`` (default ``sys.stderr``) starts with after a Ctrl-C: ``"\\n"`` on a
    terminal, where the echoed ``^C`` (or a bar) holds the line, unless a bar has just ended it; ``""`` on a
    pipe or file, which has no echo (a blank line there is noise).

    >>> import io
    >>> line_break(io.StringIO())
    ''
    """
    stream = sys.stderr if stream is None else stream
    return "\n" if _is_terminal(stream) and Progress._closed is not stream else ""


def _is_terminal(stream) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):  # no isatty, or a closed stream
        return False
