"""The PDF report as HTML: the jinja2 templates of ``templates/`` filled from a result's view.

:func:`render_html` is everything of the report but the rendering to PDF
(:mod:`.pdfrender`, WeasyPrint); it imports no WeasyPrint, so the process that plans can
write the HTML while another imports the renderer (:mod:`.pdfworker`). Templates are
autoescaped, so user text (project, customer, ...) is always shown as text.
"""

from __future__ import annotations

import functools
import hashlib
import os
import re
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import jinja2
from markupsafe import Markup, escape

from .._version import __version__
from ..i18n.messages import document_text, localize
from ..project.jobs import ScanJob, UavJob
from . import ReportMeta, templates_dir
from .formatter import Formatter
from .pdf_sections import (
    _comparison_view,
    _design_view,
    _scan_view,
    _spec_view,
    _uav_view,
)
from .view import ReportView, build_view, svg_data_uri, warning_heading_key
from .views import Row
from .wording import document_date

if TYPE_CHECKING:
    from ..project.spec import PlanResult

__all__ = ["PDF_SECTIONS", "PdfSection", "render_html"]

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


_SUBSCRIPT = re.compile(r"(?<![\w])([A-Za-zσΔ]{1,3})_([A-Za-z0-9]{1,5})(?![\w])")


def typeset(value: Any) -> Markup:
    """A formula as a printed instruction shows it: ``P_S = V_s·Mk/(k·Mc)`` with its
    subscripts set as subscripts (``P<sub>S</sub>``; a symbol of up to three letters:
    ``GSD_max`` → ``GSD<sub>max</sub>``) and ``sqrt(`` as a root sign; the rest escaped.
    The ``formula`` filter of the templates.

    >>> str(typeset("GSD = p·H/f ≤ GSD_max(Mk), k_R < 1"))
    'GSD = p·H/f ≤ GSD<sub>max</sub>(Mk), k<sub>R</sub> &lt; 1'
    """
    text = str(escape(_breakable(value)))
    text = text.replace("sqrt(", "√(")
    return Markup(_SUBSCRIPT.sub(r"\1<sub>\2</sub>", text))


class _KeptTemplates(jinja2.FileSystemBytecodeCache):
    """Compiled templates kept between processes in the user's cache folder (jinja2 checks
    each against its template's source; a new Python or jinja2 is another folder): a
    fresh ``scanplan plan`` writes its HTML without compiling the templates again. A folder
    that cannot be made or written, or a damaged file, is compiled again, never an error."""

    def load_bytecode(self, bucket: jinja2.bccache.Bucket) -> None:
        try:
            super().load_bytecode(bucket)
        except Exception:  # damaged or unreadable: compiled as without it
            bucket.reset()

    def dump_bytecode(self, bucket: jinja2.bccache.Bucket) -> None:
        try:
            os.makedirs(self.directory, exist_ok=True)
            super().dump_bytecode(bucket)
        except OSError:
            pass  # nothing kept: the next process compiles them again


def _kept_templates() -> _KeptTemplates | None:
    """The cache of compiled templates: ``templates`` in the user's cache folder
    (:func:`scanplan.io.files.user_cache_dir`), one folder per Python, jinja2 and this
    module's text (which sets how templates compile); None when no cache folder can be
    named."""
    from ..io.files import user_cache_dir

    try:
        here = hashlib.sha256(Path(__file__).read_bytes())
        here.update(f"{sys.version}|{jinja2.__version__}".encode())
        root = user_cache_dir()
    except (OSError, RuntimeError, KeyError):
        return None
    return _KeptTemplates(str(root / "templates" / here.hexdigest()[:16]))


@functools.lru_cache(maxsize=1)
def _environment() -> jinja2.Environment:
    """The templates' environment (one per process: templates are compiled once, and kept
    compiled between processes by :class:`_KeptTemplates`)."""
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(templates_dir())), bytecode_cache=_kept_templates(),
        autoescape=jinja2.select_autoescape(["html", "htm", "xml"], default=True,
                                            default_for_string=True),
        undefined=jinja2.StrictUndefined, trim_blocks=True, lstrip_blocks=True,
        keep_trailing_newline=True, finalize=_breakable)
    env.filters["formula"] = typeset
    return env


