"""The top-level Python API: plan from a notebook as from the command line.

``scanplan.plan(project)``, ``scanplan.scan(...)``, ``scanplan.uav(...)`` and
``scanplan.batch(paths)`` return result objects with the same four faces:

- ``.to_dict()`` — exactly the ``--json`` document of the command line;
- ``.to_frame()`` — a :class:`pandas.DataFrame` (units in the column names, see each
  class);
- ``.write(out_dir, formats=…)`` — what ``scanplan plan --out`` writes (a plan: the
  documents, the missions, the GIS files; a scan or uav result: its documents), through
  the same transaction;
- ``_repr_html_`` — a short summary a notebook shows (and a one-line ``repr``).

A UAV result also has ``.photos``, the photo centres of its flight layout as a DataFrame.
``scanplan.sweep(...)`` evaluates a grid of cameras, overlaps and heights as one table.
Numbers may be any :class:`numbers.Real` (``np.int64``, ``np.float32``).

pandas is imported inside ``to_frame`` only: ``import scanplan`` stays light.

>>> import scanplan
>>> r = scanplan.scan(map_scale=2000, relief_interval_m=1.0, photo_scales=[10000],
...                   camera="afa-te-100")
>>> r.to_frame()[["photo_scale", "binding", "scan_pixel_um"]].round(1).to_dict("records")
[{'photo_scale': 10000, 'binding': 'PD', 'scan_pixel_um': 11.1}]
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .api_frames import (
    SUMMARY_COLUMNS,  # noqa: F401  (a batch summary's columns: cli, tests)
    photos_frame,
    summary_frame,
    summary_row,
    typed,
)
from .errors import InputError

if TYPE_CHECKING:  # pragma: no cover
    from typing import Literal, SupportsFloat, SupportsIndex

    import pandas as pd

    from .geo.layout import Area, FlightLayout
    from .project.flightplan import LayoutOptions
    from .project.jobs import ScanJob, UavJob
    from .project.spec import PlanResult
    from .rules.results import UavPlan

__all__ = [
    "BatchResult",
    "ProjectResult",
    "ScanResult",
    "UavResult",
    "batch",
    "photos_frame",
    "plan",
    "scan",
    "summary_frame",
    "summary_row",
    "sweep",
    "uav",
]

FORMATS = ("xlsx", "pdf")


def _json_round_trip(doc: Any) -> dict[str, Any]:
    """The document as ``--json`` prints it, read back (messages become plain text)."""
    return json.loads(json.dumps(doc, ensure_ascii=False, allow_nan=False))


def _write(out_dir: str | os.PathLike[str], stem: str, formats: Iterable[str] | None, *,
           scan: Any = None, uav: Any = None, spec: Any = None, meta: Any = None,
           force: bool = False, inputs: Iterable[str] = (), batch: bool = False
           ) -> list[Path]:
    """Render the documents (and, for a specification, the exported files ``plan --out``
    writes) to memory, then write them as one transaction (all or none): the command
    line's transaction (:func:`scanplan.reports.documents.write_documents`), its targets
    checked as the command line's (never an input file — the project, its area file, its
    DEM —, never a file scanplan did not write unless ``force``); a folder ``out_dir``
    that does not exist is created, and removed again if nothing was written."""
    from .reports import ReportMeta
    from .reports import documents as doc

    folder = os.fspath(out_dir)
    if spec is None:  # a scan or uav job: its documents
        kinds = doc.outputs_chosen(formats if formats is not None else doc.DOCUMENTS,
                                   "formats")
        if any(k not in doc.DOCUMENTS for k in kinds):
            raise InputError("formats", f"must name some of {', '.join(doc.DOCUMENTS)} "
                             f"(got {', '.join(kinds)}): a plan's missions and GIS files "
                             "are written by scanplan.plan(...).write()")
    doc.refuse_folder(folder, "out_dir")
    created = doc.make_folder(folder)
    from .io.rundir import temporaries

    try:
        if spec is None:
            outputs = doc.Outputs([doc.Target(str(Path(folder) / f"{stem}.{kind}"), kind,
                                              "out_dir") for kind in kinds], {})
        else:
            outputs = doc.plan_outputs(spec, folder, formats,
                                       stem=stem if batch or stem != "spec" else None,
                                       field="out_dir", formats_field="formats")
        with temporaries():  # the renderers' temporary files in the process's run folder
            done = doc.write_documents(outputs.targets, scan=scan, uav=uav, spec=spec,
                                       meta=meta or ReportMeta(), force=force,
                                       extra=outputs.exports, extra_field="out_dir",
                                       inputs=[*inputs, *doc.project_inputs(spec)],
                                       sweep=folder if spec is not None and not batch
                                       and stem == "spec" else None)
    finally:  # a folder created here stays only if something was written into it
        doc.remove_empty(created)
    return [Path(p) for p in done.files]


def _table_html(title: str, rows: list[tuple[str, Any]]) -> str:
    import html  # a notebook's display only: not imported by a plan

    body = "".join(f"<tr><th style='text-align:left'>{html.escape(k)}</th>"
                   f"<td>{html.escape(str(v))}</td></tr>" for k, v in rows)
    return f"<div><strong>{html.escape(title)}</strong><table>{body}</table></div>"


class _JobPlan:
    """What a film and a UAV result share: the engine plan (``.plan``: a
    :class:`~scanplan.rules.results.ScanPlan` or ``UavPlan``) and its fields read through
    (``result.scenarios``, ``result.gsd_m``) as before."""

    job: Any

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_") or name == "job":
            raise AttributeError(name)
        return getattr(self.job.plan, name)

    @property
    def plan(self) -> Any:
        """The engine's plan record."""
        return self.job.plan


