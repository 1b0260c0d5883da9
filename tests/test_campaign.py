"""The hostile-input campaign: well over 1,000 hostile inputs per run, across every kind of
input scanplan takes, each delivered the way a user or a web page delivers it, each held
to the same rules:

* the command line answers 0 or 2 (never 1: a hostile input is an input error), the page's
  API 200, 403, 404 (an id that names nothing), 413, 415 or 422 (never 500), and never a
  traceback;
* nothing connects to the local listener every hostile URL and PROJ's CDN point at;
* an output folder holding a previous set and a user's file loses no byte;
* no temporary file or folder is left behind.

pytest's summary prints the count per input kind and the outcomes (conftest.py).

**Adding an input kind is one table entry** (docs/reliability.md, "The hostile-input
campaign"):

* a project-file key or section (``[uav] aircraft``, ``[control]``): nothing — every key of
  the input registry (:data:`scanplan.project.keys.KEYS`) gets the hostile values, in the
  project file and (``[project]`` keys) in the user configuration;
* a route of the page (its saved state, …): nothing — every route of the application gets
  the hostile JSON bodies and query strings; a route whose body is an uploaded file (a
  basemap) is one entry of :data:`UPLOAD_ROUTES`;
* a kind of file (a basemap format, a control-point list): one :class:`FileKind` in
  :data:`FILE_KINDS` — its suffix, the project key that names it, a small valid file and
  its own mutations (the generic ones — truncation, byte flips, hostile text — come free);
* an option of ``scan``/``uav``: nothing — every numeric and choice option of both
  commands is read from the commands.

``SCANPLAN_FUZZ=long`` delivers every combination instead of a seeded sample.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import random
import re
import socket
import tempfile
import threading
import zipfile
from collections import Counter
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.project.keys import KEYS

LONG = os.environ.get("SCANPLAN_FUZZ") == "long"
SEED = 20261128
COUNTS: Counter[str] = Counter()
"""Hostile inputs delivered, per input kind (printed by conftest.py)."""
OUTCOMES: Counter[str] = Counter()
"""Exit codes, HTTP statuses, tracebacks, connections, bytes lost, litter left."""

# --------------------------------------------------------------------------------------
# The hostile values
# --------------------------------------------------------------------------------------
URL = "http://127.0.0.1:{port}"
TEXTS = [
    "", " ", "\t\n", "x" * 100_000, "\x00", "a\x00b", "\x1b[31mred\x1b[0m", "\u202eexe.fdp",
    "\ufeffBOM", "\ud800", "\udfff lone", "😀" * 2000, "..", "../../../../etc/passwd",
    "/dev/zero", "/dev/stdin", "/proc/self/mem", "C:\\Windows\\win.ini", "\\\\srv\\share\\x",
    "~", "$HOME", "%APPDATA%", "{url}/x.kml", "file:///etc/passwd", "=HYPERLINK(\"{url}\")",
    "+1+1", "@SUM(1)", "-cmd", "<script>alert(1)</script>", "]]><x/>",
    "<!DOCTYPE x [<!ENTITY e SYSTEM \"{url}/e\">]>&e;", "%s%s%n", "{0}{1}",
    "\r\n[map]\nscale = 1", "NaN", "inf", "1e309", "٣٤", "0x10", "1_000", "null", "[]",
    "ё" * 70_000, "A" * 255, "A" * 4097,
]
"""Hostile text: control characters, lone surrogates, direction overrides, huge strings,
paths of devices and other folders, URLs of the listener, formulas, markup, format codes."""
LITERALS = [
    "nan", "inf", "-inf", "+inf", "-0.0", "0", "-1", "1e308", "1.7976931348623157e308",
    "5e-324", "9" * 5000, "99999999999999999999", "-9223372036854775809", "true", "[]",
    "[1, 2]", "[[1, 2], [3]]", "[" * 40 + "]" * 40, "{}", "{a = 1}", "1979-05-27",
    "0001-01-01", "9999-12-31", "1979-05-27T07:32:00Z", "07:32:00", '""', '"x"',
    '"' + "9" * 400 + '"', "0x7fffffffffffffff", "1_000", '"../.."', '"/dev/zero"',
    '"{url}/a.kml"', "[[37.6, 55.7], [37.6, 55.7], [37.6, 55.7]]",
    "[[1e308, 1e308], [-1e308, 1e308], [0, -1e308]]", '["nan", "inf"]',
]
"""Hostile TOML values for a key: every type, the edges of floats and integers, nesting
past the bound, dates at the ends of the calendar, paths and URLs."""
JSON_VALUES: list[Any] = [
    None, True, -0.0, 1e308, 10**400, -(10**30), [], {}, [[[]]], "x" * 100_000, "\x00",
    "../../etc/passwd", "{url}", [[37.6, 55.7]] * 3, {"$ref": "{url}"}, [1e308, -1e308],
    "1e400", "\u202e", ["a"] * 10_000,
]
"""Hostile JSON values for a key of a project sent to the API."""


def _fill(value: str, port: int) -> str:
    return value.replace("{url}", URL.format(port=port))


def _sample(items: list[Any], k: int, rng: random.Random) -> list[Any]:
    return list(items) if LONG or k >= len(items) else rng.sample(items, k)


# --------------------------------------------------------------------------------------
# The environment: a listener, a temporary folder of the campaign's own, the outcomes
# --------------------------------------------------------------------------------------
class Listener:
    """A TCP listener on 127.0.0.1 counting connections (every hostile URL points here,
    and PROJ's CDN)."""

    def __init__(self) -> None:
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(64)
        self.sock.settimeout(0.2)
        self.port = self.sock.getsockname()[1]
        self.connections = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self) -> None:
        while not self._stop.is_set():
            try:
                conn, _ = self.sock.accept()
            except OSError:
                continue
            self.connections += 1
            conn.close()

    def close(self) -> None:
        self._stop.set()
        self._thread.join(5)
        self.sock.close()