def _terrain_plot(spec: Any, view: ReportView, f: Formatter) -> str | None:
    """The heights-above-ground figure of a ``[terrain]`` plan, else None."""
    tr = getattr(getattr(spec, "uav", None), "terrain", None)
    if tr is None or len(tr.layout.photos) == 0 or tr.summary()["source"] != "dem":
        return None  # a ground range without a DEM: flat ground under every photo, not drawn
    from . import plots

    top = {r.key: r.value for r in view.tables["uav_figures"].rows}.get("max_height_m")
    return svg_data_uri(plots.terrain_svg(tr, top, f.locale))


def _terrain_rows(spec: Any, f: Formatter) -> list[tuple[str, str]]:
    """What the crew and the approver need of the relief, in words: the DEM (file, CRS,
    cell size) or the ground range given, the ground under the photos, the flight altitude
    above sea level, the heights above ground and the highest height over the relief."""
    tr = getattr(getattr(spec, "uav", None), "terrain", None)
    if tr is None:
        return []
    d = tr.summary()
    m = f("m")
    rows = []
    if d["source"] == "dem":
        cell = d.get("dem_cell_size") or [None, None]
        size = (f"{f.g(cell[0] * 3600.0)}″" if d.get("dem_geographic")
                else f"{f.g(abs(cell[0]))} {m}")
        rows.append((f("terrain_facts_dem"), f(
            "terrain_facts_dem_value", file=d["dem"], crs=d["dem_crs"], cell=size)))
    else:  # and no chart of flat ground along the strips: the note says why
        rows.append((f("terrain_facts_dem"), f("terrain_facts_range") + ". "
                     + f("terrain_facts_no_chart")))
    rows.append((f("terrain_facts_ground"),
                 f"{f.num(d['ground_min_m'], 1)}–{f.num(d['ground_max_m'], 1)} {m}"))
    alt = tr.layout.photos["altitude_m"]
    if alt.size:
        lo, hi = float(alt.min()), float(alt.max())
        alts = f"{f.num(lo, 0)}–{f.num(hi, 0)}" if hi - lo > 0.5 else f.num(hi, 0)
        rows.append((f("terrain_facts_altitude"), f(
            "terrain_facts_altitude_value", mode=f(f"terrain_facts_mode_{tr.mode}"),
            alt=f"{alts} {m}")))
    if d["agl_min_m"] is not None:
        lo, hi = f.num(d["agl_min_m"], 0), f.num(d["agl_max_m"], 0)
        rows.append((f("terrain_facts_agl"), f(  # a photo only over a DEM
            "terrain_facts_agl_value", lo=lo, hi=hi, unit=m, photo=tr.worst_resolution_photo)
            if d["source"] == "dem" else f"{lo}–{hi} {m}"))
    if tr.max_height_m is not None:
        rows.append((f("terrain_facts_max"), f"{f.num(tr.max_height_m, 0)} {m}"
                     + (f" ({f.constraint(tr.binding)})" if tr.binding else "")))
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
    f = view.document_fmt()
    now = view.when
    date = document_date(meta.date or now.date(), meta.locale)
    if scan is not None and uav is not None:
        title = f("title_plan")
    elif scan is not None:
        title = f("title_scan")
    else:
        title = f("title_uav")
    if meta.locale == "ru":  # «Лист 2 / Листов 4»
        footer = (f"{_css_string(f('sheet') + ' ')} counter(page) "
                  f"{_css_string(' / ' + f('sheets_of') + ' ')} counter(pages)")
    else:  # "Sheet 2 of 4"
        footer = (f"{_css_string(f('sheet') + ' ')} counter(page) "
                  f"{_css_string(' ' + f('sheets_of') + ' ')} counter(pages)")
    built = {}
    for section in sorted(PDF_SECTIONS, key=lambda x: x.rank):  # works cited in this order
        built[section.name] = section.build(view, f)
    ctx = {
        "lang": meta.locale, "title": title, "meta": meta, "date": date,
        "running_project": _shorten(" ".join(meta.project.split()), _RUNNING_HEADER_CHARS),
        "created": now.strftime("%Y-%m-%dT%H:%M:%SZ"),
        "generator": f"scanplan {__version__}",
        "footer_css": Markup(f"@page {{ @bottom-center {{ content: {footer}; }} }}"),
        "L": _Labels(f),
        **built,
        "sections": [s for s in PDF_SECTIONS if built[s.name]],
        "warnings_box": _warnings_box(built.get("scan"), built.get("uav"), spec, view, f),
        "references": f.references(),
    }
    view._html.append(_environment().get_template("report.html").render(**ctx))
    return view._html[0]