@dataclass(frozen=True)
class ScanResult(_JobPlan):
    """A film scan plan (``scanplan scan``).

    ``to_frame()``: one row per photo scale — ``photo_scale`` (Mc), ``binding`` (the
    constraint id), ``scan_pixel_um``, ``scanner_pixel_um`` (rounded to the scanner's
    steps; NaN without a scanner), ``resolution_on_ground_mm`` (A), ``recognition_probability``,
    ``frame_megabytes``, and one ``pixel_um_<ID>`` column per evaluated constraint.
    """

    job: ScanJob

    def to_dict(self) -> dict[str, Any]:
        """The ``scanplan scan --json`` document."""
        from .reports.jsondoc import scan_plan_dict

        return _json_round_trip(scan_plan_dict(self.job.plan, self.job.norm_set))

    def to_frame(self) -> pd.DataFrame:
        """One row per photo scale (columns in the class docstring)."""
        import pandas as pd

        rows = []
        for s in self.job.plan.scenarios:
            row: dict[str, Any] = {
                "photo_scale": int(s.photo_scale) if float(s.photo_scale).is_integer()
                else s.photo_scale, "binding": s.binding, "scan_pixel_um": s.scan_pixel_um,
                "scanner_pixel_um": s.scanner_pixel_um,
                "resolution_on_ground_mm": s.resolution_on_ground_mm,
                "recognition_probability": s.recognition_probability,
                "frame_megabytes": s.frame_megabytes}
            row.update({f"pixel_um_{c.id}": c.pixel_um for c in s.constraints})
            rows.append(row)
        frame = pd.DataFrame(rows)
        numbers = [c for c in frame.columns if c not in ("photo_scale", "binding")]
        if frame["photo_scale"].dtype != "int64":
            numbers.append("photo_scale")
        return typed(frame, strings=["binding"], floats=numbers)

    def __repr__(self) -> str:
        sc = self.job.plan.scenarios
        shown = ", ".join(f"1:{x.photo_scale:g} → {x.scan_pixel_um:.1f} µm ({x.binding})"
                          for x in sc[:3])
        more = f", … {len(sc) - 3} more" if len(sc) > 3 else ""
        return f"<ScanResult scan pixel by photo scale: {shown}{more}>"

    def write(self, out_dir: str | os.PathLike[str], formats: Iterable[str] = FORMATS, *,
              name: str = "scan", force: bool = False) -> list[Path]:
        """Write ``NAME.xlsx`` / ``NAME.pdf`` into ``out_dir`` atomically; the paths."""
        return _write(out_dir, name, formats, scan=self.job, force=force)

    def _repr_html_(self) -> str:
        from .reports.notebook import table_html
        from .reports.views import ResultTables

        return table_html(ResultTables(scan=self.job.plan)["film_constraints"],
                          "scanplan: film scan pixel by photo scale", units=True)


