"""Fault injection: a failure at any stage of writing a report or a norm set loses nothing.

Issue 7: "a failure at each stage of writing reports and norm sets (exception, disk full
simulated, interrupted rename) leaves previous files byte-identical and no temporary files
behind". Every write path × every stage is one parametrised case:

write paths
    ``write_xlsx``, ``write_pdf``, ``scan``/``uav``/``plan`` ``--xlsx --pdf``, ``plan --out``
    (one project; a batch), ``norms template``, ``norms import`` (new set; ``--force``).
stages
    rendering raises; creating the temporary file fails; ``write()`` hits ENOSPC part-way;
    ``fsync`` reports ENOSPC; ``close`` reports EIO (as NFS does); ``chmod`` fails; a rename
    fails (the first, the last, the move aside where hard links are missing); for norm sets
    also ``mkdtemp``, the loader check of the written folder and the old → .old → new swap;
    ``KeyboardInterrupt`` at those points.

Each case snapshots the tree of the target folder's parent (relative path → kind, mode,
bytes) before and after, and looks for leftovers (``.NAME.*.tmp``, ``.NAME.*.old``,
``.NAME.tmp-*``, ``.NAME.old-*``). Faults are injected by wrapping ``os`` functions for
paths below the test folder only. Rendering is fixed bytes where the write is under test;
the end-to-end cases render real reports.
"""

from __future__ import annotations

import errno
import os
import re
import shutil
import stat
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner, Result
from norm_corpus import english_workbook, russian_workbook, save

import scanplan.reports.excel as excel_mod
import scanplan.reports.pdf as pdf_mod
from scanplan.api import ScanResult
from scanplan.cli.main import main
from scanplan.cli.norms import norms as norms_group
from scanplan.errors import InputError, WriteError
from scanplan.norms import recovery as norms_recovery
from scanplan.norms import store as norms_mod
from scanplan.norms import writer as norms_writer
from scanplan.reports import write_atomic, write_atomic_many


def write_xlsx(path: str, scan: Any) -> Any:
    """The Python API's write of one workbook (``ScanResult.write``): the one document
    path's transaction."""
    folder, name = os.path.split(path)
    return ScanResult(scan).write(folder, ("xlsx",), name=name.removesuffix(".xlsx"))


def write_pdf(path: str, scan: Any) -> Any:
    """The Python API's write of one PDF (``ScanResult.write``)."""
    folder, name = os.path.split(path)
    return ScanResult(scan).write(folder, ("pdf",), name=name.removesuffix(".pdf"))

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
FILM = str(EXAMPLES / "instruction-2000-film.toml")
UAV = str(EXAMPLES / "uav-canon-2000.toml")

XLSX_BYTES = b"PK\x03\x04 a new workbook " * 300
PDF_BYTES = b"%PDF-1.7 a new specification " * 300
LEFTOVER = re.compile(r"^\.|\.(tmp|old|bak)(\b|-)|^tmp")


# ---------------------------------------------------------------------------------------
# Snapshots
# ---------------------------------------------------------------------------------------


def snapshot(root: Path) -> dict[str, tuple[Any, ...]]:
    """Every path below ``root``: kind, mode and bytes (symlinks: their target)."""
    out: dict[str, tuple[Any, ...]] = {}
    for dirpath, dirnames, filenames in os.walk(root):
        for name in dirnames + filenames:
            p = Path(dirpath, name)
            st = p.lstat()
            rel = p.relative_to(root).as_posix()
            if stat.S_ISLNK(st.st_mode):
                out[rel] = ("link", os.readlink(p))
            elif stat.S_ISDIR(st.st_mode):
                out[rel] = ("dir", oct(st.st_mode & 0o7777))
            else:
                out[rel] = ("file", oct(st.st_mode & 0o7777), p.read_bytes())
    return out


def leftovers(root: Path) -> list[str]:
    """Temporary or backup files anywhere below ``root``."""
    return sorted(p.relative_to(root).as_posix() for p in root.rglob("*")
                  if LEFTOVER.search(p.name))


# ---------------------------------------------------------------------------------------
# The fault injector
# ---------------------------------------------------------------------------------------


def enospc() -> OSError:
    return OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


def eacces() -> OSError:
    return OSError(errno.EACCES, os.strerror(errno.EACCES))


def eperm() -> OSError:
    return OSError(errno.EPERM, os.strerror(errno.EPERM))


def eio() -> OSError:
    return OSError(errno.EIO, os.strerror(errno.EIO))


def interrupt() -> BaseException:
    return KeyboardInterrupt()


def bug() -> BaseException:
    return RuntimeError("rendering failed")


