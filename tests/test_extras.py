"""The optional parts of the install (scanplan/extras.py): a DEM needs the 'terrain'
extra, the web page the 'serve' extra; without them the feature stops with exit code 2
naming the key or command, the extra and the pip command; the test extra brings both."""

from __future__ import annotations

import re
import sys
import tomllib
from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan import extras
from scanplan.cli.main import main
from scanplan.errors import InputError

ROOT = Path(__file__).resolve().parent.parent
VALLEY = ROOT / "examples" / "uav-town-valley-2000.toml"  # a DEM
FLAT = ROOT / "examples" / "uav-town-2000.toml"  # a KML polygon, no DEM


class _Blocker:
    """A finder first on the import path that makes packages look not installed."""

    def __init__(self, names: tuple[str, ...]) -> None:
        self.names = names

    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in self.names:
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
        return None


def _uninstall(monkeypatch, *names: str) -> None:
    """As if ``names`` were not installed: not imported, and not importable."""
    for key in list(sys.modules):
        if key.split(".")[0] in names:
            monkeypatch.delitem(sys.modules, key)
    monkeypatch.setattr(sys, "meta_path", [_Blocker(names), *sys.meta_path])


def _name(requirement: str) -> str:
    return re.split(r"[<>=\[ ;]", requirement, maxsplit=1)[0].lower()


def test_pyproject_extras_are_the_modules_checked():
    meta = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    optional = meta["optional-dependencies"]
    core = {_name(r) for r in meta["dependencies"]}
    for extra, modules in extras.EXTRAS.items():
        assert {_name(r) for r in optional[extra]} == set(modules.values())
        assert not core & set(modules.values())  # not brought by the plain install anyway
    assert "scanplan[terrain,serve]" in optional["test"]  # the tests need every feature
    assert extras.missing("terrain") == [] and extras.missing("serve") == []


def test_require_names_the_field_extra_and_pip_command(monkeypatch):
    _uninstall(monkeypatch, "scipy")
    with pytest.raises(InputError) as err:
        extras.require("terrain", "terrain.dem", "a DEM")
    assert err.value.field == "terrain.dem"
    assert "scipy not installed" in err.value.message and "rasterio" not in err.value.message
    assert 'pip install "scanplan[terrain]"' in err.value.message


def test_a_dem_without_the_terrain_extra_exits_2(monkeypatch):
    _uninstall(monkeypatch, "rasterio")
    r = CliRunner().invoke(main, ["plan", str(VALLEY), "--json"])
    assert r.exit_code == 2, r.output
    assert "terrain.dem" in r.stderr and "'terrain'" in r.stderr and "rasterio" in r.stderr
    assert 'pip install "scanplan[terrain]"' in r.stderr and "Traceback" not in r.output
    flat = CliRunner().invoke(main, ["plan", str(FLAT), "--json"])  # no DEM: no extra needed
    assert flat.exit_code == 0, flat.output


def test_serve_without_its_extra_exits_2(monkeypatch):
    _uninstall(monkeypatch, "uvicorn")
    r = CliRunner().invoke(main, ["serve", "--port", "0"])
    assert r.exit_code == 2, r.output
    assert "scanplan serve" in r.stderr and "uvicorn not installed" in r.stderr
    assert 'pip install "scanplan[serve]"' in r.stderr
