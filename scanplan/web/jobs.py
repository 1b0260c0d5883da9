"""What the API computes: a project given as tables, planned as ``scanplan plan`` plans it.

Each job takes the project's tables (:mod:`scanplan.web.tomlfile`) and the uploaded files it
names, writes the project file and links the files into a fresh temporary folder, and runs
the command line's own steps on it: :func:`~scanplan.project.file.parse_project` (the
project file's checks and messages), :func:`~scanplan.project.spec.plan_project`,
:func:`~scanplan.reports.jsondoc.plan_result_dict` (``plan --json``) and the one document
path of :mod:`scanplan.reports.documents` (``plan --out``'s documents and files; the
warnings worded as the terminal words them). The folder is removed when the job ends,
and its path is taken out of every message and document, which name the files as the
project does (``areas/town.kml``).

A project may name files only by the names of its uploads: ``[area] file`` and
``[terrain] dem`` must be keys of ``files``, ``[norms] set`` a bundled set's name. No path a
client sends is opened.

The jobs run in the worker process (:mod:`scanplan.web.worker`); they take and return
plain data (dicts, text, bytes).
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import re
import shutil
import tempfile
import zipfile
from collections.abc import Iterator, Mapping
from pathlib import Path, PurePosixPath
from typing import Any

from ..errors import InputError
from .tomlfile import project_tables, project_toml

__all__ = ["FILE_KEYS", "JOBS", "PROJECT_NAME", "catalogue_job", "documents_job", "files_job",
           "plan_job", "view_job", "view_json_job"]

PROJECT_NAME = "project.toml"
"""The project file's name in the job's folder (and in the messages)."""
FILE_KEYS = (("area", "file"), ("terrain", "dem"), ("map", "basemap"))
"""The keys that name a file: on the page, only an uploaded one."""
_SAFE_PART = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]*$")


def _file_name(name: Any, field: str) -> str:
    """A file name a project may use on the page: relative, ``/``-separated parts of
    letters, digits and ``._-`` (``areas/town.kml``), no ``..``."""
    parts = PurePosixPath(name).parts if isinstance(name, str) else ()
    if not parts or len(name) > 200 or not all(_SAFE_PART.match(p) for p in parts):
        raise InputError(field, f"must name an uploaded file, e.g. \"town.kml\" (got "
                         f"{str(name)[:100]!r})")
    return "/".join(parts)


def _check_names(tables: dict[str, dict[str, Any]], files: Mapping[str, str]) -> None:
    """Refuse a file key that names no upload and a norm set given as a folder."""
    for section, key in FILE_KEYS:
        value = tables.get(section, {}).get(key)
        if value is None:
            continue
        field = f"{PROJECT_NAME}: {section}.{key}"
        name = _file_name(value, field)
        if name not in files:
            raise InputError(field, f"names {name!r}, which is not uploaded; upload the file "
                             "(a path on the server is never opened)")
    norm_set = tables.get("norms", {}).get("set")
    if isinstance(norm_set, str):
        from ..norms import is_set_name

        if not is_set_name(norm_set):
            raise InputError(f"{PROJECT_NAME}: norms.set", "must be the name of a bundled "
                             "norm set (scanplan norms list); a folder is not read here")


@contextlib.contextmanager
def _staged(project: Any, files: Mapping[str, str]) -> Iterator[tuple[Path, str]]:
    """A temporary folder holding the project file and the uploads under the names the
    project gives them (hard links, else copies); removed on exit. Yields (folder, TOML)."""
    tables = project_tables(project)
    text = project_toml(tables)
    names = {_file_name(n, "files"): p for n, p in files.items()}
    _check_names(tables, names)
    folder = Path(tempfile.mkdtemp(prefix="scanplan-job-"))
    try:
        for name, stored in names.items():
            target = folder / name
            target.parent.mkdir(parents=True, exist_ok=True)
            try:
                os.link(stored, target)
            except OSError:
                shutil.copyfile(stored, target)
        yield folder, text
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def _scrub(text: str, folder: Path) -> str:
    """``text`` without the job's folder: files named as the project names them."""
    return text.replace(f"{folder}{os.sep}", "").replace(str(folder), ".")


