"""Plan every example in English and Russian and compare two such runs.

A restructuring that must not change what scanplan produces is checked with it: make a
folder of outputs from the code before the change, another from the code after, and
compare them::

    python tools/compare_outputs.py make before/ --source /path/to/old/tree
    python tools/compare_outputs.py make after/
    python tools/compare_outputs.py compare before/ after/

``make`` copies the source tree of ``--source`` into a temporary folder, and
``examples/`` (with ``tools/compare_projects/``) beside it once per language (the
``[project] locale`` line set to ``en`` or ``ru``), and runs ``scanplan plan PROJECT
--out DIR`` (the files and the terminal summary) and ``scanplan plan PROJECT --json`` for
each project with that copy of the code, ``SOURCE_DATE_EPOCH`` set and no user
configuration or norm sets. (Both runs' paths — the bundled norm sets', the projects' —
then differ only in the temporary folder.)

``compare`` reads files that are not byte-identical as what a reader sees: a PDF's text
(``pdftotext -layout``), a workbook's cell values (openpyxl), a GeoPackage's rows
(sqlite3), a zip's members, anything else as text, with each run's temporary folder
replaced by ``<work>``. It prints each difference and exits 1 on any.
"""

from __future__ import annotations

import argparse
import difflib
import json
import os
import re
import shutil
import sqlite3
import subprocess
import sys
import tempfile
import zipfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
EXTRA_PROJECTS = Path(__file__).resolve().parent / "compare_projects"
"""Projects compared beside the examples: what no example shows (film and a UAV in one
project, the comparison table), planned with the examples' area files."""
LOCALES = ("en", "ru")
MANIFEST = "manifest.json"
WORK_MARK = "<work>"
JOB_FOLDER = re.compile(r"scanplan-job-[A-Za-z0-9_]+")
"""The page's temporary folder of one job, which its exported files name."""
JOB_MARK = "scanplan-job-<id>"
EPOCH = "1700000000"
MAX_DIFF_LINES = 40
FACES = Path(__file__).resolve().parent / "compare_faces.py"
TERMINALS: dict[str, list[str]] = {
    "scan-instruction": ["scan", "--map-scale", "1:2000", "--relief", "1.0", "--photo-scale",
                         "1:10000", "--camera", "afa-te-100", "--resolving-power", "40",
                         "--pdf", "scan.pdf", "--xlsx", "scan.xlsx"],
    "scan-scales": ["scan", "--map-scale", "2000", "--relief", "0.5", "--camera", "rc30-153",
                    "--photo-scale", "5000", "--photo-scale", "10000", "--photo-scale",
                    "15000"],
    "uav-ptero": ["uav", "--camera", "canon-eos-5d-mark-ii-50", "--f-number", "8",
                  "--height-m", "300", "--height-tolerance-pct", "40", "--speed-ms", "25",
                  "--shift-factor", "0.65", "--map-scale", "2000", "--relief", "0.5",
                  "--pdf", "uav.pdf", "--xlsx", "uav.xlsx"],
    "uav-area": ["uav", "--camera", "dji-zenmuse-p1-35", "--height-m", "100", "--area-m",
                 "300x400"],
    "cameras-list": ["cameras", "list"],
    "cameras-show-film": ["cameras", "show", "rc30-153"],
    "cameras-show-digital": ["cameras", "show", "dji-zenmuse-p1-35"],
    "norms-list": ["norms", "list"],
    "norms-show": ["norms", "show", "gkinp-02-036-02"],
}
"""The other commands whose terminal (and documents) are compared, by name: the
arguments, to which ``--locale LOCALE`` is added."""
NOT_CODE = (".git", "tests", "benchmarks", "docs", "examples", "tools", "__pycache__", "*.pyc")


# -- make -------------------------------------------------------------------------------


