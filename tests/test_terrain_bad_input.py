"""Bad terrain input through the command line (issue 12, "Bad input"): every broken DEM is
exit 2 naming ``terrain.dem`` and its line, with what is wrong (and how much is missing),
no traceback and nothing written — for the UAV plan and for the film plan alike; the
doubtful ones (nodata under some photos, a geographic DEM, heights perhaps in feet) are
named warnings while the plan goes on."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import numpy as np
import pytest
import rasterio
from click.testing import CliRunner
from rasterio.transform import from_origin
from terrain_helpers import write_dem

from scanplan.cli.main import main
from scanplan.geo import dem as D

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SRC = EXAMPLES / "dem" / "town-valley.tif"


def _valley_with(tmp: Path, write) -> Path:
    """The valley example in ``tmp`` with its DEM replaced by ``write(path)``."""
    shutil.copytree(EXAMPLES / "areas", tmp / "areas")
    (tmp / "dem").mkdir()
    write(tmp / "dem" / "town-valley.tif")
    p = tmp / "valley.toml"
    p.write_text((EXAMPLES / "uav-town-valley-2000.toml").read_text(encoding="utf-8"),
                 encoding="utf-8")
    return p


def _like_example(path: Path, func, **kw) -> None:
    """A DEM on the example's grid holding func(z) of the example's heights z."""
    with rasterio.open(SRC) as src:
        z = src.read(1).astype("float64")
        profile = {**src.profile, "dtype": kw.pop("dtype", "float64"), **kw}
        t = src.transform
    with rasterio.open(path, "w", **profile) as dst:
        dst.write(np.asarray(func(z), dtype=profile["dtype"]), 1)
    assert t == profile["transform"]


def _no_crs(path: Path) -> None:
    write_dem(path, lambda x, y: x * 0 + 150, left=484090, top=6105550, cell=20, width=260,
              height=180, crs=None)


def _huge(path: Path) -> None:
    with rasterio.open(path, "w", driver="GTiff", width=D.MAX_DIMENSION_PX + 1, height=1,
                       count=1, dtype="uint8", crs="EPSG:32637",
                       transform=from_origin(484090, 6105550, 1, 1), tiled=True,
                       sparse_ok=True):
        pass


def _truncated(path: Path) -> None:
    """A valid header whose tiles are cut off: the read fails after the header."""
    data = SRC.read_bytes()
    _like_example(path, lambda z: z, compress=None, tiled=True, blockxsize=128,
                  blockysize=128)
    whole = path.read_bytes()
    path.write_bytes(whole[: len(whole) // 3])
    assert data  # the example itself is untouched


CASES = {
    "centimetres": (lambda p: _like_example(p, lambda z: z * 100.0),
                    ["look like centimetres", 'vertical_unit = "cm"']),
    "all nodata": (lambda p: _like_example(p, lambda z: np.full_like(z, -9999.0)),
                   ["none of the", "photo centres has ground under it"]),
    "no CRS": (_no_crs, ["no coordinate reference system"]),
    "huge header": (_huge, ["more than 1,000,000 on a side"]),
    "truncated tiles": (_truncated, ["could not be read"]),
    "not a TIFF": (lambda p: p.write_bytes(b"%PDF-1.4 not a raster"),
                   ["not a readable GeoTIFF"]),
    "missing": (lambda p: None, ["no such file"]),
}


@pytest.mark.parametrize("case", list(CASES))
def test_a_broken_dem_exits_2_naming_the_key_and_writes_nothing(tmp_path, case):
    write, words = CASES[case]
    p = _valley_with(tmp_path, write)
    out = tmp_path / "out"
    res = CliRunner().invoke(main, ["plan", str(p), "--out", str(out)])
    assert res.exit_code == 2, (case, res.output)
    assert "terrain.dem (line" in res.output, res.output
    for w in words:
        assert w in res.output, (case, w, res.output)
    assert "Traceback" not in res.output
    assert res.exception is None or isinstance(res.exception, SystemExit)
    assert not out.exists() or not any(out.iterdir())


def test_the_film_plan_refuses_a_broken_dem_too(tmp_path):
    shutil.copytree(EXAMPLES / "areas", tmp_path / "areas")
    (tmp_path / "dem").mkdir()
    (tmp_path / "dem" / "bad.tif").write_bytes(b"II*\x00garbage")
    text = (EXAMPLES / "film-town-relief-10000.toml").read_text(encoding="utf-8").replace(
        "ground_elevation_m = [110, 230]", 'dem = "dem/bad.tif"')
    p = tmp_path / "film.toml"
    p.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    res = CliRunner().invoke(main, ["plan", str(p), "--out", str(out)])
    assert res.exit_code == 2, res.output
    assert "terrain.dem (line" in res.output and "not a readable GeoTIFF" in res.output
    assert not out.exists() or not any(out.iterdir())


def test_a_partly_covering_dem_says_how_much_is_missing(tmp_path):
    """Half the example's DEM (its eastern half cut off): refused with km² and share."""
    def half(path: Path) -> None:
        with rasterio.open(SRC) as src:
            w = rasterio.windows.Window(0, 0, src.width // 2, src.height)
            z = src.read(1, window=w)
            profile = {**src.profile, "width": src.width // 2,
                       "transform": src.window_transform(w)}
        with rasterio.open(path, "w", **profile) as dst:
            dst.write(z, 1)

    p = _valley_with(tmp_path, half)
    res = CliRunner().invoke(main, ["plan", str(p)])
    assert res.exit_code == 2, res.output
    assert "does not cover the area" in res.output
    assert "km² (" in res.output and "%) of it lies outside the DEM" in res.output


def test_a_half_no_data_dem_exits_2_naming_the_share(tmp_path):
    """The example's DEM with its eastern half no-data: the same rule as a DEM that misses
    part of the area — exit 2 with the km² and the share, nothing planned."""
    def half(path: Path) -> None:
        def cut(z):
            z = z.copy()
            z[:, z.shape[1] // 2:] = -9999.0
            return z
        _like_example(path, cut, dtype="float32")

    p = _valley_with(tmp_path, half)
    out = tmp_path / "out"
    res = CliRunner().invoke(main, ["plan", str(p), "--out", str(out)])
    assert res.exit_code == 2, res.output
    assert "Traceback" not in res.output
    assert "terrain.dem (line" in res.output and "no-data farther than 50 m" in res.output
    share = float(re.search(r"km² \(([0-9.]+) %\) of the area", res.output).group(1))
    assert 20.0 < share < 60.0
    assert not out.exists() or not any(out.iterdir())


def test_doubtful_dems_are_named_warnings_and_the_plan_goes_on(tmp_path):
    """No-data under a few photos: filled and named (``terrain_voids_filled``); the plan is
    made."""
    def holes(path: Path) -> None:
        def punch(z):
            z = z.copy()
            z[80:84, 120:124] = -9999.0  # a small hole inside the town
            return z
        _like_example(path, punch, dtype="float32")

    p = _valley_with(tmp_path, holes)
    res = CliRunner().invoke(main, ["plan", str(p), "--json"])
    assert res.exit_code == 0, res.output
    import json
    d = json.loads(res.output)
    codes = [w["code"] for w in d["warnings"]]
    assert "terrain_voids_filled" in codes and "terrain_no_ground" not in codes
    t = d["terrain"]["uav"]
    assert t["voids_filled_px"] == 16 and t["voids_filled_m2"] == pytest.approx(16 * 400.0)
    assert t["photos_without_ground"] == 0 and t["photos_on_filled_voids"] > 0


@pytest.mark.parametrize(("key", "value", "said"), [
    ("relief_class", '"x"', "terrain.relief_class (line 8): must be one of flat, hilly"),
    ("altitude_mode", '"x"', "terrain.altitude_mode (line 8): must be one of"),
])
def test_a_bad_value_in_an_incomplete_terrain_section_is_named_first(tmp_path, key, value,
                                                                      said):
    """Bug (found by the fuzz suite in CI): ``[terrain] relief_class = "x"`` alone was told
    "[terrain]: needs dem … or ground_elevation_m" — the section's completeness was
    checked before the key's own value, so the bad key went unnamed."""
    p = tmp_path / "p.toml"
    p.write_text('[map]\nscale = 2000\nrelief_interval_m = 1\n[film]\ncamera = "rc30-153"\n'
                 f'photo_scales = [10000]\n[terrain]\n{key} = {value}\n', encoding="utf-8")
    r = CliRunner().invoke(main, ["plan", str(p)])
    assert r.exit_code == 2 and said in r.stderr, r.output
