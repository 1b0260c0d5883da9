"""The benchmark runner's table, notes, options and exit codes, with fake results.

Nothing here times anything: speed is measured by ``python benchmarks/run.py`` itself.
"""

from __future__ import annotations

import ast
import json
import math
from pathlib import Path

import pytest
from helpers import script_module

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"


@pytest.fixture(scope="module")
def runner():
    with script_module(BENCHMARKS, "run") as module:
        yield module


@pytest.fixture(scope="module")
def Result(runner):
    return runner.Result


def _fake(*rows):
    """A ``measure(quick)`` returning ``rows`` and recording the ``quick`` it got."""
    calls = []

    def measure(quick):
        calls.append(quick)
        return list(rows)

    measure.calls = calls
    return measure


def _boom(quick):
    raise RuntimeError("no fonts\nsecond line")


# --- Result: ratio convention ------------------------------------------------------

def test_ratio_is_share_of_target_for_both_directions(Result):
    upper = Result("t", 1.0, "s", 4.0, "<=")
    lower = Result("s", 200.0, "x", 50.0, ">=")
    assert upper.ratio == pytest.approx(0.25) and upper.passed and upper.status == "PASS"
    assert lower.ratio == pytest.approx(0.25) and lower.passed
    slow = Result("t", 5.0, "s", 4.0, "<=")
    weak = Result("s", 25.0, "x", 50.0, ">=")
    assert slow.ratio == pytest.approx(1.25) and not slow.passed and slow.status == "FAIL"
    assert weak.ratio == pytest.approx(2.0) and not weak.passed


def test_ratio_edge_cases(Result):
    assert Result("a", 0.0, "lines/mm", 0.01, "<=").ratio == 0.0
    assert Result("a", 4.0, "s", 4.0, "<=").passed  # on the bound passes
    nan = Result("a", math.nan, "s", 4.0, "<=")
    assert math.isnan(nan.ratio) and not nan.passed
    assert Result("a", math.inf, "lines/mm", 0.01, "<=").status == "FAIL"
    assert Result("s", 0.0, "x", 50.0, ">=").ratio == math.inf
    with pytest.raises(ValueError, match="comparison"):
        Result("a", 1.0, "s", 2.0, "<")


def test_as_dict_is_json_ready(Result):
    d = Result("a", math.inf, "s", 2.0, "<=", note="n").as_dict()
    assert d["value"] is None and d["ratio"] is None and d["status"] == "FAIL"
    json.dumps(d, allow_nan=False)


# --- table and notes ---------------------------------------------------------------

def test_table_columns_are_aligned_and_carry_the_verdicts(runner, Result):
    rows = [
        Result("engine", 1.79, "x", 3.0, "<=", note="bare numpy 50 ms"),
        Result("resolving_power.speedup", 4064.0, "x", 50.0, ">="),
        Result("reports", 5.72, "s", 4.0, "<="),
        runner.error_result("plan_batch", RuntimeError("boom")),
    ]
    text = runner.format_table(rows)
    lines = text.splitlines()
    header, rule, *body, footnote = lines
    assert [c.strip() for c in header.split("|")] == [
        "name", "measured", "target", "ratio", "result"]
    # every separator sits in the same column on the header, the rule and each row
    bars = [i for i, ch in enumerate(header) if ch == "|"]
    assert [i for i, ch in enumerate(rule) if ch == "+"] == bars
    for line in body:
        assert [i for i, ch in enumerate(line) if ch == "|"] == bars
        assert line == line.rstrip()
    cells = [[c.strip() for c in line.split("|")] for line in body]
    assert cells[0] == ["engine", "1.79 x", "<= 3 x", "0.60", "PASS"]
    assert cells[1] == ["resolving_power.speedup", "4,064 x", ">= 50 x", "0.01", "PASS"]
    assert cells[2] == ["reports", "5.72 s", "<= 4 s", "1.43", "FAIL"]
    assert cells[3] == ["plan_batch", "-", "-", "-", "ERROR"]
    assert "ratio <= 1 is a PASS" in footnote


def test_number_formats(runner):
    assert runner.fmt_number(84.23) == "84.2"
    assert runner.fmt_number(0.7391) == "0.739"
    assert runner.fmt_number(3416.2) == "3,416"
    assert runner.fmt_number(1.11e-10) == "1.1e-10"
    assert runner.fmt_number(0.0) == "0"
    assert runner.fmt_number(math.inf) == "inf"
    assert runner.fmt_ratio(1.1e-8) == "1.1e-08"
    assert runner.fmt_ratio(0.5964) == "0.60"


def test_notes_list_notes_and_errors(runner, Result):
    rows = [Result("engine", 1.0, "x", 3.0, "<=", note="baseline text"),
            Result("quiet", 1.0, "x", 3.0, "<="),
            runner.error_result("reports", OSError("no fonts\nmore"))]
    notes = runner.format_notes(rows).splitlines()
    assert notes == ["notes:", "  engine: baseline text", "  reports: ERROR OSError: no fonts"]
    assert runner.format_notes([Result("q", 1.0, "x", 3.0, "<=")]) == ""


