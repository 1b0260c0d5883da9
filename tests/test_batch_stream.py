"""A text-mode batch keeps no project's result: each worker sends back its summary-table
row and warnings as text, as ``--json`` streams its documents (memory stays flat for
thousands of projects; the measured peak is in docs/reliability.md)."""

from __future__ import annotations

import gc
import importlib
import shutil
import weakref
from pathlib import Path

from click.testing import CliRunner

from scanplan.project.spec import PlanResult

cli_main = importlib.import_module("scanplan.cli.main")

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def test_the_worker_sends_text_not_the_result(tmp_path):
    shutil.copy(EXAMPLES / "instruction-2000-film.toml", tmp_path / "a.toml")
    path = str(tmp_path / "a.toml")
    _, outcome, payload, _ = cli_main._batch_worker((path, None, "a", [path], False, False, None,
                                                     None))
    assert outcome == "ok"
    text, doc, row = payload
    row_cells, warnings = text
    assert doc is None and all(isinstance(c, str) for c in row_cells)
    assert row_cells[0] == "a.toml" and row_cells[1] == "1:2000"
    assert isinstance(warnings, str) and isinstance(row, dict)


def test_a_text_batch_keeps_no_result_alive(tmp_path, monkeypatch):
    """Every PlanResult made during a text batch is gone before the summary is printed."""
    for name in ("a", "b", "c"):
        shutil.copy(EXAMPLES / "instruction-2000-film.toml", tmp_path / f"{name}.toml")
    alive: list[weakref.ref] = []
    real = cli_main._run_project

    def tracked(*args, **kw):
        result, tables = planned = real(*args, **kw)
        assert isinstance(result, PlanResult) and tables.spec is result
        alive.append(weakref.ref(result))
        return planned

    monkeypatch.setattr(cli_main, "_run_project", tracked)
    import scanplan.reports.text as text_mod

    real_table = text_mod.batch_table
    seen = []

    def table(rows, failed):
        gc.collect()
        seen.append(sum(ref() is not None for ref in alive))
        return real_table(rows, failed)

    monkeypatch.setattr(text_mod, "batch_table", table)
    r = CliRunner().invoke(cli_main.main, ["plan", str(tmp_path), "--jobs", "1"])
    assert r.exit_code == 0, r.output
    assert len(alive) == 3 and seen == [0]
    assert "a.toml" in r.stdout and "c.toml" in r.stdout
