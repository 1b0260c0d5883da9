"""Every norm figure says what it is — norm, recommendation, estimate or practice — and a
project may set a recommendation aside with a reason that the specification prints."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.norms import load_norm_set
from scanplan.project.design import design_dict
from scanplan.project.file import parse_project
from scanplan.project.jobs import uav_job
from scanplan.project.spec import plan_project

ROOT = Path(__file__).resolve().parent.parent
AFS = ROOT / "examples" / "uav-town-2000-afs.toml"
REASONS = ('[norms.gsd_limits]\nreason = "the customer accepts 16 cm"\n\n'
           '[norms.block_relief]\nreason = "one orthophoto over a DEM"\n\n')


def test_the_bundled_figures_carry_their_status():
    ns = load_norm_set()
    assert {g.status for g in ns.gsd_limits} == {"recommendation"}       # Appendix Б
    by_scale = {o.map_scale: o.status for o in ns.objects}
    assert by_scale[500] == "estimate" and by_scale[2000] == "norm"
    assert by_scale[1000] == "estimate"  # Table 3 of Miheeva & Ilushenko has no 1:1000 row
    st = ns.parameter_status
    assert st["min_sun_elevation_deg"] == "practice"
    # a requirement of ГОСТ Р 59328's body with an exception, in the second draft's wording
    assert st["block_relief_flat_pct"] == "requirement_draft"
    assert st["image_measurement_px"] == "estimate"
    assert st["uav_max_height_m"] == "norm"
    assert set(st) == set(ns.parameters) and set(st.values()) <= {
        "norm", "recommendation", "estimate", "practice", "requirement_draft"}
    printed = load_norm_set("gkinp-02-036-02-printed")
    assert printed.parameter_status["planimetric_accuracy_mm"] == "norm"


def test_a_project_sets_table_b1_aside_with_its_reason():
    job = uav_job(camera="dji-zenmuse-p1-35", height_m=100.0, map_scale=2000,
                  relief_interval_m=0.5, gsd_limit_reason="the customer accepts 16 cm")
    assert "GL" not in {x.id for x in job.plan.limits}
    kept = uav_job(camera="dji-zenmuse-p1-35", height_m=100.0, map_scale=2000,
                   relief_interval_m=0.5)
    assert "GL" in {x.id for x in kept.plan.limits}
    text = AFS.read_text(encoding="utf-8").replace("[terrain]", REASONS + "[terrain]")
    r = plan_project(parse_project(text, AFS))
    d = design_dict(r.design)
    (g,) = d["gsd_limits"]
    assert g["set_aside"] == "the customer accepts 16 cm" and g["status"] == "recommendation"
    assert d["block_height"]["set_aside"] == "one orthophoto over a DEM"
    notes = [w for w in r.warnings if w.code == "recommendation_set_aside"]
    assert len(notes) == 2
    assert any("the customer accepts 16 cm" in w.text("ru") for w in notes)
    assert "block_split" not in {w.code for w in r.warnings}


def test_the_workbook_prints_status_and_reason(tmp_path):
    openpyxl = pytest.importorskip("openpyxl")
    text = AFS.read_text(encoding="utf-8").replace("[terrain]", REASONS + "[terrain]")
    text = text.replace('locale = "ru"', 'locale = "en"')
    path = tmp_path / "p.toml"
    path.write_text(text, encoding="utf-8")
    res = CliRunner().invoke(main, ["plan", str(path), "--xlsx", str(tmp_path / "s.xlsx")])
    assert res.exit_code == 0, res.output
    wb = openpyxl.load_workbook(tmp_path / "s.xlsx")
    cells = [str(c) for ws in wb.worksheets for row in ws.iter_rows(values_only=True)
             for c in row if c]
    joined = "\n".join(cells)
    gsd_norm = next(c for c in cells if "Table B.1 (recommendation)" in c
                    and "set aside by the project: the customer accepts 16 cm" in c)
    assert gsd_norm
    assert "set aside by the project: one orthophoto over a DEM" in joined
    assert "(practice)" in joined and "(estimate)" in joined and "(norm)" in joined


@pytest.mark.parametrize("value", ['""', '"  "'])
def test_an_empty_reason_is_refused(tmp_path, value):
    text = AFS.read_text(encoding="utf-8").replace(
        "[terrain]", f"[norms.gsd_limits]\nreason = {value}\n\n[terrain]")
    path = tmp_path / "p.toml"
    path.write_text(text, encoding="utf-8")
    res = CliRunner().invoke(main, ["plan", str(path)])
    assert res.exit_code == 2 and "Traceback" not in res.output
    assert "reason" in res.stderr
