"""Hostile GIS inputs: an area file or a DEM opens only the plain file the user named.

Each hostile file is built here, small: GDAL virtual datasets (OGR and raster VRTs, under
every name) whose sources are ``/vsicurl/`` URLs of a local HTTP listener that must see no
request at all; zip content under every input name (bounded through the KMZ path or
refused); a KMZ whose document is itself a zip; a DEM in a local (engineering) CRS; a
GeoTIFF with one damaged metadata byte; an area file of more than 100,000 features.
"""

from __future__ import annotations

import http.server
import io
import json
import threading
import urllib.error
import urllib.request
import zipfile
from pathlib import Path

import numpy as np
import pytest
import rasterio
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.errors import InputError
from scanplan.geo import area as A
from scanplan.geo import gdal_guard as G
from scanplan.geo.area import AreaSpec, load_area
from scanplan.geo.dem import open_dem, sample_dem

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
UAV_TOML = (EXAMPLES / "uav-canon-2000.toml").read_text(encoding="utf-8")
VALLEY_TOML = (EXAMPLES / "uav-town-valley-2000.toml").read_text(encoding="utf-8")
TOWN_KML = EXAMPLES / "areas" / "town-uav.kml"
VALLEY_DEM = EXAMPLES / "dem" / "town-valley.tif"
RING = [[37.60, 55.75], [37.63, 55.75], [37.63, 55.77], [37.60, 55.77], [37.60, 55.75]]


# -------------------------------------------------------------------------------------------
# Helpers
# -------------------------------------------------------------------------------------------
class _Recorder(http.server.BaseHTTPRequestHandler):
    hits: list[str]

    def _answer(self) -> None:
        self.hits.append(f"{self.command} {self.path}")
        self.send_response(404)
        self.end_headers()

    do_GET = do_HEAD = do_POST = _answer

    def log_message(self, *args: object) -> None:
        pass


@pytest.fixture
def listener():
    """A local HTTP server on 127.0.0.1 recording every request: (base URL, requests)."""
    hits: list[str] = []
    handler = type("Handler", (_Recorder,), {"hits": hits})
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    server.timeout = 1
    thread = threading.Thread(target=server.serve_forever, kwargs={"poll_interval": 0.05},
                              daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}", hits
    finally:
        server.shutdown()
        server.server_close()
        thread.join(10)


def _geojson(n: int = 1) -> bytes:
    feats = [{"type": "Feature", "properties": {"name": f"B{i}"},
              "geometry": {"type": "Polygon", "coordinates": [RING]}} for i in range(n)]
    return json.dumps({"type": "FeatureCollection", "features": feats}).encode()


def _ogr_vrt(url: str) -> str:
    return (f'<OGRVRTDataSource><OGRVRTLayer name="town"><SrcDataSource>/vsicurl/{url}/town'
            '.geojson</SrcDataSource></OGRVRTLayer></OGRVRTDataSource>')


def _raster_vrt(url: str) -> str:
    return ('<VRTDataset rasterXSize="260" rasterYSize="180"><SRS>EPSG:32637</SRS>'
            '<GeoTransform>484090, 20, 0, 6105550, 0, -20</GeoTransform>'
            '<VRTRasterBand dataType="Float32" band="1"><SimpleSource><SourceFilename>'
            f'/vsicurl/{url}/dem.tif</SourceFilename><SourceBand>1</SourceBand>'
            '</SimpleSource></VRTRasterBand></VRTDataset>')


def _bomb_zip(member: str = "doc.kml", size: int = 16 * 2**20) -> bytes:
    """A zip of one highly compressible member (ratio ~1000: a bomb's signature)."""
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr(member, b"<kml>" + b" " * size)
    return buf.getvalue()


def _cli(*args: str):
    r = CliRunner().invoke(main, [str(a) for a in args])
    out = r.output + (r.stderr or "")
    assert "Traceback" not in out and "Exception ignored" not in out, out
    assert r.exception is None or isinstance(r.exception, SystemExit), repr(r.exception)
    return r


