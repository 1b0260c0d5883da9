"""The JSON API of ``scanplan serve`` through the framework's test client: every example
planned through the API is the ``plan --json`` document of the command line; a bad input
is 422 with the command line's message; client paths are never opened; hostile uploads are
refused by the command line's own readers; the downloads are the files of ``plan --out``
and round-trip to the command line."""

from __future__ import annotations

import io
import json
import re
import zipfile
from pathlib import Path

import pytest
from click.testing import CliRunner
from fastapi.testclient import TestClient
from web_helpers import EXAMPLES, LOCAL, UPLOAD, example_request

from scanplan.cli.main import main
from scanplan.web.app import MAX_BODY_BYTES, create_app
from scanplan.web.page import TEXTS
from scanplan.web.tomlfile import project_toml
from scanplan.web.uploads import UploadStore
from scanplan.web.worker import Planner

UAV = {"project": {"name": "Block", "locale": "en"},
       "map": {"scale": 2000, "relief_interval_m": 1.0},
       "uav": {"camera": "dji-zenmuse-p1-35", "height_m": 120},
       "area": {"polygon": [[37.60, 55.75], [37.62, 55.75], [37.62, 55.76], [37.60, 55.76]]}}


@pytest.fixture(scope="module")
def client():
    store = UploadStore(max_upload_bytes=4 * 1024 * 1024)
    with TestClient(create_app(planner=Planner(inline=True), uploads=store),
                    base_url=LOCAL) as c:
        yield c
    assert not store.root.exists()  # every upload removed when the server stops


def _cli_json(path: Path) -> dict:
    r = CliRunner().invoke(main, ["plan", str(path), "--json"])
    assert r.exit_code == 0, r.output
    # the CLI names the area file and DEM by their path; the API as the project names them
    return json.loads(r.stdout.replace(f"{path.parent}/", ""))


@pytest.mark.parametrize("example", sorted(p.name for p in EXAMPLES.glob("*.toml")))
def test_every_example_through_the_api_is_plan_json(client, example):
    path = EXAMPLES / example
    r = client.post("/api/plan", json=example_request(client, path))
    assert r.status_code == 200, r.text
    api, cli = r.json(), _cli_json(path)
    # the one run-specific field: the project file's name (the page's is project.toml)
    assert api["project"].pop("file") == "project.toml"
    assert cli["project"].pop("file") == example
    assert api == cli


def test_the_view_carries_the_plan_the_map_and_the_chart(client):
    req = example_request(client, EXAMPLES / "uav-town-2000.toml")
    v = client.post("/api/view", json=req).json()
    assert v["plan"] == client.post("/api/plan", json=req).json()
    kinds = [f["properties"]["kind"] for f in v["map"]["features"]]
    layout = v["plan"]["specification"]["uav"]["layout"]
    assert kinds.count("area") == 1 and kinds.count("strip") == layout["n_strips"]
    assert kinds.count("takeoff") == layout["n_sorties"]
    photos = next(f for f in v["map"]["features"] if f["properties"]["kind"] == "photos")
    assert photos["properties"]["count"] == layout["n_photos"]
    assert v["charts"]["height"].startswith("<svg") or "<svg" in v["charts"]["height"][:200]
    assert set(v["names"]) == set(v["plan"]["uav"]["constraints"])
    assert v["toml"].startswith("# scanplan project file")
    assert v["crs"] == "EPSG:32637 — WGS 84 / UTM zone 37N"


def test_the_view_names_the_planning_crs_in_the_page_language(client):
    """A Russian page names the planning system in Russian, as the Russian PDF does."""
    req = {"project": {**UAV, "project": {"name": "Блок", "locale": "ru"}}}
    v = client.post("/api/view", json=req).json()
    assert v["crs"] == "EPSG:32637 — WGS 84 / UTM зона 37\u00a0с.\u00a0ш."
    local = {"project": {k: x for k, x in UAV.items() if k != "area"}}
    assert client.post("/api/view", json=local).json()["crs"] is None


