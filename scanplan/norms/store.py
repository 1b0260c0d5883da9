"""Norm sets and the camera/scanner catalogue: finding and loading them.

A norm set is a folder of small CSV files plus ``set.toml`` (layout and value rules in
:mod:`scanplan.norms.schema`). Bundled sets ship inside the package (``scanplan/_data/norms``
in a wheel; ``norms/`` at the repository root in a source checkout). User sets are a path,
or a name under the user's norm directory (``$SCANPLAN_NORMS_DIR``, else ``norms`` in the
platform's user data folder: :func:`scanplan.norms.paths.user_norms_dir`).
"""


from __future__ import annotations

import contextlib
import contextvars
import csv
import glob
import io
import math
import os
import re
import stat
import tomllib
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from difflib import get_close_matches
from functools import lru_cache
from itertools import pairwise
from pathlib import Path
from typing import Any

from ..errors import InputError, NotFoundError
from ..io.files import dir_lock, read_limited
from ..io.kept import Kept
from ..rules.film import ScanRules
from .citations import modern_citation
from .paths import CATALOGUE, DEFAULT_NORM_SET, bundled_norms_dir, user_norms_dir
from .records import PITCH_TOLERANCE, Camera, GsdLimit, LensCurve, MapObject, ScannerStep
from .recovery import recover_norm_dir
from .schema import (
    FIGURE_STATUSES,
    LATER_PARAMETERS,
    PARAMETERS,
    TABLES,
    TableSpec,
    ValueSpec,
)

__all__ = [
    "DEFAULT_NORM_SET",
    "PITCH_TOLERANCE",
    "Camera",
    "GsdLimit",
    "LensCurve",
    "MapObject",
    "NormSet",
    "ScannerStep",
    "bundled_norms_dir",
    "did_you_mean",
    "list_norm_sets",
    "load_norm_set",
    "one_version",
    "parse_scale",
    "read_norm_set_folder",
    "user_norms_dir",
]



def parse_scale(value: object, field_name: str) -> float:
    """A scale denominator from ``2000``, ``"2000"``, ``"1:2000"``, ``"2 000"`` or
    ``"1:10,000"`` (a comma before each group of three digits groups thousands: a scale
    denominator of 10.000 is no scale; ``"7692,5"`` is a decimal comma).

    >>> parse_scale("1:10,000", "map_scale"), parse_scale("1:2 000", "map_scale")
    (10000.0, 2000.0)

    Raises
    ------
    InputError
        Naming ``field_name`` when the value is not a finite number > 0.
    """
    allowed = "a scale denominator > 0, e.g. 2000 or 1:2000"
    if isinstance(value, bool):
        raise InputError(field_name, f"must be {allowed} (got {value!r})")
    if isinstance(value, int | float):
        try:
            v = float(value)
        except OverflowError:  # an integer too large for a float
            raise InputError(field_name, f"must be {allowed} (got a number too large for "
                             "a float)") from None
    else:
        text = str(value).strip().replace("\u00a0", "").replace("\u202f", "").replace(" ", "")
        if text.startswith("1:"):
            text = text[2:]
        if re.fullmatch(r"\d{1,3}(,\d{3})+", text):  # 10,000: thousands, as English writes
            text = text.replace(",", "")
        text = text.replace("\u2212", "-").replace(",", ".")
        try:
            v = float(text)
        except ValueError:
            raise InputError(field_name, f"must be {allowed} (got {value!r})") from None
    if not math.isfinite(v) or v <= 0:
        raise InputError(field_name, f"must be {allowed} (got {value!r})")
    return v