def _area_project(tmp: Path, area_file: Path) -> Path:
    p = tmp / "p.toml"
    p.write_text(UAV_TOML.split("[area]")[0] + f'[area]\nfile = "{area_file.name}"\n',
                 encoding="utf-8")
    return p


def _valley_project(tmp: Path, dem_name: str) -> Path:
    (tmp / "areas").mkdir(exist_ok=True)
    (tmp / "areas" / "town-uav.kml").write_bytes(TOWN_KML.read_bytes())
    (tmp / "dem").mkdir(exist_ok=True)
    p = tmp / "valley.toml"
    p.write_text(VALLEY_TOML.replace("dem/town-valley.tif", f"dem/{dem_name}"),
                 encoding="utf-8")
    return p


def _err(spec: AreaSpec) -> InputError:
    with pytest.raises(InputError) as exc:
        load_area(spec)
    return exc.value


# -------------------------------------------------------------------------------------------
# No network, no other file
# -------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["town.vrt", "town.gpkg", "town.shp", "town.kml",
                                  "town.geojson"])
def test_ogr_vrt_with_a_url_source_is_refused_and_nothing_is_requested(name, listener,
                                                                      tmp_path):
    url, hits = listener
    f = tmp_path / name
    f.write_text(_ogr_vrt(url), encoding="utf-8")
    r = _cli("plan", _area_project(tmp_path, f), "--out", tmp_path / "out")
    assert r.exit_code == 2, r.output
    assert name in r.output and "virtual dataset (VRT)" in r.output, r.output
    assert hits == []
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_vrt_behind_a_kml_prefix_and_vsi_paths_in_text_are_refused(listener, tmp_path):
    url, hits = listener
    f = tmp_path / "a.kml"
    f.write_text('<?xml version="1.0"?><kml>' + _ogr_vrt(url) + "</kml>", encoding="utf-8")
    assert "VRT" in _err(AreaSpec(file=f)).message
    g = tmp_path / "a.geojson"
    g.write_text(json.dumps({"type": "FeatureCollection", "features": [],
                             "source": f"/vsicurl/{url}/x.geojson"}), encoding="utf-8")
    e = _err(AreaSpec(file=g))
    assert e.field == str(g) and "/vsicurl/" in e.message
    assert hits == []


def _linked_crs(url: str) -> bytes:
    return json.dumps({"type": "FeatureCollection", "crs": {
        "type": "link", "properties": {"href": f"{url}/crs.wkt", "type": "ogcwkt"}},
        "features": json.loads(_geojson())["features"]}).encode()


def test_geojson_crs_link_and_kml_network_links_fetch_nothing(listener, tmp_path):
    url, hits = listener
    g = tmp_path / "linked.geojson"
    g.write_bytes(_linked_crs(url))
    e = _err(AreaSpec(file=g))
    assert e.field == str(g) and "CRS as a link" in e.message
    k = tmp_path / "links.kml"
    k.write_text(
        '<?xml version="1.0" encoding="UTF-8"?><kml xmlns="http://www.opengis.net/kml/2.2">'
        f"<Document><NetworkLink><Link><href>{url}/net.kml</href></Link></NetworkLink>"
        f'<Style id="s"><IconStyle><Icon><href>{url}/icon.png</href></Icon></IconStyle>'
        f"</Style><Placemark><name>A</name><styleUrl>{url}/style.kml#s</styleUrl>"
        "<Polygon><outerBoundaryIs><LinearRing><coordinates>37.6,55.75 37.63,55.75 "
        "37.63,55.77 37.6,55.75</coordinates></LinearRing></outerBoundaryIs></Polygon>"
        "</Placemark></Document></kml>", encoding="utf-8")
    assert load_area(AreaSpec(file=k)).area_km2 > 1  # the polygon; no link followed
    assert hits == []


