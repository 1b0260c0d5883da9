"""Benchmark: a full report pair (.xlsx + .pdf) for one project.

Renders the Excel workbook and the PDF specification for seed 002's UAV flight together
with the Table 8 film sweep (the future `plan` document: both sections), in memory.
Target: the pair under 4 s on the reference machine. A warm-up render (imports, font
loading) is excluded; the best of ``--repeat`` runs is reported.

Run: ``python benchmarks/bench_reports.py [--repeat 3]``
"""

from __future__ import annotations

import argparse
import time

from _timing import best_of

from scanplan.api import scan_job, uav_job
from scanplan.reports import ReportMeta

TARGET_S = 4.0


def run(repeat: int = 3) -> dict[str, float]:
    """Time the pair; return {'xlsx_s', 'pdf_s', 'pair_s', 'first_pair_s', 'target'}."""
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
    return {"xlsx_s": xlsx_s, "pdf_s": pdf_s, "pair_s": xlsx_s + pdf_s,
            "first_pair_s": first, "target": TARGET_S}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    res = run(ap.parse_args().repeat)
    verdict = "PASS" if res["pair_s"] < res["target"] else "FAIL"
    print(f"report pair: xlsx {res['xlsx_s']:.2f} s + pdf {res['pdf_s']:.2f} s = "
          f"{res['pair_s']:.2f} s (first, cold: {res['first_pair_s']:.2f} s) "
          f"target < {res['target']:g} s {verdict}")


if __name__ == "__main__":
    main()
