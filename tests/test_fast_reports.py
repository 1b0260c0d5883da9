"""Issue 15, fast reports: the tuned WeasyPrint import and font subsetting give the same
PDF, the PDF worker gives the same bytes as an in-process render and never leaves a
process behind, and a workbook or a block without a polygon imports no plotting or GIS
library."""

from __future__ import annotations

import datetime as dt
import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

pytest.importorskip("weasyprint")

from scanplan.cli.main import main
from scanplan.project.file import load_project
from scanplan.project.spec import plan_project
from scanplan.reports import _weasy, pdfrender
from scanplan.reports.pdf import render_html, render_pdf
from scanplan.reports.pdfworker import PdfWorker
from scanplan.reports.view import build_view

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "uav-canon-2000.toml"
fork_only = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="Linux fork")


@pytest.fixture(scope="module")
def view():
    r = plan_project(load_project(EXAMPLE))
    return build_view(scan=r.film.job if r.film else None, uav=r.uav.job if r.uav else None,
                      meta=r.meta, spec=r, when=dt.datetime(2023, 11, 14, tzinfo=dt.UTC))


def _gone(pid: int) -> bool:
    """True when ``pid`` is no child of this process any more (reaped, no zombie)."""
    try:
        os.waitpid(pid, os.WNOHANG)
    except ChildProcessError:
        return True
    return False


def test_subsetting_without_layout_tables_gives_the_same_pdf(view, monkeypatch):
    """_weasy._fonttools_subset drops GSUB/GPOS before subsetting instead of after: the
    PDF's bytes are those of WeasyPrint's own method."""
    from weasyprint.pdf import fonts

    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    ours = render_pdf(view=view)
    assert fonts.Font._fonttools_subset is _weasy._fonttools_subset or not \
        _weasy.load().__version__.startswith("70.")
    monkeypatch.setattr(fonts.Font, "_fonttools_subset", _weasy._ORIGINAL_SUBSET)
    theirs = render_pdf(view=view)
    assert ours == theirs


def _run_python(code: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=ROOT, timeout=120, check=False)


def test_fast_import_loads_the_same_libraries():
    """Without find_library WeasyPrint opens the libraries by their sonames: every library
    a plain import opens is open (HarfBuzz-Subset as present or absent as there)."""
    code = ("import json, sys\n"
            "from scanplan.reports import _weasy\n"
            "w = _weasy.load()\n"
            "from weasyprint.text import ffi\n"
            "names = ['gobject', 'pango', 'harfbuzz', 'harfbuzz_subset', 'fontconfig',"
            " 'pangoft2']\n"
            "print(json.dumps({n: getattr(ffi, n) is not None for n in names}))\n")
    fast = _run_python(code)
    plain = _run_python(code.replace("w = _weasy.load()", "import weasyprint"))
    assert fast.returncode == 0 and plain.returncode == 0, fast.stderr + plain.stderr
    assert fast.stdout == plain.stdout
    assert '"pango": true' in fast.stdout


def test_fast_import_falls_back_to_a_plain_import():
    """When the soname-first import fails, the half-imported modules are dropped and the
    ordinary import runs (here: the fast path is made to fail at once)."""
    code = ("import contextlib, sys\n"
            "from scanplan.reports import _weasy\n"
            "@contextlib.contextmanager\n"
            "def broken():\n"
            "    import weasyprint.urls\n"  # a module of the half-done import
            "    raise OSError('no library')\n"
            "    yield\n"
            "_weasy._no_find_library = broken\n"
            "w = _weasy.load()\n"
            "import weasyprint\n"
            "assert w is weasyprint and w.HTML is not None\n"
            "print('ok')\n")
    r = _run_python(code)
    assert r.returncode == 0 and r.stdout.strip() == "ok", r.stderr


