"""The plan a crew lead would choose (docs/plan-choice.md): the plans compared for a UAV
block — line direction, altitude mode, the block split by ground height — costed with the
flying time of their own sorties, the one with the least flying time that meets every
constraint recommended, the project's pinned choices kept and priced; layout and height
held to a fixed point."""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

import numpy as np
import pytest
import shapely
from click.testing import CliRunner
from terrain_helpers import write_dem

from scanplan.cli.main import main
from scanplan.geo.direction import long_axis_deg
from scanplan.project.file import load_project, parse_project
from scanplan.project.flightplan import uav_flight_figures
from scanplan.project.spec import plan_project
from scanplan.project.terrainplan import Settled, settle

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
VALLEY = EXAMPLES / "uav-town-valley-2000.toml"
AFS = EXAMPLES / "uav-town-2000-afs.toml"
TOWN = EXAMPLES / "uav-town-2000.toml"
VALLEY_PHOTOS_BEFORE = 16_442  # one altitude over the valley, the example before this choice


@pytest.fixture(scope="module")
def valley():
    return plan_project(load_project(VALLEY))


@pytest.fixture(scope="module")
def afs():
    return plan_project(load_project(AFS))


# --- the valley: the acceptance ----------------------------------------------------------

def test_the_valley_recommends_half_the_photos_with_every_constraint_held(valley):
    """Bug: the valley example recommended one altitude at 70 m, 16,442 photos, 2.2 TB, while
    following the terrain meets every constraint at 115 m. Now the plans are compared and the
    least flying time meeting every constraint is flown: at most half the photos."""
    u = valley.uav
    chosen = next(a for a in u.alternatives if a.recommended)
    assert chosen.feasible and not chosen.rejected_because and not chosen.estimate
    assert chosen.n_photos == u.job.layout.n_photos == u.job.plan.flight["photos"]
    assert chosen.n_photos <= 0.5 * VALLEY_PHOTOS_BEFORE
    assert u.terrain.mode == chosen.mode == "follow"
    # its figures are the layout's own flight figures (sorties, flying time with the turns)
    fig = uav_flight_figures(u.job.plan, u.job.layout)
    assert (chosen.flight_time_s, chosen.n_sorties) == (fig["flight_time_s"], fig["sorties"])
    # every constraint held: the worst photo within every limit, the one-height rule
    # waived by following the relief, the overlaps within the allowance
    assert u.terrain.max_height_m >= u.recommended_height_m - 1e-9
    assert valley.design.block_waived
    # the least flying time among the plans meeting every constraint
    ok = [a for a in u.alternatives if a.feasible and not a.estimate]
    assert chosen.flight_time_s == min(a.flight_time_s for a in ok)
    # and the one altitude of before is there, with what it misses
    one = next(a for a in u.alternatives if a.mode == "constant" and a.direction == "auto")
    assert one.n_photos == VALLEY_PHOTOS_BEFORE and not one.feasible
    assert one.rejected_because[0].code == "plan_choice.block"


def test_the_valley_compares_directions_and_modes(valley):
    """Every mode (constant, strip, follow) along the least flight length, the long axis
    and the direction of the least relief per strip (45°, along the valley); the split
    by ground height as an estimate."""
    alts = valley.uav.alternatives
    kinds = {(a.mode, a.direction) for a in alts if not a.estimate}
    for mode in ("constant", "strip", "follow"):
        for direction in ("auto", "long_axis", "relief"):
            assert (mode, direction) in kinds
    relief = next(a for a in alts if a.direction == "relief")
    assert abs(relief.direction_deg - 45.0) <= 2.0
    axis = next(a for a in alts if a.direction == "long_axis")
    assert axis.direction_deg == pytest.approx(
        long_axis_deg(valley.uav.job.layout.area.geometry))
    split = next(a for a in alts if a.parts > 1)
    assert split.estimate and not split.feasible
    assert split.rejected_because[0].code == "plan_choice.needs_parts"


