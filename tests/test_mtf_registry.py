"""The MTF component registry: a component is one record plus one function.

A dummy component (a constant factor 0.9, like a second haze coefficient) registered in a
fixture flows into the resolving power, into ``scanplan uav --json`` and into the workbook's
MTF sheet, and is gone again after the fixture unregisters it.
"""

from __future__ import annotations

import io
import json

import numpy as np
import openpyxl
import pytest
from click.testing import CliRunner

import scanplan.core.mtf as M
from scanplan.cli.main import main
from scanplan.project.jobs import uav_job
from scanplan.reports import ReportMeta
from scanplan.reports.excel import render_xlsx

FACTOR = 0.9
CAMERA = M.Camera(6.4, 50.0, 8.0, 36.0, 24.0)
FLIGHT = M.Flight(300.0, 25.0, 1e-3, 0.65)
UAV_ARGS = ["uav", "--camera", "canon-eos-5d-mark-ii-50", "--f-number", "8", "--height-m",
            "300", "--map-scale", "1:2000", "--relief", "0.5", "--json"]


def _prepare_dummy(setup: M.Setup) -> M.Term:
    return M.Term(lambda n, c: c, {"c": np.full(np.shape(setup.pixel_um), FACTOR)})


@pytest.fixture
def dummy():
    M.register(M.Component("dummy", "atmosphere", _prepare_dummy,
                           {"en": "Test factor", "ru": "Тестовый множитель"}, "a test"))
    try:
        yield "dummy"
    finally:
        M.unregister("dummy")


def _uav_json() -> dict:
    r = CliRunner().invoke(main, UAV_ARGS)
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


def test_builtin_registry_is_the_seed_chain():
    assert M.component_names() == M.COMPONENTS == (
        "haze", "turbulence", "lens", "pixel", "charge_transfer", "diffusion",
        "linear_motion", "random_motion")
    assert {c.family for c in M.REGISTRY} == {"atmosphere", "lens", "sensor", "motion"}
    assert all(c.label["en"] and c.label["ru"] for c in M.REGISTRY)


def test_register_refuses_a_duplicate_or_a_missing_locale(dummy):
    with pytest.raises(ValueError, match="already registered"):
        M.register(M.Component("dummy", "x", _prepare_dummy, {"en": "a", "ru": "б"}, "t"))
    with pytest.raises(ValueError, match="'ru' label"):
        M.register(M.Component("other", "x", _prepare_dummy, {"en": "a"}, "t"))


def test_dummy_component_flows_into_the_resolving_power(dummy):
    grid = np.linspace(0.0, 60.0, 7)
    comps = M.component_mtfs(grid, CAMERA, FLIGHT)
    assert list(comps)[-1] == "dummy"
    np.testing.assert_array_equal(comps["dummy"], np.full(7, FACTOR))
    with_dummy = float(M.resolving_power(CAMERA, FLIGHT).r_lpmm)
    # the same chain with the factor folded into the haze coefficient (0.9 · 0.9)
    folded = float(M.resolving_power(CAMERA, FLIGHT, M.Atmosphere(contrast_coefficient=0.81),
                                     disable=["dummy"]).r_lpmm)
    assert with_dummy == pytest.approx(folded, rel=1e-9)
    assert with_dummy < float(M.resolving_power(CAMERA, FLIGHT, disable=["dummy"]).r_lpmm)


def test_dummy_component_flows_into_uav_json(dummy):
    doc = _uav_json()
    mc = doc["mtf_centre"]
    assert mc["dummy"] == pytest.approx([FACTOR] * len(mc["freq_lpmm"]))
    M.unregister("dummy")
    try:
        plain = _uav_json()
    finally:
        M.register(M.Component("dummy", "atmosphere", _prepare_dummy,
                               {"en": "Test factor", "ru": "Тестовый множитель"}, "a test"))
    assert "dummy" not in plain["mtf_centre"]
    assert doc["resolving_power_lpmm"] < plain["resolving_power_lpmm"]
    system = np.array(mc["system"])
    np.testing.assert_allclose(system, FACTOR * np.array(plain["mtf_centre"]["system"]),
                               rtol=1e-12)


@pytest.mark.parametrize(("locale", "label"), [("en", "Test factor"),
                                                ("ru", "Тестовый множитель")])
def test_dummy_component_flows_into_the_workbook(dummy, locale, label):
    job = uav_job(camera="canon-eos-5d-mark-ii-50", f_number=8, height_m=300,
                  map_scale=2000, relief_interval_m=0.5)
    book = openpyxl.load_workbook(io.BytesIO(render_xlsx(uav=job,
                                                         meta=ReportMeta(locale=locale))))
    ws = book.worksheets[[s.title for s in book.worksheets].index("MTF" if locale == "en"
                                                                   else "ФПМ")]
    heads = [c.value for c in ws[1]]
    assert label in heads and "dummy" not in heads
    col = heads.index(label) + 1
    n = len(job.plan.mtf_centre["freq_lpmm"])
    assert [ws.cell(r, col).value for r in range(2, n + 2)] == pytest.approx([FACTOR] * n)


def test_unregistered_dummy_is_gone():
    assert "dummy" not in M.component_names()
    with pytest.raises(ValueError, match="disable must name components"):
        M.component_mtfs([0.0], CAMERA, FLIGHT, disable=["dummy"])
