"""The engine's sentences as coded messages in English and Russian (scanplan.i18n.messages).

The catalogue has the same codes and the same template fields in both languages; every code
the engine can emit is reached by a case below; a message is its English text (so the
terminal, ``--json`` and the English reports read as before) and renders the same numbers in
Russian; the Russian reports of the bundled examples carry no English engine sentence.
"""

from __future__ import annotations

import ast
import copy
import dataclasses
import html
import io
import json
import pickle
import re
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.i18n.labels import LABELS
from scanplan.i18n.messages import (
    LOCALES,
    MESSAGES,
    Message,
    document_text,
    localize,
    placeholders,
)
from scanplan.project.file import load_project
from scanplan.project.jobs import scan_job, uav_job
from scanplan.project.spec import PlanResult, plan_project
from scanplan.reports.references import Bibliography
from scanplan.reports.wording import camera_title, display_message, scanner_title, sentence
from scanplan.rules.film import CONSTRAINTS, PlanWarning, plan_scan
from scanplan.rules.uav import plan_uav

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
EPOCH = "1700000000"
NBSP = "\u00a0"

# English words of the engine's sentences that a Russian report must not contain
ENGLISH_PHRASES = ("binds", "the photo", "cannot be interpreted", "keeps", "recognised",
                   "next is", "Remedies", "is above", "rounded down", "the planned",
                   "is within", "less data", "motion blur", "forward overlap", "lets",
                   "smallest candidate", "finer than", "lines/mm", "norm set", "conclusion 3",
                   "on the ground", "after k", "instruction form", "with probability",
                   "(printed 0.4)", "(Instruction) or")


# --- the catalogue -------------------------------------------------------------------------


def test_catalogue_has_every_code_in_both_locales():
    assert LOCALES == ("en", "ru")
    for code, templates in MESSAGES.items():
        assert set(templates) == set(LOCALES), code
        assert all(templates[loc].strip() for loc in LOCALES), code
        assert "~" not in templates["en"], code  # "~" ties a number to its unit in Russian


def test_templates_have_the_same_fields_in_both_locales():
    for code, templates in MESSAGES.items():
        assert placeholders(templates["en"]) == placeholders(templates["ru"]), code


def test_russian_templates_are_russian():
    """No English word in a Russian template outside symbols, ids and option names."""
    allowed = {"objects", "parallax", "sqrt", "uav"}  # "uav": the project section [uav]
    for code, templates in MESSAGES.items():
        text = re.sub(r"\{[^}]*\}", " ", templates["ru"])
        text = re.sub(r"\[[a-z.]+\] [a-z_]+", " ", text)  # a project-file key, as typed
        words = set(re.findall(r"[A-Za-z_][A-Za-z_.]*[A-Za-z_]", text))
        # symbols such as Mc, Mk, V_s, k_R, h_c, L_obj are short or have "_"; ids have "_"
        words = {w for w in words if len(w) > 2 and "_" not in w and w != w.upper()}
        assert words <= allowed, (code, words - allowed)


def test_russian_uses_yo_like_the_labels():
    """The labels write ё (съёмка, расчёт, объём); the messages do too."""
    ru = " ".join(t["ru"] for t in MESSAGES.values())
    for word in ("съемк", "учетом", "объем ", "дает", "передает"):
        assert word not in ru, word


# --- Message: a str with a code and parameters ------------------------------------------------


def test_a_message_is_its_english_text_and_renders_in_russian():
    m = Message("reason.PR", r=40, kr=0.5)
    assert m == "keeps the photo's resolving power of 40 lines/mm (k_R = 0.5)"
    assert isinstance(m, str) and str(m) == m and f"{m}" == m
    assert m.code == "reason.PR" and m.params == {"r": 40, "kr": 0.5}
    assert m.text("en") == m
    assert m.text("ru") == f"сохраняет разрешающую способность снимка 40{NBSP}мм⁻¹ (k_R = 0,5)"
    assert m.text("de") == m  # unknown locale: English
    assert localize(m, "ru") == m.text("ru") and localize("plain", "ru") == "plain"
    assert localize(None) == ""


def test_numbers_scales_lists_names_and_nested_messages_per_locale():
    pair = Message("overlap_not_standard.pair", pixel=13.888, scale=10000.0)
    assert pair == "13.9 µm at 1:10000"
    assert pair.text("ru") == f"13,9{NBSP}мкм при 1:10{NBSP}000"
    detail = Message("overlap_not_standard.detail", pairs=[pair, pair])
    assert detail == "The parallax form gives 13.9 µm at 1:10000, 13.9 µm at 1:10000. "
    assert detail.text("ru") == (f"Параллактическая форма даёт 13,9{NBSP}мкм при 1:10{NBSP}000; "
                                 f"13,9{NBSP}мкм при 1:10{NBSP}000. ")
    at = Message("at_scales", scales=[10000.0, 15000.0])
    assert at == "at 1:10000, 1:15000"
    assert at.text("ru") == f"При масштабах снимков 1:10{NBSP}000; 1:15{NBSP}000"
    lim = Message("height_above_max", height=600.0, max=376.4, cid="PD",
                  name={"en": "interpretation", "ru": "дешифрирование"}, tolerance=None)
    assert lim == ("planned height 600 m is above the maximum planned height 376 m set by PD "
                   "(interpretation)")
    assert "по условию PD (дешифрирование)" in lim.text("ru")
    why = Message("no_feasible_photo_scale", why=[
        Message("no_feasible_photo_scale.objects", limit=8847),
        Message("no_feasible_photo_scale.scanner", scanner="photoscan-td")])
    assert "(the map's objects need photo scales up to 1:8847; scanner photoscan-td" in why


