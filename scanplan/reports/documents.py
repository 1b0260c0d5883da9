"""The one path that renders and writes documents: the command line's ``--xlsx``/``--pdf``/
``plan --out``, the Python API's ``.write()`` and the page's downloads all go through here
(no other module calls the PDF or workbook renderers).

What ``plan --out`` writes for one project — the documents and the exported files of the
outputs chosen (``--formats``: :data:`OUTPUTS`) — is :func:`plan_outputs`; the documents
of a result in memory (the page's downloads) are :func:`render`; the PDF engine is loaded
by :func:`load_pdf_engine`, which says what is missing without touching standard output.

:func:`write_documents` is the whole transaction:

1. the targets are refused before anything is rendered (:func:`refuse_targets`: a folder
   that does not exist, two documents named to one file; then every target's
   :func:`scanplan.io.targets.check_target`: never an input file, never a file scanplan
   did not write unless ``force`` …);
2. one view of the result is built (:func:`scanplan.reports.view.build_view`) and every
   requested document is rendered from it to memory — the PDF, when a worker process is
   given, on the other core while the workbook is built here;
3. the documents and the extra files of the set (``plan --out``'s missions and GIS files)
   are written all or nothing (:func:`commit`, :func:`scanplan.io.atomic.write_atomic_many`),
   the targets checked again under the folders' lock, and the exported files of an earlier
   plan that this one no longer writes removed in the same transaction (``sweep``).

What the caller says (``wrote FILE`` lines, warnings) stays with the caller: this module
prints nothing; it reports through :class:`Written` and the hooks it is given.
"""

from __future__ import annotations

import contextlib
import io
import os
import sys
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import InputError, PdfEngineError, WriteError
from ..io.targets import FileKind, check_target
from ..progress import stage

__all__ = ["DOCUMENTS", "OUTPUTS", "PDF_HELP", "Outputs", "Target", "Written", "commit",
           "load_pdf_engine", "make_folder", "outputs_chosen", "plan_outputs",
           "project_inputs", "refuse_folder", "refuse_targets", "remove_empty", "render",
           "render_documents", "render_summary", "write_documents"]

OUTPUTS = ("xlsx", "pdf", "missions", "gis")
"""The outputs ``plan --out`` writes (``--formats``, ``ProjectResult.write(formats=…)``),
in the order of the files written: the workbook, the PDF, the flight missions, the files
for a GIS."""
DOCUMENTS = ("xlsx", "pdf")
"""The outputs that are documents of a result (the others are its exported files)."""

PDF_HELP = {
    "linux": "install Pango (Debian/Ubuntu: apt-get install libpango-1.0-0 "
             "libpangoft2-1.0-0; Fedora: dnf install pango)",
    "darwin": "install Pango (brew install pango)",
    "win32": "install the GTK3 runtime (which brings Pango), as WeasyPrint's installation "
             "guide describes",
}
"""How to get the PDF engine's system library, by platform."""


@dataclass(frozen=True)
class Target:
    """One document to write.

    Attributes
    ----------
    path : str
        The file, as the user gave it.
    kind : {"xlsx", "pdf"}
        The document.
    field : str
        How messages name it (``--xlsx``, ``--out``, ``out_dir``).
    """

    path: str
    kind: str
    field: str


@dataclass(frozen=True)
class Written:
    """What a transaction did.

    Attributes
    ----------
    files : list of str
        Every file written (documents first, then the extra files), in order, as given.
    removed : list of str
        The stale exports of an earlier plan removed by the sweep.
    missing : list of str
        Documents asked for but not rendered (no PDF engine here); nothing was written
        in their place.
    """

    files: list[str]
    removed: list[str] = field(default_factory=list)
    missing: list[str] = field(default_factory=list)


def refuse_targets(targets: Sequence[Target]) -> None:
    """Refuse what no check of a single target can see: a folder that does not exist, and
    two documents named to one file (also through a link).

    Raises
    ------
    InputError
        Naming the target's field (exit 2).
    """
    for t in targets:
        folder = os.path.dirname(os.path.abspath(t.path))
        if not os.path.isdir(folder):
            raise InputError(t.field, f"folder {folder!r} does not exist")
    seen: dict[str, Target] = {}
    for t in targets:
        key = os.path.normcase(os.path.realpath(t.path))
        if key in seen:
            raise InputError(t.field, f"{t.path!r} is the file {seen[key].field} writes; "
                             "give another name")
        seen[key] = t