@pytest.mark.parametrize("name", ["dem.tif", "dem.vrt", "dem.tiff"])
def test_raster_vrt_dem_is_refused_and_nothing_is_requested(name, listener, tmp_path):
    url, hits = listener
    p = _valley_project(tmp_path, name)
    (tmp_path / "dem" / name).write_text(_raster_vrt(url), encoding="utf-8")
    r = _cli("plan", p, "--out", tmp_path / "out")
    assert r.exit_code == 2, r.output
    assert "terrain.dem (line" in r.output and name in r.output
    assert "virtual raster (VRT)" in r.output
    assert hits == []


def test_a_dem_whose_overview_companion_is_a_vrt_is_refused(listener, tmp_path):
    url, hits = listener
    p = _valley_project(tmp_path, "town-valley.tif")
    (tmp_path / "dem" / "town-valley.tif").write_bytes(VALLEY_DEM.read_bytes())
    (tmp_path / "dem" / "town-valley.tif.ovr").write_text(_raster_vrt(url), encoding="utf-8")
    r = _cli("plan", p, "--out", tmp_path / "out")
    assert r.exit_code == 2 and "town-valley.tif.ovr" in r.output, r.output
    assert hits == []
    (tmp_path / "dem" / "town-valley.tif.ovr").write_bytes(VALLEY_DEM.read_bytes())
    assert open_dem(tmp_path / "dem" / "town-valley.tif").width_px == 260  # a TIFF: fine


def test_gdal_itself_is_configured_for_the_process(listener, tmp_path, monkeypatch):
    """Past scanplan's own checks: after the first area is read, GDAL (pyogrio's and
    rasterio's) refuses a VRT and requests no URL, whatever it is handed (a host exempted
    from proxies, as NO_PROXY may list, would bypass the dead proxy: not here)."""
    import pyogrio

    for var in ("NO_PROXY", "no_proxy"):
        monkeypatch.delenv(var, raising=False)
    url, hits = listener
    f = tmp_path / "b.geojson"
    f.write_bytes(_geojson())
    load_area(AreaSpec(file=f))
    assert "OGR_VRT" not in pyogrio.list_drivers()
    vrt = tmp_path / "direct.vrt"
    vrt.write_text(_ogr_vrt(url), encoding="utf-8")
    for target in (str(vrt), f"/vsicurl/{url}/town.geojson"):
        with pytest.raises(Exception):  # noqa: B017 - GDAL's error classes vary
            pyogrio.read_info(target)
    pyogrio.read_info(io.BytesIO(_linked_crs(url)))  # GDAL would fetch the CRS: no request
    rvrt = tmp_path / "direct-raster.vrt"
    rvrt.write_text(_raster_vrt(url), encoding="utf-8")
    with pytest.raises(rasterio.errors.RasterioError), rasterio.open(rvrt, driver="GTiff"):
        pass
    with pytest.raises(rasterio.errors.RasterioError), \
            rasterio.open(f"/vsicurl/{url}/dem.tif"):
        pass
    assert hits == []
    with pytest.raises(urllib.error.HTTPError):  # the listener does hear a real request
        urllib.request.urlopen(f"{url}/control", timeout=10)
    assert hits == ["GET /control"]


# -------------------------------------------------------------------------------------------
# Zips by content
# -------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["a.kml", "a.kmz", "a.geojson", "a.json", "a.gpkg",
                                  "a.shp"])
def test_zip_content_under_every_area_name_goes_the_bounded_way(name, tmp_path):
    f = tmp_path / name
    f.write_bytes(_bomb_zip())
    e = _err(AreaSpec(file=f))
    assert e.field == str(f) and "zip bomb" in e.message, e.message
    # a genuine KMZ under any name is read (by content), through the same bounded path
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("doc.kml", TOWN_KML.read_bytes())
    f.write_bytes(buf.getvalue())
    assert load_area(AreaSpec(file=f)).area_km2 > 1


