"""The page's downloads rendered while the user looks (scanplan.web.documents): after a plan
is shown and the inputs stay unchanged, its PDF, workbook and zip are rendered ahead in a
worker of their own and a download is served from them, byte for byte what the download
job renders; a changed input is rendered anew; only the latest request is rendered ahead."""

from __future__ import annotations

import time

import pytest
from fastapi.testclient import TestClient
from web_helpers import LOCAL

import scanplan.web.documents as docs
from scanplan.web import jobs
from scanplan.web.app import create_app
from scanplan.web.worker import Planner

UAV = {"project": {"name": "Block", "locale": "en"},
       "map": {"scale": 2000, "relief_interval_m": 1.0},
       "uav": {"camera": "dji-zenmuse-p1-35", "height_m": 120},
       "area": {"polygon": [[37.60, 55.75], [37.61, 55.75], [37.61, 55.755],
                            [37.60, 55.755]]}}


@pytest.fixture
def counted(monkeypatch):
    """The documents jobs run (their requests' heights), with a short quiet time."""
    runs: list[float] = []
    real = jobs.documents_job

    def job(project, files):
        runs.append(project["uav"]["height_m"])
        return real(project, files)

    monkeypatch.setitem(jobs.JOBS, "documents", job)
    monkeypatch.setattr(docs, "QUIET_S", 0.05)
    return runs


def _settled(app, timeout_s: float = 120.0) -> None:
    d = app.state.documents
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        with d._cond:
            if d._wanted is None and not d._running:
                return
        time.sleep(0.05)
    raise AssertionError("the documents were not rendered in time")


def test_a_download_after_the_view_is_the_rendered_one(counted):
    app = create_app(planner=Planner(inline=True))
    with TestClient(app, base_url=LOCAL) as client:
        assert client.post("/api/view", json={"project": UAV}).status_code == 200
        _settled(app)
        assert counted == [120]
        for what, starts in (("pdf", b"%PDF"), ("xlsx", b"PK"), ("zip", b"PK")):
            r = client.post(f"/api/download/{what}", json={"project": UAV})
            assert r.status_code == 200 and r.content.startswith(starts)
        assert counted == [120]  # served from what was rendered ahead: no new rendering


def test_the_downloads_are_the_download_jobs_bytes(counted, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    app = create_app(planner=Planner(inline=True))
    with TestClient(app, base_url=LOCAL) as client:
        client.post("/api/view", json={"project": UAV})
        _settled(app)
        for what in ("pdf", "xlsx"):
            assert client.post(f"/api/download/{what}", json={"project": UAV}).content == \
                jobs.files_job(UAV, {}, what)[1]


def test_only_the_latest_quiet_request_is_rendered_ahead(counted, monkeypatch):
    monkeypatch.setattr(docs, "QUIET_S", 1.0)
    app = create_app(planner=Planner(inline=True))
    with TestClient(app, base_url=LOCAL) as client:
        for h in (100, 110, 120):  # a user typing: each request shown replaces the last
            app.state.documents.ahead({**UAV, "uav": {**UAV["uav"], "height_m": h}}, {})
        _settled(app)
        assert counted == [120]
        other = {"project": {**UAV, "uav": {**UAV["uav"], "height_m": 90}}}  # not shown
        assert client.post("/api/download/zip", json=other).status_code == 200
        assert counted == [120, 90]
        assert client.post("/api/download/exe", json={"project": UAV}).status_code == 422
        assert counted == [120, 90]  # refused before anything is rendered


def test_a_bad_input_is_refused_as_before(counted):
    bad = {"project": {**UAV, "uav": {**UAV["uav"], "speed_ms": -3}}}
    app = create_app(planner=Planner(inline=True))
    with TestClient(app, base_url=LOCAL) as client:
        r = client.post("/api/download/pdf", json=bad)
        assert r.status_code == 422 and "speed_ms" in r.json()["detail"]
