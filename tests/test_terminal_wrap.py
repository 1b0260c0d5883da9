"""The terminal's flight-lines line never parts "sorties:" from its number when it wraps
(it printed "…, sorties:" and "1" on the next line)."""

from __future__ import annotations

from click.testing import CliRunner

from scanplan.cli.main import main

_PROJECT = """[map]
scale = 2000
relief_interval_m = 0.5
[uav]
camera = "dji-zenmuse-p1-35"
max_flight_time_min = 60   # one sortie: the P1 is carried by more than one aircraft
[area]
polygon = [[55.08, 38.78], [55.08, 38.80], [55.07, 38.80], [55.07, 38.78]]
"""


def test_sorties_keep_their_number(tmp_path):
    path = tmp_path / "p.toml"
    path.write_text(_PROJECT, encoding="utf-8")
    out = CliRunner().invoke(main, ["plan", str(path)])
    assert out.exit_code == 0, out.output
    lines = out.stdout.splitlines()
    flight = next(i for i, x in enumerate(lines) if x.startswith("Flight lines:"))
    block = lines[flight:flight + 3]
    assert not any(x.rstrip().endswith("sorties:") for x in block), block
    assert any("sorties: 1" in x for x in block), block


def test_ceiling_limit_is_printed_as_a_height_in_both_languages():
    """The limits table's HC row gives the ceiling as a height (150 m), not a ground size
    with three decimals: in Russian "150,000 м" reads as 150 000 m."""
    argv = ["uav", "--camera", "canon-eos-5d-mark-ii-50", "--height-m", "300",
            "--map-scale", "2000", "--relief", "0.5"]
    for locale, shown, wrong in (("en", "150 m  H", "150.000 m"),
                                 ("ru", "150 м  H", "150,000 м")):
        out = CliRunner().invoke(main, [*argv, "--locale", locale])
        assert out.exit_code == 0, out.output
        row = next(x for x in out.stdout.splitlines() if x.strip().startswith("HC"))
        assert shown in row and wrong not in row, row


def test_russian_terrain_line_has_no_english_frame():
    """The Russian terminal's terrain line gives the altitude frame in Russian ("над уровнем
    моря"), not "AMSL"."""
    from pathlib import Path

    example = Path(__file__).resolve().parent.parent / "examples" / "uav-town-2000-afs.toml"
    out = CliRunner().invoke(main, ["plan", str(example)])
    assert out.exit_code == 0, out.output
    terrain = " ".join(out.stdout.split("\n\n")[0].split())
    assert "(над уровнем моря)" in terrain and "AMSL" not in terrain, terrain
