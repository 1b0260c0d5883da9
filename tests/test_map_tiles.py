"""``[map] basemap`` as an XYZ tile URL template: the tiles over the PDF map page's extent
at the zoom it prints at, fetched from a tile server on 127.0.0.1 (no test reaches the
internet), kept in the same disk cache as the page's, printed under the flight with their
attribution; offline the plan and its PDF are made all the same, without the background
and with a warning; a bad template or a missing attribution stops the plan naming the
key."""

from __future__ import annotations

import math
import socket
import subprocess
from pathlib import Path

import numpy as np
import pytest
from basemap_helpers import TileServer
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.geo.basemap import MAX_TILES, tiles_zoom
from scanplan.project.file import load_project
from scanplan.project.model import build_model
from scanplan.project.spec import plan_project

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
TILE_COLOUR = (30, 170, 190)
"""The tiles' teal: a colour nothing else on the map page has."""
ATTRIBUTION = "Local tiles © the test"


@pytest.fixture(autouse=True)
def _cache(tmp_path, monkeypatch):
    """The user's tile cache in the test's folder."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))


def _project(tmp_path: Path, basemap: str | None, attribution: str | None = ATTRIBUTION
             ) -> Path:
    (tmp_path / "areas").mkdir(exist_ok=True)
    (tmp_path / "areas" / "town-uav.kml").write_bytes(
        (EXAMPLES / "areas" / "town-uav.kml").read_bytes())
    lines = "" if basemap is None else f'basemap = "{basemap}"\n'
    if attribution is not None:
        lines += f'basemap_attribution = "{attribution}"\n'
    text = (EXAMPLES / "uav-town-2000.toml").read_text(encoding="utf-8")
    path = tmp_path / "p.toml"
    path.write_text(text.replace("[map]\n", "[map]\n" + lines, 1), encoding="utf-8")
    return path


def _pdf(tmp_path: Path, project: Path, locale: str = "en") -> tuple[list[str], Path]:
    """The PDF of ``project`` in ``locale``: its pages' text and the file."""
    text = project.read_text(encoding="utf-8")
    project.write_text(text.replace('locale = "en"', f'locale = "{locale}"').replace(
        'locale = "ru"', f'locale = "{locale}"'), encoding="utf-8")
    out = tmp_path / f"out-{locale}"
    r = CliRunner().invoke(main, ["plan", str(project), "--out", str(out), "--formats", "pdf",
                                  "-q"])
    assert r.exit_code == 0, r.output
    pdf = out / "spec.pdf"
    pages = subprocess.run(["pdftotext", str(pdf), "-"], capture_output=True, text=True,
                           check=True).stdout.split("\f")
    return pages, pdf


def _colour_pixels(pdf: Path, page: int, folder: Path, colour: tuple[int, int, int]) -> int:
    from PIL import Image

    stem = folder / f"page{page}"
    subprocess.run(["pdftoppm", "-png", "-r", "40", "-f", str(page), "-l", str(page), str(pdf),
                    str(stem)], check=True)
    (png,) = folder.glob(f"page{page}*.png")
    img = np.asarray(Image.open(png).convert("RGB")).reshape(-1, 3).astype(int)
    png.unlink()
    return int((np.abs(img - np.array(colour)) < 30).all(axis=1).sum())


def _map_page(pages: list[str], heading: str) -> int:
    (page,) = [i + 1 for i, p in enumerate(pages) if heading in p]
    return page


def _closed_port() -> int:
    """A port on 127.0.0.1 nothing listens on (a refused connection: offline)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_the_zoom_is_the_one_the_map_prints_at():
    """A tile pixel at zoom z is 2πR·cos φ / (256 · 2^z) of ground (OpenStreetMap wiki,
    "Zoom levels": 2.389 m at zoom 16 on the equator); the zoom taken is the shallowest
    whose pixel is at most the map's printed pixel."""
    pixel_z16 = 2 * math.pi * 6378137.0 / 256 / 2 ** 16
    assert abs(pixel_z16 - 2.389) < 0.001

    def around(width_m: float) -> tuple[float, float, float, float]:
        half = width_m / 2 / 111_319.49  # degrees of longitude on the equator (WGS 84)
        return (-half, -half / 10, half, half / 10)

    assert tiles_zoom(around(1600 * pixel_z16 * 1.001), 1600) == 16
    assert tiles_zoom(around(1600 * pixel_z16 * 0.999), 1600) == 17
    assert tiles_zoom(around(1600 * pixel_z16 * 2.002), 1600) == 15
    # a tile spans the same degrees of longitude at every latitude, and so does the map's
    # pixel: the same span of longitude takes the same zoom at 60° as on the equator
    assert tiles_zoom((10.0, 59.99, 10.1, 60.01), 1600) == tiles_zoom(
        (10.0, -0.01, 10.1, 0.01), 1600) == 15
    assert tiles_zoom(around(1.0), 1600) == 19  # the deepest asked for
    assert tiles_zoom((-179, -80, 179, 80), 16000) >= 0
    big = (30.0, 50.0, 40.0, 60.0)
    z = tiles_zoom(big, 100_000)
    from scanplan.geo.basemap import _tile_count

    assert _tile_count(big, z) <= MAX_TILES < _tile_count(big, z + 1)