def test_the_plans_compared_are_printed_everywhere(valley, tmp_path):
    """The terminal, the PDF, the workbook and JSON carry the plans side by side; the
    recommended one first; the JSON records have the interface's keys."""
    res = CliRunner().invoke(main, ["plan", str(VALLEY), "--out", str(tmp_path / "out"),
                                    "--formats", "pdf,xlsx"])
    assert res.exit_code == 0, res.output
    text = res.output
    assert "Plans compared" in text and "meets every constraint" in text
    table = text[text.index("Plans compared"):]
    first = next(line for line in table.splitlines() if line.startswith("  >"))
    assert "following the terrain" in first and "6,217" in first
    from pypdf import PdfReader

    pdf = " ".join(p.extract_text() for p in PdfReader(tmp_path / "out" / "spec.pdf").pages)
    assert "Plans compared" in pdf and "one-height rule" in pdf
    import openpyxl

    ws = openpyxl.load_workbook(tmp_path / "out" / "spec.xlsx")["Plans compared"]
    rows = list(ws.iter_rows(min_row=2, values_only=True))
    assert rows[0][0] == "following the terrain" and rows[0][4] == 6217
    assert "(recommended)" in rows[0][-1]
    doc = json.loads(CliRunner().invoke(main, ["plan", str(VALLEY), "--json"]).output)
    alts = doc["specification"]["uav"]["layout"]["alternatives"]
    for key in ("altitude_mode", "direction_deg", "height_m", "n_photos", "flight_time_s",
                "n_sorties", "feasible", "rejected_because", "recommended",
                "data_volume_bytes", "gsd_min_m", "gsd_max_m", "binding"):
        assert all(key in a for a in alts), key
    assert sum(a["recommended"] for a in alts) == 1
    assert doc["specification"]["uav"]["choice"].startswith("Of 10 plans compared")


def test_every_plan_is_costed_with_its_sorties_as_flown(valley, afs):
    """The flying time of a plan compared is its sorties' time as flown (the climb, the
    acceleration, the corners, the way back: geo/sorties.py) — the model of the plan flown —
    not its path at the cruise speed: the recommended plan's is the sum of its sorties'
    times, and every plan laid out takes longer than its path at the speed."""
    for res in (valley, afs):
        u = res.uav
        chosen = next(a for a in u.alternatives if a.recommended)
        sorties = u.job.layout.sorties
        assert chosen.n_sorties == len(sorties)
        assert chosen.flight_time_s == pytest.approx(sum(s.time_s for s in sorties))
        speed = u.job.plan.inputs.speed_ms
        laid_out = [a for a in u.alternatives if not a.estimate]
        assert laid_out
        for a in laid_out:
            assert a.flight_time_s > 1.02 * a.flight_length_m / speed, a


# --- the afs example: split and follow, priced -------------------------------------------

def test_afs_is_compared_with_its_split_and_follow_alternatives(afs):
    """Bug: uav-town-2000-afs recommended 16,796 photos, 291 min, 10 sorties, and only said
    "split into 5 parts or follow the terrain". Its ground is a range (no DEM), so one
    altitude is the only plan laid out; following the terrain and the block split into
    parts by ground height are priced from their layouts at the heights they would allow,
    and a warning names the cheaper one and what it needs."""
    alts = afs.uav.alternatives
    one = next(a for a in alts if a.recommended)
    # 341 min in 12 sorties of 30 min: the sorties' time as flown (the climb, the corners,
    # the way back), no longer the path at the speed (291 min, 10 sorties)
    assert (one.mode, one.n_photos, one.n_sorties) == ("constant", 16_796, 12)
    assert round(one.flight_time_s / 60) == 341 and not one.feasible
    follow = next(a for a in alts if a.mode == "follow")
    split = next(a for a in alts if a.parts > 1)
    for alt in (follow, split):
        assert alt.estimate and alt.flight_time_s < one.flight_time_s
        assert alt.n_photos < one.n_photos and alt.n_sorties <= one.n_sorties
    assert follow.rejected_because[0].code == "plan_choice.needs_dem.follow"
    # the fewest parts that meet the rule at their own height: 3 bands of 18.3 m under
    # 130 m (15 % hilly: 19.5 m allowed; 2 bands of 27.5 m would need 183 m)
    assert (split.parts, split.height_m) == (3, 130.0)
    w = next(w for w in afs.warnings if w.code == "plan_choice_needs")
    assert w.severity == "warning" and "[terrain] dem" in w.message
    assert "огибание рельефа" in w.text("ru")


# --- the project's pins --------------------------------------------------------------------

