"""Every chart axis of the documents is labelled as a heading: a capital first letter
(the heights chart read "strip number (range over its photos)" beside "Flight height, m")."""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import pytest

from scanplan.i18n.labels import LABELS

_PLOTS = Path(__file__).resolve().parent.parent / "scanplan" / "reports" / "plots.py"
_AXIS_KEYS = sorted(set(re.findall(r"set_[xy]label\(f?\"?\{?t\(\"([a-z0-9_]+)\"",
                                   _PLOTS.read_text(encoding="utf-8"))))


def test_axis_labels_are_found():
    assert {"terrain_plot_x", "agl_m", "terrain_plot_y_amsl",
            "height_m"} <= set(_AXIS_KEYS)


@pytest.mark.parametrize("locale", ["en", "ru"])
@pytest.mark.parametrize("key", _AXIS_KEYS)
def test_axis_label_is_capitalised(key, locale):
    label = LABELS[locale][key]
    assert not label[:1].islower(), (key, locale, label)


@pytest.mark.parametrize(("locale", "text"), [("en", "148.5"), ("ru", "148,5")])
def test_height_legend_gives_heights_as_the_tables_do(locale, text):
    """uav-town-2000 flies up to 148.5 m (the tables' figure): the GSD/L chart's legend
    says 148.5, not a rounded 148; whole heights stay whole (70, not 70.0); the maximum
    planned height is in whole metres, as the tables state it (136, not 136.4)."""
    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project
    from scanplan.reports.plots import view_plot
    from scanplan.reports.view import build_view

    example = Path(__file__).resolve().parent.parent / "examples" / "uav-town-2000.toml"
    result = plan_project(load_project(example))
    meta = dataclasses.replace(result.meta, locale=locale)
    view = build_view(scan=None, uav=result.uav.job, meta=meta, spec=result)
    svg = view_plot(view, "height")
    legend = " ".join(re.findall(r">([^<>]*)</text>", svg))
    assert text in svg, legend
    assert re.search(r": \d+(?:[.,]0) ", svg) is None
    assert "(HC): 136 " in svg, legend


def test_russian_height_column_heads_keep_the_unit_with_its_number():
    """'на 70 м' in a narrow column head broke before 'м' (Russian typesetting keeps a unit
    on the line of its number: a no-break space)."""
    from scanplan.i18n.labels import t

    assert t("at_height", "ru").format(h="70") == "на 70\u00a0м"
    assert t("corner_at", "ru").format(h="77") == "угол кадра, 77\u00a0м"
