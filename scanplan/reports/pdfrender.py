"""HTML to PDF: WeasyPrint, confined to the bundled assets (the renderer of :mod:`.pdf`).

This module is all a process needs to turn a report's HTML (:func:`scanplan.reports.pdfhtml.
render_html`) into PDF bytes, and imports nothing of the engine: the PDF worker
(:mod:`.pdfworker`) imports only this, while the parent plans and writes the HTML.

Safety: the renderer's URL fetcher (:class:`BundledAssetFetcher`) serves only ``data:`` URLs
and files inside the bundled templates folder — nothing a project file says can make
WeasyPrint read another local file or the network.
"""

from __future__ import annotations

import functools
import mimetypes
import os
from pathlib import Path
from typing import Any
from urllib.parse import unquote, urlsplit
from urllib.request import url2pathname

from . import _weasy, templates_dir

weasyprint = _weasy.load()  # first: the fast library search and font subsetting (_weasy)
from weasyprint.text.fonts import FontConfiguration  # noqa: E402
from weasyprint.urls import URLFetcher, URLFetcherResponse  # noqa: E402

__all__ = ["BundledAssetFetcher", "html_to_pdf", "warm_up"]


class BundledAssetFetcher(URLFetcher):  # type: ignore[misc]
    """A WeasyPrint URL fetcher that serves ``data:`` URLs and bundled assets, nothing else.

    A ``file:`` URL is served only if it resolves (symlinks followed) to a regular file
    strictly inside ``root``; every other URL (``http:``, ``https:``, ``ftp:``, other
    local files) raises :class:`ValueError`, which WeasyPrint reports as a warning and
    skips. Every URL asked for is recorded in :attr:`requested`, every refusal in
    :attr:`refused`.

    Parameters
    ----------
    root : path, optional
        The folder whose files may be read (default: :func:`templates_dir`).
    """

    def __init__(self, root: str | os.PathLike[str] | None = None) -> None:
        super().__init__(allowed_protocols=("data",), allow_redirects=False)
        self.root = Path(root if root is not None else templates_dir()).resolve(strict=True)
        self.requested: list[str] = []
        self.refused: list[str] = []

    def fetch(self, url: str, headers: Any = None) -> Any:
        """Serve ``url`` if it is a ``data:`` URL or a bundled file; else raise ValueError.

        Parameters
        ----------
        url : str
            An absolute URL.
        headers : mapping, optional
            Ignored (no network access is ever made).

        Returns
        -------
        weasyprint.urls.URLFetcherResponse
        """
        self.requested.append(url)
        scheme = url.split(":", 1)[0].lower() if ":" in url else ""
        if scheme == "data":
            return super().fetch(url)
        if scheme == "file":
            parts = urlsplit(url)
            if parts.netloc not in ("", "localhost"):
                return self._refuse(url, "remote file URL")
            try:
                path = Path(url2pathname(unquote(parts.path))).resolve(strict=True)
            except (OSError, RuntimeError, ValueError):
                return self._refuse(url, "no such bundled file")
            if path == self.root or not path.is_relative_to(self.root) or not path.is_file():
                return self._refuse(url, "outside the bundled templates")
            mime = mimetypes.guess_type(path.name)[0] or "application/octet-stream"
            if path.suffix == ".ttf":
                mime = "font/ttf"
            return URLFetcherResponse(path.as_uri(), path.read_bytes(),
                                      {"Content-Type": mime})
        return self._refuse(url, "only data: URLs and bundled assets are allowed")

    def _refuse(self, url: str, why: str) -> Any:
        self.refused.append(url)
        raise ValueError(f"scanplan report: refused to fetch {url!r} ({why})")


