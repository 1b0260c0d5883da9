"""Issue 13 item 6 and item 2: answers that agree with each other.

The inverse table respects the interpretation limit stated above it; scales are parsed
once; overlaps are percentages; the UAV recognition table lists the map scale's objects;
data volumes say "uncompressed" and give a JPEG estimate; unknown ids get a suggestion;
1:500 and 1:1000 have norm objects; a project may name its own object.
"""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.errors import InputError
from scanplan.norms import did_you_mean, load_norm_set
from scanplan.project.file import parse_project
from scanplan.project.jobs import USER_OBJECT_NAME, object_display_name, scan_job, uav_job
from scanplan.project.spec import plan_project


def _cli(*args: str):
    return CliRunner().invoke(main, list(args), prog_name="scanplan")


INSTRUCTION = dict(map_scale=2000, relief_interval_m=1.0, photo_scales=[10000],
                   camera="afa-te-100", resolving_power_lpmm=40, scanner="photoscan-td")


def test_inverse_table_shows_the_interpretation_limit_too():
    """7 µm supports 1:15798 by the constraints, but 20 cm poles stop at 1:8847 (seed 001:
    Mc_interp = 2·L·sqrt(−ln P)·R/B), so the table gives both."""
    plan = scan_job(**INSTRUCTION).plan
    reach = {r.pixel_um: r for r in plan.max_photo_scales}
    assert reach[7.0].max_photo_scale == pytest.approx(15798, abs=1)
    assert reach[7.0].limit == "PD"
    assert reach[7.0].max_photo_scale_interpretable == pytest.approx(8847.6, abs=1)
    assert plan.interpretation_limit_photo_scale == pytest.approx(
        reach[7.0].max_photo_scale_interpretable)
    for r in plan.max_photo_scales:  # never beyond either limit
        assert r.max_photo_scale_interpretable <= min(
            r.max_photo_scale, plan.interpretation_limit_photo_scale) + 1e-9
    out = _cli("scan", "--map-scale", "2000", "--relief", "1", "--photo-scale", "10000",
               "--camera", "afa-te-100", "--scanner", "photoscan-td").output
    assert "with the object interpretable" in out
    row = next(line for line in out.splitlines() if line.strip().startswith("7 "))
    assert "1:15798" in row and "1:8847" in row


def test_scales_are_parsed_once_when_loading():
    p = parse_project('[map]\nscale = "1:2 000"\nrelief_interval_m = 1\n[film]\n'
                      'camera = "rc30-153"\nphoto_scales = ["1:8000", 10000]\n', "x.toml")
    assert p.get("map", "scale") == 2000 and isinstance(p.get("map", "scale"), int)
    assert p.get("film", "photo_scales") == [8000, 10000]
    with pytest.raises(InputError) as exc:
        parse_project('[map]\nscale = "1:abc"\nrelief_interval_m = 1\n[film]\n'
                      'camera = "rc30-153"\nphoto_scales = [8000]\n', "x.toml")
    assert "map.scale (line 2)" in exc.value.field


@pytest.mark.parametrize("section, key, value, hint", [
    ("film", "forward_overlap_pct", 0.8, "not a fraction"),
    ("film", "forward_overlap_pct", 40, "no stereo"),
    ("uav", "forward_overlap_pct", 0.8, "no stereo"),
    ("uav", "side_overlap_pct", 0.6, "not a fraction"),
    ("film", "side_overlap_pct", 5, "gaps between the strips"),
])
def test_overlaps_are_percentages(tmp_path, section, key, value, hint):
    body = ('[film]\ncamera = "rc30-153"\nphoto_scales = [8000]\n' if section == "film" else
            '[uav]\ncamera = "dji-zenmuse-p1-35"\n')
    p = tmp_path / "p.toml"
    p.write_text(f"[map]\nscale = 2000\nrelief_interval_m = 1\n{body}{key} = {value}\n",
                 encoding="utf-8")
    r = _cli("plan", str(p))
    assert r.exit_code == 2
    assert f"{section}.{key} (line" in r.output
    assert "≥ 50" in r.output or "≥ 10" in r.output
    assert "percentage" in r.output and hint in r.output