def test_a_pinned_direction_is_kept_and_the_others_priced(tmp_path):
    """``[area] direction_deg`` given: the plan flies it; the least flight length and the
    long axis are compared beside it (flat ground: the flying time decides)."""
    shutil.copytree(EXAMPLES / "areas", tmp_path / "areas")
    p = tmp_path / "town.toml"
    p.write_text(TOWN.read_text(encoding="utf-8").replace('direction_deg = "auto"',
                                                          "direction_deg = 30"),
                 encoding="utf-8")
    r = plan_project(load_project(p))
    assert r.uav.job.layout.direction_deg == pytest.approx(30.0)
    alts = r.uav.alternatives
    chosen = next(a for a in alts if a.recommended)
    assert chosen.direction == "project" and chosen.allowed
    auto = next(a for a in alts if a.direction == "auto")
    assert not auto.allowed and auto.flight_time_s < chosen.flight_time_s
    assert {a.mode for a in alts} == {None}  # no terrain: one height for every direction


def test_a_flat_polygon_flies_the_least_flight_length(tmp_path):
    """The town on flat ground: the least flight length is also the least flying time;
    the long axis is priced beside it."""
    r = plan_project(load_project(TOWN))
    alts = r.uav.alternatives
    chosen = next(a for a in alts if a.recommended)
    assert chosen.direction == "auto" and chosen.n_photos == r.uav.job.layout.n_photos
    axis = next(a for a in alts if a.direction == "long_axis")
    assert axis.flight_time_s >= chosen.flight_time_s


# --- layout and height to a fixed point ------------------------------------------------------

class _Fake:
    """A layout's check at a height: whether its worst photo passes, and the largest
    height its own ground allows (what a spike under one layout's line does)."""

    def __init__(self, allows: dict[float, float]) -> None:
        self.allows = allows
        self.checked: list[float] = []

    def job(self, h: float):
        from types import SimpleNamespace

        return SimpleNamespace(plan=SimpleNamespace(inputs=SimpleNamespace(height_m=h)),
                               layout=object())

    def check(self, job):
        from types import SimpleNamespace

        h = job.plan.inputs.height_m
        self.checked.append(h)
        return SimpleNamespace(height_m=h, max_height_m=self.allows[h])


def test_settle_tries_the_heights_above_a_lowering_until_a_fixed_point():
    """The layout at 120 m has the spike under a line: its ground allows 105 m. At 105 m
    the lines miss it (145 m allowed), so the heights between are laid out again: 115 m
    hits it again (its lines pass over it), 110 m misses it and is kept — where a single
    lowering kept 105 m."""
    fake = _Fake({120.0: 105.0, 105.0: 145.0, 115.0: 100.0, 110.0: 145.0})
    got: Settled = settle(fake.check, fake.job(120.0), fake.job)
    assert fake.checked == [120.0, 105.0, 115.0, 110.0]
    assert got.result.height_m == 110.0 and got.lowered_m == 110.0
    assert got.tried == ((120.0, False), (105.0, True), (115.0, False), (110.0, True))
    # none passes above the start: the start is never exceeded
    fake = _Fake({120.0: 150.0})
    assert settle(fake.check, fake.job(120.0), fake.job).tried == ((120.0, True),)


def _spike_projects(tmp: Path) -> tuple[Path, Path]:
    """The town at 120 m with a 145 m ceiling (no tolerance) over flat ground at 100 m, and
    the same over a DEM with a 40 m spike (a 4 m square) under a line of the 120 m layout
    — where the lines laid out at 115 m and at 105 m miss it by 8–12 m (found here: the
    layouts are the planner's). Returns (flat project, spike project)."""
    shutil.copytree(EXAMPLES / "areas", tmp / "areas")
    text = TOWN.read_text(encoding="utf-8").replace(
        "height_tolerance_pct = 10", "height_tolerance_pct = 0\nheight_m = 120\n"
        "max_height_m = 145")
    flat = tmp / "flat.toml"
    flat.write_text(text, encoding="utf-8")
    lay = plan_project(load_project(flat)).uav.job.layout
    direction = lay.direction_deg  # the least flight length at 120 m, kept for the others

    def lines(height: int) -> object:
        q = tmp / f"at-{height}.toml"
        q.write_text(text.replace("height_m = 120", f"height_m = {height}").replace(
            'direction_deg = "auto"', f"direction_deg = {direction}"), encoding="utf-8")
        layout = plan_project(load_project(q)).uav.job.layout
        return shapely.MultiLineString([[s.start_xy_m, s.end_xy_m] for s in layout.strips])

    other = [lines(115), lines(105)]
    inner = lay.area.geometry.buffer(-100.0)
    spot = None
    for s in lay.strips:
        (x0, y0), (x1, y1) = s.start_xy_m, s.end_xy_m
        for t in np.linspace(0.05, 0.95, 200):
            p = shapely.Point(x0 + t * (x1 - x0), y0 + t * (y1 - y0))
            if inner.contains(p) and all(8 <= ln.distance(p) <= 12 for ln in other):
                spot = p
                break
        if spot is not None:
            break
    assert spot is not None
    bx0, by0, bx1, by1 = lay.area.geometry.bounds
    m = 600.0

    def ground(x: np.ndarray, y: np.ndarray) -> np.ndarray:
        return np.where((np.abs(x - spot.x) <= 2) & (np.abs(y - spot.y) <= 2), 140.0, 100.0)

    write_dem(tmp / "spike.tif", ground, left=bx0 - m, top=by1 + m, cell=2.0,
              width=int((bx1 - bx0 + 2 * m) / 2), height=int((by1 - by0 + 2 * m) / 2),
              crs=lay.area.plan_crs)
    spike = tmp / "spike.toml"
    spike.write_text(text.replace('direction_deg = "auto"', f"direction_deg = {direction}")
                     + '\n[terrain]\ndem = "spike.tif"\naltitude_mode = "constant"\n'
                     '[norms.block_relief]\nreason = "a mast, not ground"\n', encoding="utf-8")
    return flat, spike


