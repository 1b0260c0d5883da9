"""The PDF report: jinja2 templates in ``templates/`` rendered by WeasyPrint.

The report *renders* a :class:`scanplan.project.api.ScanJob` and/or
:class:`scanplan.project.api.UavJob`
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

Reproducibility: the creation date comes from :func:`scanplan.reports.report_datetime`
(``SOURCE_DATE_EPOCH``), the PDF identifier is a hash of the content, and the SVG plots
are deterministic, so the same input gives a byte-identical PDF.
"""

from __future__ import annotations

import functools
import mimetypes
import os
import re
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any
from urllib.parse import unquote, urlsplit
from urllib.request import url2pathname

import jinja2
from markupsafe import Markup

from .._version import __version__
from ..messages import localize
from ..project.api import ScanJob, UavJob
from . import ReportMeta, _weasy, templates_dir, write_atomic
from .design import design_view
from .labels import LABELS
from .pdf_sections import (  # noqa: F401  (_object_name: tests)
    _comparison_view,
    _Fmt,
    _object_name,
    _scan_view,
    _spec_view,
    _uav_view,
)
from .references import Bibliography
from .view import ReportView, build_view, svg_data_uri
from .wording import document_date

weasyprint = _weasy.load()  # first: the fast library search and font subsetting (_weasy)
from weasyprint.text.fonts import FontConfiguration  # noqa: E402
from weasyprint.urls import URLFetcher, URLFetcherResponse  # noqa: E402

if TYPE_CHECKING:
    from ..project.spec import PlanResult

__all__ = ["BundledAssetFetcher", "render_html", "render_pdf", "write_pdf"]

_DEFAULT_META = ReportMeta()

_RUNNING_HEADER_CHARS = 60

# ---------------------------------------------------------------------------------------
# URL fetcher: data: URLs and the bundled assets only
# ---------------------------------------------------------------------------------------


class BundledAssetFetcher(URLFetcher):  # type: ignore[misc]
    """A WeasyPrint URL fetcher that serves ``data:`` URLs and bundled assets, nothing else.

    A ``file:`` URL is served only if it resolves (symlinks followed) to a regular file
    strictly inside ``root``; every other URL (``http:``, ``https:``, ``ftp:``, other
    local files) raises :class:`ValueError`, which WeasyPrint reports as a warning and
    skips. Every URL asked for is recorded in :attr:`requested`, every refusal in
    :attr:`refused`.

    Parameters
    ----------
    root : path, optional
        The folder whose files may be read (default: :func:`templates_dir`).
    """

    def __init__(self, root: str | os.PathLike[str] | None = None) -> None:
        super().__init__(allowed_protocols=("data",), allow_redirects=False)
        self.root = Path(root if root is not None else templates_dir()).resolve(strict=True)
        self.requested: list[str] = []
        self.refused: list[str] = []

    def fetch(self, url: str, headers: Any = None) -> Any:
        """Serve ``url`` if it is a ``data:`` URL or a bundled file; else raise ValueError.

        Parameters
        ----------
        url : str
            An absolute URL.
        headers : mapping, optional
            Ignored (no network access is ever made).

        Returns
        -------
        weasyprint.urls.URLFetcherResponse
        """
        self.requested.append(url)
        scheme = url.split(":", 1)[0].lower() if ":" in url else ""
        if scheme == "data":
            return super().fetch(url)
        if scheme == "file":
            parts = urlsplit(url)
            if parts.netloc not in ("", "localhost"):
                return self._refuse(url, "remote file URL")
            try:
                path = Path(url2pathname(unquote(parts.path))).resolve(strict=True)
            except (OSError, RuntimeError, ValueError):
                return self._refuse(url, "no such bundled file")
            if path == self.root or not path.is_relative_to(self.root) or not path.is_file():
                return self._refuse(url, "outside the bundled templates")
            mime = mimetypes.guess_type(path.name)[0] or "application/octet-stream"
            if path.suffix == ".ttf":
                mime = "font/ttf"
            return URLFetcherResponse(path.as_uri(), path.read_bytes(),
                                      {"Content-Type": mime})
        return self._refuse(url, "only data: URLs and bundled assets are allowed")

    def _refuse(self, url: str, why: str) -> Any:
        self.refused.append(url)
        raise ValueError(f"scanplan report: refused to fetch {url!r} ({why})")


