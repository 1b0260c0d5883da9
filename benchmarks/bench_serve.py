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
  address; target 2 s (bare Python's start in the note).

Run: ``python benchmarks/bench_serve.py``
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
import time

from _common import ROOT, Result

VIEW_TARGET_MS = 300.0
STARTUP_TARGET_S = 2.0
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
    with TestClient(create_app()) as client:
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


def _startup_s(repeat: int) -> tuple[float, float]:
    """Median seconds until ``serve`` prints its address, and bare Python's start."""
    starts, bare = [], []
    for _ in range(repeat):
        t = time.perf_counter()
        proc = subprocess.Popen([sys.executable, "-m", "scanplan", "serve", "--port", "0",
                                 "--tiles", "none"], cwd=ROOT, stdout=subprocess.PIPE,
                                text=True)
        assert proc.stdout is not None
        line = proc.stdout.readline()
        starts.append(time.perf_counter() - t)
        proc.terminate()
        proc.wait(30)
        assert "the page is at" in line, line
        t = time.perf_counter()
        subprocess.run([sys.executable, "-c", "pass"], check=True)
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
    ]


if __name__ == "__main__":
    for r in measure(quick=False):
        print(r)