def _checker(targets: Sequence[Target], extra: Mapping[str, tuple[Any, bytes]],
             extra_field: str, inputs: Iterable[str], force: bool) -> Callable[[], None]:
    """The check of every target: before rendering, and again under the folders' lock."""
    inputs = list(inputs)

    def check() -> None:
        for t in targets:
            check_target(t.path, t.field, t.kind, inputs=inputs, force=force)
        for path, (kind, _) in extra.items():
            check_target(path, extra_field, kind, inputs=inputs, force=force)
    return check


def load_pdf_engine() -> Callable[..., bytes]:
    """The PDF renderer (:func:`scanplan.reports.pdf.render_pdf`).

    WeasyPrint's own notice on a missing library (printed on standard output, where a
    program reads ``--json``) is kept off it.

    Raises
    ------
    PdfEngineError
        WeasyPrint cannot load (no Pango): the library's reason and how to install it.
    """
    notice = io.StringIO()
    try:
        with contextlib.redirect_stdout(notice):
            from .pdf import render_pdf
    except (OSError, ImportError) as exc:  # cffi's dlopen of Pango, or no WeasyPrint
        text = str(exc)  # the library's own first line: what could not be loaded
        reason = text.splitlines()[0] if text.strip() else type(exc).__name__
        raise PdfEngineError(reason, PDF_HELP.get(sys.platform, PDF_HELP["linux"])
                             ) from None
    return render_pdf


_pdf_engine = load_pdf_engine


def render_documents(targets: Sequence[Target], *, scan: Any = None, uav: Any = None,
                     spec: Any = None, meta: Any = None,
                     pdf_engine: Callable[[], Callable[..., bytes] | None] | None = None,
                     pdf_worker: Any = None, tables: Any = None) -> dict[str, bytes]:
    """Render the documents of ``targets`` to memory from one view of the result.

    Parameters
    ----------
    targets : sequence of Target
        The documents (``xlsx``, ``pdf``), in order.
    scan, uav, spec, meta
        The result (as :func:`scanplan.reports.view.build_view` takes it).
    pdf_engine : callable, optional
        Returns the PDF renderer, or None when there is no engine (then the PDF is not
        rendered); default: :func:`scanplan.reports.pdf.render_pdf` (raising without one).
    pdf_worker : PdfWorker, optional
        Renders the PDF in another process (:mod:`scanplan.reports.pdfworker`); a worker
        that fails gives way to the renderer here.
    tables : ResultTables, optional
        The result's tables, when the caller lays them out too (``scanplan plan``'s
        terminal summary): the view holds these (:func:`scanplan.reports.view.build_view`).

    Returns
    -------
    dict of str to bytes
        path → bytes of each document rendered, in the order of ``targets``.
    """
    from .view import build_view

    engine = pdf_engine or _pdf_engine
    extra = {"spec": spec} if spec is not None else {}
    # one view of the result for every document: labels, numbers and plots built once
    view = build_view(scan=scan, uav=uav, meta=meta, spec=spec, tables=tables)
    pdf = next((t.path for t in targets if t.kind == "pdf"), None)
    # the PDF renders in the worker, from the HTML written here, while this process builds
    # the workbook; a worker that fails gives None and the PDF is rendered here (any error
    # is raised here)
    forked = False
    if pdf_worker is not None and pdf is not None:
        from .pdfhtml import render_html

        forked = pdf_worker.submit(render_html(view=view))
    rendered: dict[str, bytes] = {}
    with stage("reports", len(targets), "documents") as step:
        for t in targets:
            if t.kind == "xlsx":
                from .excel import render_xlsx as render
            elif forked or (render := engine()) is None:
                step()
                continue  # rendered by the worker, or no PDF engine here
            rendered[t.path] = render(scan=scan, uav=uav, meta=meta, view=view, **extra)
            step()
    if forked:
        data = pdf_worker.result()
        if data is None and (render := engine()) is not None:
            data = render(scan=scan, uav=uav, meta=meta, view=view, **extra)
        if data is not None:
            rendered[pdf] = data  # type: ignore[index]
    return {t.path: rendered[t.path] for t in targets if t.path in rendered}