def _shorten(text: str, limit: int) -> str:
    """``text`` cut to ``limit`` characters with an ellipsis (for the running header)."""
    return text if len(text) <= limit else text[:limit - 1].rstrip() + "…"


def _css_string(text: str) -> str:
    """``text`` as a CSS string literal (quotes, backslashes and ``<`` escaped)."""
    out = []
    for ch in text:
        if ch in '"\\<>\n\r' or ord(ch) < 32:
            out.append(f"\\{ord(ch):X} ")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


# ---------------------------------------------------------------------------------------
# Rendering
# ---------------------------------------------------------------------------------------


_LONG_RUN = re.compile(r"[^\s\u200b]{30}(?=[^\s\u200b])")


def _breakable(value: Any) -> Any:
    """Every ``{{ value }}`` of the templates: a run of 30+ characters without a space gets
    zero-width spaces, so a table cell can wrap it (``overflow-wrap: break-word``).

    ``overflow-wrap: anywhere`` would do the same, but WeasyPrint's table layout is then
    quadratic in the length of a cell's text (a 1,200-character object name of a norm set:
    45 s). Markup (the footer CSS) and ``data:`` URIs (the plots) are left as they are.
    """
    if (isinstance(value, str) and len(value) > 30 and not isinstance(value, Markup)
            and not value.startswith("data:")):
        return _LONG_RUN.sub(lambda m: m.group() + "\u200b", value)
    return value


@functools.lru_cache(maxsize=1)
def _environment() -> jinja2.Environment:
    """The templates' environment (one per process: templates are compiled once)."""
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(templates_dir())),
        autoescape=jinja2.select_autoescape(["html", "htm", "xml"], default=True,
                                            default_for_string=True),
        undefined=jinja2.StrictUndefined, trim_blocks=True, lstrip_blocks=True,
        keep_trailing_newline=True, finalize=_breakable)
    return env


def _terrain_plot(spec: Any, f: _Fmt) -> str | None:
    """The heights-above-ground figure of a ``[terrain]`` plan (issue 12), else None."""
    tr = getattr(getattr(spec, "uav", None), "terrain", None)
    if tr is None or len(tr.layout.photos) == 0:
        return None
    from . import plots

    limit = spec.uav.job.plan.max_height_m
    return svg_data_uri(plots.terrain_svg(tr, limit, f.locale))