@contextlib.contextmanager
def _planned(project: Any, files: Mapping[str, str]) -> Iterator[tuple[Any, str, Path]]:
    """(PlanResult, TOML, folder) of the project; an error's field and message without the
    job's folder."""
    from ..project.file import parse_project
    from ..project.spec import plan_project

    with _staged(project, files) as (folder, text):
        try:
            result = plan_project(parse_project(text, folder / PROJECT_NAME))
        except InputError as exc:
            raise InputError(_scrub(exc.field, folder), _scrub(exc.message, folder)) from None
        yield result, text, folder


def _plan_doc(result: Any, folder: Path) -> tuple[dict[str, Any], str]:
    """``plan --json`` of the result: the document and its compact JSON text with the
    folder scrubbed (the document's keys hold no path: it is read for them alone)."""
    from ..reports.jsondoc import plan_result_dict

    doc = plan_result_dict(result)
    text = json.dumps(doc, ensure_ascii=False, allow_nan=False, separators=(",", ":"))
    return doc, _scrub(text, folder)


def _plan_dict(result: Any, folder: Path) -> dict[str, Any]:
    """``plan --json`` of the result (as printed and read back), the folder scrubbed."""
    return json.loads(_plan_doc(result, folder)[1])  # type: ignore[no-any-return]


def plan_job(project: Any, files: Mapping[str, str]) -> dict[str, Any]:
    """The ``scanplan plan --json`` document of the project."""
    with _planned(project, files) as (result, _text, folder):
        return _plan_dict(result, folder)


def view_job(project: Any, files: Mapping[str, str]) -> dict[str, Any]:
    """What the page shows: ``plan`` (the ``plan --json`` document), ``map`` (GeoJSON of
    the area, strips, photo centres and take-offs, WGS 84), ``charts`` (the documents'
    SVG plots: the film plan's constraints, the UAV plan's heights), ``plans`` (the plans
    compared, worded, :func:`_plans`), ``toml`` and ``crs`` (the planning CRS named in the
    page's language)."""
    with _planned(project, files) as (result, text, folder):
        doc = _plan_dict(result, folder)
        return {"plan": doc, **_view_rest(result, text, doc)}


def view_json_job(project: Any, files: Mapping[str, str]) -> bytes:
    """:func:`view_job`'s answer as the UTF-8 JSON text the server sends
    (:func:`~scanplan.web.bodies.json_bytes`), made once: the ``plan --json`` document's
    text goes in as it is written, not read back and written again."""
    from .bodies import json_bytes

    with _planned(project, files) as (result, text, folder):
        doc, plan_text = _plan_doc(result, folder)
        rest = _view_rest(result, text, doc)
    try:  # the plan's text, then the rest's members: the keys in view_job's order
        return (f'{{"plan":{plan_text},'.encode() + json_bytes(rest)[1:])
    except UnicodeEncodeError:  # a lone surrogate in the plan: escaped as printable_data does
        return json_bytes({"plan": json.loads(plan_text), **rest})


def _view_rest(result: Any, text: str, doc: dict[str, Any]) -> dict[str, Any]:
    """The members of :func:`view_job`'s answer after ``plan`` (``doc``: the plan's
    document, for the names of its constraints)."""
    from ..reports.plots import PLOT_JOBS, view_plot
    from ..reports.view import build_view
    from .mapdata import map_features

    view = build_view(scan=result.film.job if result.film else None,
                      uav=result.uav.job if result.uav else None,
                      meta=result.meta, spec=result)
    charts = {name: view_plot(view, name) for name, job in PLOT_JOBS.items()
              if name != "mtf" and getattr(view, job) is not None}
    return {"map": map_features(result), "charts": charts, "toml": text,
            "names": _constraint_names(doc, view.locale),
            "warnings": _warnings(result, view.locale),
            "plans": _plans(view),
            "crs": _crs(result, view.locale)}


def _plans(view: Any) -> dict[str, Any] | None:
    """The plans compared, worded as the documents word them (:mod:`scanplan.reports.
    planwords`): ``title``, ``choice`` (why the plan), ``head`` and ``rows`` (``cells``,
    ``flags``); None without a choice."""
    if view.spec is None or not view.tables.has("plans") or not view.tables["plans"].rows:
        return None
    from ..reports.planwords import plan_cells, plan_head

    f = view.fmt
    choice = getattr(view.spec.uav, "choice", None)
    return {"title": f("plans_title"),
            "choice": f.text(choice) if choice is not None else "",
            "head": plan_head(f, terminal=True),
            "rows": [{"cells": plan_cells(r, f), "flags": sorted(r.flags)}
                     for r in view.tables["plans"].rows]}


