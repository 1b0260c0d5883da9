"""The input registry (scanplan/project/inputs.py) is the one home of every input: the
command line, the API, the project file and docs/project-file.md agree with it (issue 14)."""

from __future__ import annotations

import inspect
import re
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

from scanplan.cli.main import OPTION_NAMES, main
from scanplan.core.domains import DOMAINS
from scanplan.errors import FieldValueError, InputError
from scanplan.project import inputs as I
from scanplan.project.file import KEYS, parse_project
from scanplan.project.jobs import AIRCRAFT_SIDE_OVERLAP_PCT, UAV_DEFAULTS, scan_job, uav_job
from scanplan.project.spec import DEFAULT_FILM_SIDE_OVERLAP_PCT

ROOT = Path(__file__).resolve().parents[1]
PLAN_OF = {"scan": "film", "uav": "uav"}
NOT_INPUTS = {"xlsx_path", "pdf_path", "force", "as_json",  # where to write, not what to plan
              "quiet", "verbose"}  # how much to say


def test_docs_key_tables_are_generated_from_the_registry():
    text = (ROOT / "docs" / "project-file.md").read_text(encoding="utf-8")
    assert text.count("<!-- keys: ") == len(KEYS)
    assert I.update_docs(text) == text, "run: python -m scanplan.project.inputs " \
                                        "docs/project-file.md"
    for section, keys in KEYS.items():
        for key in keys:
            assert f"| `{key}` |" in I.markdown_table(section)


def test_update_docs_rewrites_a_stale_table():
    stale = "x\n<!-- keys: map -->\n| old |\n<!-- /keys -->\ny"
    fresh = I.update_docs(stale)
    assert "| old |" not in fresh and "| `relief_interval_m` | number |" in fresh
    assert fresh.startswith("x\n") and fresh.endswith("\ny")


def test_project_file_keys_are_the_registry():
    assert I.key_table() == KEYS
    assert KEYS["uav"]["speed_ms"] == ("number", "ground speed [m/s] (default 15; required "
                                       "for a camera on an aircraft)")
    assert all(kind in I.KINDS for keys in KEYS.values() for kind, _ in keys.values())


def _params(command: str) -> dict[str, click.Parameter]:
    return {p.name: p for p in main.commands[command].params}


@pytest.mark.parametrize("command", ["scan", "uav"])
def test_cli_options_are_the_registry(command):
    """Click introspection: each registry option of the command is there, with the
    registry's option name, destination and default; and every input option of the
    command has a record."""
    params = _params(command)
    plan = PLAN_OF[command]
    want = {r for r in I.records(plan) if r.option and plan in r.commands}
    assert want
    seen = set()
    for r in want:
        if r.section.split(".")[0] != plan and I.get(r.name, plan) is not r:
            continue  # shadowed by the plan's own record (height_formula)
        dest = r.option.lstrip("-").replace("-", "_") if r.section == "project" else r.name
        p = params[dest]
        seen.add(dest)
        assert r.option in p.opts, (r.name, p.opts)
        if r.by_carrier:  # speed and overlaps: None, uav_job chooses by carrier
            ctx = main.commands[command].make_context(command, [])
            assert ctx.params[dest] is None, r.name
        elif r.default is not None:
            want_default = str(r.default) if r.choices else r.default
            assert p.default == want_default, (r.name, p.default)
        assert p.help and I.describe(r, cli=True).split(" (")[0][1:] in p.help
    assert set(params) - NOT_INPUTS == seen


def test_option_names_cover_every_error_field():
    assert OPTION_NAMES == I.option_names()
    assert OPTION_NAMES["speed_ms"] == "--speed-ms"
    assert OPTION_NAMES["height_tolerance_up_pct"] == "--height-tolerance-pct"
    assert OPTION_NAMES["recognition_rounding"] == "--rounding"
    no_option = {"scanner", "shape", "height_tolerance_down_pct", "photo_scale"}
    assert set(DOMAINS) - no_option <= set(OPTION_NAMES)


def test_every_domain_of_a_record_exists():
    for r in I.records():
        assert not r.domain or r.domain in DOMAINS or r.domain in I.PROJECT_DOMAINS, r
        assert (I.domain_of(r) is None) == (not r.domain), r


def _defaults(func) -> dict[str, object]:
    return {k: p.default for k, p in inspect.signature(func).parameters.items()
            if p.default is not inspect.Parameter.empty}


def test_api_defaults_are_the_registry():
    uav, scan = _defaults(uav_job), _defaults(scan_job)
    for plan, got in (("uav", uav), ("film", scan)):
        for r in I.records(plan):
            if r.default is None or r.name not in got or r.section == "project":
                continue
            if r.name in UAV_DEFAULTS and plan == "uav":  # by carrier: None in the signature
                assert got[r.name] is None and UAV_DEFAULTS[r.name] == r.default
                continue
            assert got[r.name] == r.default, (plan, r.name)
    assert UAV_DEFAULTS == {"speed_ms": 15.0, "forward_overlap_pct": 80.0,
                            "side_overlap_pct": 60.0}
    assert AIRCRAFT_SIDE_OVERLAP_PCT == DEFAULT_FILM_SIDE_OVERLAP_PCT == 30.0


def test_model_defaults_agree_with_the_registry():
    """Defaults whose home is a model (the MTF chain, the norm set name) and that the
    registry shows to users are the same numbers."""
    from scanplan.core.mtf import DEFAULT_HAZE_CONTRAST, DEFAULT_K0
    from scanplan.norms import DEFAULT_NORM_SET

    assert I.by_key("uav.atmosphere", "threshold_k0").default == DEFAULT_K0
    assert I.by_key("uav.atmosphere", "haze_contrast").default == DEFAULT_HAZE_CONTRAST
    assert I.by_key("norms", "set").default == DEFAULT_NORM_SET