@dataclass(frozen=True)
class NormSet:
    """A loaded norm set: parameters, tables, and the catalogue it sees."""

    name: str
    title: str
    title_ru: str
    source: str
    path: Path
    bundled: bool
    imported_from: str
    imported_at: str
    parameters: Mapping[str, Any]
    parameter_sources: Mapping[str, str]
    shapes: Mapping[str, float]
    shape_rows: Mapping[str, Mapping[str, str]]
    objects: tuple[MapObject, ...]
    cameras: Mapping[str, Camera] = field(default_factory=dict)
    scanners: Mapping[str, tuple[float, ...]] = field(default_factory=dict)
    scanner_names: Mapping[str, str] = field(default_factory=dict)
    scanner_details: Mapping[str, tuple[ScannerStep, ...]] = field(default_factory=dict)
    lens_mtf: Mapping[str, Mapping[str, LensCurve]] = field(default_factory=dict)
    gsd_limits: tuple[GsdLimit, ...] = ()
    parameter_status: Mapping[str, str] = field(default_factory=dict)
    """What each parameter is: norm, recommendation, estimate or practice (may be empty)."""

    def gsd_limit(self, map_scale: float, area: str = "general") -> GsdLimit | None:
        """The ``gsd_limits`` row for exactly this map scale and ``area``, or None.

        A ``dense_urban`` request falls back to the ``general`` row when the table has no
        separate row for the scale (Table Б.1 has one only for 1:2000).

        >>> ns = load_norm_set()
        >>> ns.gsd_limit(2000).max_gsd_cm, ns.gsd_limit(2000, "dense_urban").max_gsd_cm
        (20.0, 14.0)
        >>> ns.gsd_limit(5000, "dense_urban").max_gsd_cm, ns.gsd_limit(3000) is None
        (30.0, True)
        """
        for wanted in dict.fromkeys((area, "general")):
            for row in self.gsd_limits:
                if row.map_scale == map_scale and row.area == wanted:
                    return row
        return None

    def rules(self, **overrides: Any) -> ScanRules:
        """The rules engine's parameters, with user overrides applied and checked.

        Parameters
        ----------
        **overrides
            Parameter names of :data:`scanplan.norms.schema.PARAMETERS` (None is ignored).
        """
        params = dict(self.parameters)
        for key, value in overrides.items():
            if value is None:
                continue
            spec = PARAMETERS[key]
            converted = _convert(value, spec.value, key)
            params[key] = converted
        constraints = params["constraints"]
        return ScanRules(
            planimetric_accuracy_mm=params["planimetric_accuracy_mm"],
            height_accuracy_fraction=params["height_accuracy_fraction"],
            processing_loss_k=params["processing_loss_k"],
            photoplan_resolution_mm=params["photoplan_resolution_mm"],
            pr_coefficient=params["pr_coefficient"],
            probability=params["probability"],
            height_formula=params["height_formula"],
            constraints=tuple(constraints),
            standard_forward_overlap_pct=params["standard_forward_overlap_pct"],
            recognition_rounding=params["recognition_rounding"],
            interpretation_min_lpmm=params["interpretation_min_lpmm"],
            interpretation_max_lpmm=params["interpretation_max_lpmm"],
            digital_height_formula=params["digital_height_formula"],
            image_measurement_px=params["image_measurement_px"],
            multi_ray=params["multi_ray"],
            uav_max_height_m=params["uav_max_height_m"],
        )

    def shape_coefficient(self, shape: str, field_name: str = "--shape") -> float:
        """B for ``shape``; :class:`NotFoundError` naming the field if it is unknown."""
        try:
            return self.shapes[shape]
        except KeyError:
            raise NotFoundError(
                field_name,
                f"unknown shape {shape!r}; norm set {self.name!r} has "
                f"{', '.join(self.shapes)}",
            ) from None

    def object_for(self, map_scale: float) -> MapObject | None:
        """The norm object for exactly this map scale, or None."""
        for obj in self.objects:
            if obj.map_scale == map_scale:
                return obj
        return None

    def camera(self, camera_id: str, field_name: str = "--camera") -> Camera:
        """A camera by id; :class:`NotFoundError` listing the ids if unknown."""
        try:
            return self.cameras[camera_id]
        except KeyError:
            raise NotFoundError(
                field_name,
                f"unknown camera {camera_id!r}{did_you_mean(camera_id, self.cameras)} Known: "
                f"{', '.join(sorted(self.cameras))} (scanplan cameras list)",
            ) from None

    def scanner_steps(self, scanner: str, field_name: str = "--scanner") -> tuple[float, ...]:
        """Scan pixels [µm] a scanner offers, ascending."""
        try:
            return self.scanners[scanner]
        except KeyError:
            raise NotFoundError(
                field_name,
                f"unknown scanner {scanner!r}{did_you_mean(scanner, self.scanners)} Known: "
                f"{', '.join(sorted(self.scanners))} (scanplan cameras list --kind scanner)",
            ) from None


