"""``scanplan scan`` and ``scanplan uav`` speak the language of ``--locale`` on the terminal,
as ``scanplan plan`` speaks its project's ``[project] locale``: every word from the label
catalogue (scanplan/reports/labels_cli.py), every message from scanplan/messages.py, every
number with the decimal comma of the Russian reports.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.reports.labels_cli import CLI

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
           "Largest photo scale", "limited by", "none", "Warnings", "plan", "pixel", "sensor",
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
