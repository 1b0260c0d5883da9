"""The page of ``scanplan serve`` in real headless Chromium (Debian's ``chromium``, driven
by Playwright with the browser's path given: no browser is downloaded).

As a user would: draw a polygon, choose a camera, see the binding constraint and the strips,
the margins the documents print, a bad value's message by its field in the page's words,
the old result dimmed; download the zip and find the PDF, workbook and missions in it; the
Russian page from a dropped area file; a whole plan made with the keyboard alone, down to
the zip; the plan kept across a language switch and a reload, cleared by New plan; the page
at 768 × 1024 and 390 × 844 (map first, at least half the screen; a polygon drawn by
touch); no serious accessibility violation (axe-core, vendored in tests/vendor); an
orthophoto GeoTIFF under the plan; tiles from a tile server on 127.0.0.1 and from an MBTiles
file, attributed. Skipped only where /usr/bin/chromium is absent (CI installs it).
Screenshots go to ``$SCANPLAN_SCREENSHOTS`` when it is set.
"""

from __future__ import annotations

import hashlib
import io
import os
import re
import subprocess
import threading
import time
import zipfile
from pathlib import Path

import pytest

CHROMIUM = "/usr/bin/chromium"
if not os.path.exists(CHROMIUM):  # pragma: no cover - CI installs it
    pytest.skip(f"{CHROMIUM} is not installed", allow_module_level=True)

from basemap_helpers import ORTHO_COLOUR, TileServer, write_mbtiles, write_ortho  # noqa: E402
from playwright.sync_api import expect, sync_playwright  # noqa: E402
from web_helpers import EXAMPLES  # noqa: E402

from scanplan.web.page import TEXTS  # noqa: E402

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
         "--disable-component-update", "--no-first-run"]
AXE = Path(__file__).parent / "vendor" / "axe-core" / "axe.min.js"
AXE_SHA256 = "29348999450cdf2849a8e70b7912fc2da85a849da39c0d0d5394f51d4a9ed95c"
TOWN = EXAMPLES / "areas" / "town-uav.kml"