def test_the_views_json_text_is_the_answer_a_dict_would_have_been(client, monkeypatch):
    """The worker's JSON text of the view (the plan's text spliced in as it was written) is
    byte for byte what FastAPI sends for :func:`view_job`'s dict; a lone surrogate in the
    plan's text is escaped as in any other answer."""
    from fastapi.responses import JSONResponse

    from scanplan.web import jobs
    from scanplan.web.bodies import printable_data

    req = example_request(client, EXAMPLES / "uav-town-2000.toml")
    files = {name: str(client.app.state.uploads.path(i, "f")) for name, i in
             req["files"].items()}
    text = jobs.view_json_job(req["project"], files)
    assert text == JSONResponse(printable_data(jobs.view_job(req["project"], files))).body
    assert client.post("/api/view", json=req).content == text
    made = jobs._plan_doc

    def lone(result, folder):
        doc, plan_text = made(result, folder)
        return doc, plan_text.replace('"project":{', '"project":{"x":"a\ud800",', 1)

    monkeypatch.setattr(jobs, "_plan_doc", lone)
    v = json.loads(jobs.view_json_job(req["project"], files))
    assert v["plan"]["project"]["x"] == "a\\ud800"
    assert v["map"] == json.loads(text)["map"]


def _cli_error(tmp_path: Path, project: dict) -> str:
    """What ``scanplan plan`` says on stderr for the project file of ``project``."""
    f = tmp_path / "project.toml"
    f.write_text(project_toml(project), encoding="utf-8")
    r = CliRunner().invoke(main, ["plan", str(f)])
    assert r.exit_code == 2, r.output
    return r.stderr.strip().replace(f"{tmp_path}/", "")


BAD = {
    "out of range": ("uav", "speed_ms", -5),
    "wrong type": ("uav", "height_m", "high"),
    "unknown key": ("uav", "heigth_m", 100),
    "unknown camera": ("uav", "camera", "no-such-camera"),
    "overlap": ("uav", "side_overlap_pct", 120),
    "bad scale": ("map", "scale", "1:two thousand"),
    "self-crossing polygon": ("area", "polygon", [[37.60, 55.75], [37.62, 55.76],
                                                  [37.62, 55.75], [37.60, 55.76]]),
}


@pytest.mark.parametrize("case", list(BAD))
def test_bad_input_is_422_with_the_cli_message(client, tmp_path, case):
    section, key, value = BAD[case]
    project = json.loads(json.dumps(UAV))
    project[section][key] = value
    r = client.post("/api/plan", json={"project": project})
    assert r.status_code == 422, r.text
    said = _cli_error(tmp_path, project)
    assert said == f"error: {r.json()['detail']}"
    assert f"{section}." in r.json()["field"] or key in r.json()["detail"]
    # the page's other routes refuse it the same way
    for route in ("/api/view", "/api/project.toml", "/api/download/xlsx"):
        assert client.post(route, json={"project": project}).json()["detail"] == \
            r.json()["detail"]


def test_a_project_without_a_plan_section_is_the_cli_message(client, tmp_path):
    project = {"map": {"scale": 2000, "relief_interval_m": 1}}
    r = client.post("/api/plan", json={"project": project})
    assert r.status_code == 422
    assert _cli_error(tmp_path, project) == f"error: {r.json()['detail']}"
    assert "needs a [film] or a [uav] section" in r.json()["detail"]


@pytest.mark.parametrize("section,key,value", [
    ("area", "file", "/etc/passwd"), ("area", "file", "../../etc/passwd"),
    ("area", "file", "town.kml"), ("terrain", "dem", "/dev/zero"),
    ("terrain", "dem", "dem.tif"), ("norms", "set", "/etc"), ("norms", "set", "../norms"),
])
def test_no_client_path_is_ever_opened(client, section, key, value, monkeypatch):
    import builtins

    opened = []
    real = builtins.open
    monkeypatch.setattr(builtins, "open", lambda f, *a, **k: (opened.append(str(f)),
                                                              real(f, *a, **k))[1])
    project = json.loads(json.dumps(UAV))
    if section == "area":
        project["area"] = {key: value}
    else:
        project.setdefault(section, {})[key] = value
    r = client.post("/api/plan", json={"project": project})
    assert r.status_code == 422, r.text
    assert f"{section}.{key}" in r.json()["detail"]
    assert not [f for f in opened if value.strip("./") in f]


def test_files_name_only_the_stores_uploads(client):
    project = json.loads(json.dumps(UAV))
    project["area"] = {"file": "town.kml"}
    for bad in ("/etc/passwd", "0123456789abcdef", "../x"):
        r = client.post("/api/plan", json={"project": project, "files": {"town.kml": bad}})
        assert r.status_code == 422 and "names no uploaded file" in r.json()["detail"]


def _hostile_kml() -> bytes:
    kml = (EXAMPLES / "areas" / "town-uav.kml").read_text(encoding="utf-8")
    dtd = '<!DOCTYPE kml [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;">]>'
    return kml.replace("?>", "?>\n" + dtd, 1).encode()