def html_to_pdf(html: str, url_fetcher: Any = None, *, fresh_fonts: bool = False) -> bytes:
    """The PDF of a report's HTML (A4; nothing is written).

    Parameters
    ----------
    html : str
        The document (:func:`scanplan.reports.pdfhtml.render_html`); relative URLs are
        the bundled templates folder's.
    url_fetcher : BundledAssetFetcher, optional
        Default a fresh :class:`BundledAssetFetcher`.
    fresh_fonts : bool, optional
        Fonts of their own for this document (a test's fetcher then sees every file the
        document asks for); default the process's fonts, kept from one report to the next.

    Returns
    -------
    bytes
        The PDF. With ``SOURCE_DATE_EPOCH`` set, identical input gives identical bytes.
    """
    fetcher = url_fetcher if url_fetcher is not None else BundledAssetFetcher()
    root = templates_dir().resolve()
    fonts = FontConfiguration() if fresh_fonts else _fonts(str(root))  # before the sheet
    sheets = []
    if not fresh_fonts and _STYLESHEET_LINK in html:  # the stylesheet parsed once
        html = html.replace(_STYLESHEET_LINK, "", 1)
        sheets = [_stylesheet(str(root), fonts)]
    doc = weasyprint.HTML(string=html, base_url=root.as_uri() + "/", url_fetcher=fetcher)
    return doc.write_pdf(pdf_identifier=True,  # type: ignore[no-any-return]
                         font_config=fonts, stylesheets=sheets)


_STYLESHEET_LINK = '<link rel="stylesheet" href="report.css">'
"""How a report's HTML names the bundled stylesheet (templates/report.html)."""


@functools.lru_cache(maxsize=2)
def _stylesheet(root: str, fonts: FontConfiguration) -> Any:
    """The bundled ``report.css``, parsed once per process (and its fonts registered with
    the process's fonts): WeasyPrint would parse it, and compile its selectors, for every
    document — about a tenth of a report's render.

    Given to WeasyPrint as a user stylesheet in place of the document's ``<link>``: the
    report's only other styles are its ``<style>`` (the page footer), which follows the
    link and so won over it before as it wins over a user stylesheet now, and the user
    agent's, which both override alike; the stylesheet has no ``!important``. The pages are
    the same (tests/test_fast_reports.py compares them as images). Kept per font
    configuration ``fonts``: its @font-face files are registered with those fonts.
    """
    path = Path(root) / "report.css"
    return weasyprint.CSS(string=path.read_text(encoding="utf-8"), base_url=path.as_uri(),
                          url_fetcher=BundledAssetFetcher(root), font_config=fonts)


def _temp() -> str:
    """The temporary folder WeasyPrint's font folder goes into (the run's folder:
    :mod:`scanplan.io.rundir`)."""
    import tempfile

    return tempfile.gettempdir()


def _fonts(root: str) -> FontConfiguration:
    """:func:`_font_config` of the templates folder ``root`` and the temporary folder, made
    again when the folder WeasyPrint keeps the fonts in has gone meanwhile (a run's
    folder removed, a temporary folder cleaned by another program): its cached fonts would
    name files that no longer exist."""
    fonts = _font_config(root, _temp())
    folder = getattr(fonts, "_folder", None)  # WeasyPrint's folder of @font-face files
    if folder is not None and not os.path.isdir(folder):
        _font_config.cache_clear()
        fonts = _font_config(root, _temp())
    return fonts


@functools.lru_cache(maxsize=2)
def _font_config(root: str, temp: str = "") -> FontConfiguration:
    """The fonts, ready for every PDF of this process (a batch renders many).

    A :class:`weasyprint.text.fonts.FontConfiguration` loads fontconfig's list of the
    system's fonts when made, and registers the bundled fonts of ``@font-face`` the first
    time a document names them, writing them into a folder of the temporary folder
    ``temp``; one per templates folder ``root``, temporary folder and process keeps both
    (and WeasyPrint's per-font caches) from one report to the next. A run's temporary
    folder is removed when the run ends (:mod:`scanplan.io.rundir`): the next run in the
    same process (a test's) gets fonts of its own.
    """
    del root, temp  # the cache key: another folder gets fonts of its own
    return FontConfiguration()


_WARM_UP_HTML = ("<!DOCTYPE html><html><head><meta charset='utf-8'>"
                 '<link rel="stylesheet" href="report.css"></head><body>'
                 "<p>Warm-up 0,5 м <strong>1:2000</strong></p></body></html>")


def warm_up() -> None:
    """Pay the first-use costs of a report ahead of it (:mod:`.pdfworker`, while the plan is
    made): a one-line document rendered with the process's fonts, so that fontconfig,
    Pango and both bundled faces are loaded, and the stylesheet parsed."""
    html_to_pdf(_WARM_UP_HTML)
