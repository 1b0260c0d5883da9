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