@dataclass(frozen=True)
class UavResult(_JobPlan):
    """A digital-camera flight plan (``scanplan uav``).

    ``to_frame()``: one row per constraint — ``constraint`` (id), ``name``, ``compares``
    (GSD, L or H), ``limit_m`` (the ground limit), ``max_planned_height_m``,
    ``max_flown_height_m``, ``margin_pct`` (at the planned height) and ``binding``. Empty
    without a map scale or a target GSD.
    """

    job: UavJob

    def to_dict(self) -> dict[str, Any]:
        """The ``scanplan uav --json`` document."""
        from .reports.jsondoc import uav_plan_dict

        return _json_round_trip(uav_plan_dict(self.job.plan, self.job.norm_set))

    def to_frame(self) -> pd.DataFrame:
        """One row per constraint (columns in the class docstring)."""
        import pandas as pd

        cols = ["constraint", "name", "compares", "limit_m", "max_planned_height_m",
                "max_flown_height_m", "margin_pct", "binding"]
        rows = [{"constraint": cid, "name": c.get("name"), "compares": c.get("compares"),
                 "limit_m": c.get("limit_m"), "max_planned_height_m": c.get("max_height_m"),
                 "max_flown_height_m": c.get("max_flown_height_m"),
                 "margin_pct": c.get("margin_pct"), "binding": bool(c.get("binding"))}
                for cid, c in (self.to_dict().get("constraints") or {}).items()]
        return typed(pd.DataFrame(rows, columns=cols),
                      strings=["constraint", "name", "compares"],
                      floats=["limit_m", "max_planned_height_m", "max_flown_height_m",
                              "margin_pct"], flags=["binding"])

    @property
    def photos(self) -> pd.DataFrame:
        """The photo centres of the flight layout (:func:`photos_frame`); empty without an
        area."""
        return photos_frame(self.job.layout)

    def __repr__(self) -> str:
        p = self.job.plan
        top = "" if p.max_height_m is None else \
            f", maximum planned {p.max_height_m:.0f} m ({p.binding})"
        return (f"<UavResult {p.inputs.camera or 'camera'} at {p.heights_m['planned']:g} m: "
                f"GSD {p.gsd_m * 100:.2f} cm{top}>")

    def write(self, out_dir: str | os.PathLike[str], formats: Iterable[str] = FORMATS, *,
              name: str = "uav", force: bool = False) -> list[Path]:
        """Write ``NAME.xlsx`` / ``NAME.pdf`` into ``out_dir`` atomically; the paths."""
        return _write(out_dir, name, formats, uav=self.job, force=force)

    def _repr_html_(self) -> str:
        from .reports.notebook import table_html
        from .reports.views import ResultTables

        p = self.job.plan
        tables = ResultTables(uav=p)
        shown = table_html(tables["uav_results"], "scanplan: UAV flight",
                           platform=p.inputs.platform)
        if p.limits:
            from .reports.formatter import formatter

            top = "—" if p.max_height_m is None else f"{formatter('en').num(p.max_height_m, 0)} m"
            shown += table_html(tables["uav_limits"],
                                f"maximum planned height: {top} ({p.binding})")
        return shown