def render_html(*, scan: ScanJob | None = None, uav: UavJob | None = None,
                meta: ReportMeta = _DEFAULT_META, spec: PlanResult | None = None,
                view: ReportView | None = None) -> str:
    """The report as an HTML document (what :func:`render_pdf` hands to WeasyPrint).

    Parameters
    ----------
    scan : ScanJob, optional
        A film scan plan and its norm set.
    uav : UavJob, optional
        A UAV flight plan and its norm set.
    meta : ReportMeta
        Title and approval block, locale.
    spec : PlanResult, optional
        The specification of ``scanplan plan`` (shown first, after the title block).
    view : ReportView, optional
        The result's view (:func:`scanplan.reports.view.build_view`), shared with the
        workbook; when given, ``scan``, ``uav``, ``meta`` and ``spec`` are taken from it.

    Returns
    -------
    str
        The HTML document; all user text escaped.

    Raises
    ------
    ValueError
        If neither ``scan`` nor ``uav`` is given, or the locale is unknown.
    """
    view = _view(scan, uav, meta, spec, view)
    scan, uav, meta, spec = view.scan, view.uav, view.meta, view.spec
    f = _Fmt(view, Bibliography(view.locale))
    now = view.when
    date = document_date(meta.date or now.date(), meta.locale)
    if scan is not None and uav is not None:
        title = f.label("pdf_title_plan")
    elif scan is not None:
        title = f.label("title_scan")
    else:
        title = f.label("title_uav")
    if meta.locale == "ru":  # «Лист 2 / Листов 4»
        footer = (f"{_css_string(f.label('sheet') + ' ')} counter(page) "
                  f"{_css_string(' / ' + f.label('sheets_of') + ' ')} counter(pages)")
    else:  # "Sheet 2 of 4"
        footer = (f"{_css_string(f.label('sheet') + ' ')} counter(page) "
                  f"{_css_string(' ' + f.label('sheets_of') + ' ')} counter(pages)")
    scan_view = _scan_view(scan, f) if scan is not None else None
    uav_view = _uav_view(uav, f) if uav is not None else None
    if uav_view is not None:
        uav_view["plot_terrain"] = _terrain_plot(spec, f)
    spec_view = _spec_view(spec, f) if spec is not None else None
    design = design_view(spec, f.locale, f.cite) if spec is not None else None
    ctx = {
        "lang": meta.locale, "title": title, "meta": meta, "date": date,
        "running_project": _shorten(" ".join(meta.project.split()), _RUNNING_HEADER_CHARS),
        "created": now.strftime("%Y-%m-%dT%H:%M:%SZ"),
        "generator": f"scanplan {__version__}",
        "footer_css": Markup(f"@page {{ @bottom-center {{ content: {footer}; }} }}"),
        "L": _Labels(f),
        "scan": scan_view,
        "uav": uav_view,
        # with a specification its own side-by-side table is shown; not this one as well
        "comparison": (_comparison_view(scan, uav, f)
                       if scan is not None and uav is not None
                       and not (spec is not None and spec.comparison) else None),
        "spec": spec_view,
        "design": design,
        "geo": _geo_views(spec, uav, meta.locale),
        "warnings_box": _warnings_box(scan_view, uav_view, spec, f),
        "references": f.bib.entries(),
    }
    return _environment().get_template("report.html").render(**ctx)


def _geo_views(spec: PlanResult | None, uav: UavJob | None, locale: str
               ) -> list[dict[str, Any]]:
    """The map pages of issue 11 (:mod:`scanplan.reports.mapview`): the specification's
    flight layouts, or the UAV job's; none without a layout."""
    from .exports import view_of
    from .mapview import geo_views

    view = view_of(spec, uav)
    return geo_views(view, locale) if view is not None else []


def _view(scan: ScanJob | None, uav: UavJob | None, meta: ReportMeta,
          spec: PlanResult | None, view: ReportView | None) -> ReportView:
    """The given view, or one built from the jobs (checked as the PDF needs them)."""
    if view is not None:
        return view
    if scan is None and uav is None:
        raise ValueError("give a scan plan, a UAV plan or both")
    if meta.locale not in ("en", "ru"):
        raise ValueError(f"locale must be 'en' or 'ru' (got {meta.locale!r})")
    return build_view(scan=scan, uav=uav, meta=meta, spec=spec)


def _warnings_box(scan_view: Any, uav_view: Any, spec: PlanResult | None,
                  f: _Fmt) -> list[str]:
    """Every warning in short form for page 1 (an approver sees them before signing): one
    line per kind of warning, with all the photo scales it concerns (as the workbook's
    box lists them)."""
    scales: dict[str, list[str]] = {}  # heading → photo scales, in order
    times: dict[str, int] = {}  # heading → warnings without a photo scale under it
    for view in (scan_view, uav_view):
        for w in view["warnings"] if view is not None else ():
            head = w["heading"] or w["message"]
            listed = scales.setdefault(head, [])
            listed += [x for x in w["scale_list"] if x not in listed]
            times[head] = times.get(head, 0) + (not w["scale_list"])
    items = [h + (f": {', '.join(xs)}" if xs else "") for h, xs in scales.items()
             for _ in range(1 if xs else max(times[h], 1))]
    if spec is not None:
        seen = {x["code"] for view in (scan_view, uav_view) if view
                for x in view["warnings"]}
        for w in spec.warnings:
            if w.code not in seen:
                key = f"pdf_warn_{w.code}"
                items.append(f.label(key) if key in LABELS["en"] else localize(w.message,
                                                                              f.locale))
    counts: dict[str, int] = {}
    for item in items:
        counts[item] = counts.get(item, 0) + 1
    return [f"{k} (×{n})" if n > 1 else k for k, n in counts.items()]