def did_you_mean(word: str, choices: Iterable[str]) -> str:
    """``" — did you mean rc30-153?"`` for the closest ids (difflib), else ``"."``
    (either ends the sentence naming the unknown id).

    Case, spaces and underscores are ignored (``RC30_153`` finds ``rc30-153``).

    Parameters
    ----------
    word : str
        What the user typed.
    choices : iterable of str
        The known ids.
    """
    def key(x: str) -> str:
        return str(x).strip().lower().replace("_", "-").replace(" ", "-")

    by_key: dict[str, str] = {}
    for c in choices:
        by_key.setdefault(key(c), c)
    close = get_close_matches(key(word), list(by_key), n=3, cutoff=0.6)
    if not close:
        return "."
    names = " or ".join(by_key[c] for c in close)
    return f" — did you mean {names}?"


# ---------------------------------------------------------------------------------------


def _convert(raw: object, spec: ValueSpec, where: str) -> Any:
    """Convert a raw value (text from a CSV or a Python value) by its rule, or raise."""
    if raw is None or (isinstance(raw, str) and raw.strip() == ""):
        if spec.required:
            raise InputError(where, f"is empty; must be {spec.describe()}")
        return None
    if spec.kind in ("float", "int"):
        if isinstance(raw, bool):
            raise InputError(where, f"must be {spec.describe()} (got {raw!r})")
        try:
            value: Any = float(str(raw).strip()) if isinstance(raw, str) else float(raw)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            raise InputError(where, f"must be {spec.describe()} (got {raw!r})") from None
        problem = spec.check(value)
        if problem:
            raise InputError(where, f"{problem} (got {raw!r})")
        return int(value) if spec.kind == "int" else value
    if spec.kind == "list":
        items = raw if isinstance(raw, list | tuple) else str(raw).split(",")
        value = tuple(str(x).strip() for x in items if str(x).strip())
        problem = spec.check(",".join(value))
        if problem:
            raise InputError(where, f"{problem} (got {raw!r})")
        return value
    value = str(raw).strip()
    problem = spec.check(value)
    if problem:
        raise InputError(where, f"{problem} (got {raw!r})")
    return value


MAX_SET_FILE_BYTES = 20 * 1024 * 1024
"""Largest file of a norm-set folder read [bytes]."""


def _read_text(path: Path) -> str:
    """A file of a norm-set folder as text: a regular UTF-8 file of bounded size (a FIFO or
    a link to /dev/zero is refused, never read)."""
    data = read_limited(path, MAX_SET_FILE_BYTES, field=str(path))
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(str(path), f"is not UTF-8 text (byte {exc.start:,})") from None


def _read_csv(path: Path) -> list[dict[str, str]]:
    """The rows of a norm file, each cell with the papers' old names written by authors and
    year (:func:`~scanplan.norms.citations.modern_citation`)."""
    with io.StringIO(_read_text(path), newline="") as fh:
        try:
            return [{k: modern_citation(v) if isinstance(v, str) else v for k, v in row.items()}
                    for row in csv.DictReader(fh)]
        except csv.Error as exc:
            raise InputError(str(path), f"cannot be read as CSV: {exc}") from None


def _typed_rows(path: Path, spec: TableSpec) -> list[dict[str, Any]]:
    """Rows of a norm table, each value converted by the schema (errors name file:row)."""
    rows = _read_csv(path)
    out = []
    for i, row in enumerate(rows, start=2):
        typed = {}
        for col in spec.columns:
            where = f"{path}:{i} ({col.name})"
            typed[col.name] = _convert(row.get(col.name), col.value, where)
        out.append(typed)
    return out