@dataclass(frozen=True)
class ProjectResult:
    """The specification for one project file (``scanplan plan``).

    ``to_frame()``: one row, the batch summary's (:data:`SUMMARY_COLUMNS`: the
    recommended photo scale and scan pixel, the recommended and maximum planned height,
    frames/photos, warning codes). ``film`` / ``uav`` give the detail as
    :class:`ScanResult` / :class:`UavResult` (a row per photo scale, per constraint).
    """

    spec: PlanResult

    @property
    def film(self) -> ScanResult | None:
        """The film part, or None."""
        return ScanResult(self.spec.film.job) if self.spec.film else None

    @property
    def uav(self) -> UavResult | None:
        """The digital-camera part, or None."""
        return UavResult(self.spec.uav.job) if self.spec.uav else None

    def to_dict(self) -> dict[str, Any]:
        """The ``scanplan plan --json`` document."""
        from .reports.jsondoc import plan_result_dict

        return _json_round_trip(plan_result_dict(self.spec))

    def to_frame(self) -> pd.DataFrame:
        """The summary row (columns: :data:`SUMMARY_COLUMNS`)."""
        return summary_frame([summary_row(self.spec)])

    @property
    def photos(self) -> pd.DataFrame:
        """The photo centres of the UAV (else the film) flight layout (:func:`photos_frame`;
        a terrain plan's own columns too); empty without an area."""
        part = self.spec.uav or self.spec.film
        return photos_frame(getattr(part, "layout", None) if part is not None else None)

    @property
    def control(self) -> pd.DataFrame | None:
        """The GCPs and checkpoints of ``[control]``, one row each (the columns of
        ``control.csv``: :data:`scanplan.geo.control.CONTROL_COLUMNS`, units in the names);
        None without ``[control]``. The counts, the rules and the error budget are
        ``to_dict()["specification"]["control"]``."""
        import pandas as pd

        from .geo.control import CONTROL_COLUMNS

        control = self.spec.control
        if control is None:
            return None
        return pd.DataFrame({k: control.points.columns[k] for k in CONTROL_COLUMNS})

    def __repr__(self) -> str:
        row = summary_row(self.spec)
        parts = [f"1:{row['map_scale']}" if row["map_scale"] else ""]
        if row["film_photo_scale"]:
            parts.append(f"film 1:{row['film_photo_scale']:g}")
        if row["uav_recommended_height_m"]:
            parts.append(f"UAV {row['uav_recommended_height_m']:g} m")
        warn = len(self.spec.warnings)
        return (f"<ProjectResult {self.spec.meta.project!r}: "
                f"{', '.join(p for p in parts if p)}; {warn} warning{'' if warn == 1 else 's'}>")

    def write(self, out_dir: str | os.PathLike[str], formats: Iterable[str] | None = None,
              *, name: str = "spec", force: bool = False) -> list[Path]:
        """Write what ``scanplan plan --out`` writes into ``out_dir``, byte for byte: the
        documents (``spec.xlsx``, ``spec.pdf``) and, over an area on the map, the missions
        and the files for a GIS — all of them, or the outputs ``formats`` names.

        Parameters
        ----------
        out_dir : str or path
            The folder (created when it does not exist).
        formats : iterable of str, optional
            Some of ``"xlsx"``, ``"pdf"``, ``"missions"``, ``"gis"``
            (:data:`scanplan.reports.documents.OUTPUTS`; ``plan --formats``); default all.
        name : str
            The documents' name (``NAME.xlsx``); another than ``"spec"`` also goes before
            the exported files' names (``NAME-flight.kml``), as a batch names them.
        force : bool
            Replace files scanplan did not write (never the project's own input files).

        Returns
        -------
        list of Path
            The files written, documents first.

        Raises
        ------
        InputError
            A bad target or output (``formats``: ``gis`` for a project without an area
            on the map …), naming it; nothing is written.
        PdfEngineError
            A PDF is asked for and the PDF engine (WeasyPrint, with the system's Pango)
            cannot load; nothing is written.
        WriteError
            The write failed; every previous file is as it was.
        """
        s = self.spec
        return _write(out_dir, name, formats, scan=s.film.job if s.film else None,
                      uav=s.uav.job if s.uav else None, spec=s, meta=s.meta, force=force,
                      inputs=[str(s.project.path)])

    def _repr_html_(self) -> str:
        row = summary_row(self.spec)
        shown = [(k, v) for k, v in row.items() if v not in (None, "")]
        summary = _table_html(f"scanplan: {self.spec.meta.project}", shown)
        if not self.spec.comparison:
            return summary
        from .reports.notebook import table_html
        from .reports.views import ResultTables

        return summary + table_html(ResultTables(spec=self.spec)["comparison"],
                                    "film and digital camera side by side", units=True)


