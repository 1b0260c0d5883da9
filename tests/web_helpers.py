"""Shared by the tests of ``scanplan serve``: an example project as an API request."""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
LOCAL = "http://127.0.0.1:8765"
"""The test client's base URL: a Host the server answers (``testserver`` is refused as a
foreign host, as a DNS-rebinding page's name is)."""
UPLOAD = {"Content-Type": "application/octet-stream"}
"""An upload's body type, as the page sends it (a simple type is refused: no cross-site
form can post an upload)."""


def example_request(client: Any, path: Path) -> dict[str, Any]:
    """The example project as ``{"project": tables, "files": {name: upload id}}``, its area
    file and DEM uploaded under the names the project gives them."""
    doc = tomllib.loads(path.read_text(encoding="utf-8"))
    tables: dict[str, dict[str, Any]] = {}

    def walk(prefix: str, table: dict[str, Any]) -> None:
        own = {}
        for k, v in table.items():
            if isinstance(v, dict):
                walk(f"{prefix}.{k}" if prefix else k, v)
            else:
                own[k] = v.isoformat() if hasattr(v, "isoformat") else v
        if prefix:
            tables[prefix] = own

    walk("", doc)
    files = {}
    for section, key in (("area", "file"), ("terrain", "dem")):
        name = tables.get(section, {}).get(key)
        if name:
            r = client.post("/api/upload", params={"name": Path(name).name},
                            content=(path.parent / name).read_bytes(), headers=UPLOAD)
            assert r.status_code == 200, r.text
            files[name] = r.json()["id"]
    return {"project": tables, "files": files}
