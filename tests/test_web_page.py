"""What the page of ``scanplan serve`` needs of the server, through the framework's test
client: the latest edit only, the photo centres packed, an upload still kept, a project file
or zip opened again (round trip to the same bytes), an area outlined before a camera, errors
in the page's words and language, the background maps (tiles from a tile server on
127.0.0.1 kept on disk, an MBTiles file, an orthophoto warped on the server) and
``[map] basemap`` on the PDF's map page."""

from __future__ import annotations

import io
import subprocess
import threading
import zipfile
from pathlib import Path

import numpy as np
import pytest
from basemap_helpers import ORTHO_COLOUR, TileServer, write_mbtiles, write_ortho
from click.testing import CliRunner
from fastapi.testclient import TestClient
from web_helpers import EXAMPLES, LOCAL, UPLOAD, example_request

from scanplan.cli.main import main
from scanplan.web.app import create_app
from scanplan.web.basemap import MAX_ZOOM, Basemaps
from scanplan.web.edits import EditGate, Superseded, parse_edit
from scanplan.web.mapdata import pack_lonlat, unpack_lonlat
from scanplan.web.pagewords import label_from_help, page_error
from scanplan.web.registry import input_rows
from scanplan.web.worker import Planner

TOWN = EXAMPLES / "areas" / "town-uav.kml"


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(planner=Planner(inline=True),
                               basemaps=Basemaps("none")), base_url=LOCAL) as c:
        yield c


def _upload(client, path: Path, name: str | None = None) -> str:
    r = client.post("/api/upload", params={"name": name or path.name},
                    content=path.read_bytes(), headers=UPLOAD)
    assert r.status_code == 200, r.text
    return r.json()["id"]


# ------------------------------------------------------------------ the latest edit only
def test_an_edit_a_newer_one_replaced_is_not_planned():
    gate, ran = EditGate(wait_s=5), []
    hold, started = threading.Event(), threading.Event()

    def first() -> str:
        started.set()
        hold.wait(5)
        ran.append(1)
        return "one"

    out: dict[str, object] = {}
    t = threading.Thread(target=lambda: out.setdefault("1", gate.run(("pageAAAA", 1), first,
                                                                     RuntimeError)))
    t.start()
    started.wait(5)
    # edits 2 and 3 arrive while 1 plans; 2 waits, then finds 3 noted: never planned
    errors: list[BaseException] = []

    def second() -> None:
        try:
            gate.run(("pageAAAA", 2), lambda: ran.append(2), RuntimeError)
        except Superseded as exc:
            errors.append(exc)

    t2 = threading.Thread(target=second)
    t2.start()
    gate.note(("pageAAAA", 3))
    hold.set()
    t.join(5)
    t2.join(5)
    assert out["1"] == "one" and ran == [1] and len(errors) == 1
    assert gate.run(("pageAAAA", 3), lambda: "three", RuntimeError) == "three"
    # another page, and a request without the header, are never superseded by it
    assert gate.run(("pageBBBB", 1), lambda: "b", RuntimeError) == "b"
    assert gate.run(None, lambda: "plain", RuntimeError) == "plain"
    assert parse_edit("bad id/1") is None and parse_edit("pageAAAA/x") is None


def test_the_view_answers_a_superseded_edit_409(client):
    req = {"project": {"map": {"scale": 2000, "relief_interval_m": 1},
                       "uav": {"camera": "dji-zenmuse-p1-35", "height_m": 120}}}
    r = client.post("/api/view", json=req, headers={"X-Scanplan-Edit": "pageCCCC/5"})
    assert r.status_code == 200
    old = client.post("/api/view", json=req, headers={"X-Scanplan-Edit": "pageCCCC/4"})
    assert old.status_code == 409 and old.json()["superseded"] is True


# ------------------------------------------------------------------ the photo centres
def test_the_photo_centres_are_packed_and_read_back_to_7_decimals(client):
    req = example_request(client, EXAMPLES / "uav-town-2000.toml")
    v = client.post("/api/view", json=req)
    assert "margins_pct" not in v.json()  # one margin: plan --json's, the documents' one
    photos = next(f for f in v.json()["map"]["features"] if f["properties"]["kind"] == "photos")
    p = photos["properties"]
    assert photos["geometry"] is None and p["every"] == 1 and p["shown"] == p["count"]
    lonlat = unpack_lonlat(p["packed"])
    from scanplan import plan

    layout = plan(EXAMPLES / "uav-town-2000.toml").spec.uav.layout
    expected = np.column_stack([layout.photos["lon_deg"], layout.photos["lat_deg"]])
    assert lonlat.shape == expected.shape
    assert np.abs(lonlat - expected).max() <= 0.5e-7 + 1e-12
    # the packed form is under half the GeoJSON pairs it replaced
    assert len(p["packed"]) < 0.5 * len(str(np.round(expected, 7).tolist()))
    assert unpack_lonlat(pack_lonlat(np.array([-179.9999999, 180.0]),
                                     np.array([-90.0, 89.9999999]))).tolist() == \
        [[-179.9999999, -90.0], [180.0, 89.9999999]]