@dataclass(frozen=True)
class BatchResult:
    """The specifications of several project files; a bad file is an error, not a stop.

    ``results`` are in the order of the files; ``errors`` maps each bad file to its
    :class:`~scanplan.errors.InputError` (naming the key and its line). ``to_frame()`` is
    the batch summary (:data:`SUMMARY_COLUMNS`), one row per planned project.
    """

    results: tuple[ProjectResult, ...]
    errors: Mapping[str, InputError] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        """The ``scanplan plan FILES --json`` document of a batch."""
        return {"projects": [r.to_dict() for r in self.results],
                "errors": [{"file": f, "message": f"{e.field}: {e.message}"}
                           for f, e in self.errors.items()]}

    def to_frame(self) -> pd.DataFrame:
        """One row per planned project (columns: :data:`SUMMARY_COLUMNS`)."""
        return summary_frame([summary_row(r.spec) for r in self.results])

    def __repr__(self) -> str:
        return f"<BatchResult {len(self.results)} planned, {len(self.errors)} errors>"

    def write(self, out_dir: str | os.PathLike[str], formats: Iterable[str] | None = None,
              *, force: bool = False) -> list[Path]:
        """Each project's outputs as ``scanplan plan DIR --out`` writes them
        (``STEM.xlsx``, ``STEM.pdf``, ``STEM-flight.kml`` …; ``formats`` as
        :meth:`ProjectResult.write`), each project all or nothing."""
        from .io.targets import batch_stems

        paths = [str(r.spec.project.path) for r in self.results]
        written: list[Path] = []
        for r, stem in zip(self.results, batch_stems(paths), strict=True):
            s = r.spec  # as the command line's batch: no project file of the batch replaced
            written += _write(out_dir, stem, formats, scan=s.film.job if s.film else None,
                              uav=s.uav.job if s.uav else None, spec=s, meta=s.meta,
                              force=force, inputs=paths, batch=True)
        return written

    def _repr_html_(self) -> str:
        import html

        frame = self.to_frame()
        errors = "".join(f"<li>{html.escape(f)}: {html.escape(e.message)}</li>"
                         for f, e in self.errors.items())
        return frame.to_html(index=False) + (f"<ul>{errors}</ul>" if errors else "")


def _load(project: Any) -> Any:
    """A project file path, a TOML string or a dict of sections → a validated Project."""
    from .project.file import load_project, parse_project

    if isinstance(project, Mapping):
        from .project.signature import plain

        return parse_project(_toml(plain(project)), "project.toml")
    if isinstance(project, os.PathLike) or (isinstance(project, str) and "\n" not in project
                                            and "=" not in project):
        return load_project(project)
    if isinstance(project, str):
        return parse_project(project, "project.toml")
    raise InputError("project", "must be a path, the TOML text of a project file, or a dict "
                     f"of its sections (got {type(project).__name__})")


def _toml(doc: Mapping[str, Any]) -> str:
    """A dict of project-file sections as TOML text (values: numbers, text, lists)."""
    def value(v: Any) -> str:
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, int | float):
            return repr(v)
        if isinstance(v, str):
            return json.dumps(v, ensure_ascii=False)
        if isinstance(v, list | tuple):
            return "[" + ", ".join(value(x) for x in v) + "]"
        raise InputError("project", f"a value must be a number, text or a list (got {v!r})")

    lines: list[str] = []

    def table(name: str, items: Mapping[str, Any]) -> None:
        lines.append(f"[{name}]")
        subs = []
        for k, v in items.items():
            if isinstance(v, Mapping):
                subs.append((f"{name}.{k}", v))
            else:
                lines.append(f"{k} = {value(v)}")
        for sub, v in subs:
            table(sub, v)

    for section, items in doc.items():
        if not isinstance(items, Mapping):
            raise InputError("project", f"[{section}] must be a dict of keys")
        table(section, items)
    return "\n".join(lines) + "\n"


