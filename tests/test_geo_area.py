"""The contract area (scanplan.geo.area, issue 11): every GIS format through pyogrio, the
feature and layer choice, CRS handling, and every kind of bad input as an InputError that
names the file, the feature, what is wrong and what is allowed."""

from __future__ import annotations

import io
import os
import zipfile
from pathlib import Path

import numpy as np
import pyogrio.raw
import pytest
import shapely

from scanplan.errors import InputError
from scanplan.geo.area import (
    MAX_AREA_KM2,
    AreaSpec,
    load_area,
    rectangle_area,
)

RING = [[37.60, 55.75], [37.63, 55.75], [37.63, 55.77], [37.60, 55.77]]


def _kml(*placemarks: tuple[str, str], doctype: str = "") -> str:
    body = "".join(
        f"<Placemark><name>{name}</name>{geom}</Placemark>" for name, geom in placemarks)
    return (f'<?xml version="1.0" encoding="UTF-8"?>{doctype}<kml xmlns="http://www.opengis.'
            f'net/kml/2.2"><Document>{body}</Document></kml>')


def _poly_kml(ring: list[list[float]]) -> str:
    coords = " ".join(f"{x},{y},0" for x, y in [*ring, ring[0]])
    return (f"<Polygon><outerBoundaryIs><LinearRing><coordinates>{coords}</coordinates>"
            "</LinearRing></outerBoundaryIs></Polygon>")


def _write(path: Path, geoms: list, names: list[str], driver: str, crs: str = "EPSG:4326",
           layer: str | None = None, append: bool = False) -> Path:
    pyogrio.raw.write(str(path), shapely.to_wkb(np.array(geoms, dtype=object)),
                      [np.array(names, dtype=object)], ["name"], driver=driver,
                      geometry_type="Polygon", crs=crs, layer=layer, append=append)
    return path


def _err(spec: AreaSpec) -> InputError:
    with pytest.raises(InputError) as exc:
        load_area(spec)
    return exc.value


# -------------------------------------------------------------------------------------------
# Formats
# -------------------------------------------------------------------------------------------
def test_kml_polygon_in_utm(tmp_path):
    f = tmp_path / "block.kml"
    f.write_text(_kml(("Town", _poly_kml(RING))), encoding="utf-8")
    a = load_area(AreaSpec(file=f))
    assert a.plan_crs == "EPSG:32637" and a.plan_crs_name == "WGS 84 / UTM zone 37N"
    assert a.georeferenced and a.input_crs == "EPSG:4326"
    assert 3.5 < a.area_km2 < 4.5 and "Town" in a.source
    lon, lat = a.centroid_lonlat
    assert lon == pytest.approx(37.615, abs=1e-3) and lat == pytest.approx(55.76, abs=1e-3)


