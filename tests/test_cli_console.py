"""The command line at a real terminal's edges: code pages, a closed pipe, -q/-v, progress,
decimal commas, a project on stdin, chosen outputs and a missing PDF engine."""

from __future__ import annotations

import io
import os
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan.cli import console
from scanplan.cli import init as cli_init
from scanplan.cli.main import main

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
RU = EXAMPLES / "uav-town-2000-afs.toml"  # Russian report text
POLYGON = EXAMPLES / "uav-town-2000.toml"  # an area polygon: missions and GIS files
SCAN = ["scan", "--map-scale", "1:2000", "--relief", "1.0", "--photo-scale", "10000",
        "--camera", "afa-te-100"]


def _run(args: list[str], env: dict[str, str] | None = None, **kw) -> subprocess.CompletedProcess:
    full = {**os.environ, "PYTHONPATH": str(ROOT), **(env or {})}
    full.pop("SCANPLAN_VERBOSITY", None)
    return subprocess.run([sys.executable, "-m", "scanplan", *args], env=full,
                          capture_output=True, timeout=300, **kw)


@pytest.mark.parametrize("encoding", ["cp1251", "cp866"])
@pytest.mark.parametrize("args", [["plan", str(RU)], SCAN, ["plan", str(RU), "--json"]])
def test_output_in_windows_code_pages(encoding, args):
    r = _run(args, {"PYTHONIOENCODING": encoding})
    assert r.returncode == 0, r.stderr.decode(encoding, "replace")
    text = r.stdout.decode(encoding)  # every byte is the code page's
    assert not r.stderr.strip()
    if args[0] == "scan":
        assert "180x180 mm" in text and "<= 4.4" in text  # × and ≤: not in either page
    else:
        assert "Дмитров" in text  # Cyrillic kept: both code pages have it


def test_unicode_terminals_are_untouched():
    r = _run(SCAN, {"PYTHONIOENCODING": "utf-8"})
    assert r.returncode == 0 and "180×180" in r.stdout.decode("utf-8")


def test_ascii_stand_ins():
    buf = io.TextIOWrapper(io.BytesIO(), encoding="cp1251")
    console._fallback(buf)
    buf.write("σ_Z × 2 ≤ 5 µm — ok, №1 “x”")
    buf.flush()
    assert buf.buffer.getvalue().decode("cp1251") == 'sigma_Z x 2 <= 5 µm — ok, №1 “x”'
    ascii_ = io.TextIOWrapper(io.BytesIO(), encoding="ascii")
    console._fallback(ascii_)
    ascii_.write("Дм σ é")
    ascii_.flush()
    assert ascii_.buffer.getvalue() == b"?? sigma e"