def test_tiles_are_printed_under_the_flight_with_their_attribution(tmp_path):
    with TileServer(TILE_COLOUR) as tiles:
        project = _project(tmp_path, tiles.url)
        pages, pdf = _pdf(tmp_path, project)
        asked = len(tiles.hits)
        assert 4 <= asked <= MAX_TILES
        zooms = {int(h.split("/")[1]) for h in tiles.hits}
        assert len(zooms) == 1 and 14 <= zooms.pop() <= 17, tiles.hits  # ~1.4–3 m a pixel
        result = plan_project(load_project(project))
    assert not [w for w in result.warnings if w.code.startswith("map_tiles")]
    page = _map_page(pages, f"Background: {ATTRIBUTION}")
    assert _colour_pixels(pdf, page, tmp_path, TILE_COLOUR) > 5000  # the map's background
    assert _colour_pixels(pdf, 1, tmp_path, TILE_COLOUR) == 0  # only on the map page
    # the server gone: the same tiles from the disk cache, nothing asked again
    cached = list((tmp_path / "cache" / "scanplan" / "tiles").rglob("*"))
    assert sum(p.is_file() for p in cached) >= asked
    ru_pages, ru_pdf = _pdf(tmp_path, project, "ru")
    page = _map_page(ru_pages, f"Подложка: {ATTRIBUTION}")
    assert _colour_pixels(ru_pdf, page, tmp_path, TILE_COLOUR) > 5000
    assert len(tiles.hits) == asked


def test_offline_the_pdf_is_made_without_background_and_says_so(tmp_path):
    project = _project(tmp_path, f"http://127.0.0.1:{_closed_port()}/{{z}}/{{x}}/{{y}}.png")
    result = plan_project(load_project(project))
    (w,) = [w for w in result.warnings if w.code.startswith("map_tiles")]
    assert w.code == "map_tiles_unreachable" and result.backgrounds == {}
    assert "127.0.0.1" in w.message.text("en") and "127.0.0.1" in w.message.text("ru")
    for locale, warning, note in (
            ("en", "no background tile came from 127.0.0.1:", "Background: none — no tile"),
            ("ru", "Тайлы подложки с 127.0.0.1:", "Подложка: нет — тайлы с 127.0.0.1:")):
        pages, pdf = _pdf(tmp_path, project, locale)
        flat = [" ".join(p.split()) for p in pages]
        assert warning in flat[0]  # page 1's warnings
        page = _map_page(flat, note)  # the map page says why it has no background
        assert _colour_pixels(pdf, page, tmp_path, TILE_COLOUR) == 0
    r = CliRunner().invoke(main, ["plan", str(project)])
    assert r.exit_code == 0 and "Traceback" not in r.output


def test_tiles_the_server_lacks_are_counted(tmp_path):
    with TileServer(TILE_COLOUR, has=lambda z, x, y: x % 2 == 0) as tiles:
        project = _project(tmp_path, tiles.url)
        result = plan_project(load_project(project))
        asked = len(tiles.hits)
    (w,) = [w for w in result.warnings if w.code.startswith("map_tiles")]
    assert w.code == "map_tiles_missing" and "uav" in result.backgrounds
    lacking = sum(int(h.split("/")[2]) % 2 for h in tiles.hits)
    assert 0 < lacking < asked
    assert f"{lacking} of the {asked} background tiles" in w.message.text("en")


@pytest.mark.parametrize("url", [
    "https://tiles.example.org/{z}/{x}.png",           # no {y}
    "ftp://tiles.example.org/{z}/{x}/{y}.png",         # not http(s)
    "tiles.example.org/{z}/{x}/{y}.png",               # no scheme
    "https://{s}.tile.example.org/{z}/{x}/{y}.png",    # a placeholder scanplan does not fill
])
def test_a_bad_template_stops_the_plan_naming_the_key(tmp_path, url):
    r = CliRunner().invoke(main, ["plan", str(_project(tmp_path, url))])
    assert r.exit_code == 2 and "Traceback" not in r.output
    assert "map.basemap (line" in r.stderr and "http(s) URL with {z}, {x} and {y}" in r.stderr


def test_a_tile_url_needs_its_attribution_and_osm_has_its_own(tmp_path):
    r = CliRunner().invoke(main, ["plan", str(_project(tmp_path, "https://t.example.org/"
                                                       "{z}/{x}/{y}.png", None))])
    assert r.exit_code == 2 and "map.basemap_attribution" in r.stderr
    assert "tile URL" in r.stderr
    m = build_model(load_project(_project(tmp_path, "osm", None))).map
    assert m.basemap_url == "https://tile.openstreetmap.org/{z}/{x}/{y}.png"
    assert m.basemap_attribution == "© OpenStreetMap contributors" and m.basemap is None
    m = build_model(load_project(_project(tmp_path, "osm", "OSM, ODbL"))).map
    assert m.basemap_attribution == "OSM, ODbL"