def test_kmz_geojson_gpkg_shapefile_give_the_same_area(tmp_path):
    poly = shapely.Polygon(RING)
    kml = _kml(("Town", _poly_kml(RING)))
    kmz = tmp_path / "block.kmz"
    with zipfile.ZipFile(kmz, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("doc.kml", kml)
    files = [kmz, _write(tmp_path / "b.geojson", [poly], ["Town"], "GeoJSON"),
             _write(tmp_path / "b.gpkg", [poly], ["Town"], "GPKG"),
             _write(tmp_path / "b.shp", [poly], ["Town"], "ESRI Shapefile")]
    ref = load_area(AreaSpec(polygon=RING)).area_km2
    for f in files:
        assert load_area(AreaSpec(file=f)).area_km2 == pytest.approx(ref, rel=1e-9), f


def test_a_projected_file_is_planned_in_its_own_crs(tmp_path):
    """A Gauss–Krüger (Pulkovo 1942 zone 7) shapefile: planned in its CRS, not UTM."""
    x0, y0 = 7_400_000.0, 6_180_000.0
    poly = shapely.box(x0, y0, x0 + 1500, y0 + 1000)
    f = _write(tmp_path / "gk.shp", [poly], ["Block"], "ESRI Shapefile", crs="EPSG:28407")
    a = load_area(AreaSpec(file=f))
    assert a.plan_crs == "EPSG:28407" and a.area_km2 == pytest.approx(1.5)
    b = load_area(AreaSpec(file=f, plan_crs="EPSG:32637"))
    assert b.plan_crs == "EPSG:32637" and b.area_km2 == pytest.approx(1.5, rel=2e-3)


def test_feature_and_layer_choice(tmp_path):
    f = tmp_path / "two.gpkg"
    _write(f, [shapely.Polygon(RING)], ["North"], "GPKG", layer="a")
    south = [[x, y - 0.1] for x, y in RING]
    _write(f, [shapely.Polygon(south)], ["South"], "GPKG", layer="b", append=True)
    e = _err(AreaSpec(file=f))
    assert str(f) in e.field and "2 polygons" in e.message and "North" in e.message
    assert "[area] feature" in e.message
    assert "North" in load_area(AreaSpec(file=f, feature="North")).source
    assert "South" in load_area(AreaSpec(file=f, feature=2)).source
    assert "South" in load_area(AreaSpec(file=f, layer="b")).source
    assert "south" not in load_area(AreaSpec(file=f, feature="north")).source.lower()
    e = _err(AreaSpec(file=f, feature="East"))
    assert e.field == "feature" and "North" in e.message
    e = _err(AreaSpec(file=f, feature=3))
    assert e.field == "feature" and "1 … 2" in e.message
    e = _err(AreaSpec(file=f, layer="c"))
    assert e.field == "layer" and "its layers: a, b" in e.message


def test_rectangle_is_not_georeferenced():
    a = rectangle_area(2000, 3000)
    assert not a.georeferenced and a.plan_crs == "LOCAL" and a.area_km2 == 6.0
    assert load_area(AreaSpec(width_m=2000, length_m=3000)) == a
    assert load_area(AreaSpec()) is None


# -------------------------------------------------------------------------------------------
# Bad input: named, with what is allowed
# -------------------------------------------------------------------------------------------
@pytest.mark.parametrize("ring,field,words", [
    ([[37.6, 55.75], [37.61, 55.75]], "polygon", "at least 3"),
    ([[37.6, 55.75], [37.6, 55.75], [37.61, 55.76], [37.6, 55.75]], "polygon", "at least 3"),
    ([[55.75, 37.6], [55.75, 137.63], [55.77, 37.63]], "polygon", "swapped"),
    ([[37.6, 55.7], [37.7, 55.8], [37.7, 55.7], [37.6, 55.8]], "polygon", "crosses itself at"),
    ([[37.6, 55.7], [37.6, 55.8], [37.6, 55.9]], "polygon", "on a line"),
    ([[190.0, 10.0], [191.0, 10.0], [191.0, 11.0]], "polygon", "longitude"),
    ([[0.0, 0.0], [3.0, 0.0], [3.0, 3.0], [0.0, 3.0]], "polygon", "10,000 km²"),
    ([[37.6, 55.7], [37.7, "x"], [37.8, 55.9]], "polygon", "two finite numbers"),
])
def test_bad_inline_polygons(ring, field, words):
    e = _err(AreaSpec(polygon=ring))
    assert e.field == field and words in e.message, e.message


def test_self_intersection_says_where():
    e = _err(AreaSpec(polygon=[[37.6, 55.7], [37.7, 55.8], [37.7, 55.7], [37.6, 55.8]]))
    assert "lon 37.650000, lat 55.750000" in e.message


def test_absurd_area_names_the_limit():
    e = _err(AreaSpec(polygon=[[0.0, 0.0], [3.0, 0.0], [3.0, 3.0], [0.0, 3.0]]))
    assert f"{MAX_AREA_KM2:,.0f}" in e.message and "wrong CRS" in e.message


@pytest.mark.parametrize("key,value", [("crs", "EPSG:999999"), ("plan_crs", "EPSG:999999"),
                                       ("crs", "not a crs")])
def test_unknown_crs(key, value):
    e = _err(AreaSpec(polygon=RING, **{key: value}))
    assert e.field == key and "EPSG" in e.message


def test_plan_crs_must_be_projected_in_metres():
    e = _err(AreaSpec(polygon=RING, plan_crs="EPSG:4326"))
    assert e.field == "plan_crs" and "projected" in e.message


def test_inline_polygon_in_a_given_crs():
    ring = [[400_000, 6_100_000], [401_000, 6_100_000], [401_000, 6_101_000]]
    a = load_area(AreaSpec(polygon=ring, crs=32637))
    assert a.plan_crs == "EPSG:32637" and a.area_km2 == pytest.approx(0.5)


def test_one_area_only(tmp_path):
    e = _err(AreaSpec(polygon=RING, width_m=100, length_m=100))
    assert "give one area" in e.message
    e = _err(AreaSpec(width_m=100))
    assert e.field == "length_m"
    e = _err(AreaSpec(feature="x"))
    assert e.field == "feature"


def test_file_without_polygon(tmp_path):
    f = tmp_path / "lines.kml"
    f.write_text(_kml(("Road", "<LineString><coordinates>37.6,55.7 37.7,55.8</coordinates>"
                               "</LineString>")), encoding="utf-8")
    e = _err(AreaSpec(file=f))
    assert e.field == str(f) and "no polygon" in e.message and "line" in e.message


def test_kml_with_entities_is_refused_before_parsing(tmp_path):
    bomb = ('<!DOCTYPE kml [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;">]>')
    f = tmp_path / "evil.kml"
    f.write_text(_kml(("&b;", _poly_kml(RING)), doctype=bomb), encoding="utf-8")
    e = _err(AreaSpec(file=f))
    assert e.field == str(f) and "<!ENTITY>" in e.message


def test_kmz_zip_bomb_is_refused_from_its_directory(tmp_path):
    f = tmp_path / "bomb.kmz"
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("doc.kml", _kml(("Town", _poly_kml(RING))) + " " * 20_000_000)
    f.write_bytes(buf.getvalue())
    e = _err(AreaSpec(file=f))
    assert e.field == str(f) and "zip bomb" in e.message


def test_kmz_that_lies_about_its_size(tmp_path):
    """A zip directory that understates an entry: reading stops at the stated size."""
    good = io.BytesIO()
    with zipfile.ZipFile(good, "w", zipfile.ZIP_STORED) as z:
        z.writestr("doc.kml", _kml(("Town", _poly_kml(RING))))
    data = bytearray(good.getvalue())
    size = len(_kml(("Town", _poly_kml(RING))))
    small = (size - 100).to_bytes(4, "little")
    # the uncompressed size in the local header (offset 22) and the central directory (24)
    data[22:26] = small
    cd = data.rfind(b"PK\x01\x02")
    data[cd + 24:cd + 28] = small
    f = tmp_path / "liar.kmz"
    f.write_bytes(bytes(data))
    e = _err(AreaSpec(file=f))
    assert e.field == str(f)


def test_missing_and_unreadable_files(tmp_path):
    e = _err(AreaSpec(file=tmp_path / "nope.geojson"))
    assert "no such file" in e.message.lower()
    bad = tmp_path / "bad.gpkg"
    bad.write_bytes(b"not a geopackage")
    e = _err(AreaSpec(file=bad))
    assert e.field == str(bad) and "cannot be read" in e.message
    e = _err(AreaSpec(file=tmp_path))
    assert e.field == str(tmp_path)


@pytest.mark.filterwarnings("ignore:'crs' was not provided")
def test_a_file_without_a_crs(tmp_path):
    """A Shapefile without .prj in Gauss–Krüger metres: WGS 84 was assumed, the message
    says so; with [area] crs it is read."""
    x0, y0 = 7_400_000.0, 6_180_000.0
    f = _write(tmp_path / "noprj.shp", [shapely.box(x0, y0, x0 + 1500, y0 + 1000)], ["B"],
               "ESRI Shapefile", crs=None)
    (tmp_path / "noprj.prj").unlink(missing_ok=True)
    e = _err(AreaSpec(file=f))
    assert "declares no CRS" in e.message and "[area] crs" in e.message
    a = load_area(AreaSpec(file=f, crs="EPSG:28407"))
    assert a.plan_crs == "EPSG:28407" and a.area_km2 == pytest.approx(1.5)
    e = _err(AreaSpec(file=_write(tmp_path / "gk.shp", [shapely.box(x0, y0, x0 + 9, y0 + 9)],
                                  ["B"], "ESRI Shapefile", crs="EPSG:28407"), crs=32637))
    assert e.field == "crs" and "differs" in e.message


def test_google_earth_kml_with_folders_and_pins(tmp_path):
    """Folders are layers (LIBKML); a pin beside the polygon is ignored."""
    f = tmp_path / "ge.kml"
    f.write_text(
        '<?xml version="1.0" encoding="UTF-8"?><kml xmlns="http://www.opengis.net/kml/2.2">'
        "<Document><Folder><name>Contract</name><Placemark><name>Block A</name>"
        f"{_poly_kml(RING)}</Placemark><Placemark><name>Base</name><Point><coordinates>"
        "37.61,55.76,0</coordinates></Point></Placemark></Folder></Document></kml>",
        encoding="utf-8")
    a = load_area(AreaSpec(file=f))
    assert "Block A" in a.source and a.area_km2 > 3


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="named pipes")
def test_hostile_files_are_refused_before_gdal_opens_them(tmp_path):
    """A FIFO or a device as the file or as a Shapefile's companion: refused, never read."""
    os.mkfifo(tmp_path / "pipe.geojson")
    e = _err(AreaSpec(file=tmp_path / "pipe.geojson"))
    assert "FIFO" in e.message
    f = _write(tmp_path / "b.shp", [shapely.Polygon(RING)], ["B"], "ESRI Shapefile")
    (tmp_path / "b.cpg").unlink(missing_ok=True)
    os.mkfifo(tmp_path / "b.cpg")
    e = _err(AreaSpec(file=f))
    assert "b.cpg is not a regular file" in e.message
    (tmp_path / "z.kml").symlink_to("/dev/zero")
    e = _err(AreaSpec(file=tmp_path / "z.kml"))
    assert "not a regular file" in e.message


