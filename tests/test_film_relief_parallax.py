"""Film over relief with the parallax form of P_Z: the frame over the lowest ground has a
larger local photo scale and, the exposures being spaced for the planned scale, a smaller
image base — the parallax form takes that local base."""

from __future__ import annotations

from pathlib import Path

import pytest

from scanplan.project.file import parse_project
from scanplan.project.spec import plan_project

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "film-town-relief-10000.toml"


def _plan(formula: str):
    text = EXAMPLE.read_text(encoding="utf-8")
    assert "[terrain]" in text
    text = text.replace("[terrain]", f'[norms]\nheight_formula = "{formula}"\n\n[terrain]')
    return plan_project(parse_project(text, EXAMPLE)).film


def test_parallax_form_uses_the_local_image_base():
    """By hand: AFA-TE-100 (f = 100 mm, l_y = 180 mm), 60 % forward overlap, 1:2000 with
    h_c = 1 m: V_z = 0.2 m, k = 2. Ground 110–230 m; the chosen 1:6000 is flown 600 m over
    the highest ground, so the frame over the lowest ground is 720 m above it: Mc_l = 7200.
    Planned image base b = 180·(1 − 0.6) = 72 mm; the ground base 72 mm × 6000 = 432 m is
    fixed, so at Mc_l the image base is b_l = 432 m / 7200 = 60 mm and
    P_Z = V_z·b_l/(k·Mc_l·f) = 200·60/(2·7200·100) mm = 8.33 µm (the planned base gave
    200·72/(2·7200·100) mm = 10 µm, 20 % too lenient)."""
    film = _plan("parallax")
    ft = film.terrain
    assert ft.photo_scale == 6000 and ft.mc_max == pytest.approx(7200)
    b_l = 180 * (1 - 0.6) * 6000 / 7200
    assert b_l == pytest.approx(60)
    by_hand_um = 200 * b_l / (2 * 7200 * 100) * 1000
    pz = next(c for c in film.recommended.constraints if c.id == "PZ")
    assert pz.pixel_um == pytest.approx(by_hand_um, rel=1e-9)
    assert pz.details["base_mm"] == pytest.approx(b_l)
    assert film.recommended.binding == "PZ"
    assert ft.scan_pixel_um == pytest.approx(by_hand_um, rel=1e-9)
    planned_base_um = 200 * 72 / (2 * 7200 * 100) * 1000
    assert planned_base_um / pz.pixel_um == pytest.approx(1.2)


def test_instruction_form_keeps_the_planned_base():
    """The Instruction's form V_z·f/(k·Mc·b) is checked as printed, with the planned base
    (with the local base Mc_l·b_l = Mc·b and the relief would drop out)."""
    film = _plan("instruction")
    ft = film.terrain
    pz = next(c for c in film.recommended.constraints if c.id == "PZ")
    mc_l = ft.mc_max
    assert pz.details["base_mm"] == pytest.approx(72)
    assert pz.pixel_um == pytest.approx(200 * 100 / (2 * mc_l * 72) * 1000, rel=1e-9)
