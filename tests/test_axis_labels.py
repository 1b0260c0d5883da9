"""Every chart axis of the documents is labelled as a heading: a capital first letter
(the heights chart read "strip number (range over its photos)" beside "Flight height, m")."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from scanplan.reports.labels import LABELS

_PLOTS = Path(__file__).resolve().parent.parent / "scanplan" / "reports" / "plots.py"
_AXIS_KEYS = sorted(set(re.findall(r"set_[xy]label\(f?\"?\{?t\(\"([a-z0-9_]+)\"",
                                   _PLOTS.read_text(encoding="utf-8"))))


def test_axis_labels_are_found():
    assert {"terrain_plot_x", "terrain_plot_y", "height_m"} <= set(_AXIS_KEYS)


@pytest.mark.parametrize("locale", ["en", "ru"])
@pytest.mark.parametrize("key", _AXIS_KEYS)
def test_axis_label_is_capitalised(key, locale):
    label = LABELS[locale][key]
    assert not label[:1].islower(), (key, locale, label)
