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
"""

from __future__ import annotations

import datetime as _dt
import io
import math
import os
import re
import zipfile
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from openpyxl import Workbook
from openpyxl.cell.cell import ILLEGAL_CHARACTERS_RE
from openpyxl.chart import Reference, ScatterChart, Series
from openpyxl.chart.axis import ChartLines
from openpyxl.chart.label import DataLabelList
from openpyxl.chart.shapes import GraphicalProperties
from openpyxl.styles import Alignment, Font, PatternFill
from openpyxl.utils import get_column_letter
from openpyxl.worksheet.pagebreak import Break
from openpyxl.worksheet.worksheet import Worksheet
from openpyxl.writer.excel import ExcelWriter

from .._version import __version__
from ..core import flight as FL
from ..core.mtf import component_label
from ..rules.film import CONSTRAINTS, height_formula_name
from . import ReportMeta, report_datetime, write_atomic
from .labels import LABELS, t
from .references import Bibliography
from .wording import (
    camera_title,
    display_message,
    document_date,
    name_title,
    object_title,
    param_name,
    param_value,
    scanner_title,
    shape_title,
)

if TYPE_CHECKING:
    from ..norms import NormSet
    from ..project.api import ScanJob, UavJob
    from ..project.spec import PlanResult
    from ..rules.film import PlanWarning
    from ..rules.uav import UavPlan

__all__ = ["render_xlsx", "write_xlsx"]

# Invariant number formats (Excel shows them with the user's decimal separator).
SCALE = '"1:"0'
INT = "#,##0"
F1 = "0.0"
F2 = "0.00"
F3 = "0.000"
F4 = "0.0000"
PCT = "0.0"
UM = "0.00"
MB = "#,##0.0"
M_LARGE = "#,##0.0"

MISSING = "—"
_DEFAULT_META = ReportMeta()
_ZIP_EPOCH = (1980, 1, 1, 0, 0, 0)
_MAX_CELL_TEXT = 32_767

_BOLD = Font(bold=True)
_TITLE = Font(bold=True, size=14)
_SECTION = Font(bold=True, size=12)
_HEADER_FILL = PatternFill("solid", fgColor="DDEBF7")
_BINDING_FILL = PatternFill("solid", fgColor="FFE699")
_WARNING_FILL = PatternFill("solid", fgColor="FCE4D6")
_WRAP = Alignment(wrap_text=True, vertical="top")
_FORMULA_START = re.compile(r"^[=+\-@\t\r]")


# ---------------------------------------------------------------------------------------
# Public API
# ---------------------------------------------------------------------------------------


def render_xlsx(
    *,
    scan: ScanJob | None = None,
    uav: UavJob | None = None,
    meta: ReportMeta = _DEFAULT_META,
    spec: PlanResult | None = None,
) -> bytes:
    """Render the Excel report of a scan plan, a UAV plan or both, in memory.

    Parameters
    ----------
    scan : ScanJob, optional
        A film scan plan and its norm set (:func:`scanplan.project.api.scan_job`).
    uav : UavJob, optional
        A UAV flight plan and its norm set (:func:`scanplan.project.api.uav_job`).
    meta : ReportMeta
        Title and approval blocks and the language (``meta.locale``: ``"en"``/``"ru"``).
    spec : PlanResult, optional
        The specification of ``scanplan plan`` (recommended photo scale / flight height,
        comparison); shown first on the Summary sheet.

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
    if scan is None and uav is None:
        raise ValueError("render_xlsx needs a scan plan, a UAV plan or both")
    when = report_datetime()
    book = _Book(meta, when)
    if uav is not None:
        book.platform = uav.plan.inputs.platform
    book.summary(scan, uav, spec)
    book.inputs(scan, uav)
    if scan is not None:
        book.constraints(scan)
        book.sweep(scan, spec)
    if uav is not None:
        book.uav(uav)
        book.mtf(uav)
    from .exports import view_of  # issue 11: the flight over the area

    if view_of(spec, uav) is not None:
        from .geosheets import add_geo_sheets

        add_geo_sheets(book, view_of(spec, uav))
    book.norms(scan, uav)
    book.warnings(scan, uav, spec)
    book.references()
    return book.to_bytes()


def write_xlsx(
    path: str | os.PathLike[str],
    *,
    scan: ScanJob | None = None,
    uav: UavJob | None = None,
    meta: ReportMeta = _DEFAULT_META,
    spec: PlanResult | None = None,
) -> Path:
    """Render the Excel report (:func:`render_xlsx`) and write it atomically to ``path``.

    Parameters
    ----------
    path : str or path
        The ``.xlsx`` to write; an existing file is replaced only by a complete report.
    scan, uav, meta
        As for :func:`render_xlsx`.

    Returns
    -------
    Path
        The written file.
    """
    data = render_xlsx(scan=scan, uav=uav, meta=meta, spec=spec)
    return write_atomic(path, data)


# ---------------------------------------------------------------------------------------
# Cell helpers
# ---------------------------------------------------------------------------------------


def _clean_text(value: object) -> str:
    """User or engine text as a string Excel accepts (no control characters, max length)."""
    text = ILLEGAL_CHARACTERS_RE.sub("", str(value))
    return text[:_MAX_CELL_TEXT]


def put_text(ws: Worksheet, row: int, col: int, value: object, *, bold: bool = False,
             wrap: bool = False) -> Any:
    """Write ``value`` as a string cell — never a formula, whatever it starts with."""
    text = _clean_text(value)
    cell = ws.cell(row=row, column=col)
    cell.value = text
    cell.data_type = "s"  # openpyxl would turn "=..." into a formula
    if _FORMULA_START.match(text):
        cell.quotePrefix = True  # and Excel keeps it text when the cell is edited
    if bold:
        cell.font = _BOLD
    if wrap:
        cell.alignment = _WRAP
    return cell


def _finite(value: object) -> float | None:
    if value is None or isinstance(value, bool):
        return None
    try:
        v = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


def put_num(ws: Worksheet, row: int, col: int, value: object, fmt: str, *,
            missing: str | None = MISSING) -> Any:
    """Write a number with an invariant number format (missing/non-finite → ``missing``)."""
    v = _finite(value)
    if v is None:
        if missing is None:
            return ws.cell(row=row, column=col)
        return put_text(ws, row, col, missing)
    cell = ws.cell(row=row, column=col)
    cell.value = int(v) if fmt in (SCALE, INT) and v.is_integer() else v
    cell.number_format = fmt
    return cell


def _mark(cells: Iterable[Any]) -> None:
    for cell in cells:
        cell.font = _BOLD
        cell.fill = _BINDING_FILL


def _header(ws: Worksheet, row: int, labels: Sequence[str], col: int = 1) -> None:
    for i, text in enumerate(labels):
        cell = put_text(ws, row, col + i, text, bold=True, wrap=True)
        cell.fill = _HEADER_FILL


def _widths(ws: Worksheet, widths: Sequence[float]) -> None:
    for i, w in enumerate(widths, start=1):
        ws.column_dimensions[get_column_letter(i)].width = w


def _fmt_number(x: float, locale: str, digits: int = 1) -> str:
    text = f"{x:.{digits}f}"
    return text.replace(".", ",") if locale == "ru" else text


def _scale_text(x: float) -> str:
    return f"1:{x:.0f}"


# ---------------------------------------------------------------------------------------
# The workbook
# ---------------------------------------------------------------------------------------