def _serve(app):
    """``app`` on a free port of 127.0.0.1 in a thread; (server, thread, URL)."""
    import uvicorn

    srv = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=0, log_level="warning"))
    thread = threading.Thread(target=srv.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 60
    while not srv.started and time.monotonic() < deadline:
        time.sleep(0.05)
    assert srv.started
    return srv, thread, f"http://127.0.0.1:{srv.servers[0].sockets[0].getsockname()[1]}/"


@pytest.fixture(scope="module")
def server():
    """``scanplan serve``'s application (worker process and all), offline (no tiles); the
    downloads' time limit generous (a shared, loaded machine renders slowly)."""
    from scanplan.web.app import create_app
    from scanplan.web.worker import Planner

    srv, thread, url = _serve(create_app(tiles="none", planner=Planner(report_limit_s=600)))
    yield url
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
    """Wait for an answer newer than ``after`` (the page's request counter) to be shown."""
    page.wait_for_function(f"Number(document.body.dataset.seq || 0) > {after} && "
                           "!document.body.dataset.planning", timeout=60_000)


def _seq(page) -> int:
    return int(page.evaluate("document.body.dataset.seq || 0"))


def _open(browser, url: str, lang: str = "en", **kw):
    """A new page (its own browser storage) at ``url``, ready; its page errors collected in
    ``page.errors``."""
    page = browser.new_page(**{"viewport": {"width": 1400, "height": 860}, **kw})
    page.errors = []
    page.on("pageerror", lambda e: page.errors.append(str(e)))
    page.goto(url + f"?lang={lang}")
    page.wait_for_selector("body[data-ready]", state="attached", timeout=60_000)
    page.bring_to_front()  # the focused tab: a file chooser opens only there
    return page


def _choose_camera(page, words: str, camera_id: str) -> None:
    page.fill("#camera-search", words)
    page.click(f"#camera-list li[data-id='{camera_id}']")


def _town_plan(page) -> None:
    """The town boundary dropped, the P1 chosen, planned."""
    before = _seq(page)
    page.set_input_files("#area-file", str(TOWN))
    _choose_camera(page, "p1 35", "dji-zenmuse-p1-35")
    _planned(page, before)
    page.wait_for_function("document.querySelectorAll('path.strip').length > 0")


def test_draw_choose_see_change_download(server, browser, tmp_path):
    page = _open(browser, server)
    expect(page.locator("h1")).to_have_text(TEXTS["en"]["title"])
    _choose_camera(page, "zenmuse p1", "dji-zenmuse-p1-35")
    # draw a polygon with the drawing tool: four clicks and the first vertex again (a
    # block of about 0.8 × 0.6 km at zoom 15: its zip renders in seconds)
    page.evaluate("window.scanplanMap.setZoom(15, {animate: false})")
    page.click("[data-tool=polygon]")
    box = page.locator("#map").bounding_box()
    pts = [(0.35, 0.3), (0.65, 0.28), (0.7, 0.7), (0.4, 0.72), (0.35, 0.3)]
    for x, y in pts:
        page.mouse.click(box["x"] + box["width"] * x, box["y"] + box["height"] * y)
    page.wait_for_function("document.querySelectorAll('path.strip').length > 0 && "
                           "!document.body.dataset.planning", timeout=60_000)
    assert not page.locator("#error").is_visible(), page.inner_text("#error")
    binding = page.inner_text("#binding")
    assert re.match(r"[A-Z]{2} — \w", binding), binding
    expect(page.locator("#constraints tr.binding")).to_have_count(1)
    n_strips = int(page.inner_text("#figures dd[data-k=strips]").replace(",", ""))
    drawn = page.evaluate("new Set([...document.querySelectorAll('path.strip')].map("
                          "p => [...p.classList].find(c => /^strip-\\d+$/.test(c)))).size")
    assert n_strips > 0 and drawn == n_strips
    # every photo centre on the map's one canvas, from the packed coordinates
    photos = int(page.inner_text("#figures dd[data-k=photos]").replace(",", ""))
    assert page.evaluate("window.scanplanPage.state && "
                         "document.querySelector('canvas.photo-layer') !== null")
    assert page.evaluate("window.scanplanMapLayers.photos.count()") == photos
    # the strip's tooltip: one strip, one sortie, in words
    tip = page.evaluate("window.scanplanMapLayers.strips.get(1).layers[0]"
                        ".getTooltip().getContent()")
    assert tip == "Strip 1 · sortie 1"
    _shot(page, "serve-en-drawn")
    # change the height: the flight follows (GSD), the margins are the documents' own
    gsd = page.inner_text("#figures dd[data-k=gsd]")
    before = _seq(page)
    page.fill("#f-uav-height_m", "60")
    _planned(page, before)
    assert page.inner_text("#figures dd[data-k=gsd]") != gsd
    margins = {r.get_attribute("data-id"): r.locator("td.margin").inner_text()
               for r in page.locator("#constraints tr[data-id]").all()}
    # a bad value: the message by its field, in the page's words (no file, line or key),
    # the last result dimmed and marked as stale
    before = _seq(page)
    page.fill("#f-uav-height_m", "-5")
    page.wait_for_function("document.body.dataset.result === 'error'", timeout=60_000)
    text = page.inner_text("#error")
    assert text.startswith("Flight height") and "project.toml" not in text and \
        "line" not in text and "uav.height_m" not in text, text
    assert page.inner_text("#f-uav-height_m-err") == "must be ≥ 1 and ≤ 20000 m (got -5)"
    assert page.get_attribute("#f-uav-height_m", "aria-invalid") == "true"
    assert page.locator("#result-body.stale").count() == 1
    assert page.locator("#stale-note").is_visible()
    before = _seq(page)
    page.fill("#f-uav-height_m", "60")
    _planned(page, before)
    assert page.locator("#result-body.stale").count() == 0
    assert not page.locator("#stale-note").is_visible()
    assert page.inner_text("#f-uav-height_m-err") == ""
    # download everything as one zip: the PDF prints the margins the page shows
    with page.expect_download(timeout=600_000) as dl:
        page.click("button[data-what='zip']")
    data = Path(dl.value.path()).read_bytes()
    zf = zipfile.ZipFile(io.BytesIO(data))
    names = set(zf.namelist())
    assert {"spec.pdf", "spec.xlsx", "project.toml", "flight.kml"} <= names
    assert any(re.fullmatch(r"mission(-\d+)?\.plan", n) for n in names)
    pdf = tmp_path / "spec.pdf"
    pdf.write_bytes(zf.read("spec.pdf"))
    printed = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True,
                             text=True, check=True).stdout
    shown = [m for m in margins.values() if m]
    assert shown and all(m.replace(" ", "\u2009") in printed or m in printed
                         for m in shown), (margins, printed[:2000])
    assert not page.errors, page.errors


