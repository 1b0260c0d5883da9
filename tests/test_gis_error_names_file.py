"""A GIS file GDAL cannot parse is named in the error as the user gave it, never by the
in-memory path (``/vsimem/pyogrio_…``) it was handed to GDAL under."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.errors import InputError
from scanplan.geo.area import AreaSpec, load_area


@pytest.mark.parametrize(("name", "data"), [
    ("junk.kml", b"<kml>garbage"),
    ("junk.geojson", b'{"type": "FeatureCollection", "features": ['),
])
def test_an_unparsable_area_file_is_named_not_gdals_memory_path(tmp_path, name, data):
    path = tmp_path / name
    path.write_bytes(data)
    with pytest.raises(InputError) as err:
        load_area(AreaSpec(file=path))
    said = f"{err.value.field}: {err.value.message}"
    assert "vsimem" not in said and "pyogrio" not in said
    assert str(path) in err.value.field
    assert "cannot be read as a GIS file" in err.value.message


def test_the_plan_command_shows_the_users_kml_name(tmp_path):
    (tmp_path / "site.kml").write_bytes(b"<kml>garbage")
    project = tmp_path / "p.toml"
    project.write_text('[map]\nscale = 2000\nrelief_interval_m = 1\n[uav]\n'
                       'camera = "dji-zenmuse-p1-35"\n[area]\nfile = "site.kml"\n',
                       encoding="utf-8")
    result = CliRunner().invoke(main, ["plan", str(project)])
    assert result.exit_code == 2, result.output
    assert "site.kml" in result.output and "vsimem" not in result.output
    assert "Traceback" not in result.output