@fork_only
def test_worker_renders_the_same_bytes_and_is_reaped(view, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    worker = PdfWorker.start()
    assert worker is not None
    pid = worker.pid
    try:
        assert worker.submit(render_html(view=view))
        data = worker.result()
    finally:
        worker.stop()
    assert data is not None, worker.error
    assert data == render_pdf(view=view)
    assert _gone(pid)


@fork_only
def test_worker_error_gives_none_and_a_reason(monkeypatch):
    """A document the child's renderer fails on: no PDF from the worker (the caller renders
    in its own process and raises the error there), the reason kept, the child reaped."""
    def broken(html: str) -> bytes:
        raise RuntimeError(f"renderer broken on {len(html)} characters")

    monkeypatch.setattr(pdfrender, "html_to_pdf", broken)  # the child is forked with it
    worker = PdfWorker.start()
    assert worker is not None
    pid = worker.pid
    try:
        assert worker.submit("<p>a report</p>")
        assert worker.result() is None
    finally:
        worker.stop()
    assert worker.error == "RuntimeError: renderer broken on 15 characters"
    assert _gone(pid)


@fork_only
def test_worker_renders_without_the_garbage_collector(monkeypatch):
    """The child lives for one document: its collector is off from the start (the parent's
    is left as it was)."""
    import gc

    from scanplan.reports import pdfworker

    seen: list[bool] = []
    monkeypatch.setattr(pdfworker, "_warm", lambda: None)
    monkeypatch.setattr(pdfrender, "html_to_pdf",  # the child is forked with it
                        lambda html: f"collector on: {gc.isenabled()}".encode())
    worker = PdfWorker.start()
    assert worker is not None
    try:
        assert worker.submit("<p>a report</p>")
        seen.append(worker.result() == b"collector on: False")
    finally:
        worker.stop()
    assert seen == [True] and gc.isenabled()


@fork_only
def test_worker_refuses_what_is_not_a_text_and_stops():
    for bad in (lambda: None, "lone surrogate \udc80"):
        worker = PdfWorker.start()
        assert worker is not None
        pid = worker.pid
        assert not worker.submit(bad)
        assert worker.result() is None
        assert worker.error.startswith(("AttributeError", "UnicodeEncodeError")), worker.error
        worker.stop()
        assert _gone(pid)


@fork_only
def test_worker_stopped_before_use_leaves_no_process():
    """A run that fails before its view is sent (a bad project file) stops the child."""
    worker = PdfWorker.start()
    assert worker is not None
    pid = worker.pid
    worker.stop()
    worker.stop()  # idempotent
    assert _gone(pid)


def test_worker_is_off_when_asked(monkeypatch):
    monkeypatch.setenv("SCANPLAN_NO_FORK", "1")
    assert PdfWorker.start() is None
    monkeypatch.delenv("SCANPLAN_NO_FORK")
    monkeypatch.setenv("SCANPLAN_DEBUG", "1")
    assert PdfWorker.start() is None


@fork_only
def test_plan_out_with_and_without_the_worker_is_byte_identical(tmp_path, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    outs = {}
    for name, off in (("worker", False), ("inprocess", True)):
        if off:
            monkeypatch.setenv("SCANPLAN_NO_FORK", "1")
        out = tmp_path / name
        r = CliRunner().invoke(main, ["plan", str(EXAMPLE), "--out", str(out)])
        assert r.exit_code == 0, r.output
        outs[name] = {p.name: p.read_bytes() for p in sorted(out.iterdir())
                      if not p.name.startswith(".")}  # the files, not their sets' folder
    assert outs["worker"] == outs["inprocess"]
    assert set(outs["worker"]) == {"spec.pdf", "spec.xlsx"}


_SCAN = ["scan", "--map-scale", "2000", "--relief", "1.0", "--photo-scale", "10000",
         "--camera", "afa-te-100", "--resolving-power", "40"]
_UAV = ["uav", "--camera", "canon-eos-5d-mark-ii-50", "--f-number", "8", "--height-m", "300",
        "--speed-ms", "25", "--map-scale", "2000", "--relief", "0.5"]


@fork_only
@pytest.mark.parametrize("args", [_SCAN, _UAV], ids=["scan", "uav"])
def test_scan_and_uav_render_their_pdf_on_the_worker(args, tmp_path, monkeypatch):
    """``scan``/``uav --pdf`` start the worker too; its PDF is the in-process one."""
    import scanplan.reports.pdfworker as pw

    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    replies: list[bytes | None] = []
    real = pw.PdfWorker.result

    def result(self: PdfWorker) -> bytes | None:
        replies.append(real(self))
        return replies[-1]

    monkeypatch.setattr(pw.PdfWorker, "result", result)
    pdfs = {}
    for name in ("worker", "inprocess"):
        if name == "inprocess":
            monkeypatch.setenv("SCANPLAN_NO_FORK", "1")
        path = tmp_path / f"{name}.pdf"
        r = CliRunner().invoke(main, [*args, "--pdf", str(path)])
        assert r.exit_code == 0, r.output
        pdfs[name] = path.read_bytes()
    assert len(replies) == 1 and replies[0] is not None  # the worker's run rendered there
    assert pdfs["worker"] == pdfs["inprocess"] == replies[0]


@fork_only
def test_a_bad_input_stops_the_worker_of_uav(tmp_path, monkeypatch):
    """A command that fails before its report still reaps the child it started."""
    import scanplan.reports.pdfworker as pw

    pids: list[int] = []
    real = pw.PdfWorker.start.__func__

    def start(cls: type[PdfWorker]) -> PdfWorker | None:
        worker = real(cls)
        pids.append(worker.pid if worker is not None else 0)
        return worker

    monkeypatch.setattr(pw.PdfWorker, "start", classmethod(start))
    r = CliRunner().invoke(main, [*_UAV[:2], "no-such-camera", *_UAV[3:], "--pdf",
                                  str(tmp_path / "u.pdf")])
    assert r.exit_code == 2, r.output
    assert len(pids) == 1 and pids[0] > 0 and _gone(pids[0])
    assert not (tmp_path / "u.pdf").exists()


@fork_only
def test_an_interrupt_while_the_worker_renders_writes_nothing(tmp_path, monkeypatch):
    """Ctrl-C while the parent waits for the PDF: no file, no temporary, the child reaped."""
    import scanplan.reports.pdfworker as pw

    pids: list[int] = []

    def interrupted(self: PdfWorker) -> bytes | None:
        pids.append(self.pid)
        raise KeyboardInterrupt

    monkeypatch.setattr(pw.PdfWorker, "result", interrupted)
    out = tmp_path / "out"
    r = CliRunner().invoke(main, ["plan", str(EXAMPLE), "--out", str(out)])
    assert r.exit_code not in (0, None), r.output
    assert not out.exists() or sorted(out.iterdir()) == []
    assert len(pids) == 1 and pids[0] > 0 and _gone(pids[0])


@fork_only
def test_a_failing_worker_still_writes_the_pdf(tmp_path, monkeypatch):
    """The child dies before it replies: the parent renders the PDF itself."""
    import scanplan.reports.pdfworker as pw

    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    monkeypatch.setattr(pw, "_warm", lambda: os._exit(3))  # the child's first step
    r = CliRunner().invoke(main, ["plan", str(EXAMPLE), "--out", str(tmp_path)])
    assert r.exit_code == 0, r.output
    assert (tmp_path / "spec.pdf").read_bytes().startswith(b"%PDF")


@pytest.mark.parametrize(("args", "absent"), [
    (["plan", str(EXAMPLE)], ("matplotlib", "weasyprint", "pandas", "pyproj", "openpyxl")),
    (["plan", str(EXAMPLE), "--xlsx", "{tmp}/s.xlsx"], ("matplotlib", "weasyprint", "pandas",
                                                        "pyproj")),
    # a polygon from a KML file: GDAL reads it without pandas, no relief module, no
    # spreadsheet reader of the norm importer
    (["plan", str(EXAMPLE.parent / "uav-town-2000.toml")],
     ("matplotlib", "weasyprint", "pandas", "openpyxl", "scanplan.geo.terrain",
      "scanplan.geo.dem", "scanplan.norms.importer", "scanplan.norms.xlsx",
      "numpy.ma")),  # numpy's masked arrays: np.unique imports them to look for a mask
])
def test_what_a_run_does_not_import(tmp_path, args, absent):
    """A plan without reports imports no report library; a workbook alone no plotting,
    PDF or GIS library (issue 15: import only what is used)."""
    argv = [a.replace("{tmp}", str(tmp_path)) for a in args]
    code = ("import sys\n"
            "from scanplan.cli.main import main\n"
            f"try:\n    main({argv!r})\nexcept SystemExit as e:\n    assert not e.code, e.code\n"
            f"print(sorted(m for m in {list(absent)!r} if m in sys.modules))\n")
    r = _run_python(code)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip().splitlines()[-1] == "[]"


def test_the_worker_forks_before_the_writers_are_imported():
    """The PDF worker's child needs the renderer only: importing the worker (the parent
    forks right after) reads neither the file writers nor the project file, which the
    parent imports after the fork; the names the package re-exports still resolve."""
    r = _run_python("import sys\n"
                    "import scanplan.reports.pdfworker\n"
                    "print(sorted(m for m in sys.modules if m.startswith(("
                    "'scanplan.io', 'scanplan.project'))))\n"
                    "from scanplan.reports import ReportMeta, write_atomic, write_atomic_many\n"
                    "print(ReportMeta.__module__, write_atomic.__module__, "
                    "write_atomic_many.__module__)\n")
    assert r.returncode == 0, r.stderr
    before, names = r.stdout.strip().splitlines()[-2:]
    assert before == "[]"
    assert names == "scanplan.project.file scanplan.io.atomic scanplan.io.atomic"


def _pages(pdf: bytes, tmp: Path) -> list[bytes]:
    import shutil

    if shutil.which("pdftoppm") is None:
        pytest.skip("pdftoppm (poppler) is not installed")
    (tmp / "d.pdf").write_bytes(pdf)
    subprocess.run(["pdftoppm", "-r", "60", "-png", "d.pdf", "p"], cwd=tmp, check=True)
    return [p.read_bytes() for p in sorted(tmp.glob("p*.png"))]


@pytest.mark.parametrize("name", ["uav-canon-2000.toml", "film-town-10000.toml"])
def test_the_stylesheet_parsed_once_gives_the_same_pages(name, tmp_path, monkeypatch):
    """report.css is parsed once per process and given as a stylesheet of the document
    (pdfrender._stylesheet): every page is the image of the document that links it."""
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    r = plan_project(load_project(ROOT / "examples" / name))
    html = render_html(view=build_view(scan=r.film.job if r.film else None,
                                       uav=r.uav.job if r.uav else None, meta=r.meta, spec=r))
    assert pdfrender._STYLESHEET_LINK in html
    parsed: list[str] = []
    real = pdfrender.weasyprint.CSS
    monkeypatch.setattr(pdfrender.weasyprint, "CSS", lambda **kw: parsed.append(
        kw["base_url"]) or real(**kw))
    pdfrender._stylesheet.cache_clear()
    ours = [pdfrender.html_to_pdf(html), pdfrender.html_to_pdf(html)]
    assert len(parsed) == 1 and ours[0] == ours[1]
    linked = pdfrender.html_to_pdf(html, fresh_fonts=True)  # WeasyPrint reads the <link>
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    assert _pages(ours[0], tmp_path / "a") == _pages(linked, tmp_path / "b")
