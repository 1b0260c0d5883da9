"""PROJ's network stays off inside scanplan whatever the environment says: with
``PROJ_NETWORK=ON`` and PROJ's CDN pointed at a local listener, CRSs whose best
transformation needs a grid that is not installed (OSGB 36 / British National Grid needs
OSTN15) make no connection — from the command line and through ``scanplan serve``, whose
plans run in a worker process. A CRS that cannot be used without a missing grid is exit 2
naming its key and the grid; installed in PROJ's user folder, the grid is used."""

from __future__ import annotations

import json
import os
import re
import shutil
import socket
import subprocess
import sys
import threading
import urllib.request
from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main

HEAD = """[project]
name = "London block"
[map]
scale = 2000
relief_interval_m = 0.5
[uav]
camera = "dji-zenmuse-p1-35"
speed_ms = 12
max_flight_time_min = 25
"""
BNG = [[530000, 180000], [531000, 180000], [531000, 181000], [530000, 181000]]
LONDON = [[-0.13, 51.50], [-0.11, 51.50], [-0.11, 51.51], [-0.13, 51.51]]


class Listener:
    """A TCP listener on 127.0.0.1 counting the connections it accepts."""

    def __init__(self) -> None:
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(64)
        self.sock.settimeout(0.2)
        self.connections = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.sock.getsockname()[1]}"

    def _run(self) -> None:
        while not self._stop.is_set():
            try:
                conn, _ = self.sock.accept()
            except OSError:
                continue
            self.connections += 1
            conn.close()

    def close(self) -> None:
        self._stop.set()
        self._thread.join(5)
        self.sock.close()


@pytest.fixture
def listener():
    lst = Listener()
    yield lst
    lst.close()


def _env(listener: Listener, tmp: Path) -> dict[str, str]:
    """PROJ's network switched on and its CDN at the listener; PROJ's user folder (its
    grid cache) empty."""
    return {**os.environ, "PROJ_NETWORK": "ON", "PROJ_NETWORK_ENDPOINT": listener.url,
            "XDG_DATA_HOME": str(tmp / "xdg"), "SCANPLAN_NO_FORK": "1"}


def _projects(tmp: Path) -> list[Path]:
    """Three ways a CRS reaches the plan: [area] crs, an area file's own CRS, plan_crs."""
    geojson = {"type": "FeatureCollection",
               "crs": {"type": "name", "properties": {"name": "EPSG:27700"}},
               "features": [{"type": "Feature", "properties": {},
                             "geometry": {"type": "Polygon", "coordinates": [BNG + BNG[:1]]}}]}
    (tmp / "bng.geojson").write_text(json.dumps(geojson), encoding="utf-8")
    texts = {"crs.toml": f"[area]\npolygon = {BNG}\ncrs = \"EPSG:27700\"\n",
             "file.toml": "[area]\nfile = \"bng.geojson\"\n",
             "plan-crs.toml": f"[area]\npolygon = {LONDON}\nplan_crs = \"EPSG:27700\"\n"}
    out = []
    for name, area in texts.items():
        (tmp / name).write_text(HEAD + area, encoding="utf-8")
        out.append(tmp / name)
    return out


def test_import_switches_the_network_off_whatever_the_environment_says():
    code = ("import os, subprocess, sys, pyproj\n"
            "pyproj.network.set_network_enabled(True)\n"
            "import scanplan\n"
            "child = subprocess.run([sys.executable, '-c', 'import os, pyproj; print("
            "os.environ[\"PROJ_NETWORK\"], pyproj.network.is_network_enabled())'],"
            " capture_output=True, text=True).stdout.split()\n"
            "print(pyproj.network.is_network_enabled(), os.environ['PROJ_NETWORK'], *child)")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       env={**os.environ, "PROJ_NETWORK": "ON"}, check=True)
    assert r.stdout.split() == ["False", "OFF", "OFF", "False"]