def test_messages_survive_copy_pickle_and_json():
    m = Message("explanation", cid="PR", name={"en": "resolving power of the photo",
                                               "ru": "разрешающая способность снимка"},
                scale=8000.0, pixel=12.5, reason=Message("reason.PR", r=40, kr=0.5), next=None)
    for other in (copy.deepcopy(m), pickle.loads(pickle.dumps(m))):
        assert isinstance(other, Message) and other == m
        assert other.text("ru") == m.text("ru")
    assert json.loads(json.dumps({"m": m})) == {"m": str(m)}


def test_messages_module_is_pure():
    """Plain data and str.format: the core's import rules (test_norm_sets) hold for it too.

    The catalogue is ``messages.py`` and its parts ``messages_*.py`` (merged into
    ``MESSAGES``); each imports nothing but these standard modules and the other parts."""
    parts = sorted((ROOT / "scanplan" / "i18n").glob("messages*.py"))
    assert parts[0].name == "messages.py"
    own = {p.stem for p in parts}
    for path in parts:
        tree = ast.parse(path.read_text(encoding="utf-8"))
        imported = set()
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                imported |= {a.name.split(".")[0] for a in node.names}
            elif isinstance(node, ast.ImportFrom) and node.module:
                if node.level:  # relative: only another part of the catalogue
                    assert node.level == 1 and node.module in own, (path.name, node.module)
                    continue
                imported.add(node.module.split(".")[0])
        # contextvars: the medium a document sets; dataclasses: the PlanWarning record
        # every layer states its findings with; math: the written pixel's significant digits
        assert imported <= {"__future__", "math", "numbers", "re", "string", "collections",
                            "typing", "contextlib", "contextvars", "dataclasses"}


# --- every code the engine can emit -------------------------------------------------------------


sys.path.insert(0, str(Path(__file__).parent))
from terrain_helpers import terrain_cases  # noqa: E402


def _messages(value: Any) -> Iterator[Message]:
    """Every Message in ``value`` and nested in its parameters."""
    if isinstance(value, Message):
        yield value
        for v in value.params.values():
            yield from _messages(v)
    elif isinstance(value, list | tuple):
        for v in value:
            yield from _messages(v)
    elif isinstance(value, dict):
        for v in value.values():
            yield from _messages(v)


def _scan_messages(plan: Any) -> Iterator[Any]:
    if plan.inputs.object is not None:
        yield plan.inputs.object.source
    for s in plan.scenarios:
        yield s.explanation
        for c in s.constraints:
            yield from (c.reason, c.equation, c.protects)
    yield from (w.message for w in plan.warnings)


def _uav_messages(plan: Any) -> Iterator[Any]:
    if plan.inputs.map_object is not None:
        yield plan.inputs.map_object.source
    for lim in plan.limits:
        yield from (lim.reason, lim.equation)
    yield from (w.message for w in plan.warnings)


def _project(tmp_path: Path, name: str, text: str) -> PlanResult:
    path = tmp_path / f"{name}.toml"
    path.write_text(text, encoding="utf-8")
    return plan_project(load_project(path))


def _export_notes_cases() -> list[Any]:
    """Why ``plan --out`` writes no mission or photo table: every reason, from the
    function that says it (the layouts are made, not planned)."""
    from types import SimpleNamespace

    from layouts import make_layout

    from scanplan.reports.exports import export_notes

    def spec(layout, platform="uav", speed=10.0):
        inputs = SimpleNamespace(platform=platform, speed_ms=speed)
        job = SimpleNamespace(plan=SimpleNamespace(inputs=inputs))
        return SimpleNamespace(uav=SimpleNamespace(job=job, layout=layout), film=None,
                               project=SimpleNamespace(get=lambda *a: None),
                               meta=SimpleNamespace(locale="en"))

    ok = make_layout()
    unlisted = dataclasses.replace(ok, photos=type(ok.photos)({}),
                                   notes={**ok.notes, "photos": 2_500_000})
    infeasible = dataclasses.replace(ok, feasible=False,
                                     reason=Message("layout.too_many_sorties",
                                                    most=1000, limit=25.0))
    return [*export_notes(spec(infeasible)), *export_notes(spec(ok, platform="aircraft")),
            *export_notes(spec(dataclasses.replace(ok, speed_ms=None), speed=None)),
            *export_notes(spec(unlisted))]