class _Book:
    """One report workbook being filled sheet by sheet."""

    def __init__(self, meta: ReportMeta, when: _dt.datetime) -> None:
        self.meta = meta
        self.loc = meta.locale if meta.locale in ("en", "ru") else "en"
        self.platform = "uav"  # "aircraft": the digital-camera sheets name an aerial survey
        self.when = when
        self.wb = Workbook()
        self._first = True
        self.title_text = ""
        self.bib = Bibliography(self.loc)

    # -- helpers ------------------------------------------------------------------------

    def t(self, key: str) -> str:
        return t(key, self.loc, self.platform)

    def text(self, value: object, ns: NormSet | None = None) -> str:
        """An engine sentence (a :class:`~scanplan.messages.Message`) in the report's
        language, ids shown by their names and the works it names by reference numbers."""
        return self.bib.cite(display_message(value, ns, self.loc))

    def yes_no(self, value: bool) -> str:
        return self.t("xlsx_yes" if value else "xlsx_no")

    def _height_rows(self, ws: Worksheet, row: int, plan: UavPlan) -> int:
        """Highest flown height at the maximum, the ceiling, and the height accuracy."""
        row = self.kv(ws, row, self.t("max_flown_height_m"), plan.max_flown_height_m, F1)
        if plan.ceiling_m is not None:
            row = self.kv(ws, row, self.t("ceiling_m"), plan.ceiling_m, F1)
        if plan.constraints_max_height_m is not None:
            row = self.kv(ws, row, self.t("constraints_max_height_m"),
                          plan.constraints_max_height_m, F1)
        acc = plan.height_accuracy
        if acc:
            row = self.kv(ws, row, self.t("height_accuracy_m"), acc["height_accuracy_m"], F4)
            row = self.kv(ws, row, self.t("sigma_z_m"),
                          acc["sigma_z_at_highest_flown_height_m"], F4)
            row = self.kv(ws, row, self.t("stereo_base_to_height"),
                          acc["stereo_base_to_height"], "0.000")
            row = self.kv(ws, row, self.t("image_measurement_px"),
                          acc["image_measurement_px"], F2)
            for form in ("normal_case", "instruction", "parallax"):
                row = self.kv(ws, row, f"{self.t('height_forms')}: {self.t('hf_' + form)}",
                              acc["forms"][form]["max_planned_height_m"], F1)
        return row

    def cname(self, cid: str) -> str:
        """A constraint id with its localised name: ``PZ — height accuracy``."""
        try:
            return f"{cid} — {self.t(cid)}"
        except KeyError:
            return cid

    def obj_name(self, ns: NormSet, name: str, map_scale: int | None) -> str:
        """A norm object's name in the report's language (unnamed: "object of the given
        size")."""
        from ..project.api import USER_OBJECT_NAME

        if map_scale is None and name == USER_OBJECT_NAME["en"]:  # a project's unnamed object
            return name_title("", "", self.loc)
        for obj in ns.objects:
            if obj.name == name and (map_scale is None or obj.map_scale == map_scale):
                return object_title(obj, self.loc)
        return name_title(name, "", self.loc)

    def shape_name(self, ns: NormSet, shape: str) -> str:
        """A shape in words in the report's language."""
        return shape_title(ns, shape, self.loc)

    def sheet(self, key: str, *, landscape: bool, widths: Sequence[float],
              header_rows: int = 1) -> Worksheet:
        """A new sheet with A4 page setup, print titles and a frozen header."""
        if self._first:
            ws = self.wb.active
            ws.title = self.t(key)
            self._first = False
        else:
            ws = self.wb.create_sheet(self.t(key))
        ws.page_setup.paperSize = ws.PAPERSIZE_A4
        ws.page_setup.orientation = "landscape" if landscape else "portrait"
        ws.page_setup.fitToWidth = 1
        ws.page_setup.fitToHeight = 0
        ws.sheet_properties.pageSetUpPr.fitToPage = True
        ws.page_margins.left = ws.page_margins.right = 0.5
        ws.page_margins.top = ws.page_margins.bottom = 0.6
        ws.print_title_rows = f"1:{header_rows}"
        ws.freeze_panes = f"A{header_rows + 1}"
        sep = " / " if self.loc == "ru" else " "
        ws.oddFooter.center.text = f"{self.t('sheet')} &P{sep}{self.t('sheets_of')} &N"
        ws.oddFooter.right.text = "&A"
        _widths(ws, widths)
        return ws

    def kv(self, ws: Worksheet, row: int, label: str, value: object, fmt: str | None = None,
           *, wrap: bool = False) -> int:
        """One ``label | value`` row; returns the next row."""
        put_text(ws, row, 1, label, wrap=True)
        if isinstance(value, bool):
            put_text(ws, row, 2, self.yes_no(value))
        elif fmt is not None:
            put_num(ws, row, 2, value, fmt)
        elif value is None or value == "":
            put_text(ws, row, 2, MISSING)
        else:
            put_text(ws, row, 2, value, wrap=wrap)
        return row + 1

    def _wide_kv(self, ws: Worksheet, row: int, label: str, text: str) -> int:
        """A ``label | long text`` row whose text spans the sheet's columns B…J (merged),
        so a paragraph reads as a paragraph, not a narrow column."""
        put_text(ws, row, 1, label, wrap=True)
        put_text(ws, row, 2, text, wrap=True)
        ws.merge_cells(start_row=row, start_column=2, end_row=row, end_column=10)
        return row + 1

    def kv_list(self, ws: Worksheet, row: int, label: str, values: Sequence[float],
                fmt: str) -> int:
        """``label | v1 | v2 | ...`` (several numbers, each in its own cell)."""
        put_text(ws, row, 1, label, wrap=True)
        if not values:
            put_text(ws, row, 2, MISSING)
        for i, v in enumerate(values):
            put_num(ws, row, 2 + i, v, fmt)
        return row + 1

    def section(self, ws: Worksheet, row: int, text: str) -> int:
        cell = put_text(ws, row, 1, text)
        cell.font = _SECTION
        return row + 1

    def to_bytes(self) -> bytes:
        """Save to memory with fixed timestamps; re-pack the zip deterministically."""
        naive = self.when.astimezone(_dt.UTC).replace(tzinfo=None)
        props = self.wb.properties
        props.created = naive
        props.modified = naive
        props.creator = f"scanplan {__version__}"
        props.lastModifiedBy = None
        props.language = "ru-RU" if self.loc == "ru" else "en-US"
        props.title = _clean_text(self.title_text)[:255]
        if self.meta.project:
            props.subject = _clean_text(self.meta.project)[:255]
        for ws in self.wb.worksheets:
            _fit_rows(ws)
        raw = io.BytesIO()
        # ExcelWriter, not Workbook.save: save() stamps `modified` with the current time.
        archive = zipfile.ZipFile(raw, "w", zipfile.ZIP_DEFLATED, allowZip64=True)
        ExcelWriter(self.wb, archive).save()
        return _repack(raw.getvalue(), self.when)

    # -- Summary ------------------------------------------------------------------------

    def summary(self, scan: ScanJob | None, uav: UavJob | None,
                spec: PlanResult | None = None) -> None:
        ws = self.sheet("xlsx_sheet_summary", landscape=True,
                        widths=(34, 16, 26, 14, 14, 14, 14, 14, 14, 70))
        titles = ([self.t("title_scan")] if scan else []) + ([self.t("title_uav")] if uav else [])
        self.title_text = "; ".join(titles)
        put_text(ws, 1, 1, self.title_text).font = _TITLE
        m = self.meta
        row = 3
        block = [("project", m.project), ("customer", m.customer), ("contractor", m.contractor)]
        block += [(k, v) for k, v in (("organisation", m.organisation),
                                      ("contract_number", m.contract_number)) if v]
        block.append(("date", document_date(m.date or self.when.date(), self.loc)))
        for key, value in block:
            put_text(ws, row, 1, self.t(key), bold=True)
            put_text(ws, row, 2, value)  # one line, running over the empty cells beside it
            row += 1
        line = "________________"
        blocks = [("approved", m.approver_position + (f", {m.organisation}"
                                                     if m.organisation else ""),
                   m.approver_name)]
        if m.agreed_position or m.agreed_name or m.agreed_organisation:
            blocks.append(("agreed", m.agreed_position + (f", {m.agreed_organisation}"
                                                         if m.agreed_organisation else ""),
                           m.agreed_name))
        for head, position, name in blocks:
            row += 1
            put_text(ws, row, 1, self.t(head)).font = _SECTION
            row += 1
            for key, value in (("position", position), ("name", name),
                               ("signature", line), ("date", line)):
                put_text(ws, row, 1, self.t(key), bold=True)
                put_text(ws, row, 2, value)
                row += 1
        row += 1
        for key, value in (("compiled_by", m.compiled_by), ("checked_by", m.checked_by)):
            put_text(ws, row, 1, self.t(key), bold=True)
            put_text(ws, row, 2, value or line)
            put_text(ws, row, 3, line)
            row += 1
        box = self._warning_lines(scan, uav, spec)
        if box:
            row = self.section(ws, row + 1, self.t("warnings_box"))
            for text in box:
                put_text(ws, row, 1, text, wrap=False).fill = _WARNING_FILL
                row += 1
        if spec is not None:
            row = self._summary_spec(ws, row + 1, spec)
        if scan is not None:
            row = self._summary_scan(ws, row + 1, scan)
        if uav is not None:
            row = self._summary_uav(ws, row + 1, uav)

    def _summary_spec(self, ws: Worksheet, row: int, spec: PlanResult) -> int:
        """The specification of ``scanplan plan``: what was chosen and why."""
        row = self.section(ws, row, self.t("spec_title"))
        if spec.film is not None:
            f, rec = spec.film, spec.film.recommended
            if rec is not None:
                key = ("spec_archive_photo_scale" if f.archive
                       else "spec_recommended_photo_scale")
                row = self.kv(ws, row, self.t(key), rec.photo_scale, '"1:"0')
                row = self.kv(ws, row, self.t("scan_pixel_um"), rec.scan_pixel_um, "0.0")
                if rec.scanner_pixel_um is not None:
                    row = self.kv(ws, row, self.t("scanner_pixel_um"), rec.scanner_pixel_um,
                                  "0.0")
                row = self.kv(ws, row, self.t("binding"),
                              self.cname(rec.binding))
                row = self.kv(ws, row, self.t("probability"), rec.recognition_probability,
                              "0.00")
                row = self.kv(ws, row, self.t("frame_megabytes"), rec.frame_megabytes, "#,##0")
                if f.frames is not None:
                    row = self.kv(ws, row, self.t("spec_frames"), f.frames, "#,##0")
                    row = self.kv(ws, row, self.t("spec_scanned_gb"), f.scanned_gigabytes,
                                  "#,##0.0")
            row = self._wide_kv(ws, row, self.t("spec_reason"),
                                self.text(f.reason, f.job.norm_set))
        if spec.uav is not None:
            u, p = spec.uav, spec.uav.job.plan
            if u.planned_height_m is not None:
                row = self.kv(ws, row, self.t("spec_planned_height_m"), u.planned_height_m,
                              "0")
            row = self.kv(ws, row, self.t("spec_recommended_height_m"),
                          u.recommended_height_m, "0")
            row = self.kv(ws, row, self.t("max_height_m"), u.max_height_m, "0")
            if p.max_flown_height_m is not None:
                row = self.kv(ws, row, self.t("max_flown_height_m"), p.max_flown_height_m, "0")
            if p.binding:
                row = self.kv(ws, row, self.t("binding"),
                              self.cname(p.binding))
            if "photos" in p.flight:
                row = self.kv(ws, row, self.t("spec_photos"), p.flight["photos"], "#,##0")
            if "data_volume_bytes" in p.flight:
                row = self.kv(ws, row, self.t("spec_data_gb"),
                              p.flight["data_volume_bytes"] / 1e9, "#,##0.0")
                row = self.kv(ws, row, self.t("data_volume_jpeg_gb"), float(
                    FL.jpeg_volume_bytes(p.flight["data_volume_bytes"])) / 1e9, "#,##0.0")
            row = self._wide_kv(ws, row, self.t("spec_reason"),
                                self.text(u.reason, u.job.norm_set))
        if spec.comparison:
            row = self.section(ws, row + 1, self.t("spec_comparison"))
            _header(ws, row, [self.t("spec_quantity"), self.t("spec_film"), self.t("spec_uav"),
                              self.t("unit")])
            row += 1
            for c in spec.comparison:
                key = f"spec_cmp_{c.get('key', '')}"
                put_text(ws, row, 1, self.t(key) if key in LABELS["en"] else c["quantity"])
                for col, key in ((2, "film"), (3, "uav")):
                    value = c[key]
                    if isinstance(value, int | float):
                        put_num(ws, row, col, value, "#,##0.000" if isinstance(value, float)
                                else "#,##0")
                    else:
                        put_text(ws, row, col, MISSING)
                unit = {"m": "pdf_m", "GB": "pdf_gb"}.get(c["unit"])
                put_text(ws, row, 4, self.t(unit) if unit else c["unit"])
                row += 1
        return row

    def _summary_scan(self, ws: Worksheet, row: int, job: ScanJob) -> int:
        plan = job.plan
        row = self.section(ws, row, f"{self.t('results')}: {self.t('xlsx_section_scan')}")
        _header(ws, row, [self.t("photo_scale"), self.t("photo_to_map"), self.t("binding"),
                          self.t("scan_pixel_um"), self.t("scanner_pixel_um"),
                          self.t("frame_megabytes"), self.t("xlsx_resolution_on_ground_mm"),
                          self.t("xlsx_required_r_lpmm"), self.t("probability"),
                          self.t("xlsx_explanation")])
        row += 1
        for s in plan.scenarios:
            put_num(ws, row, 1, s.photo_scale, SCALE)
            put_num(ws, row, 2, s.photo_to_map_ratio, F2)
            binding = put_text(ws, row, 3, self.cname(s.binding))
            pixel = put_num(ws, row, 4, s.scan_pixel_um, UM)
            _mark((binding, pixel))
            put_num(ws, row, 5, s.scanner_pixel_um, UM)
            put_num(ws, row, 6, s.frame_megabytes, MB)
            put_num(ws, row, 7, s.resolution_on_ground_mm, F1)
            put_num(ws, row, 8, s.required_resolving_power_lpmm, F1)
            put_num(ws, row, 9, s.recognition_probability, F3)
            put_text(ws, row, 10, self.text(s.explanation, job.norm_set), wrap=True)
            row += 1
        row += 1
        put_text(ws, row, 1, self.t("xlsx_interpretation_limit"), wrap=True)
        put_num(ws, row, 2, plan.interpretation_limit_photo_scale, SCALE)
        row += 1
        if plan.max_photo_scales:
            row = self.section(ws, row + 1, self.t("xlsx_reach"))
            both = plan.interpretation_limit_photo_scale is not None
            _header(ws, row, [self.t("pixel_um"), self.t("reach_pixel"), self.t("xlsx_limit")]
                    + ([self.t("reach_interpretable")] if both else []))
            row += 1
            for reach in plan.max_photo_scales:
                put_num(ws, row, 1, reach.pixel_um, UM)
                put_num(ws, row, 2, reach.max_photo_scale if reach.max_photo_scale > 0
                        else None, SCALE)
                put_text(ws, row, 3, self.cname(reach.limit))
                if both:
                    put_num(ws, row, 4, reach.max_photo_scale_interpretable or None, SCALE)
                row += 1
        return row

    def _summary_uav(self, ws: Worksheet, row: int, job: UavJob) -> int:
        plan = job.plan
        row = self.section(ws, row, f"{self.t('results')}: {self.t('xlsx_section_uav')}")
        _header(ws, row, [self.t("xlsx_parameter"), self.t("value")])
        row += 1
        row = self.kv(ws, row, self.t("height_m"), plan.heights_m.get("planned"), F1)
        row = self.kv(ws, row, self.t("gsd_m"), plan.gsd_m, F4)
        if plan.ground_resolution_m is None:
            row = self.kv(ws, row, self.t("ground_resolution_m"), self.t("not_resolvable"))
        else:
            row = self.kv(ws, row, self.t("ground_resolution_m"), plan.ground_resolution_m, F4)
        row = self.kv(ws, row, self.t("l_over_gsd"), plan.ground_resolution_to_gsd, F2)
        row = self.kv(ws, row, self.t("resolving_power_system"), plan.resolving_power_lpmm, F1)
        if plan.max_height_m is not None:
            r0 = row
            row = self.kv(ws, row, self.t("max_height_m"), plan.max_height_m, F1)
            row = self.kv(ws, row, self.t("binding"), self.cname(plan.binding or ""))
            _mark((ws.cell(r0, 2), ws.cell(r0 + 1, 2)))
        obj = plan.inputs.map_object
        if obj is not None:
            row = self.kv(ws, row, self.t("object"), object_title(obj, self.loc), wrap=True)
            for rec in plan.recognition:
                if rec.object == obj.name and rec.object_size_m == obj.size_m:
                    row = self.kv(ws, row, self.t("xlsx_p_planned"), rec.probability, F3)
                    row = self.kv(ws, row, self.t("xlsx_p_max"),
                                  rec.probability_at_max_height, F3)
                    break
        return row

    # -- Inputs -------------------------------------------------------------------------

    def inputs(self, scan: ScanJob | None, uav: UavJob | None) -> None:
        ws = self.sheet("xlsx_sheet_inputs", landscape=False, widths=(46, 16, 12, 12, 12, 12,
                                                                       12, 12))
        _header(ws, 1, [self.t("xlsx_parameter"), self.t("value")])
        row = 2
        if scan is not None:
            row = self._inputs_scan(ws, row, scan) + 1
        if uav is not None:
            row = self._inputs_uav(ws, row, uav)

    def _object_rows(self, ws: Worksheet, row: int, obj: Any, ns: NormSet) -> int:
        if obj is None:
            return self.kv(ws, row, self.t("object"), None)
        row = self.kv(ws, row, self.t("object"), object_title(obj, self.loc), wrap=True)
        row = self.kv(ws, row, self.t("xlsx_object_size_m"), obj.size_m, F3)
        row = self.kv(ws, row, self.t("xlsx_shape"), self.shape_name(ns, obj.shape))
        row = self.kv(ws, row, self.t("xlsx_shape_coefficient"), obj.shape_coefficient, F2)
        return self.kv(ws, row, self.t("xlsx_object_source"), self.text(obj.source),
                       wrap=True)

    def _inputs_scan(self, ws: Worksheet, row: int, job: ScanJob) -> int:
        inp, rules = job.plan.inputs, job.plan.rules
        row = self.section(ws, row, self.t("xlsx_section_scan"))
        row = self.kv(ws, row, self.t("map_scale"), inp.map_scale, SCALE)
        row = self.kv(ws, row, self.t("relief_interval_m"), inp.relief_interval_m, F2)
        row = self.kv_list(ws, row, self.t("photo_scale"), inp.photo_scales, SCALE)
        row = self.kv(ws, row, self.t("camera"),
                      camera_title(job.norm_set, inp.camera, self.loc) or None, wrap=True)
        row = self.kv(ws, row, self.t("focal_mm"), inp.focal_mm, F2)
        row = self.kv(ws, row, self.t("xlsx_frame_across_mm"), inp.frame_width_mm, F1)
        row = self.kv(ws, row, self.t("xlsx_frame_along_mm"), inp.frame_along_mm, F1)
        row = self.kv(ws, row, self.t("resolving_power_lpmm"), inp.resolving_power_lpmm, F1)
        row = self.kv(ws, row, self.t("forward_overlap_pct"), inp.forward_overlap_pct, F1)
        row = self._object_rows(ws, row, inp.object, job.norm_set)
        row = self.kv(ws, row, self.t("probability"), rules.probability, F3)
        row = self.kv(ws, row, self.t("xlsx_height_formula"),
                      self.text(height_formula_name(rules.height_formula)))
        row = self.kv(ws, row, self.t("xlsx_pr_coefficient"), rules.pr_coefficient, F2)
        row = self.kv(ws, row, self.t("scanner"),
                      scanner_title(job.norm_set, inp.scanner, self.loc) or None)
        if inp.scanner_steps_um:
            row = self.kv_list(ws, row, self.t("xlsx_scanner_steps_um"), inp.scanner_steps_um,
                               UM)
        if inp.candidate_pixels_um:
            row = self.kv_list(ws, row, self.t("xlsx_candidate_pixels_um"),
                               inp.candidate_pixels_um, UM)
        row = self.kv(ws, row, self.t("xlsx_bands"), inp.bands, INT)
        return self.kv(ws, row, self.t("xlsx_bits_per_band"), inp.bits_per_band, INT)

    def _inputs_uav(self, ws: Worksheet, row: int, job: UavJob) -> int:
        inp = job.plan.inputs
        row = self.section(ws, row, self.t("xlsx_section_uav"))
        rows: list[tuple[str, object, str | None]] = [
            ("camera", camera_title(job.norm_set, inp.camera, self.loc, inp.camera_name)
             or None, None),
            ("xlsx_pixel_pitch_um", inp.pixel_um, F2),
            ("focal_mm", inp.focal_mm, F2),
            ("xlsx_f_number", inp.f_number, F1),
            ("orientation", self.t(f"orientation_{inp.orientation}"), None),
            ("xlsx_sensor_width_mm", inp.sensor_width_mm, F2),
            ("xlsx_sensor_height_mm", inp.sensor_height_mm, F2),
            ("xlsx_image_width_px", inp.image_width_px, INT),
            ("xlsx_image_height_px", inp.image_height_px, INT),
            ("xlsx_min_trigger_interval_s", inp.min_trigger_interval_s, F3),
            ("height_m", inp.height_m, F1),
            ("xlsx_tolerance_up_pct", inp.height_tolerance_up_pct, F1),
            ("xlsx_tolerance_down_pct", inp.height_tolerance_down_pct, F1),
            ("xlsx_speed_ms", inp.speed_ms, F1),
            ("xlsx_exposure_s", inp.exposure_s, "0.00000"),
            ("forward_overlap_pct", inp.forward_overlap_pct, F1),
            ("side_overlap_pct", inp.side_overlap_pct, F1),
            ("xlsx_area_width_m", inp.area_width_m, M_LARGE),
            ("xlsx_area_length_m", inp.area_length_m, M_LARGE),
            ("map_scale", inp.map_scale, SCALE),
            ("relief_interval_m", inp.relief_interval_m, F2),
        ]
        for key, value, fmt in rows:
            row = self.kv(ws, row, self.t(key), value, fmt)
        row = self._object_rows(ws, row, inp.map_object, job.norm_set)
        for key, value, fmt in [
            ("xlsx_r_max", inp.r_max, F3), ("xlsx_r_min", inp.r_min, F3),
            ("xlsx_threshold_k0", inp.threshold_k0, F3),
            ("xlsx_haze_contrast", inp.haze_contrast, F3),
            ("xlsx_shift_factor", inp.shift_factor, F2),
            ("xlsx_random_speed_ms", inp.random_speed_ms, F2),
            ("xlsx_roll_rate_rad_s", inp.roll_rate_rad_s, F4),
            ("xlsx_pitch_rate_rad_s", inp.pitch_rate_rad_s, F4),
            ("xlsx_yaw_rate_rad_s", inp.yaw_rate_rad_s, F4),
            ("xlsx_roll_deg", inp.roll_deg, F2),
            ("xlsx_pitch_deg", inp.pitch_deg, F2),
            ("xlsx_bands", inp.bands, INT),
            ("xlsx_bits_per_band", inp.bits_per_band, INT),
        ]:
            row = self.kv(ws, row, self.t(key), value, fmt)
        return row

    # -- Constraints and Sweep (film) ---------------------------------------------------

    def constraints(self, job: ScanJob) -> None:
        ws = self.sheet("xlsx_sheet_constraints", landscape=True,
                        widths=(14, 9, 8, 34, 12, 12, 12, 12, 60, 60))
        _header(ws, 1, [self.t("photo_scale"), self.t("photo_to_map"), self.t("xlsx_id"),
                        self.t("constraint"), self.t("pixel_um"), self.t("xlsx_margin_um"),
                        self.t("margin_pct"), self.t("binding"), self.t("reason"),
                        self.t("xlsx_equation")])
        row = 2
        for s in job.plan.scenarios:
            for c in s.constraints:
                cells = [put_num(ws, row, 1, s.photo_scale, SCALE),
                         put_num(ws, row, 2, s.photo_to_map_ratio, F2),
                         put_text(ws, row, 3, c.id),
                         put_text(ws, row, 4, self.t(c.id) if c.id in CONSTRAINTS else c.name),
                         put_num(ws, row, 5, c.pixel_um, UM),
                         put_num(ws, row, 6, c.margin_um, UM),
                         put_num(ws, row, 7, c.margin_pct, PCT),
                         put_text(ws, row, 8, self.yes_no(c.binding))]
                put_text(ws, row, 9, self.text(c.reason), wrap=True)
                put_text(ws, row, 10, self.text(c.equation), wrap=True)
                if c.binding:
                    _mark(cells)
                row += 1
        if row > 2:
            ws.auto_filter.ref = f"A1:J{row - 1}"

    def sweep(self, job: ScanJob, spec: PlanResult | None = None) -> None:
        sweep = job.plan.sweep
        scales = list(sweep.get("photo_scale", []))
        ids = [cid for cid in job.plan.constraint_ids if cid in sweep]
        ws = self.sheet("xlsx_sheet_sweep", landscape=True,
                        widths=(14,) + (16,) * len(ids) + (16, 30))
        heads = [self.t("photo_scale")] + [f"{self.cname(cid)}, µm" if self.loc == "en"
                                           else f"{self.cname(cid)}, мкм" for cid in ids]
        _header(ws, 1, [*heads, self.t("scan_pixel_um"), self.t("binding")])
        n = len(scales)
        pixel_col = len(ids) + 2
        binding = list(sweep.get("binding", []))
        scan_px = list(sweep.get("scan_pixel_um", []))
        for i in range(n):
            row = i + 2
            put_num(ws, row, 1, scales[i], SCALE, missing=None)
            for j, cid in enumerate(ids):
                cell = put_num(ws, row, 2 + j, sweep[cid][i], UM, missing=None)
                if i < len(binding) and binding[i] == cid:
                    _mark((cell,))
            put_num(ws, row, pixel_col, scan_px[i] if i < len(scan_px) else None, UM,
                    missing=None)
            if i < len(binding):
                put_text(ws, row, pixel_col + 1, binding[i])
        if n == 0:
            return
        chart = _scatter(self.t("plot_constraints"), self.t("photo_scale"), self.t("pixel_um"))
        chart.x_axis.number_format = SCALE
        # a linear axis whose ticks fall on every candidate photo scale (a log axis would
        # label only 1:1000, 1:10000, ...)
        lo, hi, step = _scale_ticks([s.photo_scale for s in job.plan.scenarios],
                                    _finite(scales[0]) or 0.0, _finite(scales[-1]) or 1.0)
        chart.x_axis.scaling.min = lo
        chart.x_axis.scaling.max = hi
        chart.x_axis.majorUnit = step
        chart.x_axis.majorGridlines = ChartLines()
        chart.y_axis.number_format = "General"
        # pixels span a decade or more: a log axis shows the deciding (smallest) one clearly
        values = [v for cid in ids for v in (_finite(x) for x in sweep[cid]) if v]
        chart.y_axis.scaling.logBase = 10
        chart.y_axis.scaling.min = _log_floor(min(values, default=1.0))
        chart.y_axis.scaling.max = _log_ceil(max(values, default=100.0))
        chart.y_axis.majorGridlines = ChartLines()
        chart.y_axis.minorGridlines = ChartLines()
        xref = Reference(ws, min_col=1, min_row=2, max_row=n + 1)
        for j, cid in enumerate(ids):
            _add_series(chart, ws, xref, 2 + j, n, self.cname(cid))
        _add_series(chart, ws, xref, pixel_col, n, self.t("scan_pixel_um"), width_emu=44450,
                    dash="dash", color="000000")
        rec = spec.film.recommended if spec is not None and spec.film is not None else None
        self._candidate_markers(chart, ws, job, n + 3, rec.photo_scale if rec else None)
        _chart_below(ws, chart, n + 1 + 2 + len(job.plan.scenarios) + 2)

    def _candidate_markers(self, chart: ScatterChart, ws: Worksheet, job: ScanJob,
                           first_row: int, recommended: float | None) -> None:
        """One labelled point per candidate photo scale at its scan pixel: the chart names
        every candidate scale (a log axis labels only 1:1000, 1:10000, ...); the
        recommended one (the smallest feasible scale) stands out."""
        scen = job.plan.scenarios
        _header(ws, first_row, [self.t("photo_scale"), self.t("scan_pixel_um"),
                                self.t("binding")])
        for i, s in enumerate(scen):
            row = first_row + 1 + i
            put_num(ws, row, 1, s.photo_scale, SCALE)
            put_num(ws, row, 2, s.scan_pixel_um, UM)
            put_text(ws, row, 3, s.binding)
            label = f"1:{_group(s.photo_scale, self.loc)}"
            if s.photo_scale == recommended:
                label += " (" + self.t("xlsx_recommended") + ")"
            xref = Reference(ws, min_col=1, min_row=row, max_row=row)
            series = _add_series(chart, ws, xref, 2, 1, label, first_row=row)
            series.graphicalProperties.line.noFill = True
            series.marker.symbol = "diamond" if s.photo_scale == recommended else "circle"
            series.marker.size = 11 if s.photo_scale == recommended else 7
            color = "C00000" if s.photo_scale == recommended else "000000"
            series.marker.graphicalProperties = GraphicalProperties(solidFill=color)
            series.marker.graphicalProperties.line.solidFill = color
            series.dLbls = DataLabelList()
            series.dLbls.showSerName = True
            series.dLbls.showVal = False
            series.dLbls.showCatName = False
            series.dLbls.showLegendKey = False
            series.dLbls.position = "t"

    # -- UAV and MTF --------------------------------------------------------------------

    def uav(self, job: UavJob) -> None:
        plan = job.plan
        ws = self.sheet("xlsx_sheet_uav", landscape=True,
                        widths=(46, 16, 16, 16, 16, 16, 14, 12, 50, 50))
        _header(ws, 1, [self.t("xlsx_parameter"), self.t("value")])
        row = 2
        h = plan.heights_m
        lr = plan.ground_resolution_m
        for key, value, fmt in [
            ("height_m", h.get("planned"), F1),
            ("xlsx_height_min_m", h.get("min"), F1),
            ("xlsx_height_max_m", h.get("max"), F1),
            ("gsd_m", plan.gsd_m, F4),
            ("xlsx_gsd_at_max_m", plan.gsd_at_max_height_m, F4),
            ("ground_resolution_m", lr if lr is not None else self.t("not_resolvable"),
             F4 if lr is not None else None),
            ("xlsx_l_corner_m", plan.ground_resolution_corner_m, F4),
            ("xlsx_l_at_max_m", plan.ground_resolution_at_max_height_m, F4),
            ("l_over_gsd", plan.ground_resolution_to_gsd, F2),
            ("resolving_power_system", plan.resolving_power_lpmm, F1),
            ("xlsx_r_corner_lpmm", plan.resolving_power_corner_lpmm, F1),
            ("nyquist_lpmm", plan.nyquist_lpmm, F1),
            ("xlsx_resolvable", bool(plan.resolvable), None),
            ("xlsx_sensor_limited", bool(plan.sensor_limited), None),
            ("motion_blur_px", plan.motion_blur_px, F2),
            ("xlsx_max_exposure_s", plan.max_exposure_s, "0.00000"),
            ("xlsx_max_speed_ms", plan.max_speed_ms, F1),
            ("xlsx_tilted_corner_gsd_m", plan.tilted_corner_gsd_m, F4),
        ]:
            row = self.kv(ws, row, self.t(key), value, fmt)
        if plan.max_height_m is not None:
            r0 = row
            row = self.kv(ws, row, self.t("max_height_m"), plan.max_height_m, F1)
            row = self.kv(ws, row, self.t("binding"), self.cname(plan.binding or ""))
            _mark((ws.cell(r0, 2), ws.cell(r0 + 1, 2)))
            row = self._height_rows(ws, row, plan)
        if plan.limits:
            row = self.section(ws, row + 1, self.t("xlsx_height_limits"))
            _header(ws, row, [self.t("xlsx_id"), self.t("constraint"), self.t("xlsx_compares"),
                              self.t("xlsx_limit_m"), self.t("max_height_m"),
                              self.t("margin_pct"), self.t("binding"),
                              self.t("max_flown_height_m"), self.t("reason"),
                              self.t("xlsx_equation")])
            row += 1
            for lim in plan.limits:
                cells = [put_text(ws, row, 1, lim.id),
                         put_text(ws, row, 2, self.t(lim.id) if lim.id in CONSTRAINTS
                                  else lim.name),
                         put_text(ws, row, 3, lim.compares),
                         put_num(ws, row, 4, lim.limit_m, F4),
                         put_num(ws, row, 5, lim.max_height_m, F1),
                         put_num(ws, row, 6, lim.margin_pct, PCT),
                         put_text(ws, row, 7, self.yes_no(lim.binding)),
                         put_num(ws, row, 8, lim.max_flown_height_m, F1)]
                put_text(ws, row, 9, self.text(lim.reason), wrap=True)
                put_text(ws, row, 10, self.text(lim.equation), wrap=True)
                if lim.binding:
                    _mark(cells)
                row += 1
        if plan.recognition:
            row = self.section(ws, row + 1, self.t("xlsx_recognition"))
            _header(ws, row, [self.t("xlsx_object_name"), self.t("xlsx_object_size_m"),
                              self.t("xlsx_shape"), self.t("map_scale"),
                              self.t("xlsx_p_planned"), self.t("xlsx_p_max"),
                              self.t("xlsx_p_corner_max")])
            row += 1
            mobj = plan.inputs.map_object
            for rec in plan.recognition:
                cells = [put_text(ws, row, 1, self.obj_name(job.norm_set, rec.object,
                                                            rec.map_scale), wrap=True),
                         put_num(ws, row, 2, rec.object_size_m, F3),
                         put_text(ws, row, 3, self.shape_name(job.norm_set, rec.shape)),
                         put_num(ws, row, 4, rec.map_scale, SCALE),
                         put_num(ws, row, 5, rec.probability, F3),
                         put_num(ws, row, 6, rec.probability_at_max_height, F3),
                         put_num(ws, row, 7, rec.probability_corner_at_max_height, F3)]
                if (mobj is not None and rec.object == mobj.name
                        and rec.object_size_m == mobj.size_m
                        and rec.map_scale == mobj.map_scale):
                    _mark(cells)
                row += 1
        if plan.flight:
            row = self.section(ws, row + 1, self.t("xlsx_flight"))
            for key, value in plan.flight.items():
                try:
                    label = self.t(f"xlsx_flight_{key}")
                except KeyError:
                    label = key
                fmt = INT if (key.endswith("_bytes") or key in ("strips", "photos",
                                                                "photos_per_strip")) else F2
                row = self.kv(ws, row, label, value, fmt if not isinstance(value, str)
                              else None)
        curve = plan.height_curve
        heights = list(curve.get("height_m", []))
        if heights:
            row = self.section(ws, row + 1, self.t("plot_height"))
            _header(ws, row, [self.t("height_m"), self.t("gsd_m"), self.t("ground_resolution_m")])
            first = row + 1
            for i, hm in enumerate(heights):
                put_num(ws, first + i, 1, hm, F1, missing=None)
                put_num(ws, first + i, 2, curve["gsd_m"][i], F4, missing=None)
                put_num(ws, first + i, 3, curve["ground_resolution_m"][i], F4, missing=None)
            n = len(heights)
            chart = _scatter(self.t("plot_height"), self.t("height_m"), self.t("gsd_m") + "; L")
            chart.x_axis.scaling.min = 0
            chart.y_axis.scaling.min = 0
            chart.x_axis.majorGridlines = ChartLines()
            chart.x_axis.number_format = "0"
            chart.y_axis.number_format = "0.00"
            xref = Reference(ws, min_col=1, min_row=first, max_row=first + n - 1)
            _add_series(chart, ws, xref, 2, n, self.t("gsd_m"), first_row=first)
            _add_series(chart, ws, xref, 3, n, self.t("ground_resolution_m"), first_row=first)
            top = max((v for v in (_finite(x) for key in ("gsd_m", "ground_resolution_m")
                                   for x in curve[key]) if v is not None), default=1.0)
            end = self._height_markers(chart, ws, plan, first + n + 1, top,
                                       max(heights))
            _chart_below(ws, chart, end + 1)

    def _height_markers(self, chart: ScatterChart, ws: Worksheet, plan: Any, row: int,
                        top: float, right: float) -> int:
        """Vertical lines at the planned, highest flown and maximum heights and the binding
        ground limit as a horizontal line (two-point series, their cells below the curve).
        Returns the next free row."""
        h = plan.heights_m
        m = " м" if self.loc == "ru" else " m"
        marks: list[tuple[str, float, float, float, float, str, str]] = []
        if h.get("planned"):
            marks.append((f"{self.t('xlsx_planned')}: {_group(h['planned'], self.loc)}{m}",
                          h["planned"], 0.0, h["planned"], top, "000000", "solid"))
        if h.get("max") and h["max"] != h.get("planned"):
            marks.append((f"{self.t('xlsx_highest_flown')}: {_group(h['max'], self.loc)}{m}",
                          h["max"], 0.0, h["max"], top, "7F7F7F", "dash"))
        if plan.max_height_m is not None:
            marks.append((f"{self.t('max_height_m').split(',')[0]} ({plan.binding}): "
                          f"{_group(round(plan.max_height_m), self.loc)}{m}",
                          plan.max_height_m, 0.0, plan.max_height_m, top, "C00000", "sysDot"))
            ratio = h["max"] / h["planned"] if h.get("planned") and h.get("max") else 1.0
            if ratio > 1:  # where the binding limit is checked: the maximum flown high
                flown = plan.max_height_m * ratio
                marks.append((f"{self.t('xlsx_max_flown')}: {_group(flown, self.loc)}{m}",
                              flown, 0.0, flown, top, "C00000", "dash"))
        b = next((lim for lim in plan.limits if lim.binding), None)
        if b is not None and b.limit_m <= top * 1.5:
            marks.append((f"{b.compares} ≤ {_fmt_number(b.limit_m, self.loc, 3)}{m} "
                          f"({b.id})", 0.0, b.limit_m, right, b.limit_m, "C00000", "dashDot"))
        if not marks:
            return row
        _header(ws, row, [self.t("xlsx_marker"), "x", "y"])
        row += 1
        for label, x0, y0, x1, y1, color, dash in marks:
            put_text(ws, row, 1, label)
            put_num(ws, row, 2, x0, F1)
            put_num(ws, row, 3, y0, F4)
            put_num(ws, row + 1, 2, x1, F1)
            put_num(ws, row + 1, 3, y1, F4)
            xref = Reference(ws, min_col=2, min_row=row, max_row=row + 1)
            _add_series(chart, ws, xref, 3, 2, label, first_row=row, color=color,
                        dash=None if dash == "solid" else dash)
            row += 2
        return row

    def mtf(self, job: UavJob) -> None:
        plan = job.plan
        mc = plan.mtf_centre
        freq = list(mc.get("freq_lpmm", []))
        if not freq:
            return
        special = ("freq_lpmm", "system", "image_contrast", "threshold")
        comps = [k for k in mc if k not in special and isinstance(mc[k], list)]
        cols = comps + [k for k in ("system", "image_contrast", "threshold") if k in mc]
        heads = [self.t("frequency_lpmm")]
        for k in cols:
            if k == "image_contrast":
                heads.append(self.t("image_contrast"))
            elif k == "threshold":
                heads.append(self.t("threshold"))
            elif k == "system":
                heads.append(self.t("xlsx_mtf_system"))
            else:  # a registered MTF component names itself in both languages
                heads.append(component_label(k, self.loc))
        ncol = len(cols) + 1
        ws = self.sheet("xlsx_sheet_mtf", landscape=True,
                        widths=(14,) + (12,) * len(cols) + (3, 16, 12))
        _header(ws, 1, heads)
        n = len(freq)
        for i, f in enumerate(freq):
            put_num(ws, i + 2, 1, f, F2, missing=None)
            for j, k in enumerate(cols):
                put_num(ws, i + 2, 2 + j, mc[k][i], F4, missing=None)
        chart = _scatter(self.t("plot_mtf"), self.t("frequency_lpmm"), self.t("contrast"))
        chart.x_axis.scaling.min = 0
        # contrast and threshold meet low on the curve: a log axis shows the crossing
        low = [v for k in ("image_contrast", "threshold") if k in mc
               for v in (_finite(x) for x in mc[k]) if v is not None and v > 0]
        chart.y_axis.scaling.logBase = 10
        chart.y_axis.scaling.min = _log_floor(min(low, default=0.01))
        chart.y_axis.scaling.max = 1
        chart.y_axis.majorGridlines = ChartLines()
        chart.y_axis.minorGridlines = ChartLines()
        chart.y_axis.number_format = "General"
        chart.x_axis.number_format = "0"
        xref = Reference(ws, min_col=1, min_row=2, max_row=n + 1)
        for k in ("image_contrast", "threshold"):
            if k in cols:
                _add_series(chart, ws, xref, 2 + cols.index(k), n, heads[1 + cols.index(k)])
        r = plan.resolving_power_lpmm
        mcol = ncol + 2
        if r is not None and "image_contrast" in mc:
            # a two-point vertical series at R marks the crossing
            top = 1.0
            _header(ws, 1, [self.t("xlsx_r_marker"), self.t("contrast")], col=mcol)
            for i, yv in enumerate((chart.y_axis.scaling.min, top)):
                put_num(ws, 2 + i, mcol, r, F1)
                put_num(ws, 2 + i, mcol + 1, yv, F3)
            mref = Reference(ws, min_col=mcol, min_row=2, max_row=3)
            unit = "мм⁻¹" if self.loc == "ru" else "lines/mm"
            label = f"R = {_fmt_number(r, self.loc)} {unit}"
            _add_series(chart, ws, mref, mcol + 1, 2, label, dash="dash", color="C00000")
        _chart_below(ws, chart, n + 3)

    # -- Norms and Warnings -------------------------------------------------------------

    def norms(self, scan: ScanJob | None, uav: UavJob | None) -> None:
        used: list[tuple[NormSet, list[Any], str]] = []
        for job, obj, section in (
                (scan, scan.plan.inputs.object if scan else None, "xlsx_section_scan"),
                (uav, uav.plan.inputs.map_object if uav else None, "xlsx_section_uav")):
            if job is None:
                continue
            for ns, objs, _section in used:
                if ns.name == job.norm_set.name and ns.path == job.norm_set.path:
                    objs.append(obj)
                    break
            else:
                used.append((job.norm_set, [obj], section))
        ws = self.sheet("xlsx_sheet_norms", landscape=True,
                        widths=(46, 34, 44, 12, 24, 50))
        _header(ws, 1, [self.t("xlsx_parameter"), self.t("value"), self.t("source")])
        row = 2
        for ns, objs, _section in used:
            row = self._norm_set(ws, row, ns, [o for o in objs if o is not None]) + 1

    def _norm_set(self, ws: Worksheet, row: int, ns: NormSet, objs: list[Any]) -> int:
        title = ns.title_ru if self.loc == "ru" and ns.title_ru else ns.title
        row = self.section(ws, row, f"{self.t('norm_set')}: {title}")
        row = self.kv(ws, row, self.t("xlsx_norm_id"), f'[norms] set = "{ns.name}"')
        row = self.kv(ws, row, self.t("xlsx_title"), title, wrap=True)
        numbers = re.findall(r"\[\d+\]", self.bib.cite(ns.source))
        row = self.kv(ws, row, self.t("source"),
                      "; ".join(dict.fromkeys(numbers)) if numbers else ns.source, wrap=True)
        row = self.kv(ws, row, self.t("xlsx_bundled"), bool(ns.bundled))
        if not ns.bundled:  # a bundled set's folder depends on the installation
            row = self.kv(ws, row, self.t("xlsx_folder"), str(ns.path))
        if ns.imported_from:
            row = self.kv(ws, row, self.t("xlsx_imported_from"), ns.imported_from)
            row = self.kv(ws, row, self.t("xlsx_imported_at"), ns.imported_at)
        row = self.section(ws, row + 1, self.t("xlsx_parameters"))
        _header(ws, row, [self.t("xlsx_parameter"), self.t("value"), self.t("source")])
        row += 1
        for key in ns.parameters:
            value = ns.parameters[key]
            put_text(ws, row, 1, param_name(ns, key, self.loc), wrap=True)
            if isinstance(value, int | float) and not isinstance(value, bool):
                put_num(ws, row, 2, value, "0.0##")
                ws.cell(row, 2).alignment = Alignment(horizontal="left", vertical="top")
            else:
                put_text(ws, row, 2, param_value(ns, key, value, self.loc), wrap=True)
            put_text(ws, row, 3, self.bib.cite(ns.parameter_sources.get(key, "")), wrap=True)
            row += 1
        shapes_used = {o.shape for o in objs}
        row = self.section(ws, row + 1, self.t("xlsx_shapes"))
        _header(ws, row, [self.t("xlsx_shape"), self.t("xlsx_shape_coefficient"),
                          self.t("source"), self.t("xlsx_used")])
        row += 1
        for shape, coef in ns.shapes.items():
            meta = ns.shape_rows.get(shape, {})
            cells = [put_text(ws, row, 1, self.shape_name(ns, shape)),
                     put_num(ws, row, 2, coef, F2),
                     put_text(ws, row, 4, self.yes_no(shape in shapes_used))]
            put_text(ws, row, 3, self.bib.cite(meta.get("source", "")), wrap=True)
            if shape in shapes_used:
                _mark(cells)
            row += 1
        row = self.section(ws, row + 1, self.t("xlsx_objects"))
        _header(ws, row, [self.t("map_scale"), self.t("xlsx_object_name"),
                          self.t("xlsx_object_size_m"), self.t("xlsx_used"),
                          self.t("xlsx_shape"), self.t("source")])
        row += 1
        used_rows = {(o.map_scale, o.name, o.size_m) for o in objs if o.map_scale is not None}
        for obj in ns.objects:
            is_used = (obj.map_scale, obj.name, obj.size_m) in used_rows
            cells = [put_num(ws, row, 1, obj.map_scale, SCALE),
                     put_text(ws, row, 2, object_title(obj, self.loc), wrap=True),
                     put_num(ws, row, 3, obj.size_m, F3),
                     put_text(ws, row, 4, self.yes_no(is_used)),
                     put_text(ws, row, 5, self.shape_name(ns, obj.shape))]
            put_text(ws, row, 6, self.bib.cite(obj.source), wrap=True)
            if is_used:
                _mark(cells)
            row += 1
        return row

    def _warning_items(self, scan: ScanJob | None, uav: UavJob | None,
                       spec: PlanResult | None = None) -> list[tuple[str, PlanWarning, Any]]:
        items: list[tuple[str, PlanWarning, Any]] = []
        if scan is not None:
            items += [(self.t("xlsx_section_scan"), w, scan.norm_set) for w in scan.plan.warnings]
        if uav is not None:
            items += [(self.t("xlsx_section_uav"), w, uav.norm_set) for w in uav.plan.warnings]
        if spec is not None:
            seen = {w.code for _, w, _ in items}
            items += [(self.t("spec_title"), w, None) for w in spec.warnings
                      if w.code not in seen]
        return items

    def _heading(self, w: PlanWarning) -> str:
        key = f"pdf_warn_{w.code}"
        return self.t(key) if key in LABELS["en"] else ""

    def _warning_lines(self, scan: ScanJob | None, uav: UavJob | None,
                       spec: PlanResult | None) -> list[str]:
        """Every warning in short form (the Summary sheet's box)."""
        out = []
        for _section, w, ns in self._warning_items(scan, uav, spec):
            head = self._heading(w) or self.text(w.message, ns)
            scales = ", ".join(_scale_text(s) for s in w.photo_scales)
            out.append(f"! {head}" + (f": {scales}" if scales else ""))
        return list(dict.fromkeys(out))

    def warnings(self, scan: ScanJob | None, uav: UavJob | None,
                 spec: PlanResult | None = None) -> None:
        ws = self.sheet("xlsx_sheet_warnings", landscape=True, widths=(20, 14, 30, 20, 90))
        _header(ws, 1, [self.t("xlsx_section"), self.t("xlsx_severity"), self.t("warnings"),
                        self.t("photo_scale"), self.t("xlsx_message")])
        items = self._warning_items(scan, uav, spec)
        if not items:
            put_text(ws, 2, 1, self.t("no_warnings"))
            return
        for row, (section, w, ns) in enumerate(items, start=2):
            try:
                severity = self.t(f"xlsx_severity_{w.severity}")
            except KeyError:
                severity = w.severity
            cells = [put_text(ws, row, 1, section, wrap=True),
                     put_text(ws, row, 2, severity),
                     put_text(ws, row, 3, self._heading(w), wrap=True),
                     put_text(ws, row, 4, ", ".join(_scale_text(s) for s in w.photo_scales),
                              wrap=True),
                     put_text(ws, row, 5, self.text(w.message, ns), wrap=True)]
            if w.severity == "warning":
                for cell in cells:
                    cell.fill = _WARNING_FILL
        ws.auto_filter.ref = f"A1:E{len(items) + 1}"

    def references(self) -> None:
        """The works the workbook cites, numbered as in its cells."""
        ws = self.sheet("references", landscape=False, widths=(8, 110, 8))
        _header(ws, 1, ["№", self.t("references")])
        for row, (n, text) in enumerate(self.bib.entries(), start=2):
            put_num(ws, row, 1, n, INT)
            put_text(ws, row, 2, text, wrap=True)