class _Labels:
    """``L.key`` / ``L('key', x=1)`` in templates: labels in the report's locale."""

    def __init__(self, f: _Fmt) -> None:
        self._f = f

    def __getattr__(self, key: str) -> str:
        try:
            return self._f.label(key)
        except KeyError:
            raise AttributeError(key) from None

    def __call__(self, key: str, **kw: Any) -> str:
        return self._f.label(key, **kw)


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
    fetcher = url_fetcher if url_fetcher is not None else BundledAssetFetcher()
    root = templates_dir().resolve()
    doc = weasyprint.HTML(string=html, base_url=root.as_uri() + "/", url_fetcher=fetcher)
    # the process's fonts, ready from the last report; a caller's own fetcher (tests) gets
    # fresh ones, so that it sees every file the document asks for
    fonts = _font_config(str(root)) if url_fetcher is None else FontConfiguration()
    return doc.write_pdf(pdf_identifier=True,  # type: ignore[no-any-return]
                         font_config=fonts)


@functools.lru_cache(maxsize=2)
def _font_config(root: str) -> FontConfiguration:
    """The fonts, ready for every PDF of this process (a batch renders many).

    A :class:`weasyprint.text.fonts.FontConfiguration` loads fontconfig's list of the
    system's fonts when made, and registers the bundled fonts of ``@font-face`` the first
    time a document names them; one per templates folder ``root`` and process keeps both
    (and WeasyPrint's per-font caches) from one report to the next.
    """
    del root  # the cache key: the bundled fonts of another folder get their own
    return FontConfiguration()


_WARM_UP_HTML = ("<!DOCTYPE html><html><head><meta charset='utf-8'>"
                 "<link rel='stylesheet' href='report.css'></head><body>"
                 "<p>Warm-up 0,5 м <strong>1:2000</strong></p></body></html>")


def warm_up() -> None:
    """Pay the first-use costs of a report ahead of it (:mod:`.pdfworker`, while the plan is
    made): the templates compiled, and a one-line document rendered with the process's
    fonts, so that fontconfig, Pango and both bundled faces are loaded."""
    _environment().get_template("report.html")
    root = templates_dir().resolve()
    weasyprint.HTML(string=_WARM_UP_HTML, base_url=root.as_uri() + "/",
                    url_fetcher=BundledAssetFetcher()).write_pdf(
                        font_config=_font_config(str(root)))


def write_pdf(path: str | os.PathLike[str], *, scan: ScanJob | None = None,
              uav: UavJob | None = None, meta: ReportMeta = _DEFAULT_META,
              spec: PlanResult | None = None) -> Path:
    """Render the report and write it atomically to ``path``.

    The PDF is rendered in memory first; on any error an existing file at ``path`` is left
    as it was and no temporary file remains.

    Parameters
    ----------
    path : path
        Target ``.pdf``.
    scan, uav : optional
        As :func:`render_pdf` (at least one).
    meta : ReportMeta
        Title and approval block, locale.
    spec : PlanResult, optional
        The specification of ``scanplan plan``.

    Returns
    -------
    Path
        ``path``.
    """
    return write_atomic(path, render_pdf(scan=scan, uav=uav, meta=meta, spec=spec))