@pytest.fixture(scope="module")
def emitted(tmp_path_factory) -> dict[str, list[Any]]:
    """Cases that raise every warning and reach every message: {case: [engine sentences]}."""
    tmp = tmp_path_factory.mktemp("projects")
    out: dict[str, list[Any]] = {}
    out.update(terrain_cases(tmp))  # issue 12: synthetic DEMs
    film = dict(map_scale=2000, relief_interval_m=0.5, photo_scales=[5000, 10000, 15000, 20000],
                camera="rc30-153", scanner="photoscan-td")
    job = scan_job(**film)
    out["film"] = list(_scan_messages(job.plan))
    out["film 80 %"] = list(_scan_messages(scan_job(**film, forward_overlap_pct=80).plan))
    out["film one scale"] = list(_scan_messages(scan_job(**{**film, "photo_scales": [10000]},
                                                         ).plan))
    out["film parallax"] = list(_scan_messages(scan_job(**film, height_formula="parallax").plan))
    out["film own object"] = list(_scan_messages(scan_job(**film, object_size_m=0.3,
                                                          shape="square").plan))
    no_pd = dataclasses.replace(job.plan.rules, constraints=("PS", "PZ", "PP", "PR"))
    out["film without PD"] = list(_scan_messages(plan_scan(job.plan.inputs, no_pd)))
    uav = dict(camera="canon-eos-5d-mark-ii-50", f_number=8, height_m=300,
               height_tolerance_pct=40, speed_ms=25, forward_overlap_pct=80, map_scale=2000,
               relief_interval_m=0.5, area_m=(2000, 3000))
    out["uav"] = list(_uav_messages(uav_job(**uav).plan))
    out["uav too high"] = list(_uav_messages(uav_job(**{**uav, "height_m": 600}).plan))
    out["uav too high, no tolerance"] = list(_uav_messages(uav_job(
        **{**uav, "height_m": 600, "height_tolerance_pct": 0}).plan))
    out["uav trigger"] = list(_uav_messages(uav_job(**{**uav, "forward_overlap_pct": 97}).plan))
    out["uav flat scene"] = list(_uav_messages(uav_job(**{**uav, "r_min": 0.3}).plan))
    out["uav parallax"] = list(_uav_messages(uav_job(**uav, height_formula="parallax").plan))
    gsd = uav_job(**uav, gsd_cm=2.0).plan
    out["uav target GSD"] = [*_uav_messages(gsd),
                             *(CONSTRAINTS[lim.id].protects for lim in gsd.limits)]
    base = uav_job(**uav)
    out["uav multi-ray"] = list(_uav_messages(plan_uav(base.plan.inputs, dataclasses.replace(
        base.norm_set.rules(), multi_ray="strip"))))
    film_toml = (EXAMPLES / "instruction-2000-film.toml").read_text(encoding="utf-8")
    uav_toml = (EXAMPLES / "uav-canon-2000.toml").read_text(encoding="utf-8")
    archive_toml = (EXAMPLES / "archive-12000-for-2000.toml").read_text(encoding="utf-8")
    variants = {
        "plan film": film_toml,
        "plan no photo scale": film_toml.replace("photo_scales = [6000, 8000, 10000]",
                                                 "photo_scales = [10000, 12000]"),
        "plan pixel too fine": film_toml.replace(  # issue 17: a scan pixel under 0.1 µm
            "photo_scales = [6000, 8000, 10000]", "photo_scales = [100000]").replace(
            "relief_interval_m = 1.0", "relief_interval_m = 0.01"),
        # film over the relief (issue 12): 1:8000 ruled out, 1:6000 taken; nothing holds
        "plan film over relief": film_toml + "\n[terrain]\nground_elevation_m = [110, 230]\n",
        "plan film relief too deep": film_toml + "\n[terrain]\nground_elevation_m = [0, 400]\n",
        "plan uav": uav_toml,
        "plan uav lowered": uav_toml.replace("height_m = 300", "height_m = 500"),
        "plan uav within": uav_toml.replace("height_m = 300", "height_m = 200"),
        "plan uav no height": uav_toml.replace("height_m = 300\n", ""),
        "plan uav over relief": uav_toml + "\n[terrain]\nground_elevation_m = [120, 180]\n",
        "plan uav nothing resolved": uav_toml.replace("r_min = 0.1", "r_min = 0.3"),
        # flight layouts that cannot be flown (issue 11)
        "plan uav one strip": uav_toml.replace("width_m = 2000", "width_m = 10"),
        "plan uav sortie too short": uav_toml.replace("[uav]\n",
                                                      "[uav]\nmax_flight_time_min = 0.001\n"),
        "plan uav too many sorties": uav_toml.replace("[uav]\n", "[uav]\nmax_flight_time_min = 1\n")
        .replace("width_m = 2000", "width_m = 200000").replace("length_m = 3000",
                                                               "length_m = 40000"),
        "plan uav take-off too far": uav_toml.replace("[uav]\n",
                                                      "[uav]\nmax_flight_time_min = 10\n")
        .replace("width_m = 2000", "polygon = [[37.6, 55.7], [37.63, 55.7], [37.63, 55.72]]")
        .replace("length_m = 3000", "") + "\n[flight]\ntakeoff = [39.5, 55.7]\n",
        "plan uav too many strips": uav_toml.replace("height_m = 300", "height_m = 5").replace(
            "width_m = 2000", "width_m = 1000000"),
        # the aircraft (docs/aircraft.md): a camera not listed on it, a speed above its
        # maximum, more flying days than the crew has (around the clock; by the sun)
        "plan uav aircraft": uav_toml.replace("[uav]\n", '[uav]\naircraft = "dji-m350-rtk"\n'),
        "plan uav aircraft too slow": uav_toml.replace(
            'camera = "canon-eos-5d-mark-ii-50"', 'camera = "dji-phantom-4-rtk"'),
        "plan uav approximate battery": uav_toml.replace(
            'camera = "canon-eos-5d-mark-ii-50"', 'camera = "dji-phantom-4-rtk"').replace(
            "speed_ms = 25", "speed_ms = 12"),
        "plan uav flying days": uav_toml.replace("width_m = 2000", "width_m = 60000")
        + "\n[flight]\nmax_flying_days = 1\n",
        "plan uav flying days by the sun": uav_toml.replace("[uav]\n",
                                                            "[uav]\nmax_flight_time_min = 20\n")
        .replace("width_m = 2000", "width_m = 20000")
        + ("\n[flight]\nmax_flying_days = 1\n[site]\nlat_deg = 56\nlon_deg = 37\n"
           "[schedule]\nstart_date = 2025-06-01\n"),
        # archive photos: the scale is given (issue 13)
        "plan archive": archive_toml,
        "plan archive over relief": archive_toml + "\n[terrain]\nground_elevation_m = [120, 260]\n",
        "plan archive readable": archive_toml.replace('photo_scale = "1:12000"',
                                                      "photo_scale = 8000"),
        "plan archive fine scanner": (EXAMPLES / "map-10000-relief-1m.toml").read_text(
            encoding="utf-8").replace("photo_scales = [15000, 20000, 25000, 30000]",
                                      "photo_scale = 30000"),
        # issue 18: today's norms (Table Б.1, the one-height rule, the sun window)
        "plan film 1:10000": (EXAMPLES / "map-10000-relief-1m.toml").read_text(
            encoding="utf-8"),
        "plan film over table B.1": '[map]\nscale = 25000\nrelief_interval_m = 5\n[film]\n'
                                    'camera = "rc30-153"\nphoto_scales = [60000]\n',
        "plan dense urban": uav_toml.replace("[uav]", '[norms]\ngsd_area = "dense_urban"\n\n[uav]'),
        "plan block flat": uav_toml + "\n[terrain]\nground_elevation_m = [100, 150]\n",
        "plan block hilly": uav_toml + ('\n[terrain]\nground_elevation_m = [100, 160]\n'
                                        'relief_class = "hilly"\n'),
        "plan block mountainous": uav_toml + ('\n[terrain]\nground_elevation_m = [100, 200]\n'
                                              'relief_class = "mountainous"\n'),
        "plan sun winter": uav_toml + ("\n[site]\nlat_deg = 60\nlon_deg = 30\n[schedule]\n"
                                       "start_date = 2025-12-01\nend_date = 2025-12-05\n"),
        "plan sun short": uav_toml + ("\n[site]\nlat_deg = 60\nlon_deg = 30\n[schedule]\n"
                                      "start_date = 2025-06-01\nend_date = 2025-06-01\n"
                                      "turnaround_min = 600\n"),
        # the valley flown per strip and following the terrain: the height the plan was
        # lowered from, and how to fly higher in that mode
        **{f"plan valley {mode}": (EXAMPLES / "uav-town-valley-2000.toml").read_text(
            encoding="utf-8").replace('altitude_mode = "auto"', f'altitude_mode = "{mode}"')
           .replace('dem = "dem/', f'dem = "{(EXAMPLES / "dem").as_posix()}/')
           .replace('file = "areas/', f'file = "{(EXAMPLES / "areas").as_posix()}/')
           for mode in ("strip", "follow", "constant", "auto")},
        # ground deeper than the ceiling: no height holds at the worst photo
        "plan uav relief too deep": uav_toml + "\n[terrain]\nground_elevation_m = [0, 600]\n",
        # recommendations set aside with a reason; the one-step base over relief
        "plan set aside": uav_toml.replace("[uav]", '[norms.gsd_limits]\nreason = "agreed"\n'
                                           '\n[norms.block_relief]\nreason = "agreed"\n\n[uav]')
        + "\n[terrain]\nground_elevation_m = [100, 150]\n",
        "plan one-step base over relief": ('[map]\nscale = 5000\nrelief_interval_m = 1\n[uav]\n'
                                           'camera = "ultracam-eagle-80"\nf_number = 5.6\n'
                                           'speed_ms = 70\nforward_overlap_pct = 50\n[area]\n'
                                           'width_m = 10000\nlength_m = 15000\n[terrain]\n'
                                           'ground_elevation_m = [0, 300]\n'),
        # an area planned far out of its projection's zone
        "plan area out of its zone": (EXAMPLES / "uav-town-2000.toml").read_text(
            encoding="utf-8").replace('file = "areas/town-uav.kml"',
                                      f'file = "{(EXAMPLES / "areas" / "town-uav.kml").as_posix()}"'
                                      '\nplan_crs = "EPSG:32634"'),
        # where the area is: coordinates swapped (shown by the site, by the CRS), a site
        # far from the area
        **_site_variants(uav_toml),
        # ground control: a survey too coarse for the height target (and beyond it even at
        # best); markers on the valley's steep walls
        "plan control coarse": (EXAMPLES / "uav-town-2000.toml").read_text(
            encoding="utf-8").replace('file = "areas/',
                                      f'file = "{(EXAMPLES / "areas").as_posix()}/')
        + "\n[control]\ngcp_sigma_z_m = 0.08\n",
        # a crosshatch: the area flown twice, every plan compared so too
        "plan crosshatch": (EXAMPLES / "uav-town-2000.toml").read_text(
            encoding="utf-8").replace('file = "areas/',
                                      f'file = "{(EXAMPLES / "areas").as_posix()}/')
        .replace("[uav]\n", "[uav]\ncrosshatch = true\n", 1),
        "plan control valley": (EXAMPLES / "uav-town-valley-2000.toml").read_text(
            encoding="utf-8").replace('dem = "dem/', f'dem = "{(EXAMPLES / "dem").as_posix()}/')
        .replace('file = "areas/', f'file = "{(EXAMPLES / "areas").as_posix()}/')
        + '\n[control]\nmode = "rtk"\n',
    }
    variants["plan uav no height is feasible"] = uav_toml.replace(  # at most 0.56 m
        "max_height_m = 500", "max_height_m = 500\ngsd_cm = 0.01")
    variants["plan uav never feasible"] = uav_toml.replace(  # at most 0 m
        'camera = "canon-eos-5d-mark-ii-50"',
        'pixel_um = 100\nfocal_mm = 1\nsensor_mm = "36x24"').replace(
        "max_height_m = 500", "max_height_m = 500\ngsd_cm = 0.01")
    out["files not written"] = _export_notes_cases()
    out.update(_tile_cases(tmp))
    for name, text in variants.items():
        r = _project(tmp, name.replace(" ", "-"), text)
        found = [w.message for w in r.warnings]
        if r.film:
            found += [r.film.reason, *_scan_messages(r.film.job.plan)]
        if r.uav:
            found += [r.uav.reason, *_uav_messages(r.uav.job.plan)]
            found += _plans_messages(r.uav)
        out[name] = found
    return out


