"""No web page of another site can drive ``scanplan serve``: a foreign Host (DNS
rebinding), a foreign Origin, a cross-site fetch and a simple cross-site POST (a form, a
``text/plain`` upload) are refused on every route of the application — the routes are
read from the application itself, so a route added later is covered without a new test.
The last test plays the attack in real Chromium: a page of another site posts a
``text/plain`` upload and a form, and a rebound name reads the API."""

from __future__ import annotations

import json
import os
import re
import threading
import time
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

import pytest
from fastapi.testclient import TestClient
from web_helpers import LOCAL, UPLOAD

from scanplan.web.app import create_app
from scanplan.web.guard import allowed_hosts, refusal
from scanplan.web.uploads import UploadStore
from scanplan.web.worker import Planner

UAV = {"project": {"map": {"scale": 2000, "relief_interval_m": 1.0},
                   "uav": {"camera": "dji-zenmuse-p1-35", "height_m": 120},
                   "area": {"width_m": 500, "length_m": 500}}}
FOREIGN = "http://rebind.example:8765"  # a DNS-rebinding page's origin: its name, our port


def _requests(app) -> list[tuple[str, str]]:
    """(method, path) of every route of the application, path parameters filled in."""
    from starlette.routing import Mount

    out = []
    for route in app.routes:
        if isinstance(route, Mount):
            out.append(("GET", route.path + "/app.js"))
            continue
        path = re.sub(r"\{[^}]+\}", "pdf", route.path)
        for method in sorted(getattr(route, "methods", None) or {"GET"}):
            if method != "HEAD":
                out.append((method, path))
    return out


@pytest.fixture
def store():
    return UploadStore(max_upload_bytes=1024 * 1024)


@pytest.fixture
def app(store):
    return create_app(planner=Planner(inline=True), uploads=store, tiles="none")


def _send(client, method, path, **kw):
    if method == "POST":
        kw.setdefault("headers", {}).setdefault("Content-Type", "application/json")
        kw.setdefault("content", json.dumps(UAV) if path != "/api/upload" else b"<kml/>")
    return client.request(method, path, **kw)


def test_every_route_refuses_a_foreign_host(app, store):
    routes = _requests(app)
    assert {("GET", "/"), ("POST", "/api/view"), ("POST", "/api/upload"),
            ("GET", "/static/app.js"), ("GET", "/docs")} <= set(routes)
    with TestClient(app, base_url=FOREIGN) as foreign:
        for method, path in routes:
            r = _send(foreign, method, path, params={"name": "a.kml"})
            assert r.status_code == 403, (method, path, r.status_code)
            assert "this computer only" in r.json()["detail"]
    assert len(store) == 0


@pytest.mark.parametrize("host", ["127.0.0.1:8765", "localhost:8765", "[::1]:8765",
                                  "LOCALHOST.:80"])
def test_this_machines_names_are_answered(app, host):
    with TestClient(app, base_url=LOCAL) as c:
        for method, path in _requests(app):
            if method == "GET" and path != "/api/catalogue":
                r = c.get(path, headers={"Host": host})
                # a route with parameters (filled with "pdf": no such upload or tile)
                # answers for itself, 404 or 422, past the guard
                allowed = {200, 404, 422} if "/pdf" in path else {200}
                assert r.status_code in allowed, (path, host, r.status_code, r.text[:200])
                assert "this computer only" not in r.text


def test_a_cross_site_text_plain_upload_is_refused(app, store):
    with TestClient(app, base_url=LOCAL) as c:
        before = len(store)
        # what an <form enctype="text/plain"> or fetch(…, {mode: "no-cors"}) of another
        # site sends: a simple request, no preflight
        for headers in ({"Content-Type": "text/plain", "Origin": "http://evil.example"},
                        {"Content-Type": "text/plain"},
                        {"Content-Type": "application/x-www-form-urlencoded"},
                        {"Content-Type": "multipart/form-data; boundary=x"},
                        {}):
            r = c.post("/api/upload", params={"name": "a.kml"}, content=b"<kml/>",
                       headers=headers)
            assert r.status_code in (403, 415), (headers, r.status_code)
        assert len(store) == before  # nothing stored
        r = c.post("/api/upload", params={"name": "a.kml"}, content=b"<kml/>", headers=UPLOAD)
        assert r.status_code == 200 and len(store) == before + 1