def plan(project: str | os.PathLike[str] | Mapping[str, Any]) -> ProjectResult:
    """The specification for a mapping contract, as ``scanplan plan PROJECT.toml``.

    Parameters
    ----------
    project : path, str or dict
        A project file, its TOML text, or a dict with the project file's sections and keys
        (``{"map": {"scale": 2000, ...}, "film": {...}}``; docs/project-file.md).

    Returns
    -------
    ProjectResult

    Raises
    ------
    InputError
        Naming the key (and its line) of a bad value.

    Examples
    --------
    >>> import scanplan
    >>> r = scanplan.plan({"map": {"scale": 2000, "relief_interval_m": 1.0},
    ...                    "uav": {"camera": "dji-zenmuse-p1-35"}})
    >>> r.to_dict()["specification"]["uav"]["recommended_height_m"] > 0
    True
    """
    from .project.spec import plan_project

    return ProjectResult(plan_project(_load(project)))


def _registry_keywords(engine: Any, plan_kind: str, returns: str) -> Any:
    """Give an API function the keyword signature and the numpydoc *Parameters* of the
    engine's inputs, generated from the input registry (:mod:`scanplan.project.signature`);
    the function's own docstring keeps its summary and examples."""
    from .project.signature import parameters_doc, registry_signature

    def wrap(fn: Any) -> Any:
        import inspect

        fn.__signature__ = registry_signature(engine, plan_kind, returns)
        summary, _, examples = inspect.cleandoc(fn.__doc__ or "").partition("\nExamples\n")
        parts = [summary.rstrip(), parameters_doc(engine, plan_kind),
                 f"Returns\n-------\n{returns}",
                 "Raises\n------\nInputError\n    Naming the input and its allowed range."]
        if examples:
            parts.append("Examples\n" + examples.rstrip())
        first, _, rest = "\n\n".join(parts).partition("\n")
        fn.__doc__ = first + "\n" + "\n".join("    " + line if line else ""
                                              for line in rest.splitlines()) + "\n"
        return fn

    return wrap


def _engine(name: str) -> Any:
    from .project import jobs as engine

    return getattr(engine, name)