def _plans_messages(uav: Any) -> list[Any]:
    """The plans compared: why this one, how each is flown, what each misses."""
    from scanplan.project.alternatives import describe

    out: list[Any] = [uav.choice] if uav.choice is not None else []
    for a in uav.alternatives:
        out += [describe(a), *a.rejected_because, *a.findings]
    return out


def _tile_cases(tmp: Path) -> dict[str, list[Any]]:
    """``[map] basemap`` as a tile URL whose server is gone, or lacks some tiles (a tile
    server on 127.0.0.1; the tile cache in ``tmp``)."""
    import socket

    from basemap_helpers import TileServer

    town = (EXAMPLES / "uav-town-2000.toml").read_text(encoding="utf-8").replace(
        'file = "areas/', f'file = "{(EXAMPLES / "areas").as_posix()}/')
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        closed = sock.getsockname()[1]
    out: dict[str, list[Any]] = {}
    with pytest.MonkeyPatch.context() as mp, TileServer((0, 0, 0), has=lambda z, x, y: x % 2
                                                        ) as tiles:
        mp.setenv("XDG_CACHE_HOME", str(tmp / "cache"))
        for name, url in (("plan tiles unreachable", f"http://localhost:{closed}/{{z}}/{{x}}/"
                           "{y}.png"), ("plan tiles missing", tiles.url.replace(
                               "127.0.0.1", "localhost"))):  # a host name, as in use
            text = town.replace("[map]\n", f'[map]\nbasemap = "{url}"\n'
                                'basemap_attribution = "test"\n', 1)
            out[name] = [w.message for w in _project(tmp, name.replace(" ", "-"),
                                                     text).warnings]
    return out