def test_the_russian_page_from_a_dropped_area_file(server, browser):
    page = _open(browser, server, "ru", locale="ru-RU",
                 extra_http_headers={"Accept-Language": "ru"})
    expect(page.locator("h1")).to_have_text(TEXTS["ru"]["title"])
    # the area is drawn as soon as it is dropped, before a camera is chosen
    page.set_input_files("#area-file", str(TOWN))
    page.wait_for_function("document.querySelector('.leaflet-overlay-pane path') !== null",
                           timeout=60_000)
    assert page.inner_text("#state") == TEXTS["ru"]["need_camera"]
    _choose_camera(page, "p1", "dji-zenmuse-p1-35")
    before = _seq(page)
    page.fill("#f-map-relief_interval_m", "0,5")
    _planned(page, before)
    page.wait_for_function("document.querySelector('#state').textContent.includes('рассчитано')")
    assert not page.locator("#error").is_visible(), page.inner_text("#error")
    assert TEXTS["ru"]["binding"] in page.inner_text("#headline")
    assert "точность по высоте" in page.inner_text("#constraints")
    assert "м" in page.inner_text("#rec")
    assert page.locator("path.strip").count() > 0
    assert page.locator("#charts img[data-chart='height']").count() == 1
    # a bad value: said in Russian, by the field
    before = _seq(page)
    page.fill("#f-uav-speed_ms", "-5")
    page.wait_for_function("document.body.dataset.result === 'error'", timeout=60_000)
    assert page.inner_text("#f-uav-speed_ms-err") == \
        "должно быть ≥ 0 и ≤ 500 м/с (введено -5)"
    assert page.inner_text("#error").startswith("Путевая скорость")
    before = _seq(page)
    page.fill("#f-uav-speed_ms", "")
    _planned(page, before)
    _shot(page, "serve-ru-town")
    assert not page.errors, page.errors


def test_a_dropped_area_and_dem_fly_in_sorties(server, browser):
    """The town over the valley DEM in 25-minute sorties: each sortie's take-off on the
    map; the page's picture in docs/serve.png is this one. The DEM can be removed."""
    page = _open(browser, server)
    page.set_input_files("#area-file", str(TOWN))
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
    assert page.locator("#warnings li").count() > 0
    # terrain following: a strip's profile, the ground under each photo from the DEM and
    # the flight altitude above it; a strip clicked on the map is the one shown
    assert page.locator("#profile svg polygon").count() == 1
    alt = page.evaluate("window.scanplanPage.state.lastOk.map.features.find(f => "
                        "f.properties.number === 5 && f.properties.kind === 'strip')"
                        ".properties.profile")
    assert min(a - g for a, g in zip(alt["altitude_m"], alt["ground_m"], strict=True)) > 0
    assert max(alt["ground_m"]) - min(alt["ground_m"]) > 5  # the valley under the strip
    page.locator("path.strip-5").first.click(force=True)
    assert page.input_value("#profile-strip") == "5"
    assert page.inner_text("#state").startswith("planned in"), page.inner_text("#state")
    page.hover("#constraints tr.binding")
    _shot(page, "serve-town-dem")
    assert "terrain" in page.evaluate("JSON.stringify(window.scanplanPage.request().project)")
    before = _seq(page)
    page.click("#dem-remove")
    _planned(page, before)
    assert page.inner_text("#dem-status") == TEXTS["en"]["dem_none"]
    assert "terrain" not in page.evaluate(
        "JSON.stringify(window.scanplanPage.request().project)")


