"""Request bodies the API reads, bounded; and text it answers, always encodable.

:class:`BodyGuard` (ASGI middleware, in front of every route) reads a request's body before
the application does: past :data:`MAX_BODY_BYTES` it is refused with 413 (the upload routes,
:data:`UPLOAD_PATHS`, stream their bodies into the upload store, which bounds them); a JSON
body must be UTF-8 JSON nested at most :data:`MAX_JSON_DEPTH` deep, with no lone
surrogate (``"\\ud800"``: half of a character, which no file and no answer can hold) in any
key or string and no number past a double's range (``1e400``, ``NaN``) — else 422 with the
message, as an input error of the command line. Every route added later is covered.

:func:`printable` is the other side: text that goes into an answer (a message quoting a
file's feature names, a document) with every lone surrogate written as its escape, so an
answer never fails to encode.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterator
from typing import Any

__all__ = [
    "MAX_BODY_BYTES",
    "MAX_JSON_DEPTH",
    "UPLOAD_PATHS",
    "BodyGuard",
    "json_bytes",
    "json_problem",
    "printable",
    "printable_data",
]

MAX_BODY_BYTES = 8 * 1024 * 1024
"""Largest JSON request [bytes] (a project with an inline polygon of ~200,000 points)."""
MAX_JSON_DEPTH = 32
"""Deepest nesting of a JSON request (a project is 5 deep; as a project file's bound)."""
UPLOAD_PATHS = frozenset({"/api/upload"})
"""Routes whose body is an uploaded file, bounded by the upload store."""


def _lone_surrogate(text: str) -> bool:
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        return True
    return False


def _children(value: Any, path: str) -> Iterator[tuple[str | None, Any, str]]:
    if isinstance(value, dict):
        for k, v in value.items():
            yield k, v, f"{path}.{k}" if path else str(k)
    else:
        for i, v in enumerate(value):
            yield None, v, f"{path}[{i}]"


def json_problem(doc: Any, limit: int = MAX_JSON_DEPTH) -> tuple[str, str] | None:
    """(where, what) of the first thing a request may not hold: nesting deeper than
    ``limit``, a lone surrogate in a key or a string; None when there is none. Iterative:
    any depth is walked without recursion.

    >>> json_problem({"project": {"name": "a\\ud800"}})
    ('project.name', 'holds a lone surrogate (\\\\ud800), half of a character; send UTF-8 text')
    >>> json_problem([[[1]]], limit=2)[1]
    'nests lists or tables more than 2 deep'
    """
    stack: list[tuple[Any, int, str]] = [(doc, 1, "")]
    while stack:
        value, depth, path = stack.pop()
        if isinstance(value, str):
            if _lone_surrogate(value):
                return path or "request", _surrogate_text(value)
            continue
        if isinstance(value, float) and not math.isfinite(value):
            return path or "request", ("holds a number that is not finite (NaN, Infinity or "
                                       "past 1.8e308)")
        if not isinstance(value, dict | list):
            continue
        if depth > limit:  # named by the key that holds it (not by a thousand indices)
            return (path.split("[")[0] or "request",
                    f"nests lists or tables more than {limit} deep")
        for key, child, where in _children(value, path):
            if isinstance(key, str) and _lone_surrogate(key):
                return printable(where), _surrogate_text(key)
            stack.append((child, depth + 1, where))
    return None


def _surrogate_text(text: str) -> str:
    lone = next(c for c in text if 0xD800 <= ord(c) <= 0xDFFF)
    return (f"holds a lone surrogate (\\u{ord(lone):04x}), half of a character; send UTF-8 "
            "text")


def printable(text: str) -> str:
    """``text`` with every lone surrogate written as its escape (``\\ud800``).

    >>> printable("a\\ud800b")
    'a\\\\ud800b'
    """
    if not _lone_surrogate(text):
        return text
    return text.encode("utf-8", "backslashreplace").decode("utf-8")


def printable_data(value: Any) -> Any:
    """``value`` (JSON-like data) with every string and key :func:`printable`; the same
    object when it holds no lone surrogate (checked at C speed first); bytes as they are
    (a JSON text made by :func:`json_bytes` already is)."""
    if isinstance(value, bytes):
        return value
    try:
        json.dumps(value, ensure_ascii=False, default=str).encode("utf-8")
        return value
    except UnicodeEncodeError:
        pass
    except (TypeError, ValueError):  # not JSON-like (bytes, a tuple of them): as it is
        return value
    if isinstance(value, str):
        return printable(value)
    if isinstance(value, dict):
        return {printable(k) if isinstance(k, str) else k: printable_data(v)
                for k, v in value.items()}
    if isinstance(value, list | tuple):
        return type(value)(printable_data(v) for v in value)
    return value


def json_bytes(value: Any) -> bytes:
    """``value`` (JSON-like data) as the UTF-8 JSON text FastAPI's ``JSONResponse`` sends
    (compact separators, no NaN), every lone surrogate written as its escape
    (:func:`printable_data`): an answer the server passes on without encoding it again.

    >>> json_bytes({"a": [1, 2.5], "b": "\\u00e9\\ud800"}).decode()
    '{"a":[1,2.5],"b":"é\\\\\\\\ud800"}'
    """
    try:
        return _compact(value).encode("utf-8")
    except UnicodeEncodeError:
        return _compact(printable_data(value)).encode("utf-8")


def _compact(value: Any) -> str:
    return json.dumps(value, ensure_ascii=False, allow_nan=False, separators=(",", ":"))


def _refusal(status: int, field: str, message: str) -> tuple[int, bytes]:
    body = {"detail": f"{field}: {message}", "field": field, "message": message}
    if status == 413:
        body = {"detail": message}
    return status, json.dumps(body, ensure_ascii=False).encode("utf-8")


def _check_json(body: bytes) -> tuple[int, bytes] | None:
    """The refusal of a JSON body, or None."""
    try:
        doc = json.loads(body)
    except RecursionError:
        return _refusal(422, "request", f"nests lists or tables more than {MAX_JSON_DEPTH} "
                        "deep")
    except UnicodeDecodeError as exc:
        return _refusal(422, "request", f"is not UTF-8 text: {exc.reason} at byte "
                        f"{exc.start}")
    except ValueError as exc:
        return _refusal(422, "request", f"is not valid JSON: {str(exc)[:200]}")
    problem = json_problem(doc)
    return _refusal(422, *problem) if problem else None


class BodyGuard:
    """ASGI middleware: bounded bodies, checked JSON (the module docstring).

    Parameters
    ----------
    app : ASGI application
    limit : int
        Largest body [bytes] of a route that is not an upload.
    """

    def __init__(self, app: Any, limit: int = MAX_BODY_BYTES) -> None:
        self.app, self.limit = app, limit

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
        if scope["type"] != "http" or scope["path"] in UPLOAD_PATHS:
            await self.app(scope, receive, send)
            return
        headers = dict(scope.get("headers") or [])
        declared = headers.get(b"content-length", b"0")
        too_large = _refusal(413, "request", f"the request is larger than {self.limit:,} "
                             "bytes")
        if declared.isdigit() and int(declared) > self.limit:
            await _answer(send, *too_large)
            return
        chunks, seen, more = [], 0, True
        while more:
            message = await receive()
            if message["type"] == "http.disconnect":
                return
            chunk = message.get("body", b"")
            seen += len(chunk)
            if seen > self.limit:
                await _answer(send, *too_large)
                return
            chunks.append(chunk)
            more = message.get("more_body", False)
        body = b"".join(chunks)
        kind = headers.get(b"content-type", b"").split(b";")[0].strip().lower()
        if body and (kind == b"application/json" or kind.endswith(b"+json")):
            refused = _check_json(body)
            if refused is not None:
                await _answer(send, *refused)
                return
        replayed = False

        async def replay() -> Any:
            nonlocal replayed
            if replayed:
                return await receive()  # the client's disconnect, when it comes
            replayed = True
            return {"type": "http.request", "body": body, "more_body": False}

        await self.app(scope, replay, send)


async def _answer(send: Any, status: int, body: bytes) -> None:
    await send({"type": "http.response.start", "status": status,
                "headers": [(b"content-type", b"application/json"),
                            (b"content-length", str(len(body)).encode())]})
    await send({"type": "http.response.body", "body": body})
