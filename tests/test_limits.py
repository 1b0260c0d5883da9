"""Issue 19 items 3, 4, 5, 7 (and issue 17 items 2–4): every in-domain input gives a result,
workbook parts are bounded, an import that takes nothing is an error, ranges agree between
the docs and the code, and messages never name an internal variable.
"""

from __future__ import annotations

import io
import json
import math
import random
import re
import warnings
import zipfile

import pytest
from click.testing import CliRunner
from hypothesis import example, given, settings
from hypothesis import strategies as st
from norm_corpus import english_workbook

from scanplan.cli.main import main
from scanplan.core.domains import DOMAINS
from scanplan.errors import InputError
from scanplan.project.jobs import uav_job

CANON = "canon-eos-5d-mark-ii-50"
INTERNAL = re.compile(r"\b(r_lpmm|upper_lpmm|nyquist_lpmm|geometric_shift_mm|n_strips|"
                      r"IndexError|ValueError|OverflowError|RecursionError|ZeroDivisionError)\b")


def cli(*args: str):
    return CliRunner().invoke(main, [str(a) for a in args])


def finite(doc: object) -> bool:
    if isinstance(doc, float):
        return math.isfinite(doc)
    if isinstance(doc, dict):
        return all(finite(v) for v in doc.values())
    if isinstance(doc, list):
        return all(finite(v) for v in doc)
    return True