def _tab_to(page, selector: str, most: int = 150) -> None:
    """Press Tab until the element of ``selector`` has the focus (the keyboard alone)."""
    for _ in range(most):
        if page.evaluate(f"document.activeElement && document.activeElement.matches("
                         f"{selector!r})"):
            return
        page.keyboard.press("Tab")
    raise AssertionError(f"Tab never reached {selector}")


def _enter_opens_the_file_chooser(page, selector: str, tries: int = 3):
    """Enter on the focused ``selector`` opens the file chooser: its chooser. Headless
    Chromium now and then shows no chooser while another tab of the test browser holds the
    focus, so the tab is brought to the front and Enter pressed again (by the keyboard
    still) before the test fails."""
    from playwright.sync_api import TimeoutError as PlaywrightTimeout

    for attempt in range(tries):
        try:
            with page.expect_file_chooser(timeout=40_000) as fc:
                page.keyboard.press("Enter")
            return fc.value
        except PlaywrightTimeout:
            if attempt == tries - 1:
                raise
            page.bring_to_front()
            _tab_to(page, selector)
    raise AssertionError("unreachable")


def test_a_whole_plan_with_the_keyboard_alone(server, browser):
    """From an empty page to the zip, with Tab, Enter, the arrows and typing only; every
    focused control shows a visible focus."""
    page = _open(browser, server, accept_downloads=True)
    # the drop zone opens the file chooser with Enter
    _tab_to(page, "#drop")
    outline = page.evaluate("getComputedStyle(document.activeElement).outlineStyle")
    assert outline != "none"
    _enter_opens_the_file_chooser(page, "#drop").set_files(str(TOWN))
    page.wait_for_function("document.querySelector('#area-status').textContent"
                           ".includes('town-uav.kml')")
    # the camera: a combobox, chosen with the arrows and Enter
    _tab_to(page, "#camera-search")
    page.keyboard.type("zenmuse p1")
    assert page.get_attribute("#camera-search", "aria-expanded") == "true"
    page.keyboard.press("ArrowDown")
    active = page.get_attribute("#camera-search", "aria-activedescendant")
    assert active and page.get_attribute(f"#{active}", "aria-selected") == "true"
    chosen = page.get_attribute(f"#{active}", "data-id")
    before = _seq(page)
    page.keyboard.press("Enter")
    assert chosen in page.inner_text("#camera-chosen")
    _planned(page, before)
    # a value typed into a field
    _tab_to(page, "#f-uav-height_m")
    before = _seq(page)
    page.keyboard.type("120")
    _planned(page, before)
    assert not page.locator("#error").is_visible(), page.inner_text("#error")
    # the zip with Enter on its button
    _tab_to(page, "button[data-what='zip']")
    with page.expect_download(timeout=600_000) as dl:
        page.keyboard.press("Enter")
    zf = zipfile.ZipFile(io.BytesIO(Path(dl.value.path()).read_bytes()))
    assert {"spec.pdf", "spec.xlsx", "project.toml", "town-uav.kml"} <= set(zf.namelist())
    # no name typed: the documents are named after the area file, never "project"
    assert 'name = "town-uav"' in zf.read("project.toml").decode()
    # the drawing tools are named buttons the keyboard reaches
    for tool in ("polygon", "rectangle", "edit", "drag", "delete"):
        el = page.locator(f"[data-tool={tool}]")
        assert el.get_attribute("aria-label") and el.get_attribute("tabindex") == "0"
    assert not page.errors, page.errors


