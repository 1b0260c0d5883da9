"""The PDF report as HTML: the jinja2 templates of ``templates/`` filled from a result's view.

:func:`render_html` is everything of the report but the rendering to PDF
(:mod:`.pdfrender`, WeasyPrint); it imports no WeasyPrint, so the process that plans can
write the HTML while another imports the renderer (:mod:`.pdfworker`). Templates are
autoescaped, so user text (project, customer, ...) is always shown as text.
"""

from __future__ import annotations

import functools
import re
from typing import TYPE_CHECKING, Any

import jinja2
from markupsafe import Markup, escape

from .._version import __version__
from ..i18n.messages import document_text, localize
from ..project.jobs import ScanJob, UavJob
from . import ReportMeta, templates_dir
from .design import design_view
from .pdf_sections import (  # noqa: F401  (_object_name: tests)
    _comparison_view,
    _Fmt,
    _object_name,
    _scan_view,
    _spec_view,
    _uav_view,
)
from .references import Bibliography
from .view import ReportView, build_view, svg_data_uri, warning_heading_key
from .views import Row
from .wording import document_date

if TYPE_CHECKING:
    from ..project.spec import PlanResult

__all__ = ["render_html"]

_DEFAULT_META = ReportMeta()

_RUNNING_HEADER_CHARS = 60


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


_SUBSCRIPT = re.compile(r"(?<![\w])([A-Za-zσΔ])_([A-Za-z0-9]{1,5})(?![\w])")


def typeset(value: Any) -> Markup:
    """A formula as a printed instruction shows it: ``P_S = V_s·Mk/(k·Mc)`` with its
    subscripts set as subscripts (``P<sub>S</sub>``) and ``sqrt(`` as a root sign; the
    rest escaped. The ``formula`` filter of the templates."""
    text = str(escape(_breakable(value)))
    text = text.replace("sqrt(", "√(")
    return Markup(_SUBSCRIPT.sub(r"\1<sub>\2</sub>", text))


@functools.lru_cache(maxsize=1)
def _environment() -> jinja2.Environment:
    """The templates' environment (one per process: templates are compiled once)."""
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(templates_dir())),
        autoescape=jinja2.select_autoescape(["html", "htm", "xml"], default=True,
                                            default_for_string=True),
        undefined=jinja2.StrictUndefined, trim_blocks=True, lstrip_blocks=True,
        keep_trailing_newline=True, finalize=_breakable)
    env.filters["formula"] = typeset
    return env


def _terrain_plot(spec: Any, f: _Fmt) -> str | None:
    """The heights-above-ground figure of a ``[terrain]`` plan (issue 12), else None."""
    tr = getattr(getattr(spec, "uav", None), "terrain", None)
    if tr is None or len(tr.layout.photos) == 0 or tr.summary()["source"] != "dem":
        return None  # a ground range without a DEM: flat ground under every photo, not drawn
    from . import plots

    limit = spec.uav.job.plan.max_height_m
    return svg_data_uri(plots.terrain_svg(tr, limit, f.locale))


def _terrain_rows(spec: Any, f: _Fmt) -> list[tuple[str, str]]:
    """What the crew and the approver need of the relief, in words: the DEM (file, CRS,
    cell size) or the ground range given, the ground under the photos, the flight altitude
    above sea level, the heights above ground and the highest height over the relief."""
    tr = getattr(getattr(spec, "uav", None), "terrain", None)
    if tr is None:
        return []
    d = tr.summary()
    m = f.label("m")
    rows = []
    if d["source"] == "dem":
        cell = d.get("dem_cell_size") or [None, None]
        size = (f"{f.g(cell[0] * 3600.0)}″" if d.get("dem_geographic")
                else f"{f.g(abs(cell[0]))} {m}")
        rows.append((f.label("terrain_facts_dem"), f.label(
            "terrain_facts_dem_value", file=d["dem"], crs=d["dem_crs"], cell=size)))
    else:  # and no chart of flat ground along the strips: the note says why
        rows.append((f.label("terrain_facts_dem"), f.label("terrain_facts_range") + ". "
                     + f.label("terrain_facts_no_chart")))
    rows.append((f.label("terrain_facts_ground"),
                 f"{f.num(d['ground_min_m'], 1)}–{f.num(d['ground_max_m'], 1)} {m}"))
    alt = tr.layout.photos["altitude_m"]
    if alt.size:
        lo, hi = float(alt.min()), float(alt.max())
        alts = f"{f.num(lo, 0)}–{f.num(hi, 0)}" if hi - lo > 0.5 else f.num(hi, 0)
        rows.append((f.label("terrain_facts_altitude"), f.label(
            "terrain_facts_altitude_value", mode=f.label(f"terrain_facts_mode_{tr.mode}"),
            alt=f"{alts} {m}")))
    if d["agl_min_m"] is not None:
        lo, hi = f.num(d["agl_min_m"], 0), f.num(d["agl_max_m"], 0)
        rows.append((f.label("terrain_facts_agl"), f.label(  # a photo only over a DEM
            "terrain_facts_agl_value", lo=lo, hi=hi, unit=m, photo=tr.worst_resolution_photo)
            if d["source"] == "dem" else f"{lo}–{hi} {m}"))
    if tr.max_height_m is not None:
        rows.append((f.label("terrain_facts_max"), f"{f.num(tr.max_height_m, 0)} {m}"
                     + (f" ({f.cname(tr.binding)})" if tr.binding else "")))
    return rows