@pytest.mark.parametrize("headers,status", [
    ({"Origin": "http://evil.example"}, 403),
    ({"Origin": "http://127.0.0.1:9999"}, 403),   # another local server's page
    ({"Origin": "null"}, 403),                    # a sandboxed frame, a file:// page
    ({"Sec-Fetch-Site": "cross-site"}, 403),
    ({"Sec-Fetch-Site": "same-site"}, 403),
    ({"Content-Type": "text/plain"}, 415),
    ({"Origin": "http://127.0.0.1:8765", "Sec-Fetch-Site": "same-origin"}, 200),
])
def test_a_cross_site_json_request_is_refused(app, headers, status):
    with TestClient(app, base_url=LOCAL) as c:
        r = c.post("/api/plan", content=json.dumps(UAV),
                   headers={"Content-Type": "application/json", **headers})
        assert r.status_code == status, r.text
        if status != 200:
            assert "specification" not in r.text


def test_opening_the_page_from_a_link_of_another_site_still_works(app):
    with TestClient(app, base_url=LOCAL) as c:
        nav = {"Sec-Fetch-Site": "cross-site", "Sec-Fetch-Mode": "navigate"}
        assert c.get("/", headers=nav).status_code == 200
        assert c.get("/api/inputs", headers={"Sec-Fetch-Site": "cross-site",
                                             "Sec-Fetch-Mode": "cors"}).status_code == 403


def test_token_mode_answers_another_host_name_only_with_the_token():
    app = create_app(token="s3cret", planner=Planner(inline=True), host="0.0.0.0")
    with TestClient(app, base_url="http://survey-pc.local:8765") as c:
        assert c.get("/").status_code == 403
        assert c.get("/static/app.js").status_code == 403
        page = c.get("/", params={"token": "s3cret"})
        assert page.status_code == 200 and "HttpOnly" in page.headers["set-cookie"]
        assert "SameSite=Strict" in page.headers["set-cookie"]
        assert c.get("/static/app.js").status_code == 200  # the cookie carries the token
        assert c.get("/api/inputs").status_code == 200
    with TestClient(app, base_url="http://survey-pc.local:8765") as c:
        r = c.get("/", params={"token": "wrong"})
        assert r.status_code == 403 and "set-cookie" not in r.headers
    with TestClient(app, base_url=LOCAL) as c:  # this machine: the page without, the API with
        assert c.get("/").status_code == 200 and "set-cookie" not in c.get("/").headers
        assert c.get("/api/inputs").status_code == 403


def test_the_bound_address_is_a_host_and_a_wildcard_is_not():
    assert "192.168.1.5" in allowed_hosts("192.168.1.5")
    assert allowed_hosts("0.0.0.0") == allowed_hosts("::") == allowed_hosts(None)
    assert refusal("GET", "/", "", {"host": "192.168.1.5:8765"},
                   hosts=allowed_hosts("192.168.1.5"), token="t") is None
    assert refusal("GET", "/", "", {}, hosts=allowed_hosts(None), token=None)[0] == 403


# --------------------------------------------------------------------------------------
# The attack in a browser
# --------------------------------------------------------------------------------------
CHROMIUM = "/usr/bin/chromium"

