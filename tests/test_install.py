"""The installed package finds its norms from any working directory (pip install .)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import scanplan
from scanplan.norms import bundled_norms_dir

INSTALLED = os.environ.get("SCANPLAN_TEST_INSTALLED") == "1"


@pytest.mark.skipif(not INSTALLED, reason="only meaningful against a non-editable install "
                    "(.ci/run sets SCANPLAN_TEST_INSTALLED=1)")
def test_tests_run_against_the_installed_package():
    pkg = Path(scanplan.__file__).resolve().parent
    assert "site-packages" in str(pkg)
    assert bundled_norms_dir() == pkg / "_data" / "norms"


def test_console_script_from_another_directory(tmp_path):
    exe = Path(sys.executable).parent / "scanplan"
    if not exe.exists():
        exe_path = shutil.which("scanplan")
        if exe_path is None:
            pytest.skip("scanplan console script not installed")
        exe = Path(exe_path)
    out = subprocess.run([str(exe), "scan", "--map-scale", "2000", "--relief", "1",
                          "--photo-scale", "10000", "--camera", "afa-te-100", "--json"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=60,
                         env={**os.environ, "PYTHONPATH": ""})
    assert out.returncode == 0, out.stderr
    doc = json.loads(out.stdout)
    assert doc["scenarios"][0]["constraints"]["PS"]["pixel_um"] == pytest.approx(20.0)
