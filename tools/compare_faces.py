"""The page's answers and a notebook's HTML of one project, for tools/compare_outputs.py.

Run by ``compare_outputs.py make`` with the compared source tree first on ``PYTHONPATH``
(so it plans with that tree's code)::

    python tools/compare_faces.py PROJECT.toml OUT_DIR

It writes into ``OUT_DIR``:

- ``page-view.json`` — what ``POST /api/view`` answers for the project (the ``plan --json``
  document, the map, the charts, the names, the margins, the warnings, the CRS), the
  project given as the page gives it: its tables, and its area and DEM files as uploads;
- ``page/`` — the members of ``POST /api/download/zip`` (the reports, the mission and GIS
  files, the project file), each compared with its own reader;
- ``page-error.txt`` instead, when the page refuses the project (the 422 message);
- ``notebook.html`` — ``scanplan.plan(PROJECT)._repr_html_()`` and the film and UAV parts'
  ``_repr_html_()`` (what a notebook shows).
"""

from __future__ import annotations

import io
import json
import sys
import tomllib
import zipfile
from pathlib import Path
from typing import Any

FILE_KEYS = (("area", "file"), ("terrain", "dem"))


def page_tables(doc: dict[str, Any]) -> dict[str, dict[str, Any]]:
    """A parsed project file as the page's tables: sections flat (``"uav.target"``)."""
    out: dict[str, dict[str, Any]] = {}

    def walk(name: str, table: dict[str, Any]) -> None:
        keys = {}
        for key, value in table.items():
            if isinstance(value, dict):
                walk(f"{name}.{key}", value)
            else:
                keys[key] = value.isoformat() if hasattr(value, "isoformat") else value
        if keys:
            out[name] = keys

    for section, table in doc.items():
        walk(section, table)
    return out


def page_faces(project: Path, out: Path) -> None:
    """``page-view.json`` and ``page/`` (or ``page-error.txt``) of ``project``."""
    from scanplan.errors import InputError
    from scanplan.web.jobs import files_job, view_job

    tables = page_tables(tomllib.loads(project.read_text(encoding="utf-8")))
    files = {}
    for section, key in FILE_KEYS:
        name = tables.get(section, {}).get(key)
        if isinstance(name, str):
            files[name] = str(project.parent / name)
    try:
        view = view_job(tables, files)
        _name, data = files_job(tables, files, "zip")
    except InputError as exc:
        (out / "page-error.txt").write_text(f"{exc.field}: {exc.message}\n", encoding="utf-8")
        return
    text = json.dumps(view, ensure_ascii=False, indent=1, sort_keys=True, allow_nan=False)
    (out / "page-view.json").write_text(text + "\n", encoding="utf-8")
    with zipfile.ZipFile(io.BytesIO(data)) as archive:
        for info in archive.infolist():
            if info.filename in files:  # the uploads themselves: the project's inputs
                continue
            target = out / "page" / info.filename
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(archive.read(info))


def notebook_face(project: Path, out: Path) -> None:
    """``notebook.html``: the result's and its parts' ``_repr_html_``."""
    import scanplan

    result = scanplan.plan(project)
    parts = [result._repr_html_()]
    parts += [part._repr_html_() for part in (result.film, result.uav) if part is not None]
    (out / "notebook.html").write_text("\n".join(parts) + "\n", encoding="utf-8")


def main(argv: list[str]) -> int:
    project, out = Path(argv[0]).resolve(), Path(argv[1])
    out.mkdir(parents=True, exist_ok=True)
    page_faces(project, out)
    notebook_face(project, out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
