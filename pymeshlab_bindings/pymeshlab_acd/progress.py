"""A one-line progress bar for the filters. pymeshlab, when verbose, prints the filter's parameters and
MeshLab's progress callback ("LOG: 2 Decomposing: 7 parts ...    [ 43% ]") on the process's standard
error and output; while a filter runs, both file descriptors are read through a pipe and redrawn as one
line on the terminal's stderr. The filter's other log lines (summary, warnings) are passed on below it."""
import ctypes
import os
import re
import sys
import threading

_STEP = re.compile(r"^LOG: \d+ (.*?)\s+\[\s*(\d+)%\s*\]\s*$")


class ProgressBar:
    def __init__(self, ms, enabled=True, width=24):
        self.ms, self.enabled, self.width = ms, enabled, width
        self.last = ""

    def __enter__(self):
        if not self.enabled:
            return self
        sys.stdout.flush()
        sys.stderr.flush()
        self.saved = [os.dup(1), os.dup(2)]
        self.stream = os.fdopen(os.dup(2), "w")   # the real stderr, for the bar
        r, w = os.pipe()
        os.dup2(w, 1)
        os.dup2(w, 2)
        os.close(w)
        self.reader = threading.Thread(target=self._read, args=(r,), daemon=True)
        self.reader.start()
        self.ms.set_verbosity(True)
        return self

    def __exit__(self, *exc):
        if not self.enabled:
            return False
        self.ms.set_verbosity(False)
        sys.stdout.flush()
        sys.stderr.flush()
        try:
            ctypes.CDLL(None).fflush(None)   # what C still buffers goes into the pipe, not the terminal
        except (OSError, AttributeError):
            pass
        for fd, saved in ((1, self.saved[0]), (2, self.saved[1])):
            os.dup2(saved, fd)
            os.close(saved)
        self.reader.join(timeout=5)
        if self.last:
            self.stream.write("\n")
        self.stream.close()
        return False

    def _read(self, fd):
        with os.fdopen(fd, errors="replace") as f:
            for line in f:
                m = _STEP.match(line.rstrip("\n"))
                if m:
                    self._draw(int(m.group(2)), m.group(1))
                elif line.startswith("LOG:"):   # the filter's own messages; the parameter dump is dropped
                    self._note(line.split(" ", 2)[-1].strip())

    def _draw(self, pct, text):
        n = self.width * min(max(pct, 0), 100) // 100
        bar = f"[{'#' * n}{'.' * (self.width - n)}] {pct:3d}% {text}"[:100]
        self.stream.write("\r" + bar.ljust(len(self.last)))
        self.stream.flush()
        self.last = bar

    def _note(self, text):
        if self.last:
            self.stream.write("\n")
            self.last = ""
        self.stream.write(text + "\n")
        self.stream.flush()
