"""Every example's outputs before and after a change: the same, or where they differ.

Run from the repository::

    python benchmarks/compare_outputs.py snap BEFORE     # plan every example into BEFORE
    # … change the code …
    python benchmarks/compare_outputs.py snap AFTER
    python benchmarks/compare_outputs.py compare BEFORE AFTER

Take both snapshots in the same checkout (``git stash`` or ``git checkout`` between them):
the JSON documents name the norm set by its folder's path.

``snap`` plans each ``examples/*.toml`` with ``scanplan plan --json`` (the document, its
exit code and its stderr) and with ``--out`` (the terminal summary, the workbook, the PDF,
the mission and GIS files). ``compare`` compares the JSON documents as data, the workbooks
by cell values (openpyxl), the PDFs by their text (``pdftotext -layout``), the GeoPackages
by their rows (their timestamps aside) and every other file byte for byte; it lists each
file that differs, is missing or is new, and exits 1 when any does.
"""

from __future__ import annotations

import filecmp
import json
import os
import re
import shutil
import sqlite3
import subprocess
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent


def snap(out: Path) -> None:
    """Plan every example into ``out`` (emptied first)."""
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    env = {**os.environ, "PYTHONPATH": str(ROOT), "SCANPLAN_NO_FORK": "1"}
    for toml in sorted((ROOT / "examples").glob("*.toml")):
        name = toml.stem
        cmd = [sys.executable, "-m", "scanplan", "plan", str(toml.relative_to(ROOT))]
        run = subprocess.run([*cmd, "--json"], capture_output=True, env=env, cwd=ROOT)
        (out / f"{name}.json").write_bytes(run.stdout)
        (out / f"{name}.json.err").write_bytes(run.stderr)
        (out / f"{name}.json.rc").write_text(f"{run.returncode}\n")
        run = subprocess.run([*cmd, "-q", "--out", str(out / name)], capture_output=True,
                             env=env, cwd=ROOT)
        (out / f"{name}.out").write_bytes(run.stdout)  # the terminal summary
        (out / f"{name}.err").write_bytes(run.stderr)
        (out / f"{name}.rc").write_text(f"{run.returncode}\n")
        print(f"{name}: exit {run.returncode}", flush=True)


def _cells(path: Path) -> dict[str, list[list[Any]]]:
    import openpyxl

    book = openpyxl.load_workbook(path)
    return {ws.title: [[c.value for c in row] for row in ws.iter_rows()]
            for ws in book.worksheets}


def _pdf_text(path: Path) -> str:
    return subprocess.run(["pdftotext", "-layout", str(path), "-"], capture_output=True,
                          text=True, check=True).stdout


def _gpkg_rows(path: Path) -> list[str]:
    stamp = re.compile(r"\d{4}-\d\d-\d\dT[\d:.]+Z")
    with sqlite3.connect(path) as db:
        return [stamp.sub("T", line) for line in db.iterdump()]


def _same(before: Path, after: Path, top: bool) -> bool:
    if before.suffix == ".xlsx":
        return _cells(before) == _cells(after)
    if before.suffix == ".pdf":
        return _pdf_text(before) == _pdf_text(after)
    if before.suffix == ".gpkg":
        return _gpkg_rows(before) == _gpkg_rows(after)
    if before.suffix == ".json" and top:  # a --json document (not a file of --out)
        try:
            return json.loads(before.read_bytes()) == json.loads(after.read_bytes())
        except ValueError:
            pass
    return filecmp.cmp(before, after, shallow=False)


def compare(before: Path, after: Path) -> int:
    """The number of files that differ, are missing or are new (each printed)."""
    bad = 0
    for b in sorted(p for p in before.rglob("*") if p.is_file()):
        a = after / b.relative_to(before)
        if not a.is_file():
            print(f"missing  {a.relative_to(after)}")
        elif not _same(b, a, b.parent == before):
            print(f"differs  {b.relative_to(before)}")
        else:
            continue
        bad += 1
    for a in sorted(p for p in after.rglob("*") if p.is_file()):
        if not (before / a.relative_to(after)).exists():
            print(f"new      {a.relative_to(after)}")
            bad += 1
    print(f"{bad} file(s) differ")
    return bad


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "snap":
        snap(Path(sys.argv[2]))
    elif len(sys.argv) == 4 and sys.argv[1] == "compare":
        sys.exit(1 if compare(Path(sys.argv[2]), Path(sys.argv[3])) else 0)
    else:
        sys.exit(__doc__)
