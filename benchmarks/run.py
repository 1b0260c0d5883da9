"""Run every benchmark of the project and print one table.

Each ``bench_*.py`` script in this folder has ``measure(quick: bool) -> list[Result]``
(:class:`_common.Result`); this runner calls them in order, prints a line describing the
machine, one table (name | measured | target | ratio | result) and the notes under it.

ratio = measured / target for an upper bound (``<=``), target / measured for a lower bound
(``>=``): **ratio ≤ 1 is a PASS** on every row, and 0.5 means twice as good as the target.

A benchmark that raises is shown as an ERROR row; the others still run.

Run::

    python benchmarks/run.py                  # full profile, several minutes
    python benchmarks/run.py --quick          # under a minute
    python benchmarks/run.py --only engine,reports --json results.json

Exit code: 0 when every row passes, 1 when any row fails or errors, 2 on bad options.
With ``--timing-advisory`` (CI on a shared machine) a missed timing target is still shown
as FAIL but does not set the exit code; an ERROR or a failed correctness row does.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import importlib
import json
import math
import os
import platform
import sys
import time
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))

from _common import Result, error_result  # noqa: E402  (needs HERE on sys.path)

Measure = Callable[[bool], list[Result]]

#: benchmark name -> module in this folder with ``measure(quick)``; the run order.
BENCHMARKS: dict[str, str] = {
    "engine": "bench_engine",
    "resolving_power": "bench_resolving_power",
    "norms_import": "bench_norms_import",
    "reports": "bench_reports",
    "plan_batch": "bench_plan_batch",
    "fast_reports": "bench_fast_reports",
    "help": "bench_help",
    "terrain": "bench_terrain",
    "terrain_block": "bench_terrain_block",
    "flight_layout": "bench_flight_layout",
    "plan_warm": "bench_plan_warm",
    "hostile_gis": "bench_hostile_gis",
    "sweep": "bench_sweep",
    "serve": "bench_serve",
    "page": "bench_page",
}

RATIO_FOOTNOTE = (
    "ratio = measured/target for '<=' targets, target/measured for '>=' targets: "
    "ratio <= 1 is a PASS."
)


def _load(module: str) -> Measure:
    """``measure`` of the benchmark module ``module`` (imported on first use)."""
    return importlib.import_module(module).measure


def default_benchmarks() -> dict[str, Measure]:
    """Every benchmark of the project as ``{name: measure}``, in run order.

    Returns
    -------
    dict
        Name to a callable ``measure(quick)``; the module is imported only when it is
        called, so a benchmark whose imports fail becomes an ERROR row, not a crash.
    """
    return {name: (lambda quick, m=module: _load(m)(quick)) for name, module in
            BENCHMARKS.items()}


def machine_info() -> dict[str, Any]:
    """What the numbers were measured on.

    Returns
    -------
    dict
        ``python``, ``platform``, ``machine``, ``cpus``, ``numpy``, ``load_average`` (1, 5
        and 15 min; empty where the OS has none) and ``date`` (local, ISO).
    """
    try:
        import numpy

        numpy_version = numpy.__version__
    except ImportError:  # pragma: no cover - numpy is a dependency
        numpy_version = "not installed"
    try:
        load = [round(x, 2) for x in os.getloadavg()]
    except (AttributeError, OSError):  # pragma: no cover - Windows
        load = []
    return {
        "python": platform.python_version(),
        "platform": platform.platform(),
        "machine": platform.machine(),
        "cpus": os.cpu_count(),
        "numpy": numpy_version,
        "load_average": load,
        "date": _dt.date.today().isoformat(),
    }


def machine_line(info: Mapping[str, Any]) -> str:
    """One header line from :func:`machine_info`.

    Parameters
    ----------
    info : mapping
        As returned by :func:`machine_info`.

    Returns
    -------
    str
        ``"machine: Python 3.11.7, Linux-..., 2 CPUs, numpy 2.4.6, load 0.5 0.6 0.7, ..."``.
    """
    load = " ".join(f"{x:g}" for x in info.get("load_average") or []) or "n/a"
    return (f"machine: Python {info['python']}, {info['platform']}, {info['cpus']} CPUs, "
            f"numpy {info['numpy']}, load average {load}, {info['date']}")


def fmt_number(v: float) -> str:
    """A measured value or target, short and readable (``84.2``, ``0.739``, ``3,416``).

    Parameters
    ----------
    v : float
        The number.

    Returns
    -------
    str
        Three significant digits below 100, whole numbers with thousands separators
        from 100 up, scientific notation below 0.001; ``nan`` / ``inf`` as such.
    """
    if math.isnan(v):
        return "nan"
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    if v == 0:
        return "0"
    if abs(v) < 1e-3:
        return f"{v:.1e}"
    if abs(v) >= 100:
        return f"{v:,.0f}"
    return f"{v:.3g}"


def fmt_ratio(r: float) -> str:
    """The ratio column: two decimals, or :func:`fmt_number` below 0.005.

    Parameters
    ----------
    r : float
        The row's ratio.

    Returns
    -------
    str
        ``"0.60"``, ``"1.43"``, ``"1.1e-08"``, ``"0"``, ``"nan"``, ``"inf"``.
    """
    if math.isfinite(r) and abs(r) >= 0.005:
        return f"{r:.2f}"
    return fmt_number(r)


def _with_unit(v: float, unit: str) -> str:
    text = fmt_number(v)
    return f"{text} {unit}" if unit else text


def format_table(results: Sequence[Result]) -> str:
    """The table: name | measured | target | ratio | result, aligned, plus the footnote.

    Parameters
    ----------
    results : sequence of Result
        The rows, in order.

    Returns
    -------
    str
        The header, a rule, one line per row and the ratio footnote (no trailing newline).
    """
    header = ("name", "measured", "target", "ratio", "result")
    rows = []
    for r in results:
        if r.error is not None:
            rows.append((r.name, "-", "-", "-", "ERROR"))
            continue
        rows.append((
            r.name,
            _with_unit(r.value, r.unit),
            f"{r.comparison} {_with_unit(r.target, r.unit)}",
            fmt_ratio(r.ratio),
            r.status,
        ))
    widths = [max(len(row[i]) for row in [header, *rows]) for i in range(len(header))]
    # name left-aligned, numbers right-aligned, result left-aligned
    align = ("<", ">", ">", ">", "<")

    def line(cells: Sequence[str]) -> str:
        cells = (f"{c:{a}{w}}" for c, a, w in zip(cells, align, widths, strict=True))
        return " | ".join(cells).rstrip()

    out = [line(header), "-+-".join("-" * w for w in widths)]
    out += [line(row) for row in rows]
    out.append(RATIO_FOOTNOTE)
    return "\n".join(out)


def format_notes(results: Sequence[Result]) -> str:
    """The notes under the table: one ``name: note`` (or the error) per row that has one.

    Parameters
    ----------
    results : sequence of Result
        The rows.

    Returns
    -------
    str
        ``"notes:"`` and one indented line per row; empty when no row has a note.
    """
    lines = []
    for r in results:
        text = f"ERROR {r.error}" if r.error is not None else r.note
        if text:
            lines.append(f"  {r.name}: {text}")
    return "\n".join(["notes:", *lines]) if lines else ""


def exit_code(results: Sequence[Result], timing_advisory: bool = False) -> int:
    """0 when every row passed, else 1 (a failure, an error, or no rows at all).

    Parameters
    ----------
    results : sequence of Result
        The rows.
    timing_advisory : bool
        Let a missed *timing* target pass (it is still shown as FAIL): for CI on a shared
        machine, where load, not the code, decides a wall time. Errors and correctness
        rows (``timing=False``) still give 1.

    Returns
    -------
    int
        The process exit code.
    """
    if not results:
        return 1
    binding = [r for r in results
               if not (timing_advisory and r.timing and r.error is None)]
    return 0 if all(r.passed for r in binding) else 1


def run_benchmarks(benchmarks: Mapping[str, Measure], quick: bool,
                   progress: Callable[[str], None] | None = None) -> list[Result]:
    """Call every ``measure(quick)``; a benchmark that raises becomes one ERROR row.

    Parameters
    ----------
    benchmarks : mapping
        Name to ``measure`` callable, in run order.
    quick : bool
        Passed to each ``measure``.
    progress : callable, optional
        Called with a short line before and after each benchmark (e.g. ``print`` to
        stderr).

    Returns
    -------
    list of Result
        All rows, in order.
    """
    results: list[Result] = []
    for name, measure in benchmarks.items():
        if progress:
            progress(f"running {name} ...")
        t0 = time.perf_counter()
        try:
            rows = list(measure(quick))
            if not rows:
                raise RuntimeError("measure() returned no results")
            for row in rows:
                if not isinstance(row, Result):
                    raise TypeError(f"measure() returned {type(row).__name__}, not Result")
        except Exception as exc:  # shown as an ERROR row; the other benchmarks still run
            rows = [error_result(name, exc)]
        results.extend(rows)
        if progress:
            progress(f"  {name} done in {time.perf_counter() - t0:.1f} s")
    return results


def _parse_only(text: str, known: Sequence[str]) -> list[str]:
    names = [n.strip() for n in text.split(",") if n.strip()]
    unknown = [n for n in names if n not in known]
    if not names or unknown:
        raise ValueError(
            f"unknown benchmark {', '.join(unknown) or repr(text)}; "
            f"choose from {', '.join(known)}"
        )
    return names


def main(argv: Sequence[str] | None = None,
         benchmarks: Mapping[str, Measure] | None = None) -> int:
    """Command line: parse options, run, print the table, write JSON if asked.

    Parameters
    ----------
    argv : sequence of str, optional
        The options (default: ``sys.argv[1:]``).
    benchmarks : mapping, optional
        Name to ``measure`` callable (default: :func:`default_benchmarks`); tests pass fakes.

    Returns
    -------
    int
        0 all PASS, 1 any FAIL or ERROR, 2 bad options.
    """
    benchmarks = default_benchmarks() if benchmarks is None else dict(benchmarks)
    ap = argparse.ArgumentParser(
        prog="python benchmarks/run.py",
        description="Run every benchmark of the project and print one table.",
        epilog=RATIO_FOOTNOTE,
    )
    ap.add_argument("--quick", action="store_true",
                    help="fast profile (under a minute): fewer repeats, smaller samples")
    ap.add_argument("--only", metavar="NAME[,NAME]",
                    help=f"run only these benchmarks: {', '.join(benchmarks)}")
    ap.add_argument("--timing-advisory", action="store_true",
                    help="exit 0 although a timing target is missed (shown as FAIL); errors "
                    "and correctness rows still exit 1 — for CI on a shared machine")
    ap.add_argument("--json", metavar="FILE", type=Path,
                    help="also write the machine and the rows as JSON to FILE")
    try:
        args = ap.parse_args(argv)
    except SystemExit as exc:  # argparse exits 2 on bad options, 0 on --help
        return int(exc.code or 0)
    if args.only is not None:
        try:
            names = _parse_only(args.only, list(benchmarks))
        except ValueError as exc:
            print(f"{ap.prog}: error: --only: {exc}", file=sys.stderr)
            return 2
        benchmarks = {n: benchmarks[n] for n in benchmarks if n in names}

    info = machine_info()
    profile = "quick" if args.quick else "full"
    print(machine_line(info))
    print(f"profile: {profile}", flush=True)
    t0 = time.perf_counter()
    results = run_benchmarks(benchmarks, args.quick,
                             progress=lambda s: print(s, file=sys.stderr, flush=True))
    wall = time.perf_counter() - t0
    code = exit_code(results, timing_advisory=args.timing_advisory)
    print()
    print(format_table(results))
    notes = format_notes(results)
    if notes:
        print()
        print(notes)
    print()
    print(f"{sum(r.passed for r in results)}/{len(results)} PASS in {wall:.1f} s")
    if args.json is not None:
        payload = {"machine": info, "profile": profile, "wall_s": wall, "exit_code": code,
                   "results": [r.as_dict() for r in results]}
        args.json.write_text(json.dumps(payload, indent=2, ensure_ascii=False) + "\n",
                             encoding="utf-8")
    return code


if __name__ == "__main__":
    raise SystemExit(main())
