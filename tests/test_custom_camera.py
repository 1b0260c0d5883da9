"""A camera given by its data (pixel pitch, focal length, sensor size) rather than a
catalogue id: it has a name in the documents, its data volume follows from its sensor and
pixel, and a missing f-number is asked for in words that fit it."""

from __future__ import annotations

import io

import pytest
from click.testing import CliRunner
from openpyxl import load_workbook

from scanplan.cli.main import main
from scanplan.errors import InputError
from scanplan.project.file import load_project
from scanplan.project.inputs import INPUTS
from scanplan.project.jobs import uav_job
from scanplan.project.spec import plan_project

_CUSTOM = dict(pixel_um=4.4, focal_mm=35.0, sensor_mm="36x24", f_number=5.6, height_m=100.0)


def test_image_size_and_data_volume_follow_from_sensor_and_pixel():
    job = uav_job(**_CUSTOM, area_m="500x500")
    inp = job.plan.inputs
    assert (inp.image_width_px, inp.image_height_px) == (round(36000 / 4.4),
                                                           round(24000 / 4.4))
    photos = job.plan.flight["photos"]
    expected = photos * 8182 * 5455 * 3  # 3 bands of 8 bits
    assert job.plan.flight["data_volume_bytes"] == pytest.approx(expected)


def test_a_portrait_custom_camera_turns_its_image_size():
    inp = uav_job(**_CUSTOM, orientation="portrait").plan.inputs
    assert (inp.image_width_px, inp.image_height_px) == (5455, 8182)


def test_a_catalogue_camera_keeps_its_published_image_size():
    inp = uav_job(camera="dji-zenmuse-p1-35", height_m=100.0).plan.inputs
    assert (inp.image_width_px, inp.image_height_px) == (8192, 5460)


def test_the_given_camera_name_is_the_name_the_reports_show():
    inp = uav_job(**_CUSTOM, camera_name="  Sony  a7R IV  ").plan.inputs
    assert inp.camera_name == "Sony a7R IV"
    assert uav_job(**_CUSTOM).plan.inputs.camera_name == ""
    assert uav_job(camera="dji-zenmuse-p1-35", height_m=100.0).plan.inputs.camera_name \
        .startswith("DJI Zenmuse P1")


@pytest.mark.parametrize("bad", ["", "   ", 5])
def test_an_empty_camera_name_is_refused_naming_the_key(bad):
    with pytest.raises(InputError) as err:
        uav_job(**_CUSTOM, camera_name=bad)
    assert err.value.field == "camera_name"


def test_camera_name_is_a_registry_key_with_an_option():
    rec = INPUTS["uav.camera_name"]
    assert rec.option == "--camera-name" and rec.kind == "str"


def test_a_custom_camera_without_f_number_is_asked_for_it_in_words():
    result = CliRunner().invoke(main, ["uav", "--pixel-um", "1", "--focal-mm", "300",
                                       "--sensor-mm", "60x3", "--height-m", "20"])
    assert result.exit_code == 2, result.output
    assert "--f-number" in result.output
    assert "camera ''" not in result.output
    assert "given by its pixel pitch, focal length and sensor size" in result.output


def test_the_project_file_names_a_custom_camera_in_the_workbook(tmp_path):
    from scanplan.reports.excel import render_xlsx

    path = tmp_path / "custom.toml"
    path.write_text('[project]\nname = "t"\n[map]\nscale = 2000\nrelief_interval_m = 1\n'
                    '[uav]\ncamera_name = "Survey camera 36 MP"\npixel_um = 4.4\n'
                    'focal_mm = 35\nsensor_mm = "36x24"\nf_number = 5.6\nheight_m = 100\n'
                    '[area]\nwidth_m = 500\nlength_m = 500\n', encoding="utf-8")
    result = plan_project(load_project(path))
    assert result.uav.job.plan.inputs.camera_name == "Survey camera 36 MP"
    assert "data_volume_bytes" in result.uav.job.plan.flight
    book = load_workbook(io.BytesIO(render_xlsx(uav=result.uav.job, meta=result.meta,
                                                spec=result)))
    cells = [str(c.value) for ws in book.worksheets for row in ws.iter_rows() for c in row
             if c.value is not None]
    assert any("Survey camera 36 MP" in c for c in cells)


def test_a_film_camera_given_by_its_data_is_named_in_the_documents(tmp_path):
    from scanplan.reports.excel import render_xlsx

    path = tmp_path / "film.toml"
    path.write_text('[project]\nlocale = "ru"\n[map]\nscale = 2000\nrelief_interval_m = 1\n'
                    '[film]\ncamera_name = "ТАФА-10"\nfocal_mm = 100\nframe_mm = "180x180"\n'
                    'resolving_power_lpmm = 40\nphoto_scales = [8000]\n', encoding="utf-8")
    result = plan_project(load_project(path))
    assert result.film.job.plan.inputs.camera_name == "ТАФА-10"
    book = load_workbook(io.BytesIO(render_xlsx(scan=result.film.job, meta=result.meta,
                                                spec=result)))
    cells = [str(c.value) for ws in book.worksheets for row in ws.iter_rows() for c in row
             if c.value is not None]
    assert any(c == "ТАФА-10" for c in cells)


def test_the_terminal_heads_a_custom_camera_with_its_name():
    result = CliRunner().invoke(main, ["uav", "--pixel-um", "4.4", "--focal-mm", "35",
                                       "--sensor-mm", "36x24", "--f-number", "5.6",
                                       "--height-m", "100", "--camera-name", "Survey 36 MP",
                                       "--area-m", "500x500"])
    assert result.exit_code == 0, result.output
    assert result.output.splitlines()[0] == "UAV plan — Survey 36 MP"
    assert "data volume" in result.output