def test_a_language_switch_and_a_reload_keep_the_plan(server, browser):
    page = _open(browser, server)
    _town_plan(page)
    page.fill("#f-uav-height_m", "110")
    page.click("input[name=platform][value=film]")
    page.click("input[name=platform][value=uav]")  # Film → Digital keeps the camera
    assert "dji-zenmuse-p1-35" in page.inner_text("#camera-chosen")
    page.locator("#more").evaluate("d => d.open = true")
    page.fill("#f-project-name", "Kept plan")
    before = _seq(page)
    page.fill("#f-uav-speed_ms", "11")
    _planned(page, before)
    rec = page.inner_text("#rec")
    request = page.evaluate("JSON.stringify(window.scanplanPage.request())")
    # switch the language: the same plan, in Russian
    page.click("#lang-other")
    page.wait_for_selector("body[data-ready]", state="attached", timeout=60_000)
    _planned(page)
    assert page.evaluate("document.documentElement.lang") == "ru"
    assert page.input_value("#f-uav-height_m") == "110"
    assert page.input_value("#f-project-name") == "Kept plan"
    assert "dji-zenmuse-p1-35" in page.inner_text("#camera-chosen")
    assert "town-uav.kml" in page.inner_text("#area-status")
    assert page.inner_text("#rec").split()[0] == rec.split()[0]
    assert page.locator("path.strip").count() > 0
    same = page.evaluate("JSON.stringify(window.scanplanPage.request())")
    assert same == request.replace('"locale":"en"', '"locale":"ru"')
    # reload: still there
    page.reload()
    page.wait_for_selector("body[data-ready]", state="attached", timeout=60_000)
    _planned(page)
    assert page.evaluate("JSON.stringify(window.scanplanPage.request())") == same
    assert page.inner_text("#rec").split()[0] == rec.split()[0]
    _shot(page, "serve-ru-kept")
    # New plan clears it on purpose
    page.click("#new-plan")
    page.wait_for_selector("body[data-ready]", state="attached", timeout=60_000)
    assert page.input_value("#f-uav-height_m") == ""
    assert page.inner_text("#area-status") == TEXTS["ru"]["no_area"]
    assert not page.errors, page.errors


def _map_share(page) -> float:
    """The share of the viewport the map fills at the top of the page."""
    return page.evaluate("""() => {
        const r = document.getElementById('map').getBoundingClientRect();
        const w = Math.max(0, Math.min(r.right, innerWidth) - Math.max(r.left, 0));
        const h = Math.max(0, Math.min(r.bottom, innerHeight) - Math.max(r.top, 0));
        return w * h / (innerWidth * innerHeight); }""")


@pytest.mark.parametrize("width,height,lang", [(768, 1024, "en"), (390, 844, "ru"),
                                               (768, 1024, "ru"), (390, 844, "en")])
def test_tablet_and_phone_layouts(server, browser, width, height, lang):
    """The map first, across the width, at least half the screen; the inputs and results
    below; a polygon drawn by touch on the phone."""
    page = _open(browser, server, lang, viewport={"width": width, "height": height},
                 has_touch=True, is_mobile=width < 700, device_scale_factor=1)
    assert _map_share(page) >= 0.5, _map_share(page)
    assert page.evaluate("document.documentElement.scrollWidth") <= width
    _choose_camera(page, "zenmuse p1", "dji-zenmuse-p1-35")
    page.evaluate("window.scrollTo(0, 0)")
    page.tap("[data-tool=polygon]")
    box = page.locator("#map").bounding_box()
    # (right of the drawing tool's actions, which open beside it)
    for x, y in [(0.5, 0.4), (0.85, 0.4), (0.85, 0.8), (0.5, 0.8), (0.5, 0.4)]:
        page.touchscreen.tap(box["x"] + box["width"] * x, box["y"] + box["height"] * y)
        page.wait_for_timeout(400)
    page.wait_for_function("document.querySelectorAll('path.strip').length > 0 && "
                           "!document.body.dataset.planning", timeout=60_000)
    page.evaluate("window.scrollTo(0, 0)")
    assert _map_share(page) >= 0.5
    _shot(page, f"serve-{lang}-{width}")
    assert not page.errors, page.errors