def with_locale(text: str, locale: str) -> str:
    """The project file ``text`` with its ``[project] locale`` set to ``locale``.

    Parameters
    ----------
    text : str
        A project file (TOML).
    locale : str
        ``"en"`` or ``"ru"``.

    Returns
    -------
    str
        The file with its ``locale = …`` line replaced, or one added under ``[project]``.
    """
    line = f'locale = "{locale}"'
    new, count = re.subn(r'(?m)^locale\s*=.*$', line, text, count=1)
    if count:
        return new
    return re.sub(r"(?m)^\[project\]\s*$", f"[project]\n{line}", text, count=1)


def copy_projects(examples: Path, into: Path, locale: str) -> list[Path]:
    """Copy the ``examples`` folder to ``into`` with every project in ``locale``.

    Returns
    -------
    list of Path
        The copied project files, sorted by name.
    """
    shutil.copytree(examples, into)
    for extra in sorted(EXTRA_PROJECTS.glob("*.toml")):  # read beside the examples' files
        shutil.copy2(extra, into / extra.name)
    projects = sorted(into.glob("*.toml"))
    for path in projects:
        path.write_text(with_locale(path.read_text(encoding="utf-8"), locale), encoding="utf-8")
    return projects


def _environment(source: Path, home: Path) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items()
           if not k.startswith("SCANPLAN_") and k != "PYTHONPATH"}
    env.update(PYTHONPATH=str(source), SOURCE_DATE_EPOCH=EPOCH, HOME=str(home),
               XDG_CONFIG_HOME=str(home / "config"), SCANPLAN_NORMS_DIR=str(home / "norms"),
               SCANPLAN_CONFIG=str(home / "none.toml"), PYTHONHASHSEED="0")
    return env


def run_project(project: Path, out: Path, source: Path, home: Path) -> None:
    """Plan one project twice (``--out`` and ``--json``) into the folder ``out``."""
    env = _environment(source, home)
    command = [sys.executable, "-m", "scanplan", "plan", project.name]
    files = out / "files"
    plan = subprocess.run([*command, "--out", str(files)], cwd=project.parent, env=env,
                          capture_output=True, text=True, check=False)
    as_json = subprocess.run([*command, "--json"], cwd=project.parent, env=env,
                             capture_output=True, text=True, check=False)
    files.mkdir(parents=True, exist_ok=True)
    (out / "terminal.txt").write_text(plan.stdout.replace(str(files), "<out>"), encoding="utf-8")
    (out / "stderr.txt").write_text(plan.stderr.replace(str(files), "<out>"), encoding="utf-8")
    (out / "result.json").write_text(as_json.stdout, encoding="utf-8")
    (out / "json-stderr.txt").write_text(as_json.stderr, encoding="utf-8")
    (out / "exit.txt").write_text(f"plan {plan.returncode}\njson {as_json.returncode}\n",
                                  encoding="utf-8")
    faces = subprocess.run([sys.executable, str(FACES), project.name, str(out)],
                           cwd=project.parent, env=env, capture_output=True, text=True,
                           check=False)
    (out / "faces-stderr.txt").write_text(f"exit {faces.returncode}\n{faces.stderr}",
                                          encoding="utf-8")


def run_terminal(args: list[str], locale: str, out: Path, source: Path, home: Path) -> None:
    """Run ``scanplan ARGS --locale LOCALE`` in the folder ``out/files`` (where its
    ``--pdf``/``--xlsx`` land); its terminal, errors and exit code into ``out``."""
    files = out / "files"
    files.mkdir(parents=True, exist_ok=True)
    done = subprocess.run([sys.executable, "-m", "scanplan", *args, "--locale", locale],
                          cwd=files, env=_environment(source, home), capture_output=True,
                          text=True, check=False)
    (out / "terminal.txt").write_text(done.stdout, encoding="utf-8")
    (out / "stderr.txt").write_text(done.stderr.replace(str(files), "<out>"), encoding="utf-8")
    (out / "exit.txt").write_text(f"{done.returncode}\n", encoding="utf-8")


