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
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .. import norms as _norms
from ..errors import InputError
from ..norms import cells as norms_cells
from ..norms import export as norms_export
from ..norms import limits as norms_limits
from ..norms import recovery as norms_recovery
from ..norms import store as norms_store
from ..norms.schema import TABLES
from ..safeio import read_limited, write_all

__all__ = ["ParsedCameras", "import_camera_file", "read_camera_file", "user_catalogue_dir"]

MAX_JSON_BYTES = 5 * 1024 * 1024
"""Largest camera-list JSON read [bytes] (QGroundControl's is about 12 kB)."""
MAX_JSON_ENTRIES = 5000
JSON_SUFFIXES = (".json",)
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
    problems = norms_cells._Problems()
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
        raise norms_cells._fail(path.name, "has no cameras")
    return ParsedCameras(path.name, rows, [])


def _qgc_document(path: Path) -> list[Any]:
    """The camera list of a QGroundControl JSON file, read within bounds."""
    data = read_limited(path, MAX_JSON_BYTES, field=str(path))
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise norms_cells._fail(path.name, f"is not UTF-8 text (byte {exc.start:,})") from None
    try:
        doc = json.loads(text, parse_constant=_refuse_constant)
    except json.JSONDecodeError as exc:
        raise norms_cells._fail(path.name, f"is not valid JSON: {exc.msg}",
                             at=f"{path.name}:{exc.lineno}:{exc.colno}") from None
    except (ValueError, RecursionError) as exc:
        raise norms_cells._fail(path.name, f"is not a camera list: {str(exc)[:200]}") from None
    if not isinstance(doc, list):
        raise norms_cells._fail(path.name, "is not a camera list: the top level must be a JSON "
                             "list of cameras, as QGroundControl's CameraMetaData.json")
    if len(doc) > MAX_JSON_ENTRIES:
        raise norms_cells._fail(path.name, f"has {len(doc):,} entries; the limit is "
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
        row[column] = norms_cells._num_text(float(v))
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
        row["min_trigger_interval_s"] = norms_cells._num_text(float(trigger))
    return row if ok else None


def _text_problem(text: str) -> str | None:
    try:
        norms_cells._check_text(text)
    except norms_cells._Bad as exc:
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
    if table is not None and table not in ("cameras", "scanners", "lens_mtf"):
        raise InputError("--table", f"must be cameras, scanners or lens_mtf (got {table!r})")
    if len(source) > 1000 or _text_problem(source):
        raise InputError("--source", "must be text of at most 1,000 characters without "
                         "control characters")
    if p.suffix.lower() in JSON_SUFFIXES:
        norms_cells._check_file(p)
        parsed = _read_qgc_json(p, source)
    else:
        if p.suffix.lower() in norms_limits.CSV_SUFFIXES and table is None:
            stem = p.stem.lower()
            table = ("lens_mtf" if "mtf" in stem or "чкх" in stem else
                     "scanners" if "scanner" in stem or "сканер" in stem else
                     "cameras" if "camera" in stem or "камер" in stem else None)
        parsed_set = _norms.read_norm_file(p, table=table, base=_norms.DEFAULT_NORM_SET)
        wanted = [t for t in parsed_set.from_file if t in ("cameras", "scanners", "lens_mtf")]
        if not wanted:
            raise norms_cells._fail(p.name, "has no cameras or scanners table",
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
    _check_rows(parsed)
    return parsed


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
                        norms_store._load_cameras(f)
                    elif table == "scanners":
                        norms_store._load_scanners(f)
                    else:
                        norms_store._load_lens_mtf(f)
                except InputError as exc:
                    msg = exc.message
                    m = re.match(r".*?:(\d+) \((\w+)\)$", exc.field)
                    at = (f"{parsed.source_file} {table} row {int(m.group(1)) - 1} "
                          f"({m.group(2)})" if m else parsed.source_file)
                    raise norms_cells._fail(parsed.source_file, msg, at=at) from None
    if known_cameras is not None:
        digital = known_cameras | {r["id"] for r in parsed.cameras if r.get("kind") == "digital"}
        for i, r in enumerate(parsed.lens_mtf, start=1):
            if r.get("camera") not in digital:
                raise norms_cells._fail(parsed.source_file, f"{r.get('camera')!r} is not a digital "
                                     "camera of the catalogue or of this file",
                                     at=f"{parsed.source_file} lens_mtf row {i} (camera)")


def _existing(folder: Path, table: str) -> list[dict[str, str]]:
    f = folder / TABLES[table].file
    if not f.is_file():
        return []
    return norms_export._raw_csv(f)


def import_camera_file(path: str | os.PathLike[str], *, force: bool = False,
                       source: str = "", table: str | None = None) -> tuple[Path, ParsedCameras]:
    """Read, check and add a camera/scanner file to the user catalogue.

    Parameters
    ----------
    path : str or path
        See :func:`read_camera_file`.
    force : bool
        Replace user cameras (and scanners) that have the same id; without it an id the
        user catalogue already holds is an error.
    source, table
        See :func:`read_camera_file`.

    Returns
    -------
    (Path, ParsedCameras)
        The user catalogue folder and what was added.
    """
    parsed = read_camera_file(path, source=source, table=table)
    ns = _norms.load_norm_set()
    _check_rows(parsed, {c.id for c in ns.cameras.values() if c.kind == "digital"})
    folder = user_catalogue_dir()
    folder.mkdir(parents=True, exist_ok=True)
    with norms_recovery._norm_dir_lock(folder):  # one import at a time: no lost update
        _merge_into(folder, parsed, force)
    return folder, parsed


def _merge_into(folder: Path, parsed: ParsedCameras, force: bool) -> None:
    """Add ``parsed`` to the catalogue files in ``folder`` (checked, then replaced)."""
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
    merged = ParsedCameras(parsed.source_file, cams, scanners, (), tuple(lens))
    _check_rows(merged)
    for table, rows in (("cameras", cams), ("scanners", scanners), ("lens_mtf", lens)):
        if rows:
            _replace(folder / TABLES[table].file, _csv_text(table, rows))


def _replace(target: Path, text: str) -> None:
    """Write ``target`` atomically: a fsynced temporary file renamed over it."""
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
    try:
        try:
            write_all(fd, text.encode("utf-8"))
        finally:
            os.close(fd)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