_ATTACK = """<!DOCTYPE html><html><body>
<iframe name="sink" style="display:none"></iframe>
<form id="f" method="POST" target="sink" action="{api}plan"
      enctype="application/x-www-form-urlencoded">
  <input name='{{"project": {{}}, "x": "' value='"}}'></form>
<script>
window.results = [];
async function go() {{
  try {{  // a text/plain upload: a simple request, sent without a preflight
    await fetch("{api}upload?name=town.kml", {{method: "POST", mode: "no-cors",
      body: "<kml/>", headers: {{"Content-Type": "text/plain"}}}});
    results.push("sent");
  }} catch (e) {{ results.push("upload failed " + e); }}
  document.getElementById("f").submit();
  results.push("form");
  window.done = true;
}}
go();
</script></body></html>"""

_REBOUND = """<!DOCTYPE html><html><body><script>
window.done = false;
(async () => {{
  try {{
    const r = await fetch("/api/inputs");  // same origin for the browser: the rebound name
    window.got = [r.status, await r.text()];
  }} catch (e) {{ window.got = [0, String(e)]; }}
  window.done = true;
}})();
</script></body></html>"""


@pytest.mark.skipif(not os.path.exists(CHROMIUM), reason=f"{CHROMIUM} is not installed")
def test_a_rebinding_page_in_chromium_is_refused(tmp_path):
    """A page of another site (a second local server) sends a text/plain upload and a
    form post to the API; then a page whose name rebinds to 127.0.0.1 (Chromium's host
    resolver maps it) reads the API as its own origin. Nothing is stored, the form gets
    no plan, the rebound read is 403."""
    import uvicorn
    from playwright.sync_api import sync_playwright

    store = UploadStore()
    app = create_app(tiles="none", uploads=store, planner=Planner(inline=True))
    srv = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=0, log_level="warning"))
    thread = threading.Thread(target=srv.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 60
    while not srv.started and time.monotonic() < deadline:
        time.sleep(0.05)
    port = srv.servers[0].sockets[0].getsockname()[1]
    api = f"http://127.0.0.1:{port}/api/"
    seen: list[str] = []

    class Evil(BaseHTTPRequestHandler):
        def do_GET(self) -> None:
            body = _ATTACK.format(api=api).encode()
            self.send_response(200)
            self.send_header("Content-Type", "text/html")
            self.end_headers()
            self.wfile.write(body)

        def log_message(self, *args: object) -> None:
            seen.append(self.path)

    evil = ThreadingHTTPServer(("127.0.0.1", 0), Evil)
    threading.Thread(target=evil.serve_forever, daemon=True).start()
    flags = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
             "--disable-background-networking", "--disable-component-update",
             "--host-resolver-rules=MAP rebind.example 127.0.0.1",
             # the browser's own guard against public pages reaching this machine is off:
             # the test is of the server's guard (a browser without one, an older one)
             "--disable-features=LocalNetworkAccessChecks,BlockInsecurePrivateNetworkRequests,"
             "PrivateNetworkAccessSendPreflights"]
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=CHROMIUM, args=flags)
            page = browser.new_page()
            page.goto(f"http://127.0.0.1:{evil.server_address[1]}/")
            page.wait_for_function("window.done === true", timeout=30000)
            assert page.evaluate("window.results") == ["sent", "form"]
            page.wait_for_timeout(1000)  # the form's post lands in the hidden frame
            sink = page.frame(name="sink")
            assert "specification" not in (sink.content() if sink else "")
            # the rebinding page: served from the attacker's name (its first DNS answer),
            # then its same-origin fetch reaches 127.0.0.1 under that name
            rebound = f"http://rebind.example:{port}/"
            page.route(rebound, lambda route: route.fulfill(
                status=200, content_type="text/html", body=_REBOUND))
            page.goto(rebound)
            page.wait_for_function("window.done === true", timeout=30000)
            status, body = page.evaluate("window.got")
            browser.close()
    finally:
        evil.shutdown()
        srv.should_exit = True
        thread.join(30)
    assert seen  # the attacker's page was served
    assert len(store) == 0  # the cross-site upload stored nothing
    assert status == 403 and "relief_interval_m" not in body
