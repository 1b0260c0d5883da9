"""The report's line charts are SVG written directly (scanplan/reports/svgchart.py and
chartscale.py), not by matplotlib (issue 15, fast reports): round ticks, broken lines at
gaps, escaped text, the same bytes every time, a glyph width table that is the bundled
font's, nothing of the plots' legends and annotations lost, and no matplotlib imported by
a plan without a map."""

from __future__ import annotations

import math
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from itertools import pairwise
from pathlib import Path

import pytest

from scanplan.i18n.labels import t
from scanplan.i18n.numbers import Numbers
from scanplan.project.file import load_project
from scanplan.project.spec import plan_project
from scanplan.reports import plots
from scanplan.reports.chartscale import (
    ADVANCE,
    ASCENT_EM,
    CAP_EM,
    DESCENT_EM,
    UNITS_PER_EM,
    estimate_width_pt,
    log_ticks,
    nice_ticks,
    text_width_pt,
)
from scanplan.reports.svgchart import Chart
from scanplan.reports.views import ResultTables
from scanplan.rules.registry import CONSTRAINTS

ROOT = Path(__file__).resolve().parents[1]
FONT = ROOT / "templates" / "fonts" / "DejaVuSans.ttf"
SVG = "{http://www.w3.org/2000/svg}"


def _texts(svg: str) -> list[ET.Element]:
    return list(ET.fromstring(svg.encode("utf-8")).iter(f"{SVG}text"))


def _strings(svg: str) -> list[str]:
    return [e.text or "" for e in _texts(svg)]


# -- ticks ---------------------------------------------------------------------------------

