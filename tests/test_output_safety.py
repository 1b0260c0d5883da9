"""Issue 19: never destroy a user's file — where reports may be written.

Items 1 (outputs that are inputs, extensions, foreign files, --force, write-protected files,
symbolic links, ``-``, ``--out`` with ``--xlsx``), 2 (batch names unique per project),
6 (a lock on the output folder; a truthful rollback message), 7 (report names up to the
file system's 255-byte limit; folders fsynced after renames) and issue 17 item 5 (stale
temporaries of a killed write are removed by the next write). Most cases render fixed bytes
(the path handling is under test); the ownership cases render real reports once.
"""

from __future__ import annotations

import contextlib
import errno
import io
import multiprocessing as mp
import os
import stat
import sys
import zipfile
from pathlib import Path

import pytest
from click.testing import CliRunner

import scanplan.reports.excel as excel_mod
import scanplan.reports.pdf as pdf_mod
from scanplan.cli.main import batch_stems, main
from scanplan.errors import InputError, WriteError
from scanplan.io.targets import folder_lock, written_by_scanplan
from scanplan.reports import write_atomic_many

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
FILM = EXAMPLES / "instruction-2000-film.toml"


def cli(*args: str):
    return CliRunner().invoke(main, [str(a) for a in args])


@pytest.fixture()
def work(tmp_path, monkeypatch):
    """A folder with a copy of the film example as ``proj.toml``; the current directory."""
    (tmp_path / "proj.toml").write_bytes(FILM.read_bytes())
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.fixture()
def marked_renders(monkeypatch):
    """Rendering returns small bytes that name the project (and say scanplan made them)."""
    def xlsx(**kw):
        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w") as zf:
            zf.writestr("docProps/core.xml", "<cp:coreProperties><dc:creator>scanplan test"
                        "</dc:creator></cp:coreProperties>")
            zf.writestr("project", kw["meta"].project)
        return buf.getvalue()

    def pdf(**kw):
        return b"%PDF-1.7\n<</Creator (scanplan test)>>\n" + kw["meta"].project.encode()

    monkeypatch.setattr(excel_mod, "render_xlsx", xlsx)
    monkeypatch.setattr(pdf_mod, "render_pdf", pdf)
    monkeypatch.setenv("SCANPLAN_NO_FORK", "1")  # the PDF is this process's stand-in render


def project_of(path: Path) -> str:
    """The project name a marked rendering wrote into ``path``."""
    data = path.read_bytes()
    if data.startswith(b"%PDF"):
        return data.split(b"\n", 2)[2].decode()
    with zipfile.ZipFile(io.BytesIO(data)) as zf:
        return zf.read("project").decode()


# ---------------------------------------------------------------------------------------
# Item 1: an output that is an input; extensions; '-'; --out with --xlsx
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("option", ["--xlsx", "--pdf"])
def test_output_that_is_the_project_file_is_refused(work, marked_renders, option):
    """Bug: ``plan proj.toml --xlsx proj.toml`` exited 0 and replaced the project file."""
    before = (work / "proj.toml").read_bytes()
    r = cli("plan", "proj.toml", option, "proj.toml")
    assert r.exit_code == 2
    assert f"error: {option}: 'proj.toml' is the input file 'proj.toml'" in r.stderr
    assert (work / "proj.toml").read_bytes() == before


def test_output_that_is_the_project_through_a_link_is_refused_even_with_force(
        work, marked_renders):
    """The same file under another name (a hard link with the right extension, a symbolic
    link) is still the input; --force does not change that."""
    os.link(work / "proj.toml", work / "proj.pdf")
    (work / "alias.xlsx").symlink_to(work / "proj.toml")
    before = (work / "proj.toml").read_bytes()
    for option, target in (("--pdf", "proj.pdf"), ("--xlsx", "alias.xlsx")):
        r = cli("plan", "proj.toml", option, target, "--force")
        assert r.exit_code == 2, r.output
        assert "is the input file 'proj.toml'" in r.stderr
    assert (work / "proj.toml").read_bytes() == before


@pytest.mark.parametrize(("option", "name", "needed"), [
    ("--xlsx", "report.pdf", ".xlsx"), ("--xlsx", "report", ".xlsx"),
    ("--pdf", "report.xlsx", ".pdf"), ("--pdf", "report.toml", ".pdf")])
def test_extension_must_fit_the_report(work, marked_renders, option, name, needed):
    r = cli("plan", "proj.toml", option, name)
    assert r.exit_code == 2
    assert f"error: {option}: {name!r} does not end in {needed}" in r.stderr
    assert not (work / name).exists()