# ------------------------------------------------------------------ uploads, open, area
def test_a_reloaded_page_finds_its_uploads(client):
    uid = _upload(client, TOWN)
    r = client.get(f"/api/upload/{uid}")
    assert r.status_code == 200 and r.json() == {"id": uid, "name": "town-uav.kml",
                                                 "size": TOWN.stat().st_size}
    assert client.get("/api/upload/0123456789abcdef").status_code == 404
    assert client.get("/api/upload/..%2F..%2Fetc").status_code == 404


@pytest.mark.parametrize("example", ["uav-town-2000.toml", "uav-town-2000-afs.toml",
                                     "film-town-relief-10000.toml", "uav-p1-500.toml"])
def test_a_project_file_opened_again_downloads_the_same_bytes(client, example):
    """project.toml → open → the tables the page sends → project.toml: the same bytes."""
    req = example_request(client, EXAMPLES / example)
    first = client.post("/api/project.toml", json=req)
    assert first.status_code == 200, first.text
    tid = client.post("/api/upload", params={"name": "project.toml"},
                      content=first.content, headers=UPLOAD).json()["id"]
    opened = client.post("/api/open", json={"id": tid}).json()
    files = dict(req["files"])
    assert sorted(opened["missing"]) == sorted(files)  # a bare project file has no files
    again = client.post("/api/project.toml", json={"project": opened["project"],
                                                   "files": files})
    assert again.status_code == 200, again.text
    assert again.content == first.content


def test_the_downloaded_zip_opens_with_its_files(client):
    req = example_request(client, EXAMPLES / "uav-town-valley-2000.toml")
    z = client.post("/api/download/zip", json=req)
    assert z.status_code == 200, z.text
    zid = client.post("/api/upload", params={"name": "scanplan.zip"},
                      content=z.content, headers=UPLOAD).json()["id"]
    opened = client.post("/api/open", json={"id": zid}).json()
    assert opened["missing"] == []
    # the GIS files name the area file as the project does, not the job's temporary folder
    members = zipfile.ZipFile(io.BytesIO(z.content))
    for name in members.namelist():
        assert b"scanplan-job-" not in members.read(name), name
    assert b"areas/town-uav.kml" in members.read("flight.geojson")
    files = {name: f["id"] for name, f in opened["files"].items()}
    assert set(files) == set(req["files"])
    for name, uid in files.items():
        assert client.get(f"/api/upload/{uid}").json()["size"] == \
            len(zipfile.ZipFile(io.BytesIO(z.content)).read(name))
    assert client.post("/api/plan", json={"project": opened["project"], "files": files}
                       ).json() == client.post("/api/plan", json=req).json()


def test_opening_refuses_what_is_not_a_project(client):
    bad = client.post("/api/upload", params={"name": "p.toml"}, content=b"[map\nscale=",
                      headers=UPLOAD).json()
    r = client.post("/api/open", json={"id": bad["id"]}, params={"lang": "en"})
    assert r.status_code == 422 and "is not valid TOML" in r.json()["detail"]
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zf:
        zf.writestr("other.txt", "x")
    zid = client.post("/api/upload", params={"name": "a.zip"}, content=buf.getvalue(),
                      headers=UPLOAD).json()
    r = client.post("/api/open", json={"id": zid["id"]})
    assert r.status_code == 422 and "holds no project.toml" in r.json()["detail"]
    # a zip naming a file outside itself: never opened
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zf:
        zf.writestr("project.toml", '[map]\nscale = 2000\n[area]\nfile = "../../etc/passwd"\n')
    zid = client.post("/api/upload", params={"name": "a.zip"}, content=buf.getvalue(),
                      headers=UPLOAD).json()
    r = client.post("/api/open", json={"id": zid["id"]})
    assert r.status_code == 422 and "must name an uploaded file" in r.json()["detail"]


