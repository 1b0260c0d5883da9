"""Nothing temporary is left behind: every temporary file and folder of a run (WeasyPrint's
``weasyprint-*``, openpyxl's, ``scanplan-gpkg-*``, the page's uploads and ``scanplan-job-*``
folders with their hard links) lives in the run's folder, which goes when the run ends —
normally, by ``SIGTERM``, or when the page's plan passes its time limit; a folder a
``kill -9`` left is swept by the next run, only once its owner is gone.

Each command runs in a child process with ``TMPDIR`` pointing at a folder of the test's own,
which must be empty afterwards."""

from __future__ import annotations

import fcntl
import json
import os
import re
import signal
import subprocess
import sys
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from scanplan.io import rundir

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
TOWN = EXAMPLES / "uav-town-2000.toml"


def _env(tmp: Path) -> dict[str, str]:
    tmp.mkdir(exist_ok=True)
    env = {k: v for k, v in os.environ.items() if k not in rundir.TEMP_VARIABLES}
    return {**env, "TMPDIR": str(tmp)}


def _scanplan(*args: str, tmp: Path, **kw) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "scanplan", *args], env=_env(tmp),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)


def _wait_for(what, timeout_s: float = 120.0):
    """Poll ``what()`` until it is true (a deadline, not a timed assertion)."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        found = what()
        if found:
            return found
        time.sleep(0.02)
    raise AssertionError("never happened")


def _litter(tmp: Path) -> list[str]:
    return sorted(str(p.relative_to(tmp)) for p in tmp.rglob("*"))


def test_a_plan_with_every_output_leaves_nothing(tmp_path):
    tmp = tmp_path / "tmp"
    p = _scanplan("plan", str(TOWN), "--out", str(tmp_path / "out"), tmp=tmp)
    _, err = p.communicate(timeout=600)
    assert p.returncode == 0, err
    assert (tmp_path / "out" / "flight.gpkg").exists() and (tmp_path / "out" / "spec.pdf").exists()
    assert _litter(tmp) == []  # no weasyprint-*, openpyxl.*, scanplan-gpkg-*


def test_sigterm_in_the_middle_of_a_plan_leaves_nothing(tmp_path):
    tmp = tmp_path / "tmp"
    out = tmp_path / "out"
    p = _scanplan("plan", str(TOWN), "--out", str(out), tmp=tmp)
    # the PDF worker has made WeasyPrint's font folder: the run is well under way
    _wait_for(lambda: list(tmp.rglob("weasyprint-*")))
    p.send_signal(signal.SIGTERM)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 128 + signal.SIGTERM, err
    assert "Traceback" not in err
    assert _litter(tmp) == []
    if out.exists():  # the output set is whole or absent; no temporary is left in it
        assert not [n for n in os.listdir(out) if n.endswith((".tmp", ".old", ".part"))]


def test_a_killed_runs_folder_is_swept_by_the_next_run_and_a_live_one_is_not(tmp_path):
    tmp = tmp_path / "tmp"
    live = _scanplan("serve", "--port", "0", "--tiles", "none", tmp=tmp)
    try:
        assert "the page is at" in live.stdout.readline()
        served = _wait_for(lambda: list(tmp.glob(rundir.PREFIX + "*")))
        killed = _scanplan("plan", str(TOWN), "--out", str(tmp_path / "out"), tmp=tmp)
        _wait_for(lambda: list(tmp.glob(rundir.PREFIX + "*/weasyprint-*")))
        killed.kill()
        killed.communicate(timeout=60)
        left = sorted(set(tmp.glob(rundir.PREFIX + "*")) - set(served))
        assert len(left) == 1 and any(left[0].rglob("*"))  # kill -9: its folder is left
        nxt = _scanplan("cameras", "list", tmp=tmp)
        nxt.communicate(timeout=120)
        assert nxt.returncode == 0
        assert not left[0].exists()  # swept: its owner is gone
        assert all(f.exists() for f in served)  # the live server's folder stays
    finally:
        live.send_signal(signal.SIGTERM)
        live.communicate(timeout=120)
    assert _litter(tmp) == []


def _post(url: str, body: bytes, kind: str = "application/json") -> dict:
    req = urllib.request.Request(url, data=body, headers={"Content-Type": kind})
    try:
        with urllib.request.urlopen(req, timeout=300) as r:
            data = r.read()
    except urllib.error.HTTPError as exc:
        raise AssertionError(exc.read()) from None
    return json.loads(data) if kind == "application/octet-stream" else {"bytes": len(data)}


def test_a_server_stopped_by_sigterm_leaves_nothing(tmp_path):
    tmp = tmp_path / "tmp"
    srv = _scanplan("serve", "--port", "0", "--tiles", "none", tmp=tmp)
    try:
        url = re.search(r"http://\S+/", srv.stdout.readline()).group(0)
        kml = (EXAMPLES / "areas" / "town-uav.kml").read_bytes()
        up = _post(url + "api/upload?name=town.kml", kml, "application/octet-stream")
        project = {"project": {"map": {"scale": 2000, "relief_interval_m": 0.5},
                               "uav": {"camera": "dji-zenmuse-p1-35", "height_m": 120},
                               "area": {"width_m": 400, "length_m": 400}},
                   "files": {"town.kml": up["id"]}}
        assert _post(url + "api/download/pdf", json.dumps(project).encode())["bytes"] > 0
        assert list(tmp.rglob("weasyprint-*"))  # the worker rendered a PDF
        assert list(tmp.rglob("town.kml"))  # the upload is kept
    finally:
        srv.send_signal(signal.SIGTERM)
        _, err = srv.communicate(timeout=120)
    assert "Traceback" not in err
    assert _litter(tmp) == []


def test_a_plan_past_its_time_limit_leaves_no_job_folder_and_no_link(tmp_path):
    """The job is killed in the middle (a quarter of its own time): its folder of hard
    links to the uploads goes with the worker's folder, so a removed upload's bytes do
    not stay on the disk."""
    from fastapi.testclient import TestClient
    from web_helpers import LOCAL, example_request

    from scanplan.web.app import create_app
    from scanplan.web.uploads import UploadStore
    from scanplan.web.worker import Planner

    planner = Planner(limit_s=600, report_limit_s=600)
    store = UploadStore()
    with TestClient(create_app(planner=planner, uploads=store), base_url=LOCAL) as c:
        req = example_request(c, TOWN)
        uploads = [store.path(i) for i in req["files"].values()]
        start = time.monotonic()
        assert c.post("/api/download/pdf", json=req).status_code == 200
        took_s = time.monotonic() - start
        renderer = c.app.state.documents.planner  # the downloads' worker of their own
        folder = Path(renderer._folder)
        renderer.report_limit_s = took_s / 4
        req["project"]["project"]["name"] += " (again)"  # not the rendered one kept
        r = c.post("/api/download/pdf", json=req)
        assert r.status_code == 504, r.text
        assert not list(rundir.run_dir().rglob("scanplan-job-*"))  # the killed job's
        assert [os.stat(u).st_nlink for u in uploads] == [1] * len(uploads)
        assert not folder.exists()  # the killed worker's folder


# --------------------------------------------------------------------------------------
# The sweep itself
# --------------------------------------------------------------------------------------
def _run_folder(base: Path, name: str, *, owner: bool = True) -> Path:
    folder = base / f"{rundir.PREFIX}{name}"
    folder.mkdir()
    (folder / "weasyprint-x").mkdir()
    if owner:
        (folder / rundir.OWNER).write_text("1\n")
    return folder


def test_the_sweep_removes_only_folders_whose_owner_is_gone(tmp_path):
    gone = _run_folder(tmp_path, "aaaaaaaa")
    alive = _run_folder(tmp_path, "bbbbbbbb")
    holder = subprocess.Popen([sys.executable, "-c", (
        "import fcntl, os, sys, time\n"
        f"fd = os.open({str(alive / rundir.OWNER)!r}, os.O_RDONLY)\n"
        "fcntl.flock(fd, fcntl.LOCK_EX); print('locked', flush=True); time.sleep(120)")],
        stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "locked"
        young = _run_folder(tmp_path, "cccccccc", owner=False)  # being made right now
        old = _run_folder(tmp_path, "dddddddd", owner=False)
        os.utime(old, (time.time() - 2 * rundir.UNLOCKED_GRACE_S,) * 2)
        target = _run_folder(tmp_path, "eeeeeeee")
        link = tmp_path / f"{rundir.PREFIX}ffffffff"
        link.symlink_to(target, target_is_directory=True)  # never followed
        other = tmp_path / "scanplan-runner-12345678"  # not a run's name
        other.mkdir()
        removed = rundir.sweep(tmp_path)
        assert sorted(Path(p).name for p in removed) == [gone.name, old.name, target.name]
        assert alive.exists() and young.exists() and other.exists() and link.is_symlink()
    finally:
        holder.kill()
        holder.wait()
    assert [Path(p).name for p in rundir.sweep(tmp_path)] == [alive.name]  # now it is gone


def test_a_run_scope_locks_its_folder_and_removes_it(tmp_path, monkeypatch):
    import tempfile

    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    for name in ("path", "owner", "fd"):  # not the test process's own run folder
        monkeypatch.setattr(rundir._STATE, name, None)
    with rundir.run_scope() as folder:
        assert folder.parent == tmp_path and tempfile.gettempdir() == str(folder)
        assert os.environ["TMPDIR"] == str(folder)
        fd = os.open(folder / rundir.OWNER, os.O_RDONLY)
        try:
            with pytest.raises(BlockingIOError):
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        finally:
            os.close(fd)
        assert rundir.sweep(tmp_path) == []
    assert not folder.exists() and tempfile.gettempdir() == str(tmp_path)


def test_a_pdf_renders_after_its_font_folder_was_cleaned_away(tmp_path, monkeypatch):
    """A long-running process (the page's worker, a notebook) whose temporary folder a
    cleaner emptied (systemd-tmpfiles, another program): WeasyPrint's cached fonts named
    files that were gone, and every later PDF failed (a 500 on the page)."""
    import shutil
    import tempfile

    from scanplan.project.jobs import scan_job
    from scanplan.reports.pdf import render_pdf

    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    job = scan_job(map_scale=2000, relief_interval_m=0.5, photo_scales=[10000],
                   camera="rc30-153")
    first = render_pdf(scan=job)
    folders = list(tmp_path.glob("weasyprint-*"))
    assert folders
    for folder in folders:
        shutil.rmtree(folder)
    again = render_pdf(scan=job)
    assert again.startswith(b"%PDF") and len(again) == pytest.approx(len(first), rel=0.01)