def test_overlap_option_is_percent_too():
    r = _cli("uav", "--camera", "dji-zenmuse-p1-35", "--height-m", "100", "--overlap-pct", "0.8")
    assert r.exit_code == 2 and "error: --overlap-pct" in r.output and "percentage" in r.output


def test_uav_recognition_lists_the_map_scales_objects_once():
    job = uav_job(camera="dji-zenmuse-p1-35", height_m=100, map_scale=10000,
                  relief_interval_m=1.0)
    rows = [(r.object, r.map_scale) for r in job.plan.recognition]
    assert rows == [("boreholes", 10000)]
    # with the project's own object, it comes first
    job = uav_job(camera="dji-zenmuse-p1-35", height_m=100, map_scale=2000,
                  relief_interval_m=1.0, object_size_m=0.6, object_name="manhole covers")
    assert [r.object for r in job.plan.recognition] == ["manhole covers", "poles, hydrants"]
    # without a map scale: every norm object once (boreholes are at 1:10000 and 1:25000)
    job = uav_job(camera="dji-zenmuse-p1-35", height_m=100)
    names = [(r.object, r.object_size_m) for r in job.plan.recognition]
    assert len(names) == len(set(names))
    assert ("boreholes", 2.2) in names


def test_data_volume_says_uncompressed_and_estimates_jpeg():
    from scanplan.core.flight import JPEG_COMPRESSION_RATIO
    from scanplan.i18n.labels import LABELS

    assert JPEG_COMPRESSION_RATIO == 9.0  # Canon: 20.2 MP Large/Fine JPEG ≈ 6.6 MB vs 60.6 MB
    for key in ("data_volume_gb", "data_volume_gb", "spec_cmp_data_volume"):
        assert "uncompressed" in LABELS["en"][key]
        assert "без сжатия" in LABELS["ru"][key]
    r = _cli("uav", "--camera", "dji-zenmuse-p1-35", "--height-m", "100", "--area-m",
             "500x500")
    assert "GB uncompressed (JPEG ≈" in r.output
    d = json.loads(_cli("uav", "--camera", "dji-zenmuse-p1-35", "--height-m", "100",
                        "--area-m", "500x500", "--json").output)
    fl = d["flight"]
    assert fl["data_volume_jpeg_bytes"] == pytest.approx(fl["data_volume_bytes"] / 9.0)


def test_did_you_mean():
    assert did_you_mean("rc30", ["rc30-153", "afa-te-100"]) == " — did you mean rc30-153?"
    assert did_you_mean("DJI_Mavic_3E", ["dji-mavic-3e"]) == " — did you mean dji-mavic-3e?"
    assert did_you_mean("zzzz", ["rc30-153"]) == "."
    r = _cli("uav", "--camera", "dji-zenmuse-p1", "--height-m", "100")
    assert r.exit_code == 2 and "did you mean dji-zenmuse-p1-35" in r.output
    r = _cli("scan", "--map-scale", "2000", "--relief", "1", "--photo-scale", "10000",
             "--camera", "rc30-153", "--scanner", "photoscan")
    assert r.exit_code == 2 and "did you mean photoscan-td" in r.output


@pytest.mark.parametrize("norm_set", ["gkinp-02-036-02", "gkinp-02-036-02-printed"])
def test_norm_objects_for_500_and_1000(norm_set):
    ns = load_norm_set(norm_set)
    o500, o1000 = ns.object_for(500), ns.object_for(1000)
    assert (o500.size_m, o500.shape) == (0.15, "circle")
    assert (o1000.name, o1000.size_m) == ("poles, hydrants", 0.20)
    for o in (o500, o1000):
        assert "Условные знаки для топографических планов масштабов 1:5000, 1:2000, 1:1000 " \
               "и 1:500" in o.source and "Недра, 1989" in o.source
        assert o.name_ru
    # the smaller the map scale, never a smaller object
    sizes = [o.size_m for o in sorted(ns.objects, key=lambda o: o.map_scale)]
    assert sizes == sorted(sizes)


