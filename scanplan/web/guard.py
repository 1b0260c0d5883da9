"""Who may drive ``scanplan serve``: the Host, Origin and request-kind checks of every route.

A server on 127.0.0.1 is reachable by every web page the user opens: a page of another site
may send requests to it (cross-site requests), and through *DNS rebinding* (a name of the
attacker's that first resolves to the attacker's server, then to 127.0.0.1) it may even read
the answers, which carry the user configuration's names. :class:`RequestGuard`, one ASGI
middleware in front of every route — the page, its scripts, the API, the API's
documentation, and any route added later — refuses:

1. **a foreign Host** (403): the Host header must name this machine — ``localhost``,
   ``127.0.0.1``, ``::1`` — or the address the server was told to listen on. A rebinding
   page's requests carry the attacker's name. With ``--allow-remote`` (token mode) another
   name (the machine's name on the network) is accepted with the token: the ``?token=`` of
   the printed address, the ``X-Scanplan-Token`` header, or the cookie the page gets when it
   is opened with the token (``SameSite=Strict``: never sent by another site's page);
2. **a foreign Origin** (403): a browser names the page a request comes from; it must be
   this server (scheme, host and port of the Host header);
3. **a cross-site fetch** (403): ``Sec-Fetch-Site: cross-site`` or ``same-site`` (another
   port or name) on anything but opening the page by a link;
4. **a simple cross-site request** (415): a request that changes something (``POST`` …) must
   have a body type that a page of another site cannot send without the server's leave
   (CORS "preflight", which this server never grants): JSON (``application/json``) or
   ``application/octet-stream`` (uploads). ``text/plain``, form posts
   (``application/x-www-form-urlencoded``, ``multipart/form-data``) and a body without a
   type are refused, so no HTML form or ``fetch(…, {mode: "no-cors"})`` of another site is
   ever accepted.

With a token (``--allow-remote``) every ``/api/`` request must also carry it.
"""

from __future__ import annotations

import ipaddress
import json
import secrets
from collections.abc import Iterable
from typing import Any
from urllib.parse import parse_qs, urlsplit

__all__ = ["COOKIE", "LOCAL_HOSTS", "RequestGuard", "allowed_hosts", "refusal"]

LOCAL_HOSTS = frozenset({"localhost", "127.0.0.1", "::1"})
"""Names of this machine a request's Host may carry."""
COOKIE = "scanplan_token"
"""The cookie that carries the token for the page's own files (token mode)."""
_SAFE_METHODS = frozenset({"GET", "HEAD", "OPTIONS"})
_SIMPLE_TYPES = frozenset({"text/plain", "application/x-www-form-urlencoded",
                           "multipart/form-data"})
"""Body types a page of another site may send without a CORS preflight (Fetch standard,
"CORS-safelisted request-header": Content-Type)."""


def allowed_hosts(bound: str | None) -> frozenset[str]:
    """The Host names a server listening on ``bound`` answers without a token: this
    machine's names and ``bound`` itself (not a wildcard address such as ``0.0.0.0``).

    >>> sorted(allowed_hosts("192.168.1.5"))
    ['127.0.0.1', '192.168.1.5', '::1', 'localhost']
    >>> allowed_hosts("0.0.0.0") == LOCAL_HOSTS
    True
    """
    hosts = set(LOCAL_HOSTS)
    if bound:
        name = _host_name(bound)
        try:
            wildcard = ipaddress.ip_address(name).is_unspecified
        except ValueError:
            wildcard = False
        if name and not wildcard:
            hosts.add(name)
    return frozenset(hosts)


def _host_name(host: str) -> str:
    """The name part of a Host header value (no port, no brackets, lower case, no final
    dot): ``[::1]:8765`` → ``::1``, ``LocalHost.:80`` → ``localhost``."""
    host = host.strip().lower()
    if host.startswith("["):
        name = host[1:host.find("]")] if "]" in host else host[1:]
    elif host.count(":") == 1:
        name = host.split(":")[0]
    else:
        name = host  # a bare IPv6 address (the bound address as given) or a plain name
    return name.rstrip(".")


def _authority(value: str, scheme: str) -> str:
    """``host:port`` of a Host header or an Origin's, with the scheme's default port."""
    parts = urlsplit(f"{scheme}://{value}" if "://" not in value else value)
    try:
        port = parts.port
    except ValueError:
        return ""
    default = 443 if parts.scheme == "https" else 80
    return f"{(parts.hostname or '').rstrip('.')}:{port or default}"