@dataclass
class Env:
    """What a channel delivers into."""

    tmp: Path
    port: int
    violations: list[str] = field(default_factory=list)
    client: Any = None


@pytest.fixture
def env(tmp_path, monkeypatch):
    listener = Listener()
    scratch = tmp_path / "temporary"
    scratch.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(scratch))  # every run's folder in here
    monkeypatch.setenv("PROJ_NETWORK", "ON")
    monkeypatch.setenv("PROJ_NETWORK_ENDPOINT", URL.format(port=listener.port))
    monkeypatch.setenv("SCANPLAN_NO_FORK", "1")
    monkeypatch.chdir(tmp_path)
    e = Env(tmp_path / "work", listener.port)
    e.tmp.mkdir()
    yield e
    listener.close()
    from scanplan.io import rundir

    rundir.remove()  # a library user's run folder (the page's uploads): removed at exit
    OUTCOMES["connections"] += listener.connections
    litter = [p for p in scratch.rglob("*")]
    OUTCOMES["litter left"] += len(litter)
    assert listener.connections == 0, "a hostile input made a connection"
    assert litter == [], litter[:5]
    assert e.violations == [], "\n".join(e.violations[:20])


def _cli(env: Env, kind: str, what: str, args: list[str], **kw: Any) -> int:
    """Run a command; a violation is any exit but 0 and 2, or a traceback."""
    COUNTS[kind] += 1
    r = CliRunner().invoke(main, args, **kw)
    out = r.output + (r.stderr or "")
    OUTCOMES[f"exit {r.exit_code}"] += 1
    bad = r.exit_code not in (0, 2) or "Traceback" in out or not (
        r.exception is None or isinstance(r.exception, SystemExit))
    if "Traceback" in out or not (r.exception is None or isinstance(r.exception, SystemExit)):
        OUTCOMES["tracebacks"] += 1
    if bad:
        env.violations.append(f"{kind}: {what[:120]!r}: exit {r.exit_code}: "
                              f"{out.strip()[-300:]!r} {r.exception!r}")
    return r.exit_code


# --------------------------------------------------------------------------------------
# The project file and the user configuration: every key of the registry
# --------------------------------------------------------------------------------------
BASE: dict[str, dict[str, str]] = {
    "project": {"name": '"Hostile"'},
    "map": {"scale": "2000", "relief_interval_m": "0.5"},
    "uav": {"camera": '"dji-zenmuse-p1-35"', "height_m": "100"},
    "area": {"width_m": "300", "length_m": "300"},
}