def _site_variants(uav_toml: str) -> dict[str, str]:
    """Projects whose area is swapped (Moscow given as [lat, lon]) or far from its site."""
    base = re.sub(r"\[area\][^\[]*", "", uav_toml)
    swapped = ("\n[area]\npolygon = [[55.75, 37.60], [55.76, 37.60], [55.76, 37.61], "
               "[55.75, 37.61]]\n")
    moscow = ("\n[area]\npolygon = [[37.60, 55.75], [37.61, 55.75], [37.61, 55.76], "
              "[37.60, 55.76]]\n")
    sun = "\n[schedule]\nstart_date = 2025-06-01\nend_date = 2025-06-02\n"
    return {
        "plan area swapped by the site": base + swapped + sun
        + "\n[site]\nlat_deg = 55.75\nlon_deg = 37.6\n",
        "plan area swapped by the crs": base + swapped + 'plan_crs = "EPSG:28407"\n',
        "plan site far from the area": base + moscow + sun
        + "\n[site]\nlat_deg = 59.94\nlon_deg = 30.31\n",
    }


def test_every_catalogue_code_is_reached_and_every_sentence_is_a_message(emitted):
    codes = set()
    for case, found in emitted.items():
        for value in found:
            assert isinstance(value, Message), (case, value)
            codes |= {m.code for m in _messages(value)}
    assert codes == set(MESSAGES), (set(MESSAGES) - codes, codes - set(MESSAGES))


