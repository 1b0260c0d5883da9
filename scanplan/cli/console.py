"""The terminal side of the command line: encodings, a closed pipe, -q/-v, progress.

- **Encodings.** Text goes out in the stream's own encoding. Where that encoding cannot
  show a character (``σ`` or ``×`` in cp1251, ``—`` in cp866, anything beyond ASCII in a
  C locale) the character is written as its ASCII stand-in (``sigma``, ``x``, ``-``) and,
  failing that, as ``?``: an error handler (:func:`fallback_handler`) is set on stdout and stderr
  (:func:`setup_streams`), so no report ever stops on an encoding.
- **A closed pipe.** When the reader of stdout goes away (``scanplan … | head``) the
  command stops quietly with exit code :data:`EXIT_PIPE` (141, as a program that the
  shell reports killed by SIGPIPE), printing nothing more (:func:`closed_pipe`).
- **Verbosity.** ``-q`` leaves only warnings and errors on stderr (no ``wrote FILE``
  lines, no progress); ``-v`` adds a line per project of a batch as it is done.
  :func:`info` prints a note unless quiet, :func:`detail` only when verbose.
- **Progress.** :class:`Progress` is click's progress bar (count, rate, time left) on
  stderr, shown only when stderr is a terminal and not quiet (:func:`shows_progress`);
  off a terminal nothing is drawn. A batch has one bar over its projects; one plan has a
  bar per long stage (the missions of every sortie, the reports, the files written),
  drawn by :class:`StageBar` from the stages the work reports (:mod:`scanplan.progress`).
"""

from __future__ import annotations

import codecs
import contextlib
import io
import os
import sys
import time
import unicodedata
from collections.abc import Iterable, Iterator
from typing import Any

import click

from .. import progress

__all__ = ["EXIT_PIPE", "FALLBACK", "Progress", "StageBar", "closed_pipe", "detail",
           "fallback_handler", "info", "set_verbosity", "setup_streams", "shows_progress",
           "stage_bars", "staged", "verbosity", "verbosity_options"]

EXIT_PIPE = 141
"""Exit code when stdout's reader has gone (128 + SIGPIPE)."""

FALLBACK = "scanplan-ascii"
"""The prefix of the codec error handlers (:func:`fallback_handler`) that write a character
the stream cannot encode as its ASCII stand-in, else ``?``."""

_ASCII = {
    "σ": "sigma", "Σ": "Sum", "×": "x", "·": "*", "−": "-", "–": "-", "—": "-", "…": "...",
    "≤": "<=", "≥": ">=", "≈": "~", "≠": "!=", "±": "+/-", "√": "sqrt", "°": " deg",
    "µ": "u", "μ": "u", "²": "2", "³": "3", "«": '"', "»": '"', "„": '"', "“": '"',
    "”": '"', "‘": "'", "’": "'", "→": "->", "←": "<-", "↑": "^", "↓": "v", "⁻¹": "^-1",
    "¹": "1", "⁰": "0", "₀": "0", "₁": "1", "₂": "2", "Δ": "D", "δ": "d", "φ": "phi",
    "λ": "lambda", "π": "pi", "∞": "inf", "\u00a0": " ", "\u202f": " ", "\u2009": " ",
    "№": "No.", "•": "*", "▲": "^", "▼": "v",
}


def _stand_in(char: str, encoding: str) -> str:
    """What to write for ``char`` in ``encoding``: its stand-in, its letters without
    accents, else ``?``."""
    bare = "".join(c for c in unicodedata.normalize("NFKD", char)
                   if not unicodedata.combining(c))
    for candidate in (_ASCII.get(char), bare):
        if candidate:
            try:
                candidate.encode(encoding)
            except (UnicodeEncodeError, LookupError):
                continue
            return candidate
    return "?"


def fallback_handler(encoding: str) -> str:
    """The name of the error handler for streams in ``encoding`` (registered on first use:
    a code-page codec reports itself as "charmap", so each encoding has its own)."""
    name = f"{FALLBACK}:{encoding}"
    try:
        codecs.lookup_error(name)
    except LookupError:
        def handler(exc: UnicodeError) -> tuple[str, int]:
            if not isinstance(exc, UnicodeEncodeError):
                raise exc
            text = exc.object[exc.start:exc.end]
            return "".join(_stand_in(c, encoding) for c in text), exc.end

        codecs.register_error(name, handler)
    return name


_state: dict[str, int] = {"verbosity": 0}


def set_verbosity(quiet: bool = False, verbose: int = 0) -> None:
    """-q (−1), default (0), -v (1 and more); the environment variable
    ``SCANPLAN_VERBOSITY`` carries it into a batch's worker processes."""
    level = -1 if quiet else int(verbose)
    _state["verbosity"] = level
    os.environ["SCANPLAN_VERBOSITY"] = str(level)


def verbosity() -> int:
    """The verbosity in force: −1 quiet, 0 default, ≥ 1 verbose."""
    env = os.environ.get("SCANPLAN_VERBOSITY")
    if env and env.lstrip("-").isdigit():
        return int(env)
    return _state["verbosity"]


def _quiet(ctx: click.Context, param: click.Parameter, value: bool) -> None:
    if value:
        set_verbosity(quiet=True)


def _verbose(ctx: click.Context, param: click.Parameter, value: int) -> None:
    if value and verbosity() >= 0:
        set_verbosity(verbose=value)


