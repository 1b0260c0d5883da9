"""Benchmark: the page of ``scanplan serve`` in a real browser — from an edit to the new
result drawn.

Row:

- ``page.edit_to_drawn_ms`` — the town (``examples/areas/town-uav.kml``, the DJI Zenmuse P1,
  ``examples/uav-town-2000.toml``'s scale and relief) on the page in headless Chromium
  (Debian's ``chromium``, driven by Playwright as ``tests/test_web_browser.py`` drives it),
  served by ``scanplan serve``'s application with its worker process; ten edits of the
  flight height, each timed in the page from the keystroke's ``input`` event to the first
  frame after the new result is drawn (headline, table, strips, photo centres); the median.
  Target 150 ms. The note splits it: the request (the server's plan, the pipe, the JSON,
  the browser's fetch and parse), the drawing and the rest (the edit to the request, the
  frame), and gives the same project's plan alone in this process
  (``plan_project`` + the ``plan --json`` document) as the baseline the page adds to.

Run: ``python benchmarks/bench_page.py`` (needs /usr/bin/chromium and the ``serve`` and
``test`` extras).
"""

from __future__ import annotations

import json
import statistics
import threading
import time

from _common import ROOT, Result

TARGET_MS = 150.0
CHROMIUM = "/usr/bin/chromium"
EDITS = 10

_EDIT_JS = """async (value) => {
  const el = document.getElementById('f-uav-height_m');
  const before = document.body.dataset.seq;
  const t0 = performance.now();
  el.value = String(value);
  el.dispatchEvent(new Event('input', {bubbles: true}));
  await new Promise((resolve) => {
    const ob = new MutationObserver(() => {
      if (document.body.dataset.seq !== before && !document.body.dataset.planning) {
        ob.disconnect(); resolve();
      }
    });
    ob.observe(document.body, {attributes: true});
  });
  await new Promise((r) => requestAnimationFrame(() => r()));
  return {total: performance.now() - t0, draw: Number(document.body.dataset.drawMs),
          request: Number(document.body.dataset.requestMs),
          error: document.body.dataset.result !== 'ok'};
}"""


def _plan_alone_ms(repeat: int) -> float:
    """The same project planned in this process (plan + JSON), median [ms]."""
    from scanplan.project.file import parse_project
    from scanplan.project.spec import plan_project
    from scanplan.reports.jsondoc import plan_result_dict

    text = ("[project]\nlocale = \"en\"\n[map]\nscale = 2000\nrelief_interval_m = 0.5\n"
            "[uav]\ncamera = \"dji-zenmuse-p1-35\"\nheight_m = 120\n"
            "[area]\nfile = \"areas/town-uav.kml\"\n")
    path = ROOT / "examples" / "project.toml"
    json.dumps(plan_result_dict(plan_project(parse_project(text, path))))  # warm
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        json.dumps(plan_result_dict(plan_project(parse_project(text, path))))
        times.append((time.perf_counter() - t) * 1000)
    return statistics.median(times)


def _edits(edits: int) -> list[dict[str, float]]:
    import uvicorn
    from playwright.sync_api import sync_playwright

    from scanplan.web.app import create_app

    srv = uvicorn.Server(uvicorn.Config(create_app(tiles="none"), host="127.0.0.1", port=0,
                                        log_level="warning"))
    thread = threading.Thread(target=srv.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 60
    while not srv.started and time.monotonic() < deadline:
        time.sleep(0.05)
    url = f"http://127.0.0.1:{srv.servers[0].sockets[0].getsockname()[1]}/?lang=en"
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=CHROMIUM, args=[
                "--headless", "--no-sandbox", "--disable-gpu",
                "--disable-background-networking", "--no-first-run"])
            page = browser.new_page(viewport={"width": 1400, "height": 860})
            page.goto(url)
            page.wait_for_selector("body[data-ready]", state="attached", timeout=60_000)
            page.set_input_files("#area-file", str(ROOT / "examples" / "areas" /
                                                   "town-uav.kml"))
            page.fill("#f-map-relief_interval_m", "0.5")
            page.fill("#camera-search", "p1 35")
            page.click("#camera-list li[data-id='dji-zenmuse-p1-35']")
            page.wait_for_function("document.body.dataset.result === 'ok' && "
                                   "!document.body.dataset.planning", timeout=120_000)
            page.evaluate(_EDIT_JS, 119)  # warm: the worker has planned the town once
            out = [page.evaluate(_EDIT_JS, 120 + i) for i in range(edits)]
            browser.close()
    finally:
        srv.should_exit = True
        thread.join(30)
    return out


def measure(quick: bool) -> list[Result]:
    """The median of ten edits on the page, the request and drawing parts in the note."""
    import os

    if not os.path.exists(CHROMIUM):
        return [Result("page.edit_to_drawn_ms", float("nan"), "ms", TARGET_MS, "<=",
                       error=f"RuntimeError: {CHROMIUM} is not installed")]
    runs = _edits(EDITS)
    total = statistics.median(r["total"] for r in runs)
    draw = statistics.median(r["draw"] for r in runs)
    request = statistics.median(r["request"] for r in runs)
    alone = _plan_alone_ms(3 if quick else 9)
    load = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    bad = sum(bool(r["error"]) for r in runs)
    return [Result("page.edit_to_drawn_ms", total, "ms", TARGET_MS, "<=",
                   note=f"town, headless Chromium, median of {EDITS} edits of the height "
                   f"(min {min(r['total'] for r in runs):.0f}, max "
                   f"{max(r['total'] for r in runs):.0f} ms); the request (sent to answer "
                   f"read) {request:.0f} ms of it, drawing {draw:.0f} ms, the rest before "
                   f"the request and the frame; the same plan alone in this process "
                   f"{alone:.0f} ms; load average {load}"
                   + (f"; {bad} edits answered an error" if bad else ""))]


if __name__ == "__main__":
    for r in measure(quick=False):
        print(r)