def _axe(page) -> list[dict]:
    """axe-core's serious and critical violations of the page as it is."""
    assert hashlib.sha256(AXE.read_bytes()).hexdigest() == AXE_SHA256
    page.add_script_tag(path=str(AXE))
    found = page.evaluate("""async () => {
        const r = await axe.run(document, {resultTypes: ['violations']});
        return r.violations.filter(v => ['serious', 'critical'].includes(v.impact))
          .map(v => ({id: v.id, impact: v.impact, nodes: v.nodes.slice(0, 3)
            .map(n => n.target.join(' '))}));
    }""")
    return found


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_no_serious_accessibility_violation(server, browser, lang):
    page = _open(browser, server, lang)
    assert _axe(page) == []
    _town_plan(page)
    page.fill("#f-uav-height_m", "-5")  # an error shown by its field
    page.wait_for_function("document.body.dataset.result === 'error'", timeout=60_000)
    assert _axe(page) == []


def _pixels(page, selector: str) -> list[tuple[int, int, int]]:
    """The colours of a grid of points over an element, from a screenshot."""
    from PIL import Image

    box = page.locator(selector).bounding_box()
    img = Image.open(io.BytesIO(page.screenshot())).convert("RGB")
    return [img.getpixel((int(box["x"] + box["width"] * fx), int(box["y"] + box["height"] * fy)))
            for fx in (0.1, 0.3, 0.5, 0.7, 0.9) for fy in (0.1, 0.3, 0.5, 0.7, 0.9)]


def _near(c, ref, tol=40) -> bool:
    return all(abs(a - b) <= tol for a, b in zip(c, ref, strict=True))


def test_an_orthophoto_under_the_plan(server, browser, tmp_path):
    ortho = write_ortho(tmp_path / "ortho.tif")
    page = _open(browser, server, accept_downloads=True)
    # offline without a background, the page says so and offers the choices
    assert page.locator("#map-note").is_visible()
    assert TEXTS["en"]["no_basemap"] in page.inner_text("#map-note")
    _town_plan(page)
    page.select_option("#basemap", "ortho")
    page.set_input_files("#ortho-file", str(ortho))
    page.wait_for_selector("img.ortho", timeout=60_000)
    page.wait_for_function("document.querySelector('img.ortho').complete && "
                           "document.querySelector('img.ortho').naturalWidth > 0")
    assert not page.locator("#map-note").is_visible()
    assert sum(_near(c, ORTHO_COLOUR) for c in _pixels(page, "#map")) >= 3
    assert "ortho.tif" in page.inner_text(".leaflet-control-attribution")
    _shot(page, "serve-en-ortho")
    # the project names it; the PDF's map page prints it
    request = page.evaluate("window.scanplanPage.request()")
    assert request["project"]["map"]["basemap"] == "ortho.tif"
    with page.expect_download(timeout=600_000) as dl:
        page.click("button[data-what='pdf']")
    pdf = tmp_path / "spec.pdf"
    pdf.write_bytes(Path(dl.value.path()).read_bytes())
    text = subprocess.run(["pdftotext", str(pdf), "-"], capture_output=True, text=True,
                          check=True).stdout
    assert "Background: ortho.tif" in text
    assert not page.errors, page.errors