def _kmz_bomb() -> bytes:
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("doc.kml", (EXAMPLES / "areas" / "town-uav.kml").read_text()
                   + " " * 20_000_000)
    return buf.getvalue()


def _huge_dem(tmp_path: Path) -> bytes:
    import rasterio
    from rasterio.transform import from_origin

    from scanplan.geo import dem as D

    p = tmp_path / "huge.tif"
    with rasterio.open(p, "w", driver="GTiff", width=D.MAX_DIMENSION_PX + 1, height=1,
                       count=1, dtype="uint8", crs="EPSG:32637", tiled=True,
                       transform=from_origin(484090, 6105550, 1, 1), sparse_ok=True):
        pass
    return p.read_bytes()


@pytest.mark.parametrize("case", ["entities", "kmz bomb", "huge dem", "not a raster"])
def test_hostile_uploads_are_refused_by_the_cli_readers(client, tmp_path, case):
    req = example_request(client, EXAMPLES / "uav-town-valley-2000.toml")
    if case in ("entities", "kmz bomb"):
        name, data = (("town.kml", _hostile_kml()) if case == "entities"
                      else ("town.kmz", _kmz_bomb()))
        key, says = ("area", "file"), ("<!ENTITY>" if case == "entities" else "zip bomb")
    else:
        name = "dem.tif"
        data = _huge_dem(tmp_path) if case == "huge dem" else b"%PDF-1.4 not a raster"
        key = ("terrain", "dem")
        says = "more than 1,000,000" if case == "huge dem" else "not a readable GeoTIFF"
    up = client.post("/api/upload", params={"name": name}, content=data,
                     headers=UPLOAD).json()
    req["project"][key[0]][key[1]] = up["name"]
    req["files"][up["name"]] = up["id"]
    r = client.post("/api/plan", json=req)
    assert r.status_code == 422, r.text
    assert says in r.json()["detail"] and f"{key[0]}.{key[1]}" in r.json()["detail"]
    assert "scanplan-job-" not in r.text  # the job's folder never shows


def test_uploads_are_bounded_and_named_by_the_server(client):
    r = client.post("/api/upload", params={"name": "../../big.tif"},
                    content=b"x" * (4 * 1024 * 1024 + 1), headers=UPLOAD)
    assert r.status_code == 422 and "larger than 4.0 MB" in r.json()["detail"]
    r = client.post("/api/upload", params={"name": "/etc/../a b.kml"}, content=b"<kml/>",
                    headers=UPLOAD)
    assert r.status_code == 200 and r.json()["name"] == "a_b.kml"
    assert client.post("/api/upload", params={"name": "e.kml"}, content=b"",
                       headers=UPLOAD).status_code == 422


def test_a_body_past_the_bound_is_refused(client):
    r = client.post("/api/plan", content=b"{" + b" " * MAX_BODY_BYTES + b"}",
                    headers={"Content-Type": "application/json"})
    assert r.status_code == 413


def test_the_project_file_round_trips_to_the_cli(client, tmp_path):
    req = example_request(client, EXAMPLES / "uav-town-valley-2000.toml")
    req["project"]["uav"]["height_m"] = 110
    text = client.post("/api/project.toml", json=req).text
    (tmp_path / "areas").mkdir()
    (tmp_path / "dem").mkdir()
    for name in req["files"]:
        (tmp_path / name).write_bytes((EXAMPLES / name).read_bytes())
    (tmp_path / "project.toml").write_text(text, encoding="utf-8")
    assert client.post("/api/plan", json=req).json() == _cli_json(tmp_path / "project.toml")


def test_the_zip_holds_reports_missions_gis_and_a_project_that_runs(client, tmp_path):
    req = example_request(client, EXAMPLES / "uav-town-2000.toml")
    r = client.post("/api/download/zip", json=req)
    assert r.status_code == 200 and r.headers["content-type"] == "application/zip"
    zf = zipfile.ZipFile(io.BytesIO(r.content))
    names = set(zf.namelist())
    assert {"spec.pdf", "spec.xlsx", "flight.kml", "flight.geojson", "photos.csv",
            "project.toml", "areas/town-uav.kml"} <= names
    missions = sorted(n for n in names if re.fullmatch(r"mission-\d+\.plan", n))
    planned = client.post("/api/plan", json=req).json()
    assert len(missions) == planned["specification"]["uav"]["sorties"]
    assert zf.read("spec.pdf").startswith(b"%PDF")
    import openpyxl

    book = openpyxl.load_workbook(io.BytesIO(zf.read("spec.xlsx")))
    assert book.sheetnames
    assert json.loads(zf.read(missions[0]))["fileType"] == "Plan"
    # the folder of the zip runs as it is: the same plan through the command line
    zf.extractall(tmp_path)
    assert planned == _cli_json(tmp_path / "project.toml")