# ---------------------------------------------------------------------------------------
# Item 3: zero image motion
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("speed", ["0", "1e-320", "0.0"])
def test_zero_ground_speed_gives_a_result(speed):
    """Bug: ``--speed-ms 0`` (inside the documented 0–500 m/s) exited 1 with IndexError
    whenever the image motion was exactly zero."""
    r = cli("uav", "--camera", CANON, "--height-m", "300", "--speed-ms", speed,
            "--map-scale", "2000", "--relief", "0.5", "--area-m", "1000x1000", "--json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert finite(doc)
    assert doc["resolving_power_lpmm"] > 0 and doc["max_height_m"] > 0
    assert doc["flight"]["photo_interval_s"] is None  # a hover has no photo interval
    text = cli("uav", "--camera", CANON, "--height-m", "300", "--speed-ms", speed,
               "--area-m", "1000x1000")
    assert text.exit_code == 0
    assert "inf" not in text.stdout and "nan" not in text.stdout
    assert "photo interval                  — (ground speed ≈ 0)" in text.stdout


def test_zero_motion_resolving_power_is_the_limit_of_slow_motion():
    """R at speed 0 is the limit of R as the speed goes to 0 (continuity, not a stand-in)."""
    still = uav_job(camera=CANON, f_number=8, height_m=300, speed_ms=0.0).plan
    slow = uav_job(camera=CANON, f_number=8, height_m=300, speed_ms=1e-6).plan
    fast = uav_job(camera=CANON, f_number=8, height_m=300, speed_ms=25).plan
    assert still.resolving_power_lpmm == pytest.approx(slow.resolving_power_lpmm, rel=1e-6)
    assert still.resolving_power_lpmm > fast.resolving_power_lpmm


def _domain(name: str) -> st.SearchStrategy[float]:
    d = DOMAINS[name]
    lo, hi = d.lo, d.hi
    edges = [x for x, ok in ((lo, not d.lo_open), (hi, not d.hi_open)) if ok]
    inner = st.floats(lo, hi, exclude_min=d.lo_open, exclude_max=d.hi_open,
                      allow_nan=False, allow_subnormal=lo == 0)
    return st.one_of(st.sampled_from(edges), inner) if edges else inner


@settings(max_examples=150, deadline=None)
@given(speed=_domain("speed_ms"), exposure=_domain("exposure_s"),
       shift=_domain("shift_factor"), height=st.floats(20, 2000),
       rnd=st.one_of(st.just(0.0), _domain("random_speed_ms")),
       roll=st.one_of(st.just(0.0), _domain("roll_rate_rad_s")),
       k0=st.one_of(st.none(), _domain("threshold_k0")), mapped=st.booleans())
def test_every_in_domain_motion_gives_a_result_or_not_feasible(speed, exposure, shift, height,
                                                              rnd, roll, k0, mapped):
    """Bug: 675 of 5,000 random in-domain API calls ended in IndexError. Every documented
    motion input (speed, exposure, shift factor, random speed and rate, threshold contrast
    over their whole domains, edges included) gives a plan: R is a positive number or the
    image is "not resolvable" with its warning; no library warning escapes."""
    extra = {"map_scale": 2000, "relief_interval_m": 0.5} if mapped else {}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a numpy RuntimeWarning fails the test
        plan = uav_job(camera=CANON, f_number=8, height_m=height, speed_ms=speed,
                       exposure_s=exposure, shift_factor=shift, random_speed_ms=rnd,
                       roll_rate_rad_s=roll, threshold_k0=k0, **extra).plan
    codes = {w.code for w in plan.warnings}
    if plan.resolving_power_lpmm is None:
        assert "not_resolvable" in codes
    else:
        assert plan.resolving_power_lpmm > 0 and math.isfinite(plan.ground_resolution_m)


# ---------------------------------------------------------------------------------------
# Item 7: --shift-factor range; no internal names in messages
# ---------------------------------------------------------------------------------------


def test_shift_factor_range_is_the_documented_one():
    """Bug: documented up to 10, refused above 1. Both say (0, 1] now (seed 000: the
    photographic shift is at most the geometric one)."""
    d = DOMAINS["shift_factor"]
    assert (d.lo, d.hi, d.lo_open, d.hi_open) == (0, 1, True, False)
    assert cli("uav", "--camera", CANON, "--height-m", "300",
               "--shift-factor", "1").exit_code == 0
    r = cli("uav", "--camera", CANON, "--height-m", "300", "--shift-factor", "1.5")
    assert r.exit_code == 2
    assert "error: --shift-factor: must be a finite number > 0 and ≤ 1 (got 1.5)" in r.stderr
    assert "0 < k ≤ 1" in cli("uav", "--help").stdout


@pytest.mark.parametrize("args", [
    ["--speed-ms", "1e-320"], ["--speed-ms", "0", "--exposure-s", "10"],
    ["--k0", "0.4999999999999"], ["--k0", "0.5"], ["--r-min", "0.3"],
    ["--exposure-s", "1e-6", "--speed-ms", "500"], ["--exposure-s", "10", "--speed-ms", "500"],
    ["--shift-factor", "5e-324"], ["--random-speed-ms", "100", "--roll-rate", "10"]])
def test_messages_never_name_internal_variables(args):
    """Bug: messages named ``r_lpmm`` and ``upper_lpmm`` (exit 1). Extreme in-domain input
    is exit 0, or exit 2 naming an option."""
    r = cli("uav", "--camera", CANON, "--height-m", "300", "--map-scale", "2000",
            "--relief", "0.5", *args)
    assert r.exit_code in (0, 2), r.output
    assert not INTERNAL.search(r.output), r.output
    if r.exit_code == 2:
        assert re.search(r"error: --[a-z-]+:", r.stderr), r.stderr


# ---------------------------------------------------------------------------------------
# Item 4: every workbook part is bounded
# ---------------------------------------------------------------------------------------


def _with_styles(tmp_path, n: int):
    """The bundled set as a workbook whose styles part holds ``n`` more cell formats
    (random ids, so it does not compress like a zip bomb)."""
    buf = io.BytesIO()
    english_workbook().save(buf)
    rnd = random.Random(7)
    path = tmp_path / f"styles-{n}.xlsx"
    with zipfile.ZipFile(io.BytesIO(buf.getvalue())) as zin, \
            zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as zout:
        for info in zin.infolist():
            data = zin.read(info)
            if info.filename == "xl/styles.xml":
                xf = b"".join(b'<xf numFmtId="%d" fontId="0" fillId="0" borderId="0"/>'
                              % rnd.randrange(10**6) for _ in range(n))
                head = re.search(rb'<cellXfs count="\d+">', data).end()
                data = data[:head] + xf + data[head:]
            zout.writestr(info, data)
    return path


def test_styles_part_with_a_million_entries_is_refused_before_parsing(tmp_path, user_dir):
    """Bug: a 4.9 MB xlsx whose styles part held 3 million entries passed every limit and
    took 54–80 s and 2.5 GB in ``norms validate``."""
    import tracemalloc

    from scanplan.norms import limits as norms_limits

    path = _with_styles(tmp_path, norms_limits.MAX_PART_ELEMENTS + 1000)
    tracemalloc.start()
    try:
        r = cli("norms", "validate", path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert r.exit_code == 2
    assert "zip member xl/styles.xml holds more than 100,000 XML elements" in r.output
    assert peak < 60 * 2**20  # streamed in chunks, never parsed


def test_styles_part_of_a_real_size_is_fine(tmp_path, user_dir):
    r = cli("norms", "validate", _with_styles(tmp_path, 2000))
    assert r.exit_code == 0, r.output


# ---------------------------------------------------------------------------------------
# Item 5: an import that takes nothing from the file
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("sheet", ["my-objects", "Sheet1", "Лист1"])
def test_workbook_without_a_norm_sheet_is_an_error_even_with_a_base(tmp_path, user_dir, sheet):
    """Bug: ``norms import my-objects.xlsx --name x --base SET`` with the only sheet named
    after the file exited 0, with the base set unchanged and the user's values dropped
    behind a ``note:`` line."""
    import openpyxl

    wb = openpyxl.Workbook()
    ws = wb.active
    ws.title = sheet
    ws.append(["map_scale", "object", "size_m", "shape", "source"])
    ws.append([2000, "wells", 0.5, "circle", "ours"])
    path = tmp_path / "my-objects.xlsx"
    wb.save(path)
    r = cli("norms", "import", path, "--name", "x", "--base", "gkinp-02-036-02")
    assert r.exit_code == 2
    assert f"no sheet is a norm table (sheets: {sheet!r}); nothing would be imported" \
        in r.output
    assert "name each sheet after its table: parameters, shapes, objects" in r.output
    assert not (user_dir / "x").exists()


def test_workbook_with_one_norm_sheet_and_a_base_still_imports(tmp_path, user_dir):
    import openpyxl

    wb = openpyxl.Workbook()
    ws = wb.active
    ws.title = "objects"
    ws.append(["map_scale", "object", "size_m", "shape", "source"])
    ws.append([2000, "wells", 0.5, "circle", "ours"])
    wb.create_sheet("notes")
    path = tmp_path / "mine.xlsx"
    wb.save(path)
    r = cli("norms", "import", path, "--name", "x", "--base", "gkinp-02-036-02")
    assert r.exit_code == 0, r.output
    assert "wells" in (user_dir / "x" / "objects.csv").read_text(encoding="utf-8")


def test_input_error_is_what_the_api_raises_for_a_bad_shift_factor():
    with pytest.raises(InputError) as info:
        uav_job(camera=CANON, f_number=8, height_m=300, shift_factor=2)
    assert info.value.field == "shift_factor"


# ---------------------------------------------------------------------------------------
# Issue 17 item 4: finite, meaningful numbers for extreme film input
# ---------------------------------------------------------------------------------------


def _log(name: str) -> st.SearchStrategy[float]:
    d = DOMAINS[name]
    return st.floats(math.log10(d.lo), math.log10(d.hi)).map(lambda e: float(f"{10 ** e:.6g}"))


@settings(max_examples=120, deadline=None)
@example(mk=100.0, mc=1e6, relief=0.01, size=1.0, r=1.0, focal=1.0)  # P_Z 0.000011 µm
@given(mk=_log("map_scale"), mc=_log("photo_scale"), relief=_log("relief_interval_m"),
       size=_log("object_size_m"), r=_log("resolving_power_lpmm"), focal=_log("focal_mm"))
def test_extreme_film_input_prints_no_zero_pixel_inf_or_nan(mk, mc, relief, size, r, focal):
    """Bug: 65 of ~5,000 random valid film inputs printed a scan pixel of 0.0, and inf/nan
    and numpy warnings reached the output. Every pixel printed is a positive number with its
    significant digits; every JSON number is finite; no library warning reaches the user."""
    args = ["scan", "--map-scale", f"{mk:g}", "--relief", f"{relief:g}", "--photo-scale",
            f"{mc:g}", "--focal-mm", f"{focal:g}", "--frame-mm", "230x230",
            "--resolving-power", f"{r:g}", "--object-size-m", f"{size:g}"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        text = cli(*args)
        doc = cli(*args, "--json")
    assert text.exit_code == 0, (args, text.output)
    assert doc.exit_code == 0
    assert finite(json.loads(doc.stdout))
    assert not re.search(r"\b(inf|nan)\b|\w+Warning\b", text.output), text.output
    rows = [line for line in text.stdout.splitlines()
            if re.match(r"(P[SZPRD]  |scan pixel)", line)]
    assert rows
    for line in rows:  # an English number, its thousands grouped: 5,529.5
        value = line.split()[-1].rstrip("*")
        assert re.fullmatch(r"\d{1,3}(,\d{3})*(\.\d+)?", value), (args, line)
        assert float(value.replace(",", "")) > 0, (args, line)


# ---------------------------------------------------------------------------------------
# Issue 17 item 6: the batch JSON is streamed
# ---------------------------------------------------------------------------------------


def test_batch_json_is_streamed_and_keeps_no_results(tmp_path, monkeypatch):
    """Bug: ``plan --json`` over 2,000 projects held 647 MB at its peak (every result kept
    until the end). Each project's JSON is printed when it is planned and the result
    dropped; the document is byte-identical to the one built whole."""
    import gc
    import weakref
    from pathlib import Path

    import scanplan.project.spec as spec_mod

    examples = Path(__file__).resolve().parent.parent / "examples"
    for i in range(6):
        (tmp_path / f"p{i}.toml").write_bytes(
            (examples / "instruction-2000-film.toml").read_bytes())
    (tmp_path / "p9-bad.toml").write_text("[map]\nscale = -5\n", encoding="utf-8")
    alive: list[weakref.ref] = []
    most = [0]
    real = spec_mod.plan_project

    def counting(project):
        result = real(project)
        gc.collect()
        most[0] = max(most[0], sum(r() is not None for r in alive))
        alive.append(weakref.ref(result))
        return result

    monkeypatch.setattr(spec_mod, "plan_project", counting)
    r = cli("plan", tmp_path, "--json")
    assert r.exit_code == 2  # the bad project
    doc = json.loads(r.stdout)
    assert r.stdout == json.dumps(doc, ensure_ascii=False, indent=2) + "\n"
    assert len(doc["projects"]) == 6
    assert [e["file"].rsplit("/", 1)[-1] for e in doc["errors"]] == ["p9-bad.toml"]
    assert most[0] == 0  # no earlier result was alive when the next one was planned


def test_batch_json_with_every_project_bad_is_still_one_document(tmp_path):
    for i in range(2):
        (tmp_path / f"b{i}.toml").write_text("[map]\nscale = -5\n", encoding="utf-8")
    r = cli("plan", tmp_path, "--json")
    assert r.exit_code == 2
    doc = json.loads(r.stdout)
    assert doc["projects"] == [] and len(doc["errors"]) == 2
    assert r.stdout == json.dumps(doc, ensure_ascii=False, indent=2) + "\n"