def render(kinds: Sequence[str], *, scan: Any = None, uav: Any = None, spec: Any = None,
           meta: Any = None, tables: Any = None, beside: Iterable[Any] = ()
           ) -> dict[str, bytes]:
    """The documents ``kinds`` (``"xlsx"``, ``"pdf"``) of one result, in memory, rendered
    from one view as ``plan --out`` renders them (the page's downloads).

    ``beside``: the exported formats (file kinds or their names) written beside the
    documents — what they may say is beside them (none: downloaded alone).

    Raises
    ------
    PdfEngineError
        A PDF is asked for and its engine cannot load.
    """
    targets = [Target(kind, kind, kind) for kind in kinds]
    if spec is not None:
        from .exports import with_exports

        spec = with_exports(spec, beside)
    return render_documents(targets, scan=scan, uav=uav, spec=spec, meta=meta, tables=tables)


def render_summary(frame: Any) -> dict[str, bytes]:
    """A batch's summary (one row per project) as ``{"csv": …, "xlsx": …}``."""
    from .summary import summary_csv, summary_xlsx

    return {"csv": summary_csv(frame), "xlsx": summary_xlsx(frame)}


@dataclass(frozen=True)
class Outputs:
    """What ``plan --out`` writes for one project.

    Attributes
    ----------
    targets : list of Target
        The documents (``NAME.xlsx``, ``NAME.pdf``) of the outputs chosen.
    exports : dict
        The exported files of the outputs chosen: path → (format, bytes).
    """

    targets: list[Target]
    exports: dict[str, tuple[Any, bytes]]


def is_output_name(name: str) -> bool:
    """Whether ``name`` is a file ``plan --out`` may write at its folder's top: the reports
    (``spec.pdf``, ``spec.xlsx``) or an exported file
    (:data:`scanplan.geo.export.formats.FORMATS`, a film layout's ``film-`` ones too)."""
    import re

    from ..geo.export.formats import FORMATS

    if name.casefold() in {"spec.pdf", "spec.xlsx"}:
        return True
    return any(re.fullmatch(f"(?:film-)?{f.name_pattern()}", name, re.IGNORECASE)
               for f in FORMATS)


def outputs_chosen(formats: Iterable[str] | None, field: str) -> tuple[str, ...]:
    """The outputs named by ``formats`` (None: all of :data:`OUTPUTS`), in their order.

    Raises
    ------
    InputError
        Naming ``field``: an unknown output, or none.
    """
    if formats is None:
        return OUTPUTS
    names = [str(f).strip().lower() for f in ([formats] if isinstance(formats, str)
                                              else formats)]
    bad = [n for n in names if n not in OUTPUTS]
    if bad or not names:
        raise InputError(field, f"must name some of {', '.join(OUTPUTS)} (got "
                         f"{', '.join(names) if names else 'none'})")
    return tuple(f for f in OUTPUTS if f in names)


