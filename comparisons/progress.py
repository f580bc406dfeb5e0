"""Progress on standard error that keeps up without flooding a log: on a terminal one line,
rewritten in place; anywhere else (a file, a CI log) at most one line every `INTERVAL` seconds,
and none at all for a run shorter than that.  A line that must be read (a failure, a warning)
goes through `Progress.say`: printed whole on a line of its own, the live line drawn again
after it.  The stream is looked up when written to (``sys.stderr`` at that moment)."""
from __future__ import annotations

import sys
import time

#: seconds between two progress lines in a log (not a terminal)
INTERVAL = 5.0
#: seconds between two redraws of the live line on a terminal
REDRAW = 0.1


class Progress:
    """One progress line (see the module's docstring).

    Parameters
    ----------
    stream : file, optional
        Where to write (default: ``sys.stderr`` when written).
    interval : float, optional
        Seconds between lines when the stream is not a terminal (default `INTERVAL`).
    tty : bool, optional
        Whether to rewrite the line in place (default: ``stream.isatty()``).
    clock : callable
        Seconds, monotonic (a test's clock).
    """

    def __init__(self, stream=None, *, interval=None, tty=None, clock=time.monotonic):
        self._stream, self._tty, self.clock = stream, tty, clock
        self.interval = INTERVAL if interval is None else interval
        self.start = self._last = clock()
        self._live = ""      # the text on the terminal's live line ('' none)
        self._pending = ""   # the latest text not yet written to a log

    @property
    def stream(self):
        return self._stream if self._stream is not None else sys.stderr

    @property
    def tty(self):
        if self._tty is None:
            isatty = getattr(self.stream, "isatty", None)
            return bool(isatty and isatty())
        return self._tty

    def _write(self, text):
        self.stream.write(text)
        self.stream.flush()

    def update(self, text, *, final=False):
        """The state now.  A log gets it when `interval` has passed since the start or the last
        line; ``final`` (the last update of a run) also when the run lasted that long."""
        now = self.clock()
        if self.tty:
            if final or now - self._last >= REDRAW or not self._live:
                self._write(f"\r{text}\x1b[K")
                self._live, self._last = text, now
            return
        if now - self._last >= self.interval or (final and now - self.start >= self.interval):
            self._write(f"{text}\n")
            self._pending, self._last = "", now
        else:
            self._pending = text

    def say(self, text):
        """A line that must be read, whole and at once; the live line is drawn again after."""
        if self.tty and self._live:
            self._write(f"\r\x1b[K{text}\n{self._live}\x1b[K")
        else:
            self._write(f"{text}\n")

    def close(self):
        """End the live line on a terminal (the next output starts on a line of its own)."""
        if self.tty and self._live:
            self._write("\n")
            self._live = ""