def test_zip_with_more_members_or_bytes_than_allowed(tmp_path, monkeypatch):
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_STORED) as z:
        for i in range(A.MAX_KMZ_ENTRIES + 1):
            z.writestr(f"{i}.txt", b"")
    f = tmp_path / "many.geojson"
    f.write_bytes(buf.getvalue())
    assert "entries" in _err(AreaSpec(file=f)).message
    monkeypatch.setattr(A, "MAX_KMZ_INFLATED", 1000)
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_STORED) as z:
        z.writestr("doc.kml", b"<kml>" + b" " * 2000)
    f.write_bytes(buf.getvalue())
    assert "would inflate" in _err(AreaSpec(file=f)).message


def test_kmz_whose_document_is_a_stored_inner_zip_is_refused(tmp_path):
    inner = _bomb_zip()
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_STORED) as z:
        z.writestr("doc.kml", inner)
    f = tmp_path / "nested.kmz"
    f.write_bytes(buf.getvalue())
    e = _err(AreaSpec(file=f))
    assert "archive inside the archive" in e.message and "a zip archive" in e.message


@pytest.mark.parametrize("data, says", [
    (b"\x1f\x8b\x08\x00" + b"\x00" * 20, "gzip"),
    (b"SQLite format 3\x00" + b"\x00" * 100, "not a GeoPackage"),
    (b"II*\x00" + b"\x00" * 20, "TIFF"),
])
def test_other_containers_are_refused_by_content(data, says, tmp_path):
    f = tmp_path / "a.geojson"
    f.write_bytes(data)
    e = _err(AreaSpec(file=f))
    assert says in e.message and "whatever its name" in e.message


def test_zip_named_tif_as_dem_is_refused_unread(tmp_path):
    p = _valley_project(tmp_path, "dem.tif")
    (tmp_path / "dem" / "dem.tif").write_bytes(_bomb_zip("dem.tif"))
    r = _cli("plan", p)
    assert r.exit_code == 2 and "a zip archive, whatever its name" in r.output, r.output


def test_geopackage_and_shapefile_are_still_read(tmp_path):
    import pyogrio.raw
    import shapely

    poly = shapely.Polygon(RING)
    for name, driver in (("b.gpkg", "GPKG"), ("b.shp", "ESRI Shapefile")):
        pyogrio.raw.write(str(tmp_path / name), shapely.to_wkb(np.array([poly], dtype=object)),
                          [np.array(["Town"], dtype=object)], ["name"], driver=driver,
                          geometry_type="Polygon", crs="EPSG:4326")
        assert load_area(AreaSpec(file=tmp_path / name)).area_km2 > 1
    for text in ("/vsicurl/http://127.0.0.1:9/x.prj", "http://127.0.0.1:9/x.prj"):
        (tmp_path / "b.prj").write_text(text, encoding="utf-8")
        e = _err(AreaSpec(file=tmp_path / "b.shp"))
        assert "b.prj is not the plain text" in e.message


# -------------------------------------------------------------------------------------------
# DEM details and large files
# -------------------------------------------------------------------------------------------
def test_dem_in_a_local_engineering_crs_exits_2(tmp_path):
    p = _valley_project(tmp_path, "local.tif")
    with rasterio.open(VALLEY_DEM) as src:
        z, profile = src.read(1), dict(src.profile)
    profile["crs"] = rasterio.crs.CRS.from_wkt(
        'LOCAL_CS["Site grid",LOCAL_DATUM["Site",0],UNIT["metre",1],'
        'AXIS["Easting",EAST],AXIS["Northing",NORTH]]')
    with rasterio.open(tmp_path / "dem" / "local.tif", "w", **profile) as dst:
        dst.write(z, 1)
    r = _cli("plan", p)
    assert r.exit_code == 2, r.output
    assert "terrain.dem (line" in r.output and "local (engineering)" in r.output
    # under an abstract width × length block (a local frame too) the same DEM is sampled
    info = open_dem(tmp_path / "dem" / "local.tif")
    x = np.array([info.bounds[0] + 500.0])
    y = np.array([info.bounds[3] - 500.0])
    assert info.local and np.isfinite(sample_dem(info, x, y, "LOCAL").elevation_m).all()
    with pytest.raises(InputError, match="local \\(engineering\\)"):
        sample_dem(info, x, y, "EPSG:32637")