def test_the_15_ms_speed_lives_in_one_place():
    """The issue's example: the UAV speed default is written once, in the registry."""
    hits = [p for p in (ROOT / "scanplan").rglob("*.py")
            if re.search(r"\b15(\.0)?\b[^\n]*m/s|speed_ms[^\n]*\b15\.0\b",
                         p.read_text(encoding="utf-8"))]
    assert [p.name for p in hits] == ["inputs.py"]


@pytest.mark.parametrize("field,plan,key", [
    ("height_tolerance_up_pct", "uav", ("uav", "height_tolerance_pct")),
    ("sensor_width_mm", "uav", ("uav", "sensor_mm")),
    ("k0", "uav", ("uav.atmosphere", "threshold_k0")),
    ("height_formula", "uav", ("uav", "height_formula")),
    ("height_formula", "film", ("norms", "height_formula")),
    ("photo_scale", "film", ("film", "photo_scales")),
    ("frame_along_mm", "film", ("film", "frame_mm")),
    ("--norms", "film", ("norms", "set")),
    ("area_m", "uav", ("", "area")),
    ("nonsense", "uav", None),
])
def test_project_key_of_an_error_field(field, plan, key):
    assert I.project_key(field, plan) == key


def test_a_project_error_names_the_key_from_the_registry(tmp_path):
    from scanplan.project.spec import plan_project

    text = (ROOT / "examples" / "uav-canon-2000.toml").read_text(encoding="utf-8")
    text = re.sub(r"(?m)^height_tolerance_pct = .*$", "height_tolerance_pct = 150", text)
    with pytest.raises(InputError) as err:
        plan_project(parse_project(text, tmp_path / "p.toml"))
    assert "uav.height_tolerance_pct (line " in err.value.field


def test_core_errors_carry_a_typed_field_and_nobody_splits_messages():
    from scanplan.core.flight import ground_sample_distance_m

    with pytest.raises(FieldValueError) as err:
        ground_sample_distance_m(-1.0, 50.0, 100.0)
    assert err.value.field == "pixel_um" and err.value.message.startswith("must be > 0")
    assert str(err.value).startswith("pixel_um must be > 0")  # the text as before
    splitters = [str(p.relative_to(ROOT)) for p in (ROOT / "scanplan").rglob("*.py")
                 if re.search(r"str\(exc\)\.(r?split|partition)|exc\.args\[0\]\.split",
                              p.read_text(encoding="utf-8"))]
    assert not splitters


def test_uav_engine_turns_a_model_error_into_an_input_error():
    from scanplan.rules import uav as U

    job = uav_job(camera="dji-zenmuse-p1-35", height_m=100.0)
    bad = job.plan.inputs.__class__(**{**vars(job.plan.inputs), "r_min": 0.5, "r_max": 0.3})
    with pytest.raises(InputError) as err:
        U._resolution(bad, 100.0)
    assert err.value.field == "r_min"


def _strings_of_xlsx(path: Path) -> str:
    import openpyxl

    book = openpyxl.load_workbook(path)
    return "\n".join(str(c.value) for ws in book for row in ws.iter_rows() for c in row
                     if c.value is not None)


@pytest.mark.parametrize("example,edits", [
    ("instruction-2000-film.toml", [(r'(?m)^scale = .*$', 'scale = "1:2000"'),
                                    (r'(?m)^photo_scales = .*$',
                                     'photo_scales = ["1:6000", "1:8 000", "1:10000"]')]),
    ("archive-12000-for-2000.toml", [(r'(?m)^scale = .*$', 'scale = "1:2 000"'),
                                     (r'(?m)^photo_scale = .*$', 'photo_scale = "1:12000"')]),
    ("map-10000-relief-1m.toml", [(r'(?m)^scale = .*$', 'scale = "1:10000"')]),
])
def test_a_scale_written_1_colon_n_never_prints_1_1_n(tmp_path, example, edits):
    """Issue 14's symptom: ``[map] scale = "1:10000"`` printed "map 1:1:10000"."""
    text = (ROOT / "examples" / example).read_text(encoding="utf-8")
    for pattern, repl in edits:
        text, n = re.subn(pattern, repl, text, count=1)
        assert n == 1, pattern
    project = tmp_path / "p.toml"
    project.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    runner = CliRunner()
    shown = runner.invoke(main, ["plan", str(project), "--out", str(out)])
    assert shown.exit_code == 0, shown.output
    as_json = runner.invoke(main, ["plan", str(project), "--json"])
    assert as_json.exit_code == 0
    texts = {"text": shown.output, "json": as_json.output,
             "xlsx": _strings_of_xlsx(out / "spec.xlsx")}
    if example.startswith("instruction"):
        from pypdf import PdfReader

        texts["pdf"] = "\n".join(p.extract_text() for p in PdfReader(out / "spec.pdf").pages)
    for kind, shown_text in texts.items():
        assert "1:1:" not in shown_text, kind
        assert re.search(r"1:2[  ]?000|1:10[  ]?000|2000", shown_text), kind


def test_a_plans_records_are_made_once():
    """A plan asks for its inputs' records hundreds of times (defaults, domains, kwargs):
    the tuple of a plan's records and each name's lookup are made once per process."""
    assert I.records("uav") is I.records("uav")
    assert I.records() is I.records()
    assert [r.name for r in I.records("uav")] == [
        r.name for r in I._RECORDS if "uav" in r.plans]
    # the plan's own section still wins over a shared one, from the cache as without it
    assert I.get("forward_overlap_pct", "uav").section == "uav"
    assert I.get("forward_overlap_pct", "uav") is I.get("forward_overlap_pct", "uav")