def test_tiles_from_a_local_tile_server_and_an_mbtiles_file(browser, tmp_path):
    """The server fetches the tiles of its own URL template (here a tile server on
    127.0.0.1), keeps them on disk and shows them attributed; an MBTiles file works offline."""
    from scanplan.web.app import create_app
    from scanplan.web.basemap import Basemaps

    mb = write_mbtiles(tmp_path / "town.mbtiles", (30, 160, 60))
    with TileServer((40, 90, 200)) as tiles:
        basemaps = Basemaps(tiles.url, "Local tiles © test", mb, cache=tmp_path / "cache")
        srv, thread, url = _serve(create_app(basemaps=basemaps))
        try:
            page = _open(browser, url)
            assert page.input_value("#basemap") == "mbtiles"  # offline first
            page.set_input_files("#area-file", str(TOWN))  # the map goes to the town
            page.wait_for_function("document.querySelectorAll('.leaflet-tile-loaded')"
                                   ".length > 0", timeout=60_000)
            page.wait_for_timeout(1000)
            assert "Test tiles © the test" in page.inner_text(".leaflet-control-attribution")
            assert sum(_near(c, (30, 160, 60)) for c in _pixels(page, "#map")) >= 10
            page.select_option("#basemap", "tiles")
            page.wait_for_function("[...document.querySelectorAll('.leaflet-tile-loaded')]"
                                   ".some(t => t.src.includes('/api/tiles/tiles/'))",
                                   timeout=60_000)
            page.wait_for_timeout(1000)
            assert "Local tiles © test" in page.inner_text(".leaflet-control-attribution")
            assert sum(_near(c, (40, 90, 200)) for c in _pixels(page, "#map")) >= 10
            assert tiles.hits and not page.locator("#map-note").is_visible()
            _shot(page, "serve-en-tiles")
            assert not page.errors, page.errors
        finally:
            srv.should_exit = True
            thread.join(30)
    assert list((tmp_path / "cache").rglob("*/*/*/[0-9]*"))  # kept on disk


def _direction(page) -> float:
    """The plan's flight-line direction [°, clockwise from grid north]."""
    return page.evaluate("window.scanplanPage.lastDirection()")


def test_the_line_direction_by_a_handle_on_the_map(server, browser):
    """As QGroundControl's survey: a handle turns the strips — dragged with the mouse, or
    moved with the arrow keys (a slider for a screen reader)."""
    page = _open(browser, server)
    _town_plan(page)
    first = _direction(page)
    handle = page.locator(".direction-handle")
    assert handle.get_attribute("role") == "slider"
    assert abs(float(handle.get_attribute("aria-valuenow")) - first % 180) < 0.06
    # the keyboard: Shift+→ turns by 10°
    handle.focus()
    before = _seq(page)
    page.keyboard.press("Shift+ArrowRight")
    _planned(page, before)
    want = round((first + 10) % 180, 1)
    assert float(page.input_value("#f-area-direction_deg").replace(",", ".")) == want
    assert abs(_direction(page) - want) < 0.06
    # the mouse: dragged a quarter turn about the area's centre
    box = handle.bounding_box()
    hx, hy = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    cx, cy = page.evaluate("""() => { const m = window.scanplanMap;
        const p = m.latLngToContainerPoint(window.scanplanMapLayers.handleCenter());
        const r = m.getContainer().getBoundingClientRect();
        return [r.left + p.x, r.top + p.y]; }""")
    before = _seq(page)
    page.mouse.move(hx, hy)
    page.mouse.down()
    tx, ty = cx - (hy - cy), cy + (hx - cx)  # the handle turned by 90° on the screen
    for k in range(1, 11):
        page.mouse.move(hx + (tx - hx) * k / 10, hy + (ty - hy) * k / 10)
    page.mouse.up()
    _planned(page, before)
    turned = (_direction(page) - want) % 180
    assert abs(turned - 90) < 3, (want, _direction(page))
    assert page.locator("path.strip").count() > 0
    assert not page.errors, page.errors


def test_the_plans_compared_are_shown_under_the_figures(server, browser):
    """The town on flat ground: the least flight length and the long axis compared — the
    table in the results panel, worded as the documents word it, the recommended plan first
    and marked, why it was chosen above the table."""
    page = _open(browser, server)
    _town_plan(page)
    box = page.locator("#alternatives")
    expect(box).to_be_visible()
    assert page.inner_text("#alternatives h3") == "Plans compared"
    assert page.inner_text("#alternatives p.choice").startswith("Of 2 plans compared")
    rows = page.locator("#alternatives table.plans tr.recommended:not(.why)")
    expect(rows).to_have_count(1)
    first = page.locator("#alternatives table.plans tr:not(.why)").nth(1).inner_text()
    assert "(least length)" in first, first
    assert "(long axis)" in page.inner_text("#alternatives table.plans")
    assert "meets every constraint (recommended)" in page.inner_text("#alternatives")
    assert not page.errors, page.errors