if TYPE_CHECKING:  # the signatures a type checker reads: the registry's keywords, typed
    # <typed signatures: python -m scanplan.project.signature scanplan/api.py>
    def scan(
            *,
            map_scale: SupportsFloat | str,
            relief_interval_m: SupportsFloat,
            photo_scales: Iterable[SupportsFloat | str],
            camera: str | None = ...,
            camera_name: str | None = ...,
            focal_mm: SupportsFloat | None = ...,
            frame_mm: str | None = ...,
            resolving_power_lpmm: SupportsFloat | None = ...,
            forward_overlap_pct: SupportsFloat | None = ...,
            norms: str | os.PathLike[str] = ...,
            object_size_m: SupportsFloat | None = ...,
            shape: str | None = ...,
            object_name: str | None = ...,
            probability: SupportsFloat | None = ...,
            height_formula: Literal['instruction', 'parallax'] | None = ...,
            pr_coefficient: SupportsFloat | None = ...,
            recognition_rounding: Literal['exact', 'paper'] | None = ...,
            scanner: str | None = ...,
            bands: SupportsIndex = ...,
            bits_per_band: SupportsIndex = ...,
            pixel_um: Iterable[SupportsFloat] = ...,
    ) -> ScanResult: ...

    def uav(
            *,
            height_m: SupportsFloat | None = ...,
            camera: str | None = ...,
            camera_name: str | None = ...,
            pixel_um: SupportsFloat | None = ...,
            focal_mm: SupportsFloat | None = ...,
            sensor_mm: str | None = ...,
            f_number: SupportsFloat | None = ...,
            speed_ms: SupportsFloat | None = ...,
            exposure_s: SupportsFloat = ...,
            forward_overlap_pct: SupportsFloat | None = ...,
            side_overlap_pct: SupportsFloat | None = ...,
            height_tolerance_pct: SupportsFloat = ...,
            map_scale: SupportsFloat | str | None = ...,
            relief_interval_m: SupportsFloat | None = ...,
            norms: str | os.PathLike[str] = ...,
            object_size_m: SupportsFloat | None = ...,
            shape: str | None = ...,
            object_name: str | None = ...,
            probability: SupportsFloat | None = ...,
            height_formula: Literal['instruction', 'parallax', 'normal_case'] | None = ...,
            r_max: SupportsFloat = ...,
            r_min: SupportsFloat = ...,
            threshold_k0: SupportsFloat | None = ...,
            haze_contrast: SupportsFloat | None = ...,
            shift_factor: SupportsFloat = ...,
            random_speed_ms: SupportsFloat = ...,
            roll_rate_rad_s: SupportsFloat = ...,
            pitch_rate_rad_s: SupportsFloat = ...,
            yaw_rate_rad_s: SupportsFloat = ...,
            area_m: str | None = ...,
            roll_deg: SupportsFloat = ...,
            pitch_deg: SupportsFloat = ...,
            orientation: Literal['landscape', 'portrait'] | None = ...,
            max_height_m: SupportsFloat | None = ...,
            gsd_cm: SupportsFloat | None = ...,
            gsd_area: Literal['general', 'dense_urban'] = ...,
            parallax_error_px: SupportsFloat | None = ...,
            gsd_limit_reason: str | None = ...,
            area: Area | None = ...,
            layout_options: LayoutOptions | None = ...,
            flown_band_m: tuple[float, float] | None = ...,
            laid_out: FlightLayout | None = ...,
            limits: UavPlan | None = ...,
            curves: bool = ...,
    ) -> UavResult: ...
    # </typed signatures>
else:  # at run time: one keyword per input of the registry (its signature and its docs)
    @_registry_keywords(_engine("scan_job"), "film", "ScanResult")
    def scan(**inputs: Any) -> ScanResult:
        """Plan the scanning of film photos, as ``scanplan scan``: every constraint at each
        candidate photo scale. Numbers may be any :class:`numbers.Real`.

        Examples
        --------
        >>> import scanplan
        >>> r = scanplan.scan(map_scale="1:2000", relief_interval_m=1.0,
        ...                   photo_scales=[8000, 10000], camera="afa-te-100")
        >>> list(r.to_frame()["photo_scale"])
        [8000, 10000]
        """
        from .project.jobs import scan_job
        from .project.signature import plain

        return ScanResult(scan_job(**plain(inputs)))


    @_registry_keywords(_engine("uav_job"), "uav", "UavResult")
    def uav(**inputs: Any) -> UavResult:
        """Plan a digital-camera flight, as ``scanplan uav``: GSD, the MTF ground resolution,
        blur, flight geometry and, with a map scale or a target GSD, the maximum planned
        height under every limit. Numbers may be any :class:`numbers.Real`.

        Examples
        --------
        >>> import numpy as np, scanplan
        >>> r = scanplan.uav(camera="dji-zenmuse-p1-35", height_m=np.int64(100),
        ...                  map_scale=1000, relief_interval_m=np.float32(0.5))
        >>> "max_planned_height_m" in r.to_frame().columns
        True
        """
        from .project.jobs import uav_job
        from .project.signature import plain

        return UavResult(uav_job(**plain(inputs)))


