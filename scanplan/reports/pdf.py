"""The PDF report: jinja2 templates in ``templates/`` rendered by WeasyPrint.

The report *renders* a :class:`scanplan.project.jobs.ScanJob` and/or
:class:`scanplan.project.jobs.UavJob`
(their plans and norm set); every number comes from the plan objects, formatted per
locale (decimal comma in Russian). The document is A4 with the approval block («УТВЕРЖДАЮ»
/ APPROVED) and, when the project names one, the agreement block («СОГЛАСОВАНО» / AGREED),
a title block (organisation and contract number when given), every warning in short form
on page 1, inputs, the result table with the binding constraint highlighted and explained,
warnings, formulas with numbered references, SVG plots, the list of references, the
«Составил / Проверил» (compiled / checked) lines and «Лист N / Листов M» ("Sheet N of M")
footers. Nothing internal reaches the page: parameters by name and unit, values in words,
cameras and scanners by model, works by reference number (:mod:`.references`, :mod:`.wording`).

Safety: templates are autoescaped, so user text (project, customer, ...) is always shown
as text; and the renderer's URL fetcher (:class:`BundledAssetFetcher`) serves only
``data:`` URLs and files inside the bundled templates folder — nothing a project file
says can make WeasyPrint read another local file or the network.

Layout: :mod:`.pdfhtml` writes the HTML (jinja2, no WeasyPrint), :mod:`.pdfrender` turns
HTML into PDF (WeasyPrint, no engine); this module joins the two. A plan writing both reports
renders the HTML itself and hands it to the PDF worker (:mod:`.pdfworker`).

Reproducibility: the creation date comes from :func:`scanplan.reports.report_datetime`
(``SOURCE_DATE_EPOCH``), the PDF identifier is a hash of the content, and the SVG plots
are deterministic, so the same input gives a byte-identical PDF.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from ..project.jobs import ScanJob, UavJob
from . import ReportMeta, templates_dir  # noqa: F401  (templates_dir: tests)
from .pdfhtml import _DEFAULT_META, render_html
from .pdfrender import (  # noqa: F401  (weasyprint, _font_config, warm_up: callers, tests)
    BundledAssetFetcher,
    _font_config,
    html_to_pdf,
    warm_up,
    weasyprint,
)
from .view import ReportView

if TYPE_CHECKING:
    from ..project.spec import PlanResult

__all__ = ["BundledAssetFetcher", "render_html", "render_pdf"]


def render_pdf(*, scan: ScanJob | None = None, uav: UavJob | None = None,
               meta: ReportMeta = _DEFAULT_META,
               url_fetcher: Callable[[str], Any] | None = None,
               spec: PlanResult | None = None, view: ReportView | None = None) -> bytes:
    """Render the report to PDF bytes (A4; nothing is written).

    Parameters
    ----------
    scan : ScanJob, optional
        A film scan plan and its norm set.
    uav : UavJob, optional
        A UAV flight plan and its norm set. Both: the sections one after the other and a
        short comparison.
    meta : ReportMeta
        Title and approval block, locale (``"en"`` or ``"ru"``).
    url_fetcher : BundledAssetFetcher, optional
        For tests; default a fresh :class:`BundledAssetFetcher`.
    spec : PlanResult, optional
        The specification of ``scanplan plan``.
    view : ReportView, optional
        The result's view, shared with the workbook (then the arguments above but
        ``url_fetcher`` are taken from it).

    Returns
    -------
    bytes
        The PDF. With ``SOURCE_DATE_EPOCH`` set, identical input gives identical bytes.
    """
    html = render_html(scan=scan, uav=uav, meta=meta, spec=spec, view=view)
    # the fetcher made here (tests spy on this module's name); the process's fonts, ready
    # from the last report, and fresh ones with a caller's own fetcher
    fetcher = url_fetcher if url_fetcher is not None else BundledAssetFetcher()
    return html_to_pdf(html, fetcher, fresh_fonts=url_fetcher is not None)