# ---------------------------------------------------------------------------------------
# Charts
# ---------------------------------------------------------------------------------------


def _scatter(title: str, x_title: str, y_title: str) -> ScatterChart:
    chart = ScatterChart()
    chart.title = title
    chart.style = 2
    chart.scatterStyle = "line"
    chart.x_axis.title = x_title
    chart.y_axis.title = y_title
    chart.x_axis.axPos = "b"
    chart.x_axis.delete = False  # newer Excel hides axes openpyxl leaves undecided
    chart.y_axis.delete = False
    chart.legend.position = "b"
    chart.width = 24
    chart.height = 13
    return chart


def _scale_ticks(candidates: Sequence[float], lo: float, hi: float) -> tuple[float, float,
                                                                            float]:
    """(min, max, major unit) of a photo-scale axis with a tick on every candidate scale:
    the largest round step that divides them all, at most 20 ticks over the range."""
    for step in (10000.0, 5000.0, 2500.0, 2000.0, 1000.0, 500.0, 250.0, 100.0):
        if all(float(c) % step == 0 for c in candidates) and (hi - lo) / step <= 20:
            break
    else:
        step = max((hi - lo) / 10, 1.0)
    return math.floor(lo / step) * step, math.ceil(hi / step) * step, step


def _log_floor(x: float) -> float:
    """The power of ten at or below ``x`` (a log axis's minimum)."""
    return float(10 ** math.floor(math.log10(x))) if x > 0 else 0.01