def load_cameras(path: Path) -> dict[str, Camera]:
    """Cameras of a catalogue file; ids unique, the exact pitch derived (file:row errors)."""
    out: dict[str, Camera] = {}
    for i, r in enumerate(_typed_rows(path, TABLES["cameras"]), start=2):
        if r["id"] in out:
            raise InputError(f"{path}:{i} (id)", f"camera id {r['id']!r} appears twice; "
                             "ids must be unique (keep both entries under different ids)")
        for key in ("platform", "orientation", "note", "shutter", "source", "name_ru"):
            r[key] = r[key] or ""
        published = r["pixel_um"]
        r["published_pixel_um"] = published
        if r["kind"] == "digital" and r["image_width_px"]:
            exact = r["sensor_width_mm"] * 1000.0 / r["image_width_px"]
            if published is not None and abs(published / exact - 1) > PITCH_TOLERANCE:
                raise InputError(
                    f"{path}:{i} (pixel_um)",
                    f"{published:g} µm disagrees with sensor width / image width = "
                    f"{r['sensor_width_mm']:g} mm / {r['image_width_px']} px = {exact:.4g} µm "
                    f"by more than {PITCH_TOLERANCE:.0%}; correct one of them")
            r["pixel_um"] = exact
        out[r["id"]] = Camera(**r)
    return out


_Scanners = tuple[dict[str, tuple[float, ...]], dict[str, str], dict[str, tuple[ScannerStep, ...]]]


def load_scanners(path: Path) -> _Scanners:
    """Steps, names and per-step details of a scanners file; a step listed twice for one
    scanner is an error (file:row)."""
    details: dict[str, list[ScannerStep]] = {}
    names: dict[str, str] = {}
    for i, r in enumerate(_typed_rows(path, TABLES["scanners"]), start=2):
        sid = r["scanner"]
        if any(s.pixel_um == r["pixel_um"] for s in details.get(sid, ())):
            raise InputError(f"{path}:{i} (pixel_um)", f"scanner {sid!r} lists "
                             f"{r['pixel_um']:g} µm twice; each step once")
        names[sid] = r["name"] or names.get(sid) or sid
        details.setdefault(sid, []).append(ScannerStep(
            sid, names[sid], r["pixel_um"], r["bit_depth"] or "", r["frame_scan_min"],
            r["note"] or "", r["source"] or ""))
    det = {k: tuple(sorted(v, key=lambda s: s.pixel_um)) for k, v in details.items()}
    return {k: tuple(s.pixel_um for s in v) for k, v in det.items()}, names, det


def load_lens_mtf(path: Path) -> dict[str, dict[str, LensCurve]]:
    """Lens MTF tables: camera → position → curve (≥ 2 points, one per frequency)."""
    points: dict[tuple[str, str], list[tuple[float, float, str, int]]] = {}
    for i, r in enumerate(_typed_rows(path, TABLES["lens_mtf"]), start=2):
        points.setdefault((r["camera"], r["position"]), []).append(
            (r["freq_lpmm"], r["mtf"], r["source"] or "", i))
    out: dict[str, dict[str, LensCurve]] = {}
    for (cam, pos), pts in points.items():
        pts.sort()
        for a, b in pairwise(pts):
            if a[0] == b[0]:
                raise InputError(f"{path}:{b[3]} (freq_lpmm)", f"{cam} {pos}: frequency "
                                 f"{b[0]:g} lines/mm appears twice; each frequency once")
        if len(pts) < 2:
            raise InputError(f"{path}:{pts[0][3]} (freq_lpmm)", f"{cam} {pos}: a curve needs "
                             "at least two frequencies")
        sources = "; ".join(dict.fromkeys(p[2] for p in pts if p[2]))
        out.setdefault(cam, {})[pos] = LensCurve(tuple(p[0] for p in pts),
                                                 tuple(p[1] for p in pts), sources)
    return out