def test_closed_pipe_exits_quietly():
    full = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.Popen([sys.executable, "-m", "scanplan", "plan", str(RU)], env=full,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.close()  # the reader has gone before anything was printed (| head -0)
    _, err = proc.communicate(timeout=300)
    assert proc.returncode == console.EXIT_PIPE
    assert err == b""  # no "error: Broken pipe", no "Exception ignored"


def test_quiet_and_verbose(tmp_path):
    runner = CliRunner()
    loud = runner.invoke(main, ["plan", str(RU), "--out", str(tmp_path / "a"),
                                "--formats", "xlsx"])
    assert loud.exit_code == 0 and "wrote" in loud.stderr
    quiet = runner.invoke(main, ["plan", str(RU), "--out", str(tmp_path / "b"), "-q",
                                 "--formats", "xlsx"])
    assert quiet.exit_code == 0 and quiet.stderr == "" and (tmp_path / "b" / "spec.xlsx").exists()
    before = runner.invoke(main, ["-q", "plan", str(RU), "--out", str(tmp_path / "c"),
                                  "--formats", "xlsx"])
    assert before.exit_code == 0 and before.stderr == ""
    again = runner.invoke(main, ["plan", str(RU), "--out", str(tmp_path / "d"),
                                 "--formats", "xlsx"])
    assert "wrote" in again.stderr  # -q of the earlier run is not kept
    verbose = runner.invoke(main, ["plan", str(RU), str(POLYGON), "-v", "--jobs", "1"])
    assert verbose.exit_code == 0
    assert f"1/2 {RU}: ok" in verbose.stderr and f"2/2 {POLYGON}: ok" in verbose.stderr
    assert "planning" not in verbose.stderr  # no progress bar off a terminal


class _Tty(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_progress_bar_on_a_terminal_only(monkeypatch):
    tty = _Tty()
    monkeypatch.setattr(sys, "stderr", tty)
    console.set_verbosity()
    bar = console.Progress(4, "planning", "projects", delay_s=0.0)
    for n in range(1, 5):
        bar.step(n)
    bar.close()
    shown = tty.getvalue()
    assert "planning" in shown and "4/4" in shown and "projects/s" in shown
    off = io.StringIO()  # not a terminal: nothing drawn
    monkeypatch.setattr(sys, "stderr", off)
    bar = console.Progress(4, "planning", "projects", delay_s=0.0)
    bar.step(2)
    bar.close()
    assert off.getvalue() == ""
    monkeypatch.setattr(sys, "stderr", tty)
    console.set_verbosity(quiet=True)  # -q: no bar at a terminal either
    start = len(tty.getvalue())
    bar = console.Progress(4, "planning", "projects", delay_s=0.0)
    bar.step(3)
    bar.close()
    console.set_verbosity()
    assert tty.getvalue()[start:] == ""


def test_decimal_comma_in_options_and_prompts(tmp_path, monkeypatch):
    runner = CliRunner()
    base = ["uav", "--camera", "dji-zenmuse-p1-35", "--map-scale", "2000", "--json"]
    comma = runner.invoke(main, [*base, "--relief", "0,5", "--height-m", "97,5"])
    point = runner.invoke(main, [*base, "--relief", "0.5", "--height-m", "97.5"])
    assert comma.exit_code == 0, comma.output
    assert comma.stdout == point.stdout
    bad = runner.invoke(main, [*base, "--relief", "0,5,1"])
    assert bad.exit_code == 2 and "--relief" in bad.output
    monkeypatch.setattr(cli_init, "_interactive", lambda: True)
    p = tmp_path / "asked.toml"
    r = runner.invoke(main, ["init", str(p)], input="uav\n1:500\n0,25\nTown\nru\n\n")
    assert r.exit_code == 0, r.output
    assert tomllib.loads(p.read_text(encoding="utf-8"))["map"]["relief_interval_m"] == 0.25


def test_plan_reads_the_project_from_stdin(tmp_path):
    runner = CliRunner()
    text = RU.read_text(encoding="utf-8")
    r = runner.invoke(main, ["plan", "-", "--json"], input=text)
    assert r.exit_code == 0, r.output
    from_file = runner.invoke(main, ["plan", str(RU), "--json"])
    assert r.stdout.replace("<stdin>", "") .count("Дмитров") == from_file.stdout.count("Дмитров")
    mixed = runner.invoke(main, ["plan", "-", str(RU)], input=text)
    assert mixed.exit_code == 2 and "standard input" in mixed.output
    empty = runner.invoke(main, ["plan", "-"], input="")
    assert empty.exit_code == 2 and "<stdin>" in empty.output
    bad = runner.invoke(main, ["plan", "-"], input="[map]\nscale = 2000\n")
    assert bad.exit_code == 2 and "<stdin>" in bad.output and "relief_interval_m" in bad.output


def _small_polygon(tmp_path: Path) -> Path:
    """POLYGON's project over a polygon of about 380 × 450 m (one sortie): the same kinds of output,
    each a few photos long."""
    path = tmp_path / "small-polygon.toml"
    path.write_text(POLYGON.read_text(encoding="utf-8").split("[area]")[0] + (
        "[area]\npolygon = [[37.600, 55.750], [37.606, 55.750], [37.606, 55.754], "
        "[37.600, 55.754]]\n"), encoding="utf-8")
    return path


def test_formats_choose_the_outputs(tmp_path):
    runner = CliRunner()
    small = _small_polygon(tmp_path)
    r = runner.invoke(main, ["plan", str(small), "--out", str(tmp_path / "m"),
                             "--formats", "missions"])
    assert r.exit_code == 0, r.output
    names = sorted(p.name for p in (tmp_path / "m").iterdir() if not p.name.startswith("."))
    assert names and all(n.startswith("mission") for n in names)
    assert any(n.endswith(".plan") for n in names) and any(n.endswith(".waypoints")
                                                            for n in names)
    r = runner.invoke(main, ["plan", str(small), "--out", str(tmp_path / "g"),
                             "--formats", "gis,xlsx"])
    assert sorted(p.name for p in (tmp_path / "g").iterdir() if p.name[0] != ".") == [
        "flight.geojson", "flight.gpkg", "flight.kml", "photos.csv", "spec.xlsx"]
    bad = runner.invoke(main, ["plan", str(small), "--out", str(tmp_path / "x"),
                               "--formats", "xlsx,docx"])
    assert bad.exit_code == 2 and "--formats" in bad.output and "missions" in bad.output
    # without --out there is nothing for it to choose: said, not silently ignored
    alone = runner.invoke(main, ["plan", str(small), "--formats", "xlsx"])
    assert alone.exit_code == 2 and "error: --formats: chooses the files --out writes" in (
        alone.stderr), alone.output


@pytest.fixture
def no_pdf_engine(tmp_path):
    """A WeasyPrint that fails to load as it does without the system's Pango (cffi's
    dlopen raises OSError), first on the import path of the child process."""
    fake = tmp_path / "fake" / "weasyprint"
    fake.mkdir(parents=True)
    (fake / "__init__.py").write_text(
        "raise OSError(\"cannot load library 'libpango-1.0-0': libpango-1.0-0: cannot open "
        "shared object file: No such file or directory\")\n", encoding="utf-8")
    return {"PYTHONPATH": os.pathsep.join([str(fake.parent), str(ROOT)])}


def test_without_pdf_engine_the_rest_is_written(tmp_path, no_pdf_engine):
    import openpyxl

    out = tmp_path / "out"
    small = _small_polygon(tmp_path)
    r = _run(["plan", str(small), "--out", str(out)], no_pdf_engine)
    err = r.stderr.decode("utf-8")
    assert r.returncode == 0, err
    names = {p.name for p in out.iterdir() if not p.name.startswith(".")}
    assert "spec.xlsx" in names and "spec.pdf" not in names
    assert {"flight.kml", "flight.geojson", "photos.csv"} <= names
    assert any(n.startswith("mission") and n.endswith(".plan") for n in names)
    assert "PDF engine (WeasyPrint) could not load" in err and "libpango" in err
    assert "apt-get install libpango-1.0-0" in err and "Traceback" not in err
    openpyxl.load_workbook(out / "spec.xlsx")  # a real workbook
    # asked for by name: the workbook is still written, and the run fails at the end
    named = _run(["plan", str(small), "--out", str(tmp_path / "n"), "--formats",
                  "xlsx,pdf"], no_pdf_engine)
    assert named.returncode == 1
    assert {p.name for p in (tmp_path / "n").iterdir() if p.name[0] != "."} == {"spec.xlsx"}
    assert "error: the PDF was not written" in named.stderr.decode("utf-8")
