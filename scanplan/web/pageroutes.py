"""The routes the page needs beside the plan: an upload still kept, a project file or the
page's zip opened again, the outline of an area before it can be planned.

- ``GET /api/upload/{id}`` — the upload's ``id``, stored ``name`` and ``size`` (404 when the
  store no longer keeps it): a reloaded page checks the files it had;
- ``POST /api/open`` — ``{"id": upload id}`` of a project file (``.toml``) or of the zip
  *Everything* downloads: the project as the tables the page sends (``project``), the files
  it names that the zip held, stored as uploads (``files``: name → ``{id, name}``), and the
  ones still to be uploaded (``missing``). Only the project file and the files it names are
  read from a zip, each within the upload store's bounds;
- ``POST /api/area`` — the outline of the request's ``[area]`` (GeoJSON, WGS 84): a
  dropped file is drawn before a camera is chosen;
- ``GET /api/tiles/{source}/{z}/{x}/{y}`` — a tile of a source the server was configured
  with (:mod:`scanplan.web.basemap`);
- ``GET /api/basemap/{id}`` and ``…/image.png`` — an uploaded GeoTIFF warped to Web
  Mercator: its bounds and size, and the picture.

Each is safe by construction: a client names an upload only by the id the store gave, a
zip member only by the names a project may use (:func:`scanplan.web.jobs._file_name`).
"""

from __future__ import annotations

import datetime as dt
import tomllib
import zipfile
from pathlib import Path
from typing import Any

from fastapi import FastAPI, HTTPException
from fastapi.responses import FileResponse, Response
from pydantic import BaseModel, Field

from ..errors import InputError
from .basemap import Basemaps
from .uploads import UploadStore
from .worker import Planner

__all__ = ["MAX_PROJECT_BYTES", "MAX_ZIP_MEMBERS", "AreaRequest", "OpenRequest", "open_project",
           "page_routes", "project_tables_of"]

MAX_PROJECT_BYTES = 1024 * 1024
"""Largest project file opened [bytes] (a polygon of ~20,000 typed vertices)."""
MAX_ZIP_MEMBERS = 10_000
"""Most entries of a zip looked through for the project file and its files."""


class AreaRequest(BaseModel):
    """A project's tables (only ``[area]`` is read) and the uploads it names."""

    project: dict[str, Any] = Field(description="section → {key: value}, as /api/plan")
    files: dict[str, str] = Field(default_factory=dict, description="file name → upload id")


class OpenRequest(BaseModel):
    """A project file or zip already uploaded."""

    id: str = Field(description="the id /api/upload answered for the file")


def _plain(value: Any) -> Any:
    """A TOML value as JSON: a date as its ISO text (the page sends it back so)."""
    if isinstance(value, dt.date | dt.datetime | dt.time):
        return value.isoformat()
    if isinstance(value, list):
        return [_plain(v) for v in value]
    return value


def project_tables_of(text: str, name: str = "project.toml") -> dict[str, dict[str, Any]]:
    """The tables of a project file as the page sends them: ``{section: {key: value}}``,
    dotted sections flat (``"uav.target"``), dates as ISO text.

    >>> project_tables_of('[map]\\nscale = 2000\\n[uav.target]\\nr_max = 0.3\\n')
    {'map': {'scale': 2000}, 'uav.target': {'r_max': 0.3}}

    Raises
    ------
    InputError
        ``name`` when the text is not TOML.
    """
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(name, f"is not valid TOML: {exc}") from None
    tables: dict[str, dict[str, Any]] = {}

    def walk(prefix: str, table: dict[str, Any]) -> None:
        own = {}
        for k, v in table.items():
            if isinstance(v, dict):
                walk(f"{prefix}.{k}" if prefix else k, v)
            else:
                own[k] = _plain(v)
        if prefix and own:
            tables[prefix] = own
        elif not prefix and own:
            raise InputError(name, f"has keys outside a section ({', '.join(own)}); a "
                             "project file's keys are in sections such as [map]")

    walk("", doc)
    return tables


def _text(data: bytes, name: str) -> str:
    if len(data) > MAX_PROJECT_BYTES:
        raise InputError(name, f"is larger than {MAX_PROJECT_BYTES:,} bytes, the largest "
                         "project file the page opens")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(name, f"is not UTF-8 text (byte {exc.start:,}); save it as UTF-8"
                         ) from None


