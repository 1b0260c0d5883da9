"""The documents of one result written as one transaction: the command line's ``--xlsx``/
``--pdf``/``plan --out`` and the Python API's ``.write()`` both go through here.

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

import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import InputError, WriteError
from ..io.targets import FileKind, check_target
from ..progress import stage

__all__ = ["Target", "Written", "commit", "make_folder", "project_inputs", "refuse_folder",
           "refuse_targets", "remove_empty", "render_documents", "write_documents"]


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


def _pdf_engine() -> Callable[..., bytes]:
    """The PDF renderer; an engine that cannot load raises (OSError, ImportError)."""
    from .pdf import render_pdf

    return render_pdf


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
