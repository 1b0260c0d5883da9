"""The page of ``scanplan serve`` in English and Russian.

The HTML (``static/index.html``) holds no words of its own: every text the page shows is a
key of :data:`TEXTS` (:data:`scanplan.i18n.labels_page.PAGE`), in both languages (a test
checks that both have every key), filled in by the script from the configuration this
module puts into the page.
"""

from __future__ import annotations

import html
import json

from .._version import __version__
from ..i18n.labels_page import PAGE as TEXTS

__all__ = ["TEXTS", "page_html"]



def page_html(lang: str, tiles: str = "osm") -> str:
    """The page in ``lang`` (``"en"`` or ``"ru"``) with the default tile layer ``tiles``
    (``"osm"``, ``"none"`` or a URL template with ``{z}/{x}/{y}``)."""
    from pathlib import Path

    lang = lang if lang in TEXTS else "en"
    config = {"lang": lang, "texts": TEXTS[lang], "tiles": tiles, "version": __version__}
    text = (Path(__file__).parent / "static" / "index.html").read_text(encoding="utf-8")
    blob = json.dumps(config, ensure_ascii=False).replace("</", "<\\/")
    return (text.replace("{{lang}}", lang)
            .replace("{{title}}", html.escape(TEXTS[lang]["title"]))
            .replace("{{config}}", blob))
