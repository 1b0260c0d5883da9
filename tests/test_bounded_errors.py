"""Request and file shapes that gave a traceback, a 500 or exit 1 give a clean answer:
HTTP 422 with the message, exit 2 naming the key, the file or the option — or, within
bounds, a plan. Each case is one that failed before."""

from __future__ import annotations

import io
import json
import math
import zipfile
from pathlib import Path

import pytest
from click.testing import CliRunner
from fastapi.testclient import TestClient
from web_helpers import EXAMPLES, LOCAL, UPLOAD

from scanplan.cli.main import main
from scanplan.web.app import create_app
from scanplan.web.uploads import UploadStore
from scanplan.web.worker import Planner

BLOCK = {"map": {"scale": 2000, "relief_interval_m": 1.0},
         "uav": {"camera": "dji-zenmuse-p1-35", "height_m": 120},
         "area": {"width_m": 500, "length_m": 500}}
JSON = {"Content-Type": "application/json"}
HEAD = (EXAMPLES / "uav-canon-2000.toml").read_text(encoding="utf-8").split("[area]")[0]


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(planner=Planner(inline=True), uploads=UploadStore()),
                    base_url=LOCAL, raise_server_exceptions=False) as c:
        yield c


def _cli(*args: str, **kw):
    r = CliRunner().invoke(main, [str(a) for a in args], **kw)
    assert "Traceback" not in r.output, r.output
    assert r.exception is None or isinstance(r.exception, SystemExit), repr(r.exception)
    return r


# --------------------------------------------------------------------------------------
# Requests
# --------------------------------------------------------------------------------------
@pytest.mark.parametrize("route", ["/api/plan", "/api/view", "/api/project.toml",
                                   "/api/download/pdf"])
def test_a_lone_surrogate_in_a_request_is_422_naming_the_key(client, route):
    project = json.loads(json.dumps(BLOCK))
    project["project"] = {"name": "Town \ud800 plan"}
    r = client.post(route, content=json.dumps({"project": project}), headers=JSON)
    assert r.status_code == 422, r.text
    assert r.json()["field"] == "project.project.name"
    assert "lone surrogate (\\ud800)" in r.json()["detail"]


def test_a_lone_surrogate_in_a_file_name_is_422(client):
    r = client.post("/api/plan", content=json.dumps({"project": BLOCK,
                                                     "files": {"a\udc00.kml": "x"}}),
                    headers=JSON)
    assert r.status_code == 422 and "lone surrogate" in r.json()["detail"]


@pytest.mark.parametrize("depth", [900, 3000, 200_000])
def test_a_deep_list_in_a_request_is_422_with_the_message(client, depth):
    deep = "[" * depth + "]" * depth
    body = json.dumps({"project": BLOCK})[:-2] + f', "x": {deep}}}}}'
    r = client.post("/api/plan", content=body, headers=JSON)
    assert r.status_code == 422, r.text[:300]
    assert "nests lists or tables more than 32 deep" in r.json()["detail"]
    assert len(r.json()["detail"]) < 200  # named by its key, not a thousand indices


def test_a_request_that_is_not_utf8_json_is_422(client):
    for body in (b'{"project": {"project": {"name": "\xff\xfe"}}}', b'{"project": ',
                 b'{"project": {"project": {"name": "\xed\xa0\x80"}}}'):  # CESU-8 half
        r = client.post("/api/plan", content=body, headers=JSON)
        assert r.status_code == 422, (body, r.status_code)
        assert r.json()["field"] in ("request", "project.project.name")


def test_a_lone_surrogate_in_an_uploaded_file_never_breaks_the_answer(client):
    """A GeoJSON area whose feature names hold escaped lone surrogates: the message that
    lists them is an answer (422), never a 500."""
    ring = [[37.60, 55.75], [37.62, 55.75], [37.62, 55.76], [37.60, 55.76], [37.60, 55.75]]
    feats = [{"type": "Feature", "properties": {"name": f"B\ud800{i}"},
              "geometry": {"type": "Polygon", "coordinates": [ring]}} for i in range(2)]
    data = json.dumps({"type": "FeatureCollection", "features": feats}).encode()
    up = client.post("/api/upload", params={"name": "a.geojson"}, content=data,
                     headers=UPLOAD).json()
    project = json.loads(json.dumps(BLOCK))
    project["area"] = {"file": "a.geojson"}
    for route in ("/api/plan", "/api/view"):
        r = client.post(route, json={"project": project, "files": {"a.geojson": up["id"]}})
        assert r.status_code in (200, 422), (route, r.status_code, r.text[:300])
        r.json()