def test_pdf_and_workbook_downloads(client):
    req = {"project": UAV}
    pdf = client.post("/api/download/pdf", json=req)
    assert pdf.status_code == 200 and pdf.content.startswith(b"%PDF")
    assert 'filename="spec.pdf"' in pdf.headers["content-disposition"]
    assert client.post("/api/download/exe", json=req).status_code == 422


def test_inputs_are_the_registry_and_the_catalogue_the_norm_sets(client):
    from scanplan.project.inputs import INPUTS

    rows = client.get("/api/inputs").json()
    assert {(r["section"], r["key"]) for r in rows} == \
        {(i.section, i.key) for i in INPUTS.values() if i.key}
    speed = next(r for r in rows if (r["section"], r["key"]) == ("uav", "speed_ms"))
    assert speed["unit"] == "m/s" and speed["default"] == 15.0 and "ground speed" in speed["help"]
    lat = next(r for r in rows if (r["section"], r["key"]) == ("site", "lat_deg"))
    assert (lat["min"], lat["max"]) == (-90, 90)  # a project-file key's own domain
    cat = client.get("/api/catalogue").json()
    assert any(c["id"] == "dji-zenmuse-p1-35" for c in cat["cameras"])
    assert all(s["pixels_um"] for s in cat["scanners"])
    assert client.get("/api/catalogue", params={"norms": "/etc"}).status_code == 422


def test_the_page_speaks_the_browsers_language(client):
    assert 'lang="ru"' in client.get("/", headers={"Accept-Language": "ru-RU,ru;q=0.9"}).text
    assert 'lang="en"' in client.get("/", headers={"Accept-Language": "de,en;q=0.5"}).text
    page = client.get("/?lang=ru").text
    assert 'lang="ru"' in page and TEXTS["ru"]["rec_height"] in page
    assert set(TEXTS["en"]) == set(TEXTS["ru"])
    assert client.get("/static/vendor/leaflet/leaflet.js").status_code == 200
    assert client.get("/openapi.json").json()["paths"]["/api/plan"]


def test_a_token_guards_every_api_call():
    with TestClient(create_app(token="s3cret", planner=Planner(inline=True)),
                    base_url=LOCAL) as c:
        assert c.get("/api/inputs").status_code == 403
        assert c.get("/api/inputs", headers={"X-Scanplan-Token": "wrong"}).status_code == 403
        assert c.get("/api/inputs", headers={"X-Scanplan-Token": "s3cret"}).status_code == 200
        assert c.get("/api/inputs", params={"token": "s3cret"}).status_code == 200


def test_a_plan_past_its_time_limit_is_stopped_and_the_next_one_runs():
    planner = Planner(limit_s=1e-4)
    with TestClient(create_app(planner=planner), base_url=LOCAL) as c:
        r = c.post("/api/plan", json={"project": UAV})
        assert r.status_code == 504 and "was stopped" in r.json()["detail"]
        planner.limit_s = 120
        r = c.post("/api/plan", json={"project": UAV})
        assert r.status_code == 200 and r.json()["specification"]["uav"]["strips"] > 0
        bad = json.loads(json.dumps(UAV))
        bad["uav"]["speed_ms"] = -1
        r = c.post("/api/plan", json={"project": bad})  # the worker's input error: 422
        assert r.status_code == 422 and "uav.speed_ms" in r.json()["detail"]


def test_no_job_folder_is_left_behind(client, tmp_path, monkeypatch):
    import glob
    import tempfile

    # a temporary folder of this test's own: another test run on the machine makes job
    # folders of its own in the shared one meanwhile
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    pattern = str(tmp_path / "scanplan-job-*")
    before = set(glob.glob(pattern))
    assert before == set()
    bad = json.loads(json.dumps(UAV))
    bad["uav"]["speed_ms"] = -1
    assert client.post("/api/view", json={"project": UAV}).status_code == 200
    assert client.post("/api/plan", json={"project": bad}).status_code == 422
    assert client.post("/api/download/xlsx", json={"project": UAV}).status_code == 200
    assert set(glob.glob(pattern)) == before