def verbosity_options(f: Any) -> Any:
    """``-q/--quiet`` and ``-v/--verbose`` on a command (before or after its name)."""
    f = click.option("-v", "--verbose", count=True, expose_value=False, callback=_verbose,
                     help="Say more on stderr: every file written (not one line per series of "
                     "missions), each project of a batch as it is done.")(f)
    return click.option("-q", "--quiet", is_flag=True, expose_value=False, callback=_quiet,
                        help="Only warnings and errors on stderr: no 'wrote FILE' lines, no "
                        "progress.")(f)


def info(line: str) -> None:
    """A note on stderr (``wrote FILE``), unless quiet."""
    if verbosity() >= 0:
        click.echo(line, err=True)


def detail(line: str) -> None:
    """A detail on stderr, only when verbose."""
    if verbosity() >= 1:
        click.echo(line, err=True)


def _fallback(stream: Any) -> None:
    """Set :data:`FALLBACK` on a text stream whose encoding is not a Unicode one."""
    if not isinstance(stream, io.TextIOWrapper):
        return
    encoding = codecs.lookup(stream.encoding or "ascii").name
    if encoding.startswith("utf") or (stream.errors or "").startswith(FALLBACK):
        return
    try:
        stream.reconfigure(errors=fallback_handler(encoding))
    except (ValueError, io.UnsupportedOperation):  # pragma: no cover - a closed stream
        pass


def setup_streams() -> None:
    """Make stdout and stderr write every character (:func:`fallback_handler`)."""
    _fallback(sys.stdout)
    _fallback(sys.stderr)


def closed_pipe() -> int:
    """After stdout's reader went away: point stdout at the null device (so that the
    interpreter's last flush says nothing) and return :data:`EXIT_PIPE`."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, io.UnsupportedOperation):  # not a real file: nothing to do
        pass
    return EXIT_PIPE


def shows_progress(stream: Any = None) -> bool:
    """Whether progress bars are drawn: on a terminal (``stream``, default stderr) and
    not quiet (``-q``); never off a terminal (a pipe, a file, a test runner)."""
    stream = sys.stderr if stream is None else stream
    try:
        tty = bool(stream.isatty())
    except (AttributeError, ValueError):  # no isatty, or a closed stream
        tty = False
    return verbosity() >= 0 and tty


class Progress:
    """click's progress bar on stderr — count, per cent, rate and time left — for work of
    ``total`` steps that runs longer than ``delay_s``; drawn only when stderr is a
    terminal and not quiet (off a terminal nothing is written).

    ``step(done)`` moves it; ``clear()`` wipes the bar before other stderr lines (the next
    step draws it again); ``close()`` ends it.
    """

    def __init__(self, total: int, label: str, unit: str = "", delay_s: float = 1.0) -> None:
        self.total, self.label, self.unit, self.delay_s = total, label, unit, delay_s
        self.start = time.monotonic()
        self.on = shows_progress() and total > 1
        self.bar: Any = None

    def _rate(self, done: int) -> str:
        elapsed = time.monotonic() - self.start
        return f"{done / elapsed:.1f} {self.unit}/s" if elapsed > 0 and done else ""

    def step(self, done: int) -> None:
        """``done`` of ``total`` steps are done."""
        if not self.on:
            return
        if self.bar is None:
            if time.monotonic() - self.start <= self.delay_s:
                return
            self.bar = click.progressbar(length=self.total, label=self.label,
                                         file=sys.stderr, show_pos=True, show_eta=True,
                                         item_show_func=lambda rate: rate)
            self.bar.__enter__()
        self.bar.update(done - self.bar.pos, self._rate(done))

    def clear(self) -> None:
        """Wipe the bar's line (other stderr lines follow)."""
        if self.bar is not None:
            sys.stderr.write("\r\x1b[K")
            sys.stderr.flush()

    def close(self) -> None:
        """End the bar (its line stays, with the final count)."""
        if self.bar is not None:
            self.bar.__exit__(None, None, None)
            self.bar = None


class StageBar:
    """A :class:`scanplan.progress.Listener` that draws each stage of one plan as a
    :class:`Progress` bar (its label, count, rate and time left), for a stage that runs
    longer than ``delay_s``; used with :func:`scanplan.progress.listening`."""

    def __init__(self, delay_s: float = 0.5) -> None:
        self.delay_s = delay_s
        self.bar: Progress | None = None
        self.done = 0

    def begin(self, label: str, total: int, unit: str) -> None:
        """A stage of ``total`` steps begins: a new bar (drawn once it is late)."""
        self.end()
        self.bar, self.done = Progress(total, label, unit, self.delay_s), 0

    def advance(self, steps: int) -> None:
        """``steps`` more steps of the stage are done."""
        if self.bar is not None:
            self.done = min(self.done + steps, self.bar.total)
            self.bar.step(self.done)

    def end(self) -> None:
        """The stage is over: its bar (if drawn) keeps its final line."""
        if self.bar is not None:
            self.bar.close()
            self.bar = None


@contextlib.contextmanager
def stage_bars() -> Iterator[None]:
    """Draw the stages of the work done within this block (:class:`StageBar`) when
    progress is shown (:func:`shows_progress`); otherwise nobody listens."""
    with progress.listening(StageBar() if shows_progress() else None):
        yield


def staged(items: Iterable[Any], label: str, unit: str = "") -> Iterator[Any]:
    """``items`` one by one as a stage of :mod:`scanplan.progress` (one step each, counted
    when the next is asked for, or the loop ends)."""
    items = list(items)
    with progress.stage(label, len(items), unit) as step:
        for item in items:
            yield item
            step()