def _crs(result: Any, locale: str) -> str | None:
    """The planning CRS of the area named in ``locale`` as the documents name it (None
    without a georeferenced area)."""
    from ..reports.mapview import area_crs_text

    area = result.area
    return area_crs_text(area, locale) if area is not None and area.georeferenced else None


def _warnings(result: Any, locale: str) -> list[dict[str, str]]:
    """The plan's warnings in ``locale``, worded as the terminal summary words them."""
    from ..reports.text import warning_items

    return [{"code": code, "severity": severity, "text": text}
            for code, severity, text in warning_items(result, locale)]


def _constraint_names(doc: dict[str, Any], locale: str) -> dict[str, str]:
    """The reports' name of each constraint the plan evaluated, in ``locale``."""
    from ..reports.formatter import formatter

    ids = set((doc.get("uav") or {}).get("constraints") or {})
    for s in (doc.get("film") or {}).get("scenarios") or []:
        ids |= set(s.get("constraints") or {})
    f = formatter(locale)
    return {cid: f.constraint(cid) for cid in sorted(ids)}


def files_job(project: Any, files: Mapping[str, str], what: str) -> tuple[str, bytes]:
    """A download: ``"pdf"``, ``"xlsx"`` (the reports) or ``"zip"`` (the reports, the
    mission and GIS files of ``plan --out``, the project file and its uploads) as
    (file name, bytes): the one of :func:`documents_job` (the bytes the page serves)."""
    if what not in ("pdf", "xlsx", "zip"):
        raise InputError("what", f'must be "pdf", "xlsx" or "zip" (got {what!r})')
    return documents_job(project, files)[what]


def documents_job(project: Any, files: Mapping[str, str]) -> dict[str, tuple[str, bytes]]:
    """Every download of the project at once, from one plan: ``{"pdf": …, "xlsx": …,
    "zip": …}`` as :func:`files_job` gives each (:mod:`scanplan.web.documents` renders
    them while the user looks at the plan). The PDF and the workbook downloaded alone say
    no file is beside them; those in the zip say which are."""
    from ..reports import documents

    project, files = _inputs_apart(project, files)  # the zip holds each upload once
    with _planned(project, files) as (result, text, folder):
        jobs = _jobs(result)
        alone = documents.render(("pdf", "xlsx"), **jobs)
        return {"pdf": ("spec.pdf", alone["pdf"]), "xlsx": ("spec.xlsx", alone["xlsx"]),
                "zip": ("scanplan.zip", _zip(result, jobs, text, folder, files))}


def _jobs(result: Any) -> dict[str, Any]:
    """The result as :func:`scanplan.reports.documents.render` takes it."""
    return {"scan": result.film.job if result.film else None,
            "uav": result.uav.job if result.uav else None,
            "meta": result.meta, "spec": result}


def _zip(result: Any, jobs: Mapping[str, Any], text: str, folder: Path,
         files: Mapping[str, str]) -> bytes:
    """The zip of everything: the project file, its uploads, everything ``plan --out``
    writes — the reports (saying which files are beside them), the mission and GIS files."""
    from ..reports import documents

    chosen = documents.plan_outputs(result, "")  # everything plan --out writes
    rendered = documents.render([t.kind for t in chosen.targets], **jobs,
                                beside=[kind for kind, _ in chosen.exports.values()])
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as zf:
        zf.writestr(PROJECT_NAME, text)
        for name in sorted(files):
            zf.write(folder / _file_name(name, "files"), _file_name(name, "files"))
        for t in sorted(chosen.targets, key=lambda t: t.kind != "pdf"):
            zf.writestr(t.path, rendered[t.kind])
        for path, (_kind, data) in sorted(chosen.exports.items()):
            zf.writestr(path, _scrub_text_file(path, data, folder))
    return out.getvalue()


INPUTS_FOLDER = "inputs"
"""The zip's folder for an uploaded file named like one of the outputs."""


def _is_output_name(name: str) -> bool:
    """Whether a file of the zip's top level could have this name: the reports, the
    project file, an exported file (:data:`scanplan.geo.export.formats.FORMATS`)."""
    from ..reports.documents import is_output_name

    return name.casefold() == PROJECT_NAME or is_output_name(name)