def _scan_section(view: ReportView, f: Formatter) -> dict[str, Any] | None:
    return _scan_view(view.scan, view, f) if view.scan is not None else None


def _uav_section(view: ReportView, f: Formatter) -> dict[str, Any] | None:
    if view.uav is None:
        return None
    out = _uav_view(view.uav, view, f)
    out["plot_terrain"] = _terrain_plot(view.spec, view, f)
    out["terrain_rows"] = _terrain_rows(view.spec, f)
    return out


def _spec_section(view: ReportView, f: Formatter) -> dict[str, Any] | None:
    return _spec_view(view.spec, view, f) if view.spec is not None else None


def _plans_section(view: ReportView, f: Formatter) -> dict[str, Any] | None:
    """The plans compared (the ``plans`` table, words of :mod:`.planwords`), or None."""
    if view.spec is None or not view.tables.has("plans") or not view.tables["plans"].rows:
        return None
    from .planwords import plan_cells, plan_head

    choice = getattr(view.spec.uav, "choice", None)
    return {"title": f("plans_title"), "note": f("plans_note"),
            "choice": f.message(choice) if choice is not None else "",
            "head": plan_head(f),
            "rows": [{"cells": plan_cells(r, f), "css": " ".join(sorted(r.flags))}
                     for r in view.tables["plans"].rows]}


def _comparison_section(view: ReportView, f: Formatter) -> dict[str, Any] | None:
    """Film and digital camera side by side — not with a specification, which shows its
    own comparison."""
    if view.scan is None or view.uav is None or (view.spec is not None
                                                 and view.spec.comparison):
        return None
    return _comparison_view(view, f)


def _control_section(view: ReportView, f: Formatter) -> dict[str, Any] | None:
    """The ground control (``templates/_control.html``): the rows of the control tables,
    worded once (:mod:`scanplan.reports.controlwords`), their sources cited."""
    if view.spec is None or getattr(view.spec, "control", None) is None:
        return None
    from .controlwords import check_rows, rule_rows, summary_rows

    return {"summary": summary_rows(view.tables, f),
            "checks": [(*r[:5], f.cite(r[5])) for r in check_rows(view.tables, f)],
            "rules": [(*r[:3], f.cite(r[3])) for r in rule_rows(view.tables, f)]}


def _geo_section(view: ReportView, f: Formatter) -> list[dict[str, Any]]:
    return _geo_views(view.spec, view.uav, f.locale)


@dataclass(frozen=True)
class PdfSection:
    """One section of the PDF.

    Attributes
    ----------
    name : str
        The name its template reads its dictionary under.
    build : callable
        ``build(view, f) -> dict | list | None``: the section's words and numbers (from
        the view's tables, with the document's formatter ``f``); None or empty: the
        document has no such section.
    template : str
        Its template in ``templates/`` (``_spec.html``).
    rank : int
        When it is built: works are numbered in the order they are first cited, so a
        section's citations are numbered after those of the sections of a lower rank. A
        new section keeps the default: after the others.
    """

    name: str
    build: Callable[[ReportView, Formatter], Any]
    template: str
    rank: int = 100


