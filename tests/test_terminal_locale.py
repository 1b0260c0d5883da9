"""``scanplan scan`` and ``scanplan uav`` speak the language of ``--locale`` on the terminal,
as ``scanplan plan`` speaks its project's ``[project] locale``: every word from the label
catalogue (scanplan/i18n/labels_cli.py), every message from scanplan/i18n/messages.py, every
number with the decimal comma of the Russian reports.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.i18n.labels_cli import CLI

TOWN = str(Path(__file__).resolve().parent.parent / "examples" / "areas" / "town-uav.kml")
SCAN = ["scan", "--map-scale", "1:2000", "--relief", "1.0", "--photo-scale", "10000",
        "--photo-scale", "15000", "--camera", "afa-te-100", "--scanner", "photoscan-td",
        "--pixel-um", "15"]
UAV = ["uav", "--camera", "canon-eos-5d-mark-ii-50", "--f-number", "8", "--height-m", "300",
       "--height-tolerance-pct", "40", "--speed-ms", "25", "--map-scale", "2000", "--relief",
       "0.5", "--area-m", "2000x3000", "--max-flight-time-min", "30"]
UAV_POLYGON = ["uav", "--camera", "dji-zenmuse-p1-35", "--height-m", "100", "--area-file",
               TOWN, "--roll-deg", "3", "--pitch-deg", "2"]
SCAN_POLYGON = ["scan", "--map-scale", "2000", "--relief", "1", "--photo-scale", "10000",
                "--focal-mm", "100", "--frame-mm", "180x180", "--resolving-power", "40",
                "--area-file", TOWN]

#: English words of the terminal reports (labels, headings, units) that a Russian report
#: must not show.
ENGLISH = ["Scan plan", "camera", "frame", "lines/mm", "forward overlap", "norm set",
           "object to interpret", "binding", "scan pixel", "scanner", "step",
           "scanned frame", "photo resolution", "Why", "Interpretation limit",
           "Smallest photo scale", "limited by", "none", "Warnings", "plan", "pixel", "sensor",
           "height", "speed", "exposure", "overlaps", "scene contrast", "threshold",
           "resolving power", "ground resolution", "motion blur", "Flight geometry",
           "footprint", "line spacing", "photo interval", "strips", "photos",
           "flight length", "data volume", "Recognition probability", "object", "shape",
           "corner", "Maximum planned", "constraint", "limit", "compared with",
           "highest flown", "Height accuracy", "Area", "Flight lines", "sorties",
           "direction", "turns", "uncompressed", "km", "min", "mm", "MB", "GB", "m/s",
           "planimetric", "interpretation", "normal case", "Instruction", "used", "at"]


def _run(args):
    res = CliRunner().invoke(main, args)
    assert res.exit_code == 0, res.output
    return res.stdout


def _english_left(text: str) -> list[str]:
    # the option the user typed and the area file, named as typed
    text = text.replace("--pixel-um", "").replace(TOWN, "")
    return [word for word in ENGLISH
            if re.search(rf"(?<![\w-]){re.escape(word)}(?![\w-])", text, flags=re.I)]


@pytest.mark.parametrize("args", [SCAN, UAV, UAV_POLYGON, SCAN_POLYGON],
                         ids=["scan", "uav", "uav-polygon", "scan-polygon"])
def test_russian_terminal_has_no_english_words_and_a_decimal_comma(args):
    ru = _run([*args, "--locale", "ru"])
    body = ru.splitlines()[1:]  # the first line names the camera as its maker does
    assert _english_left("\n".join(body)) == []
    assert re.search(r"\d,\d", ru)  # 0,75; 11,1 мкм
    # no decimal point in a number the report computes (ids and model names aside)
    points = [line for line in body if re.search(r"(?<![\w./-])\d+\.\d+(?![\w.])", line)]
    assert points == []
    en = _run(args)
    assert _english_left(en)  # the same words are there in English
    assert not re.search(r"[А-Яа-яЁё]", en)


def test_english_and_russian_have_the_same_words():
    assert set(CLI["en"]) == set(CLI["ru"])
    for key, text in CLI["en"].items():  # the same fields to fill
        assert set(re.findall(r"{(\w+)}", text)) == set(re.findall(r"{(\w+)}", CLI["ru"][key])), key


def test_russian_numbers_match_the_english_ones():
    """The same figures, written two ways: 11.1 → 11,1, 10,000 → 10 000."""
    en, ru = _run(SCAN), _run([*SCAN, "--locale", "ru"])
    pick = re.compile(r"^PD .*?(\d[\d.,]*)\*", flags=re.M)
    assert pick.search(en).group(1).replace(".", ",") == pick.search(ru).group(1)
    assert "1:10,000" not in en and "1:10000" in en and "1:10\u00a0000" in ru


def test_a_bad_locale_is_a_usage_error():
    res = CliRunner().invoke(main, [*SCAN, "--locale", "de"])
    assert res.exit_code == 2 and "--locale" in res.output


# --- the catalogue listings: `cameras list/show`, `norms list/show`, `norms template` -----

CATALOGUE_ENGLISH = ["kind", "carried by", "frame/sensor", "image px", "pixel µm", "cameras",
                     "scanners", "scan pixels", "bit depth", "frame min", "note", "source",
                     "name", "where", "imported", "title", "bundled", "parameters", "value",
                     "unit", "shapes", "objects", "gsd_limits", "film", "aircraft"]


def _catalogue_english(text: str) -> list[str]:
    return [w for w in CATALOGUE_ENGLISH
            if re.search(rf"(?<![\w-]){re.escape(w)}(?![\w-])", text, flags=re.I)]


def test_cameras_list_in_russian():
    ru = _run(["cameras", "list", "--locale", "ru"])
    head = ru.splitlines()[0]
    assert head.split()[:3] == ["камера", "тип", "носитель"] and "модель" in head
    assert _catalogue_english(head) == [] and re.search(r"\d,\d", ru)
    assert "камер: " in ru and "сканеров: " in ru
    assert "dmc-ii-140" in ru and "цифровая" in ru and "самолёт" in ru
    en = _run(["cameras", "list"])
    assert en.splitlines()[0].split()[:3] == ["id", "kind", "carried"]
    assert re.search(r"^\d+ cameras$", en, flags=re.M)


@pytest.mark.parametrize("camera", ["rc30-153", "photoscan-td", "dji-zenmuse-p1-35"])
def test_cameras_show_in_russian(camera):
    ru = _run(["cameras", "show", camera, "--locale", "ru"])
    keys = "\n".join(line.split("  ")[0] for line in ru.splitlines()[1:] if line.strip())
    assert _catalogue_english(keys) == [], keys
    assert re.search(r"\d,\d", ru) or camera == "photoscan-td"
    if camera == "rc30-153":
        assert "плёночная" in ru and "центральный" in ru and "фокусное расстояние" in ru
        assert "153,0" in ru and "— (формула дифракции)" in ru


def test_norms_list_and_show_in_russian():
    ru = _run(["norms", "list", "--locale", "ru"])
    assert ru.splitlines()[0].split()[:2] == ["имя", "где"] and "встроенный" in ru
    assert "ГКИНП" in ru and _catalogue_english(ru.splitlines()[0]) == []
    show = _run(["norms", "show", "gkinp-02-036-02", "--locale", "ru"])
    assert "Коэффициенты формы" in show and "Минимальные объекты" in show
    assert "круг (B = 0,97)" in show and "Точность в плане" in show
    heads = [line for line in show.splitlines() if line.startswith(("параметр", "форма",
                                                                   "масштаб", "камера"))]
    assert heads and _catalogue_english("\n".join(heads)) == []
    assert "planimetric_accuracy_mm" in _run(["norms", "show", "gkinp-02-036-02"])


def test_norms_template_takes_locale_like_the_other_commands(tmp_path):
    openpyxl = pytest.importorskip("openpyxl")
    for flag in ("--locale", "--lang"):  # --lang: the older spelling, still accepted
        path = tmp_path / f"t{flag}.xlsx"
        _run(["norms", "template", str(path), flag, "ru", "--no-catalogue"])
        assert "Параметры" in openpyxl.load_workbook(path, read_only=True).sheetnames


def test_a_blur_just_over_the_limit_is_never_printed_as_the_limit():
    """0.5004 px beside the warning that it exceeds 0.5 px reads 0.5004, not 0.50."""
    from click.testing import CliRunner

    import scanplan
    from scanplan.cli.main import main

    base = dict(camera="canon-eos-5d-mark-ii-50", f_number=8, height_m=300, speed_ms=25)
    blur25 = scanplan.uav(**base).plan.motion_blur_px
    speed = 25 * 0.5004 / blur25
    assert 0.5 < scanplan.uav(**{**base, "speed_ms": speed}).plan.motion_blur_px < 0.505
    r = CliRunner().invoke(main, ["uav", "--camera", "canon-eos-5d-mark-ii-50", "--f-number",
                                  "8", "--height-m", "300", "--speed-ms", repr(speed)])
    assert r.exit_code == 0, r.output
    row = next(line for line in r.output.splitlines() if line.startswith("motion blur ("))
    assert row.split()[-1] == "0.5004" and "motion blur 0.5004 px" in r.output
