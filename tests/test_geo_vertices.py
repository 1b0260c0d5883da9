"""An area given as a CSV/TXT list of its vertices plans to the same polygon as the KML of
the same vertices, in every dialect a customer's engineer sends; a bad cell is an input
error naming its line and column."""

from __future__ import annotations

import shutil
from pathlib import Path

import pyogrio
import pytest
import shapely
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from pyproj import Transformer

from scanplan.cli.main import main
from scanplan.errors import InputError
from scanplan.geo.area import AreaSpec, load_area
from scanplan.project.file import load_project
from scanplan.project.spec import plan_project

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
KML = EXAMPLES / "areas" / "town-uav.kml"


def _ring() -> list[tuple[float, float]]:
    _, _, wkb, _ = pyogrio.raw.read(KML, layer=0)
    return [(x, y) for x, y, *_ in shapely.from_wkb(wkb[0]).exterior.coords]


def _dialects(ring):
    """Five dialects of the same vertices: (file name, text)."""
    comma = "lon,lat\n" + "".join(f"{x!r},{y!r}\n" for x, y in ring)
    semicolon = "Latitude;Longitude\r\n" + "".join(  # lat first, decimal comma, CRLF
        f"{y!r};{x!r}\r\n".replace(".", ",") for x, y in ring[:-1])
    tab = "".join(f"{x!r}\t{y!r}\n".replace(".", ",") for x, y in ring)  # no header
    spaces = "# town boundary\n\n" + "".join(f"  {x!r}   {y!r}\n" for x, y in ring) + "\n"
    semicolon_bare = "".join(f"{x!r};{y!r}\n".replace(".", ",") for x, y in ring)
    return [("comma.csv", comma), ("semicolon.csv", semicolon), ("tab.txt", tab),
            ("spaces.txt", spaces), ("bare.csv", semicolon_bare)]


@pytest.fixture(scope="module")
def kml_area():
    return load_area(AreaSpec(file=str(KML)))


@pytest.mark.parametrize("index", range(5))
def test_vertex_list_is_the_kml_polygon(tmp_path, kml_area, index):
    name, text = _dialects(_ring())[index]
    path = tmp_path / name
    path.write_text(text, encoding="utf-8", newline="")
    area = load_area(AreaSpec(file=str(path)))
    assert area.plan_crs == kml_area.plan_crs
    assert area.geometry.normalize().equals_exact(kml_area.geometry.normalize(), 1e-6)
    assert area.geometry.area == pytest.approx(kml_area.geometry.area, rel=1e-12)


def test_projected_vertices_with_a_stated_crs(tmp_path, kml_area):
    """x, y in metres (UTM 37N) with [area] crs: the same polygon."""
    tr = Transformer.from_crs("EPSG:4326", "EPSG:32637", always_xy=True)
    rows = "".join(f"{i};{e:.4f};{n:.4f}\n".replace(".", ",")
                   for i, (e, n) in enumerate((tr.transform(x, y) for x, y in _ring()), 1))
    path = tmp_path / "survey.csv"
    path.write_text("point;easting;northing\n" + rows, encoding="utf-8")
    area = load_area(AreaSpec(file=str(path), crs="EPSG:32637"))
    diff = area.geometry.symmetric_difference(kml_area.geometry).area
    assert diff < 1e-6 * kml_area.geometry.area


def test_a_plan_over_the_vertex_list_is_the_plan_over_the_kml(tmp_path):
    proj = tmp_path / "p.toml"
    (tmp_path / "areas").mkdir()
    shutil.copy(KML, tmp_path / "areas")
    name, text = _dialects(_ring())[1]
    (tmp_path / "areas" / name).write_text(text, encoding="utf-8")
    base = (EXAMPLES / "uav-town-2000.toml").read_text()
    proj.write_text(base.replace('file = "areas/town-uav.kml"', f'file = "areas/{name}"'))
    assert f"areas/{name}" in proj.read_text()
    a = plan_project(load_project(str(EXAMPLES / "uav-town-2000.toml"))).uav.layout
    b = plan_project(load_project(str(proj))).uav.layout
    assert (len(b.photos), len(b.strips), len(b.sorties)) == (
        len(a.photos), len(a.strips), len(a.sorties))