# -------------------------------------------------------------------------------------------
# Kept between plans: the page re-plans the same area on every edit
# -------------------------------------------------------------------------------------------
def test_the_same_file_is_read_once_and_a_changed_one_again(tmp_path, monkeypatch):
    import scanplan.geo.area as A
    from scanplan.io.kept import Kept

    # an empty store: another test of this worker may have read the same bytes under its
    # own name (each call then gives that area renamed, a new object each time)
    monkeypatch.setattr(A, "_KEPT", Kept(A._KEPT_AREAS))
    reads: list[str] = []
    real = A._load_polygon
    monkeypatch.setattr(A, "_load_polygon", lambda spec: reads.append(str(spec.file)) or
                        real(spec))
    f = tmp_path / "block.kml"
    f.write_text(_kml(("Town", _poly_kml(RING))), encoding="utf-8")
    first = load_area(AreaSpec(file=f))
    assert load_area(AreaSpec(file=f)) is first and len(reads) == 1
    wider = [[37.60, 55.75], [37.66, 55.75], [37.66, 55.77], [37.60, 55.77]]
    f.write_text(_kml(("Town", _poly_kml(wider))), encoding="utf-8")  # same name, new bytes
    again = load_area(AreaSpec(file=f))
    assert len(reads) == 2 and again.area_km2 > 1.5 * first.area_km2
    assert load_area(AreaSpec(file=f, plan_crs="EPSG:32638")).plan_crs == "EPSG:32638"
    assert load_area(AreaSpec(polygon=RING)) is load_area(AreaSpec(polygon=RING))
    moved = tmp_path / "elsewhere" / "copy.kml"  # the same bytes under another name
    moved.parent.mkdir()
    moved.write_bytes(f.read_bytes())
    other = load_area(AreaSpec(file=moved))
    assert str(moved) not in reads
    assert other.source_file == str(moved) and other.source.startswith(str(moved))
    assert str(f) not in other.source and other.geometry.equals(again.geometry)
    A.forget_read_areas()  # forgotten: read and projected again, the same area
    fresh = load_area(AreaSpec(file=moved))
    assert reads.count(str(moved)) == 1 and fresh is not other
    assert fresh.geometry.equals(other.geometry) and fresh.plan_crs == other.plan_crs


def test_a_shapefile_is_read_every_time(tmp_path, monkeypatch):
    import scanplan.geo.area as A

    reads: list[str] = []
    real = A._load_polygon
    monkeypatch.setattr(A, "_load_polygon", lambda spec: reads.append(str(spec.file)) or
                        real(spec))
    f = _write(tmp_path / "b.shp", [shapely.Polygon(RING)], ["Town"], "ESRI Shapefile")
    load_area(AreaSpec(file=f))
    load_area(AreaSpec(file=f))
    assert len(reads) == 2  # its .prj and .dbf are files of their own


def test_pyogrio_is_imported_without_pandas_and_pandas_still_works():
    """pyogrio's package imports pandas only for GeoPandas' data frames; without GeoPandas
    scanplan imports pyogrio without it (0.3–0.9 s), and pandas imports as ever after."""
    import subprocess
    import sys

    code = ("import sys\n"
            "from scanplan.geo.gdal_guard import import_pyogrio\n"
            "p = import_pyogrio()\n"
            "print('pandas' in sys.modules, p.__version__ is not None)\n"
            "import pandas\n"
            "print(pandas.DataFrame({'a': [1]}).shape)\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       check=True)
    assert r.stdout.split("\n")[:2] == ["False True", "(1, 1)"]
