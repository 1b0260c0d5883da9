"""Benchmark: a full report pair (.xlsx + .pdf) for one project.

Renders the Excel workbook and the PDF specification for seed 002's UAV flight together
with the Table 8 film sweep (the future `plan` document: both sections), in memory.
Target: the pair under 4 s on the reference machine. A warm-up render (imports, font
loading) is excluded; the best of ``--repeat`` runs is reported. For scale, the pair is
also compared, in the same process, with the smallest job of the same two libraries: a
one-paragraph WeasyPrint page and a one-cell openpyxl workbook, both in memory.

Run: ``python benchmarks/bench_reports.py [--repeat 3]``
"""

from __future__ import annotations

import argparse
import io
import time

from _common import Result
from _timing import best_of

from scanplan.project.jobs import scan_job, uav_job
from scanplan.reports import ReportMeta

TARGET_S = 4.0


def trivial_pdf() -> bytes:
    """Baseline: a one-paragraph WeasyPrint page, in memory."""
    import weasyprint

    return weasyprint.HTML(string="<p>Scan pixel 20 µm</p>").write_pdf()


def trivial_xlsx() -> bytes:
    """Baseline: a one-cell openpyxl workbook, in memory."""
    import openpyxl

    wb = openpyxl.Workbook()
    wb.active.append(["Scan pixel, µm", 20])
    out = io.BytesIO()
    wb.save(out)
    return out.getvalue()


def run(repeat: int = 3) -> dict[str, float]:
    """Time the pair and the baseline.

    Returns ``{'xlsx_s', 'pdf_s', 'pair_s', 'first_pair_s', 'base_xlsx_s', 'base_pdf_s',
    'target'}`` (seconds; the baseline pair is warmed up too).
    """
    from scanplan.reports.excel import render_xlsx
    from scanplan.reports.pdf import render_pdf

    scan = scan_job(map_scale=2000, relief_interval_m=0.5,
                    photo_scales=[5000, 10000, 15000, 20000], camera="rc30-153",
                    scanner="photoscan-td")
    uav = uav_job(camera="canon-eos-5d-mark-ii-50", f_number=8, height_m=300,
                  height_tolerance_pct=40, speed_ms=25, map_scale=2000, relief_interval_m=0.5,
                  area_m="2000x3000")
    meta = ReportMeta(project="Town of Lida, topographic plan 1:2000", customer="Customer",
                      contractor="Contractor", approver_position="Chief engineer",
                      approver_name="I. I. Ivanov")
    t0 = time.perf_counter()
    render_xlsx(scan=scan, uav=uav, meta=meta)
    render_pdf(scan=scan, uav=uav, meta=meta)
    first = time.perf_counter() - t0
    xlsx_s = best_of(lambda: render_xlsx(scan=scan, uav=uav, meta=meta), repeat)
    pdf_s = best_of(lambda: render_pdf(scan=scan, uav=uav, meta=meta), repeat)
    trivial_xlsx()
    trivial_pdf()
    base_xlsx_s = best_of(trivial_xlsx, repeat)
    base_pdf_s = best_of(trivial_pdf, repeat)
    return {"xlsx_s": xlsx_s, "pdf_s": pdf_s, "pair_s": xlsx_s + pdf_s,
            "first_pair_s": first, "base_xlsx_s": base_xlsx_s, "base_pdf_s": base_pdf_s,
            "target": TARGET_S}


def measure(quick: bool = False) -> list[Result]:
    """The runner's entry: the warm report pair as one row against the 4 s target.

    Parameters
    ----------
    quick : bool, optional
        Best of 1 instead of 3 (after the same warm-up render).

    Returns
    -------
    list of Result
        ``reports``: seconds for the .xlsx + .pdf pair, target ≤ 4 s.
    """
    repeat = 1 if quick else 3
    r = run(repeat)
    base = r["base_xlsx_s"] + r["base_pdf_s"]
    return [Result(
        "reports", r["pair_s"], "s", r["target"], "<=",
        note=f"xlsx {r['xlsx_s']:.2f} s + pdf {r['pdf_s']:.2f} s, warm, best of {repeat} "
             f"(first, cold pair {r['first_pair_s']:.2f} s); {r['pair_s'] / base:.0f}x a "
             f"one-cell openpyxl workbook + one-paragraph WeasyPrint page "
             f"({base * 1000:.0f} ms)",
    )]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    res = run(ap.parse_args().repeat)
    verdict = "PASS" if res["pair_s"] < res["target"] else "FAIL"
    print(f"report pair: xlsx {res['xlsx_s']:.2f} s + pdf {res['pdf_s']:.2f} s = "
          f"{res['pair_s']:.2f} s (first, cold: {res['first_pair_s']:.2f} s) "
          f"target < {res['target']:g} s {verdict}")
    base = res["base_xlsx_s"] + res["base_pdf_s"]
    print(f"baseline, same process: one-cell openpyxl workbook {res['base_xlsx_s'] * 1000:.0f} ms "
          f"+ one-paragraph WeasyPrint page {res['base_pdf_s'] * 1000:.0f} ms; the pair is "
          f"{res['pair_s'] / base:.0f}x that")


if __name__ == "__main__":
    main()
