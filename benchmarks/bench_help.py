"""Benchmark: ``scanplan --help`` over a bare ``python -c pass`` (issue 15).

Both are whole fresh processes; the row is the difference of the medians of ``repeat``
runs each (wall time; the note gives the CPU time too, which load does not inflate).
Target: at most 0.1 s over bare Python, which needs
``--help`` not to import numpy or the engine (the lazy imports of ``scanplan`` and
``scanplan.cli``); a second, correctness row checks that numpy is not imported.

Run: ``python benchmarks/bench_help.py``
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time

from _common import Result

TARGET_S = 0.1
HELP = "import sys; from scanplan.cli import main; sys.argv = ['scanplan', '--help']; main()"


def _wall(code: str, repeat: int) -> tuple[float, float]:
    """Median wall time and median CPU time (user + system) of ``repeat`` processes [s]."""
    import resource

    times, cpus = [], []
    for _ in range(repeat):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], capture_output=True, check=False)
        times.append(time.perf_counter() - start)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpus.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    return statistics.median(times), statistics.median(cpus)


def measure(quick: bool) -> list[Result]:
    """The help's time over bare Python, and whether it imported numpy."""
    repeat = 5 if quick else 11
    bare, bare_cpu = _wall("pass", repeat)
    helped, helped_cpu = _wall(HELP, repeat)
    probe = subprocess.run(
        [sys.executable, "-c", HELP.replace("main()", "") + "import contextlib\n"
         "with contextlib.suppress(SystemExit): main()\nprint('numpy' in sys.modules)"],
        capture_output=True, text=True, check=False)
    numpy = probe.stdout.strip().endswith("True")
    return [
        Result("help.over_bare_python", helped - bare, "s", TARGET_S, "<=",
               note=f"help over bare python: median of {repeat} fresh processes each "
               f"(bare {bare * 1000:.0f} ms, help {helped * 1000:.0f} ms wall; CPU time "
               f"bare {bare_cpu * 1000:.0f} ms, help {helped_cpu * 1000:.0f} ms: on a loaded "
               "machine the wall time waits for a core)"),
        Result("help.numpy_imported", float(numpy), "", 0.0, "<=", timing=False,
               note="1 if `scanplan --help` imported numpy"),
    ]


if __name__ == "__main__":
    for r in measure(quick=False):
        print(r)