def project_text(overrides: dict[tuple[str, str], str]) -> str:
    """The base project with ``(section, key) → TOML value`` set (sections added); an
    area given as a file or a polygon replaces the base's block (one area a project)."""
    doc = {s: dict(t) for s, t in BASE.items()}
    if {("area", "file"), ("area", "polygon")} & set(overrides):
        doc["area"] = {}
    for (section, key), value in overrides.items():
        doc.setdefault(section, {})[key] = value
    return "".join(f"[{s}]\n" + "".join(f"{k} = {v}\n" for k, v in t.items())
                   for s, t in doc.items())


def toml_string(text: str) -> str:
    """A TOML basic string of ``text`` (a lone surrogate kept as its escape: an invalid
    file, as a hand-edited one can be)."""
    out = json.dumps(text, ensure_ascii=True)
    return re.sub(r"\\u00([01][0-9a-f])", r"\\u00\1", out)


def _write(path: Path, text: str) -> Path:
    path.write_bytes(text.encode("utf-8", "surrogatepass"))
    return path


def project_cases(rng: random.Random) -> list[tuple[tuple[str, str], str]]:
    cases = []
    per_key = 5
    for section, keys in KEYS.items():
        for key, (kind, _) in keys.items():
            values = _sample(LITERALS, per_key, rng)
            if kind in ("str", "crs", "feature", "direction", "date"):
                values += [toml_string(t) for t in _sample(TEXTS, 3, rng)]
            cases += [((section, key), v) for v in values]
    return cases


def test_every_key_of_the_project_file(env):
    rng = random.Random(SEED)
    for (section, key), value in project_cases(rng):
        value = _fill(value, env.port)
        p = _write(env.tmp / "p.toml", project_text({(section, key): value}))
        _cli(env, "project file key", f"{section}.{key} = {value}", ["plan", str(p)])


def test_every_key_of_the_user_configuration(env, monkeypatch):
    rng = random.Random(SEED + 1)
    config = env.tmp / "config.toml"
    monkeypatch.setenv("SCANPLAN_CONFIG", str(config))
    p = _write(env.tmp / "p.toml", project_text({}))
    values = LITERALS + [toml_string(t) for t in TEXTS]
    for key in KEYS["project"]:
        for value in _sample(values, 6, rng):
            value = _fill(value, env.port)
            _write(config, f"[project]\n{key} = {value}\n")
            _cli(env, "user configuration key", f"{key} = {value}", ["plan", str(p)])
    for text in ("[project]\n" + "a = " + "[" * 5000 + "]" * 5000, "\x00" * 100,
                 "[project]\n[project]\n", "[other]\nx = 1\n", "[project\n"):
        _write(config, text)
        _cli(env, "user configuration key", text[:40], ["plan", str(p)])


def test_the_output_folder_loses_nothing(env):
    """Hostile projects written with --out into a folder holding a previous set and a
    user's own file: refused ones change no byte of what a reader sees."""
    out = env.tmp / "out"
    good = _write(env.tmp / "good.toml", project_text({}))
    assert _cli(env, "--out over a previous set", "good", ["plan", str(good), "--out",
                                                              str(out), "--formats", "xlsx"]) == 0
    (out / "notes.txt").write_bytes(b"the user's own notes")

    def seen() -> dict[str, bytes]:
        files = {}
        for p in out.iterdir():
            if not p.name.startswith("."):
                with contextlib.suppress(OSError):
                    files[p.name] = p.read_bytes()
        return files

    before = seen()
    rng = random.Random(SEED + 2)
    for (section, key), value in _sample(project_cases(rng), 25, rng):
        p = _write(env.tmp / "h.toml", project_text({(section, key): _fill(value, env.port)}))
        code = _cli(env, "--out over a previous set", f"{section}.{key} = {value}",
                    ["plan", str(p), "--out", str(out), "--formats", "xlsx"])
        now = seen()
        if code != 0:
            lost = sum(len(d) for n, d in before.items() if now.get(n) != d)
            OUTCOMES["bytes lost"] += lost
            if lost:
                env.violations.append(f"{section}.{key} = {value}: {lost} bytes lost")
        if now.get("notes.txt") != b"the user's own notes":
            OUTCOMES["bytes lost"] += len(b"the user's own notes")
            env.violations.append("the user's own file changed")
        before = now


