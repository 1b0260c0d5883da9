"""``scanplan.reports.wording.sentence``: an engine sentence printed in a document reads as a
sentence (capital first letter, full stop), and a symbol is never capitalised."""

from __future__ import annotations

import pytest

from scanplan.reports.wording import sentence


@pytest.mark.parametrize(("text", "expected"), [
    ("motion blur 0.68 px at 70 m exceeds 0.5 px", "Motion blur 0.68 px at 70 m exceeds 0.5 px."),
    ("the altitude ceiling of 150 m binds: raise [uav] max_height_m",
     "The altitude ceiling of 150 m binds: raise [uav] max_height_m."),
    ("over low ground the photos are too high.", "Over low ground the photos are too high."),
    ("k_R = 0.5 keeps the resolving power", "k_R = 0.5 keeps the resolving power."),
    ("σ_Z exceeds the tolerance", "σ_Z exceeds the tolerance."),
    ("1:6000 is the smallest candidate", "1:6000 is the smallest candidate."),
    ("Рекомендуемая высота полёта 135 м.", "Рекомендуемая высота полёта 135 м."),
    ("what follows:", "What follows:"),
    ("  ", ""),
])
def test_sentence(text, expected):
    assert sentence(text) == expected
