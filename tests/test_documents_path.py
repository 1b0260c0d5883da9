"""The one document path (reports/documents.py) as a user meets it: the Python API writes
what ``plan --out`` writes, an output asked for that the project cannot give is refused,
and a missing PDF engine is scanplan's own error with nothing on standard output."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

import scanplan
from scanplan.cli.main import main
from scanplan.errors import InputError
from scanplan.io.folderset import current_set, read_manifest, supported
from scanplan.io.targets import SETS, is_managed

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
EPOCH = "1700000000"


def _small_polygon(tmp_path: Path) -> Path:
    """uav-town-2000's project over a polygon of about 380 × 450 m (one sortie): every
    kind of output, each a few photos long."""
    path = tmp_path / "small-polygon.toml"
    text = (EXAMPLES / "uav-town-2000.toml").read_text(encoding="utf-8").split("[area]")[0]
    path.write_text(text + "[area]\npolygon = [[37.600, 55.750], [37.606, 55.750], "
                    "[37.606, 55.754], [37.600, 55.754]]\n", encoding="utf-8")
    return path


def _block(tmp_path: Path) -> Path:
    """A UAV project over a width × length block: no area on the map."""
    path = tmp_path / "block.toml"
    path.write_text('[map]\nscale = 2000\nrelief_interval_m = 0.5\n[uav]\n'
                    'camera = "dji-zenmuse-p1-35"\n[area]\nwidth_m = 500\nlength_m = 400\n',
                    encoding="utf-8")
    return path


def _visible(folder: Path) -> list[str]:
    """The names a reader of ``folder`` sees: its files, not the folder of file sets."""
    return sorted(p.name for p in folder.iterdir() if p.name != SETS)


def _files(folder: Path) -> dict[str, bytes]:
    """What a reader of ``folder`` opens: each visible file's bytes (a link followed)."""
    return {name: (folder / name).read_bytes() for name in _visible(folder)}


def test_write_writes_every_file_plan_out_writes_byte_for_byte(tmp_path, monkeypatch):
    """``ProjectResult.write()`` (no ``formats``) and ``scanplan plan --out`` give the same
    files with the same bytes: the documents, the missions and the GIS files."""
    monkeypatch.setenv("SOURCE_DATE_EPOCH", EPOCH)
    monkeypatch.setenv("SCANPLAN_NO_FORK", "1")
    project = _small_polygon(tmp_path)
    r = CliRunner().invoke(main, ["plan", str(project), "--out", str(tmp_path / "cli")])
    assert r.exit_code == 0, r.output
    written = scanplan.plan(project).write(tmp_path / "api")
    cli, api = _files(tmp_path / "cli"), _files(tmp_path / "api")
    assert {"spec.xlsx", "spec.pdf", "flight.kml", "flight.geojson", "flight.gpkg",
            "photos.csv", "mission.plan", "mission.waypoints"} <= set(cli)
    assert sorted(api) == sorted(cli)
    assert [n for n in cli if api[n] != cli[n]] == []
    assert [p.name for p in written][:2] == ["spec.xlsx", "spec.pdf"]
    # written as plan --out writes: one set swapped in at once, each name a link into it
    assert supported(tmp_path)
    for folder in (tmp_path / "cli", tmp_path / "api"):
        assert [n for n in _visible(folder) if not is_managed(folder / n)] == []
        assert sorted(read_manifest(current_set(folder))) == sorted(cli)


def test_write_chooses_outputs_as_formats_does(tmp_path):
    project = _small_polygon(tmp_path)
    result = scanplan.plan(project)
    names = sorted(p.name for p in result.write(tmp_path / "gis", formats=["gis", "xlsx"]))
    assert names == ["flight.geojson", "flight.gpkg", "flight.kml", "photos.csv",
                     "spec.xlsx"]
    with pytest.raises(InputError) as exc:
        result.write(tmp_path / "bad", formats=["docx"])
    assert exc.value.field == "formats" and "xlsx, pdf, missions, gis" in exc.value.message
    assert not (tmp_path / "bad").exists()


def test_gis_without_an_area_on_the_map_is_refused(tmp_path):
    """Bug: ``--formats gis`` on a project without a polygon exited 0 having written
    nothing it was asked for. Now exit 2, naming the option and why."""
    block = _block(tmp_path)
    r = CliRunner().invoke(main, ["plan", str(block), "--out", str(tmp_path / "o"),
                                  "--formats", "gis"])
    assert r.exit_code == 2, r.output
    assert "error: --formats: gis writes the flight over the area" in r.stderr
    assert "has no area on the map" in r.stderr and "Traceback" not in r.output
    assert not (tmp_path / "o").exists()
    with pytest.raises(InputError) as exc:
        scanplan.plan(block).write(tmp_path / "a", formats=["missions"])
    assert exc.value.field == "formats"
    # all outputs (no --formats): the documents, and a note that no flight files are due
    r = CliRunner().invoke(main, ["plan", str(block), "--out", str(tmp_path / "all")])
    assert r.exit_code == 0, r.output