def test_extension_is_checked_without_case(work, marked_renders):
    r = cli("plan", "proj.toml", "--xlsx", "R.XLSX", "--pdf", "R.Pdf")
    assert r.exit_code == 0, r.output
    assert (work / "R.XLSX").is_file() and (work / "R.Pdf").is_file()


@pytest.mark.parametrize("command", ["plan", "scan"])
def test_dash_is_refused(work, marked_renders, command):
    args = (["plan", "proj.toml"] if command == "plan" else
            ["scan", "--map-scale", "2000", "--relief", "1", "--photo-scale", "10000",
             "--camera", "rc30-153"])
    r = cli(*args, "--xlsx", "-")
    assert r.exit_code == 2
    assert "error: --xlsx: '-' (standard output) cannot take a report" in r.stderr
    assert not (work / "-").exists()


def test_out_together_with_xlsx_is_refused(work, marked_renders):
    """Bug: ``--out`` silently won over ``--xlsx``."""
    r = cli("plan", "proj.toml", "--out", "out", "--xlsx", "a.xlsx")
    assert r.exit_code == 2
    assert "error: --out: give either --out" in r.stderr
    assert not (work / "out").exists() and not (work / "a.xlsx").exists()


# ---------------------------------------------------------------------------------------
# Item 1: existing files — ours, foreign, empty, write-protected, links, folders
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("option", ["--xlsx", "--pdf"])
def test_foreign_file_is_kept_without_force_and_replaced_with_it(work, marked_renders, option):
    name = "mine.xlsx" if option == "--xlsx" else "mine.pdf"
    (work / name).write_bytes(b"the user's own file")
    r = cli("plan", "proj.toml", option, name)
    assert r.exit_code == 2
    assert f"error: {option}: {name!r} exists and was not written by scanplan; give " \
           "--force" in r.stderr
    assert (work / name).read_bytes() == b"the user's own file"
    r = cli("plan", "proj.toml", option, name, "--force")
    assert r.exit_code == 0, r.output
    assert written_by_scanplan(work / name, name[-4:].lstrip("."))


def test_our_own_reports_are_replaced_without_force(work):
    """Real reports from a previous run (workbook creator and PDF /Creator say scanplan)
    are recognised, so re-running a plan needs no --force."""
    r = cli("plan", "proj.toml", "--out", "out")
    assert r.exit_code == 0, r.output
    assert written_by_scanplan(work / "out/spec.xlsx", "xlsx")
    assert written_by_scanplan(work / "out/spec.pdf", "pdf")
    assert not written_by_scanplan(work / "out/spec.pdf", "xlsx")
    stamp = (work / "out/spec.pdf").stat().st_ino
    r = cli("plan", "proj.toml", "--out", "out")
    assert r.exit_code == 0, r.output
    assert (work / "out/spec.pdf").stat().st_ino != stamp  # replaced


@pytest.mark.parametrize(("data", "kind", "ours"), [
    (b"", "pdf", False), (b"%PDF-1.7 made by Word /Creator (Microsoft Word)", "pdf", False),
    (b"PK\x03\x04 not really a zip", "xlsx", False),
    (b"%PDF-1.4\n<</Creator (scanplan 0.1.0)>>", "pdf", True),
    (b"%PDF-1.4\n<</Creator (scanplanner 2)>>", "pdf", False)])
def test_written_by_scanplan(tmp_path, data, kind, ours):
    p = tmp_path / f"x.{kind}"
    p.write_bytes(data)
    assert written_by_scanplan(p, kind) is ours


def test_an_empty_file_is_replaced(work, marked_renders):
    """An empty file (``touch report.pdf``) holds nothing to lose."""
    (work / "r.pdf").write_bytes(b"")
    r = cli("plan", "proj.toml", "--pdf", "r.pdf")
    assert r.exit_code == 0, r.output
    assert (work / "r.pdf").read_bytes().startswith(b"%PDF")


def test_write_protected_file_is_refused_even_with_force(work, marked_renders):
    (work / "old.pdf").write_bytes(b"%PDF-1.4\n<</Creator (scanplan 0.1.0)>>")
    (work / "old.pdf").chmod(0o444)
    before = (work / "old.pdf").read_bytes()
    r = cli("plan", "proj.toml", "--pdf", "old.pdf", "--force")
    assert r.exit_code == 2
    assert "error: --pdf: 'old.pdf' is write-protected" in r.stderr
    assert (work / "old.pdf").read_bytes() == before
    assert stat.S_IMODE((work / "old.pdf").stat().st_mode) == 0o444