def open_project(store: UploadStore, upload_id: str) -> dict[str, Any]:
    """What ``POST /api/open`` answers for the upload ``upload_id`` (see the module)."""
    from .jobs import FILE_KEYS, PROJECT_NAME, _file_name

    path = store.path(upload_id, "file")
    named = {}
    if zipfile.is_zipfile(path):
        with zipfile.ZipFile(path) as zf:
            infos = zf.infolist()[:MAX_ZIP_MEMBERS]
            members = {i.filename: i for i in infos if not i.is_dir()}
            if PROJECT_NAME not in members:
                raise InputError(path.name, f"holds no {PROJECT_NAME} (the zip the page "
                                 "downloads has it at its top)")
            info = members[PROJECT_NAME]
            if info.file_size > MAX_PROJECT_BYTES:
                _text(b" " * (MAX_PROJECT_BYTES + 1), PROJECT_NAME)
            tables = project_tables_of(_text(zf.read(info), PROJECT_NAME), PROJECT_NAME)
            for section, key in FILE_KEYS:
                value = tables.get(section, {}).get(key)
                if not isinstance(value, str):
                    continue
                name = _file_name(value, f"{PROJECT_NAME}: {section}.{key}")
                member = members.get(name)
                if member is None:
                    continue
                if member.file_size > store.max_upload_bytes:
                    raise InputError(name, f"is larger than {store.max_upload_bytes:,} bytes, "
                                     "the largest upload")
                with zf.open(member) as f:
                    item = store.add(Path(name).name, iter(lambda f=f: f.read(1 << 20), b""))
                named[value] = {"id": item.id, "name": item.name}
    else:
        tables = project_tables_of(_text(path.read_bytes(), path.name), path.name)
    wanted = [v for s, k in FILE_KEYS
              if isinstance(v := tables.get(s, {}).get(k), str)]
    return {"project": tables, "files": named,
            "missing": [v for v in wanted if v not in named]}


def page_routes(app: FastAPI, planner: Planner, store: UploadStore, basemaps: Basemaps
                ) -> None:
    """Add the page's routes (see the module docstring) to ``app``."""
    _basemap_routes(app, planner, store, basemaps)
    @app.get("/api/upload/{upload_id}")
    def upload_info(upload_id: str) -> dict[str, Any]:
        """The upload ``upload_id`` if the server still keeps it: id, stored name, size."""
        try:
            path = store.path(upload_id, "file")
        except InputError as exc:
            raise HTTPException(404, exc.message) from None
        return {"id": upload_id, "name": path.name, "size": path.stat().st_size}

    @app.post("/api/open")
    def open_file(req: OpenRequest) -> dict[str, Any]:
        """A project file or the page's zip: its tables, the files it held, those missing."""
        return open_project(store, req.id)

    @app.post("/api/area")
    def area(req: AreaRequest) -> dict[str, Any]:
        """The outline of the request's ``[area]`` (GeoJSON FeatureCollection, WGS 84)."""
        files = {name: str(store.path(i, f"files.{name}")) for name, i in req.files.items()}
        return planner.run("area", req.project, files)  # type: ignore[no-any-return]


def _basemap_routes(app: FastAPI, planner: Planner, store: UploadStore,
                    basemaps: Basemaps) -> None:
    """The tiles and the orthophoto (:mod:`scanplan.web.basemap`)."""
    import json

    @app.get("/api/tiles/{source}/{z}/{x}/{y}", response_class=Response)
    def tile(source: str, z: int, x: int, y: int) -> Response:
        """A tile of a configured source (fetched once, then from the disk cache)."""
        got = basemaps.tile(source, z, x, y)
        if got is None:
            return Response(status_code=404)
        return Response(got[0], media_type=got[1],
                        headers={"Cache-Control": "private, max-age=86400"})

    def _ortho(upload_id: str) -> tuple[Path, dict[str, Any]]:
        path = store.path(upload_id, "file")
        png, meta = path.parent / "basemap.png", path.parent / "basemap.json"
        if not meta.is_file():
            info = planner.run("ortho", str(path), str(png))
            meta.write_text(json.dumps(info), encoding="utf-8")
        return png, json.loads(meta.read_text(encoding="utf-8"))

    @app.get("/api/basemap/{upload_id}")
    def ortho(upload_id: str) -> dict[str, Any]:
        """An uploaded GeoTIFF as a background: bounds [[s, w], [n, e]] [°], size [px]."""
        return _ortho(upload_id)[1]

    @app.get("/api/basemap/{upload_id}/image.png", response_class=FileResponse)
    def ortho_png(upload_id: str) -> FileResponse:
        """The picture of :func:`ortho` (PNG, Web Mercator)."""
        return FileResponse(_ortho(upload_id)[0], media_type="image/png")