#: The PDF's sections in the order of the document (``report.html`` includes each
#: present one's template after page 1's boxes).
PDF_SECTIONS: tuple[PdfSection, ...] = (
    PdfSection("spec", _spec_section, "_spec.html", rank=2),
    PdfSection("plans", _plans_section, "_plans.html", rank=2),
    PdfSection("design", lambda v, f: _design_view(v, f) if v.spec is not None else None,
               "_design.html", rank=3),
    PdfSection("control", _control_section, "_control.html", rank=5),
    PdfSection("scan", _scan_section, "_scan.html", rank=0),
    PdfSection("uav", _uav_section, "_uav.html", rank=1),
    PdfSection("comparison", _comparison_section, "_comparison.html", rank=4),
    PdfSection("geo", _geo_section, "_map.html", rank=6),
    PdfSection("symbols", lambda v, f: [(r.value, f(r.fields["meaning"]))
                                        for r in v.tables["symbols"].rows],
               "_symbols.html"),
)


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
                  view: ReportView, f: Formatter) -> dict[str, list[str]]:
    """Page 1's boxes in short form (an approver sees them before signing): ``warnings``,
    what to act on, apart from ``notes``, information and conditions checked. One line per
    kind, with all the photo scales it concerns (as the workbook's box lists them); a
    warning of the specification alone says which section explains it."""
    scales: dict[tuple[str, str], list[str]] = {}  # (severity, heading) → photo scales
    times: dict[tuple[str, str], int] = {}  # … → warnings without a photo scale under it
    for part in (scan_view, uav_view):
        for w in part["warnings"] if part is not None else ():
            head = (w["severity"], w["heading"] or w["message"])
            listed = scales.setdefault(head, [])
            listed += [x for x in w["scale_list"] if x not in listed]
            times[head] = times.get(head, 0) + (not w["scale_list"])
    items = [(sev, h + (f": {f.list_sep.join(xs)}" if xs else ""))
             for (sev, h), xs in scales.items()
             for _ in range(1 if xs else max(times[(sev, h)], 1))]
    if spec is not None:  # the specification's own (the view's warnings table)
        items += [(r.fields["severity"], _spec_item(r, spec, f))
                  for r in view.tables["warnings"].rows if r.fields["section"] == "spec"]
    out: dict[str, list[str]] = {"warnings": [], "notes": []}
    for sev in ("warning", "info"):
        counts: dict[str, int] = {}
        for s, item in items:
            if (s == "info") == (sev == "info"):
                counts[item] = counts.get(item, 0) + 1
        out["notes" if sev == "info" else "warnings"] = [
            f"{k} (×{n})" if n > 1 else k for k, n in counts.items()]
    return out


def _spec_item(r: Row, spec: PlanResult, f: Formatter) -> str:
    """A warning of the specification alone (no section lists it; a row of the warnings
    table) on page 1: its heading and the section that explains it — the specification's
    reasons or the survey design's notes — or, when neither does, its whole sentence."""
    key = warning_heading_key(r.key)
    message = r.values[0]
    reasons = [getattr(x, "reason", None) for x in (spec.uav, spec.film) if x is not None]
    design = getattr(spec, "design", None)
    if key and message in reasons:
        return f("box_see", item=f(key), section=f("spec_title"))
    if key and design is not None and any(x.code == r.key for x in design.warnings):
        return f("box_see", item=f(key), section=f("survey_design"))
    return localize(message, f.locale)


class _Labels:
    """``L.key`` / ``L('key', x=1)`` in templates: labels in the report's locale."""

    def __init__(self, f: Formatter) -> None:
        self._f = f

    def __getattr__(self, key: str) -> str:
        try:
            return self._f(key)
        except KeyError:
            raise AttributeError(key) from None

    def __call__(self, key: str, **kw: Any) -> str:
        return self._f(key, **kw)