def test_symbolic_link_is_refused_and_its_file_kept(work, marked_renders):
    (work / "real.pdf").write_bytes(b"%PDF-1.4\n<</Creator (scanplan 0.1.0)>>")
    (work / "link.pdf").symlink_to("real.pdf")
    (work / "dangling.xlsx").symlink_to("nowhere.xlsx")
    r = cli("plan", "proj.toml", "--pdf", "link.pdf", "--force")
    assert r.exit_code == 2
    assert "error: --pdf: 'link.pdf' is a symbolic link (to 'real.pdf')" in r.stderr
    assert (work / "link.pdf").is_symlink()
    r = cli("plan", "proj.toml", "--xlsx", "dangling.xlsx")
    assert r.exit_code == 2 and "is a symbolic link" in r.stderr
    assert not (work / "nowhere.xlsx").exists()


def test_fifo_target_is_refused_without_opening_it(work, marked_renders):
    os.mkfifo(work / "pipe.pdf")
    r = cli("plan", "proj.toml", "--pdf", "pipe.pdf")
    assert r.exit_code == 2
    assert "is a FIFO (named pipe); give a file name" in r.stderr
    assert stat.S_ISFIFO(os.lstat(work / "pipe.pdf").st_mode)


def test_foreign_file_in_out_folder_stops_one_project_of_a_batch(work, marked_renders):
    """In a batch the refusal is that project's error (exit 2); the others are written."""
    (work / "b.toml").write_bytes(FILM.read_bytes())
    (work / "out").mkdir()
    (work / "out/b.pdf").write_bytes(b"someone's notes")
    r = cli("plan", "proj.toml", "b.toml", "--out", "out")
    assert r.exit_code == 2
    assert "'out/b.pdf' exists and was not written by scanplan" in r.stderr
    assert (work / "out/b.pdf").read_bytes() == b"someone's notes"
    assert not (work / "out/b.xlsx").exists()  # the pair is refused as one
    assert (work / "out/proj.xlsx").is_file() and (work / "out/proj.pdf").is_file()


# ---------------------------------------------------------------------------------------
# Item 2: batch outputs unique per project
# ---------------------------------------------------------------------------------------