@pytest.mark.parametrize(("lo", "hi", "expected"), [
    (0, 78, [0, 10, 20, 30, 40, 50, 60, 70]),  # the MTF chart's frequencies, lines/mm
    (0, 0.0845, [0, 0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08]),  # GSD, m
    (0, 385, [0, 50, 100, 150, 200, 250, 300, 350]),  # heights, m
    (-3, 7, [-2, 0, 2, 4, 6]),
    (0.0012, 0.0019, [0.0012, 0.0013, 0.0014, 0.0015, 0.0016, 0.0017, 0.0018, 0.0019]),
    (1e-7, 9e-7, [1e-7, 2e-7, 3e-7, 4e-7, 5e-7, 6e-7, 7e-7, 8e-7, 9e-7]),
    (0, 22, [0, 2.5, 5, 7.5, 10, 12.5, 15, 17.5, 20]),
])
def test_nice_ticks_are_round_steps_as_matplotlib_gives(lo, hi, expected):
    assert nice_ticks(lo, hi) == pytest.approx(expected, rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("seed", range(40))
def test_nice_ticks_are_within_the_range_evenly_stepped_and_few(seed):
    import random

    rnd = random.Random(seed)
    lo = rnd.uniform(-1e3, 1e3) * 10.0 ** rnd.randint(-6, 4)
    hi = lo + rnd.uniform(1e-3, 1e3) * 10.0 ** rnd.randint(-6, 4)
    bins = rnd.randint(3, 9)
    ticks = nice_ticks(lo, hi, bins)
    assert 2 <= len(ticks) <= bins + 1, (lo, hi, ticks)
    assert all(lo - 1e-9 * (hi - lo) <= v <= hi + 1e-9 * (hi - lo) for v in ticks)
    steps = [b - a for a, b in pairwise(ticks)]
    step = steps[0]
    assert all(math.isclose(s, step, rel_tol=1e-6) for s in steps)
    mantissa = step / 10.0 ** math.floor(math.log10(step) + 1e-12)
    assert any(math.isclose(mantissa, m, rel_tol=1e-6) for m in (1, 2, 2.5, 5)), step


def test_integer_ticks_count_whole_strips():
    assert nice_ticks(0.5, 88.5, integer=True) == [10, 20, 30, 40, 50, 60, 70, 80]
    assert nice_ticks(0.5, 3.5, integer=True) == [1, 2, 3]


def test_log_ticks_are_one_two_five():
    assert log_ticks(0.06, 0.9) == [0.05, 0.1, 0.2, 0.5, 1.0]
    assert log_ticks(5.6, 48) == [5.0, 10.0, 20.0, 50.0]
    assert log_ticks(1.1e-4, 3e-4) == [1e-4, 2e-4]


def test_a_long_log_axis_keeps_its_decades_only():
    chart = Chart("en")
    ax = chart.panels[0]
    ax.set_yscale("log")
    ax.plot([0, 1], [1e-5, 1e3], colour="#000000")
    labels = set(_strings(chart.svg()))
    assert {"0.0001", "0.01", "1", "100"} <= labels
    assert "2" not in labels and "0.5" not in labels


def test_tick_labels_follow_the_locale():
    chart = Chart("ru")
    ax = chart.panels[0]
    ax.plot([0, 12000], [0, 0.05], colour="#000000")
    labels = _strings(chart.svg())
    assert "10\u00a0000" in labels and "0,04" in labels


# -- drawing -------------------------------------------------------------------------------

def test_a_missing_value_breaks_the_line():
    chart = Chart("en")
    ax = chart.panels[0]
    ax.plot([0, 1, 2, 3, 4, 5], [1, 2, math.nan, 4, None, 5], colour="#1f77b4")
    lines = list(ET.fromstring(chart.svg()).iter(f"{SVG}polyline"))
    assert [len(e.get("points").split()) for e in lines] == [2, 1, 1]


def test_a_non_positive_value_breaks_a_log_line():
    chart = Chart("en")
    ax = chart.panels[0]
    ax.set_yscale("log")
    ax.plot([0, 1, 2, 3, 4], [1, 2, 0, 4, 5], colour="#1f77b4")
    lines = list(ET.fromstring(chart.svg()).iter(f"{SVG}polyline"))
    assert [len(e.get("points").split()) for e in lines] == [2, 2]


def test_text_is_escaped_and_the_svg_parses():
    label = "a < b & c > d — GSD ≤ 0,038 м \"q\" 'r'"
    chart = Chart("ru")
    ax = chart.panels[0]
    ax.plot([0, 1], [0, 1], colour="#000000", label=label)
    ax.annotate("x < 1 & y", 0.5, 0.5)
    ax.set_xlabel("<x>")
    ax.set_ylabel("&y")
    svg = chart.svg()
    assert "a &lt; b &amp; c &gt; d" in svg
    assert {label, "x < 1 & y", "<x>", "&y"} <= set(_strings(svg))


def test_the_same_chart_gives_the_same_bytes():
    def draw() -> str:
        chart = Chart("en", (3, 2))
        top, bottom = chart.panels
        top.plot([0, 1, 2], [0.1, 0.5, 0.25], colour="#1f77b4", dash="--", label="a")
        bottom.band([1, 2, 3], [1, 2, 1], [3, 4, 2], colour="#8c564b", label="b")
        top.axhline(0.3, colour="#d62728", dash=":", label="c")
        return chart.svg()
    a, b = draw(), draw()
    assert a == b and a.startswith("<?xml")
    ET.fromstring(a.encode("utf-8"))


def test_dashes_scale_with_the_line_width_as_before():
    chart = Chart("en")
    ax = chart.panels[0]
    ax.plot([0, 1], [0, 1], colour="#d62728", width=1.2, dash="--")
    ax.axvline(0.5, colour="#ff7f0e", width=0.9, dash=(5, 2, 1, 2))
    svg = chart.svg()
    assert 'stroke-dasharray="4.44 1.92"' in svg  # matplotlib's "--": 3.7, 1.6 line widths
    assert 'stroke-dasharray="4.5 1.8 0.9 1.8"' in svg


# -- fonts and layout ----------------------------------------------------------------------

def test_the_width_table_is_the_bundled_font():
    ttlib = pytest.importorskip("fontTools.ttLib")
    font = ttlib.TTFont(str(FONT))
    cmap, hmtx = font.getBestCmap(), font["hmtx"]
    assert font["head"].unitsPerEm == UNITS_PER_EM
    assert (font["hhea"].ascent / UNITS_PER_EM, -font["hhea"].descent / UNITS_PER_EM) == (
        ASCENT_EM, DESCENT_EM)
    glyf = font["glyf"]
    for ch in "H147":  # a capital and the flat-topped digits (round ones overshoot 2 %)
        assert glyf[cmap[ord(ch)]].yMax / UNITS_PER_EM == CAP_EM, ch
    for ch, width in ADVANCE.items():
        assert hmtx[cmap[ord(ch)]][0] == width, repr(ch)


def test_the_estimate_bounds_every_latin_and_cyrillic_glyph():
    import string

    ttlib = pytest.importorskip("fontTools.ttLib")
    font = ttlib.TTFont(str(FONT))
    cmap, hmtx = font.getBestCmap(), font["hmtx"]
    chars = (string.ascii_letters + string.punctuation + " ⁻¹²³·×±≤≥−–—…°µ«»ёЁ"
             + "".join(chr(c) for c in range(0x410, 0x450)))
    for ch in chars:
        real = hmtx[cmap[ord(ch)]][0] / UNITS_PER_EM
        assert estimate_width_pt(ch, 1.0) >= real, (ch, real)


@pytest.fixture(scope="module")
def examples():
    out = {}
    for name in ("uav-canon-2000", "instruction-2000-film", "uav-town-2000",
                 "uav-town-valley-2000"):
        out[name] = plan_project(load_project(ROOT / "examples" / f"{name}.toml"))
    return out


def _all_svgs(examples) -> dict[tuple[str, str, str], str]:
    out = {}
    for name, r in examples.items():
        for loc in ("en", "ru"):
            if r.film is not None:
                film = ResultTables.of_jobs(r.film.job)
                out[name, "constraints", loc] = plots.constraints_svg(film, loc)
            if r.uav is not None:
                uav = ResultTables.of_jobs(None, r.uav.job)
                out[name, "mtf", loc] = plots.mtf_svg(uav, loc)
                out[name, "height", loc] = plots.height_svg(uav, loc)
                if r.uav.terrain is not None:
                    out[name, "terrain", loc] = plots.terrain_svg(
                        r.uav.terrain, r.uav.job.plan.max_height_m, loc)
    return out


def test_the_estimate_is_at_least_every_label_s_width(examples):
    """The legend's columns are sized by an estimate: it is never below the real width of
    any text of the report's plots."""
    ttlib = pytest.importorskip("fontTools.ttLib")
    font = ttlib.TTFont(str(FONT))
    cmap, hmtx = font.getBestCmap(), font["hmtx"]
    seen = 0
    for svg in _all_svgs(examples).values():
        for e in _texts(svg):
            size = float(e.get("font-size"))
            real = sum(hmtx[cmap[ord(c)]][0] for c in e.text) * size / UNITS_PER_EM
            assert estimate_width_pt(e.text, size) >= real, e.text
            if all(c in ADVANCE for c in e.text):  # a tick label: exact
                assert text_width_pt(e.text, size) == pytest.approx(real)
            seen += 1
    assert seen > 200


def _expected_texts(r, plot: str, loc: str) -> list[str]:
    """Every legend label and annotation each plot had with matplotlib (same wording)."""
    n = Numbers(loc)
    m = t("m", loc)
    if plot == "constraints":
        p = r.film.job.plan
        out = [f"{cid} — {CONSTRAINTS[cid].name_ru if loc == 'ru' else CONSTRAINTS[cid].name}"
               for cid in p.constraint_ids if cid in p.sweep]
        out.append(t("scan_pixel_um", loc))
        out += [f"{s.binding} {n.num(s.scan_pixel_um, 1)}" for s in p.scenarios]
        return [*out, f"{t('photo_scale', loc)} 1:Mc", t("pixel_um", loc)]
    p = r.uav.job.plan
    if plot == "mtf":
        return [t("image_contrast", loc), t("threshold", loc),
                f"R = {n.num(p.resolving_power_lpmm, 1)}", t("nyquist_short", loc),
                t("frequency_lpmm", loc), t("contrast", loc)]
    if plot == "height":
        # the ground sample distance by the catalogue's words (in Russian not the Latin
        # symbol: «размер пикселя на местности»); L is a symbol in both languages
        gsd = t("gsd_symbol", loc)
        out = [gsd, "L", f"{t('planned', loc)}: ", f"{t('highest_flown', loc)}: ",
               t("h_max_planned", loc).format(cid=p.binding) + f": {n.num(p.max_height_m, 0)} {m}",
               t("height_m", loc), f"{gsd}, L, {m}"]
        if p.max_flown_height_m and p.max_flown_height_m > p.max_height_m * (1 + 1e-9):
            out.append(f"{t('h_max_flown', loc)}: {n.num(p.max_flown_height_m, 0)} {m}")
        if p.ceiling_m is not None and p.ceiling_m <= max(p.height_curve["height_m"]):
            out.append(f"{t('HC', loc)}: ")
        out += [f"{gsd if lim.compares == 'GSD' else lim.compares} ≤ "
                f"{n.num(lim.limit_m, 3)} {m} ({lim.id})"
                for lim in p.limits if lim.binding and lim.compares in ("GSD", "L")]
        return out
    tr = r.uav.terrain
    return [t("agl_m", loc), t("ground_m", loc), t("altitude_m", loc),
            f"{t('terrain_plot_planned', loc)}: {n.num(tr.height_m, 0)} {m}",
            f"{t('max_height', loc)}", t("terrain_plot_x", loc)]


@pytest.mark.parametrize("loc", ["en", "ru"])
def test_every_legend_label_and_annotation_is_drawn(examples, loc):
    checked = set()
    for (name, plot, locale), svg in _all_svgs(examples).items():
        if locale != loc:
            continue
        texts = _strings(svg)
        joined = "\n".join(texts)
        flowing = " ".join(texts)  # an axis label longer than its axis is wrapped on lines
        for want in _expected_texts(examples[name], plot, loc):
            assert want in joined or want in flowing, (name, plot, want, texts)
        if loc == "ru":  # GSD is a symbol of the formulas, not a word of a Russian chart
            assert "GSD" not in joined, (name, plot, texts)
        checked.add(plot)
    assert checked == {"constraints", "mtf", "height", "terrain"}


def _boxes(svg: str):
    """(left, right, baseline, text) of the unrotated texts."""
    out = []
    for e in _texts(svg):
        if e.get("transform"):
            continue
        x, y, size = float(e.get("x")), float(e.get("y")), float(e.get("font-size"))
        w = estimate_width_pt(e.text, size)
        anchor = e.get("text-anchor", "start")
        left = x - (w / 2 if anchor == "middle" else w if anchor == "end" else 0)
        out.append((left, left + w, y, size, e.text))
    return out


def test_nothing_overlaps_and_the_legend_is_below_the_plot(examples):
    for key, svg in _all_svgs(examples).items():
        root = ET.fromstring(svg.encode("utf-8"))
        width = float(root.get("viewBox").split()[2])
        height = float(root.get("viewBox").split()[3])
        clip = [r for c in root.iter(f"{SVG}clipPath") for r in c]
        plot_bottom = max(float(r.get("y")) + float(r.get("height")) for r in clip)
        boxes = _boxes(svg)
        for left, _right, y, size, text in boxes:
            assert left >= 0 and y <= height, (key, text)
            if all(c in ADVANCE for c in text):  # tick labels: exact width, in the figure
                assert left + text_width_pt(text, size) <= width, key
        # the x tick labels on one baseline do not collide
        ticks = sorted((b for b in boxes if b[3] == 7.0 and all(c in ADVANCE for c in b[4])
                        and b[2] > plot_bottom), key=lambda b: b[0])
        for a, b in pairwise(ticks):
            if a[2] == b[2]:
                assert a[0] + text_width_pt(a[4], 7.0) <= b[0] + 1e-6, (key, a[4], b[4])
        # the legend (7 pt, not digits only, after the axis title) lies under the plots
        legend = [b for b in boxes if b[3] == 7.0 and b[2] > plot_bottom + 20]
        assert legend, key
        assert all(b[2] - 7.0 > plot_bottom for b in legend), key
        assert all(b[1] <= width for b in legend), key  # even at the generous estimate


def test_labels_of_close_points_never_overprint():
    """Photo scales close together: the second label goes above its point; one with no
    room on either side is left out (the tables give every value)."""
    chart = Chart("en")
    ax = chart.panels[0]
    xs = [5000, 5050, 5100, 9000]
    ax.plot([1000, 20000], [10, 10], colour="#000000")
    for x in xs:
        ax.annotate(f"PR {x}", x, 10, dy=11, anchor="middle", size=6.5)
    svg = chart.svg()
    boxes = [b for b in _boxes(svg) if b[4].startswith("PR ")]
    assert [b[4] for b in boxes] == ["PR 5000", "PR 5050", "PR 9000"]
    assert boxes[1][2] < boxes[0][2]  # above the line, the first below
    for a, b in pairwise(sorted(boxes)):
        assert a[1] <= b[0] or abs(a[2] - b[2]) >= 6.5, (a, b)


def test_a_long_axis_title_of_a_short_panel_is_set_in_two_lines(examples):
    r = examples["uav-town-valley-2000"]
    svg = plots.terrain_svg(r.uav.terrain, r.uav.job.plan.max_height_m, "ru")
    title = t("terrain_plot_y_amsl", "ru")
    texts = _strings(svg)
    assert title not in texts
    assert any(a + " " + b == title for a, b in pairwise(texts))


# -- imports -------------------------------------------------------------------------------

def test_a_plan_with_both_reports_imports_no_matplotlib(tmp_path):
    """The plots are SVG text: a report without a map or terrain figure never imports
    matplotlib (it took 0.26 s to import and 0.2 s to draw the two UAV plots)."""
    pytest.importorskip("weasyprint")
    out = tmp_path / "out"
    code = ("import os, sys\n"
            "os.environ['SCANPLAN_NO_FORK'] = '1'\n"
            "from scanplan.cli.main import main\n"
            f"try:\n    main(['plan', {str(ROOT / 'examples' / 'uav-canon-2000.toml')!r}, "
            f"'--out', {str(out)!r}])\nexcept SystemExit as e:\n    assert not e.code, e.code\n"
            "print(sorted(m for m in sys.modules if m.split('.')[0] == 'matplotlib'))\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT,
                       timeout=180, check=False)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip().splitlines()[-1] == "[]"
    assert (out / "spec.pdf").read_bytes().startswith(b"%PDF")
    assert (out / "spec.xlsx").is_file()


def test_the_nyquist_label_stands_clear_of_the_curves(examples):
    """The label beside the Nyquist line is put where neither curve crosses the line
    (matplotlib's, always half-way up, often lay across the image contrast curve)."""
    import re

    for name, r in examples.items():
        if r.uav is None:
            continue
        svg = plots.mtf_svg(ResultTables.of_jobs(None, r.uav.job), "en")
        root = ET.fromstring(svg.encode("utf-8"))
        label = next(e for e in root.iter(f"{SVG}text") if e.text == "Nyquist")
        y = float(re.match(r"translate\(\S+ (\S+)\)", label.get("transform")).group(1))
        half = estimate_width_pt("Nyquist", 6.5) / 2
        ends = [float(p.get("points").split()[-1].split(",")[1])
                for p in root.iter(f"{SVG}polyline")]
        assert len(ends) == 2
        assert all(abs(y - e) > half for e in ends), (name, y, ends)


@pytest.mark.parametrize(("locale", "expected"), [("en", ["6000", "8000", "10000"]),
                                                  ("ru", ["6000", "8000", "10\u00a0000"])])
def test_photo_scale_ticks_read_as_the_scales_in_the_text(locale, expected):
    """The constraints plot labels its photo scales as every sentence and table writes
    them (``1:10000``, ``1:10 000``): the denominator, not a grouped number (``10,000``)."""
    plan = plan_project(load_project(ROOT / "examples" / "instruction-2000-film.toml")).film
    svg = plots.constraints_svg(ResultTables.of_jobs(plan.job), locale)
    ticks = [x for x in _strings(svg) if x.replace("\u00a0", "").isdigit()]
    assert ticks[:3] == expected


def test_the_highest_flown_at_the_maximum_shows_over_the_ceiling_it_equals(examples):
    """Over the valley HC binds: the highest flown height at the maximum is the 150 m
    ceiling. Its dash-dot line is drawn after (over) the ceiling's solid line at the same x,
    so both lines of the legend can be seen (the solid line hid it)."""
    p = examples["uav-town-valley-2000"].uav.job.plan
    assert p.max_flown_height_m == pytest.approx(p.ceiling_m)
    svg = plots.height_svg(ResultTables.of_jobs(None, examples["uav-town-valley-2000"].uav.job),
                           "en")
    ceiling = re.search(r'<path d="(M[\d.]+ [\d.]+V[\d.]+)"[^>]*stroke="#8c564b"', svg)
    flown = re.search(r'<path d="(M[\d.]+ [\d.]+V[\d.]+)"[^>]*stroke="#ff7f0e"', svg)
    assert ceiling and flown and ceiling[1] == flown[1]
    assert ceiling.start() < flown.start()