def _log_ceil(x: float) -> float:
    """The power of ten at or above ``x`` (a log axis's maximum)."""
    return float(10 ** math.ceil(math.log10(x))) if x > 0 else 1.0


def _group(x: float, locale: str) -> str:
    """A whole number grouped by thousands (no-break space in Russian)."""
    text = f"{round(float(x)):,d}"
    return text.replace(",", "\u00a0") if locale == "ru" else text.replace(",", "")


_CM_PER_CHAR = 0.2  # a column width unit (one "0" of Calibri 11) on paper [cm], about


def _sheet_width_cm(ws: Worksheet) -> float:
    """The printed width of the sheet's used columns at 100 % [cm]."""
    widths = [ws.column_dimensions[get_column_letter(c)].width or 8.43
              for c in range(1, ws.max_column + 1)]
    return sum(widths) * _CM_PER_CHAR


def _chart_below(ws: Worksheet, chart: ScatterChart, row: int) -> None:
    """Put ``chart`` below the data from ``row`` on, starting a printed page, sized to the
    sheet's printed width (the page is fitted to that width) and short enough to fit the
    page's height: a chart is never split across pages nor shrunk to a stamp."""
    ws.row_breaks.append(Break(id=row - 1))
    sheet_cm = max(_sheet_width_cm(ws), 24.0)
    landscape = ws.page_setup.orientation == "landscape"
    page_ratio = (17.0 / 27.7) if landscape else (26.0 / 19.0)  # printable height/width
    chart.width = 0.95 * sheet_cm
    chart.height = min(0.55 * chart.width, 0.8 * sheet_cm * page_ratio)
    ws.add_chart(chart, f"A{row}")