def _inputs_apart(project: Any, files: Mapping[str, str]) -> tuple[Any, dict[str, str]]:
    """The project and its uploads with every upload named like an output
    (``flight.kml``) moved to ``inputs/`` — the project's keys follow — so that the zip
    holds each file once and, unpacked, plans the same area again."""
    renamed = {name: f"{INPUTS_FOLDER}/{name}" for name in files
               if isinstance(name, str) and _is_output_name(name)}
    if not renamed or not isinstance(project, dict):
        return project, dict(files)
    tables = {section: dict(table) if isinstance(table, dict) else table
              for section, table in project.items()}
    for section, key in FILE_KEYS:
        table = tables[section] if section in tables else None
        if isinstance(table, dict) and key in table and table[key] in renamed:
            table[key] = renamed[table[key]]
    return tables, {renamed.get(name, name): path for name, path in files.items()}


_TEXT_EXPORTS = (".kml", ".geojson", ".csv", ".plan", ".waypoints", ".txt")


def _scrub_text_file(name: str, data: bytes, folder: Path) -> bytes:
    """A text export (KML, GeoJSON, CSV, mission) naming the area file as the project does,
    not by the job's temporary folder; other files unchanged."""
    if not name.lower().endswith(_TEXT_EXPORTS):
        return data
    try:
        return _scrub(data.decode("utf-8"), folder).encode("utf-8")
    except UnicodeDecodeError:
        return data


def catalogue_job(norms: str, locale: str) -> dict[str, Any]:
    """The cameras and scanners of a bundled norm set, as ``scanplan cameras list`` lists
    them: ``cameras`` (id, name, kind, carrier, focal, pixel, sensor) and ``scanners``
    (id, name, scan pixels)."""
    from ..norms import is_set_name, load_norm_set
    from ..reports.wording import camera_title, scanner_title

    if not is_set_name(norms):
        raise InputError("norms", "must be the name of a bundled norm set")
    ns = load_norm_set(norms)
    cams = [{"id": c.id, "name": camera_title(ns, c.id, locale) if locale == "ru" else c.name,
             "kind": c.kind, "carrier": c.carrier, "focal_mm": c.focal_mm,
             "pixel_um": c.pixel_um, "sensor_mm": [c.sensor_width_mm, c.sensor_height_mm]}
            for c in sorted(ns.cameras.values(), key=lambda c: (c.kind, c.carrier, c.id))]
    scanners = [{"id": sid, "name": scanner_title(ns, sid, locale),
                 "pixels_um": [s.pixel_um for s in ns.scanner_details[sid]]}
                for sid in sorted(ns.scanner_details)]
    return {"norms": norms, "cameras": cams, "scanners": scanners}


JOBS = {"plan": plan_job, "view": view_job, "view_json": view_json_job, "files": files_job,
        "documents": documents_job, "catalogue": catalogue_job}
"""The jobs the worker runs, by name."""


def area_job(project: Any, files: Mapping[str, str]) -> dict[str, Any]:
    """The outline of the project's ``[area]`` alone (GeoJSON FeatureCollection, WGS 84;
    empty for a width × length block or none): the page draws a dropped file before the
    plan can be made (no camera chosen yet). Read by the command line's area reader."""
    from ..project.file import parse_project
    from ..project.model import build_model
    from ..project.spec import project_area
    from .mapdata import area_features

    tables = project_tables(project)
    only: dict[str, Any] = {"map": {"scale": 2000, "relief_interval_m": 1},
                            "uav": {"height_m": 100}}
    if "area" in tables:
        only["area"] = {k: v for k, v in tables["area"].items() if k != "direction_deg"}
    with _staged(only, files) as (folder, text):
        try:
            area = project_area(build_model(parse_project(text, folder / PROJECT_NAME)))
        except InputError as exc:
            raise InputError(_scrub(exc.field, folder), _scrub(exc.message, folder)) from None
        return area_features(area)


def ortho_job(path: str, cache: str) -> dict[str, Any]:
    """An uploaded GeoTIFF as the page's background (:func:`scanplan.web.basemap.ortho_job`)."""
    from .basemap import ortho_job as job

    return job(path, cache)


JOBS["area"] = area_job
JOBS["ortho"] = ortho_job