# --- exit codes and options ----------------------------------------------------------

def test_exit_code_logic(runner, Result):
    ok = Result("a", 1.0, "s", 2.0, "<=")
    bad = Result("b", 3.0, "s", 2.0, "<=")
    assert runner.exit_code([ok, ok]) == 0
    assert runner.exit_code([ok, bad]) == 1
    assert runner.exit_code([ok, runner.error_result("c", ValueError("x"))]) == 1
    assert runner.exit_code([]) == 1


def test_main_all_pass_exit_0_and_quick_is_passed_on(runner, Result, capsys, tmp_path):
    a = _fake(Result("a", 1.0, "s", 2.0, "<=", note="first"))
    b = _fake(Result("b.x", 60.0, "x", 50.0, ">="), Result("b.y", 0.0, "mm", 0.1, "<="))
    out_json = tmp_path / "r.json"
    code = runner.main(["--quick", "--json", str(out_json)], benchmarks={"a": a, "b": b})
    assert code == 0
    assert a.calls == [True] and b.calls == [True]
    out = capsys.readouterr().out
    assert out.startswith("machine: Python ")
    assert "profile: quick" in out and "3/3 PASS" in out and "  a: first" in out
    data = json.loads(out_json.read_text(encoding="utf-8"))
    assert data["exit_code"] == 0 and data["profile"] == "quick"
    assert [r["name"] for r in data["results"]] == ["a", "b.x", "b.y"]
    assert {"python", "platform", "cpus", "numpy"} <= set(data["machine"])


def test_main_a_failure_exits_1(runner, Result, capsys):
    fast = _fake(Result("a", 1.0, "s", 2.0, "<="))
    slow = _fake(Result("b", 3.0, "s", 2.0, "<="))
    assert runner.main([], benchmarks={"a": fast, "b": slow}) == 1
    assert fast.calls == [False]
    assert "1/2 PASS" in capsys.readouterr().out


def test_main_a_raising_benchmark_is_an_error_row_not_a_crash(runner, Result, capsys):
    after = _fake(Result("after", 1.0, "s", 2.0, "<="))
    code = runner.main([], benchmarks={"boom": _boom, "after": after})
    assert code == 1
    assert after.calls == [False]  # the rest still ran
    out = capsys.readouterr().out
    row = next(line for line in out.splitlines() if line.startswith("boom "))
    assert row.rstrip().endswith("ERROR")
    assert "boom: ERROR RuntimeError: no fonts" in out


def test_main_only_selects_by_name(runner, Result, capsys):
    a = _fake(Result("a", 1.0, "s", 2.0, "<="))
    b = _fake(Result("b", 1.0, "s", 2.0, "<="))
    assert runner.main(["--only", "b"], benchmarks={"a": a, "b": b}) == 0
    assert a.calls == [] and b.calls == [False]


@pytest.mark.parametrize("only", ["nope", "a,nope", ","])
def test_main_only_rejects_unknown_names_with_exit_2(runner, Result, capsys, only):
    a = _fake(Result("a", 1.0, "s", 2.0, "<="))
    assert runner.main(["--only", only], benchmarks={"a": a}) == 2
    assert a.calls == []
    assert "--only" in capsys.readouterr().err


def test_main_only_knows_the_real_benchmark_names(runner, capsys):
    # the real registry, but an unknown name: rejected before anything is imported or run
    assert runner.main(["--only", "engine,warp_drive"]) == 2
    err = capsys.readouterr().err
    assert "warp_drive" in err and "plan_batch" in err


def test_bad_option_exits_2(runner, capsys):
    assert runner.main(["--no-such-option"], benchmarks={}) == 2


def test_every_registered_module_has_a_measure_entry(runner):
    # read, not imported: importing would pull in the whole package and time nothing anyway
    for module in runner.BENCHMARKS.values():
        tree = ast.parse((BENCHMARKS / f"{module}.py").read_text(encoding="utf-8"))
        functions = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}
        assert "measure" in functions, module
        assert [a.arg for a in functions["measure"].args.args] == ["quick"], module


def test_timing_advisory_lets_only_timing_rows_miss(runner, Result):
    """--timing-advisory: a missed time passes the exit code; an error or a failed
    correctness row does not."""
    slow = Result("x", 2.0, "s", 1.0, "<=")
    wrong = Result("y.agreement", 1.0, "lines/mm", 0.01, "<=", timing=False)
    broken = runner.error_result("z", RuntimeError("boom"))
    assert runner.exit_code([slow]) == 1
    assert runner.exit_code([slow], timing_advisory=True) == 0
    assert runner.exit_code([slow, wrong], timing_advisory=True) == 1
    assert runner.exit_code([slow, broken], timing_advisory=True) == 1