def sweep(*, height_m: Any, camera: Any = None, forward_overlap_pct: Any = None,
          side_overlap_pct: Any = None, **inputs: Any) -> pd.DataFrame:
    """A grid of UAV plans as one tidy table: every camera × forward overlap × side overlap
    × height, the heights of each in one vectorised engine pass.

    Parameters
    ----------
    height_m : Real or sequence of Real
        Planned heights above ground. Unit: m.
    camera : str or sequence of str, optional
        Catalogue camera ids (``scanplan cameras list``); None with ``pixel_um``,
        ``focal_mm`` and ``sensor_mm``.
    forward_overlap_pct, side_overlap_pct : Real or sequence of Real, optional
        Overlaps. Unit: %. Default: the carrier's, as :func:`uav`.
    **inputs
        Any other keyword of :func:`uav`, one value each (not ``area``, ``area_m``,
        ``layout_options``: a sweep lays out no flight).

    Returns
    -------
    pandas.DataFrame
        One row per combination; the columns (units in their names) are
        :data:`scanplan.project.sweep.SWEEP_FRAME_COLUMNS`: ``camera``, ``height_m``,
        the overlaps, ``gsd_cm``, ``resolution_cm`` (MTF L), ``motion_blur_px``,
        footprints, ``base_m``, ``line_spacing_m``, ``photo_interval_s``,
        ``max_planned_height_m``, ``binding``, ``within_limits``. Each row equals
        :func:`uav` with the same inputs.

    Raises
    ------
    InputError
        Naming the input, and the camera for an error of one camera (no f-number).

    Examples
    --------
    >>> import numpy as np, scanplan
    >>> t = scanplan.sweep(camera=["dji-zenmuse-p1-35", "dji-mavic-3e"],
    ...                    height_m=np.arange(60, 160, 20), map_scale=2000,
    ...                    relief_interval_m=0.5)
    >>> t.shape, str(t["gsd_cm"].dtype), str(t["camera"].dtype)
    ((10, 17), 'float64', 'string')
    """
    from .project.signature import plain
    from .project.sweep import sweep_frame

    heights = plain(list(height_m) if not isinstance(height_m, str | bytes) and
                    hasattr(height_m, "__iter__") else height_m)
    return sweep_frame(height_m=heights, camera=camera,
                       forward_overlap_pct=plain(forward_overlap_pct),
                       side_overlap_pct=plain(side_overlap_pct), **plain(inputs))


def project_files(paths: Iterable[str | os.PathLike[str]]) -> list[str]:
    """Project files of ``paths``: files as given, folders' ``*.toml`` sorted by name.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> for name in ("b.toml", "a.toml", "notes.txt"):
    ...     _ = (folder / name).write_text("")
    >>> [pathlib.Path(f).name for f in project_files([folder, "x.toml"])]
    ['a.toml', 'b.toml', 'x.toml']
    >>> import shutil; shutil.rmtree(folder)
    """
    files: list[str] = []
    for item in paths:
        item = os.fspath(item)
        if os.path.isdir(item):
            files += sorted(os.path.join(item, f) for f in os.listdir(item)
                            if f.endswith(".toml"))
        else:
            files.append(item)
    return files


def batch(paths: str | os.PathLike[str] | Iterable[str | os.PathLike[str]]) -> BatchResult:
    r"""Plan several project files (folders: their ``*.toml``); a bad one is kept as a
    typed error while the others are planned.

    Examples
    --------
    >>> import pathlib, tempfile, scanplan
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "a.toml").write_text(
    ...     '[map]\nscale = 2000\nrelief_interval_m = 1\n[uav]\ncamera = "dji-zenmuse-p1-35"\n')
    >>> _ = (folder / "b.toml").write_text("[map]\nscale = 2000\n")
    >>> b = scanplan.batch(folder)
    >>> len(b.results), [pathlib.Path(f).name for f in b.errors]
    (1, ['b.toml'])
    >>> error = b.errors[str(folder / "b.toml")]
    >>> error.field.endswith("map.relief_interval_m"), error.message
    (True, 'is required: the relief interval in m')
    """
    from .project.file import load_project
    from .project.spec import plan_project

    if isinstance(paths, str | os.PathLike):
        paths = [paths]
    results: list[ProjectResult] = []
    errors: dict[str, InputError] = {}
    for path in project_files(paths):
        try:
            results.append(ProjectResult(plan_project(load_project(path))))
        except InputError as exc:
            errors[path] = exc
    return BatchResult(tuple(results), errors)

