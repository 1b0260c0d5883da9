"""Benchmark: reports in under a second (issue 15, part 3).

Two rows, each against a baseline measured in the same run:

* ``fast_reports.cold_plan`` — ``scanplan plan examples/uav-canon-2000.toml --out DIR``
  with both reports (spec.xlsx + spec.pdf) in a fresh Python process, the median wall time
  of ``--runs`` processes. Target ≤ 1.0 s. Baselines, also whole processes: a bare
  ``python -c pass`` and the same plan without reports.
* ``fast_reports.pdf_floor`` — the PDF render of the same project from its view (the
  plots, drawn once per result, are not redrawn; their drawing is timed in the note),
  warm, best of ``--repeat``, divided by the render of a minimal WeasyPrint document with the same
  number of A4 pages, the same two SVG plots and the bundled font (one short paragraph
  per page, everything else left out). Target ≤ 1.3×.

Run: ``python benchmarks/bench_fast_reports.py [--runs 7] [--repeat 5]``
"""

from __future__ import annotations

import argparse
import base64
import os
import statistics
import subprocess
import sys
import tempfile
import time

from _common import ROOT, Result
from _timing import best_of

PROJECT = ROOT / "examples" / "uav-canon-2000.toml"
COLD_TARGET_S = 1.0
FLOOR_TARGET = 1.3


def _wall(argv: list[str]) -> float:
    """Wall time [s] of one whole process (its output discarded; failure raises)."""
    env = {**os.environ, "SOURCE_DATE_EPOCH": "1700000000"}
    t0 = time.perf_counter()
    subprocess.run(argv, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                   env=env, cwd=ROOT)
    return time.perf_counter() - t0


def cold(runs: int) -> dict[str, float]:
    """Median wall times [s] of fresh processes: the plan with reports, without, bare."""
    cli = [sys.executable, "-c", "from scanplan.cli.main import main; main()", "plan",
           str(PROJECT)]
    with tempfile.TemporaryDirectory() as out:
        _wall([*cli, "--out", out, "--force"])  # warm the OS file cache, not the process
        with_reports = [_wall([*cli, "--out", out, "--force"]) for _ in range(runs)]
    without = [_wall(cli) for _ in range(runs)]
    bare = [_wall([sys.executable, "-c", "pass"]) for _ in range(runs)]
    return {"with_reports_s": statistics.median(with_reports),
            "without_reports_s": statistics.median(without),
            "bare_s": statistics.median(bare)}


def _data_uri(svg: str) -> str:
    return "data:image/svg+xml;base64," + base64.b64encode(svg.encode("utf-8")).decode()


def floor_html(svgs: list[str], pages: int) -> str:
    """The minimal document: ``pages`` A4 pages, the bundled font, the plots as the report
    embeds them (``data:`` SVG, full text width), one paragraph per page."""
    body = []
    for i in range(pages):
        img = (f'<img src="{svgs[i]}" style="width: 100%">' if i < len(svgs) else "")
        body.append(f'<section style="break-after: page"><p>Page {i + 1}: GSD 0,027 м, '
                    f'L 0,045 m.</p>{img}</section>')
    return ("<!doctype html><html><head><meta charset='utf-8'><style>"
            "@page { size: A4; margin: 18mm 15mm 20mm 20mm }"
            "@font-face { font-family: 'Scanplan Sans'; src: url('fonts/DejaVuSans.ttf') }"
            "body { font-family: 'Scanplan Sans'; font-size: 9.5pt }"
            "</style></head><body>" + "".join(body) + "</body></html>")


