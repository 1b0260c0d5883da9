"""``scanplan serve`` on the command line: localhost unless told otherwise, a token off it,
the page and API served, the vendored scripts as the registry shipped them."""

from __future__ import annotations

import hashlib
import json
import re
import subprocess
import sys
import urllib.error
import urllib.request
from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main

VENDOR = Path(__file__).resolve().parents[1] / "scanplan" / "web" / "static" / "vendor"


@pytest.mark.parametrize("args,says", [
    (["--host", "0.0.0.0"], "--host: 0.0.0.0 is reachable from other machines; add "
     "--allow-remote"),
    (["--host", "192.168.1.5"], "add --allow-remote"),
    (["--tiles", "ftp://tiles/{z}/{x}/{y}"], "--tiles: must be"),
    (["--port", "70000"], "70000 is not in the range"),
])
def test_bad_options_exit_2_before_anything_listens(args, says):
    r = CliRunner().invoke(main, ["serve", *args])
    assert r.exit_code == 2 and says in r.output


def test_help_lists_serve_without_importing_the_framework():
    code = ("import sys; from scanplan.cli.main import main\n"
            "try: main(['--help'])\nexcept SystemExit: pass\n"
            "print('fastapi' in sys.modules, 'uvicorn' in sys.modules)")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       check=True)
    assert re.search(r"^\s+serve\s+Plan on a map", r.stdout, re.M)
    assert r.stdout.strip().endswith("False False")


def _serve(*args: str) -> tuple[subprocess.Popen, str]:
    proc = subprocess.Popen([sys.executable, "-m", "scanplan", "serve", "--port", "0",
                             "--tiles", "none", *args], stdout=subprocess.PIPE, text=True)
    lines = [proc.stdout.readline() for _ in range(3 if "--allow-remote" in args else 2)]
    return proc, "".join(lines)


def test_serve_prints_its_address_and_serves_the_page():
    proc, said = _serve()
    try:
        url = re.search(r"http://127\.0\.0\.1:\d+/", said).group(0)
        page = urllib.request.urlopen(url + "?lang=ru", timeout=30).read().decode()
        assert '<html lang="ru">' in page and "static/vendor/leaflet/leaflet.js" in page
        rows = json.loads(urllib.request.urlopen(url + "api/inputs", timeout=30).read())
        assert any(r["key"] == "relief_interval_m" for r in rows)
    finally:
        proc.terminate()
        proc.wait(30)
    assert proc.returncode is not None


def test_off_localhost_every_api_call_needs_the_printed_token():
    proc, said = _serve("--host", "0.0.0.0", "--allow-remote")
    try:
        token = re.search(r"token \(every API call needs it\): (\S+)", said).group(1)
        url = re.search(r"http://\S+?/(?=\?)", said).group(0)
        with pytest.raises(urllib.error.HTTPError) as e:
            urllib.request.urlopen(url + "api/inputs", timeout=30)
        assert e.value.code == 403
        ok = urllib.request.Request(url + "api/inputs", headers={"X-Scanplan-Token": token})
        assert urllib.request.urlopen(ok, timeout=30).status == 200
    finally:
        proc.terminate()
        proc.wait(30)


def test_vendored_scripts_are_the_registry_files_the_notice_names():
    notice = (VENDOR / "NOTICE.md").read_text(encoding="utf-8")
    hashes = re.findall(r"^([0-9a-f]{64})  (\S+)$", notice, re.M)
    assert len(hashes) == 4
    for digest, name in hashes:
        assert hashlib.sha256((VENDOR / name).read_bytes()).hexdigest() == digest, name
    for folder in ("leaflet", "leaflet-geoman"):
        assert "Permission is hereby granted" in (VENDOR / folder / "LICENSE").read_text() \
            or "Redistribution and use" in (VENDOR / folder / "LICENSE").read_text()
    assert "polyclip-ts" in (VENDOR / "leaflet-geoman" / "THIRD-PARTY-LICENSES.txt").read_text()
