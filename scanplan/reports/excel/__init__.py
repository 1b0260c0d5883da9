"""The Excel report: every number of a scan and/or UAV plan in a workbook for approval.

Sheets (names in the report's language; only those with content are written):

- **Summary** — title and approval blocks, then the headline: per photo scale the binding
  constraint, scan pixel, scanner step and data volume with the engine's explanation;
  for a UAV flight GSD, L, L/GSD, the maximum flight height and its binding constraint,
  and the recognition of the map's smallest object.
- **Inputs** — what the plan was computed from.
- **Constraints** — every constraint at every photo scale (binding row highlighted).
- **Sweep** — the dense photo-scale sweep with a native chart (pixel per constraint).
- **UAV** — results, the constraints as maximum flight heights (binding highlighted),
  recognition of the norm objects, flight geometry, GSD and L against height (chart).
- **MTF** — the MTF of every component at the frame centre, the image contrast and the
  threshold, with a chart marking the resolving power R at their crossing.
- **Norms** — the norm set and the rows used (highlighted).
- **Warnings** — the engine's warnings.

Numbers are stored as numbers with invariant number formats (a Russian Excel shows them
with a decimal comma); scales are integers shown as ``1:10000``. Text from users is always
stored as a string cell, never a formula. Nothing is recomputed here: every value is read
from the plan objects. The workbook is rendered to memory, its zip re-packed with fixed
timestamps (``SOURCE_DATE_EPOCH`` gives byte-identical output) and written atomically.

The package: :mod:`.cells` (formats, styles, safe cells, the deterministic zip),
:mod:`.charts` (native charts), :mod:`.book` (the workbook being filled: page setup,
``label | value`` rows, the view's labels and numbers) and one module per group of sheets
(:mod:`.summary`, :mod:`.inputs`, :mod:`.film`, :mod:`.uav`, :mod:`.closing`). The sheets
are written in the order of :data:`SHEETS`; a sheet whose section the report lacks is
left out. A new sheet is one writer ``(book, view) -> None`` and one :class:`Sheet`
record in :data:`SHEETS` (see docs/architecture.md, "Reports").
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from ...i18n.labels import t as t  # re-exported: the sheets' labels
from ...i18n.messages import document_text
from .. import ReportMeta
from ..view import ReportView, build_view
from .book import Book
from .cells import _BINDING_FILL as _BINDING_FILL  # re-exported: the binding highlight
from .cells import MISSING as MISSING
from .cells import _repack as _repack  # re-exported: the batch summary workbook
from .cells import put_num as put_num
from .cells import put_text as put_text
from .closing import norms_sheet, references_sheet, warnings_sheet
from .control import control_sheet
from .design import write_design_sheet
from .film import constraints_sheet, sweep_sheet
from .inputs import inputs_sheet
from .plans import write_plans_sheet
from .summary import summary_sheet
from .terrain import terrain_sheet
from .uav import mtf_sheet, uav_sheet

if TYPE_CHECKING:
    from ...project.jobs import ScanJob, UavJob
    from ...project.spec import PlanResult

__all__ = ["SHEETS", "Book", "Sheet", "render_xlsx"]

_DEFAULT_META = ReportMeta()
_Book = Book  # the former name


@dataclass(frozen=True)
class Sheet:
    """One sheet (or group of sheets) of the workbook.

    Attributes
    ----------
    name : str
        A short name (for the reader of the code; the sheet's title is a label).
    write : callable
        ``write(book, view)``: adds the sheet(s) to ``book``.
    section : str or None
        The view's section the sheet needs (:data:`scanplan.reports.view.SECTION_ORDER`);
        ``None``: always written.
    """

    name: str
    write: Callable[[Book, ReportView], None]
    section: str | None = None


#: The workbook's sheets in order.
SHEETS: tuple[Sheet, ...] = (
    Sheet("summary", lambda b, v: summary_sheet(b, v.scan, v.uav, v.spec)),
    Sheet("design", lambda b, v: write_design_sheet(b, v.spec), "spec"),
    Sheet("plans", write_plans_sheet, "spec"),
    Sheet("control", lambda b, v: control_sheet(b, v.spec), "spec"),
    Sheet("inputs", lambda b, v: inputs_sheet(b, v.scan, v.uav)),
    Sheet("constraints", lambda b, v: constraints_sheet(b), "film"),
    Sheet("sweep", lambda b, v: sweep_sheet(b, v.scan, v.spec), "film"),
    Sheet("uav", lambda b, v: uav_sheet(b, v.uav), "uav"),
    Sheet("mtf", lambda b, v: mtf_sheet(b, v.uav), "uav"),
    Sheet("terrain", lambda b, v: terrain_sheet(b, v.spec), "spec"),
    Sheet("flight", lambda b, v: _flight_sheets(b, v)),  # issue 11: Strips, Photos
    Sheet("norms", lambda b, v: norms_sheet(b, v.scan, v.uav)),
    Sheet("warnings", lambda b, v: warnings_sheet(b, v.scan, v.uav)),
    Sheet("references", lambda b, v: references_sheet(b)),
)


def _flight_sheets(book: Book, view: ReportView) -> None:
    """The Strips and Photos sheets of the flight over the area (issue 11), when the
    specification (or the UAV job) has a flight layout."""
    from ..exports import view_of
    from ..geosheets import add_geo_sheets

    flights = view_of(view.spec, view.uav)
    if flights is not None:
        add_geo_sheets(book, flights)


@document_text()
def render_xlsx(
    *,
    scan: ScanJob | None = None,
    uav: UavJob | None = None,
    meta: ReportMeta = _DEFAULT_META,
    spec: PlanResult | None = None,
    view: ReportView | None = None,
) -> bytes:
    """Render the Excel report of a scan plan, a UAV plan or both, in memory.

    Parameters
    ----------
    scan : ScanJob, optional
        A film scan plan and its norm set (:func:`scanplan.project.jobs.scan_job`).
    uav : UavJob, optional
        A UAV flight plan and its norm set (:func:`scanplan.project.jobs.uav_job`).
    meta : ReportMeta
        Title and approval blocks and the language (``meta.locale``: ``"en"``/``"ru"``).
    spec : PlanResult, optional
        The specification of ``scanplan plan`` (recommended photo scale / flight height,
        comparison); shown first on the Summary sheet.
    view : ReportView, optional
        The result's view (:func:`scanplan.reports.view.build_view`), shared with the PDF;
        when given, the arguments above are taken from it.

    Returns
    -------
    bytes
        The ``.xlsx`` file. With ``SOURCE_DATE_EPOCH`` set, two renders of the same plans
        are byte-identical.

    Raises
    ------
    ValueError
        If neither ``scan`` nor ``uav`` is given.
    """
    if view is None:
        if scan is None and uav is None:
            raise ValueError("render_xlsx needs a scan plan, a UAV plan or both")
        view = build_view(scan=scan, uav=uav, meta=meta, spec=spec)
    if not view.citations:  # number the works as the PDF of this result numbers them
        from ..pdfhtml import render_html

        render_html(view=view)
    book = Book(view)
    for sheet in SHEETS:
        if sheet.section is None or view.has(sheet.section):
            sheet.write(book, view)
    return book.to_bytes()