def _strip_angles(page) -> list[float]:
    """Each drawn strip's direction on the screen [°, 0 … 180), from its path's ends."""
    return page.evaluate("""() => [...document.querySelectorAll('path.strip')].map((p) => {
        const n = (p.getAttribute('d').match(/-?[0-9.]+/g) || []).map(Number);
        if (n.length < 4) return null;
        const dx = n[n.length - 2] - n[0], dy = n[n.length - 1] - n[1];
        return ((Math.atan2(dx, -dy) * 180 / Math.PI) % 180 + 180) % 180;
      }).filter((a) => a !== null)""")


def test_a_crosshatch_by_its_checkbox_draws_strips_in_two_directions(server, browser):
    """The "Crosshatch (double grid)" checkbox among the UAV inputs, ticked from the
    keyboard: the map draws the second pass's strips at + 90° beside the first's, the
    figures count both; it is kept across a reload and sent as ``[uav] crosshatch``."""
    page = _open(browser, server)
    _town_plan(page)
    one = _strip_angles(page)
    assert max(one) - min(one) < 2, one  # one direction
    n_one = len(one)
    box = page.locator("#f-uav-crosshatch")
    expect(box).to_be_visible()
    assert page.inner_text("label[for='f-uav-crosshatch']") == "Crosshatch (double grid)"
    box.focus()
    before = _seq(page)
    page.keyboard.press("Space")
    assert box.is_checked()
    _planned(page, before)
    page.wait_for_function(f"document.querySelectorAll('path.strip').length > {n_one}")
    both = _strip_angles(page)
    first = one[0]
    turned = [a for a in both if abs(((a - first + 90) % 180) - 90) > 45]
    assert turned and len(turned) < len(both), both
    assert all(abs(((a - first) % 180) - 90) < 3 for a in turned), (first, turned)
    _shot(page, "crosshatch-en")
    # kept in the saved state: a reload ticks it again and plans both passes
    before = 0
    page.reload()
    page.wait_for_selector("body[data-ready]", state="attached", timeout=60_000)
    _planned(page, before)
    expect(page.locator("#f-uav-crosshatch")).to_be_checked()
    page.wait_for_function(f"document.querySelectorAll('path.strip').length > {n_one}")
    assert not page.errors, page.errors


def test_the_crosshatch_checkbox_speaks_russian(server, browser):
    page = _open(browser, server, lang="ru")
    assert page.inner_text("label[for='f-uav-crosshatch']") == "Двойная сетка"
    assert not page.errors, page.errors


def test_a_lone_edit_is_asked_for_at_once_and_an_identical_one_not_again(server, browser):
    """The first edit after a pause goes out in its own event (no pause before the
    request); the same input again within the gathering time sends nothing new: one
    request, its answer shown."""
    page = _open(browser, server)
    _town_plan(page)
    sent = []
    page.on("request", lambda r: sent.append(r.url) if "/api/view" in r.url else None)
    before = _seq(page)
    at_once = page.evaluate("""() => {
      const el = document.getElementById('f-uav-height_m');
      el.value = '125';
      el.dispatchEvent(new Event('input', {bubbles: true}));
      const planning = document.body.dataset.planning === '1';
      el.dispatchEvent(new Event('input', {bubbles: true}));
      return planning;
    }""")
    assert at_once
    _planned(page, before)
    page.wait_for_timeout(300)  # the gathered second event's turn has passed
    assert len(sent) == 1, sent
    assert _seq(page) == before + 1
    assert page.evaluate("document.body.dataset.result") == "ok"
    assert page.input_value("#f-uav-height_m") == "125"
    assert not page.errors, page.errors
    page.close()
