"""The altitude ceiling of flights without an airspace-use permission: strictly below 150 m
(Federal Rules for the Use of the Airspace as amended by Decree No. 1016 of 21.06.2023), and
the conditions printed with the plan (settlements: para. 49; uncontrolled aerodromes)."""

from __future__ import annotations

import pytest

from scanplan.i18n.messages import localize
from scanplan.norms import load_norm_set
from scanplan.project.jobs import uav_job
from scanplan.reports.references import Bibliography

CAM = dict(camera="dji-mavic-3e", speed_ms=10.0, exposure_s=0.001)


def _codes(plan) -> set[str]:
    return {w.code for w in plan.warnings}


def test_exactly_150_m_is_not_below_150_m():
    at = uav_job(**CAM, height_m=150.0).plan
    assert "airspace_not_below" in _codes(at)
    w = next(x for x in at.warnings if x.code == "airspace_not_below")
    assert "below 150 m" in w.text("en") and "менее 150" in w.text("ru")
    below = uav_job(**CAM, height_m=149.0).plan
    assert "airspace_not_below" not in _codes(below)
    # with a +10 % tolerance, 137 m is flown up to 150.7 m
    assert "airspace_not_below" in _codes(uav_job(**CAM, height_m=137.0,
                                                  height_tolerance_pct=10.0).plan)


def test_recommended_height_stays_below_the_ceiling():
    """Without a planned height the flight is planned at the maximum rounded down to 5 m:
    145 m, not 150 m, under the norm set's ceiling."""
    job = uav_job(**CAM, map_scale=10000, relief_interval_m=5.0)
    assert job.plan.binding == "HC"
    assert job.plan.max_height_m < 150.0
    assert job.plan.max_height_m == pytest.approx(150.0)
    assert job.plan.heights_m["planned"] == 145.0
    assert "airspace_not_below" not in _codes(job.plan)


def test_a_projects_own_ceiling_is_inclusive():
    plan = uav_job(**CAM, height_m=150.0, max_height_m=150.0).plan
    assert not {"airspace_not_below", "airspace_conditions"} & _codes(plan)
    hc = next(x for x in plan.limits if x.id == "HC")
    assert hc.max_height_m == 150.0


def test_conditions_are_printed_with_the_plan():
    plan = uav_job(**CAM, height_m=100.0).plan
    w = next(x for x in plan.warnings if x.code == "airspace_conditions")
    assert w.severity == "info"
    en, ru = w.text("en"), w.text("ru")
    km = load_norm_set().parameters["uav_uncontrolled_aerodrome_km"]
    assert km == 5
    assert "No. 1016 of 21.06.2023" in en and "01.03.2024" in en
    # the conditions are data (norms/catalogue/airspace-conditions.csv), their wording's
    # date printed; «контрольные точки аэродромов» are reference points, not boundaries
    assert "10 km from the reference points of aerodromes and 2 km from landing sites" in en
    assert "boundaries" not in en and "границ" not in ru
    assert "25 km of the state border" in en and "0.25 kg" in en
    assert "settlement" in en and "local government" in en and "para. 49" in en
    assert "№\u00a01016" in ru and "населённым пунктом" in ru and "п. 49" in ru
    assert "10\u00a0км от контрольных точек аэродромов" in ru
    assert "as secondary sources describe it" in en
    hc = next(x for x in plan.limits if x.id == "HC")
    assert "below 150 m" in localize(hc.reason, "en")
    assert "менее 150" in localize(hc.reason, "ru")


def test_aircraft_have_no_uav_conditions():
    plan = uav_job(camera="ultracam-eagle-80", f_number=5.6, speed_ms=70.0,
                   height_m=2000.0).plan
    assert not {"airspace_not_below", "airspace_conditions"} & _codes(plan)


def test_reference_cites_the_amendment():
    bib = Bibliography("en")
    cited = bib.cite("Federal Rules for the Use of the Airspace 2010")
    text = " ".join(t for _, t in bib.entries())
    assert cited.startswith("[1]")
    assert "Decree No. 1016 of 21 June 2023" in text and "52(3)" in text


def test_conditions_come_from_the_data_with_their_wording_date():
    """An update of the rules is an edit of the data file: every condition has a source, a
    wording date and a status, and the plan prints that date."""
    from scanplan.norms.airspace import airspace_conditions

    conds = airspace_conditions()
    assert {c.id for c in conds} >= {"vlos", "below_150", "below_100", "border", "settlement"}
    assert all(c.source and c.status in ("norm", "secondary") for c in conds)
    date = max(c.wording_date for c in conds)
    plan = uav_job(**CAM, height_m=100.0).plan
    en = next(x for x in plan.warnings if x.code == "airspace_conditions").text("en")
    y, m, d = date.split("-")
    assert f"in force from {d}.{m}.{y}" in en
    for c in conds:
        assert c.text_en.replace("{ceiling}", "150") in en