def _token_given(headers: dict[str, str], query: str) -> str:
    """The token a request carries: header, ``?token=`` or the page's cookie."""
    given = headers.get("x-scanplan-token") or (parse_qs(query).get("token") or [""])[0]
    if given:
        return given
    for part in headers.get("cookie", "").split(";"):
        name, _, value = part.strip().partition("=")
        if name == COOKIE:
            return value
    return ""


def _valid(token: str | None, headers: dict[str, str], query: str) -> bool:
    """Whether the request carries the server's token."""
    if not token:
        return False
    return secrets.compare_digest(_token_given(headers, query).encode(), token.encode())


def refusal(method: str, path: str, query: str, headers: dict[str, str], *,
            hosts: Iterable[str], token: str | None, scheme: str = "http"
            ) -> tuple[int, str] | None:
    """Why a request is refused (HTTP status, message), or None (the module's rules).

    Parameters
    ----------
    method, path, query : str
        The request line (``query`` without ``?``).
    headers : dict of str to str
        Header names in lower case → value.
    hosts : iterable of str
        Host names answered without a token (:func:`allowed_hosts`).
    token : str or None
        The server's token (token mode), or None.
    scheme : str
        ``http`` (or ``https`` behind a proxy).
    """
    host = headers.get("host", "")
    name = _host_name(host)
    valid = _valid(token, headers, query)
    if name not in hosts and not valid:
        return 403, (f"this server answers requests to this computer only (localhost), not "
                     f"to {name[:100]!r}; a page of another site cannot use it"
                     + (" (open the address with the token scanplan serve printed)"
                        if token else ""))
    origin = headers.get("origin")
    if origin is not None and (origin == "null" or
                               _authority(origin, scheme) != _authority(host, scheme)):
        return 403, f"a request from another site ({origin[:100]}) is refused"
    site = headers.get("sec-fetch-site", "")
    navigation = method in ("GET", "HEAD") and headers.get("sec-fetch-mode") == "navigate"
    if site in ("cross-site", "same-site") and not navigation:
        return 403, "a request from another site is refused"
    if method not in _SAFE_METHODS:
        kind = headers.get("content-type", "").split(";")[0].strip().lower()
        if not kind or kind in _SIMPLE_TYPES:
            return 415, ("a request that sends data must be JSON (application/json) or, for "
                         "an upload, application/octet-stream (got "
                         f"{kind or 'no type'!r}): a page of another site cannot send these")
    if token and path.startswith("/api/") and not valid:
        return 403, "a valid token is required (the one `scanplan serve` printed)"
    return None


class RequestGuard:
    """ASGI middleware applying :func:`refusal` to every HTTP request (and setting the
    token cookie when the page is opened with the token).

    Parameters
    ----------
    app : ASGI application
        The application behind it.
    hosts : iterable of str
        Host names answered without a token.
    token : str or None
        The token of token mode.
    """

    def __init__(self, app: Any, *, hosts: Iterable[str], token: str | None) -> None:
        self.app, self.hosts, self.token = app, frozenset(hosts), token

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
        if scope["type"] not in ("http", "websocket"):
            await self.app(scope, receive, send)
            return
        headers: dict[str, str] = {}
        for key, value in scope.get("headers") or []:
            headers.setdefault(key.decode("latin-1").lower(), value.decode("latin-1"))
        query = (scope.get("query_string") or b"").decode("latin-1")
        method = scope.get("method", "GET")
        refused = refusal(method, scope["path"], query, headers, hosts=self.hosts,
                          token=self.token, scheme=scope.get("scheme", "http"))
        if refused is not None:
            if scope["type"] == "websocket":
                await send({"type": "websocket.close", "code": 1008})
            else:
                await _answer(send, *refused)
            return
        if self.token and scope["path"] == "/" and _valid(self.token, headers, query):
            send = _with_cookie(send, self.token)
        await self.app(scope, receive, send)


async def _answer(send: Any, status: int, message: str) -> None:
    body = json.dumps({"detail": message}).encode()
    await send({"type": "http.response.start", "status": status,
                "headers": [(b"content-type", b"application/json"),
                            (b"content-length", str(len(body)).encode())]})
    await send({"type": "http.response.body", "body": body})


def _with_cookie(send: Any, token: str) -> Any:
    """``send`` adding the token cookie to the response's headers (the page's scripts,
    styles and images then load on a host name that needs the token)."""
    cookie = f"{COOKIE}={token}; Path=/; HttpOnly; SameSite=Strict".encode()

    async def sending(message: Any) -> None:
        if message["type"] == "http.response.start":
            message = {**message, "headers": [*message.get("headers", []),
                                              (b"set-cookie", cookie)]}
        await send(message)
    return sending
