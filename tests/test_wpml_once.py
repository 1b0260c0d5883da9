"""The DJI routes of a many-sortie plan are made from one set of sortie missions: routing
each sortie used to remake every sortie's mission (quadratic in the sorties; a 100 km²
block of 113 sorties spent 90 s there)."""

from __future__ import annotations

from layouts import make_layout

from scanplan.geo.export import MissionOptions
from scanplan.geo.export import wpml as wpml_mod
from scanplan.geo.mission import sortie_missions


def test_missions_made_once_and_routes_unchanged(monkeypatch):
    layout = make_layout(width_m=1200.0, length_m=600.0, sorties=4)
    options = MissionOptions(speed_ms=9.0)
    camera = next(iter(wpml_mod.DJI_CAMERAS))
    calls = []

    def counted(*args, **kwargs):
        calls.append(1)
        return sortie_missions(*args, **kwargs)

    monkeypatch.setattr(wpml_mod, "sortie_missions", counted)
    files, reason = wpml_mod.wpml_files(layout, options, camera)
    assert reason is None and len(files) == 4
    assert len(calls) == 1
    calls.clear()
    # each route is the one sortie_route makes on its own
    missions = sortie_missions(layout, options.speed_ms)
    for s in layout.sorties:
        assert (wpml_mod.sortie_route(layout, s.number, options, missions=missions)
                == wpml_mod.sortie_route(layout, s.number, options))
