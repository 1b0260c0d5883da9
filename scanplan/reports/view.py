"""The report view model: what every renderer shows, built once per result.

A result (:class:`scanplan.project.spec.PlanResult`, or a film and/or UAV job with their
norm set) becomes one :class:`ReportView`: the language, the sections present (in document
order), the one formatter of that language (:class:`~.formatter.Formatter`: words by
concept, numbers with the digits a row declares, decimal comma and no-break-space
thousands in Russian), the result's tables (:mod:`.views`), and the plots as SVG —
drawn on first use by :func:`scanplan.reports.plots.view_plot` and kept in the view, so a
workbook, an HTML page and a PDF of one result share them (SVG written directly,
:mod:`.svgchart`: no plotting library). The renderers (terminal
text, Excel, PDF; the JSON document needs no locale) lay out what the view holds; they
never recompute a number.

Extending the documents (a new section, e.g. the map page of the area, or a new sheet):
add its name to :data:`SECTION_ORDER`, make :func:`section_names` say when it is present,
and give the renderers its layout (a sheet writer registered in
``scanplan.reports.excel.SHEETS``; a ``{% if view.has('name') %}`` block of the PDF
templates). See docs/architecture.md, "Reports".
"""

from __future__ import annotations

import base64
import datetime as _dt
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..i18n.labels import LABELS
from .formatter import Formatter, formatter
from .views import ResultTables

if TYPE_CHECKING:
    from ..project.file import ReportMeta
    from ..project.jobs import ScanJob, UavJob
    from ..project.spec import PlanResult

__all__ = ["LOCALES", "SECTION_ORDER", "ReportView", "build_view", "section_names"]

LOCALES = ("en", "ru")

#: The sections of a report in document order. A section is present when
#: :func:`section_names` says so; renderers iterate the names they know.
SECTION_ORDER: tuple[str, ...] = ("spec", "film", "uav", "comparison")

# ---------------------------------------------------------------------------------------
# The view
# ---------------------------------------------------------------------------------------


def section_names(scan: Any, uav: Any, spec: Any) -> tuple[str, ...]:
    """The sections a report of these results has, in :data:`SECTION_ORDER`.

    Parameters
    ----------
    scan, uav : job or None
        The film and the UAV job.
    spec : PlanResult or None
        The specification of ``scanplan plan``.

    Returns
    -------
    tuple of str
        ``"spec"`` with a specification, ``"film"`` / ``"uav"`` with a job,
        ``"comparison"`` with both jobs.
    """
    present = {"spec": spec is not None, "film": scan is not None, "uav": uav is not None,
               "comparison": scan is not None and uav is not None}
    return tuple(name for name in SECTION_ORDER if present.get(name))


def svg_data_uri(svg: str) -> str:
    """An SVG as a ``data:`` URI (what the PDF's HTML embeds)."""
    return "data:image/svg+xml;base64," + base64.b64encode(svg.encode("utf-8")).decode()


@dataclass
class ReportView:
    """One result as the documents show it; built once (:func:`build_view`), rendered by
    the workbook and the PDF (and anything else added later).

    Attributes
    ----------
    scan, uav : job or None
        The film scan and UAV flight jobs (plan and norm set).
    spec : PlanResult or None
        The specification of ``scanplan plan``.
    meta : ReportMeta
        Title, approval blocks, language.
    when : datetime
        The document's creation time (``SOURCE_DATE_EPOCH`` when set).
    locale, platform : str
        The language and the digital platform (``"uav"`` / ``"aircraft"``).
    fmt : Formatter
        The words and numbers of ``locale`` and ``platform`` (a document that cites works
        takes ``fmt.document(view.citations)``).
    sections : tuple of str
        The sections present, in order (:func:`section_names`).
    tables : ResultTables
        The result's tables (:mod:`scanplan.reports.views`), each built on first use and
        laid out alike by every renderer of this view.
    charts : dict
        The plots drawn so far, as SVG (:func:`scanplan.reports.plots.view_plot` draws
        each on first use and keeps it here).
    citations : list
        The works cited so far, in order of first citation, shared by every document
        rendered from this view: the PDF and the workbook of one run number a work alike.
    """

    scan: ScanJob | None
    uav: UavJob | None
    spec: PlanResult | None
    meta: ReportMeta
    when: _dt.datetime
    locale: str
    platform: str
    fmt: Formatter
    sections: tuple[str, ...]
    tables: ResultTables = field(default_factory=ResultTables, repr=False)
    charts: dict[str, str] = field(default_factory=dict, repr=False)
    _html: list[str] = field(default_factory=list, repr=False)  # the PDF's HTML, once
    citations: list[Any] = field(default_factory=list, repr=False)

    def has(self, section: str) -> bool:
        """Whether the report has ``section``."""
        return section in self.sections

    def document_fmt(self) -> Formatter:
        """The formatter of one document of this view that cites works: its own reference
        list, numbered as every other document of this result numbers the works."""
        return self.fmt.document(self.citations)

    def job_of(self, which: str) -> Any:
        """The ``"scan"`` or ``"uav"`` job; ValueError when the report has none."""
        job = self.scan if which == "scan" else self.uav
        if job is None:
            raise ValueError(f"this report has no {which} plan")
        return job


def build_view(*, scan: ScanJob | None = None, uav: UavJob | None = None,
               meta: ReportMeta | None = None, spec: PlanResult | None = None,
               when: _dt.datetime | None = None,
               tables: ResultTables | None = None) -> ReportView:
    """The view of one result, for every renderer.

    Parameters
    ----------
    scan, uav : job, optional
        The film and/or UAV job (at least one).
    meta : ReportMeta, optional
        Title, approval blocks and language (default: English, no project data).
    spec : PlanResult, optional
        The specification of ``scanplan plan``.
    when : datetime, optional
        The creation time (default :func:`scanplan.reports.report_datetime`).
    tables : ResultTables, optional
        The result's tables when another renderer of the same result holds them already
        (``scanplan plan``'s terminal summary); built here otherwise.

    Returns
    -------
    ReportView

    Raises
    ------
    ValueError
        If neither ``scan`` nor ``uav`` is given, or ``tables`` are another result's.
    """
    from . import ReportMeta, report_datetime

    if scan is None and uav is None:
        raise ValueError("a report needs a scan plan, a UAV plan or both")
    meta = meta if meta is not None else ReportMeta()
    locale = meta.locale if meta.locale in LOCALES else "en"
    platform = uav.plan.inputs.platform if uav is not None else "uav"
    if tables is None:
        tables = ResultTables.of_jobs(scan, uav, spec)
    elif any(mine is not theirs for mine, theirs in (
            (tables.scan, scan.plan if scan is not None else None),
            (tables.uav, uav.plan if uav is not None else None), (tables.spec, spec))):
        raise ValueError("the tables given are not this result's")
    return ReportView(scan=scan, uav=uav, spec=spec, meta=meta,
                      when=when if when is not None else report_datetime(),
                      locale=locale, platform=platform, fmt=formatter(locale, platform),
                      sections=section_names(scan, uav, spec),
                      tables=tables)


def warning_heading_key(warning: Any) -> str | None:
    """The label key of a warning's short heading (page 1, the Warnings sheet, the PDF's
    warnings): ``warn_<code>``, None when the catalogue has none.

    Parameters
    ----------
    warning : PlanWarning or str
        A warning with ``code`` and ``message``, or its code (a warnings table's row key).

    Returns
    -------
    str or None
        ``"warn_<code>"``.
    """
    key = f"warn_{warning if isinstance(warning, str) else warning.code}"
    return key if key in LABELS["en"] else None