def make(out: Path, source: Path, examples: Path, jobs: int = 2,
         only: list[str] | None = None) -> None:
    """Plan every example of ``examples`` in each language into ``out``.

    Parameters
    ----------
    out : Path
        A new folder: ``LOCALE/PROJECT/`` per run and a manifest.
    source : Path
        The source tree whose ``scanplan`` plans (copied, then put first on ``PYTHONPATH``).
    examples : Path
        The folder of example projects (copied, never written).
    jobs : int
        Projects planned at once.
    only : list of str, optional
        Project names (file stems) to plan; all when not given.
    """
    out.mkdir(parents=True, exist_ok=False)
    work = Path(tempfile.mkdtemp(prefix="scanplan-compare-"))
    try:
        shutil.copytree(source, work / "source", ignore=shutil.ignore_patterns(*NOT_CODE))
        source = work / "source"
        (work / "home" / "norms").mkdir(parents=True)
        runs: list[Any] = []
        for locale in LOCALES:
            for project in copy_projects(examples, work / locale, locale):
                if not only or project.stem in only:
                    runs.append((run_project, project, out / locale / project.stem))
            runs += [(run_terminal, args, locale, out / "terminals" / locale / name)
                     for name, args in TERMINALS.items() if not only or name in only]
        with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
            done = pool.map(lambda r: r[0](*r[1:], source, work / "home"), runs)
            list(done)
        manifest = {"work": str(work), "runs": len(runs)}
        (out / MANIFEST).write_text(json.dumps(manifest, indent=1), encoding="utf-8")
    finally:
        shutil.rmtree(work, ignore_errors=True)


# -- compare ----------------------------------------------------------------------------


def _pdf_text(path: Path) -> list[str]:
    done = subprocess.run(["pdftotext", "-layout", str(path), "-"], capture_output=True,
                          check=False)
    if done.returncode:
        return [f"(pdftotext failed: {done.stderr.decode(errors='replace').strip()})"]
    return done.stdout.decode("utf-8", errors="replace").splitlines()


def _workbook_cells(path: Path) -> list[str]:
    import openpyxl

    book = openpyxl.load_workbook(path, read_only=True, data_only=False)
    try:
        lines = [f"sheets: {book.sheetnames!r}"]
        for sheet in book.worksheets:
            for row in sheet.iter_rows():
                lines += [f"{sheet.title}!{cell.coordinate}\t{cell.value!r}"
                          for cell in row if getattr(cell, "value", None) is not None]
        return lines
    finally:
        book.close()


def _geopackage_rows(path: Path) -> list[str]:
    with sqlite3.connect(f"file:{path}?mode=ro", uri=True) as db:
        return list(db.iterdump())


def _zip_members(path: Path) -> list[str]:
    with zipfile.ZipFile(path) as archive:
        lines = []
        for info in archive.infolist():
            lines.append(f"== {info.filename}")
            lines += archive.read(info).decode("utf-8", errors="replace").splitlines()
        return lines


def readable(path: Path, work: str) -> list[str]:
    """What a reader sees in the output file ``path``, as lines.

    Parameters
    ----------
    path : Path
        An output file.
    work : str
        The temporary folder of its run, replaced by ``<work>``.

    Returns
    -------
    list of str
        PDF text, workbook cells, GeoPackage rows, zip members or the text of the file,
        the page's job folder (``scanplan-job-…``) replaced by ``scanplan-job-<id>``.
    """
    suffix = path.suffix.lower()
    if suffix == ".pdf":
        lines = _pdf_text(path)
    elif suffix == ".xlsx":
        lines = _workbook_cells(path)
    elif suffix == ".gpkg":
        lines = _geopackage_rows(path)
    elif suffix in (".kmz", ".zip"):
        lines = _zip_members(path)
    else:
        lines = path.read_bytes().decode("utf-8", errors="replace").splitlines()
    lines = [line.replace(work, WORK_MARK) for line in lines] if work else lines
    return [JOB_FOLDER.sub(JOB_MARK, line) for line in lines]


def _work_of(folder: Path) -> str:
    manifest = folder / MANIFEST
    if not manifest.is_file():
        return ""
    return json.loads(manifest.read_text(encoding="utf-8")).get("work", "")