# --------------------------------------------------------------------------------------
# The options of scan and uav
# --------------------------------------------------------------------------------------
OPTION_VALUES = ["nan", "inf", "-inf", "-1", "0", "1e309", "1e-320", "", " ", "٣", "0x10",
                 "1_0", "-", "1,5", "1.5.5", "9" * 5000, "\x1b[2J", "1:0", "1:-5", "--help"]
REQUIRED = {"scan": ["--map-scale", "2000", "--relief", "0.5", "--camera", "rc30-153",
                     "--photo-scale", "10000"],
            "uav": ["--camera", "dji-zenmuse-p1-35", "--height-m", "100"]}


def test_every_option_of_scan_and_uav(env):
    import click

    rng = random.Random(SEED + 3)
    for command, required in REQUIRED.items():
        for param in main.commands[command].params:
            if not isinstance(param, click.Option) or param.is_flag or \
                    param.name in ("xlsx_path", "pdf_path"):
                continue
            name = max(param.opts, key=len)
            for value in _sample(OPTION_VALUES, 3, rng):
                _cli(env, "scan/uav option", f"{command} {name} {value}",
                     [command, *required, name, value])


def test_every_argument_of_the_aircraft_catalogue(env):
    """``aircraft show ID`` and ``aircraft list --camera ID``: any text is a name that is
    found or refused (exit 2), in both languages and as JSON."""
    rng = random.Random(SEED + 6)
    for text in [*_sample(TEXTS, 16, rng), "dji-m350-rtk", "DJI-M350-RTK", "-"]:
        text = _fill(text, env.port)
        for args in (["show", text], ["show", text, "--json", "--locale", "ru"],
                     ["list", "--camera", text], ["list", "--camera", text, "--json"]):
            _cli(env, "aircraft argument", " ".join(args), ["aircraft", *args])


# --------------------------------------------------------------------------------------
# Files: areas, vertex lists, DEMs — one FileKind per kind
# --------------------------------------------------------------------------------------
RING = [[37.600, 55.750], [37.606, 55.750], [37.606, 55.754], [37.600, 55.754],
        [37.600, 55.750]]


def _kml(name: str = "Town", coords: str | None = None, head: str = "") -> bytes:
    coords = coords or " ".join(f"{x},{y},0" for x, y in RING)
    return (f'<?xml version="1.0" encoding="UTF-8"?>{head}<kml xmlns="http://www.opengis.net'
            f'/kml/2.2"><Document><Placemark><name>{name}</name><Polygon><outerBoundaryIs>'
            f"<LinearRing><coordinates>{coords}</coordinates></LinearRing></outerBoundaryIs>"
            "</Polygon></Placemark></Document></kml>").encode("utf-8", "surrogatepass")


def _geojson(ring: Any = None, name: Any = "Town", extra: str = "") -> bytes:
    feature = {"type": "Feature", "properties": {"name": name},
               "geometry": {"type": "Polygon", "coordinates": [ring or RING]}}
    text = json.dumps({"type": "FeatureCollection", "features": [feature]})
    return (text[:-1] + extra + "}").encode("utf-8", "surrogatepass")


def _csv(rows: Iterable[str]) -> bytes:
    return ("\n".join(rows) + "\n").encode("utf-8", "surrogatepass")


def _zip(members: dict[str, bytes]) -> bytes:
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as zf:
        for name, data in members.items():
            zf.writestr(name, data)
    return buf.getvalue()


def _dem() -> bytes:
    import numpy as np
    import rasterio
    from rasterio.transform import from_origin

    buf = io.BytesIO()
    with rasterio.MemoryFile() as mem:
        with mem.open(driver="GTiff", width=40, height=40, count=1, dtype="float32",
                      crs="EPSG:4326", transform=from_origin(37.59, 55.76, 0.0005, 0.0005)
                      ) as ds:
            ds.write(np.full((1, 40, 40), 150.0, dtype="float32"))
        buf.write(mem.read())
    return buf.getvalue()