def plan_outputs(result: Any, out_dir: str, formats: Iterable[str] | None = None, *,
                 stem: str | None = None, field: str = "--out",
                 formats_field: str = "--formats",
                 note: Callable[[str], None] | None = None) -> Outputs:
    """The documents and exported files ``plan --out`` writes for one project into
    ``out_dir``: the chosen outputs (``formats``, None: all of them).

    An exported output named in ``formats`` that this project writes no file of — ``gis``
    or ``missions`` for a project without a polygon, ``missions`` for a film survey — is
    refused rather than silently skipped.

    Parameters
    ----------
    result : PlanResult
        The specification.
    out_dir : str
        The folder.
    formats : iterable of str, optional
        Some of :data:`OUTPUTS`.
    stem : str, optional
        A batch's name for the project: ``NAME.xlsx``, ``NAME-flight.kml`` (default
        ``spec.xlsx``, ``flight.kml``).
    field, formats_field : str
        How messages name the folder and the outputs (``--out``, ``--formats``).
    note : callable, optional
        Told why an exported file the user may expect is not written.

    Returns
    -------
    Outputs

    Raises
    ------
    InputError
        ``formats_field``: an unknown output, or one this project writes nothing of.
    """
    chosen = outputs_chosen(formats, formats_field)
    targets = [Target(os.path.join(out_dir, (stem or "spec") + f".{kind}"), kind, field)
               for kind in DOCUMENTS if kind in chosen]
    exported = [o for o in chosen if o not in DOCUMENTS]
    exports: dict[str, tuple[Any, bytes]] = {}
    if exported:
        from .exports import export_files

        every = export_files(result, out_dir, prefix=f"{stem}-" if stem is not None else "",
                             note=note)
        exports = {path: item for path, item in every.items()
                   if item[0].output in exported}
        if formats is not None:
            _refuse_unwritten(result, exported, exports, formats_field)
    return Outputs(targets, exports)


def _refuse_unwritten(result: Any, exported: list[str],
                      exports: Mapping[str, tuple[Any, bytes]], field: str) -> None:
    """An exported output asked for by name that this project writes no file of."""
    written = {item[0].output for item in exports.values()}
    missing = [o for o in exported if o not in written]
    if not missing:
        return
    area = getattr(result, "area", None)
    name = getattr(getattr(result, "project", None), "path", None) or "the project"
    if area is None or not area.georeferenced:
        why = (f"{name} has no area on the map: give [area] file or [area] polygon "
               "(a width × length block has no place to fly over)")
    else:
        from .exports import export_notes

        notes = [n.text("en") for n in export_notes(result)]
        why = "; ".join(notes) if notes else f"{name} has no flight it can be written for"
    raise InputError(field, f"{' and '.join(missing)} writes the flight over the area: "
                     f"{why}")


def commit(files: Mapping[str, bytes], *, check: Callable[[], None], sweep: str | None = None,
           announce: Callable[[Mapping[str, bytes]], None] | None = None,
           ) -> tuple[list[Path], list[str]]:
    """Write ``files`` all or nothing (:func:`scanplan.io.atomic.write_atomic_many`),
    ``check`` run again under the folders' lock, together with the removal of the
    exported files of an earlier run in the folder ``sweep`` that this set no longer
    holds (``mission-04.plan`` of six sorties, now three).

    Returns
    -------
    (list of Path, list of str)
        The files written, and the stale files removed.
    """
    from ..io.atomic import write_atomic_many

    removed: list[str] = []

    def stale() -> list[str]:  # under the transaction's lock, after the check
        from .exports import stale_exports

        removed[:] = stale_exports(sweep, set(files)) if sweep else []
        return removed

    if announce is not None:
        announce(files)
    written = write_atomic_many(files, check=check, remove=stale if sweep else None,
                                as_set=sweep)
    return written, removed


