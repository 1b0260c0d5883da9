"""docs/architecture.md, "Adding an input: touch two files", followed literally.

The package is copied, a new UAV input (a lens-hood glare factor, 0.5–2) is added the way
the walkthrough says — one ``Input`` record in ``project/inputs.py`` with its domain in
``core/domains.py``, and the keyword of ``project/jobs.py``'s job function — and nothing
else. Everything the walkthrough promises then follows from the record: the option of
``scanplan uav`` with its help and default, the project-file key, its validation (exit 2
naming the key, its line and the range; the option and the range), the keyword of the
Python API, the model's ``given`` and the generated key table of the docs.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import scanplan

PKG = Path(scanplan.__file__).parent  # the package under test (installed, or this checkout)
ROOT = PKG.parent
EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

RECORD = ('    Input("glare_factor", "uav", "glare_factor", _NUM, "lens-hood glare factor", "",\n'
          '          default=1.0, domain="glare_factor", option="--glare-factor",\n'
          '          commands=(UAV,)),\n')
DOMAIN = '    "glare_factor": Domain(0.5, 2, "", meaning="lens-hood glare factor"),\n'
KEYWORD = "    glare_factor: float = 1.0,\n"


def _insert(path: Path, anchor: str, text: str, *, before: bool = False) -> None:
    """Insert ``text`` after (or before) the one occurrence of ``anchor`` in ``path``."""
    source = path.read_text(encoding="utf-8")
    assert source.count(anchor) == 1, f"{path.name}: the walkthrough's anchor {anchor!r} moved"
    at = source.index(anchor) + (0 if before else len(anchor))
    path.write_text(source[:at] + text + source[at:], encoding="utf-8")


@pytest.fixture(scope="module")
def tree(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A copy of the package with the new input added in the two places."""
    root = tmp_path_factory.mktemp("walkthrough")
    shutil.copytree(PKG, root / "scanplan", ignore=shutil.ignore_patterns("__pycache__"))
    for folder in ("norms", "templates"):  # data beside the package in a source checkout
        if (ROOT / folder).is_dir() and not (root / folder).exists():
            shutil.copytree(ROOT / folder, root / folder)
    pkg = root / "scanplan"
    # 1. the record, and its domain
    _insert(pkg / "project" / "inputs.py", "\n)\n\nINPUTS: dict[str, Input]", "\n" + RECORD[:-1],
            before=True)
    _insert(pkg / "core" / "domains.py", "DOMAINS: dict[str, Domain] = {\n", DOMAIN)
    # 2. the keyword of the job function (an engine would read it from there)
    _insert(pkg / "project" / "jobs.py", '    yaw_rate_rad_s: float = _UAV["yaw_rate_rad_s"],\n',
            KEYWORD)
    return root


def _run(tree: Path, *args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(tree), "SCANPLAN_NO_FORK": "1"}
    return subprocess.run([sys.executable, *args], capture_output=True, text=True, env=env,
                          cwd=cwd or tree, timeout=300)


def _project(tmp_path: Path, value: str) -> Path:
    text = (EXAMPLES / "uav-canon-2000.toml").read_text(encoding="utf-8")
    text = text.replace("exposure_s = 0.001\n", f"exposure_s = 0.001\nglare_factor = {value}\n")
    path = tmp_path / "glare.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_the_option_and_its_help_follow_from_the_record(tree):
    out = _run(tree, "-m", "scanplan", "uav", "--help")
    assert out.returncode == 0, out.stderr
    text = " ".join(out.stdout.split())
    assert "--glare-factor" in text and "lens-hood glare factor" in text


def test_a_bad_option_value_names_the_option_and_the_range(tree):
    out = _run(tree, "-m", "scanplan", "uav", "--camera", "canon-eos-5d-mark-ii-50",
               "--height-m", "300", "--map-scale", "2000", "--relief", "0.5",
               "--glare-factor", "5")
    assert out.returncode == 2, out.stderr
    assert "--glare-factor" in out.stderr and "Traceback" not in out.stderr
    assert "≥ 0.5 and ≤ 2" in out.stderr, out.stderr


def test_a_bad_project_key_names_the_key_its_line_and_the_range(tree, tmp_path):
    path = _project(tmp_path, "5")
    out = _run(tree, "-m", "scanplan", "plan", str(path), "--json")
    assert out.returncode == 2, out.stderr
    line = path.read_text(encoding="utf-8").splitlines().index("glare_factor = 5") + 1
    assert f"uav.glare_factor (line {line})" in out.stderr, out.stderr
    assert "≥ 0.5 and ≤ 2" in out.stderr and "Traceback" not in out.stderr


def test_the_key_reaches_the_model_the_job_and_the_api(tree, tmp_path):
    path = _project(tmp_path, "1.5")
    out = _run(tree, "-m", "scanplan", "plan", str(path), "--json")
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout)["specification"]["uav"]["planned_height_m"] == 300
    probe = (
        "import inspect, scanplan\n"
        "from scanplan.project.model import build_model\n"
        "from scanplan.project.file import load_project\n"
        f"m = build_model(load_project({str(path)!r}))\n"
        "assert m.uav.given['glare_factor'] == 1.5, m.uav.given\n"
        "p = inspect.signature(scanplan.uav).parameters['glare_factor']\n"
        "assert p.default == 1.0, p\n"
        "assert 'Lens-hood glare factor' in scanplan.uav.__doc__\n"
        "r = scanplan.uav(camera='canon-eos-5d-mark-ii-50', height_m=300, map_scale=2000,\n"
        "                 relief_interval_m=0.5, glare_factor=1.2)\n"
        "from scanplan.errors import InputError\n"
        "try:\n"
        "    scanplan.uav(camera='canon-eos-5d-mark-ii-50', height_m=300, glare_factor=5)\n"
        "except InputError as e:\n"
        "    assert e.field == 'glare_factor' and '≤ 2' in e.message, e\n"
        "else:\n"
        "    raise AssertionError('glare_factor=5 was taken')\n"
        "print(type(r).__name__)\n"
    )
    out = _run(tree, "-c", probe)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "UavResult"


def test_the_docs_key_table_gains_the_key(tree):
    probe = ("from scanplan.project.inputs import markdown_table\n"
             "print(markdown_table('uav'))\n")
    out = _run(tree, "-c", probe)
    assert out.returncode == 0, out.stderr
    rows = [line for line in out.stdout.splitlines() if "glare_factor" in line]
    assert len(rows) == 1 and "lens-hood glare factor" in rows[0] and "1" in rows[0]
