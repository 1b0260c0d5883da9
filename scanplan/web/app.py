"""The web application of ``scanplan serve``: one page and a JSON API (FastAPI).

Routes (``/docs`` shows them with their schemas, ``/openapi.json`` is the OpenAPI text):

- ``GET /`` — the page, in English or Russian (``?lang=``, else the browser's
  Accept-Language);
- ``GET /api/inputs`` — the input registry: every key of a project file with its unit,
  range, default and help;
- ``GET /api/catalogue`` — the cameras and scanners of a norm set;
- ``POST /api/upload?name=`` — an area or DEM file as the request body; its id;
- ``POST /api/plan`` — the ``scanplan plan --json`` document of a project;
- ``POST /api/view`` — that document with the map, the charts and the project file;
- ``POST /api/project.toml`` — the project file;
- ``POST /api/download/{pdf|xlsx|zip}`` — the reports, or everything ``plan --out`` writes
  with the project file and its uploads, as one zip.

A project is sent as ``{"project": {section: {key: value}}, "files": {name: upload id}}``.
A bad input answers 422 with the command line's message (``{"detail": "project.toml:
uav.speed_ms (line 9): must be …", "field": …, "message": …}``). Bodies are bounded
and JSON bodies checked for depth and lone surrogates (:mod:`scanplan.web.bodies`; uploads
are bounded by :mod:`scanplan.web.uploads`). Every request passes
:class:`scanplan.web.guard.RequestGuard` first: a foreign Host or Origin, a cross-site
fetch and a body type another site's page could send are refused, on every route; with a
``token`` every ``/api/`` request must carry it (header ``X-Scanplan-Token`` or
``?token=``).
"""

from __future__ import annotations

from contextlib import asynccontextmanager
from pathlib import Path
from typing import Any

from fastapi import FastAPI, Query, Request
from fastapi.responses import HTMLResponse, JSONResponse, Response
from fastapi.staticfiles import StaticFiles
from pydantic import BaseModel, Field

from .._version import __version__
from ..errors import InputError
from .bodies import MAX_BODY_BYTES, BodyGuard, printable
from .documents import Documents
from .guard import RequestGuard, allowed_hosts
from .uploads import UploadStore
from .worker import Busy, Failed, Planner, TimedOut

__all__ = ["MAX_BODY_BYTES", "PlanRequest", "create_app"]

STATIC = Path(__file__).parent / "static"


class PlanRequest(BaseModel):
    """A project as the tables of a project file, and the uploads it names."""

    project: dict[str, Any] = Field(description="section → {key: value}, the sections and "
                                    "keys of a project file (docs/project-file.md); dotted "
                                    "sections flat: {\"uav.target\": {\"r_max\": 0.3}}")
    files: dict[str, str] = Field(default_factory=dict, description="a file name the project "
                                  "uses ([area] file, [terrain] dem) → the id of its upload")


def _input_error(exc: InputError, lang: str | None = None) -> JSONResponse:
    """422 with the command line's message (every lone surrogate a file brought written as
    its escape: :func:`scanplan.web.bodies.printable`); with ``lang`` (``?lang=`` of the
    page's requests) also ``page``: the key, label and text the page shows by the field
    (:func:`scanplan.web.pagewords.page_error`)."""
    field, message = printable(exc.field), printable(exc.message)
    body: dict[str, Any] = {"detail": f"{field}: {message}", "field": field,
                            "message": message}
    if lang in ("en", "ru"):
        from .pagewords import page_error

        body["page"] = page_error(field, message, lang)
    return JSONResponse(body, 422)


def _language(request: Request, lang: str | None) -> str:
    """``?lang=`` if it is en or ru, else the first of them in Accept-Language, else en."""
    if lang in ("en", "ru"):
        return lang
    header = request.headers.get("accept-language", "")
    for part in header.split(","):
        code = part.split(";")[0].strip().lower()[:2]
        if code in ("en", "ru"):
            return code
    return "en"


def create_app(*, token: str | None = None, planner: Planner | None = None,
               uploads: UploadStore | None = None, tiles: str | None = None,
               basemaps: Any = None, host: str | None = None) -> FastAPI:
    """The application.

    Parameters
    ----------
    token : str or None
        Required on every ``/api/`` request when given (serving off localhost), and on
        every request naming a host other than ``host`` and this machine's names.
    planner : Planner or None
        Runs the plans (default: a worker process with the default time limits).
    uploads : UploadStore or None
        Keeps the uploads (default: a new store, removed when the application stops).
    tiles : str or None
        The page's tile layer: a URL template, ``"osm"`` (OpenStreetMap, the
        default) or ``"none"`` (no background map: offline); ignored with ``basemaps``.
    basemaps : scanplan.web.basemap.Basemaps or None
        The background maps offered (tiles, MBTiles, their cache); default: ``tiles``'s.
    host : str or None
        The address the server listens on: a Host header may name it (besides
        ``localhost``, ``127.0.0.1`` and ``::1``).
    """
    from .basemap import Basemaps

    basemaps = basemaps if basemaps is not None else Basemaps(tiles or "osm")
    planner = planner if planner is not None else Planner()
    store = uploads if uploads is not None else UploadStore()
    documents = Documents.beside(planner, lambda files: _files(store, dict(files)))

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> Any:
        import threading

        threading.Thread(target=planner.warm_up, daemon=True).start()
        try:
            yield
        finally:
            documents.close()
            planner.close()
            store.close()

    app = FastAPI(title="scanplan", version=__version__, lifespan=lifespan,
                  description="Plan a photogrammetric survey: the JSON API of the page "
                  "`scanplan serve` shows. `/api/plan` answers what `scanplan plan --json` "
                  "prints for the same project file.")
    app.state.planner, app.state.uploads, app.state.token = planner, store, token

    app.add_middleware(BodyGuard, limit=MAX_BODY_BYTES)
    # added last: the outermost layer, in front of every route (those added later too)
    app.add_middleware(RequestGuard, hosts=allowed_hosts(host), token=token)

    _error_handlers(app)

    from .page import page_html

    app.mount("/static", StaticFiles(directory=STATIC), name="static")

    @app.get("/", response_class=HTMLResponse, include_in_schema=False)
    def page(request: Request, lang: str | None = None) -> HTMLResponse:
        return HTMLResponse(page_html(_language(request, lang), basemaps.page_list(),
                                      basemaps.default))

    @app.get("/favicon.ico", include_in_schema=False)
    def favicon() -> Response:
        return Response((STATIC / "favicon.svg").read_bytes(), media_type="image/svg+xml")

    _routes(app, planner, store, documents)
    from .pageroutes import page_routes

    page_routes(app, planner, store, basemaps)
    return app