@document_text()
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
    if view._html:  # already rendered from this view (the workbook numbers its works
        return view._html[0]  # by it, the PDF is made from it): the same document
    scan, uav, meta, spec = view.scan, view.uav, view.meta, view.spec
    f = _Fmt(view, Bibliography(view.locale, view.citations))
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
        uav_view["terrain_rows"] = _terrain_rows(spec, f)
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
        "control": _control_view(view, f) if spec is not None and getattr(
            spec, "control", None) is not None else None,
        "geo": _geo_views(spec, uav, meta.locale),
        "warnings_box": _warnings_box(scan_view, uav_view, spec, f),
        "references": f.bib.entries(),
    }
    view._html.append(_environment().get_template("report.html").render(**ctx))
    return view._html[0]


def _control_view(view: ReportView, f: Any) -> dict[str, Any]:
    """The control section (``templates/_control.html``): the rows of the control tables,
    worded once (:mod:`scanplan.reports.controlwords`), their sources cited."""
    from .controlwords import check_rows, rule_rows, summary_rows

    loc = view.locale
    return {"summary": summary_rows(view.tables, loc),
            "checks": [(*r[:5], f.cite(r[5])) for r in check_rows(view.tables, loc)],
            "rules": [(*r[:3], f.cite(r[3])) for r in rule_rows(view.tables, loc)]}


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
                  f: _Fmt) -> dict[str, list[str]]:
    """Page 1's boxes in short form (an approver sees them before signing): ``warnings``,
    what to act on, apart from ``notes``, information and conditions checked. One line per
    kind, with all the photo scales it concerns (as the workbook's box lists them); a
    warning of the specification alone says which section explains it."""
    scales: dict[tuple[str, str], list[str]] = {}  # (severity, heading) → photo scales
    times: dict[tuple[str, str], int] = {}  # … → warnings without a photo scale under it
    for view in (scan_view, uav_view):
        for w in view["warnings"] if view is not None else ():
            head = (w["severity"], w["heading"] or w["message"])
            listed = scales.setdefault(head, [])
            listed += [x for x in w["scale_list"] if x not in listed]
            times[head] = times.get(head, 0) + (not w["scale_list"])
    items = [(sev, h + (f": {f.list_sep.join(xs)}" if xs else ""))
             for (sev, h), xs in scales.items()
             for _ in range(1 if xs else max(times[(sev, h)], 1))]
    if spec is not None:  # the specification's own (the view's warnings table)
        items += [(r.fields["severity"], _spec_item(r, spec, f))
                  for r in f.view.tables["warnings"].rows if r.fields["section"] == "spec"]
    out: dict[str, list[str]] = {"warnings": [], "notes": []}
    for sev in ("warning", "info"):
        counts: dict[str, int] = {}
        for s, item in items:
            if (s == "info") == (sev == "info"):
                counts[item] = counts.get(item, 0) + 1
        out["notes" if sev == "info" else "warnings"] = [
            f"{k} (×{n})" if n > 1 else k for k, n in counts.items()]
    return out


def _spec_item(r: Row, spec: PlanResult, f: _Fmt) -> str:
    """A warning of the specification alone (no section lists it; a row of the warnings
    table) on page 1: its heading and the section that explains it — the specification's
    reasons or the survey design's notes — or, when neither does, its whole sentence."""
    key = warning_heading_key(r.key)
    message = r.values[0]
    reasons = [getattr(x, "reason", None) for x in (spec.uav, spec.film) if x is not None]
    design = getattr(spec, "design", None)
    if key and message in reasons:
        return f.label("box_see", item=f.label(key), section=f.label("spec_title"))
    if key and design is not None and any(x.code == r.key for x in design.warnings):
        return f.label("box_see", item=f.label(key), section=f.label("design_title"))
    return localize(message, f.locale)


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