def _fit_rows(ws: Worksheet) -> None:
    """Row heights for wrapped text, so no wrapped cell runs over the next row in programs
    that do not measure text when opening a file (LibreOffice keeps stored heights)."""
    width = {c: (ws.column_dimensions[get_column_letter(c)].width or 8.43)
             for c in range(1, ws.max_column + 1)}
    merged = {(r.min_row, r.min_col): sum(width.get(c, 8.43)
                                          for c in range(r.min_col, r.max_col + 1))
              for r in ws.merged_cells.ranges if r.min_row == r.max_row}
    for row in ws.iter_rows():
        lines = 1
        for cell in row:
            if not isinstance(cell.value, str) or not cell.alignment.wrap_text:
                continue
            w = merged.get((cell.row, cell.column), width.get(cell.column, 8.43))
            chars = max(w * (0.9 if cell.font.bold else 1.05) - 1, 4)
            n = sum(max(1, math.ceil(len(part) / chars)) for part in cell.value.split("\n"))
            lines = max(lines, n)
        if lines > 1:
            ws.row_dimensions[row[0].row].height = 15 * lines + 2
            for cell in row:  # numbers beside a paragraph read from its first line
                if cell.value is not None and cell.alignment.vertical != "top":
                    al = cell.alignment
                    cell.alignment = Alignment(horizontal=al.horizontal, vertical="top",
                                               wrap_text=al.wrap_text)