def _orthophoto() -> bytes:
    """An RGB GeoTIFF over the area (a background of the PDF's map page)."""
    import numpy as np
    import rasterio
    from rasterio.transform import from_origin

    buf = io.BytesIO()
    with rasterio.MemoryFile() as mem:
        with mem.open(driver="GTiff", width=40, height=40, count=3, dtype="uint8",
                      crs="EPSG:4326", transform=from_origin(37.59, 55.76, 0.0005, 0.0005)
                      ) as ds:
            ds.write(np.arange(3 * 40 * 40, dtype="uint32").reshape(3, 40, 40)
                     .astype("uint8"))
        buf.write(mem.read())
    return buf.getvalue()


def _png(width: int = 256, height: int = 256) -> bytes:
    from PIL import Image

    buf = io.BytesIO()
    Image.new("RGB", (width, height), (40, 120, 40)).save(buf, "PNG")
    return buf.getvalue()


def _png_claiming(width: int, height: int) -> bytes:
    """A tiny PNG whose header claims ``width`` × ``height`` pixels (a decompression bomb's
    header; its CRC made right so a reader believes it)."""
    import struct
    import zlib

    data = bytearray(_png(1, 1))
    ihdr = struct.pack(">II", width, height) + bytes(data[24:29])
    data[16:29] = ihdr
    data[29:33] = struct.pack(">I", zlib.crc32(b"IHDR" + ihdr))
    return bytes(data)


def _mbtiles(rows: Iterable[tuple[Any, Any, Any, Any]] | None = None,
             metadata: Iterable[tuple[str, str]] | None = (("name", "t"),),
             schema: str | None = None) -> bytes:
    """An MBTiles file (SQLite) of ``rows`` (zoom, column, TMS row, data); default one
    tile at zoom 14 over the area."""
    import sqlite3

    if rows is None:  # the tile of the area's corner at zoom 14: x 9903, y 5122
        rows = [(14, 9903, 2 ** 14 - 1 - 5122, _png())]
    with tempfile.TemporaryDirectory(dir=Path.cwd()) as folder:
        path = Path(folder) / "t.mbtiles"
        db = sqlite3.connect(path)
        db.executescript(schema if schema is not None else
                         "CREATE TABLE metadata (name TEXT, value TEXT);"
                         "CREATE TABLE tiles (zoom_level INTEGER, tile_column INTEGER, "
                         "tile_row INTEGER, tile_data BLOB);")
        if metadata is not None:
            db.executemany("INSERT INTO metadata VALUES (?, ?)", list(metadata))
        if rows := list(rows):
            db.executemany("INSERT INTO tiles VALUES (?, ?, ?, ?)", rows)
        db.commit()
        db.close()
        return path.read_bytes()


def _mbtiles_mutations(port: int) -> list[bytes]:
    corner = (9903, 2 ** 14 - 1 - 5122)
    return [
        _mbtiles(schema="CREATE TABLE tiles (zoom_level, tile_column, tile_row, tile_data);",
                 metadata=None),  # no metadata table
        _mbtiles(schema="CREATE TABLE other (x);", metadata=None, rows=[]),  # no tiles
        _mbtiles(rows=[]),
        _mbtiles(rows=[(14, *corner, b"\x89PNG\r\n\x1a\n" + b"\x00" * 40)]),
        _mbtiles(rows=[(14, *corner, _png_claiming(100_000, 100_000))]),  # a bomb's header
        _mbtiles(rows=[(14, *corner, _png_claiming(12_000, 12_000))]),
        _mbtiles(rows=[(14, *corner, f"{URL.format(port=port)}/tile.png".encode())]),
        _mbtiles(rows=[("x", *corner, _png())]), _mbtiles(rows=[(None, None, None, None)]),
        _mbtiles(rows=[(99, 0, 0, _png())]), _mbtiles(rows=[(-3, -1, -1, _png())]),
        _mbtiles(rows=[(14, 2 ** 62, 2 ** 62, _png())]),
        _mbtiles(rows=[(z, 0, 0, _png()) for z in range(0, 30)]),
        _mbtiles(metadata=[("bounds", "nan,nan,inf,inf"), ("name", "\x00\x1b[2J" * 100)]),
    ]