@pytest.fixture
def no_pdf_engine(tmp_path):
    """A WeasyPrint that fails to load as it does without the system's Pango: its own
    notice on standard output, then cffi's OSError."""
    fake = tmp_path / "fake" / "weasyprint"
    fake.mkdir(parents=True)
    (fake / "__init__.py").write_text(
        "print('WeasyPrint could not import some external libraries.')\n"
        "raise OSError(\"cannot load library 'libpango-1.0-0': libpango-1.0-0: cannot open "
        "shared object file: No such file or directory\")\n", encoding="utf-8")
    return {**os.environ, "PYTHONPATH": os.pathsep.join([str(fake.parent), str(ROOT)])}


def test_write_without_a_pdf_engine_is_scanplans_error(tmp_path, no_pdf_engine):
    """Bug: without Pango ``write()`` raised a raw OSError and WeasyPrint's notice went to
    standard output. Now scanplan's PdfEngineError, saying what to install; nothing on
    stdout, nothing written; the other documents are still written when asked for."""
    script = (
        "import scanplan, sys\n"
        "from scanplan.errors import PdfEngineError\n"
        f"r = scanplan.plan({str(_block(tmp_path))!r})\n"
        "try:\n"
        f"    r.write({str(tmp_path / 'out')!r})\n"
        "except PdfEngineError as exc:\n"
        "    print(exc, file=sys.stderr)\n"
        "    sys.exit(3)\n")
    done = subprocess.run([sys.executable, "-c", script], env=no_pdf_engine,
                          capture_output=True, text=True, check=False)
    assert done.returncode == 3, done.stderr
    assert done.stdout == ""
    assert "no PDF written: the PDF engine (WeasyPrint) could not load" in done.stderr
    assert "libpango" in done.stderr and "apt-get install" in done.stderr
    assert not (tmp_path / "out").exists()  # not even the folder of file sets
    only = subprocess.run([sys.executable, "-c", script.replace(
        "r.write(", "r.write(formats=['xlsx'], out_dir=")], env=no_pdf_engine,
        capture_output=True, text=True, check=False)
    assert only.returncode == 0, only.stderr
    assert only.stdout == "" and _visible(tmp_path / "out") == ["spec.xlsx"]
    assert sorted(os.listdir(tmp_path / "out")) == [SETS, "spec.xlsx"]  # one set, no leftovers
    assert sorted(read_manifest(current_set(tmp_path / "out"))) == ["spec.xlsx"]


def test_the_command_lines_outputs_are_the_document_paths():
    """``--formats`` names the outputs of reports/documents.py (the command line keeps its
    own copy so that ``scanplan --help`` imports no report)."""
    from scanplan.cli.outputs import FORMATS
    from scanplan.reports.documents import OUTPUTS

    assert FORMATS == OUTPUTS


def test_shell_completion_offers_cameras_norm_sets_and_outputs(monkeypatch):
    """Tab completes a camera id, a norm set and the outputs of ``--formats`` (click's
    completion, as docs/cli.md tells a shell to use it)."""
    from click.shell_completion import ShellComplete

    def complete(args: list[str], incomplete: str) -> list[str]:
        comp = ShellComplete(main, {}, "scanplan", "_SCANPLAN_COMPLETE")
        return [c.value for c in comp.get_completions(args, incomplete)]

    assert "dji-zenmuse-p1-35" in complete(["uav", "--camera"], "dji-zen")
    assert "rc30-153" in complete(["cameras", "show"], "rc30")
    assert "gkinp-02-036-02" in complete(["scan", "--norms"], "gk")
    assert complete(["plan", "x.toml", "--formats"], "xlsx,m") == ["xlsx,missions"]
    assert "pdf" not in complete(["plan", "x.toml", "--formats"], "pdf,")
    text = (ROOT / "docs" / "cli.md").read_text(encoding="utf-8")
    assert "_SCANPLAN_COMPLETE=bash_source scanplan" in text


def test_plan_locale_overrides_the_projects_language(tmp_path):
    """``plan --locale ru`` prints and writes in Russian an English project (a bundled
    example is planned in Russian without editing it)."""
    project = _block(tmp_path)  # no [project] locale: English
    runner = CliRunner()
    en = runner.invoke(main, ["plan", str(project)])
    ru = runner.invoke(main, ["plan", str(project), "--locale", "ru"])
    assert en.exit_code == 0 and ru.exit_code == 0, ru.output
    assert "recommended flight height" in en.stdout
    assert "рекомендуемая высота полёта" in ru.stdout and "recommended" not in ru.stdout
    bad = runner.invoke(main, ["plan", str(project), "--locale", "de"])
    assert bad.exit_code == 2 and "--locale" in bad.stderr
