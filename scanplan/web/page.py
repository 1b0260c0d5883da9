"""The page of ``scanplan serve`` in English and Russian.

The HTML (``static/index.html``) holds no words of its own: every text the page shows is a
key of :data:`TEXTS` (:data:`scanplan.i18n.labels_page.PAGE`), in both languages (a test
checks that both have every key), filled in by the script from the configuration this
module puts into the page.
"""

from __future__ import annotations

import html
import json
from typing import Any

from .._version import __version__
from ..i18n.labels_page import PAGE as TEXTS

__all__ = ["TEXTS", "page_html"]


def page_html(lang: str, basemaps: list[dict[str, Any]] | None = None,
              default: str = "none") -> str:
    """The page in ``lang`` (``"en"`` or ``"ru"``) offering the background maps ``basemaps``
    (:meth:`scanplan.web.basemap.Basemaps.page_list`; "none" always) with ``default`` shown
    first."""
    from pathlib import Path

    lang = lang if lang in TEXTS else "en"
    none = {"id": "none", "name": TEXTS[lang]["tiles_none"]}
    config = {"lang": lang, "texts": TEXTS[lang], "basemaps": [*(basemaps or []), none],
              "basemap_default": default, "version": __version__}
    text = (Path(__file__).parent / "static" / "index.html").read_text(encoding="utf-8")
    blob = json.dumps(config, ensure_ascii=False).replace("</", "<\\/")
    return (text.replace("{{lang}}", lang)
            .replace("{{title}}", html.escape(TEXTS[lang]["title"]))
            .replace("{{config}}", blob))