def _project(folder: Path, name: str, title: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    text = FILM.read_text(encoding="utf-8")
    lines = [f'name = "{title}"' if line.startswith("name =") else line
             for line in text.splitlines()]
    p = folder / name
    p.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return p


def test_batch_projects_with_one_name_get_their_own_reports(work, marked_renders):
    """Bug: ``plan a/x.toml b/x.toml --out out`` wrote out/x.* twice (the second pair
    replaced the first) and reported both written."""
    a = _project(work / "a", "x.toml", "Project A")
    b = _project(work / "b", "x.toml", "Project B")
    c = _project(work / "c", "X.toml", "Project C")  # a case-insensitive file system
    r = cli("plan", a, b, c, "--out", "out")
    assert r.exit_code == 0, r.output
    assert {p.name for p in (work / "out").iterdir()} == {
        "x.xlsx", "x.pdf", "x-2.xlsx", "x-2.pdf", "X-3.xlsx", "X-3.pdf",
        "summary.csv", "summary.xlsx"}  # the batch summary (issue 15)
    assert project_of(work / "out/x.xlsx") == "Project A"
    assert project_of(work / "out/x-2.pdf") == "Project B"
    assert project_of(work / "out/X-3.xlsx") == "Project C"
    assert f"wrote out/x-2.xlsx (for {b}; the name x is taken by another project" in r.stderr
    assert f"wrote out/x.pdf (for {a})" in r.stderr


def test_batch_stems():
    assert batch_stems(["a/x.toml", "b/x.toml", "c/x-2.toml", "d/y.toml"]) == [
        "x", "x-2", "x-2-2", "y"]
    assert batch_stems(["A.toml", "a.toml"]) == ["A", "a-2"]


# ---------------------------------------------------------------------------------------
# Item 6: a lock on the output folder; a truthful rollback message
# ---------------------------------------------------------------------------------------


def _writer(folder: str, tag: str, rounds: int) -> None:
    """Write the pair ``rounds`` times, slowly between the renames (a wide window)."""
    import time

    real = os.replace

    def slow_replace(src, dst, **kw):
        real(src, dst, **kw)
        time.sleep(0.002)

    os.replace = slow_replace  # this child process only
    for i in range(rounds):
        data = f"{tag}-{i}".encode()
        write_atomic_many({os.path.join(folder, "spec.xlsx"): data,
                           os.path.join(folder, "spec.pdf"): data})


def _checker(folder: str, rounds: int, out: mp.Queue) -> None:
    """Read the pair under the folder lock; count pairs from two different writes."""
    mixed = seen = 0
    for _ in range(rounds):
        with folder_lock([folder]):
            try:
                x = Path(folder, "spec.xlsx").read_bytes()
                p = Path(folder, "spec.pdf").read_bytes()
            except FileNotFoundError:
                continue
        seen += 1
        mixed += x != p
    out.put((seen, mixed))


def test_two_writers_into_one_folder_never_mix_their_pairs(tmp_path):
    """Bug: two writers to one --out could leave one's spec.xlsx beside the other's
    spec.pdf. Every pair a reader sees under the folder lock is one write's pair."""
    ctx = mp.get_context("fork")
    folder = str(tmp_path)
    q: mp.Queue = ctx.Queue()
    procs = [ctx.Process(target=_writer, args=(folder, t, 25)) for t in ("A", "B", "C")]
    checker = ctx.Process(target=_checker, args=(folder, 200, q))
    for p in [*procs, checker]:
        p.start()
    for p in [*procs, checker]:
        p.join(120)
        assert p.exitcode == 0
    seen, mixed = q.get(timeout=10)
    assert seen > 0 and mixed == 0
    assert Path(folder, "spec.xlsx").read_bytes() == Path(folder, "spec.pdf").read_bytes()
    assert sorted(os.listdir(folder)) == ["spec.pdf", "spec.xlsx"]  # nothing left over


def test_rollback_message_says_when_another_program_changed_a_file(tmp_path, monkeypatch):
    """Bug: a rollback reported "none … was changed" although a file had changed. A file
    another program (not holding the lock) replaced during the write is named."""
    x, p = tmp_path / "spec.xlsx", tmp_path / "spec.pdf"
    x.write_bytes(b"old x")
    p.write_bytes(b"old p")
    real = os.replace
    calls = []

    def replace(src, dst, **kw):
        calls.append(dst)
        if len(calls) == 2:  # the PDF's rename: someone else wrote it just now
            p.unlink()
            p.write_bytes(b"another program's PDF")
            raise OSError(errno.EIO, os.strerror(errno.EIO))
        return real(src, dst, **kw)

    monkeypatch.setattr(os, "replace", replace)
    with pytest.raises(WriteError) as info:
        write_atomic_many({x: b"new x", p: b"new p"})
    monkeypatch.undo()
    msg = str(info.value)
    assert "none of" not in msg
    assert f"{p} changed during the write (by another program)" in msg
    assert x.read_bytes() == b"old x"


def test_rollback_message_when_nothing_else_changed(tmp_path, monkeypatch):
    x, p = tmp_path / "spec.xlsx", tmp_path / "spec.pdf"
    x.write_bytes(b"old x")
    real = os.replace
    calls = []

    def replace(src, dst, **kw):
        calls.append(dst)
        if len(calls) == 2:
            raise OSError(errno.EIO, os.strerror(errno.EIO))
        return real(src, dst, **kw)

    monkeypatch.setattr(os, "replace", replace)
    with pytest.raises(WriteError, match=f"none of {x}, {p} was changed"):
        write_atomic_many({x: b"new x", p: b"new p"})
    monkeypatch.undo()
    assert x.read_bytes() == b"old x" and not p.exists()


# ---------------------------------------------------------------------------------------
# Issue 17 item 5: stale temporaries of a killed write
# ---------------------------------------------------------------------------------------


def test_stale_temporaries_are_removed_by_the_next_write(tmp_path):
    stale = [".spec.xlsx.ab12cd_9.tmp", ".spec.pdf.0123abcd.old", ".spec.pdf.zz9_yy8x.tmp"]
    kept = [".spec.xlsx.notes.tmp", ".other.pdf.0123abcd.tmp", ".spec.xlsx.0123abcd.bak",
            "spec.xlsx.0123abcd.tmp"]
    for name in stale + kept:
        (tmp_path / name).write_bytes(b"x")
    (tmp_path / ".spec.pdf.abcdabcd.tmp").mkdir()  # not a file: not ours, kept
    write_atomic_many({tmp_path / "spec.xlsx": b"x", tmp_path / "spec.pdf": b"p"})
    names = set(os.listdir(tmp_path))
    assert names == {*kept, ".spec.pdf.abcdabcd.tmp", "spec.xlsx", "spec.pdf"}


def test_killed_write_leftovers_are_cleaned_end_to_end(tmp_path):
    """A child killed with SIGKILL in the middle of writing leaves its temporary; the next
    write to that folder removes it."""
    import signal

    ctx = mp.get_context("fork")

    def child() -> None:
        import scanplan.io.atomic as rep  # the atomic writers live in io.atomic

        real = rep._write_temp

        def die(target, data):
            tmp = real(target, data)
            os.kill(os.getpid(), signal.SIGKILL)
            return tmp

        rep._write_temp = die
        write_atomic_many({tmp_path / "spec.xlsx": b"x", tmp_path / "spec.pdf": b"p"})

    p = ctx.Process(target=child)
    p.start()
    p.join(60)
    assert p.exitcode == -signal.SIGKILL
    assert [n for n in os.listdir(tmp_path) if n.endswith(".tmp")]  # the leftover
    write_atomic_many({tmp_path / "spec.xlsx": b"x2", tmp_path / "spec.pdf": b"p2"})
    assert sorted(os.listdir(tmp_path)) == ["spec.pdf", "spec.xlsx"]


# ---------------------------------------------------------------------------------------
# Item 7: long names; directory fsync
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("size", [242, 250, 255])
def test_report_names_up_to_255_bytes(work, marked_renders, size):
    """Bug: names of 242–255 bytes were refused (the temporary name was too long)."""
    stem = "я" * ((size - 5) // 2) + "a" * ((size - 5) % 2)  # two-byte letters
    name = stem + ".xlsx"
    assert len(name.encode()) == size
    r = cli("plan", "proj.toml", "--xlsx", name)
    assert r.exit_code == 0, r.output
    assert (work / name).is_file()
    r = cli("plan", "proj.toml", "--xlsx", name)  # and replaced (a backup name is needed)
    assert r.exit_code == 0, r.output
    assert sorted(os.listdir(work)) == sorted(["proj.toml", name])


def test_report_name_over_the_limit_is_bad_input(work, marked_renders):
    name = "a" * 251 + ".xlsx"
    r = cli("plan", "proj.toml", "--xlsx", name)
    assert r.exit_code == 2
    assert "error: --xlsx: the file name is 256 bytes long; the file system allows 255" \
        in r.stderr


def _dir_fsyncs(monkeypatch) -> list[str]:
    synced: list[str] = []
    real = os.fsync

    def fsync(fd):
        if stat.S_ISDIR(os.fstat(fd).st_mode):
            synced.append(os.readlink(f"/proc/self/fd/{fd}"))
        return real(fd)

    monkeypatch.setattr(os, "fsync", fsync)
    return synced


@pytest.mark.skipif(not os.path.isdir("/proc/self/fd"), reason="needs /proc")
def test_report_folder_is_fsynced_after_the_renames(tmp_path, monkeypatch):
    synced = _dir_fsyncs(monkeypatch)
    write_atomic_many({tmp_path / "spec.xlsx": b"x", tmp_path / "spec.pdf": b"p"})
    assert set(synced) == {str(tmp_path)} and synced[-1] == str(tmp_path)


@pytest.mark.skipif(not os.path.isdir("/proc/self/fd"), reason="needs /proc")
def test_norm_folder_is_fsynced_after_the_swap(user_dir, monkeypatch):
    from norm_corpus import english_workbook, save

    from scanplan.norms import import_norm_file

    src = save(english_workbook(), user_dir.parent, "n.xlsx")
    synced = _dir_fsyncs(monkeypatch)
    import_norm_file(src, "mine")
    assert str(user_dir) in synced
    synced.clear()
    import_norm_file(src, "mine", force=True)
    assert str(user_dir) in synced


def test_norm_template_follows_the_same_rules(work):
    """``norms template FILE --force`` refuses a symbolic link and a write-protected file
    like the reports do (it replaced the link with a workbook)."""
    (work / "l.xlsx").symlink_to("proj.toml")
    (work / "ro.xlsx").write_bytes(b"x")
    (work / "ro.xlsx").chmod(0o444)
    r = cli("norms", "template", "l.xlsx", "--force")
    assert r.exit_code == 2 and "is a symbolic link" in r.output
    assert (work / "l.xlsx").is_symlink()
    r = cli("norms", "template", "ro.xlsx", "--force")
    assert r.exit_code == 2 and "is write-protected" in r.output
    assert (work / "ro.xlsx").read_bytes() == b"x"


@pytest.mark.parametrize("args", [
    ["plan", "{uav}", "--pdf", "{missing}/s.pdf"],
    ["plan", "{uav}", "--xlsx", "{missing}/s.xlsx"],
    ["uav", "--camera", "canon-eos-5d-mark-ii-50", "--height-m", "300", "--pdf",
     "{missing}/u.pdf"],
    ["scan", "--map-scale", "2000", "--relief", "0.5", "--photo-scale", "10000",
     "--camera", "rc30-153", "--xlsx", "{missing}/s.xlsx"],
], ids=["plan-pdf", "plan-xlsx", "uav-pdf", "scan-xlsx"])
def test_a_report_into_a_missing_folder_is_refused_before_the_plan(args, tmp_path):
    """Exit 2 naming the option, before anything is planned or printed (the audit found
    the plan printed first and the error after it)."""
    missing = tmp_path / "no-such-folder"
    argv = [a.format(uav=EXAMPLES / "uav-canon-2000.toml", missing=missing) for a in args]
    r = CliRunner().invoke(main, argv)
    assert r.exit_code == 2, r.output
    option = "--pdf" if any(a.endswith(".pdf") for a in argv) else "--xlsx"
    assert r.stdout == "" and f"{option}: folder" in r.stderr, (r.stdout, r.stderr)
    assert not missing.exists()


# ---------------------------------------------------------------------------------------
# The whole output set of a polygon plan is one transaction: crash points, concurrency
# ---------------------------------------------------------------------------------------


def _polygon_project(folder: Path, name: str, flight_min: int) -> Path:
    """The town example as ``name`` with ``max_flight_time_min`` in place of its aircraft
    (sorties change with it)."""
    text = (EXAMPLES / "uav-town-2000.toml").read_text(encoding="utf-8")
    text = text.replace('file = "areas/', f'file = "{EXAMPLES}/areas/')
    text = text.replace('aircraft = "dji-m350-rtk"', f"max_flight_time_min = {flight_min}")
    assert f"max_flight_time_min = {flight_min}" in text  # the example still names its aircraft
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def town_plans(tmp_path_factory):
    """The town plan with six sorties (``old``) and with fewer (``new``), planned once."""
    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project

    d = tmp_path_factory.mktemp("town")
    return {key: plan_project(load_project(_polygon_project(d, f"{key}.toml", minutes)))
            for key, minutes in (("old", 25), ("new", 60))}


@pytest.fixture()
def planned(monkeypatch, town_plans, marked_renders):
    """``plan`` returns the cached plan of the project file's stem (old/new/block), and
    its mission and GIS files rendered once."""
    import scanplan.project.spec as spec_mod

    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")  # the GeoPackage's timestamps
    real = spec_mod.plan_project

    def cached(project):
        stem = Path(str(getattr(project, "path", "") or "")).stem
        return town_plans[stem] if stem in town_plans else real(project)

    monkeypatch.setattr(spec_mod, "plan_project", cached)

    # The mission and GIS files of a cached plan are rendered once per folder too: the
    # rendering is nine tenths of a write, and these tests are about the transaction that
    # writes the files (the same bytes every time: the tests compare sets byte for byte)
    import scanplan.reports.exports as exports_mod

    real_exports = exports_mod.export_files
    rendered: dict[tuple[int, str, str], tuple[dict, list[str]]] = {}

    def cached_exports(spec, folder, *, prefix="", note=None):
        if not any(spec is p for p in town_plans.values()):
            return real_exports(spec, folder, prefix=prefix, note=note)
        key = (id(spec), folder, prefix)
        if key not in rendered:
            notes: list[str] = []
            rendered[key] = (real_exports(spec, folder, prefix=prefix, note=notes.append),
                             notes)
        files, notes = rendered[key]
        for line in notes if note else ():
            note(line)
        return dict(files)

    monkeypatch.setattr(exports_mod, "export_files", cached_exports)

    def xlsx(**kw):  # as marked_renders, but the same bytes every time (a fixed zip date)
        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w") as zf:
            for name, text in (("docProps/core.xml", "<dc:creator>scanplan test</dc:creator>"),
                               ("project", kw["meta"].project)):
                zf.writestr(zipfile.ZipInfo(name, (2020, 1, 1, 0, 0, 0)), text)
        return buf.getvalue()

    monkeypatch.setattr(excel_mod, "render_xlsx", xlsx)


def _visible(folder: Path) -> dict[str, bytes]:
    """The files a reader finds in ``folder``: name → bytes (a link that leads nowhere —
    a name the visible set does not hold — is no file)."""
    out = {}
    for p in folder.iterdir():
        if not p.name.startswith("."):
            with contextlib.suppress(FileNotFoundError):
                out[p.name] = p.read_bytes()
    return out


def _hidden(folder: Path) -> list[str]:
    """Hidden things in ``folder`` other than its sets, and in its sets anything but the
    current set and the one before it (a temporary, a backup, a journal, a half-made set)."""
    from scanplan.io.folderset import SETS

    sets = folder / SETS
    inside = sorted(os.listdir(sets)) if sets.is_dir() else []
    keep = {"current", "previous", *(os.readlink(sets / n) for n in ("current", "previous")
                                      if (sets / n).is_symlink())}
    return [n for n in os.listdir(folder) if n.startswith(".") and n != SETS] + [
        f"{SETS}/{n}" for n in inside if n not in keep]


def _write_set(work: Path, stem: str) -> dict[str, bytes]:
    """``plan STEM.toml --out out``; the folder's files after it."""
    r = cli("plan", f"{stem}.toml", "--out", "out", "--force")
    assert r.exit_code == 0, r.output
    return _visible(work / "out")


def _killed_at(step: int, work: Path) -> int:
    """Run ``plan new.toml --out out`` in a child that is killed (SIGKILL) just before its
    ``step``-th change of the folder's entries (a rename, a link or symbolic link, an
    unlink, a folder made or removed); its exit code (0: it finished)."""
    import signal

    out = os.path.abspath(work / "out")

    def child() -> None:
        count = [0]
        for name in ("replace", "rename", "link", "symlink", "unlink", "mkdir", "rmdir"):
            real = getattr(os, name)

            def op(*args, _real=real, **kw):
                if any(os.path.abspath(os.fspath(a)).startswith(out) for a in args[:2]
                       if isinstance(a, str | os.PathLike)):
                    count[0] += 1
                    if count[0] == step:
                        os.kill(os.getpid(), signal.SIGKILL)
                return _real(*args, **kw)

            setattr(os, name, op)
        r = cli("plan", "new.toml", "--out", "out", "--force")
        if r.exit_code:
            print(r.output, repr(r.exception), file=sys.stderr, flush=True)
        os._exit(r.exit_code)

    p = mp.get_context("fork").Process(target=child)
    p.start()
    p.join(120)
    return p.exitcode


def test_a_polygon_plan_killed_at_every_step_leaves_all_old_or_all_new(work, planned):
    """Bug: a kill -9 between two renames left an old mission-03 beside a new plan of
    fewer sorties in the folder, until the next write recovered it — a crew copying the
    missions after a crash took a mixed set. Killed before each change of the folder's
    entries (every rename, link, unlink, folder made or removed: the new set built, the
    plain files of the old layout adopted, the links made, the swap, the stale missions'
    links dropped), the folder **at the instant after the kill** — no recovery — shows a
    reader the old set or the new one, byte for byte; the next write leaves nothing
    behind."""
    _polygon_project(work, "old.toml", 25)
    _polygon_project(work, "new.toml", 60)
    new = _write_set(work, "new")
    old = _write_set(work, "old")
    assert len([n for n in old if n.endswith(".plan")]) > len(
        [n for n in new if n.endswith(".plan")])  # the new plan has fewer sorties
    for plain in (False, True):  # a folder of sets; one of plain files (adopted first)
        outcomes = []
        for step in range(1, 1000):
            if plain:
                _plain_files(work / "out")
            code = _killed_at(step, work)
            after = _visible(work / "out")  # the instant after the kill: nothing recovered
            if code == 0:  # the child ran to the end: every step was tried
                break
            assert code == -9, code
            assert after in (old, new), (f"killed at step {step}: a mixed set", sorted(
                n for n in set(after) | set(old) if after.get(n) != old.get(n)), sorted(
                n for n in set(after) | set(new) if after.get(n) != new.get(n)))
            outcomes.append("new" if after == new else "old")
            _write_set(work, "old")  # the next write: the old set again, nothing left over
            assert _hidden(work / "out") == []
        assert _visible(work / "out") == new
        assert "old" in outcomes and "new" in outcomes  # the commit point lies between
        if plain:  # each plain file linked and renamed while adopted
            assert len(outcomes) > 2 * len(old)
        _write_set(work, "old")


def _plain_files(folder: Path) -> None:
    """The folder as an earlier scanplan left it: plain files, no sets."""
    import shutil

    from scanplan.io.folderset import SETS

    files = _visible(folder)
    shutil.rmtree(folder / SETS, ignore_errors=True)
    for p in folder.iterdir():
        p.unlink()
    for name, data in files.items():
        (folder / name).write_bytes(data)


def _writer_of(project: str, folder: str, rounds: int) -> None:
    for _ in range(rounds):
        r = cli("plan", project, "--out", folder, "--force")
        if r.exit_code != 0:
            print(f"{project}: exit {r.exit_code}: {r.output}", file=sys.stderr, flush=True)
            os._exit(3)


def _set_checker(folder: str, sets: list[dict[str, bytes]], rounds: int,
                 out: mp.Queue) -> None:
    """Read the folder under its lock; count states that are no run's complete set."""
    mixed = seen = 0
    for _ in range(rounds):
        with folder_lock([folder]):
            files = _visible(Path(folder))
        if not files:
            continue
        seen += 1
        mixed += files not in sets
    out.put((seen, mixed))


@pytest.mark.parametrize("look", ["access", "written_by_scanplan"])
def test_a_file_another_run_sweeps_away_during_the_check_is_not_refused(work, monkeypatch,
                                                                        look):
    """Bug: the check before rendering (it runs without the folder's lock) saw a mission
    file, then another run's transaction swept it away; the next look at the vanished file
    (may I write it? did scanplan write it?) said no, and the run stopped with "is
    write-protected" (one run in a few hundred of the test below). A file gone meanwhile
    has nothing to protect: the check under the lock decides."""
    import scanplan.io.targets as targets

    target = work / "gone.pdf"
    target.write_bytes(b"%PDF-1.7 not ours")

    def swept(real):
        def look_after_sweep(*args, **kw):
            target.unlink(missing_ok=True)  # another run's sweep, between two looks
            return real(*args, **kw)
        return look_after_sweep

    if look == "access":
        monkeypatch.setattr(targets.os, "access", swept(os.access))
    else:
        monkeypatch.setattr(targets, "written_by_scanplan", swept(written_by_scanplan))
    targets.check_target(str(target), "--out", "pdf", force=False)  # no InputError
    assert not target.exists()
    target.write_bytes(b"%PDF-1.7 not ours")  # still there at every look: refused
    monkeypatch.undo()
    with pytest.raises(InputError, match="not written by scanplan"):
        targets.check_target(str(target), "--out", "pdf", force=False)


def test_different_projects_into_one_folder_never_delete_each_others_files(work, planned):
    """Bug: a run of a project without a polygon swept, after its own write, the missions
    and GIS files another run had just written into the same folder. The sweep is part of
    the transaction now: the folder is always one run's complete set."""
    _polygon_project(work, "old.toml", 25)
    (work / "block.toml").write_bytes(FILM.read_bytes())  # no polygon: no exported files
    town = _write_set(work, "old")
    block = _write_set(work, "block")
    assert set(block) == {"spec.xlsx", "spec.pdf"} and len(town) > 10
    ctx = mp.get_context("fork")
    q: mp.Queue = ctx.Queue()
    procs = [ctx.Process(target=_writer_of, args=(p, "out", 4))
             for p in ("old.toml", "block.toml")]
    checker = ctx.Process(target=_set_checker, args=(str(work / "out"), [town, block], 300, q))
    for p in [*procs, checker]:
        p.start()
    for p in [*procs, checker]:
        p.join(300)
        assert p.exitcode == 0
    seen, mixed = q.get(timeout=10)
    assert seen > 0 and mixed == 0
    assert _visible(work / "out") in (town, block)
    assert _hidden(work / "out") == []


@pytest.mark.parametrize("name", ["flight.kml", "flight.geojson"])
def test_the_area_file_is_never_replaced_even_with_force(work, planned, name):
    """Bug: an area saved as OUT/flight.kml (or .geojson) was overwritten by the exported
    flight with --force; only project files were protected as inputs."""
    out = work / "out"
    out.mkdir()
    src = EXAMPLES / "areas" / "town-uav.kml"
    if name.endswith(".kml"):
        (out / name).write_bytes(src.read_bytes())
    else:
        import json

        import pyogrio.raw
        import shapely

        _, _, geometry, _ = pyogrio.raw.read(src)
        polygon = shapely.from_wkb(geometry[0])
        (out / name).write_text(json.dumps({"type": "FeatureCollection", "features": [
            {"type": "Feature", "properties": {},
             "geometry": shapely.geometry.mapping(polygon)}]}), encoding="utf-8")
    before = (out / name).read_bytes()
    text = (EXAMPLES / "uav-town-2000.toml").read_text(encoding="utf-8")
    (work / "area.toml").write_text(text.replace('file = "areas/town-uav.kml"',
                                                 f'file = "out/{name}"'), encoding="utf-8")
    r = cli("plan", "area.toml", "--out", "out", "--force")
    assert r.exit_code == 2, r.output
    assert f"--out: 'out/{name}' is the input file" in r.stderr
    assert (out / name).read_bytes() == before
    assert sorted(os.listdir(out)) == [name]  # nothing of the set was written


def test_a_batch_project_named_summary_keeps_its_workbook(work, marked_renders):
    """Bug: a batch project summary.toml wrote summary.xlsx, which the batch summary then
    replaced. The project gets summary-2.xlsx (and is told why)."""
    (work / "summary.toml").write_bytes(FILM.read_bytes())
    r = cli("plan", "summary.toml", "proj.toml", "--out", "out")
    assert r.exit_code == 0, r.output
    names = sorted(os.listdir(work / "out"))
    assert names == ["proj.pdf", "proj.xlsx", "summary-2.pdf", "summary-2.xlsx",
                     "summary.csv", "summary.xlsx"]
    assert "the name summary is taken by the batch summary" in r.stderr
    assert project_of(work / "out" / "summary-2.xlsx")
    assert batch_stems(["summary.toml", "Summary.toml"]) == ["summary-2", "Summary-3"]