@pytest.mark.parametrize(("text", "words"), [
    ("lon;lat\n37,60;55,70\n37,62;abc\n37,62;55,71\n", ["line 3", "'lat'", "'abc'"]),
    ("lon,lat\n37.60,55.70\n37.62,55,70\n37.62,55.71\n",  # a decimal comma: never guessed
     ["line 3 has 3 cells", "the header has 2", "decimal mark is a point"]),
    ("id,lon,lat\n1,37.60,55.70\n2,37.62,55.70\n3,37.62,\n", ["line 4", "'lat'"]),
    ("name,value\nA,1\n", ["line 1", "lon and lat"]),
    ("1;37.60;55.70\n2;37.62;55.70\n3;37.62;55.71\n", ["line 1 has 3 cells", "header"]),
    ("37.60,55.70\n37.62,55.70\n", ["2 distinct", "at least 3"]),
    ("# nothing\n\n", ["no vertex"]),
    ("lon;lat\n", ["no vertex"]),
    ("lon;lat\n1e400;55\n2;3\n4;5\n", ["line 2", "'lon'", "finite"]),
])
def test_bad_vertex_lists_name_line_and_column(tmp_path, text, words):
    path = tmp_path / "v.csv"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(InputError) as err:
        load_area(AreaSpec(file=str(path)))
    assert err.value.field == str(path)
    for w in words:
        assert w in err.value.message


def test_not_utf8_is_an_input_error(tmp_path):
    path = tmp_path / "v.txt"
    path.write_bytes("широта;долгота\n".encode("cp1251"))
    with pytest.raises(InputError, match="not UTF-8"):
        load_area(AreaSpec(file=str(path)))


def test_cli_exit_2_names_the_cell(tmp_path):
    (tmp_path / "areas").mkdir()
    (tmp_path / "areas" / "v.csv").write_text("lon,lat\n37.6,55.7\n37.7,x\n37.7,55.8\n")
    base = (EXAMPLES / "uav-town-2000.toml").read_text()
    (tmp_path / "p.toml").write_text(base.replace("areas/town-uav.kml", "areas/v.csv"))
    res = CliRunner().invoke(main, ["plan", str(tmp_path / "p.toml")])
    assert res.exit_code == 2
    assert "line 3, column 'lat': 'x' is not a finite number" in res.output
    assert "Traceback" not in res.output


def test_a_wkt_table_is_read_by_shapely_not_gdal(tmp_path, kml_area):
    ring = _ring()
    wkt = shapely.Polygon(ring).wkt
    path = tmp_path / "area.csv"
    path.write_text(f'id,WKT\n1,"{wkt}"\n', encoding="utf-8")
    area = load_area(AreaSpec(file=str(path)))
    assert area.geometry.symmetric_difference(kml_area.geometry).area < 1e-6 * area.geometry.area


@settings(max_examples=150, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(st.lists(st.one_of(
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.text(alphabet=st.characters(blacklist_categories=["Cs"]), max_size=6)),
    min_size=0, max_size=4), max_size=8),
    st.sampled_from([",", ";", "\t", " ", ", "]))
def test_any_text_is_a_polygon_or_an_input_error(tmp_path, rows, sep):
    """Whatever a vertex list holds, reading it gives a polygon, GDAL's turn (None) or an
    input error — never another exception."""
    from scanplan.geo.vertices import read_vertices

    path = tmp_path / "fuzz.csv"
    path.write_text("\n".join(sep.join(r) for r in rows), encoding="utf-8")
    try:
        out = read_vertices(path, "fuzz.csv")
    except InputError as exc:
        assert exc.field == "fuzz.csv" and exc.message
    else:
        assert out is None or isinstance(out, shapely.Polygon)


def test_a_vertex_list_has_no_layer(tmp_path):
    path = tmp_path / "v.csv"
    path.write_text("lon,lat\n37.6,55.7\n37.7,55.7\n37.7,55.8\n", encoding="utf-8")
    with pytest.raises(InputError) as err:
        load_area(AreaSpec(file=str(path), layer="boundary"))
    assert err.value.field == "layer" and "list of vertices" in err.value.message