def _load_gsd_limits(path: Path) -> tuple[GsdLimit, ...]:
    """The ``gsd_limits`` table; a (map scale, area) pair listed twice is an error."""
    seen: dict[tuple[int, str], int] = {}
    out = []
    for i, r in enumerate(_typed_rows(path, TABLES["gsd_limits"]), start=2):
        key = (r["map_scale"], r["area"])
        if key in seen:
            raise InputError(f"{path}:{i} (map_scale)", f"1:{key[0]} {key[1]} is listed twice "
                             f"(also row {seen[key]}); one row per scale and area")
        seen[key] = i
        out.append(GsdLimit(r["map_scale"], r["area"], r["max_gsd_cm"], r["source"] or "",
                            r.get("status") or ""))
    return tuple(sorted(out, key=lambda g: (g.map_scale, g.area)))


@lru_cache(maxsize=1)
def bundled_catalogue() -> tuple[dict[str, Camera], _Scanners]:
    """The bundled camera and scanner catalogue (``norms/catalogue/``), as loaded."""
    folder = bundled_norms_dir() / CATALOGUE
    return load_cameras(folder / "cameras.csv"), load_scanners(folder / "scanners.csv")


def is_set_name(text: str) -> bool:
    """Whether ``--norms``/``[norms] set`` text is a set *name* (looked up in the bundled
    and user folders) rather than a folder path: no separator, not starting with ``.``.

    Parameters
    ----------
    text : str
        What the user wrote.
    """
    return "/" not in text and os.sep not in text and not text.startswith(".")


def _resolve(name_or_path: str | os.PathLike[str]) -> tuple[Path, bool]:
    text = os.fspath(name_or_path)
    bundled = bundled_norms_dir()
    if not text.strip():
        raise NotFoundError("--norms", "is empty; give a norm set name (scanplan norms list) "
                            "or the path of a norm set folder")
    longest = max(len(os.fsencode(part)) for part in text.split(os.sep))
    if longest > 255 or len(os.fsencode(text)) > 4096:
        raise NotFoundError("--norms", f"is {len(text):,} characters long: no norm set has "
                            "such a name (an imported name has at most 64 characters; a "
                            "folder name at most 255 bytes, a path 4,096; scanplan norms list)")
    # a name is looked up in the bundled and user folders; "..", ".x" and "a/b" are paths
    is_name = is_set_name(text)
    if text and is_name and text != CATALOGUE:
        if (bundled / text / "set.toml").is_file():
            return bundled / text, True
        if _user_set_exists(text) or _put_back(text):
            return user_norms_dir() / text, False
    p = Path(text).expanduser()
    if (p / "set.toml").is_file():
        return p, False
    known = ", ".join(s for s, _ in list_norm_sets())
    if not is_name or text.startswith("~"):
        raise NotFoundError(
            "--norms",
            f"no norm set folder {text!r}: {p.absolute()} has no set.toml (a norm set is a "
            f"bundled or imported name: {known}; or a folder with set.toml and its CSV files)",
        )
    raise NotFoundError(
        "--norms",
        f"no norm set {text!r}: give a bundled or imported name ({known}) or the path of a "
        "norm set folder (scanplan norms list)",
    )


def _user_set_exists(name: str) -> bool:
    """Whether user set ``name`` exists; looked at again under the norm directory's shared
    lock when it seems missing (an import may be swapping it in right now)."""
    found = (user_norms_dir() / name / "set.toml").is_file()
    if not found and user_norms_dir().is_dir():
        with dir_lock(user_norms_dir(), exclusive=False):
            found = (user_norms_dir() / name / "set.toml").is_file()
    return found


def _put_back(name: str) -> bool:
    """Restore user set ``name`` if a crashed ``norms import --force`` left it aside."""
    folder = user_norms_dir()
    try:
        if not any(folder.glob(f".{glob.escape(name)}.old-*")):
            return False
        recover_norm_dir(folder, name)
    except OSError:
        return False
    return (folder / name / "set.toml").is_file()


