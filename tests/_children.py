"""Child Python processes for tests that send them signals (shared by the test modules).

A test that signals a child must not depend on how pytest itself was started. Started in the
background (``nohup``, ``setsid ... &``, a CI runner), a process inherits SIGINT *ignored*, and a
Python interpreter that starts with SIGINT ignored keeps it ignored: Ctrl-C would never reach
the child, whose long solve then runs on after the test has given up. So:

* every child sets its own SIGINT disposition: its script starts with
  ``signal.signal(SIGINT, signal.default_int_handler)`` (what an interactive ``python`` has),
  before it can print its "ready" line;
* every child runs in its own session and process group (``start_new_session``), gets SIGINT
  the way a terminal sends Ctrl-C (to its whole group), and
* is always killed with its whole group (SIGKILL) and reaped when the ``with`` block ends --
  after a failed assertion or a timeout too -- so no CPU-heavy process outlives its test.

Usage::

    with python_child(script, cwd=tmp_path) as child:   # returns once the child printed "ready"
        child.interrupt()                                # SIGINT to the child's group
        out, err = child.communicate(timeout=60)
"""

from __future__ import annotations

import os
import selectors
import signal
import subprocess
import sys
import textwrap
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Optional, Union

__all__ = ["CHILD_PROLOGUE", "Child", "python_child"]

#: Prepended to every child script: the SIGINT disposition of an interactive interpreter,
#: whatever the test run inherited.
CHILD_PROLOGUE = "import signal as _signal; _signal.signal(_signal.SIGINT, _signal.default_int_handler)\n"

#: Seconds a child may take to start and print its first line (imports on a loaded machine).
START_TIMEOUT = 120.0


class Child:
    """A running child process in its own process group; see :func:`python_child`."""

    def __init__(self, proc: subprocess.Popen[bytes]) -> None:
        self.proc = proc
        self._read = {"stdout": b"", "stderr": b""}  # read from the pipes before communicate()

    @property
    def pid(self) -> int:
        return self.proc.pid

    def read_line(self, timeout: float = START_TIMEOUT, stream: str = "stdout") -> str:
        """The next line the child writes to ``stream`` ("stdout" or "stderr"; without the
        newline); ``AssertionError`` if none comes within ``timeout`` seconds or the child exits
        first (with its stderr). What is read stays out of :meth:`communicate`'s result."""
        pipe = self.proc.stdout if stream == "stdout" else self.proc.stderr
        assert pipe is not None
        deadline = time.monotonic() + timeout
        fd = pipe.fileno()
        with selectors.DefaultSelector() as selector:
            selector.register(fd, selectors.EVENT_READ)
            while b"\n" not in self._read[stream]:
                left = deadline - time.monotonic()
                assert left > 0, f"no line on {stream} within {timeout:g} s; so far {self._read[stream]!r}"
                if not selector.select(left):
                    continue
                chunk = os.read(fd, 65536)
                if not chunk:
                    self.proc.wait(timeout=10)
                    raise AssertionError(
                        f"the child exited ({self.proc.returncode}) before writing a line on {stream}; "
                        f"read so far {self._read!r}, stderr {self._stderr_so_far()!r}"
                    )
                self._read[stream] += chunk
        line, self._read[stream] = self._read[stream].split(b"\n", 1)
        return line.decode()

    def _stderr_so_far(self) -> str:
        if self.proc.stderr is None or self.proc.poll() is None:
            return ""
        return self.proc.stderr.read().decode(errors="replace")

    def cpu_seconds(self) -> float:
        """CPU time (user + system, all threads) the child has used so far, from ``/proc``."""
        fields = Path(f"/proc/{self.pid}/stat").read_text().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")

    def wait_cpu(self, seconds: float, timeout: float = START_TIMEOUT) -> None:
        """Waits until the child has used ``seconds`` more CPU time than when called: work under
        way, however loaded the machine (a wall-clock sleep can end before the work starts).
        Falls back to a plain sleep where ``/proc`` does not exist."""
        if not Path(f"/proc/{self.pid}/stat").exists():  # pragma: no cover - not Linux
            time.sleep(seconds)
            return
        start, deadline = self.cpu_seconds(), time.monotonic() + timeout
        while self.cpu_seconds() - start < seconds:
            assert self.proc.poll() is None, "the child ended before using the CPU time waited for"
            assert time.monotonic() < deadline, f"the child did not use {seconds:g} s of CPU within {timeout:g} s"
            time.sleep(0.02)

    def interrupt(self) -> float:
        """Ctrl-C: SIGINT to the child's process group, as a terminal sends it. Returns the
        ``time.monotonic()`` just before sending."""
        assert self.proc.poll() is None, "the child ended before the signal"
        sent = time.monotonic()
        os.killpg(self.proc.pid, signal.SIGINT)
        return sent

    def communicate(self, timeout: float) -> tuple[str, str]:
        """The rest of stdout and stderr once the child has exited (``subprocess.TimeoutExpired``
        after ``timeout`` seconds; the ``with`` block then kills it)."""
        out, err = self.proc.communicate(timeout=timeout)
        text, errors = (self._read["stdout"] + out).decode(), (self._read["stderr"] + err).decode()
        self._read = {"stdout": b"", "stderr": b""}
        return text, errors

    def kill(self) -> None:
        """SIGKILL to the child's whole process group (its own children too); reaps the child."""
        try:
            os.killpg(self.proc.pid, signal.SIGKILL)
        except ProcessLookupError:  # the group is gone: every member has exited
            pass
        try:
            self.proc.communicate(timeout=30)  # reap, close the pipes
        except subprocess.TimeoutExpired:  # pragma: no cover - SIGKILL cannot be ignored
            pass


@contextmanager
def python_child(
    script: str, cwd: Union[str, Path], *, ready: Optional[str] = "ready", timeout: float = START_TIMEOUT
) -> Iterator[Child]:
    """Runs ``python -c script`` (dedented, after :data:`CHILD_PROLOGUE`) in ``cwd`` in a new
    session, waits for the line ``ready`` on its stdout (unless ``ready`` is ``None``) and yields
    it; the child and its process group are killed when the block ends, however it ends."""
    proc = subprocess.Popen(
        [sys.executable, "-c", CHILD_PROLOGUE + textwrap.dedent(script)],
        cwd=cwd,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        start_new_session=True,  # own session and process group: killpg reaches exactly the child's
    )
    child = Child(proc)
    try:
        if ready is not None:
            line = child.read_line(timeout)
            assert line.strip() == ready, (line, child._stderr_so_far())
        yield child
    finally:
        child.kill()