def test_damaged_metadata_byte_is_one_clean_refusal(tmp_path, capfd):
    data = bytearray(VALLEY_DEM.read_bytes())
    at = bytes(data).index(b"<GDALMetadata>") + 2
    data[at] ^= 0xFF  # one byte of the TIFF's metadata text: no longer UTF-8
    p = _valley_project(tmp_path, "town-valley.tif")
    (tmp_path / "dem" / "town-valley.tif").write_bytes(bytes(data))
    r = _cli("plan", p)
    assert r.exit_code == 2, r.output
    assert "damaged GeoTIFF" in r.output and "town-valley.tif" in r.output
    printed = capfd.readouterr()
    assert "Traceback" not in printed.out + printed.err
    assert "UnicodeDecodeError" not in printed.out + printed.err + r.output


def test_more_than_100000_features_are_refused_with_their_count(tmp_path):
    """Nothing is dropped unseen: beyond the limit the file is refused, saying how many."""
    f = tmp_path / "many.geojson"
    f.write_bytes(_geojson(A.MAX_FEATURES + 1))
    e = _err(AreaSpec(file=f))
    assert f"{A.MAX_FEATURES + 1:,} features" in e.message, e.message
    assert f"at most {A.MAX_FEATURES:,}" in e.message


def test_the_limit_itself_is_read(tmp_path, monkeypatch):
    monkeypatch.setattr(A, "MAX_FEATURES", 3)
    f = tmp_path / "three.geojson"
    f.write_bytes(_geojson(3))
    e = _err(AreaSpec(file=f))
    assert "holds 3 polygons" in e.message  # all three seen: the choice is asked for
    f.write_bytes(_geojson(4))
    assert "4 features" in _err(AreaSpec(file=f)).message


def test_sniff_kinds():
    assert G.sniff(b"PK\x03\x04rest") == "zip"
    assert G.sniff(b"  <?xml version='1.0'?><kml xmlns='x'>") == "kml"
    assert G.sniff(b"<VRTDataset rasterXSize='1'>") == "vrt"
    assert G.sniff(b'\xef\xbb\xbf{"type": "FeatureCollection"}') == "json"
    assert G.sniff(b"MM\x00*") == "tiff"
    assert G.sniff(b"") == "empty"
    assert G.indirection(b"x /VSIZIP/y") == "/VSIZIP/"
    assert G.indirection(b"plain text") is None


def test_hardening_prints_nothing_when_a_gdal_lacks_a_skipped_driver():
    """pyogrio's GDAL is built without some skipped drivers (CouchDB, TileDB): hardened
    before pyogrio was imported, its driver registration printed "Warning 1: Unable to find
    driver … to unload from GDAL_SKIP" to the user's terminal on every plan with a file
    output. In a fresh interpreter — also one started by a hardened process, which
    inherits its GDAL_SKIP — nothing on stderr, and the skipped drivers are gone."""
    import subprocess
    import sys

    code = ("from scanplan.geo import gdal_guard as g; g.harden()\n"
            "import pyogrio, rasterio\n"
            "d = pyogrio.list_drivers()\n"
            "assert 'VRT' not in d and 'OGR_VRT' not in d, sorted(d)\n")
    import os

    G.harden()
    assert "CouchDB" in os.environ["GDAL_SKIP"]
    for env in ({k: v for k, v in os.environ.items() if k != "GDAL_SKIP"}, dict(os.environ)):
        env["PYTHONPATH"] = str(Path(G.__file__).parents[2])
        r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           timeout=120, env=env)
        assert r.returncode == 0, r.stderr
        assert r.stderr == "", ("GDAL_SKIP" in env, r.stderr)