def _put_back_catalogue() -> None:
    """Restore the user camera catalogue if a killed ``cameras import`` left it aside
    (``.catalogue.old-*`` and no ``catalogue``): one ``stat`` when all is well."""
    folder = user_norms_dir()
    if (folder / CATALOGUE).exists() or not folder.is_dir():
        return
    try:
        if any(folder.glob(f".{CATALOGUE}.old-*")):
            recover_norm_dir(folder, CATALOGUE)
    except OSError:
        pass


_HELD_SETS: contextvars.ContextVar[dict[str, NormSet] | None] = contextvars.ContextVar(
    "scanplan_norm_sets", default=None)


@contextlib.contextmanager
def one_version() -> Iterator[None]:
    """Within it, each norm set is read (and its files looked at) once: a plan made of
    several jobs uses one version of a set, and does not take the norm folder's lock and
    look at every file of the set for each job (per thread and task: a context variable).
    """
    token = _HELD_SETS.set({})
    try:
        yield
    finally:
        _HELD_SETS.reset(token)


def load_norm_set(name_or_path: str | os.PathLike[str] = DEFAULT_NORM_SET) -> NormSet:
    """Load a norm set by bundled/user name or folder path.

    Parameters
    ----------
    name_or_path : str or path
        ``"gkinp-02-036-02"``, an imported set's name, or a folder.

    Returns
    -------
    NormSet

    Raises
    ------
    NotFoundError
        If no such set exists (the message lists the known ones).
    InputError
        If a file of the set breaks the schema (the message names file, row and column).
    """
    held = _HELD_SETS.get()
    key = os.fspath(name_or_path)
    if held is not None and key in held:
        return held[key]
    found = _load_norm_set(name_or_path)
    if held is not None:
        held[key] = found
    return found


def _load_norm_set(name_or_path: str | os.PathLike[str]) -> NormSet:
    _put_back_catalogue()
    for _ in range(3):
        path, bundled = _resolve(name_or_path)
        path = path.resolve()
        known = _read_before(path, bundled)
        if known is not None:
            return known
        # An import replaces a set, or the user camera catalogue, under an exclusive lock on
        # the norm directory; reading under a shared lock sees the old version or the new
        # one, never a mix, and never one missing half-way through the swap.
        with dir_lock(user_norms_dir(), exclusive=False):
            user_cat = _user_catalogue_fingerprint()
            if bundled:  # read-only, part of the installation
                return _read_locked(path, bundled, _fingerprint(path), user_cat)
            with dir_lock(path.parent, exclusive=False):
                if (path / "set.toml").is_file():
                    return _read_locked(path, bundled, _fingerprint(path), user_cat)
    raise NotFoundError("--norms", f"norm set {os.fspath(name_or_path)!r} disappeared while "
                        "it was read (replaced or deleted by another program); try again")


def _user_catalogue_fingerprint() -> tuple[tuple[str, int, int, int, int], ...]:
    """The user catalogue's files (``scanplan cameras import``): an import is seen at once."""
    folder = user_norms_dir() / CATALOGUE
    try:
        return _fingerprint(folder) if folder.is_dir() else ()
    except OSError:
        return ()


def _fingerprint(path: Path) -> tuple[tuple[str, int, int, int, int], ...]:
    """(name, size, mtime, inode, ctime) of the set's files: a replaced set is never served
    from the cache (an import writes new files, so at least the inode and ctime change)."""
    out = []
    for f in sorted(path.iterdir()):
        st = f.stat()
        if stat.S_ISREG(st.st_mode):
            out.append((f.name, st.st_size, st.st_mtime_ns, st.st_ino, st.st_ctime_ns))
    return tuple(out)


_Fingerprint = tuple[tuple[str, int, int, int, int], ...]
_READ_KEPT = 16
_READ: Kept[tuple[Path, bool, _Fingerprint, _Fingerprint], NormSet] = Kept(_READ_KEPT)
"""The norm sets read under the lock, by folder and the fingerprints of its files and of the
user catalogue's (the last :data:`_READ_KEPT`)."""


def forget_read_sets() -> None:
    """Forget every norm set read (the next load reads the files again)."""
    _READ.clear()