@dataclass(frozen=True)
class FileKind:
    """A kind of file scanplan reads: its suffix, the project key that names it, a small
    valid file and mutations of its own (the generic ones are added to every kind);
    ``formats``: the outputs written (``plan --out DIR --formats``) when the file is read
    only then (a background of the PDF's map page), else the plan only."""

    name: str
    suffix: str
    key: tuple[str, str]
    valid: Callable[[], bytes]
    mutations: Callable[[int], list[bytes]]
    extra: dict[tuple[str, str], str] = field(default_factory=dict)
    formats: str | None = None


FILE_KINDS = [
    FileKind("KML area", ".kml", ("area", "file"), _kml, lambda port: [
        _kml(head=f'<!DOCTYPE kml [<!ENTITY e SYSTEM "{URL.format(port=port)}/e">]>',
             name="&e;"),
        _kml(coords="nan,nan,0 inf,1,0 1e400,2,0"), _kml(coords="1," * 10_000),
        _kml(coords=" ".join(f"{37.6 + i * 1e-7},{55.75},0" for i in range(3))),
        _kml(name="<![CDATA[" + "\ud800" * 3 + "]]>"),
        b"<kml>" + b"<Folder>" * 3000 + b"</Folder>" * 3000 + b"</kml>",
        _kml().replace(b"<Document>", f'<Document><NetworkLink><Link><href>{URL.format(port=port)}'
                                      f'/n.kml</href></Link></NetworkLink>'.encode()),
        b'<?xml version="1.0"?><!DOCTYPE kml [' + b'<!ENTITY a "aaaaaaaaaa">' * 50 + b"]><kml/>",
        _kml().replace(b"<Document>", b'<Document><xi:include xmlns:xi="http://www.w3.org/2001'
                                      b'/XInclude" href="/etc/passwd" parse="text"/>')]),
    FileKind("GeoJSON area", ".geojson", ("area", "file"), _geojson, lambda port: [
        _geojson(extra=f', "crs": {{"type": "link", "properties": {{"href": '
                       f'"{URL.format(port=port)}/crs"}}}}'),
        _geojson(ring=[[float("nan"), 1], [2, 3], [4, 5], [float("nan"), 1]]),
        b'{"type": "FeatureCollection", "features": [' + b"[" * 100_000 + b"]" * 100_000 + b"]}",
        _geojson(ring=[[1e308, 1e308], [-1e308, 1e308], [0, -1e308], [1e308, 1e308]]),
        _geojson(ring=[["37.6", "55.75"], ["a", "b"], [None, None], ["37.6", "55.75"]]),
        _geojson(name="\ud800" * 10), _geojson(name="x" * 1_000_000),
        b'{"type": "Topology", "objects": {}}', b'{"type": "GeometryCollection"}']),
    FileKind("vertex list", ".csv", ("area", "file"),
             lambda: _csv([f"{x};{y}" for x, y in RING]), lambda port: [
        _csv(["lon;lat"]), _csv(["lon;lat;lon", "1;2;3"]), _csv(["x;y", "nan;nan", "inf;1",
                                                             "1;2"]),
        _csv(["lon,lat", "37,6;55,7", "1e400,1"]), _csv(["\ufefflon;lat", "\x00;\x00"]),
        _csv([f"{37.6 + i * 1e-6};55.75" for i in range(200_000)]),
        _csv(["долгота;широта", "37,6;55,75", "37,7;55,75", "37,7;55,8"]),
        _csv(["id;WKT", "1;POLYGON EMPTY", "2;GEOMETRYCOLLECTION(POINT(1 2))"]),
        _csv(["id;WKT", "1;POLYGON((0 0, 1e400 0, 1 1, 0 0))", "2;" + "(" * 10_000]),
        _csv(["id;WKT", '1;"POLYGON((37.6 55.75, 37.61 55.75, 37.61 55.76, 37.6 55.75))'])]),
    FileKind("KMZ area", ".kmz", ("area", "file"), lambda: _zip({"doc.kml": _kml()}),
             lambda port: [
        _zip({"../../evil.kml": _kml()}), _zip({"doc.kml": _zip({"doc.kml": _kml()})}),
        _zip({"doc.kml": b"<kml>" + b" " * 8_000_000 + b"</kml>"}), _zip({}),
        _zip({f"{i}.kml": _kml() for i in range(300)}), b"PK\x03\x04" + b"\x00" * 100]),
    FileKind("DEM", ".tif", ("terrain", "dem"), _dem, lambda port: [
        b"II*\x00" + b"\xff" * 200, b"MM\x00*" + b"\x00" * 8, b"II+\x00" + b"\x00" * 12],
        extra={("area", "polygon"): str([[x, y] for x, y in RING])}),
    FileKind("GeoTIFF background", ".tif", ("map", "basemap"), _orthophoto, lambda port: [
        b"II*\x00" + b"\xff" * 200, _dem()],
        extra={("area", "polygon"): str([[x, y] for x, y in RING])}, formats="pdf"),
    FileKind("MBTiles background", ".mbtiles", ("map", "basemap"), _mbtiles,
             _mbtiles_mutations, extra={("area", "polygon"): str([[x, y] for x, y in RING])},
             formats="pdf"),
]
"""The kinds of file scanplan reads, each with hostile variants (docstring at the top:
one entry per new kind)."""