def test_a_spike_under_a_line_no_longer_keeps_the_height_lowered_for_it(tmp_path):
    """Bug: a 40 m spike under a flight line lowered the height 120 → 105 m; the lines laid
    out again at 105 m miss it, and 105 m was kept (+31 % photos) although a higher height
    whose own lines miss it meets every constraint. Now layout and height are iterated to
    a fixed point: 120 m (spike under a line: 105 m allowed) → 105 m (lines miss it: 145 m
    allowed) → 115 m, laid out again, whose lines miss it too: 115 m is kept. (Lines laid
    along another direction that miss it at 120 m keep 120 m: the plans compared.)"""
    flat, spike = _spike_projects(tmp_path)
    r = plan_project(load_project(spike))
    u = r.uav
    chosen = next(a for a in u.alternatives if a.recommended)
    assert chosen.direction == "project" and chosen.mode == "constant"
    assert chosen.heights_tried == ((120.0, False), (105.0, True), (115.0, True))
    assert u.recommended_height_m == 115.0 and chosen.feasible
    assert u.terrain.max_height_m >= 115.0 - 1e-9
    # the first check: the spike under a line of the 120 m layout allows 105 m, as before
    first = u.terrain.max_height_m
    assert first > 140.0  # the 115 m lines miss it: the flat 145 m less nothing
    at_105 = flat.read_text(encoding="utf-8").replace("height_m = 120", "height_m = 105")
    n_105 = plan_project(parse_project(at_105, flat)).uav.job.layout.n_photos
    assert chosen.n_photos < n_105 / 1.15  # (115/105)² = 1.20


# --- printed heights over relief ---------------------------------------------------------------

def test_sigma_z_and_the_heights_printed_over_relief_are_the_heights_flown(afs):
    """Bug: over relief σ_Z, GSD and L were printed "at the highest flown height 90 m"
    (afs: the planned 90 m + 0 %) while the photos fly 90–145 m above their ground. Now they
    are at the heights really flown: JSON, the terminal, the PDF sentence and the chart."""
    from scanplan.norms import load_norm_set
    from scanplan.reports.plots import height_svg
    from scanplan.reports.views import ResultTables
    from scanplan.rules.constraints import sigma_z_m

    u = afs.uav
    plan = u.job.plan
    agl = np.asarray(u.terrain.layout.photos["agl_m"], dtype=float)
    hi = float(np.nanmax(agl)) * (1 + plan.inputs.height_tolerance_up_pct / 100)
    assert plan.over_relief and plan.heights_m["max"] == pytest.approx(hi)
    assert hi == pytest.approx(145.0, abs=0.5)  # 90 m over the highest ground, 55 m relief
    acc = plan.height_accuracy
    rules = load_norm_set("gkinp-02-036-02").rules()
    assert acc["sigma_z_at_highest_flown_height_m"] == pytest.approx(
        float(sigma_z_m(plan.inputs, rules, hi)), rel=1e-9)
    assert acc["sigma_z_at_highest_flown_height_m"] > 1.5 * float(
        sigma_z_m(plan.inputs, rules, 90.0))
    assert plan.gsd_at_max_height_m == pytest.approx(plan.gsd_m * hi / 90.0, rel=1e-9)
    doc = json.loads(CliRunner().invoke(main, ["plan", str(AFS), "--json"]).output)
    assert doc["uav"]["height_accuracy"]["sigma_z_at_highest_flown_height_m"] == \
        pytest.approx(acc["sigma_z_at_highest_flown_height_m"])
    assert doc["specification"]["uav"]["recommended_flown_height_m"] == pytest.approx(hi)
    svg = height_svg(ResultTables.of_jobs(None, u.job), "en")
    assert "highest flown: 145 m" in svg
    out = CliRunner().invoke(main, ["plan", str(AFS)]).output
    assert re.search(r"ошибка высот σ_Z\s+0,0\d\d м на высоте 145 м", out)
    assert "90–145 м" in out