def test_every_warning_code_is_its_message_code(emitted):
    warning_codes = {k.removeprefix("warn_") for k in LABELS["en"]
                     if k.startswith("warn_")}
    seen = set()
    for found in emitted.values():
        for value in found:
            if value.code in warning_codes:
                seen.add(value.code)
    assert seen == warning_codes  # each warning the reports have a heading for is raised


def test_russian_rendering_of_every_emitted_sentence(emitted):
    """Decimal comma, no English words beyond symbols, ids and the norm data's own text."""
    for case, found in emitted.items():
        for value in found:
            ru = value.text("ru")
            assert ru != str(value), (case, ru)
            assert "~" not in ru, (case, ru)
            assert not re.search(r"\d (мкм|мм|м|пикс\.|%)(\W|$)", ru), (case, ru)  # tied
            for phrase in ENGLISH_PHRASES:
                assert phrase not in ru, (case, phrase, ru)
            assert _english_words(ru, []) == [], (case, ru)
            clauses = re.sub(r"п\.\s\d+(\.\d+)+", "", ru)  # a norm's clause: п. 6.2.1
            assert not re.search(r"\d\.\d", clauses), (case, ru)  # decimal comma


def test_english_text_is_what_the_engine_always_said(emitted):
    """Phrases the docs and earlier tests quote, unchanged."""
    film = " ".join(map(str, emitted["film"]))
    assert ("PZ (height accuracy) binds at 1:10000: 8.3 µm keeps height error within 0.2·h_c = "
            "0.1 m (relief interval 0.5 m) after k = 2, Instruction's (f/b) form; next is PD at "
            "11.1 µm (+33 %).") in film
    assert ("at 1:10000, 1:15000, 1:20000 P_D (11.1, 7.4, 5.5 µm) < P_R (12.5 µm): poles, "
            "hydrants (0.2 m, circle) cannot be interpreted even on the original photos") in film
    assert ("finer than the finest step of scanner 'photoscan-td' (7 µm); choose a larger photo "
            "scale or another scanner") in film
    assert "P_S = V_s·Mk/(k·Mc) — GKINP (GNTA)-02-036-02; Miheeva & Ilushenko 2015, eq. (1)" \
        in film  # issue 13: works by author and year, never "seed 001"
    uav = " ".join(map(str, emitted["plan uav lowered"]))
    # the height given (500 m) is not called "planned", which is the lowered 210 m
    assert ("the flight height given in the project, 500 m, is above the maximum planned "
            "height 214 m (PZ binds); lowered to 210 m") in uav
    assert CONSTRAINTS["PR"].equation == ("P_R = k_R/R, k_R = 0.5 (printed 0.4) — "
                                          "Miheeva & Ilushenko 2015, eqs. (4)–(6)")


def test_json_keeps_english_and_adds_the_parameters():
    r = CliRunner().invoke(main, ["plan", str(EXAMPLES / "uav-canon-2000.toml"), "--json"])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    blur = next(w for w in doc["warnings"] if w["code"] == "motion_blur")
    # the example is lowered from the given 300 m to 210 m (the digital height accuracy)
    assert blur["message"].startswith("motion blur 0.93 px at 210 m exceeds 0.5 px")
    assert blur["params"]["denominator"] == 1858 and blur["params"]["height"] == 210
    assert doc["specification"]["uav"]["reason"] == (
        "the flight height given in the project, 300 m, is above the maximum planned height "
        "214 m (PZ binds); lowered to 210 m")
    assert PlanWarning("x", "plain").text("ru") == "plain"  # a plain string stays as it is


# --- the Russian reports of the bundled examples -------------------------------------------


def _norm_text(text: str) -> str:
    return " ".join(text.replace(NBSP, " ").split())