def test_the_command_line_makes_no_connection(listener, tmp_path):
    projects = _projects(tmp_path)
    r = subprocess.run([sys.executable, "-m", "scanplan", "plan", *map(str, projects),
                        "--out", str(tmp_path / "out")], capture_output=True, text=True,
                       env=_env(listener, tmp_path), timeout=600)
    assert r.returncode == 0, r.stderr
    assert "Traceback" not in r.stderr
    assert len(list((tmp_path / "out").glob("*.pdf"))) == len(projects)
    assert listener.connections == 0


def test_serve_makes_no_connection_from_a_clients_request(listener, tmp_path):
    proc = subprocess.Popen([sys.executable, "-m", "scanplan", "serve", "--port", "0",
                             "--tiles", "none"], stdout=subprocess.PIPE, text=True,
                            env=_env(listener, tmp_path))
    try:
        url = re.search(r"http://\S+/", proc.stdout.readline()).group(0)
        project = {"project": {"map": {"scale": 2000, "relief_interval_m": 0.5},
                               "uav": {"camera": "dji-zenmuse-p1-35", "speed_ms": 12},
                               "area": {"polygon": BNG, "crs": "EPSG:27700"}}}
        for route in ("api/view", "api/download/zip"):
            req = urllib.request.Request(url + route, data=json.dumps(project).encode(),
                                         headers={"Content-Type": "application/json"})
            with urllib.request.urlopen(req, timeout=300) as answer:
                assert answer.status == 200
    finally:
        proc.terminate()
        proc.wait(60)
    assert listener.connections == 0


@pytest.mark.parametrize("key,value", [
    ("crs", "+proj=longlat +ellps=clrk66 +nadgrids=us_noaa_conus.tif +type=crs"),
    ("plan_crs", "+proj=utm +zone=15 +ellps=clrk66 +nadgrids=us_noaa_conus.tif +units=m "
                 "+type=crs"),
])
def test_a_crs_whose_grid_is_missing_is_exit_2_naming_the_key(tmp_path, key, value):
    ring = [[-95.0, 40.0], [-94.99, 40.0], [-94.99, 40.01], [-95.0, 40.01]]
    p = tmp_path / "p.toml"
    p.write_text(HEAD + f"[area]\npolygon = {ring}\n{key} = \"{value}\"\n", encoding="utf-8")
    r = CliRunner().invoke(main, ["plan", str(p)])
    assert r.exit_code == 2, r.output
    assert f"area.{key} (line" in r.output and "us_noaa_conus.tif" in r.output
    assert "not installed" in r.output and "sync --file us_noaa_conus.tif" in r.output


GRID = Path("/usr/share/proj/nzgd2kgrid0005.gsb")  # Debian's proj-data


@pytest.mark.skipif(not GRID.exists(), reason="proj-data's NZGD grid is not installed")
def test_a_grid_installed_in_the_proj_user_folder_is_used(listener, tmp_path):
    ring = [[174.70, -41.30], [174.72, -41.30], [174.72, -41.29], [174.70, -41.29]]
    p = tmp_path / "nz.toml"
    p.write_text(HEAD + f"[area]\npolygon = {ring}\ncrs = \"+proj=longlat +ellps=intl "
                 f"+nadgrids={GRID.name} +type=crs\"\n", encoding="utf-8")
    env = _env(listener, tmp_path)

    def run() -> subprocess.CompletedProcess:
        return subprocess.run([sys.executable, "-m", "scanplan", "plan", str(p)],
                              capture_output=True, text=True, env=env, timeout=300)

    missing = run()
    assert missing.returncode == 2 and GRID.name in missing.stderr
    (tmp_path / "xdg" / "proj").mkdir(parents=True)
    shutil.copy(GRID, tmp_path / "xdg" / "proj" / GRID.name)
    installed = run()
    assert installed.returncode == 0, installed.stderr
    assert listener.connections == 0