def _add_series(chart: ScatterChart, ws: Worksheet, xref: Reference, col: int, n: int,
                title: str, *, first_row: int = 2, width_emu: int = 22225,
                dash: str | None = None, color: str | None = None) -> Series:
    yref = Reference(ws, min_col=col, min_row=first_row, max_row=first_row + n - 1)
    series = Series(yref, xref, title=_clean_text(title))
    series.marker.symbol = "none"
    series.smooth = False
    series.graphicalProperties.line.width = width_emu
    if dash:
        series.graphicalProperties.line.dashStyle = dash
    if color:
        series.graphicalProperties.line.solidFill = color
    chart.series.append(series)
    return series


# ---------------------------------------------------------------------------------------
# Deterministic zip
# ---------------------------------------------------------------------------------------


def _repack(raw: bytes, when: _dt.datetime) -> bytes:
    """Rewrite the zip with one fixed timestamp, compression and permissions per member.

    openpyxl stamps every member with the current time; the re-pack keeps the member order
    and contents and makes the bytes depend on ``when`` only.
    """
    utc = when.astimezone(_dt.UTC)
    stamp = max((utc.year, utc.month, utc.day, utc.hour, utc.minute, utc.second), _ZIP_EPOCH)
    out = io.BytesIO()
    with zipfile.ZipFile(io.BytesIO(raw)) as src, \
            zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as dst:
        for info in src.infolist():
            member = zipfile.ZipInfo(info.filename, date_time=stamp)
            member.compress_type = zipfile.ZIP_DEFLATED
            member.create_system = 3
            member.external_attr = 0o644 << 16
            dst.writestr(member, src.read(info.filename), compresslevel=6)
    return out.getvalue()