class Faults:
    """Wrap ``os`` functions; ``arm(op, n, exc)`` makes the n-th call below ``root`` fail.

    Counted calls: ``open`` (files created), ``mkdir``, ``chmod``, ``replace``, ``link`` on
    paths below ``root``; ``write``, ``fsync``, ``close`` on the files created there. For
    ``write`` the n is the n-th file created: its first write stores half the data (a short
    write, as on a filling disk) and the next one raises. ``close`` closes, then raises.
    """

    OPS = ("open", "mkdir", "write", "fsync", "close", "chmod", "replace", "link")

    def __init__(self, monkeypatch: pytest.MonkeyPatch, root: Path) -> None:
        self.root = os.path.abspath(root) + os.sep
        self.real = {op: getattr(os, op) for op in self.OPS}
        self.armed: dict[str, dict[int, Callable[[], BaseException]]] = {}
        self.always: dict[str, Callable[[], BaseException]] = {}
        self.calls: Counter[str] = Counter()
        self.files: dict[int, int] = {}  # fd → n-th file created
        self.created = 0
        self.short: set[int] = set()
        for op in self.OPS:
            monkeypatch.setattr(os, op, getattr(self, "_" + op))

    def arm(self, op: str, nth: int, exc: Callable[[], BaseException]) -> Faults:
        self.armed.setdefault(op, {})[nth] = exc
        return self

    def fail_always(self, op: str, exc: Callable[[], BaseException]) -> Faults:
        self.always[op] = exc
        return self

    def _below(self, *paths: Any) -> bool:
        return any(os.path.abspath(os.fspath(p)).startswith(self.root) for p in paths)

    def _hit(self, op: str, n: int | None = None) -> None:
        if op in self.always:
            raise self.always[op]()
        if n is None:
            self.calls[op] += 1
            n = self.calls[op]
        exc = self.armed.get(op, {}).get(n)
        if exc is not None:
            raise exc()

    def _open(self, path: Any, flags: int, mode: int = 0o777, **kw: Any) -> int:
        counted = bool(flags & os.O_CREAT) and self._below(path)
        if counted:
            self._hit("open")
        fd = self.real["open"](path, flags, mode, **kw)
        if counted:
            self.created += 1
            self.files[fd] = self.created
        return fd

    def _mkdir(self, path: Any, mode: int = 0o777, **kw: Any) -> None:
        if self._below(path) and not os.path.lexists(path):  # not Path.mkdir(exist_ok=True)
            self._hit("mkdir")
        self.real["mkdir"](path, mode, **kw)

    def _write(self, fd: int, data: Any) -> int:
        nth = self.files.get(fd)
        exc = self.armed.get("write", {}).get(nth) if nth else None
        if exc is not None:
            if fd in self.short:
                raise exc()
            self.short.add(fd)
            return self.real["write"](fd, bytes(memoryview(data)[: max(1, len(data) // 2)]))
        return self.real["write"](fd, data)

    def _fsync(self, fd: Any) -> None:
        if isinstance(fd, int) and fd in self.files:
            self._hit("fsync")
        self.real["fsync"](fd)

    def _close(self, fd: int) -> None:
        tracked = self.files.pop(fd, None) is not None
        self.real["close"](fd)
        if tracked:
            self._hit("close")

    def _chmod(self, path: Any, mode: int, **kw: Any) -> None:
        if self._below(path):
            self._hit("chmod")
        self.real["chmod"](path, mode, **kw)

    def _replace(self, src: Any, dst: Any, **kw: Any) -> None:
        if self._below(src, dst):
            self._hit("replace")
        self.real["replace"](src, dst, **kw)

    def _link(self, src: Any, dst: Any, **kw: Any) -> None:
        if self._below(src, dst):
            self._hit("link")
        self.real["link"](src, dst, **kw)


# ---------------------------------------------------------------------------------------
# Report write paths
# ---------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def scan_job():
    from scanplan.project.jobs import scan_job as make

    return make(map_scale=2000, relief_interval_m=0.5, photo_scales=[10000], camera="rc30-153")


@pytest.fixture()
def work(tmp_path, monkeypatch):
    """``work/out`` with an unrelated file in each; the current directory is ``work``."""
    w = tmp_path / "work"
    (w / "out").mkdir(parents=True)
    (w / "notes.txt").write_bytes(b"not ours")
    (w / "out" / "readme.txt").write_bytes(b"not ours either")
    monkeypatch.chdir(w)
    return w


def previous_report(name: str) -> bytes:
    """Recognisable bytes of a report scanplan wrote before (its creator property says
    scanplan, so it is replaced without --force)."""
    if name.endswith(".pdf"):
        return b"%PDF-1.7\n<</Creator (scanplan 0.0)>>\nOLD " + name.encode() * 50
    import io
    import zipfile

    buf = io.BytesIO()
    when = (2020, 1, 1, 0, 0, 0)  # fixed: two calls seconds apart give the same bytes
    with zipfile.ZipFile(buf, "w") as zf:
        zf.writestr(zipfile.ZipInfo("docProps/core.xml", when),
                    "<cp:coreProperties><dc:creator>scanplan 0.0"
                    "</dc:creator></cp:coreProperties>")
        zf.writestr(zipfile.ZipInfo("OLD", when), name * 50)
    return buf.getvalue()


def put_old(work: Path, targets: tuple[str, ...]) -> None:
    """The previous reports: recognisable bytes and a mode a rewrite must keep."""
    for t in targets:
        p = work / t
        p.write_bytes(previous_report(t))
        p.chmod(0o640)


@pytest.fixture()
def fmp():
    """A MonkeyPatch of its own for the faults: undone before the test looks at the tree,
    leaving the fixtures' patches (current directory, environment) in place."""
    with pytest.MonkeyPatch.context() as mp:
        yield mp


@pytest.fixture()
def fixed_renders(monkeypatch):
    """Rendering returns fixed bytes (the write is under test, not the renderer)."""
    monkeypatch.setattr(excel_mod, "render_xlsx", lambda **kw: XLSX_BYTES)
    monkeypatch.setattr(pdf_mod, "render_pdf", lambda **kw: PDF_BYTES)
    # the renders under test are this process's (a PDF worker's child would render the
    # real document; its own failures: tests/test_fast_reports.py)
    monkeypatch.setenv("SCANPLAN_NO_FORK", "1")


def break_render(monkeypatch: pytest.MonkeyPatch, kind: str,
                 exc: Callable[[], BaseException]) -> None:
    def broken(*args: Any, **kw: Any) -> bytes:
        raise exc()

    if kind == "xlsx":
        monkeypatch.setattr(excel_mod, "render_xlsx", broken)
    elif kind == "pdf":
        monkeypatch.setattr(pdf_mod, "render_pdf", broken)
    else:  # the norm template: openpyxl's save renders the workbook
        import openpyxl.workbook.workbook as wbmod

        monkeypatch.setattr(wbmod.Workbook, "save", broken)


def cli(*args: str) -> Result:
    return CliRunner().invoke(main, list(args))


@dataclass(frozen=True)
class WritePath:
    """One way reports get written: the files (in write order) and how to run it."""

    name: str
    targets: tuple[str, ...]
    renders: tuple[str, ...]  # which renderer produces each target
    run: Callable[[Any], Any]  # (scan_job) → CLI Result, or None for the API
    is_cli: bool = True


PATHS = (
    WritePath("api-write-xlsx", ("out/spec.xlsx",), ("xlsx",),
              lambda job: write_xlsx("out/spec.xlsx", scan=job), is_cli=False),
    WritePath("api-write-pdf", ("out/spec.pdf",), ("pdf",),
              lambda job: write_pdf("out/spec.pdf", scan=job), is_cli=False),
    WritePath("scan", ("out/spec.xlsx", "out/spec.pdf"), ("xlsx", "pdf"),
              lambda job: cli("scan", "--map-scale", "2000", "--relief", "0.5",
                              "--photo-scale", "10000", "--camera", "rc30-153",
                              "--xlsx", "out/spec.xlsx", "--pdf", "out/spec.pdf")),
    WritePath("uav", ("out/spec.xlsx", "out/spec.pdf"), ("xlsx", "pdf"),
              lambda job: cli("uav", "--camera", "canon-eos-5d-mark-ii-50", "--height-m",
                              "300", "--xlsx", "out/spec.xlsx", "--pdf", "out/spec.pdf")),
    WritePath("plan-out", ("out/spec.xlsx", "out/spec.pdf"), ("xlsx", "pdf"),
              lambda job: cli("plan", FILM, "--out", "out")),
    WritePath("plan-xlsx-pdf", ("out/spec.xlsx", "out/spec.pdf"), ("xlsx", "pdf"),
              lambda job: cli("plan", FILM, "--xlsx", "out/spec.xlsx", "--pdf", "out/spec.pdf")),
    WritePath("norms-template", ("out/norms.xlsx",), ("template",),
              lambda job: cli("norms", "template", "out/norms.xlsx", "--force")),
)


@dataclass(frozen=True)
class Stage:
    """Where the write fails: os faults to arm, or a renderer to break."""

    name: str
    faults: tuple[tuple[str, int, Callable[[], BaseException]], ...] = ()
    render: int | None = None  # index of the renderer that raises
    exc: Callable[[], BaseException] = enospc
    named: int = 0  # index of the file the message must name
    no_hard_links: bool = False
    needs_existing: bool = False

    @property
    def error(self) -> BaseException:
        return self.exc() if self.render is not None else self.faults[-1][2]()


def stages(n: int) -> list[Stage]:
    """The stages of writing ``n`` files (1 or 2). The transaction's journal is renamed
    into place before the targets (``replace`` 1) and again at the commit point
    (``replace`` n + 2); the targets' renames are ``replace`` 2 … n + 1."""
    last = n - 1
    out = [
        Stage("render-raises", render=0, exc=bug),
        Stage("open-temp-fails", (("open", 1, eacces),)),
        Stage("write-disk-full-part-way", (("write", 1, enospc),)),
        Stage("fsync-disk-full", (("fsync", n, enospc),), named=last),
        Stage("close-io-error", (("close", 1, eio),)),
        Stage("chmod-fails", (("chmod", n, eperm),), named=last),
        Stage("journal-write-fails", (("write", n + 1, enospc),), named=last),
        Stage("journal-rename-fails", (("replace", 1, eio),), named=last),
        Stage("rename-fails-first", (("replace", 2, eio),)),
        Stage("commit-fails", (("replace", n + 2, enospc),), named=last),
        Stage("interrupt-render", render=last, exc=interrupt),
        Stage("interrupt-write", (("write", n, interrupt),)),
        Stage("interrupt-rename-first", (("replace", 2, interrupt),)),
        Stage("interrupt-commit", (("replace", n + 2, interrupt),)),
    ]
    if n > 1:
        out += [
            Stage("render-raises-second", render=1, exc=bug),
            Stage("open-temp-fails-second", (("open", 2, enospc),), named=1),
            Stage("write-disk-full-second", (("write", 2, enospc),), named=1),
            Stage("rename-fails-last", (("replace", 3, eio),), named=1),
            Stage("interrupt-rename-last", (("replace", 3, interrupt),)),
            # no hard links (FAT, some shares): the old file is moved aside, then back
            Stage("no-links-move-aside-fails", (("replace", 2, eio),), no_hard_links=True,
                  needs_existing=True),
            Stage("no-links-rename-fails-last", (("replace", 5, enospc),), named=1,
                  no_hard_links=True, needs_existing=True),
            Stage("no-links-interrupt-last", (("replace", 5, interrupt),),
                  no_hard_links=True, needs_existing=True),
        ]
    return out


CASES = [
    pytest.param(path, stage, existing, id=f"{path.name}-{stage.name}-"
                 + ("replace" if existing else "new"))
    for path in PATHS
    for stage in stages(len(path.targets))
    for existing in (True, False)
    if existing or not stage.needs_existing
]


def run_path(path: WritePath, job: Any) -> tuple[Any, BaseException | None]:
    """Run a write path: (CLI result or None, the exception the API raised)."""
    if path.is_cli:
        return path.run(job), None
    try:
        path.run(job)
    except BaseException as exc:  # the test inspects it
        return None, exc
    return None, None


@pytest.fixture()
def journal_only(monkeypatch):
    """``plan --out`` written with the journal, as where the file system has no links (the
    output folder's sets and their own faults: tests/test_folder_sets.py)."""
    import scanplan.io.folderset as folderset

    monkeypatch.setattr(folderset, "supported", lambda folder: False)


@pytest.mark.parametrize(("path", "stage", "existing"), CASES)
def test_report_write_faults(path, stage, existing, work, scan_job, fixed_renders, fmp,
                             journal_only):
    """The matrix: any failure leaves every previous file byte-identical, nothing else."""
    if existing:
        put_old(work, path.targets)
    before = snapshot(work)
    faults = Faults(fmp, work)
    for op, nth, exc in stage.faults:
        faults.arm(op, nth, exc)
    if stage.no_hard_links:
        faults.fail_always("link", eperm)
    if stage.render is not None:
        break_render(fmp, path.renders[min(stage.render, len(path.renders) - 1)],
                     stage.exc)

    result, raised = run_path(path, scan_job)

    fmp.undo()  # the real os again before looking
    assert snapshot(work) == before
    assert leftovers(work) == []
    error = stage.error
    named = path.targets[min(stage.named, len(path.targets) - 1)]
    if not path.is_cli:
        assert type(raised) is (WriteError if isinstance(error, OSError) else type(error))
        if isinstance(error, OSError):
            assert raised.path == named and raised.errno == error.errno
            assert str(raised).startswith(f"cannot write {named}: {error.strerror}")
        return
    assert result.exit_code == 1, result.output
    assert result.exception is None or isinstance(result.exception, SystemExit), \
        result.exception
    assert "Traceback" not in result.output
    if isinstance(error, KeyboardInterrupt):
        assert "Aborted!" in result.stderr
    elif isinstance(error, OSError):
        assert f"error: cannot write {named}: {error.strerror}" in result.stderr
    else:
        assert "error: RuntimeError: rendering failed" in result.stderr
    assert "wrote" not in result.stderr


def test_matrix_is_explicit():
    """Dozens of cases: every write path meets every stage."""
    assert len(CASES) >= 150
    assert {p.values[0].name for p in CASES} == {p.name for p in PATHS}


# ---------------------------------------------------------------------------------------
# Bugs found, one regression test each
# ---------------------------------------------------------------------------------------


def test_plan_out_never_leaves_a_new_xlsx_beside_an_old_pdf(work, fmp, journal_only):
    """Bug: ``plan --out`` wrote spec.xlsx, then spec.pdf; a failure on the PDF left a new
    workbook beside the old PDF — a pair an engineer could sign. End to end (real
    rendering): the PDF's rename fails, both previous files stay byte-identical."""
    targets = ("out/spec.xlsx", "out/spec.pdf")
    put_old(work, targets)
    before = snapshot(work)
    Faults(fmp, work).arm("replace", 3, enospc)  # 1: the journal, 2: spec.xlsx
    r = cli("plan", FILM, "--out", "out")
    fmp.undo()
    assert r.exit_code == 1
    assert r.stderr == ("error: cannot write out/spec.pdf: No space left on device; none of "
                        "out/spec.xlsx, out/spec.pdf was changed\n")
    assert snapshot(work) == before and leftovers(work) == []


def test_write_xlsx_end_to_end_disk_full_then_success(work, scan_job, fmp):
    """Real workbook: disk full part-way keeps the old file; the next write replaces it
    (same mode) with a workbook openpyxl reads."""
    openpyxl = pytest.importorskip("openpyxl")
    put_old(work, ("out/spec.xlsx",))
    before = snapshot(work)
    faults = Faults(fmp, work).arm("write", 1, enospc)
    with pytest.raises(WriteError, match=r"^cannot write out/spec.xlsx: No space left"):
        write_xlsx("out/spec.xlsx", scan=scan_job)
    assert faults.calls["replace"] == 0
    fmp.undo()
    assert snapshot(work) == before and leftovers(work) == []
    write_xlsx("out/spec.xlsx", scan=scan_job)
    assert (work / "out/spec.xlsx").stat().st_mode & 0o777 == 0o640
    assert openpyxl.load_workbook(work / "out/spec.xlsx").worksheets
    assert leftovers(work) == []


def test_write_pdf_end_to_end_interrupted_rename(work, scan_job, monkeypatch, fmp):
    """Real PDF: the rename fails (then Ctrl-C at the same point); the old PDF stays."""
    put_old(work, ("out/spec.pdf",))
    before = snapshot(work)
    data = pdf_mod.render_pdf(scan=scan_job)
    assert data.startswith(b"%PDF")
    monkeypatch.setattr(pdf_mod, "render_pdf", lambda **kw: data)  # rendered once
    Faults(fmp, work).fail_always("replace", eio)
    with pytest.raises(WriteError) as info:
        write_pdf("out/spec.pdf", scan=scan_job)
    assert info.value.message == "cannot write out/spec.pdf: Input/output error"
    assert isinstance(info.value, OSError) and info.value.errno == errno.EIO
    Faults(fmp, work).fail_always("replace", interrupt)
    with pytest.raises(KeyboardInterrupt):
        write_pdf("out/spec.pdf", scan=scan_job)
    fmp.undo()
    assert snapshot(work) == before and leftovers(work) == []


def test_rollback_that_fails_too_says_where_the_old_file_is(work, fixed_renders, fmp,
                                                            journal_only):
    """Double fault: the PDF's rename fails and putting spec.xlsx back fails as well.
    Nothing is lost: the message names the backup holding the previous spec.xlsx."""
    put_old(work, ("out/spec.xlsx", "out/spec.pdf"))
    old = snapshot(work)
    Faults(fmp, work).arm("replace", 3, enospc).arm("replace", 4, eio)
    r = cli("plan", FILM, "--out", "out")
    fmp.undo()
    assert r.exit_code == 1 and "Traceback" not in r.output
    m = re.search(r"out/spec.xlsx could not be put back \(Input/output error\); the previous "
                  r"file is kept as (\S+)\n", r.stderr)
    assert r.stderr.startswith("error: cannot write out/spec.pdf: No space left on device; ")
    assert m, r.stderr
    backup = Path(m[1])
    assert backup.read_bytes() == old["out/spec.xlsx"][2]
    assert (work / "out/spec.pdf").read_bytes() == old["out/spec.pdf"][2]
    # the journal stays: the next write into the folder puts spec.xlsx back first
    assert [p for p in leftovers(work) if not p.endswith(".old")] == [
        "out/.scanplan-journal.json"]
    from scanplan.io.journal import recover

    assert recover([work / "out"]) == ["rolled back"]
    assert snapshot(work) == old and leftovers(work) == []


def test_cli_disk_full_message_names_the_file_and_reason(work, fixed_renders, fmp):
    """Bug: an OSError came out as ``error: OSError: [Errno 28] No space left on device:
    '/abs/out/.spec.pdf.x1y2.tmp'`` — the temporary file, not the report."""
    Faults(fmp, work).arm("write", 1, enospc)
    r = cli("scan", "--map-scale", "2000", "--relief", "0.5", "--photo-scale", "10000",
            "--camera", "rc30-153", "--pdf", "out/spec.pdf")
    assert (r.exit_code, r.stderr) == (
        1, "error: cannot write out/spec.pdf: No space left on device\n")


def test_debug_shows_the_traceback(work, fixed_renders, monkeypatch, fmp, journal_only):
    monkeypatch.setenv("SCANPLAN_DEBUG", "1")
    Faults(fmp, work).arm("replace", 2, eio)  # 1 is the journal
    r = cli("plan", FILM, "--out", "out")
    assert r.exit_code == 1 and "Traceback" in r.stderr
    assert "error: cannot write out/spec.xlsx: Input/output error" in r.stderr


def test_other_os_errors_name_the_file(work, monkeypatch):
    """An OSError that is not a write (here: reading the norm set) names its file too."""
    import scanplan.project.jobs

    def boom(**kw):
        raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), "/srv/norms/set.toml")

    monkeypatch.setattr(scanplan.project.jobs, "scan_job", boom)
    r = cli("scan", "--map-scale", "2000", "--relief", "0.5", "--photo-scale", "10000",
            "--camera", "rc30-153")
    assert r.exit_code == 1
    assert r.stderr.startswith("error: /srv/norms/set.toml: Permission denied")


def test_same_file_for_xlsx_and_pdf_is_bad_input(work, fixed_renders):
    """Bug: ``--xlsx r --pdf r`` wrote the workbook, then the PDF over it. Now exit 2."""
    r = cli("plan", FILM, "--xlsx", "out/r", "--pdf", "out/./r")
    assert r.exit_code == 2 and "--pdf" in r.stderr and "--xlsx" in r.stderr
    assert sorted(p.name for p in (work / "out").iterdir()) == ["readme.txt"]


def test_target_that_is_a_folder_writes_nothing(work, fixed_renders):
    """Bug: with out/spec.pdf a folder, ``plan --out`` wrote spec.xlsx, then crashed on
    the PDF (IsADirectoryError). Now nothing is written, exit 2 naming the file (issue 19:
    a target that is not a regular file is bad input, refused before anything is written)."""
    (work / "out/spec.pdf").mkdir()
    put_old(work, ("out/spec.xlsx",))
    before = snapshot(work)
    r = cli("plan", FILM, "--out", "out")
    assert r.exit_code == 2
    assert "error: --out: 'out/spec.pdf' is a folder; give a file name" in r.stderr
    assert snapshot(work) == before


def test_plan_out_new_folder_is_removed_on_failure(work, fixed_renders, fmp):
    """Bug: ``plan --out new/dir`` created the folders, and a failure left them empty."""
    Faults(fmp, work).arm("write", 2, enospc)
    before = snapshot(work)
    r = cli("plan", FILM, "--out", "new/dir")
    assert r.exit_code == 1 and "cannot write new/dir/spec." in r.stderr
    r = cli("plan", str(work / "missing.toml"), "--out", "new/dir")
    assert r.exit_code == 2
    fmp.undo()
    assert snapshot(work) == before
    assert cli("plan", FILM, "--out", "new/dir").exit_code == 0
    assert sorted(p.name for p in (work / "new/dir").iterdir()
                  if not p.name.startswith(".")) == ["spec.pdf", "spec.xlsx"]


def test_out_folder_that_cannot_be_created(work, fmp):
    Faults(fmp, work).arm("mkdir", 1, eacces)
    r = cli("plan", FILM, "--out", "sub/out")
    assert r.exit_code == 1
    assert "error: cannot create folder sub/out: Permission denied" in r.stderr
    fmp.undo()
    assert not (work / "sub").exists()


def test_write_atomic_many_api(tmp_path, monkeypatch):
    """The helper on its own: order, modes, the same file twice, a folder as target."""
    a, b = tmp_path / "a.bin", tmp_path / "b.bin"
    a.write_bytes(b"old a")
    a.chmod(0o600)
    assert write_atomic_many({a: b"new a", b: b"new b"}) == [a, b]
    assert (a.read_bytes(), b.read_bytes()) == (b"new a", b"new b")
    assert a.stat().st_mode & 0o777 == 0o600
    with pytest.raises(ValueError, match="twice"):
        write_atomic_many({str(a): b"1", f"{tmp_path}/./a.bin": b"2"})
    with pytest.raises(WriteError, match="it is a folder"):
        write_atomic_many({a: b"x", tmp_path: b"y"})
    assert a.read_bytes() == b"new a"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.bin", "b.bin"]
    assert write_atomic(tmp_path / "c.bin", b"c") == tmp_path / "c.bin"


def test_a_command_without_reports_writes_and_syncs_nothing(tmp_path, monkeypatch):
    """``scan``/``uav`` with ``--json`` and no report: an empty transaction, which wrote a
    journal into the current folder (five fsyncs a run) before; now it only checks."""
    monkeypatch.chdir(tmp_path)
    synced = []
    real = os.fsync
    monkeypatch.setattr(os, "fsync", lambda fd: synced.append(fd) or real(fd))
    for args in (["scan", "--map-scale", "2000", "--relief", "2", "--photo-scale", "8000",
                  "--camera", "rc30-153"],
                 ["uav", "--camera", "dji-mavic-3e", "--height-m", "100"]):
        r = CliRunner().invoke(main, [*args, "--json"])
        assert r.exit_code == 0, r.output
    assert synced == [] and list(tmp_path.iterdir()) == []
    checked = []
    assert write_atomic_many({}, check=lambda: checked.append(1)) == [] and checked == [1]
    assert synced == [] and list(tmp_path.iterdir()) == []


def test_backup_is_a_hard_link_while_renaming(tmp_path, monkeypatch):
    """Between the renames the previous file stays in place (a hard link backs it up), so
    even a process killed there leaves every target a complete file."""
    a, b = tmp_path / "a", tmp_path / "b"
    a.write_bytes(b"old a")
    b.write_bytes(b"old b")
    seen = []
    real = os.replace

    def spy(src, dst, **kw):
        seen.append((Path(src).name, Path(dst).name, a.read_bytes(),
                     sorted(p.name for p in tmp_path.iterdir())))
        return real(src, dst, **kw)

    monkeypatch.setattr(os, "replace", spy)
    write_atomic_many({a: b"new a", b: b"new b"})
    seen = [s for s in seen if s[1] in ("a", "b")]  # not the journal's renames
    assert seen[0][2] == b"old a" and any(n.endswith(".old") for n in seen[0][3])
    assert seen[1][1] == "b" and seen[1][2] == b"new a"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a", "b"]


# ---------------------------------------------------------------------------------------
# plan: a batch
# ---------------------------------------------------------------------------------------

BATCH_TARGETS = ("out/a.xlsx", "out/a.pdf", "out/b.xlsx", "out/b.pdf")


@pytest.fixture()
def batch(work):
    projects = work.parent / "projects"
    projects.mkdir()
    shutil.copy(FILM, projects / "a.toml")
    shutil.copy(UAV, projects / "b.toml")
    put_old(work, BATCH_TARGETS)
    return projects


@pytest.mark.parametrize(("fault", "written", "named"), [
    # per project: write xlsx, pdf, the journal, its commit; replace the journal, xlsx,
    # pdf, the commit
    pytest.param(("replace", 2, eio), (), "out/a.xlsx", id="first-project-rename"),
    pytest.param(("write", 2, enospc), (), "out/a.pdf", id="first-project-disk-full"),
    pytest.param(("write", 5, enospc), ("a",), "out/b.xlsx", id="second-project-disk-full"),
    pytest.param(("replace", 7, eio), ("a",), "out/b.pdf", id="second-project-last-rename"),
    pytest.param(("replace", 7, interrupt), ("a",), "", id="second-project-interrupt"),
])
def test_batch_write_failure_stops_the_batch(batch, work, fixed_renders, fmp,
                                             fault, written, named):
    """A write failure (disk full) stops the batch with exit 1: projects already written
    stay written, the failing project's previous pair is intact, later ones are not run."""
    before = snapshot(work)
    Faults(fmp, work).arm(*fault)
    # --jobs 1: the faults are injected into this process, not into worker processes
    r = cli("plan", str(batch / "a.toml"), str(batch / "b.toml"), "--out", "out",
            "--jobs", "1")
    fmp.undo()
    after = snapshot(work)
    for t in BATCH_TARGETS:
        stem = Path(t).stem
        if stem in written:
            assert after[t][2] in (XLSX_BYTES, PDF_BYTES) and after[t][1] == "0o640"
        else:
            assert after[t] == before[t], t
    assert leftovers(work) == []
    assert r.exit_code == 1 and "Traceback" not in r.output
    assert r.exception is None or isinstance(r.exception, SystemExit)
    if not named:
        assert "Aborted!" in r.stderr
        return
    reason = fault[2]().strerror
    assert f"error: cannot write {named}: {reason}" in r.stderr
    stopped_at = "a.toml" if not written else "b.toml"
    assert f"error: the batch stopped at {batch / stopped_at} ({len(written)} of 2 " \
           "projects written" in r.stderr
    if not written:
        assert f"not planned: {batch / 'b.toml'}" in r.stderr
    assert "1 failed" in r.stdout  # the summary is still printed


def test_batch_bad_project_still_continues_and_disk_full_wins(batch, work, fixed_renders, fmp):
    """A bad project is exit 2 and the batch runs on; a later disk-full makes it exit 1."""
    (batch / "0-bad.toml").write_text("[map]\nscale = -5\n", encoding="utf-8")
    r = cli("plan", str(batch), "--out", "out")
    assert r.exit_code == 2 and "2 planned, 1 failed" in r.stdout
    put_old(work, BATCH_TARGETS)
    Faults(fmp, work).arm("write", 5, enospc)  # a: 4 writes (2 files, the journal twice)
    r = cli("plan", str(batch), "--out", "out", "--json", "--jobs", "1")  # faults: here
    fmp.undo()
    assert r.exit_code == 1
    import json

    doc = json.loads(r.stdout)
    assert [Path(e["file"]).name for e in doc["errors"]] == ["0-bad.toml", "b.toml"]
    assert "cannot write out/b.xlsx: No space left on device" in doc["errors"][1]["message"]
    assert (work / "out/b.xlsx").read_bytes() == previous_report("out/b.xlsx")
    assert (work / "out/a.xlsx").read_bytes() == XLSX_BYTES


# ---------------------------------------------------------------------------------------
# Norm sets: import (new, --force) and the template
# ---------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def sources(tmp_path_factory):
    d = tmp_path_factory.mktemp("norm-sources")
    return {"en": save(english_workbook(), d, "en.xlsx"),
            "ru": save(russian_workbook(), d, "ru.xlsx")}


@pytest.fixture()
def user_dir(tmp_path, monkeypatch):
    """``nwork/user-norms`` ($SCANPLAN_NORMS_DIR) holding an unrelated set ``keep``."""
    d = tmp_path / "nwork" / "user-norms"
    d.mkdir(parents=True)
    monkeypatch.setenv("SCANPLAN_NORMS_DIR", str(d))
    norms_mod.forget_read_sets()
    yield d
    norms_mod.forget_read_sets()


@pytest.fixture(scope="module")
def set_files(sources, tmp_path_factory):
    """How many files an imported set has (the n of the last file written)."""
    root = tmp_path_factory.mktemp("count")
    path, _ = norms_writer.import_norm_file(sources["ru"], "count", root=root)
    return len(list(path.iterdir()))


def prepare_sets(user_dir: Path, sources: dict[str, Path], existing: bool) -> None:
    norms_writer.import_norm_file(sources["en"], "keep", root=user_dir)
    if existing:
        norms_writer.import_norm_file(sources["en"], "mine", root=user_dir)


def break_verify(monkeypatch: pytest.MonkeyPatch, exc: Callable[[], BaseException]) -> None:
    real = norms_mod.read_norm_set_folder

    def broken(path, **kw):
        if Path(path).name.startswith("."):  # the written, not yet renamed folder
            raise exc()
        return real(path, **kw)

    monkeypatch.setattr(norms_mod, "read_norm_set_folder", broken)


def loader_rejects() -> BaseException:
    return InputError("set.toml", "the loader rejects it")


NORM_STAGES = [
    # (id, faults, verify exception, only with an existing set)
    ("mkdtemp-fails", (("mkdir", 1, enospc),), None, False),
    ("chmod-fails", (("chmod", 1, eperm),), None, False),
    ("open-first-file-fails", (("open", 1, eacces),), None, False),
    ("write-disk-full-first", (("write", 1, enospc),), None, False),
    ("write-disk-full-last", (("write", -1, enospc),), None, False),
    ("fsync-disk-full-last", (("fsync", -1, enospc),), None, False),
    ("close-io-error", (("close", 2, eio),), None, False),
    ("verify-os-error", (), eio, False),
    ("verify-rejects", (), loader_rejects, False),
    ("rename-fails-first", (("replace", 1, eio),), None, False),
    ("rename-new-in-fails", (("replace", 2, enospc),), None, True),
    ("interrupt-write", (("write", 2, interrupt),), None, False),
    ("interrupt-verify", (), interrupt, False),
    ("interrupt-rename-first", (("replace", 1, interrupt),), None, False),
    ("interrupt-rename-new-in", (("replace", 2, interrupt),), None, True),
]

NORM_CASES = [
    pytest.param(stage, existing, id=f"{'force' if existing else 'new'}-{stage[0]}")
    for stage in NORM_STAGES
    for existing in (False, True)
    if existing or not stage[3]
]


@pytest.mark.parametrize(("stage", "existing"), NORM_CASES)
def test_norm_import_faults(stage, existing, user_dir, sources, set_files, fmp):
    """``norms import`` (new set, and ``--force`` over an existing one): any failure leaves
    the norm directory byte-identical — the old set loads as before."""
    _, faults, verify, _ = stage
    prepare_sets(user_dir, sources, existing)
    before = snapshot(user_dir.parent)
    f = Faults(fmp, user_dir.parent)
    for op, nth, exc in faults:
        f.arm(op, set_files if nth == -1 else nth, exc)
    if verify is not None:
        break_verify(fmp, verify)
    args = ["norms", "import", str(sources["ru"]), "--name", "mine"]
    r = cli(*args, *(["--force"] if existing else []))
    fmp.undo()
    assert snapshot(user_dir.parent) == before
    assert leftovers(user_dir.parent) == []
    assert "Traceback" not in r.output
    assert r.exception is None or isinstance(r.exception, SystemExit), r.exception
    error = (faults[-1][2] if faults else verify)()
    if isinstance(error, KeyboardInterrupt):
        assert r.exit_code == 1 and "Aborted!" in r.stderr
    elif isinstance(error, InputError):
        assert r.exit_code == 2 and "the loader rejects it" in r.stderr
    else:
        assert r.exit_code == 1
        assert r.stderr == (f"error: cannot write norm set 'mine' to {user_dir / 'mine'}: "
                            f"{error.strerror}\n")
    norms_mod.forget_read_sets()
    if existing:
        assert norms_mod.load_norm_set("mine").parameters["planimetric_accuracy_mm"] == 0.2
    r = cli("norms", "list", "--json")
    assert r.exit_code == 0 and r.stderr == ""  # nothing to recover


def test_norm_matrix_is_explicit():
    assert len(NORM_CASES) >= 25


def test_norm_import_end_to_end_then_success(user_dir, sources, fmp):
    """Disk full while importing over a set, then the same import succeeds and replaces
    it; no leftovers either way."""
    prepare_sets(user_dir, sources, existing=True)
    before = snapshot(user_dir.parent)
    Faults(fmp, user_dir.parent).arm("fsync", 3, enospc)
    with pytest.raises(WriteError) as info:
        norms_writer.import_norm_file(sources["ru"], "mine", force=True)
    assert info.value.errno == errno.ENOSPC and info.value.path == str(user_dir / "mine")
    fmp.undo()
    assert snapshot(user_dir.parent) == before
    norms_writer.import_norm_file(sources["ru"], "mine", force=True, root=user_dir)
    norms_mod.forget_read_sets()
    assert norms_mod.load_norm_set(user_dir / "mine").parameters[
        "planimetric_accuracy_mm"] == pytest.approx(0.4)
    assert leftovers(user_dir.parent) == []


def test_norm_swap_double_fault_is_recovered_by_the_next_command(user_dir, sources, fmp):
    """Bug: when the new set's rename failed and moving the old one back failed too, the
    old set was left in ``.mine.old-*``, hidden from ``norms list`` and unknown to
    ``--norms mine``. Now the message says where it is, and the next command puts it
    back."""
    prepare_sets(user_dir, sources, existing=True)
    before = snapshot(user_dir.parent)
    Faults(fmp, user_dir.parent).arm("replace", 2, enospc).arm("replace", 3, eio)
    r = cli("norms", "import", str(sources["ru"]), "--name", "mine", "--force")
    fmp.undo()
    assert r.exit_code == 1 and "Traceback" not in r.output
    assert r.stderr.startswith(f"error: cannot write norm set 'mine' to {user_dir / 'mine'}: "
                               "No space left on device; the previous set could not be put "
                               "back (Input/output error); it is kept in ")
    assert [p.name[:10] for p in user_dir.iterdir() if p.name.startswith(".")] == [
        ".mine.old-"]
    r = cli("norms", "list")
    assert r.exit_code == 0 and "put back norm set 'mine'" in r.stderr
    assert "mine" in r.stdout
    assert snapshot(user_dir.parent) == before


def crash_between_renames(user_dir: Path) -> None:
    """What ``kill -9`` between "old → .old" and ".tmp → new" leaves behind."""
    (user_dir / "mine").rename(user_dir / ".mine.old-k1ll3d00")
    partial = user_dir / ".mine.tmp-abcd1234"
    partial.mkdir()
    (partial / "parameters.csv").write_bytes(b"name,value\nplanimetric")


def test_crash_between_swap_renames_load_puts_the_set_back(user_dir, sources):
    """Bug: after a crash between the two renames ``--norms mine`` said "no norm set
    'mine'" and ``norms list`` hid it. Loading it now restores it."""
    prepare_sets(user_dir, sources, existing=True)
    before = snapshot(user_dir.parent)
    crash_between_renames(user_dir)
    norms_mod.forget_read_sets()
    assert norms_mod.load_norm_set("mine").parameters["planimetric_accuracy_mm"] == 0.2
    assert snapshot(user_dir.parent) == before and leftovers(user_dir.parent) == []


def test_crash_between_swap_renames_list_puts_the_set_back(user_dir, sources):
    prepare_sets(user_dir, sources, existing=True)
    before = snapshot(user_dir.parent)
    crash_between_renames(user_dir)
    r = cli("norms", "list", "--json")
    assert r.exit_code == 0
    import json

    assert "mine" in {s["name"] for s in json.loads(r.stdout)["norm_sets"]}
    assert "put back norm set 'mine'" in r.stderr
    assert snapshot(user_dir.parent) == before


def test_crash_between_swap_renames_next_import(user_dir, sources):
    """The next import restores first: without --force it refuses (the set exists again),
    with --force it replaces it; no leftovers either way."""
    prepare_sets(user_dir, sources, existing=True)
    before = snapshot(user_dir.parent)
    crash_between_renames(user_dir)
    r = cli("norms", "import", str(sources["ru"]), "--name", "mine")
    assert r.exit_code == 2 and "--force" in r.stderr
    assert snapshot(user_dir.parent) == before
    crash_between_renames(user_dir)
    r = cli("norms", "import", str(sources["ru"]), "--name", "mine", "--force")
    assert r.exit_code == 0, r.output
    assert leftovers(user_dir.parent) == []
    assert sorted(p.name for p in user_dir.iterdir()) == ["keep", "mine"]


def test_crash_after_the_swap_leftover_old_is_deleted(user_dir, sources):
    """A crash while deleting the replaced set leaves ``.mine.old-*`` beside the new
    ``mine``: the next import deletes it (and a crashed import's ``.tmp-``)."""
    prepare_sets(user_dir, sources, existing=True)
    shutil.copytree(user_dir / "mine", user_dir / ".mine.old-0123abcd")
    (user_dir / ".mine.old-0123abcd" / "set.toml").unlink()  # half deleted
    (user_dir / ".other.tmp-zz99yy88").mkdir()
    actions = norms_recovery.recover_norm_dir(user_dir)
    assert len(actions) == 2 and all("deleted" in a for a in actions)
    assert sorted(p.name for p in user_dir.iterdir()) == ["keep", "mine"]
    assert norms_recovery.recover_norm_dir(user_dir) == []


def test_failed_import_creates_no_norm_dir(tmp_path, sources, monkeypatch, fmp):
    """Bug: a failed first import left the freshly created (empty) norm directory."""
    root = tmp_path / "fresh" / "norms"
    monkeypatch.setenv("SCANPLAN_NORMS_DIR", str(root))
    Faults(fmp, tmp_path).arm("write", 1, enospc)
    r = cli("norms", "import", str(sources["en"]), "--name", "mine")
    assert r.exit_code == 1 and "No space left on device" in r.stderr
    fmp.undo()
    assert list(tmp_path.iterdir()) == []


def test_norms_group_alone_turns_write_errors_into_exit_1(user_dir, sources, fmp):
    """Bug: run on its own (``norms.main``), the group let an OSError escape as a
    traceback. Now exit 1, and with --json a JSON error too."""
    Faults(fmp, user_dir.parent).arm("replace", 1, eio)
    r = CliRunner().invoke(norms_group, ["import", str(sources["en"]), "--name", "mine",
                                         "--json"])
    assert r.exit_code == 1
    assert r.exception is None or isinstance(r.exception, SystemExit)
    import json

    doc = json.loads(r.stdout)
    assert doc["ok"] is False
    assert doc["errors"][0]["message"] == "Input/output error"
    assert doc["errors"][0]["text"] == f"{user_dir / 'mine'}: Input/output error"
    assert "error: cannot write norm set 'mine'" in r.stderr


def test_template_file_mode(work):
    """Bug: the template was written through mkstemp and kept its 0600 mode; a replaced
    template lost its mode. Now 0666 less the umask, and a replaced file keeps its own."""
    umask = os.umask(0o022)
    try:
        assert cli("norms", "template", "out/t.xlsx").exit_code == 0
        assert (work / "out/t.xlsx").stat().st_mode & 0o777 == 0o644
        (work / "out/t.xlsx").chmod(0o664)
        assert cli("norms", "template", "out/t.xlsx", "--force").exit_code == 0
        assert (work / "out/t.xlsx").stat().st_mode & 0o777 == 0o664
    finally:
        os.umask(umask)
    assert leftovers(work) == []


def test_template_end_to_end_rename_fails(work, fmp):
    """Real template, a rename that fails: the old template is intact."""
    put_old(work, ("out/norms.xlsx",))
    before = snapshot(work)
    Faults(fmp, work).arm("replace", 1, enospc)
    r = cli("norms", "template", "out/norms.xlsx", "--force")
    fmp.undo()
    assert (r.exit_code, r.stderr) == (
        1, "error: cannot write out/norms.xlsx: No space left on device\n")
    assert snapshot(work) == before
