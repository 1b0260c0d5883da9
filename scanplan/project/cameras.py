"""User cameras and scanners: ``scanplan cameras import FILE``.

A user catalogue lives beside the user norm sets, in ``<user norm directory>/catalogue``
(``cameras.csv`` and ``scanners.csv``, the columns of :mod:`scanplan.norms.schema`); every norm
set sees it on top of the bundled catalogue (same id: the user's wins). It is filled from

* a spreadsheet (``.xlsx``) with a ``cameras``/``Камеры`` and/or ``scanners``/``Сканеры``
  sheet, or a single-table CSV — read by the norm importer, so with the same size limits,
  refusals of hostile files and cell-addressed errors (English or Russian headers);
* QGroundControl's camera list (``CameraMetaData.json``: a JSON list of objects with
  ``canonicalName``, ``sensorWidth``, ``sensorHeight``, ``imageWidth``, ``imageHeight``,
  ``focalLength``, ``landscape``, ``minTriggerInterval``).

Nothing is written unless the whole file is valid; the catalogue files are replaced
atomically.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import re
import tempfile
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from .. import norms as _norms
from ..core.domains import DOMAINS, Domain
from ..errors import InputError, WriteError
from ..io.files import read_limited
from ..norms import cells as norms_cells
from ..norms import export as norms_export
from ..norms import limits as norms_limits
from ..norms import recovery as norms_recovery
from ..norms import store as norms_store
from ..norms import writer as norms_writer
from ..norms.schema import TABLES

__all__ = ["ParsedCameras", "import_camera_file", "read_camera_file", "user_catalogue_dir"]

MAX_JSON_BYTES = 5 * 1024 * 1024
"""Largest camera-list JSON read [bytes] (QGroundControl's is about 12 kB)."""
MAX_JSON_ENTRIES = 5000
JSON_SUFFIXES = (".json",)
_CAMERA_TABLES = ("cameras", "scanners", "lens_mtf")
"""The catalogue's tables a camera file may hold."""
_QGC_NUMBERS = {  # QGroundControl key → (catalogue column, integer?)
    "sensorWidth": ("sensor_width_mm", False),
    "sensorHeight": ("sensor_height_mm", False),
    "imageWidth": ("image_width_px", True),
    "imageHeight": ("image_height_px", True),
    "focalLength": ("focal_mm", False),
}


def user_catalogue_dir() -> Path:
    """Folder of the user catalogue (``catalogue`` in the user norm directory)."""
    return _norms.user_norms_dir() / _norms.CATALOGUE


@dataclass(frozen=True)
class ParsedCameras:
    """A checked camera/scanner file, ready to write.

    Attributes
    ----------
    source_file : str
        Name of the file it came from.
    cameras, scanners : list of dict
        Rows (schema column → text) for ``cameras.csv`` and ``scanners.csv``.
    lens_mtf : tuple of dict
        Rows for ``lens-mtf.csv`` (a camera's lens MTF table, from a ``lens_mtf`` /
        ``ЧКХ объективов`` sheet).
    warnings : tuple of str
        Notes (ignored sheets, columns, entries).
    """

    source_file: str
    cameras: list[dict[str, str]]
    scanners: list[dict[str, str]]
    warnings: tuple[str, ...] = ()
    lens_mtf: tuple[dict[str, str], ...] = ()


def _slug(text: str) -> str:
    s = re.sub(r"[^a-z0-9]+", "-", text.lower().replace("@", " ")).strip("-")
    return s[:64].rstrip("-") or "camera"


def _refuse_constant(name: str) -> Any:
    raise ValueError(f"{name} is not a number JSON allows")


def _read_qgc_json(path: Path, source: str) -> ParsedCameras:
    """QGroundControl's camera list → catalogue rows (every entry checked)."""
    doc = _qgc_document(path)
    spec = TABLES["cameras"]
    problems = norms_cells.Problems()
    rows: list[dict[str, str]] = []
    seen: dict[str, int] = {}
    for i, item in enumerate(doc, start=1):
        where = f"{path.name} entry {i}"
        if not isinstance(item, dict):
            problems.add(_norms.ImportProblem(where, "must be a JSON object (a camera)"))
            continue
        row = _qgc_row(item, where, spec, problems)
        if row is None:
            continue
        if row["id"] in seen:
            problems.add(_norms.ImportProblem(
                f"{where} (canonicalName)", f"gives the same id {row['id']!r} as entry "
                f"{seen[row['id']]}", hint="rename one of them"))
            continue
        seen[row["id"]] = i
        given = ("sensorWidth, sensorHeight, imageWidth, imageHeight, focalLength, landscape"
                 + (", minTriggerInterval" if row["min_trigger_interval_s"] else ""))
        row["source"] = (f"QGroundControl camera list {path.name}, entry {i}: {given}; "
                         "pixel = sensor width / image width" + (f"; {source}" if source else ""))
        rows.append(row)
    problems.raise_if_any(path.name)
    if not rows:
        raise norms_cells.fail(path.name, "has no cameras")
    return ParsedCameras(path.name, rows, [])


def _qgc_document(path: Path) -> list[Any]:
    """The camera list of a QGroundControl JSON file, read within bounds."""
    data = read_limited(path, MAX_JSON_BYTES, field=str(path))
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise norms_cells.fail(path.name, f"is not UTF-8 text (byte {exc.start:,})") from None
    try:
        doc = json.loads(text, parse_constant=_refuse_constant)
    except json.JSONDecodeError as exc:
        raise norms_cells.fail(path.name, f"is not valid JSON: {exc.msg}",
                             at=f"{path.name}:{exc.lineno}:{exc.colno}") from None
    except (ValueError, RecursionError) as exc:
        raise norms_cells.fail(path.name, f"is not a camera list: {str(exc)[:200]}") from None
    if not isinstance(doc, list):
        raise norms_cells.fail(path.name, "is not a camera list: the top level must be a JSON "
                             "list of cameras, as QGroundControl's CameraMetaData.json")
    if len(doc) > MAX_JSON_ENTRIES:
        raise norms_cells.fail(path.name, f"has {len(doc):,} entries; the limit is "
                             f"{MAX_JSON_ENTRIES:,}")
    return doc


def _qgc_row(item: dict[str, Any], where: str, spec: Any, problems: Any
             ) -> dict[str, str] | None:
    """One QGroundControl camera as a catalogue row (no source yet); None, with the
    problems added, when an entry is bad."""
    name = item.get("canonicalName")
    if not isinstance(name, str) or not name.strip():
        problems.add(_norms.ImportProblem(f"{where} (canonicalName)",
                                            "must be the camera's name (text)"))
        return None
    name = name.strip()
    bad_text = _text_problem(name)
    if bad_text:
        problems.add(_norms.ImportProblem(f"{where} (canonicalName)", bad_text))
        return None
    row = {c.name: "" for c in spec.columns}
    row.update(id=_slug(name), kind="digital", platform="uav", name=name)
    ok = True
    for key, (column, integer) in _QGC_NUMBERS.items():
        v = item.get(key)
        rule = spec.column(column).value
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
            problems.add(_norms.ImportProblem(
                f"{where} ({key})", f"must be {rule.describe()}",
                value=None if v is None else str(v)[:50]))
            ok = False
            continue
        if integer and v != int(v):
            problems.add(_norms.ImportProblem(f"{where} ({key})",
                                                "must be a whole number of pixels",
                                                value=str(v)))
            ok = False
            continue
        problem = rule.check(float(v))
        if problem:
            problems.add(_norms.ImportProblem(f"{where} ({key})", problem, value=str(v)))
            ok = False
            continue
        row[column] = norms_cells.num_text(float(v))
    landscape = item.get("landscape", True)
    if not isinstance(landscape, bool):
        problems.add(_norms.ImportProblem(f"{where} (landscape)",
                                            "must be true or false", value=str(landscape)))
        ok = False
    else:
        row["orientation"] = "landscape" if landscape else "portrait"
    trigger = item.get("minTriggerInterval", 0)
    rule = spec.column("min_trigger_interval_s").value
    if isinstance(trigger, bool) or not isinstance(trigger, int | float) \
            or not math.isfinite(trigger) or rule.check(float(trigger)):
        problems.add(_norms.ImportProblem(
            f"{where} (minTriggerInterval)", f"must be {rule.describe()}",
            value=str(trigger)[:50]))
        ok = False
    elif trigger > 0:  # QGroundControl writes 0 for "not specified"
        row["min_trigger_interval_s"] = norms_cells.num_text(float(trigger))
    return row if ok else None


def _text_problem(text: str) -> str | None:
    try:
        norms_cells.check_text(text)
    except norms_cells.Bad as exc:
        return str(exc)
    return None


def read_camera_file(path: str | os.PathLike[str], *, source: str = "",
                     table: str | None = None) -> ParsedCameras:
    """Read and check a camera/scanner file (nothing is written).

    Parameters
    ----------
    path : str or path
        ``.json`` (QGroundControl's camera list), ``.xlsx`` (sheets ``cameras``/``Камеры``
        and/or ``scanners``/``Сканеры``) or ``.csv`` (one of those tables).
    source : str
        Where the values come from; added to each row's source.
    table : {"cameras", "scanners"}, optional
        The table a CSV holds (default: from its file name or headers).

    Returns
    -------
    ParsedCameras

    Raises
    ------
    NormImportError
        Listing every problem (entry or cell, value, rule, hint).
    InputError
        For an unreadable, oversized or hostile file.
    """
    p = Path(path)
    if table is not None and table not in _CAMERA_TABLES:
        raise InputError("--table", f"must be cameras, scanners or lens_mtf (got {table!r})")
    if len(source) > 1000 or _text_problem(source):
        raise InputError("--source", "must be text of at most 1,000 characters without "
                         "control characters")
    if p.suffix.lower() in JSON_SUFFIXES:
        norms_cells.check_file(p)
        parsed = _read_qgc_json(p, source)
    else:
        if p.suffix.lower() in norms_limits.CSV_SUFFIXES and table is None:
            stem = p.stem.lower()
            table = ("lens_mtf" if "mtf" in stem or "чкх" in stem else
                     "scanners" if "scanner" in stem or "сканер" in stem else
                     "cameras" if "camera" in stem or "камер" in stem else None)
        if p.suffix.lower() not in (*norms_limits.CSV_SUFFIXES, *norms_limits.XLSX_SUFFIXES,
                                    ".xls"):
            raise norms_cells.fail(p.name, f"unknown file type {p.suffix or '(none)'}; give "
                                   "QGroundControl's camera list (.json), a workbook (.xlsx) "
                                   "or a table (.csv)")
        parsed_set = _norms.read_norm_file(p, table=table, base=_norms.DEFAULT_NORM_SET,
                                           candidates=_CAMERA_TABLES)
        wanted = [t for t in parsed_set.from_file if t in _CAMERA_TABLES]
        if not wanted:
            raise norms_cells.fail(p.name, "has no cameras or scanners table",
                                 'name the sheet "cameras" ("Камеры") or "scanners" '
                                 '("Сканеры"), or give --table')
        stamp = f"imported from {p.name}" + (f"; {source}" if source else "")
        out: dict[str, list[dict[str, str]]] = {"cameras": [], "scanners": [], "lens_mtf": []}
        for name in wanted:
            for row in parsed_set.tables[name]:
                row = dict(row)
                row["source"] = f"{row['source']} ({stamp})" if row.get("source") else stamp
                out[name].append(row)
        parsed = ParsedCameras(p.name, out["cameras"], out["scanners"],
                               parsed_set.warnings, tuple(out["lens_mtf"]))
    if not (parsed.cameras or parsed.scanners or parsed.lens_mtf):
        raise norms_cells.fail(p.name, "has no cameras: its table has a header and no rows",
                                "add a row per camera (scanplan norms template shows the "
                                "columns)")
    _check_rows(parsed)
    _check_domains(parsed)
    return parsed


#: catalogue column → planning domain (:data:`scanplan.core.domains.DOMAINS`), per kind
_CAMERA_DOMAINS = {
    "digital": {"sensor_width_mm": "sensor_width_mm", "sensor_height_mm": "sensor_height_mm",
                "focal_mm": "focal_mm", "pixel_um": "pixel_um", "f_number": "f_number"},
    "film": {"sensor_width_mm": "frame_width_mm", "sensor_height_mm": "frame_along_mm",
             "focal_mm": "focal_mm", "resolving_power_lpmm": "resolving_power_lpmm"},
}


def _domain_text(d: Domain) -> str:
    lo = f"{'>' if d.lo_open else '≥'} {d.lo:g}"
    hi = f"{'<' if d.hi_open else '≤'} {d.hi:g}"
    return f"{lo} and {hi}{' ' + d.unit if d.unit else ''}"


def _in_domain(d: Domain, x: float) -> bool:
    return (x > d.lo if d.lo_open else x >= d.lo) and (x < d.hi if d.hi_open else x <= d.hi)


def _check_domains(parsed: ParsedCameras) -> None:
    """Refuse cameras and scanners no command can plan with: every value within the
    planning domain of the input it becomes (a sensor of 1e-300 mm, an image of 1e20 px
    — a pixel of 1e-16 µm —, a 0.0001 µm scanner step), named by table, row and column
    with the allowed range."""
    problems = norms_cells.Problems()
    src = parsed.source_file

    def bad(table: str, i: int, col: str, value: str, message: str) -> None:
        problems.add(_norms.ImportProblem(f"{src} {table} row {i} ({col})", message,
                                          value=value))

    for i, r in enumerate(parsed.cameras, start=1):
        for col, name in _CAMERA_DOMAINS.get(r.get("kind") or "digital", {}).items():
            text = r.get(col) or ""
            if not text:
                continue
            d = DOMAINS[name]
            if not _in_domain(d, float(text)):
                bad("cameras", i, col, text, f"must be {_domain_text(d)} ({d.meaning}: the "
                    "range every command accepts)")
        if (r.get("kind") or "digital") != "digital":
            continue
        d = DOMAINS["pixel_um"]
        for side, px_col in (("sensor_width_mm", "image_width_px"),
                             ("sensor_height_mm", "image_height_px")):
            if not (r.get(side) and r.get(px_col)):
                continue
            pitch = float(r[side]) * 1000.0 / float(r[px_col])
            if not _in_domain(d, pitch):
                lo, hi = float(r[side]) * 1000.0 / d.hi, float(r[side]) * 1000.0 / d.lo
                bad("cameras", i, px_col, r[px_col],
                    f"gives a pixel of {r[side]} mm / {r[px_col]} px = {pitch:.4g} µm; a "
                    f"pixel must be {_domain_text(d)}, so {px_col} must be between "
                    f"{math.ceil(lo):,} and {math.floor(hi):,} px")
    d = DOMAINS["scanner"]
    for i, r in enumerate(parsed.scanners, start=1):
        text = r.get("pixel_um") or ""
        if text and not _in_domain(d, float(text)):
            bad("scanners", i, "pixel_um", text, f"must be {_domain_text(d)} ({d.meaning}: "
                "the range every command accepts)")
    problems.raise_if_any(src)


def _csv_text(table: str, rows: list[dict[str, str]]) -> str:
    cols = [c.name for c in TABLES[table].columns]
    buf = io.StringIO()
    w = csv.DictWriter(buf, cols, lineterminator="\n", extrasaction="ignore")
    w.writeheader()
    for r in rows:
        w.writerow({c: r.get(c, "") or "" for c in cols})
    return buf.getvalue()


def _check_rows(parsed: ParsedCameras, known_cameras: set[str] | None = None) -> None:
    """Run the loader's rules (unique ids, pitch within 2 %, one row per step, lens tables
    of known digital cameras) on the rows."""
    with tempfile.TemporaryDirectory() as tmp:
        for table, rows in (("cameras", parsed.cameras), ("scanners", parsed.scanners),
                            ("lens_mtf", list(parsed.lens_mtf))):
            if rows:
                f = Path(tmp) / TABLES[table].file
                f.write_text(_csv_text(table, rows), encoding="utf-8")
                try:
                    if table == "cameras":
                        norms_store.load_cameras(f)
                    elif table == "scanners":
                        norms_store.load_scanners(f)
                    else:
                        norms_store.load_lens_mtf(f)
                except InputError as exc:
                    msg = exc.message
                    m = re.match(r".*?:(\d+) \((\w+)\)$", exc.field)
                    at = (f"{parsed.source_file} {table} row {int(m.group(1)) - 1} "
                          f"({m.group(2)})" if m else parsed.source_file)
                    raise norms_cells.fail(parsed.source_file, msg, at=at) from None
    if known_cameras is not None:
        digital = known_cameras | {r["id"] for r in parsed.cameras if r.get("kind") == "digital"}
        for i, r in enumerate(parsed.lens_mtf, start=1):
            if r.get("camera") not in digital:
                raise norms_cells.fail(parsed.source_file, f"{r.get('camera')!r} is not a digital "
                                     "camera of the catalogue or of this file",
                                     at=f"{parsed.source_file} lens_mtf row {i} (camera)")


def _existing(folder: Path, table: str) -> list[dict[str, str]]:
    f = folder / TABLES[table].file
    if not f.is_file():
        return []
    return norms_export.raw_csv(f)


def import_camera_file(path: str | os.PathLike[str], *, force: bool = False,
                       source: str = "", table: str | None = None) -> tuple[Path, ParsedCameras]:
    """Read, check and add a camera/scanner file to the user catalogue.

    The catalogue is replaced as one version, as a norm set is: the merged tables are
    written to a temporary folder beside it, checked as every command will read them (the
    bundled catalogue plus these), and swapped in under the norm directory's exclusive
    lock; commands read it under the shared lock (old or new, never a mix), and a swap a
    kill interrupted is put back by the next import or load
    (:func:`scanplan.norms.recover_norm_dir`).

    Parameters
    ----------
    path : str or path
        See :func:`read_camera_file`.
    force : bool
        Replace user cameras (and scanners) that have the same id; without it an id the
        user catalogue already holds is an error. A camera replaced by one of another kind
        (digital → film) loses the user lens MTF tables of the old camera (said in the
        warnings): a lens table belongs to a digital camera.
    source, table
        See :func:`read_camera_file`.

    Returns
    -------
    (Path, ParsedCameras)
        The user catalogue folder and what was added (its warnings include what the
        merge dropped).
    """
    parsed = read_camera_file(path, source=source, table=table)
    root_dir = _norms.user_norms_dir()
    folder = root_dir / _norms.CATALOGUE
    try:
        root_dir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise WriteError.from_os_error(str(root_dir), exc, action="create folder") from exc
    with norms_recovery.norm_dir_lock(root_dir):  # one import at a time: no lost update
        try:
            norms_recovery.recover_locked(root_dir, _norms.CATALOGUE)
            files, dropped = _merge_into(folder, parsed, force)
            norms_writer.swap_in(root_dir, _norms.CATALOGUE, files, verify=_verify_catalogue)
        except OSError as exc:
            if isinstance(exc, WriteError):
                raise
            raise WriteError.from_os_error(str(folder), exc,
                                           action="write the camera catalogue") from exc
    if dropped:
        parsed = replace(parsed, warnings=(*parsed.warnings, *dropped))
    return folder, parsed


def _verify_catalogue(folder: Path) -> None:
    """The written catalogue ``folder`` loads as every command will load it: on top of
    the bundled catalogue, lens tables of digital cameras only."""
    cams = dict(norms_store.bundled_catalogue()[0])
    lens: dict[str, dict[str, Any]] = {}
    bundled = _norms.bundled_norms_dir() / _norms.CATALOGUE
    for f, load in ((bundled / "lens-mtf.csv", norms_store.load_lens_mtf),
                    (folder / "lens-mtf.csv", norms_store.load_lens_mtf)):
        if f.is_file():
            for cam_id, curves in load(f).items():
                lens.setdefault(cam_id, {}).update(curves)
    if (folder / "cameras.csv").is_file():
        cams.update(norms_store.load_cameras(folder / "cameras.csv"))
    if (folder / "scanners.csv").is_file():
        norms_store.load_scanners(folder / "scanners.csv")
    norms_store.checked_lens(lens, cams)


def _merge_into(folder: Path, parsed: ParsedCameras, force: bool
                ) -> tuple[dict[str, str], list[str]]:
    """The catalogue files with ``parsed`` added (checked), and what the merge dropped."""
    new_ids = {r["id"] for r in parsed.cameras}
    new_scanners = {r["scanner"] for r in parsed.scanners}
    old_cams = _existing(folder, "cameras")
    old_scanners = _existing(folder, "scanners")
    clash = sorted(new_ids & {r.get("id", "") for r in old_cams}) + sorted(
        new_scanners & {r.get("scanner", "") for r in old_scanners})
    if clash and not force:
        raise InputError(parsed.source_file, f"the user catalogue already has {', '.join(clash)}"
                         f" ({folder}); give --force to replace them")
    cams = [r for r in old_cams if r.get("id") not in new_ids] + parsed.cameras
    scanners = [r for r in old_scanners if r.get("scanner") not in new_scanners] + \
        parsed.scanners
    curves = {(r["camera"], r["position"]) for r in parsed.lens_mtf}
    lens = [r for r in _existing(folder, "lens_mtf")
            if (r.get("camera"), r.get("position")) not in curves] + list(parsed.lens_mtf)
    # a lens table belongs to a digital camera: one replaced by a film camera loses it
    bundled = {c.id: c.kind for c in norms_store.bundled_catalogue()[0].values()}
    kinds = {**bundled, **{r.get("id", ""): r.get("kind", "") for r in cams}}
    for i, r in enumerate(parsed.lens_mtf, start=1):  # the file's own tables: refused
        if kinds.get(r.get("camera", "")) != "digital":
            raise norms_cells.fail(parsed.source_file, f"{r.get('camera')!r} is not a "
                                    "digital camera of the catalogue or of this file",
                                    at=f"{parsed.source_file} lens_mtf row {i} (camera)")
    # the catalogue's tables of a camera that is no longer digital: dropped, and said
    gone = sorted({r.get("camera", "") for r in lens
                   if kinds.get(r.get("camera", "")) != "digital"})
    dropped = [f"the lens MTF table of {cam!r} was removed from the user catalogue: "
               f"{cam!r} is now a {kinds.get(cam) or 'missing'} camera, and only a digital "
               "camera has one" for cam in gone]
    lens = [r for r in lens if r.get("camera") not in gone]
    merged = ParsedCameras(parsed.source_file, cams, scanners, (), tuple(lens))
    _check_rows(merged)
    files = {TABLES[t].file: _csv_text(t, rows)
             for t, rows in (("cameras", cams), ("scanners", scanners), ("lens_mtf", lens))
             if rows}
    return files, dropped