def _read_before(path: Path, bundled: bool) -> NormSet | None:
    """The set as read before, when its files and the user catalogue's are still the very
    files read then (the same fingerprints, taken without the lock); else None.

    No lock is needed to see that: an import writes new files (other inodes and ctimes), so
    a fingerprint taken while one swaps a set in is a mix that matches no version read
    under the lock, and the set is then read under it."""
    try:
        key = (path, bundled, _fingerprint(path), _user_catalogue_fingerprint())
    except OSError:  # gone or being swapped: read under the lock
        return None
    return _READ.get(key, None)  # type: ignore[return-value]


def _read_locked(path: Path, bundled: bool, fingerprint: _Fingerprint,
                 user_catalogue: _Fingerprint = ()) -> NormSet:
    """The set read (under the caller's lock), or the one read before with these very
    files."""
    key = (path, bundled, fingerprint, user_catalogue)
    return _READ.made(key, lambda: read_norm_set_folder(path, bundled=bundled))


def _read_parameters(pfile: Path, bundled: bool
                     ) -> tuple[dict[str, Any], dict[str, str], dict[str, str]]:
    """A set's parameters, their sources and their status (norm, recommendation, estimate,
    practice or ""); parameters newer than a user set are taken from the default set (with a
    note in the source)."""
    params: dict[str, Any] = {}
    sources: dict[str, str] = {}
    statuses: dict[str, str] = {}
    for i, row in enumerate(_read_csv(pfile), start=2):
        name = (row.get("name") or "").strip()
        if name not in PARAMETERS:
            raise InputError(f"{pfile}:{i} (name)", f"unknown parameter {name!r}; known: "
                             f"{', '.join(PARAMETERS)}")
        params[name] = _convert(row.get("value"), PARAMETERS[name].value, f"{pfile}:{i} (value)")
        sources[name] = (row.get("source") or "").strip()
        status = (row.get("status") or "").strip()
        if status and status not in FIGURE_STATUSES:
            raise InputError(f"{pfile}:{i} (status)", f"must be one of "
                             f"{', '.join(FIGURE_STATUSES)} (got {status!r})")
        statuses[name] = status
    missing = [n for n in PARAMETERS if n not in params]
    if missing and not bundled and set(missing) <= set(LATER_PARAMETERS):
        base = load_norm_set(DEFAULT_NORM_SET)
        for n in missing:
            params[n] = base.parameters[n]
            sources[n] = (f"{base.parameter_sources[n]} (taken from {DEFAULT_NORM_SET}: this "
                          "set predates the parameter)")
            statuses[n] = base.parameter_status.get(n, "")
        missing = []
    if missing:
        raise InputError(str(pfile), f"missing parameters: {', '.join(missing)}")
    return params, sources, statuses


def _set_catalogue(path: Path) -> tuple[dict[str, Camera], dict[str, tuple[float, ...]],
                                         dict[str, str], dict[str, tuple[ScannerStep, ...]],
                                         dict[str, dict[str, LensCurve]]]:
    """The cameras, scanner steps, scanner names and details, and lens tables a set sees:
    the bundled catalogue, the user catalogue (scanplan cameras import), the set's own."""
    cams, (steps, names, details) = bundled_catalogue()
    cams, steps, names, details = dict(cams), dict(steps), dict(names), dict(details)
    # the bundled lens tables, the user catalogue (scanplan cameras import), the set's own
    lens: dict[str, dict[str, LensCurve]] = {}
    for folder in (bundled_norms_dir() / CATALOGUE, user_norms_dir() / CATALOGUE, path):
        if (folder / "lens-mtf.csv").is_file():
            for cam_id, curves in load_lens_mtf(folder / "lens-mtf.csv").items():
                lens.setdefault(cam_id, {}).update(curves)
    for folder in (user_norms_dir() / CATALOGUE, path):
        if (folder / "cameras.csv").is_file():
            cams.update(load_cameras(folder / "cameras.csv"))
        if (folder / "scanners.csv").is_file():
            s2, n2, d2 = load_scanners(folder / "scanners.csv")
            steps.update(s2)
            names.update(n2)
            details.update(d2)
    return cams, steps, names, details, lens


