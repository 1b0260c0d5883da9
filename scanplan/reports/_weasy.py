"""WeasyPrint, imported and tuned for scanplan's reports (issue 15: reports in under a second).

Two costs of WeasyPrint that do not depend on the document are cut here, and nothing else
about WeasyPrint changes:

* **The library search at import.** ``weasyprint.text.ffi`` opens GLib, Pango, HarfBuzz,
  fontconfig and PangoFT2 by trying several names per library (``libpango-1.0-0``,
  ``pango-1.0-0``, ``pango-1.0``, ``libpango-1.0.so.0`` ...); cffi hands each name that is
  not a file name to :func:`ctypes.util.find_library`, which on Linux runs ``ldconfig`` and
  then ``gcc`` and ``ld`` in subprocesses — about 0.3 s of a 0.6 s import, on every run.
  :func:`load` imports WeasyPrint with ``find_library`` answering "not found" at once, so
  WeasyPrint goes on to the names it also tries, the libraries' sonames
  (``libpango-1.0.so.0``), which the dynamic loader opens directly: the same libraries,
  found the way every program finds them. Should that fail (an unusual install that only
  ``find_library`` can see), the half-imported modules are dropped and WeasyPrint is
  imported again the ordinary way, so the result never differs from a plain import.
* **Font subsetting without HarfBuzz-Subset.** Where libharfbuzz-subset is missing,
  WeasyPrint 70 subsets the embedded fonts with fontTools and drops their ``GSUB`` and
  ``GPOS`` tables (a PDF needs neither). fontTools 4.68 reads both tables in full before
  dropping them (``_compact_layout_tables``): DejaVu Sans's kerning alone is some 37,000
  value records, 40–100 ms per font and PDF. :func:`_fonttools_subset` is WeasyPrint's
  method with the two tables removed *before* subsetting — the same options, the same
  output bytes (``tests/test_fast_reports.py`` compares them).

Only :func:`load` changes anything, and only in this process; it is idempotent.
"""

from __future__ import annotations

import contextlib
import io
import sys
from types import ModuleType
from typing import Any

__all__ = ["load"]

_LOADED: ModuleType | None = None
_ORIGINAL_SUBSET: Any = None  # WeasyPrint's own method, replaced by _fonttools_subset


@contextlib.contextmanager
def _no_find_library() -> Any:
    """``ctypes.util.find_library`` answers None at once (Linux only) while in the block."""
    if not sys.platform.startswith("linux"):
        yield
        return
    import ctypes.util

    original = ctypes.util.find_library
    ctypes.util.find_library = lambda name: None
    try:
        yield
    finally:
        ctypes.util.find_library = original


def _import_fast() -> ModuleType:
    """``import weasyprint`` with the soname-first library search; ordinary on failure."""
    if "weasyprint" in sys.modules:
        return sys.modules["weasyprint"]
    before = set(sys.modules)
    try:
        # WeasyPrint prints a help text to stdout when a library is not found; the ordinary
        # import below prints it again if it is true
        with _no_find_library(), contextlib.redirect_stdout(io.StringIO()):
            import weasyprint
        return weasyprint
    except (OSError, ImportError):
        for name in set(sys.modules) - before:  # the half-imported modules
            if name == "weasyprint" or name.startswith("weasyprint."):
                del sys.modules[name]
    import weasyprint

    return weasyprint


def _fonttools_subset(self: Any, to_unicode: Any, hinting: Any) -> None:
    """``weasyprint.pdf.fonts.Font._fonttools_subset`` (WeasyPrint 70, BSD licence) with
    ``GSUB`` and ``GPOS`` removed before subsetting instead of after (see the module
    docstring): the same options and the same bytes, without reading two tables that are
    dropped anyway."""
    from fontTools import subset
    from fontTools.ttLib import TTFont, TTLibError
    from weasyprint.logger import LOGGER

    full_font = io.BytesIO(self.file_content)
    options = subset.Options(
        retain_gids=True, passthrough_tables=True, ignore_missing_glyphs=True,
        hinting=hinting, desubroutinize=True, notdef_outline=bool(self.missing))
    options.drop_tables += ["GSUB", "GPOS", "SVG"]
    subsetter = subset.Subsetter(options)
    subsetter.populate(gids=to_unicode)
    try:
        ttfont = TTFont(full_font, fontNumber=self.index)
        for tag in ("GSUB", "GPOS"):
            if tag in ttfont:
                del ttfont[tag]
        subsetter.subset(ttfont)
    except TTLibError as exception:
        LOGGER.warning('Unable to subset "%s" with fontTools', self.family)
        LOGGER.debug("Original exception:", exc_info=exception)
    else:
        optimized_font = io.BytesIO()
        ttfont.save(optimized_font)
        self.file_content = optimized_font.getvalue()


def _patch_subset(weasyprint: ModuleType) -> None:
    """Install :func:`_fonttools_subset` on WeasyPrint 70's ``Font`` (another version keeps
    its own method)."""
    if not str(getattr(weasyprint, "__version__", "")).startswith("70."):
        return
    from weasyprint.pdf import fonts

    global _ORIGINAL_SUBSET
    font = getattr(fonts, "Font", None)
    if font is not None and hasattr(font, "_fonttools_subset"):
        if font._fonttools_subset is not _fonttools_subset:
            _ORIGINAL_SUBSET = font._fonttools_subset
        font._fonttools_subset = _fonttools_subset


def load() -> ModuleType:
    """WeasyPrint, imported the fast way and with the faster font subsetting (once).

    Returns
    -------
    module
        The ``weasyprint`` module.
    """
    global _LOADED
    if _LOADED is None:
        module = _import_fast()
        _patch_subset(module)
        _LOADED = module
    return _LOADED