def pdf_vs_floor(repeat: int) -> dict[str, float]:
    """The report's PDF render and the minimal document's, warm, best of ``repeat``
    interleaved runs [s]."""
    import weasyprint
    from weasyprint.text.fonts import FontConfiguration

    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project
    from scanplan.reports import templates_dir
    from scanplan.reports.pdf import BundledAssetFetcher, render_html, render_pdf

    result = plan_project(load_project(PROJECT))
    jobs = {"scan": result.film.job if result.film else None,
            "uav": result.uav.job if result.uav else None, "meta": result.meta,
            "spec": result}
    try:
        from scanplan.reports.view import build_view

        view = build_view(**jobs)
        svgs = [view.plot_uri(name) for name in ("mtf", "height")]

        def render() -> bytes:  # the result's view: its plots are drawn once, not here
            return render_pdf(view=view)

        def draw() -> None:
            fresh = build_view(**jobs)
            fresh.plot("mtf")
            fresh.plot("height")
    except ImportError:  # a tree before the view model (the "before" numbers)
        from scanplan.reports import plots

        svgs = [_data_uri(plot(result.uav.job.plan, result.meta.locale))
                for plot in (plots.mtf_svg, plots.height_svg)]

        def render() -> bytes:  # draws the plots every time: nothing keeps them
            return render_pdf(**jobs)

        def draw() -> None:
            for plot in (plots.mtf_svg, plots.height_svg):
                plot(result.uav.job.plan, result.meta.locale)
    base = templates_dir().resolve().as_uri() + "/"
    render()  # warm-up: fonts, templates
    pages = len(weasyprint.HTML(string=render_html(**jobs), base_url=base,
                                url_fetcher=BundledAssetFetcher()).render().pages)
    html = floor_html(svgs, pages)
    fonts = FontConfiguration()

    def floor() -> bytes:
        return weasyprint.HTML(string=html, base_url=base,
                               url_fetcher=BundledAssetFetcher()).write_pdf(font_config=fonts)

    floor()
    pdf_s = floor_s = float("inf")
    for _ in range(repeat):  # interleaved: a change of the machine's load hits both
        pdf_s = min(pdf_s, best_of(render, 1))
        floor_s = min(floor_s, best_of(floor, 1))
    return {"pdf_s": pdf_s, "floor_s": floor_s, "pages": pages,
            "plots_s": best_of(draw, repeat)}


def measure(quick: bool = False) -> list[Result]:
    """The runner's entry: the two rows.

    Parameters
    ----------
    quick : bool, optional
        3 processes and best of 2 renders instead of 7 and 5.

    Returns
    -------
    list of Result
        ``fast_reports.cold_plan`` [s] (≤ 1.0) and ``fast_reports.pdf_floor`` [x] (≤ 1.3).
    """
    runs, repeat = (3, 2) if quick else (7, 5)
    c = cold(runs)
    f = pdf_vs_floor(repeat)
    return [
        Result("fast_reports.cold_plan", c["with_reports_s"], "s", COLD_TARGET_S, "<=",
               note=f"plan + spec.xlsx + spec.pdf of {PROJECT.name}, fresh process, median "
                    f"of {runs}; without reports {c['without_reports_s']:.2f} s, bare "
                    f"`python -c pass` {c['bare_s']:.2f} s"),
        Result("fast_reports.pdf_floor", f["pdf_s"] / f["floor_s"], "x", FLOOR_TARGET, "<=",
               note=f"PDF render {f['pdf_s'] * 1000:.0f} ms (warm, best of {repeat}) / a "
                    f"minimal WeasyPrint document with the same {f['pages']:.0f} pages, SVGs "
                    f"and bundled font {f['floor_s'] * 1000:.0f} ms; drawing the two plots "
                    f"(once per result) {f['plots_s'] * 1000:.0f} ms"),
    ]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=7, help="fresh processes per median")
    ap.add_argument("--repeat", type=int, default=5, help="warm renders, best of")
    args = ap.parse_args()
    c = cold(args.runs)
    print(f"cold plan with both reports: {c['with_reports_s']:.2f} s (median of {args.runs}; "
          f"target <= {COLD_TARGET_S:g} s); without reports {c['without_reports_s']:.2f} s; "
          f"bare python {c['bare_s']:.2f} s")
    f = pdf_vs_floor(args.repeat)
    print(f"PDF render {f['pdf_s'] * 1000:.0f} ms vs minimal document "
          f"{f['floor_s'] * 1000:.0f} ms ({f['pages']:.0f} pages): "
          f"{f['pdf_s'] / f['floor_s']:.2f}x (target <= {FLOOR_TARGET:g}x); the two plots "
          f"{f['plots_s'] * 1000:.0f} ms")


if __name__ == "__main__":
    main()