def read_norm_set_folder(path: Path, *, bundled: bool = False) -> NormSet:
    """Read and check the norm set in ``path`` (uncached; :func:`load_norm_set` caches).

    Raises
    ------
    InputError
        If a file of the set breaks the schema (message names file, row and column).
    """
    try:
        meta = {k: modern_citation(v) if isinstance(v, str) else v
                for k, v in tomllib.loads(_read_text(path / "set.toml")).get("set", {}).items()}
    except (OSError, tomllib.TOMLDecodeError) as exc:
        raise InputError(f"{path / 'set.toml'}", f"cannot be read: {exc}") from None
    pfile = path / "parameters.csv"
    params, sources, statuses = _read_parameters(pfile, bundled)
    shape_rows = {r["shape"]: r for r in _typed_rows(path / "shapes.csv", TABLES["shapes"])}
    shapes = {k: float(r["coefficient"]) for k, r in shape_rows.items()}
    if params["shape"] not in shapes:
        raise InputError(f"{pfile} (shape)", f"default shape {params['shape']!r} is not in "
                         f"shapes.csv ({', '.join(shapes)})")
    objects = []
    for r in _typed_rows(path / "objects.csv", TABLES["objects"]):
        if r["shape"] not in shapes:
            raise InputError(f"{path / 'objects.csv'} (shape)",
                             f"shape {r['shape']!r} of {r['object']!r} is not in shapes.csv")
        objects.append(MapObject(r["map_scale"], r["object"], r["object_ru"] or "",
                                 r["size_m"], r["shape"], r["source"] or "",
                                 r.get("status") or ""))
    cams, steps, names, details, lens = _set_catalogue(path)
    return NormSet(
        name=str(meta.get("name") or path.name),
        title=str(meta.get("title", "")),
        title_ru=str(meta.get("title_ru", "")),
        source=str(meta.get("source", "")),
        path=path,
        bundled=bundled,
        imported_from=str(meta.get("imported_from", "")),
        imported_at=str(meta.get("imported_at", "")),
        parameters=params,
        parameter_sources=sources,
        shapes=shapes,
        shape_rows={k: {kk: str(vv or "") for kk, vv in v.items()} for k, v in shape_rows.items()},
        objects=tuple(sorted(objects, key=lambda o: o.map_scale)),
        cameras=cams,
        scanners=steps,
        scanner_names=names,
        scanner_details=details,
        lens_mtf=checked_lens(lens, cams),
        gsd_limits=(_load_gsd_limits(path / "gsd-limits.csv")
                    if (path / "gsd-limits.csv").is_file() else ()),
        parameter_status=statuses,
    )


def checked_lens(lens: dict[str, dict[str, LensCurve]], cams: Mapping[str, Camera]
                  ) -> dict[str, dict[str, LensCurve]]:
    """Lens tables of known digital cameras only (an unknown id is an error)."""
    for cam_id in lens:
        cam = cams.get(cam_id)
        if cam is None or cam.kind != "digital":
            raise InputError("lens-mtf.csv (camera)", f"{cam_id!r} is not a digital camera of "
                             "the catalogue (scanplan cameras list --kind digital)")
    return lens


def list_norm_sets() -> list[tuple[str, str]]:
    """(name, where) of every bundled and user norm set."""
    found = []
    for folder, where in ((bundled_norms_dir(), "bundled"), (user_norms_dir(), "user")):
        if folder.is_dir():
            for sub in sorted(folder.iterdir()):
                # ".NAME.tmp-*" / ".NAME.old-*" are an interrupted import's leftovers
                if not sub.name.startswith(".") and (sub / "set.toml").is_file():
                    found.append((sub.name, where))
    return found


def cameras(norm_set: NormSet | None = None) -> Iterable[Camera]:
    """Cameras visible to a norm set (the bundled catalogue plus the set's own)."""
    ns = norm_set or load_norm_set()
    return ns.cameras.values()