def reader_files(folder: Path) -> set[str]:
    """The files a reader sees: an output folder's set of files by their names (the links
    through ``.scanplan-sets/current``), not the sets' own folder."""
    return {p.relative_to(folder).as_posix() for p in folder.rglob("*")
            if p.is_file() and p.name != MANIFEST and ".scanplan-sets" not in p.parts}


def compare_file(a: Path, b: Path, work_a: str = "", work_b: str = "") -> list[str]:
    """The differences between two output files, as readable lines (empty: the same).

    Parameters
    ----------
    a, b : Path
        The file of the first and of the second run.
    work_a, work_b : str
        Each run's temporary folder (replaced by ``<work>``).

    Returns
    -------
    list of str
        A unified diff of what a reader sees, at most ``MAX_DIFF_LINES`` lines.
    """
    if a.read_bytes() == b.read_bytes():
        return []
    lines_a, lines_b = readable(a, work_a), readable(b, work_b)
    if lines_a == lines_b:
        return []
    diff = list(difflib.unified_diff(lines_a, lines_b, str(a), str(b), n=1, lineterm=""))
    more = len(diff) - MAX_DIFF_LINES
    return diff[:MAX_DIFF_LINES] + ([f"... {more} more diff lines"] if more > 0 else [])


def compare_folders(a: Path, b: Path, subset: bool = False) -> list[str]:
    """Every difference between two output folders of ``make``.

    Parameters
    ----------
    a, b : Path
        The folders (the first run, the second run).
    subset : bool
        ``b`` holds some of the runs of ``a`` (``make --only``): the runs missing from
        ``b`` are not differences.

    Returns
    -------
    list of str
        One block of lines per file missing on one side or differing; empty when the two
        runs are the same.
    """
    files_a, files_b = reader_files(a), reader_files(b)
    if subset:
        runs = {_run_of(name) for name in files_b}
        files_a = {name for name in files_a if _run_of(name) in runs}
    problems = [f"only in {a}: {name}" for name in sorted(files_a - files_b)]
    problems += [f"only in {b}: {name}" for name in sorted(files_b - files_a)]
    work_a, work_b = _work_of(a), _work_of(b)
    for name in sorted(files_a & files_b):
        diff = compare_file(a / name, b / name, work_a, work_b)
        if diff:
            problems.append(f"differs: {name}\n" + "\n".join(diff))
    return problems


def _run_of(name: str) -> str:
    """The run a file of a ``make`` folder belongs to: ``en/PROJECT``,
    ``terminals/en/NAME``."""
    parts = name.split("/")
    return "/".join(parts[:3] if parts[0] == "terminals" else parts[:2])


# -- command line -----------------------------------------------------------------------


def main(argv: list[str] | None = None) -> int:
    """Run ``make`` or ``compare``; the exit status (1: the folders differ)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    maker = commands.add_parser("make", help="plan every example into a new folder")
    maker.add_argument("out", type=Path)
    maker.add_argument("--source", type=Path, default=REPO,
                       help="the source tree to plan with (default: this one)")
    maker.add_argument("--examples", type=Path, default=REPO / "examples")
    maker.add_argument("--jobs", type=int, default=2)
    maker.add_argument("--only", nargs="*", help="project names (file stems)")
    comparer = commands.add_parser("compare", help="compare two folders of make")
    comparer.add_argument("a", type=Path)
    comparer.add_argument("b", type=Path)
    comparer.add_argument("--subset", action="store_true",
                          help="the second folder holds some of the runs (make --only)")
    args = parser.parse_args(argv)
    if args.command == "make":
        make(args.out, args.source.resolve(), args.examples.resolve(), args.jobs, args.only)
        return 0
    problems = compare_folders(args.a, args.b, args.subset)
    for problem in problems:
        print(problem)
    count = len(reader_files(args.b) if args.subset
                else reader_files(args.a) | reader_files(args.b))
    print(f"{len(problems)} of {count} files differ" if problems else f"all {count} files match")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