def _error_handlers(app: FastAPI) -> None:
    """Each error of a plan answered with its HTTP status and message."""

    @app.exception_handler(InputError)
    async def on_input(request: Request, exc: InputError) -> JSONResponse:
        return _input_error(exc, request.query_params.get("lang"))

    @app.exception_handler(TimedOut)
    async def on_timeout(request: Request, exc: TimedOut) -> JSONResponse:
        return JSONResponse({"detail": str(exc)}, 504)

    @app.exception_handler(Busy)
    async def on_busy(request: Request, exc: Busy) -> JSONResponse:
        return JSONResponse({"detail": str(exc)}, 503)

    @app.exception_handler(Failed)
    async def on_failed(request: Request, exc: Failed) -> JSONResponse:
        return JSONResponse({"detail": str(exc)}, 500)


def _files(store: UploadStore, files: dict[str, str]) -> dict[str, str]:
    """Upload ids → the stored files' paths (only the store's own files)."""
    return {name: str(store.path(upload_id, f"files.{name}"))
            for name, upload_id in files.items()}


def _routes(app: FastAPI, planner: Planner, store: UploadStore, documents: Documents) -> None:
    """The API's routes."""
    app.state.documents = documents  # the downloads, rendered while the user looks

    @app.get("/api/inputs")
    def inputs(lang: str = Query("en", pattern="^(en|ru)$")) -> list[dict[str, Any]]:
        """Every key of a project file: section, key, kind, unit, range, default, help."""
        from .registry import input_rows

        return input_rows(lang)

    @app.get("/api/catalogue")
    def catalogue(norms: str = "gkinp-02-036-02",
                  lang: str = Query("en", pattern="^(en|ru)$")) -> dict[str, Any]:
        """The cameras and scanners of a bundled norm set (``scanplan cameras list``)."""
        return planner.run("catalogue", norms, lang)  # type: ignore[no-any-return]

    @app.post("/api/upload")
    async def upload(request: Request, name: str = Query(..., max_length=300)
                     ) -> dict[str, Any]:
        """Store the request's body as an upload named like ``name``; its id, stored name
        and size. The file is read only when a project names it."""
        writer = store.open(name)
        try:
            async for chunk in request.stream():
                writer.write(chunk)
            item = writer.done()
        except BaseException:
            writer.abort()
            raise
        return {"id": item.id, "name": item.name, "size": item.size}

    @app.post("/api/plan")
    def plan(req: PlanRequest) -> dict[str, Any]:
        """The ``scanplan plan --json`` document of the project."""
        return planner.run("plan", req.project, _files(store, req.files))  # type: ignore

    from .edits import EditGate, Superseded, parse_edit, superseded_answer

    gate = EditGate(planner.wait_s)

    @app.post("/api/view", response_model=None, response_class=JSONResponse)
    def view(req: PlanRequest, request: Request) -> Response:
        """``plan`` (as /api/plan), ``map`` (GeoJSON, WGS 84), ``charts`` (SVG), ``toml``.
        With ``X-Scanplan-Edit: PAGE/N`` an edit a newer one of the same page replaced is
        answered 409 without being planned (:mod:`scanplan.web.edits`). The worker gives
        the answer's JSON text, sent as it is (the same bytes a dict's answer has)."""
        edit = parse_edit(request.headers.get("x-scanplan-edit"))
        try:
            shown = gate.run(edit, lambda: planner.run(
                "view_json", req.project, _files(store, req.files)),
                lambda: Busy(f"another plan is running; tried for {gate.wait_s:g} s"))
        except Superseded:
            return JSONResponse(superseded_answer(), 409)
        documents.ahead(req.project, req.files)  # the downloads, while the user looks
        return Response(shown, media_type="application/json")

    @app.post("/api/project.toml")
    def project_file(req: PlanRequest) -> Response:
        """The project file (TOML) that ``scanplan plan`` runs (checked first)."""
        from .tomlfile import project_toml

        planner.run("plan", req.project, _files(store, req.files))
        return Response(project_toml(req.project), media_type="application/toml",
                        headers={"Content-Disposition": 'attachment; filename="project.toml"'})

    @app.post("/api/download/{what}")
    def download(what: str, req: PlanRequest) -> Response:
        """``pdf``, ``xlsx``, or ``zip``: the reports, missions, GIS files, project file."""
        name, data = documents.get(req.project, req.files, what)
        kind = {"pdf": "application/pdf", "zip": "application/zip"}.get(
            what, "application/vnd.openxmlformats-officedocument.spreadsheetml.sheet")
        return Response(data, media_type=kind,
                        headers={"Content-Disposition": f'attachment; filename="{name}"'})
