"""A layout's WGS 84 longitude and latitude are projected when first read, to the same values.

A plan lays out more layouts than it keeps (the plans compared), and the page re-plans on
every edit: the photo centres' lon/lat are projected from their planning-CRS x/y only when
something reads them. These tests check that what is read, copied or pickled equals the
eager projection, and that nothing is projected before it is read.
"""

from __future__ import annotations

import copy
import pickle
from pathlib import Path

import numpy as np
import pytest
from pyproj import Transformer

import scanplan
from scanplan.geo import crs as geocrs
from scanplan.geo.layout import PHOTO_COLUMNS, LonLatColumns

TOWN = Path(__file__).resolve().parents[1] / "examples" / "uav-town-2000.toml"


@pytest.fixture(scope="module")
def town_layout():
    return scanplan.plan(TOWN).spec.uav.layout


def _eager(layout) -> tuple[np.ndarray, np.ndarray]:
    """The lon/lat a fresh PROJ transformer gives for the layout's x/y."""
    tr = Transformer.from_crs(layout.area.plan_crs, 4326, always_xy=True)
    lon, lat = tr.transform(layout.photos["x_m"], layout.photos["y_m"])
    return np.asarray(lon, dtype=float), np.asarray(lat, dtype=float)


def test_lon_lat_read_equal_the_projection_of_x_and_y(town_layout):
    cols = town_layout.photos.columns
    assert isinstance(cols, LonLatColumns)
    assert list(cols) == list(PHOTO_COLUMNS)  # the order of every table and file
    lon, lat = _eager(town_layout)
    np.testing.assert_array_equal(cols["lon_deg"], lon)
    np.testing.assert_array_equal(town_layout.photos["lat_deg"], lat)
    assert 38.0 < float(np.mean(lon)) < 39.5 and 55.0 < float(np.mean(lat)) < 56.5  # the town


def test_nothing_is_projected_before_it_is_read(town_layout, monkeypatch):
    calls: list[object] = []
    real = geocrs.transformer
    monkeypatch.setattr(geocrs, "transformer", lambda *a: calls.append(a) or real(*a))
    cols = LonLatColumns({k: v for k, v in town_layout.photos.columns.items()
                          if k not in ("lon_deg", "lat_deg")}, town_layout.area.plan_crs)
    assert len(cols) == len(PHOTO_COLUMNS) and "lon_deg" in cols and not calls
    np.testing.assert_array_equal(cols["x_m"], town_layout.photos["x_m"])
    assert not calls
    lat = cols["lat_deg"]
    assert calls == [(town_layout.area.plan_crs, 4326)]
    assert cols["lat_deg"] is lat and cols["lon_deg"] is cols["lon_deg"]  # both kept
    assert len(calls) == 1


@pytest.mark.parametrize("copier", [dict, copy.copy, copy.deepcopy,
                                    lambda c: pickle.loads(pickle.dumps(c))])
def test_a_copy_or_a_pickle_holds_every_column_computed(town_layout, copier):
    fresh = LonLatColumns(dict(town_layout.photos.columns.items()), town_layout.area.plan_crs)
    held = copier(fresh)
    assert isinstance(held, dict) and list(held) == list(PHOTO_COLUMNS)
    lon, lat = _eager(town_layout)
    np.testing.assert_array_equal(held["lon_deg"], lon)
    np.testing.assert_array_equal(held["lat_deg"], lat)


def test_the_photo_table_and_a_local_frame_are_unchanged(town_layout):
    frame = scanplan.plan(TOWN).photos
    lon, lat = _eager(town_layout)
    np.testing.assert_array_equal(frame["lon_deg"].to_numpy(), lon)
    np.testing.assert_array_equal(frame["lat_deg"].to_numpy(), lat)
    block = scanplan.plan(Path(__file__).resolve().parents[1] / "examples"
                          / "uav-canon-2000.toml").spec.uav.layout
    assert not block.area.georeferenced  # a width × length block: no place on the map
    assert type(block.photos.columns) is dict and list(block.photos.columns) == list(PHOTO_COLUMNS)
    assert np.isnan(block.photos["lon_deg"]).all() and np.isnan(block.photos["lat_deg"]).all()