def test_an_area_is_outlined_before_a_camera_is_chosen(client):
    uid = _upload(client, TOWN)
    r = client.post("/api/area", json={"project": {"area": {"file": "town-uav.kml"}},
                                       "files": {"town-uav.kml": uid}})
    assert r.status_code == 200, r.text
    (f,) = r.json()["features"]
    lon, lat = np.array(f["geometry"]["coordinates"][0]).T
    assert 38.76 < lon.min() < lon.max() < 38.82 and 55.07 < lat.min() < lat.max() < 55.09
    block = client.post("/api/area", json={"project": {"area": {"width_m": 100,
                                                                "length_m": 200}}})
    assert block.json()["features"] == []


# ------------------------------------------------------------------ errors as the page says them
def test_errors_in_the_page_words_and_language(client):
    req = {"project": {"map": {"scale": 2000, "relief_interval_m": 1},
                       "uav": {"camera": "dji-zenmuse-p1-35", "speed_ms": -5}}}
    for lang, label, text in [
            ("en", "Ground speed", "must be ≥ 0 and ≤ 500 m/s (got -5)"),
            ("ru", "Путевая скорость", "должно быть ≥ 0 и ≤ 500 м/с (введено -5)")]:
        r = client.post(f"/api/view?lang={lang}", json=req)
        assert r.status_code == 422
        body = r.json()
        assert body["detail"].startswith("project.toml: uav.speed_ms (line")  # unchanged
        assert body["page"] == {"key": "uav.speed_ms", "label": label, "text": text}
    scales = {"project": {"map": {"scale": 2000, "relief_interval_m": 1},
                          "film": {"camera": "rc30-153", "photo_scales": "many"}}}
    page = client.post("/api/view?lang=ru", json=scales).json()["page"]
    assert page["key"] == "film.photo_scales" and "[" not in page["text"], page


def test_every_field_of_the_form_has_its_own_label():
    """The three agreement keys were all labelled "agreement block"."""
    from scanplan.web.page import TEXTS

    for lang in ("en", "ru"):
        seen: dict[str, str] = {}
        for row in input_rows(lang):
            if row["managed"]:
                continue
            key = f"{row['section']}.{row['key']}"
            label = TEXTS[lang].get(f"lbl.{key}") or row["label"] or \
                label_from_help(row["help"])
            if row["section"] in ("uav", "film") or row["section"].startswith("norms"):
                continue  # the same quantity of the two platforms, shown one at a time
            assert label not in seen, (lang, key, seen.get(label))
            seen[label] = key
    assert page_error("project.toml: [uav] (line 3)", "unknown section", "en")["key"] == "uav"


# ------------------------------------------------------------------ the background maps
def test_tiles_come_from_the_configured_server_only_and_are_kept_on_disk(tmp_path):
    with TileServer((40, 90, 200)) as tiles:
        b = Basemaps(tiles.url, "Local tiles © test", cache=tmp_path / "cache")
        with TestClient(create_app(planner=Planner(inline=True), basemaps=b), base_url=LOCAL) as c:
            r = c.get("/api/tiles/tiles/12/2489/1293")
            assert r.status_code == 200 and r.headers["content-type"] == "image/png"
            assert tiles.hits == ["/12/2489/1293.png"]
            assert c.get("/api/tiles/tiles/12/2489/1293").content == r.content
            assert tiles.hits == ["/12/2489/1293.png"]  # the second from the disk cache
            # nothing but the configured template is ever fetched
            for bad in ("/api/tiles/osm/1/0/0", f"/api/tiles/tiles/{MAX_ZOOM + 1}/0/0",
                        "/api/tiles/tiles/2/4/0", "/api/tiles/tiles/2/0/-1"):
                assert c.get(bad).status_code == 422, bad
            assert c.get("/api/tiles/tiles/1/0/0?url=http://127.0.0.1:1/").status_code == 200
            assert len(tiles.hits) == 2 and tiles.hits[1] == "/1/0/0.png"
            html = c.get("/").text
            assert "Local tiles © test" in html and tiles.url not in html
    # offline now: the kept tile still comes
    with TestClient(create_app(planner=Planner(inline=True), basemaps=b), base_url=LOCAL) as c:
        assert c.get("/api/tiles/tiles/12/2489/1293").status_code == 200
        assert c.get("/api/tiles/tiles/12/2489/1294").status_code == 404