def write_documents(targets: Sequence[Target], *, scan: Any = None, uav: Any = None,
                    spec: Any = None, meta: Any = None,
                    extra: Mapping[str, tuple[str | FileKind, bytes]] | None = None,
                    extra_field: str = "--out", inputs: Iterable[str] = (),
                    force: bool = False, sweep: str | None = None,
                    pdf_engine: Callable[[], Callable[..., bytes] | None] | None = None,
                    pdf_worker: Any = None,
                    on_missing: Callable[[list[str]], None] | None = None,
                    announce: Callable[[Mapping[str, bytes]], None] | None = None,
                    tables: Any = None) -> Written:
    """Render the documents of ``targets`` and write them with ``extra`` as one
    transaction: all of them, or none (the module docstring's steps).

    Parameters
    ----------
    targets : sequence of Target
        The documents, in the order they are written.
    scan, uav, spec, meta
        The result.
    extra : mapping, optional
        Other files of the same set: path → (file kind, bytes) (``plan --out``'s exports).
    extra_field : str
        How messages name the extra files' targets.
    inputs : iterable of str
        The run's input files: no target may be one of them (even with ``force``).
    force : bool
        Replace existing files scanplan did not write.
    sweep : str, optional
        The folder whose exported files of an earlier plan go in the same transaction.
    pdf_engine, pdf_worker
        As :func:`render_documents`.
    on_missing : callable, optional
        Told the documents not rendered, before anything is written.
    announce : callable, optional
        Told the whole set just before it is written.
    tables : ResultTables, optional
        As :func:`render_documents`.

    Raises
    ------
    InputError
        A refused target (nothing touched).
    WriteError
        The write failed; every previous file is as it was.
    """
    extra = dict(extra or {})
    targets = list(targets)
    if spec is not None:  # what the documents may say is beside them: this set's exports
        from .exports import with_exports

        spec = with_exports(spec, (kind for kind, _ in extra.values()))
        if tables is not None:  # the caller's tables, of the same result: nothing they show
            tables.spec = spec  # depends on which files the run writes beside them
    check = _checker(targets, extra, extra_field, inputs, force)
    refuse_targets(targets)
    check()
    rendered = render_documents(targets, scan=scan, uav=uav, spec=spec, meta=meta,
                                pdf_engine=pdf_engine, pdf_worker=pdf_worker, tables=tables)
    missing = [t.path for t in targets if t.path not in rendered]
    if missing and on_missing is not None:
        on_missing(missing)
    files = {**rendered, **{path: data for path, (_, data) in extra.items()}}
    _, removed = commit(files, check=check, sweep=sweep, announce=announce)
    return Written(list(files), removed, missing)


def project_inputs(result: Any) -> list[str]:
    """The files a planned project read besides itself: its area file, its DEM (never
    replaced by an output, even with ``force``)."""
    project = getattr(result, "project", None)  # the parsed model (project/model.py)
    if project is None:
        return []
    found: list[str] = []
    area_file = project.area.file
    if isinstance(area_file, str) and area_file:
        found.append(os.path.expanduser(area_file))  # already resolved beside the project
    terrain = project.terrain
    if terrain is not None and terrain.config.dem is not None:
        found.append(str(terrain.config.dem))  # resolved beside the project file
    return found


def refuse_folder(path: str, field: str) -> None:
    """The folder the documents go into (``--out``, ``out_dir``) may be created: not an
    existing file, not below one (``FILE/x``), nor (or a folder above it) a symbolic link
    to nothing — scanplan creates missing folders, not the target of a broken link.

    Raises
    ------
    InputError
        Naming ``field`` (exit 2).
    """
    if os.path.exists(path) and not os.path.isdir(path):
        raise InputError(field, f"{path!r} is not a folder")
    probe = path
    while probe and not os.path.exists(probe):
        if os.path.islink(probe):
            shown = "" if probe == path else f" (in {path!r})"
            raise InputError(field, f"{probe!r}{shown} is a symbolic link to "
                             f"{os.readlink(probe)!r}, which does not exist; create that "
                             "folder, or give another")
        parent = os.path.dirname(probe.rstrip(os.sep))
        if parent == probe:
            break
        probe = parent
    if probe and probe != path and os.path.exists(probe) and not os.path.isdir(probe):
        raise InputError(field, f"{path!r} cannot be created: {probe!r} is a file, not a "
                         "folder; give another folder")


def make_folder(path: str) -> list[str]:
    """``os.makedirs(path)``; the folders it created, deepest first (to undo on failure:
    :func:`remove_empty`).

    Raises
    ------
    WriteError
        The folder could not be created (nothing left behind).
    """
    created = []
    probe = os.path.abspath(path)
    while probe and not os.path.exists(probe):
        created.append(probe)
        probe = os.path.dirname(probe)
    try:
        os.makedirs(path, exist_ok=True)
    except OSError as exc:
        remove_empty(created)
        raise WriteError.from_os_error(path, exc, action="create folder") from exc
    return created


def remove_empty(folders: list[str]) -> None:
    """Remove the folders (deepest first) that are still empty."""
    for folder in folders:
        try:
            os.rmdir(folder)
        except OSError:
            return