def _allowed(result: PlanResult) -> list[str]:
    """Text a Russian report may show in English: the user's own text and the norm data."""
    m = result.meta
    out = [m.project, m.customer, m.contractor, m.approver_position, m.approver_name,
]
    jobs = [j for j in (result.film.job if result.film else None,
                        result.uav.job if result.uav else None) if j is not None]
    for job in jobs:
        ns = job.norm_set
        out += [ns.source, ns.title, *ns.parameter_sources.values(),
                *(o.source for o in ns.objects)]
        out += [str(v) for v in ns.parameters.values()]
        out += [s.get("source", "") for s in ns.shape_rows.values()]
        inp = job.plan.inputs
        out += [getattr(inp, "camera", ""), getattr(inp, "camera_name", "")]
        out += [*ns.scanner_names.values(), *(c.name for c in ns.cameras.values())]
        out += [camera_title(ns, c, "ru") for c in ns.cameras]
        out += [scanner_title(ns, sc, "ru") for sc in ns.scanner_names]
    from scanplan.reports.references import references

    # a Russian reference list cites an English work by its English title and imprint
    # (GOST R 7.0.100-2018), never a translation
    out += [r.ru for r in references()]
    return sorted((_norm_text(x) for x in out if x), key=len, reverse=True)


def _english_words(text: str, allowed: list[str]) -> list[str]:
    text = _norm_text(text)
    for a in allowed:
        text = text.replace(a, " ")
    word = r"[A-Za-z]*[a-z][A-Za-z]*"
    return re.findall(rf"\b{word}(?: +{word}\b)+", text)


@pytest.fixture(scope="module", params=sorted(p.name for p in EXAMPLES.glob("*.toml")))
def russian(request, tmp_path_factory):
    """A bundled example (and film + UAV together) rendered in Russian: PDF text, xlsx cells."""
    pypdf = pytest.importorskip("pypdf")
    openpyxl = pytest.importorskip("openpyxl")
    from scanplan.reports.excel import render_xlsx
    from scanplan.reports.pdf import render_pdf

    result = plan_project(load_project(EXAMPLES / request.param))
    meta = dataclasses.replace(result.meta, locale="ru")
    kw = dict(scan=result.film.job if result.film else None,
              uav=result.uav.job if result.uav else None, meta=meta, spec=result)
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("SOURCE_DATE_EPOCH", EPOCH)
        pdf = render_pdf(**kw)
        xlsx = render_xlsx(**kw)
    text = "\n".join(_body(p.extract_text(), result.project.name)
                     for p in pypdf.PdfReader(io.BytesIO(pdf)).pages)
    book = openpyxl.load_workbook(io.BytesIO(xlsx))
    cells = [c.value for ws in book for row in ws.iter_rows() for c in row
             if isinstance(c.value, str)]
    return result, text, cells


def _engine_sentences(result: PlanResult) -> list[Message]:
    found: list[Any] = [w.message for w in result.warnings]
    if result.film:
        found += [result.film.reason, *_scan_messages(result.film.job.plan)]
    if result.uav:
        found += [result.uav.reason, *_uav_messages(result.uav.job.plan)]
    return [m for m in found if isinstance(m, Message)]


def _body(page: str, name: str) -> str:
    """A page's text without what closes every page — the sheet number, the running head
    (the project's name and the document's title) and the empty list markers around
    them —, so a sentence the page break cuts reads on."""
    lines = page.split("\n")
    while lines and (lines[-1].strip() in ("", "•")
                     or re.fullmatch(r"(Лист|Sheet) \d+ (/ Листов|of) \d+", lines[-1].strip())
                     or lines[-1].startswith(name)):
        lines.pop()
    return "\n".join(lines)


def _squeeze(text: str) -> str:
    """Text without any whitespace (the PDF wraps lines anywhere, even after a slash), the
    documents' reference numbers made alike, formulas as typeset (P_S → P<sub>S</sub>, GSD_max →
    GSD<sub>max</sub>, read back as PS, GSDmax; sqrt( → √()."""
    text = re.sub(r"</?sub>", "", text).replace("sqrt(", "√(")
    text = re.sub(r"(?<![\w])([A-Za-zσΔ]{1,3})_([A-Za-z0-9]{1,5})(?![\w])", r"\1\2", text)
    return re.sub(r"\[\d+\]", "[n]", re.sub(r"\s", "", text))


def _as_document(m: Message, ns: Any, locale: str) -> str:
    """An engine sentence as a document shows it: ids by names, works by reference number."""
    with document_text():
        return Bibliography(locale).cite(display_message(m, ns, locale))


def _job_ns(result: PlanResult) -> Any:
    return (result.film.job if result.film else result.uav.job).norm_set