def test_the_pdf_and_the_workbook_print_the_heights_flown(afs, tmp_path):
    from pypdf import PdfReader

    res = CliRunner().invoke(main, ["plan", str(AFS), "--out", str(tmp_path),
                                    "--formats", "pdf,xlsx"])
    assert res.exit_code == 0, res.output
    pdf = " ".join(" ".join(p.extract_text().split()) for p in
                   PdfReader(tmp_path / "spec.pdf").pages)
    assert "на наибольшей фактической высоте 145 м" in pdf
    assert "на наибольшей фактической высоте 90 м" not in pdf
    import openpyxl

    ws = openpyxl.load_workbook(tmp_path / "spec.xlsx")["БПЛА"]
    labels = [c.value for c in ws["A"] if isinstance(c.value, str)]
    assert any(v.startswith("наибольшая фактическая: 145") for v in labels)
    assert not any(v.startswith("наибольшая фактическая: 90") for v in labels)


# --- "written beside this report" only when it is -------------------------------------------------

@pytest.mark.parametrize(("formats", "beside"), [("pdf,xlsx", False), ("pdf,gis", True)])
def test_the_photo_table_is_said_beside_the_report_only_when_written(tmp_path, formats,
                                                                   beside):
    """Bug: ``plan --formats pdf,xlsx`` (and ``--pdf FILE``) said the photo centres "are in
    the photo-centre table written beside this report", which was not written."""
    from pypdf import PdfReader

    shutil.copytree(EXAMPLES / "areas", tmp_path / "areas")
    shutil.copytree(EXAMPLES / "dem", tmp_path / "dem")
    project = tmp_path / "valley.toml"  # one altitude: 16,442 photos, more than a sheet holds
    project.write_text(VALLEY.read_text(encoding="utf-8").replace(
        'altitude_mode = "auto"', 'altitude_mode = "constant"'), encoding="utf-8")
    out = tmp_path / "out"
    res = CliRunner().invoke(main, ["plan", str(project), "--out", str(out),
                                    "--formats", formats])
    assert res.exit_code == 0, res.output
    assert (out / "photos.csv").exists() is beside
    pdf = " ".join(" ".join(p.extract_text().split()) for p in
                   PdfReader(out / "spec.pdf").pages)
    assert ("written beside this report" in pdf) is beside
    if not beside:
        assert "written with the mission files when the project is planned" in pdf
    single = tmp_path / "single.pdf"
    res = CliRunner().invoke(main, ["plan", str(project), "--pdf", str(single)])
    assert res.exit_code == 0, res.output
    text = " ".join(" ".join(p.extract_text().split()) for p in PdfReader(single).pages)
    assert "written beside this report" not in text


def test_a_ground_range_without_a_dem_is_planned_at_one_altitude():
    """A range of ground elevations: strips cannot be held over ground the plan does not
    know; one altitude is laid out, following the terrain is priced as an estimate."""
    text = ("[map]\nscale = 2000\nrelief_interval_m = 0.5\n[uav]\n"
            'camera = "dji-zenmuse-p1-35"\nspeed_ms = 12\n[area]\nwidth_m = 1000\n'
            "length_m = 1200\n[terrain]\nground_elevation_m = [100, 104]\n")
    r = plan_project(parse_project(text, "range.toml"))
    modes = {(a.mode, a.estimate) for a in r.uav.alternatives}
    assert ("constant", False) in modes and ("follow", True) in modes
    assert ("strip", False) not in modes
    chosen = next(a for a in r.uav.alternatives if a.recommended)
    assert chosen.feasible  # 4 m of relief: within 7 % of the height
