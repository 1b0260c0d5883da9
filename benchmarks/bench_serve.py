"""Benchmark: ``scanplan serve`` — how fast the page's plan comes back, how fast it starts.

Rows:

- ``serve.view_ms`` — the slowest example's median round trip of ``POST /api/view`` (what
  the page sends on every change: the plan without reports, its map, chart and project
  file) through the framework's test client to the real worker process; target 300 ms. The
  note gives every example's time and, as the same-process baseline, the command line's
  own ``plan_project`` + ``plan --json`` document of the same project (the ratio is the
  page's overhead: the pipe, the map, the chart).
- ``serve.view_over_plan`` — the median over the examples of that round trip over the
  baseline; target 1.5×.
- ``serve.startup_s`` — a fresh ``python -m scanplan serve --port 0`` until it prints its
  address, compiled bytecode in place as an installed package has it; target 1.5 s (bare
  Python's start in the note).
- ``serve.zip_s`` — the zip of every download of the town (``POST /api/download/zip``:
  the PDF, the workbook, the missions and GIS files, the project file and its upload) once
  the page has shown the plan and the user has looked at it for the time it takes to render
  them ahead (:mod:`scanplan.web.documents`); target 3 s. The note gives the time of a zip
  asked for at once, while nothing was rendered ahead.

Run: ``python benchmarks/bench_serve.py``
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
import time

from _common import ROOT, Result, child_env

_LOCAL = "http://127.0.0.1:8765"
"""The page's own address: the server answers only its own host names."""

VIEW_TARGET_MS = 300.0
STARTUP_TARGET_S = 1.5
ZIP_TARGET_S = 3.0
OVERHEAD_TARGET = 1.5


def _view_times(repeat: int) -> dict[str, tuple[float, float]]:
    """Example → (median /api/view round trip [ms], median in-process plan [ms])."""
    sys.path.insert(0, str(ROOT / "tests"))
    from fastapi.testclient import TestClient
    from web_helpers import EXAMPLES, example_request

    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project
    from scanplan.reports.jsondoc import plan_result_dict
    from scanplan.web.app import create_app

    out = {}
    with TestClient(create_app(), base_url=_LOCAL) as client:
        for path in sorted(EXAMPLES.glob("*.toml")):
            req = example_request(client, path)
            assert client.post("/api/view", json=req).status_code == 200  # warm
            api = []
            for _ in range(repeat):
                t = time.perf_counter()
                client.post("/api/view", json=req)
                api.append((time.perf_counter() - t) * 1000)
            base = []
            for _ in range(repeat):
                t = time.perf_counter()
                json.dumps(plan_result_dict(plan_project(load_project(path))))
                base.append((time.perf_counter() - t) * 1000)
            out[path.stem] = (statistics.median(api), statistics.median(base))
    return out


def _settled(app: object, timeout_s: float = 600.0) -> None:
    """Wait until nothing is being rendered ahead."""
    docs = app.state.documents  # type: ignore[attr-defined]
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        with docs._cond:
            if docs._wanted is None and not docs._running:
                return
        time.sleep(0.1)


def _zip_times(repeat: int) -> tuple[float, float]:
    """Median seconds of the town's zip after the plan was shown and looked at, and of
    one asked for at once (nothing rendered ahead), through real worker processes."""
    sys.path.insert(0, str(ROOT / "tests"))
    from fastapi.testclient import TestClient
    from web_helpers import EXAMPLES, example_request

    from scanplan.web.app import create_app

    app = create_app()
    looked, at_once = [], []
    with TestClient(app, base_url=_LOCAL) as client:
        req = example_request(client, EXAMPLES / "uav-town-2000.toml")
        heights = iter(range(130, 10, -5))
        for _ in range(repeat):
            req["project"]["uav"]["height_m"] = next(heights)
            assert client.post("/api/view", json=req).status_code == 200
            _settled(app)
            t = time.perf_counter()
            r = client.post("/api/download/zip", json=req)
            looked.append(time.perf_counter() - t)
            assert r.status_code == 200, r.text
            req["project"]["uav"]["height_m"] = next(heights)
            client.post("/api/view", json=req)
            t = time.perf_counter()
            r = client.post("/api/download/zip", json=req)  # clicked at once
            at_once.append(time.perf_counter() - t)
            assert r.status_code == 200, r.text
    return statistics.median(looked), statistics.median(at_once)


def _startup_s(repeat: int) -> tuple[float, float]:
    """Median seconds until ``serve`` prints its address, and bare Python's start."""
    starts, bare = [], []
    subprocess.run([sys.executable, "-c", "import scanplan.cli.serve, fastapi, uvicorn"],
                   check=True, env=child_env())  # bytecode compiled, as installed
    for _ in range(repeat):
        t = time.perf_counter()
        proc = subprocess.Popen([sys.executable, "-m", "scanplan", "serve", "--port", "0",
                                 "--tiles", "none"], cwd=ROOT, stdout=subprocess.PIPE,
                                text=True, env=child_env())
        assert proc.stdout is not None
        line = proc.stdout.readline()
        starts.append(time.perf_counter() - t)
        proc.terminate()
        proc.wait(30)
        assert "the page is at" in line, line
        t = time.perf_counter()
        subprocess.run([sys.executable, "-c", "pass"], check=True, env=child_env())
        bare.append(time.perf_counter() - t)
    return statistics.median(starts), statistics.median(bare)


def measure(quick: bool) -> list[Result]:
    """The slowest example's /api/view round trip, and the start of ``serve``."""
    repeat = 1 if quick else 9  # quick (CI): one round trip per example, advisory
    times = _view_times(repeat)
    worst = max(times, key=lambda k: times[k][0])
    detail = "; ".join(f"{k} {a:.0f} ms (plan alone {b:.0f} ms, ×{a / b:.2f})"
                       for k, (a, b) in times.items())
    start, bare = _startup_s(1 if quick else 5)
    looked, at_once = _zip_times(1 if quick else 3)
    ratio = statistics.median(a / b for a, b in times.values())
    return [
        Result("serve.view_ms", times[worst][0], "ms", VIEW_TARGET_MS, "<=",
               note=f"POST /api/view, median of {repeat} per example, worst {worst}: "
               f"{detail}"),
        Result("serve.view_over_plan", ratio, "x", OVERHEAD_TARGET, "<=",
               note="median over the examples of /api/view over the command line's plan "
               "and JSON of the same project in this process: the page's own cost"),
        Result("serve.startup_s", start, "s", STARTUP_TARGET_S, "<=",
               note=f"`python -m scanplan serve` until it prints its address (bare python "
               f"{bare * 1000:.0f} ms); the worker process warms up after that"),
        Result("serve.zip_s", looked, "s", ZIP_TARGET_S, "<=",
               note=f"the town's zip once the plan was shown and rendered ahead; asked for "
               f"at once after the view: {at_once:.1f} s"),
    ]


if __name__ == "__main__":
    for r in measure(quick=False):
        print(r)