def test_russian_pdf_has_no_english_engine_sentence(russian):
    result, text, _ = russian
    flat = _norm_text(text)
    for phrase in ENGLISH_PHRASES:
        assert phrase not in flat, phrase
    assert _english_words(text, _allowed(result)) == []
    assert "английском" not in flat  # the old note saying the engine's texts are English
    # the engine's sentences are there, in Russian: warnings, reasons of the specification,
    # explanations, formulas, the binding limit's reason
    squeezed = _squeeze(text)
    shown = [m for m in _engine_sentences(result)
             if not m.code.startswith(("reason.", "limit.", "object_source."))]
    if result.uav:
        shown += [lim.reason for lim in result.uav.job.plan.limits if lim.binding]
    assert shown
    for m in shown:
        assert _squeeze(_as_document(m, _job_ns(result), "ru")) in squeezed, m.code


def test_russian_workbook_has_no_english_engine_sentence(russian):
    result, _, cells = russian
    allowed = _allowed(result)
    for value in cells:
        for phrase in ENGLISH_PHRASES:
            assert phrase not in value, (phrase, value)
        assert _english_words(value, allowed) == [], value
    # warnings, reasons, explanations, constraint reasons and formulas, limits, object source
    squeezed = {_squeeze(c) for c in cells}
    for m in _engine_sentences(result):
        if not m.code.startswith("protects."):
            assert _squeeze(_as_document(m, _job_ns(result), "ru")) in squeezed, m.code


def test_no_engine_language_note_left():
    assert "pdf_engine_language" not in LABELS["en"]
    assert "pdf_engine_language" not in LABELS["ru"]
    macros = (ROOT / "templates" / "_macros.html").read_text(encoding="utf-8")
    assert "engine_language" not in macros


def test_english_pdf_shows_the_english_sentences():
    """The English report prints exactly the engine's English text."""
    pytest.importorskip("weasyprint")
    from scanplan.reports.pdf import render_html

    result = plan_project(load_project(EXAMPLES / "instruction-2000-film.toml"))
    page = html.unescape(render_html(scan=result.film.job, meta=result.meta, spec=result))
    for m in _engine_sentences(result):
        if not m.code.startswith("reason."):  # a reason is shown inside its explanation
            text = _as_document(m, _job_ns(result), "en")
            # after a heading or alone, a document prints it as a sentence (capital, stop)
            assert any(_squeeze(x) in _squeeze(page) for x in (text, sentence(text))), m.code


@pytest.mark.parametrize(("blur", "en", "ru"), [(0.5004, "0.5004 px", "0,5004"),
                                                (0.734, "0.73 px", "0,73")])
def test_motion_blur_is_never_shown_equal_to_its_limit(blur, en, ru):
    """A blur just over the 0.5 px limit read "0,50 пикс. больше допустимого 0,5": the
    warning shows as many decimals as it takes to be above the limit."""
    from scanplan.core.flight import MAX_BLUR_PX
    from scanplan.core.shown import shown_above as _shown_above
    from scanplan.i18n.messages import Message

    m = Message("motion_blur", blur=_shown_above(blur, MAX_BLUR_PX), height=70.0,
                limit=MAX_BLUR_PX, denominator=2000, speed=12.0)
    assert f"motion blur {en} at 70 m exceeds 0.5 px" in m.text("en")
    assert f"Смаз {ru}" in m.text("ru")


# --- Russian plural forms -------------------------------------------------------------------


@pytest.mark.parametrize(("n", "form"), [
    (1, "снимок"), (2, "снимка"), (5, "снимков"), (11, "снимков"), (21, "снимок"),
    (22, "снимка"), (25, "снимков"), (101, "снимок"), (111, "снимков"), (1501, "снимок"),
    (12, "снимков"), (14, "снимков"), (1004, "снимка"), (0, "снимков")])
def test_russian_plural_forms(n, form):
    from scanplan.i18n.messages import plural

    assert plural(n, ("снимок", "снимка", "снимков"), "ru") == form


@pytest.mark.parametrize(("n", "expected"), [(1, "1\u00a0маршрут"), (22, "22\u00a0маршрута"),
                                             (1501, "1\u00a0501\u00a0маршрут"),
                                             (111, "111\u00a0маршрутов")])
def test_a_message_counts_with_the_right_noun(n, expected):
    text = Message("layout.too_many_strips", n=n, spacing=40.0, most=10).text("ru")
    assert f"нужно {expected} при" in text
    assert f"needs {n:,d} strips" in Message("layout.too_many_strips", n=n, spacing=40.0,
                                             most=10)


def test_the_terminal_counts_strips_and_photos_with_the_right_nouns():
    from types import SimpleNamespace

    from scanplan.reports.text import format_layout

    layout = SimpleNamespace(notes={"photos": 1501}, photos=(), strips=[object()] * 21,
                             direction_deg=90.0, flight_length_m=1000.0, turn_length_m=0.0,
                             flight_time_s=0, kind="film", feasible=True, reason=None)
    text = " ".join(format_layout(layout, locale="ru").split())
    assert "21 маршрут, 1 501 снимок," in text.replace("\u00a0", " ")
    text = " ".join(format_layout(layout, locale="en").split())
    assert "21 strips, 1,501 photos," in text