def _generic(valid: bytes, rng: random.Random) -> list[bytes]:
    """Mutations of any file: truncations, flipped bytes, noise, an empty file."""
    out = [b"", valid[: len(valid) // 2], valid[:1], valid + b"\x00" * 64, bytes(range(256))]
    for _ in range(6):
        data = bytearray(valid)
        for _ in range(rng.randint(1, 8)):
            data[rng.randrange(len(data))] = rng.randrange(256)
        out.append(bytes(data))
    return out


@pytest.mark.parametrize("kind", FILE_KINDS, ids=[k.name for k in FILE_KINDS])
def test_every_kind_of_file(env, kind):
    rng = random.Random(f"{SEED}{kind.name}")
    valid = kind.valid()
    generic = _generic(valid, rng)
    if kind.formats:  # each file read makes a document: the generic shapes, not the flips
        generic = generic[:5]
    variants = [valid, *kind.mutations(env.port), *generic]
    name = f"input{kind.suffix}"
    for data in variants:
        (env.tmp / name).write_bytes(data)
        p = _write(env.tmp / "f.toml", project_text({kind.key: json.dumps(name),
                                                      **kind.extra}))
        out = ["--out", str(env.tmp / "out"), "--formats", kind.formats] if kind.formats \
            else []
        _cli(env, f"file: {kind.name}", f"{name}: {data[:60]!r}", ["plan", str(p), *out])


# --------------------------------------------------------------------------------------
# The page's API: every route, read from the application
# --------------------------------------------------------------------------------------
UPLOAD_ROUTES = {"/api/upload": "name"}
"""Routes whose body is an uploaded file → the query parameter naming it."""
OK_STATUSES = {200, 403, 404, 413, 415, 422}
"""Clean answers; 404: a route naming an upload or a tile by id, and no such one."""


@pytest.fixture
def client(env):
    from fastapi.testclient import TestClient

    from scanplan.web.app import create_app
    from scanplan.web.uploads import UploadStore
    from scanplan.web.worker import Planner

    with TestClient(create_app(planner=Planner(inline=True), uploads=UploadStore(),
                               tiles="none"), base_url="http://127.0.0.1:8765",
                    raise_server_exceptions=False) as c:
        yield c


def _http(env: Env, kind: str, what: str, r: Any) -> None:
    COUNTS[kind] += 1
    OUTCOMES[f"http {r.status_code}"] += 1
    ok = r.status_code in OK_STATUSES
    if r.status_code != 200 or r.headers.get("content-type", "").startswith("application/json"):
        try:
            r.json()
        except ValueError:
            ok = False
    if not ok or "Traceback" in r.text:
        OUTCOMES["tracebacks" if "Traceback" in r.text else "http failures"] += 1
        env.violations.append(f"{kind}: {what[:120]}: {r.status_code} {r.text[:300]!r}")


def _routes(app: Any) -> list[tuple[str, str]]:
    from starlette.routing import Mount

    out = []
    for route in app.routes:
        if isinstance(route, Mount):
            continue
        for method in sorted(getattr(route, "methods", None) or ()):
            if method in ("GET", "POST"):
                out.append((method, re.sub(r"\{[^}]+\}", "pdf", route.path)))
    return out


def json_bodies(port: int, rng: random.Random) -> list[bytes]:
    """Hostile JSON requests: shapes, values at every key of the registry, files maps."""
    bodies: list[Any] = [[], "x", 1, None, {"project": None}, {"project": []},
                         {"project": {"map": []}}, {"project": {"map": {"scale": {}}}},
                         {"project": {str(i): {} for i in range(5000)}},
                         {"project": {"map": {"scale": 2000}}, "files": {"../../x": "0" * 16}},
                         {"project": {"area": {"file": "a.kml"}}, "files": {"a.kml": 7}},
                         {"project": {"area": {"file": "/etc/passwd"}}, "files": {}},
                         {"project": {"norms": {"set": "/"}}}]
    base = {s: {k: json.loads(v) if not v.startswith('"') else v.strip('"')
                for k, v in t.items()} for s, t in BASE.items()}
    for section, keys in KEYS.items():
        for key in keys:
            for value in _sample(JSON_VALUES, 2, rng):
                doc = json.loads(json.dumps(base))
                doc.setdefault(section, {})[key] = json.loads(_fill(json.dumps(value), port))
                bodies.append({"project": doc})
    raw = [json.dumps(b).encode() for b in bodies]
    raw += [b'{"project": {"project": {"name": "\\ud800"}}}', b"[" * 50 + b"]" * 50,
            b'{"project": ' + b"[" * 5000 + b"]" * 5000 + b"}", b'{"a": 1e400}',
            b"\xff\xfe{}", b'{"project": {}}' + b" " * 100, b"{" * 10]
    return raw


def test_every_route_of_the_page(env, client):
    rng = random.Random(SEED + 4)
    bodies = json_bodies(env.port, rng)
    for method, path in _routes(client.app):
        if method == "GET":
            for value in _sample([t for t in TEXTS if len(t) < 4000], 12, rng):
                value = _fill(value, env.port)
                try:
                    r = client.get(path, params={"lang": value, "norms": value})
                except (UnicodeEncodeError, ValueError):  # not sendable in a URL
                    continue
                _http(env, "page API: query", f"{path}?{value[:40]}", r)
            continue
        if path in UPLOAD_ROUTES:
            continue
        # every body to the plan; the view (maps, charts) and the downloads (documents)
        # take longer: a sample
        chosen = bodies if path == "/api/plan" else _sample(bodies, 40 if LONG else 15, rng)
        for body in chosen:
            r = client.post(path, content=body, headers={"Content-Type": "application/json"})
            _http(env, "page API: JSON body", f"{path} {body[:80]!r}", r)


def test_every_upload_route_and_the_plan_of_its_file(env, client):
    rng = random.Random(SEED + 5)
    kinds = {k.suffix: k for k in FILE_KINDS}
    for path, param in UPLOAD_ROUTES.items():
        names = [t for t in TEXTS if len(t) < 4000]  # longer: no client sends such a URL
        for name in [*_sample(names, 8, rng), "a.kml", "a.geojson", "a.csv", "a.kmz"]:
            name = _fill(name, env.port)
            suffix = Path(name).suffix if Path(name).suffix in kinds else ".kml"
            kind = kinds[suffix]
            for data in [kind.valid(), *kind.mutations(env.port)[:3]]:
                try:
                    r = client.post(path, params={param: name}, content=data,
                                    headers={"Content-Type": "application/octet-stream"})
                except (UnicodeEncodeError, ValueError):  # not sendable in a URL
                    continue
                _http(env, "page API: upload", f"{path} {name[:40]!r}", r)
                if r.status_code != 200:
                    continue
                up = r.json()
                req = {"project": {"map": {"scale": 2000, "relief_interval_m": 0.5},
                                   "uav": {"camera": "dji-zenmuse-p1-35", "height_m": 100},
                                   "area": {"file": up["name"]}},
                       "files": {up["name"]: up["id"]}}
                _http(env, "page API: plan of an upload", up["name"],
                      client.post("/api/plan", json=req))