def test_an_mbtiles_file_serves_its_tiles_read_only(tmp_path):
    from PIL import Image

    mb = write_mbtiles(tmp_path / "t.mbtiles", (30, 160, 60), zooms=range(0, 3))
    b = Basemaps("none", mbtiles=mb)
    assert b.default == "mbtiles" and b.page_list()[0]["attribution"] == "Test tiles © the test"
    with TestClient(create_app(planner=Planner(inline=True), basemaps=b), base_url=LOCAL) as c:
        r = c.get("/api/tiles/mbtiles/0/0/0")
        assert r.status_code == 200
        assert Image.open(io.BytesIO(r.content)).getpixel((5, 5)) == (30, 160, 60)
        assert c.get("/api/tiles/mbtiles/5/0/0").status_code == 404  # no such zoom
    assert (tmp_path / "t.mbtiles").stat().st_size > 0
    (tmp_path / "bad.mbtiles").write_bytes(b"not sqlite at all" * 100)
    from scanplan.errors import InputError

    with pytest.raises(InputError, match="--mbtiles"):
        Basemaps("none", mbtiles=tmp_path / "bad.mbtiles")


def test_an_orthophoto_is_warped_to_web_mercator_on_the_server(client, tmp_path):
    from PIL import Image

    ortho = write_ortho(tmp_path / "ortho.tif")
    uid = _upload(client, ortho)
    info = client.get(f"/api/basemap/{uid}").json()
    (s, w), (n, e) = info["bounds"]
    assert abs(w - 38.765) < 0.002 and abs(e - 38.818) < 0.002
    assert abs(s - 55.069) < 0.002 and abs(n - 55.092) < 0.002
    png = client.get(f"/api/basemap/{uid}/image.png")
    img = Image.open(io.BytesIO(png.content)).convert("RGBA")
    assert img.size == (info["width"], info["height"]) and max(img.size) <= 2048
    colours = {img.getpixel((x, y))[:3] for x in range(5, img.size[0], 37)
               for y in range(5, img.size[1], 37)}
    assert any(all(abs(a - b) < 30 for a, b in zip(c, ORTHO_COLOUR, strict=True))
               for c in colours)
    # not a GeoTIFF: refused with the reader's words
    kml = _upload(client, TOWN)
    r = client.get(f"/api/basemap/{kml}", params={"lang": "en"})
    assert r.status_code == 422 and "not a readable GeoTIFF" in r.json()["detail"]


@pytest.mark.parametrize("kind", ["ortho.tif", "tiles.mbtiles"])
def test_the_basemap_is_printed_on_the_pdf_map_page(tmp_path, kind):
    """``[map] basemap``: an orthophoto (or an MBTiles file's tiles) under the flight on the
    map page, its source named; a file that is neither stops the plan naming the key."""
    (tmp_path / "areas").mkdir()
    (tmp_path / "areas" / "town-uav.kml").write_bytes(TOWN.read_bytes())
    if kind.endswith(".tif"):
        write_ortho(tmp_path / kind)
    else:
        write_mbtiles(tmp_path / kind, ORTHO_COLOUR)
    text = (EXAMPLES / "uav-town-2000.toml").read_text(encoding="utf-8")
    text = text.replace("[map]\n", f'[map]\nbasemap = "{kind}"\nbasemap_attribution = '
                        '"Orthophoto 2026, the town survey"\n', 1)
    (tmp_path / "p.toml").write_text(text, encoding="utf-8")
    r = CliRunner().invoke(main, ["plan", str(tmp_path / "p.toml"), "--out",
                                  str(tmp_path / "out"), "--formats", "pdf", "-q"])
    assert r.exit_code == 0, r.output
    pdf = tmp_path / "out" / "spec.pdf"
    pages = subprocess.run(["pdftotext", str(pdf), "-"], capture_output=True, text=True,
                           check=True).stdout.split("\f")
    (page,) = [i + 1 for i, p in enumerate(pages) if "Background: Orthophoto 2026" in p]
    subprocess.run(["pdftoppm", "-png", "-r", "40", "-f", str(page), "-l", str(page), str(pdf),
                    str(tmp_path / "map")], check=True)
    from PIL import Image

    (png,) = tmp_path.glob("map*.png")
    img = np.asarray(Image.open(png).convert("RGB")).reshape(-1, 3).astype(int)
    magenta = (np.abs(img - np.array(ORTHO_COLOUR)) < 40).all(axis=1).sum()
    assert magenta > 2000  # the orthophoto's squares (the tiles' colour) on the page
    (tmp_path / kind).write_text("not a tiff", encoding="utf-8")
    r = CliRunner().invoke(main, ["plan", str(tmp_path / "p.toml")])
    assert r.exit_code == 2 and "map.basemap (line" in r.stderr and "GeoTIFF" in r.stderr


def test_the_page_routes_are_in_the_api_description(client):
    paths = client.get("/openapi.json").json()["paths"]
    assert {"/api/upload/{upload_id}", "/api/open", "/api/area",
            "/api/tiles/{source}/{z}/{x}/{y}", "/api/basemap/{upload_id}",
            "/api/basemap/{upload_id}/image.png"} <= set(paths)