def test_plans_at_500_and_1000_run_out_of_the_box():
    for mk, mc in ((500, 2500), (1000, 5000)):
        plan = scan_job(map_scale=mk, relief_interval_m=0.5, photo_scales=[mc],
                        camera="rc30-153", resolving_power_lpmm=40).plan
        assert plan.inputs.object.map_scale == mk
        assert "PD" in {c.id for c in plan.scenarios[0].constraints}


def test_object_name_in_both_languages(tmp_path):
    from scanplan.reports.formatter import formatter

    ns = load_norm_set("gkinp-02-036-02")
    base = ("[map]\nscale = 500\nrelief_interval_m = 0.5\n[norms]\n{norms}"
            "[film]\ncamera = 'rc30-153'\nphoto_scales = [2500]\n")
    named = plan_project(parse_project(base.format(
        norms='object_name = "люки колодцев"\nobject_size_m = 0.6\n'), tmp_path / "a.toml"))
    obj = named.film.job.plan.inputs.object
    assert (obj.name, obj.name_ru, obj.size_m) == ("люки колодцев", "люки колодцев", 0.6)
    unnamed = plan_project(parse_project(base.format(norms="object_size_m = 0.6\n"),
                                         tmp_path / "b.toml"))
    obj = unnamed.film.job.plan.inputs.object
    assert obj.name == USER_OBJECT_NAME["en"] and obj.name_ru == USER_OBJECT_NAME["ru"]
    assert formatter("ru").object_named(ns, obj.name, obj.size_m) == "объект заданного размера"
    assert object_display_name(ns, obj.name, obj.size_m, None, "en") == "object of the given size"
    reason_ru = unnamed.film.job.plan.scenarios[0].constraint("PD").reason.text("ru")
    assert "объект заданного размера" in reason_ru and "object" not in reason_ru
    with pytest.raises(InputError) as exc:
        parse_project(base.format(norms='object_name = "x"\n'), tmp_path / "c.toml")
    assert "norms.object_name (line 5)" in exc.value.field


def test_named_object_in_the_reports(tmp_path):
    p = tmp_path / "named.toml"
    p.write_text("[project]\nlocale = 'ru'\n[map]\nscale = 500\nrelief_interval_m = 0.5\n"
                 "[norms]\nobject_size_m = 0.6\n[film]\ncamera = 'rc30-153'\n"
                 "photo_scales = [2500]\n", encoding="utf-8")
    r = _cli("plan", str(p), "--xlsx", str(tmp_path / "s.xlsx"))
    assert r.exit_code == 0, r.output
    from openpyxl import load_workbook

    wb = load_workbook(tmp_path / "s.xlsx")
    cells = [str(c.value) for ws in wb for row in ws.iter_rows() for c in row if c.value]
    assert any("объект заданного размера" in c for c in cells)
    assert "object" not in cells


def test_inverse_table_both_columns_in_the_reports(tmp_path):
    """The workbook and the PDF label both columns (en and ru)."""
    pypdf = pytest.importorskip("pypdf")
    from openpyxl import load_workbook

    for locale, label in (("en", "Smallest photo scale with the map object interpretable"),
                          ("ru", "Предельный масштаб снимков с дешифрированием объекта")):
        x, p = tmp_path / f"{locale}.xlsx", tmp_path / f"{locale}.pdf"
        r = _cli("scan", "--map-scale", "2000", "--relief", "1", "--photo-scale", "10000",
                 "--camera", "afa-te-100", "--scanner", "photoscan-td", "--locale", locale,
                 "--xlsx", str(x), "--pdf", str(p))
        assert r.exit_code == 0, r.output
        cells = {str(c.value) for ws in load_workbook(x) for row in ws.iter_rows()
                 for c in row if c.value is not None}
        assert label in cells
        text = " ".join(" ".join(pg.extract_text().split()) for pg in pypdf.PdfReader(p).pages)
        assert label in text or label.replace(" ", "") in text.replace(" ", "")


def test_unnamed_object_is_the_reports_label():
    from scanplan.i18n.labels import LABELS

    for loc in ("en", "ru"):
        assert USER_OBJECT_NAME[loc] == LABELS[loc]["obj_unnamed"]
