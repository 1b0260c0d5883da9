"""The bundled examples planned and rendered once per test run, for the tests that read
their documents many ways (imported as ``documents``; tests/ is on sys.path).

Each example is planned once per locale (``[project] locale`` set to it) and each document
rendered once: the workbook's bytes and the workbook read back, the PDF's text by page, the
HTML the PDF is made of. The tests only read what these return.
"""

from __future__ import annotations

import dataclasses
import io
from functools import cache
from pathlib import Path
from typing import Any

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


@cache
def planned(example: str, locale: str) -> Any:
    """The plan of one example (a path) in one locale."""
    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project

    project = load_project(example)
    values = {sec: dict(v) for sec, v in project.values.items()}
    values.setdefault("project", {})["locale"] = locale
    return plan_project(dataclasses.replace(project, values=values))


def jobs(result: Any) -> dict[str, Any]:
    """The reports' arguments for a plan."""
    return {"scan": result.film.job if result.film else None,
            "uav": result.uav.job if result.uav else None, "meta": result.meta,
            "spec": result}


@cache
def workbook(example: str, locale: str) -> bytes:
    """spec.xlsx of one example in one locale."""
    from scanplan.reports.excel import render_xlsx

    return render_xlsx(**jobs(planned(example, locale)))


@cache
def loaded_workbook(example: str, locale: str) -> Any:
    """The workbook read back by openpyxl."""
    from openpyxl import load_workbook

    return load_workbook(io.BytesIO(workbook(example, locale)))


@cache
def pdf_pages(example: str, locale: str) -> tuple[str, ...]:
    """The text of every page of spec.pdf of one example in one locale (pypdf)."""
    import pypdf

    from scanplan.reports.pdf import render_pdf

    data = render_pdf(**jobs(planned(example, locale)))
    return tuple(page.extract_text() for page in pypdf.PdfReader(io.BytesIO(data)).pages)


@cache
def page_html(example: str, locale: str) -> str:
    """The HTML the PDF of one example in one locale is made of."""
    from scanplan.reports.pdf import render_html

    return render_html(**jobs(planned(example, locale)))
