"""The page of ``scanplan serve`` in real headless Chromium (Debian's ``chromium``, driven
by Playwright with the browser's path given: no browser is downloaded): draw a polygon,
choose a camera, see the binding constraint and the strips, change the height and see the
margin change, download the zip and find the PDF, workbook and missions in it; the Russian
page from a dropped area file. Skipped only where /usr/bin/chromium is absent (CI installs
it). Screenshots go to ``$SCANPLAN_SCREENSHOTS`` when it is set."""

from __future__ import annotations

import io
import os
import re
import threading
import time
import zipfile
from pathlib import Path

import pytest

CHROMIUM = "/usr/bin/chromium"
if not os.path.exists(CHROMIUM):  # pragma: no cover - CI installs it
    pytest.skip(f"{CHROMIUM} is not installed", allow_module_level=True)

from playwright.sync_api import expect, sync_playwright  # noqa: E402
from web_helpers import EXAMPLES  # noqa: E402

from scanplan.web.page import TEXTS  # noqa: E402

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
         "--disable-component-update", "--no-first-run"]


@pytest.fixture(scope="module")
def server():
    """``scanplan serve``'s application on a free port, in a thread (worker process and
    all), offline (no tile layer)."""
    import uvicorn

    from scanplan.web.app import create_app

    app = create_app(tiles="none")
    srv = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=0, log_level="warning"))
    thread = threading.Thread(target=srv.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 60
    while not srv.started and time.monotonic() < deadline:
        time.sleep(0.05)
    assert srv.started
    yield f"http://127.0.0.1:{srv.servers[0].sockets[0].getsockname()[1]}/"
    srv.should_exit = True
    thread.join(30)


@pytest.fixture(scope="module")
def browser():
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
        yield b
        b.close()


def _shot(page, name: str) -> None:
    folder = os.environ.get("SCANPLAN_SCREENSHOTS")
    if folder:
        page.screenshot(path=str(Path(folder) / f"{name}.png"))


def _planned(page, after: int = 0) -> None:
    """Wait for a plan newer than ``after`` (the page's request counter) to be shown."""
    page.wait_for_function(f"Number(document.body.dataset.seq || 0) > {after} && "
                           "!document.body.dataset.planning", timeout=60_000)


def _seq(page) -> int:
    return int(page.evaluate("document.body.dataset.seq || 0"))


def _choose_camera(page, words: str, camera_id: str) -> None:
    page.wait_for_selector("body[data-catalogue]", timeout=60_000)
    page.fill("#camera-search", words)
    page.click(f"#camera-list li[data-id='{camera_id}']")


def test_draw_choose_see_change_download(server, browser, tmp_path):
    page = browser.new_page(viewport={"width": 1400, "height": 860}, accept_downloads=True)
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(server + "?lang=en")
    expect(page.locator("h1")).to_have_text(TEXTS["en"]["title"])
    page.wait_for_selector("#f-uav-height_m")
    _choose_camera(page, "zenmuse p1", "dji-zenmuse-p1-35")
    # draw a polygon with the drawing tool: four clicks and the first vertex again
    page.click(".leaflet-pm-icon-polygon")
    box = page.locator("#map").bounding_box()
    pts = [(0.35, 0.3), (0.65, 0.28), (0.7, 0.7), (0.4, 0.72), (0.35, 0.3)]
    for x, y in pts:
        page.mouse.click(box["x"] + box["width"] * x, box["y"] + box["height"] * y)
    page.wait_for_function("document.querySelectorAll('path.strip').length > 0 && "
                           "!document.body.dataset.planning", timeout=60_000)
    assert not page.locator("#error").is_visible(), page.inner_text("#error")
    binding = page.inner_text("#binding")
    assert re.match(r"[A-Z]{2} — \w", binding), binding
    row = page.locator("#constraints tr.binding")
    expect(row).to_have_count(1)
    n_strips = int(page.inner_text("#figures dd[data-k=strips]").replace(",", ""))
    drawn = page.evaluate("new Set([...document.querySelectorAll('path.strip')].map("
                          "p => [...p.classList].find(c => /^strip-\\d+$/.test(c)))).size")
    assert n_strips > 0 and drawn == n_strips
    _shot(page, "serve-en-drawn")
    # change the height: the margins follow
    margin = page.inner_text("#constraints tr[data-id='PZ'] td.margin")
    before = _seq(page)
    page.fill("#f-uav-height_m", "60")
    _planned(page, before)
    after = page.inner_text("#constraints tr[data-id='PZ'] td.margin")
    assert after != margin and float(after.split()[0].replace(",", "")) > \
        float(margin.split()[0].replace(",", ""))
    # a bad value: the server's message, the field marked
    before = _seq(page)
    page.fill("#f-uav-height_m", "-5")
    page.wait_for_function("document.body.dataset.result === 'error'", timeout=60_000)
    assert "uav.height_m" in page.inner_text("#error")
    assert page.locator(".field.bad #f-uav-height_m").count() == 1
    page.fill("#f-uav-height_m", "60")
    _planned(page, before)
    # download everything as one zip
    with page.expect_download(timeout=120_000) as dl:
        page.click("button[data-what='zip']")
    data = Path(dl.value.path()).read_bytes()
    names = set(zipfile.ZipFile(io.BytesIO(data)).namelist())
    assert {"spec.pdf", "spec.xlsx", "project.toml", "flight.kml"} <= names
    assert any(re.fullmatch(r"mission(-\d+)?\.plan", n) for n in names)
    assert not errors, errors


def test_the_russian_page_from_a_dropped_area_file(server, browser):
    page = browser.new_page(viewport={"width": 1400, "height": 860},
                            locale="ru-RU", extra_http_headers={"Accept-Language": "ru"})
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(server)
    expect(page.locator("h1")).to_have_text(TEXTS["ru"]["title"])
    page.wait_for_selector("#f-uav-height_m")
    page.set_input_files("#area-file", str(EXAMPLES / "areas" / "town-uav.kml"))
    _choose_camera(page, "p1", "dji-zenmuse-p1-35")
    page.fill("#f-map-relief_interval_m", "0,5")
    page.wait_for_function("document.querySelectorAll('path.strip').length > 0 && "
                           "!document.body.dataset.planning && "
                           "document.querySelector('#f-map-relief_interval_m').value === '0,5'",
                           timeout=60_000)
    _planned(page, _seq(page) - 1)
    page.wait_for_function("document.querySelector('#state').textContent.includes('рассчитано')")
    assert not page.locator("#error").is_visible(), page.inner_text("#error")
    assert TEXTS["ru"]["binding"] in page.inner_text("#headline")
    assert "точность по высоте" in page.inner_text("#constraints")
    assert "м" in page.inner_text("#rec")
    assert page.locator("path.strip").count() > 0
    assert page.locator("#charts img[data-chart='height']").count() == 1
    _shot(page, "serve-ru-town")
    assert not errors, errors


def test_a_dropped_area_and_dem_fly_in_sorties(server, browser):
    """The town over the valley DEM in 25-minute sorties: each sortie's take-off on the
    map; the page's picture in docs/serve.png is this one."""
    page = browser.new_page(viewport={"width": 1400, "height": 860})
    page.goto(server + "?lang=en")
    page.wait_for_selector("#f-uav-max_flight_time_min")
    page.set_input_files("#area-file", str(EXAMPLES / "areas" / "town-uav.kml"))
    page.set_input_files("#dem-file", str(EXAMPLES / "dem" / "town-valley.tif"))
    page.wait_for_function("document.querySelector('#dem-status').textContent"
                           " === 'town-valley.tif'")
    _choose_camera(page, "p1 35", "dji-zenmuse-p1-35")
    page.fill("#f-map-relief_interval_m", "0.5")
    page.fill("#f-uav-height_m", "135")
    page.fill("#f-uav-max_flight_time_min", "25")
    before = _seq(page)
    page.fill("#f-uav-speed_ms", "12")
    _planned(page, before)
    assert not page.locator("#error").is_visible(), page.inner_text("#error")
    sorties = int(page.inner_text("#figures dd[data-k=sorties]"))
    assert sorties > 1
    expect(page.locator(".takeoff-icon")).to_have_count(sorties)
    assert "valley" in page.inner_text("#warnings") or page.locator(
        "#warnings li").count() > 0
    page.hover("#constraints tr.binding")
    _shot(page, "serve-town-dem")