def _wkt_list(path: Path, n: int = 20_000) -> int:
    """A vertex list of one 20,000-vertex WKT polygon (0.46 MB in one cell)."""
    pts = [(37.6 + 0.01 * math.cos(2 * math.pi * i / n), 55.75 + 0.01 * math.sin(
        2 * math.pi * i / n)) for i in range(n)]
    wkt = "POLYGON((" + ", ".join(f"{x:.7f} {y:.7f}" for x, y in [*pts, pts[0]]) + "))"
    path.write_text("id;WKT\n1;" + wkt + "\n", encoding="utf-8")
    return len(wkt)


def test_a_20000_vertex_wkt_list_is_planned_from_the_cli_and_the_server(client, tmp_path):
    size = _wkt_list(tmp_path / "boundary.csv")
    assert size > 400_000
    p = tmp_path / "p.toml"
    p.write_text(HEAD + '[area]\nfile = "boundary.csv"\n', encoding="utf-8")
    r = _cli("plan", p, "--json")
    assert r.exit_code == 0, r.output
    cli = json.loads(r.stdout)
    up = client.post("/api/upload", params={"name": "boundary.csv"},
                     content=(tmp_path / "boundary.csv").read_bytes(), headers=UPLOAD).json()
    project = json.loads(json.dumps(BLOCK))
    project["area"] = {"file": "boundary.csv"}
    r = client.post("/api/plan", json={"project": project,
                                       "files": {"boundary.csv": up["id"]}})
    assert r.status_code == 200, r.text[:300]
    assert r.json()["area"]["area_km2"] == pytest.approx(cli["area"]["area_km2"])


# --------------------------------------------------------------------------------------
# Files and options
# --------------------------------------------------------------------------------------
@pytest.mark.parametrize("value", ["[" * 5000 + "]" * 5000, "{a = " * 5000 + "}" * 5000,
                                   "9" * 5000])
def test_a_hostile_user_configuration_is_exit_2_naming_the_file(tmp_path, monkeypatch, value):
    config = tmp_path / "config.toml"
    config.write_text(f"[project]\norganisation = {value}\n", encoding="utf-8")
    monkeypatch.setenv("SCANPLAN_CONFIG", str(config))
    r = _cli("plan", EXAMPLES / "uav-canon-2000.toml")
    assert r.exit_code == 2, r.output
    assert str(config) in r.stderr


@pytest.mark.parametrize("option", ["--out"])
def test_an_output_folder_under_an_existing_file_is_exit_2(tmp_path, option):
    (tmp_path / "notes.txt").write_text("mine", encoding="utf-8")
    for out in ("notes.txt/x", "notes.txt/x/y"):
        r = _cli("plan", EXAMPLES / "uav-canon-2000.toml", option, tmp_path / out)
        assert r.exit_code == 2, r.output
        assert "notes.txt" in r.stderr and "is a file, not a folder" in r.stderr
    assert (tmp_path / "notes.txt").read_text(encoding="utf-8") == "mine"


def test_an_area_uploaded_as_flight_kml_is_once_in_the_zip(client, tmp_path):
    kml = (EXAMPLES / "areas" / "town-uav.kml").read_bytes()
    up = client.post("/api/upload", params={"name": "flight.kml"}, content=kml,
                     headers=UPLOAD).json()
    project = {"map": {"scale": 2000, "relief_interval_m": 0.5},
               "uav": {"camera": "dji-zenmuse-p1-35", "speed_ms": 12,
                       "max_flight_time_min": 25},
               "area": {"file": "flight.kml"}}
    req = {"project": project, "files": {"flight.kml": up["id"]}}
    r = client.post("/api/download/zip", json=req)
    assert r.status_code == 200, r.text[:300]
    zf = zipfile.ZipFile(io.BytesIO(r.content))
    names = zf.namelist()
    assert len(names) == len(set(names))  # every member once
    assert zf.read("inputs/flight.kml") == kml  # the area, apart from the flight's KML
    assert zf.read("flight.kml") != kml
    zf.extractall(tmp_path)
    again = _cli("plan", tmp_path / "project.toml", "--json")
    assert again.exit_code == 0, again.output
    planned = client.post("/api/plan", json=req).json()
    assert json.loads(again.stdout)["specification"] == planned["specification"]


def test_a_header_only_parameters_csv_is_refused_naming_the_file(tmp_path, user_dir):
    (tmp_path / "parameters.csv").write_text("name,value,unit,source,note\n",
                                             encoding="utf-8")
    for command in (["norms", "import", tmp_path / "parameters.csv", "--name", "mine"],
                    ["norms", "validate", tmp_path / "parameters.csv"]):
        r = _cli(*command)
        assert r.exit_code == 2, r.output
        assert "parameters.csv" in r.stderr and "no rows" in r.stderr
    assert not (user_dir / "mine").exists()
