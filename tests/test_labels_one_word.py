"""One English label, one Russian word: the same English text under two keys (one per
renderer: workbook, PDF, terminal, CLI listings, web page) must read the same in Russian,
so a surveyor does not meet «Путевая скорость» in the PDF and «Скорость полёта» in the
workbook for the same ground speed.

The catalogues: the report labels (:data:`scanplan.i18n.labels.LABELS`, which merges
``labels_more`` and ``labels_geo``, and the carrier-specific ``AIRCRAFT_LABELS`` that
:func:`~scanplan.i18n.labels.t` consults first), the terminal and listing templates
(:data:`scanplan.i18n.labels_cli.CLI`), the terminal summary's area and terrain words
(:mod:`scanplan.reports.text`), the web page's texts (:data:`scanplan.web.page.TEXTS`) and the
constraint names of the registry (which :func:`t` falls back to). Texts are compared after
stripping surrounding whitespace; a trailing unit (", m") is part of the text. Two English
labels that mean different things must differ in English.
"""

from __future__ import annotations

from collections import defaultdict

from scanplan.i18n.labels import AIRCRAFT_LABELS, LABELS
from scanplan.i18n.labels_cli import CLI
from scanplan.reports import text as _text
from scanplan.rules.registry import CONSTRAINTS
from scanplan.web.page import TEXTS

CATALOGUES: dict[str, dict[str, dict]] = {
    "labels": LABELS,
    "aircraft": AIRCRAFT_LABELS,
    "cli": CLI,
    "text.area": _text._AREA_TEXT,
    "text.terrain": _text._TERRAIN_TEXT,
    "web": TEXTS,
}


def _pairs() -> list[tuple[str, str, str]]:
    """Every (English, Russian, where) of the catalogues; plural tuples are not labels."""
    out = []
    for name, cat in CATALOGUES.items():
        for key, en in cat["en"].items():
            ru = cat["ru"].get(key)
            if isinstance(en, str) and isinstance(ru, str):
                out.append((en.strip(), ru.strip(), f"{name}:{key}"))
    for cid, rec in CONSTRAINTS.items():
        out.append((rec.title("en").strip(), rec.title("ru").strip(), f"constraint:{cid}"))
    return out


def conflicts() -> dict[str, dict[str, list[str]]]:
    """English text → {Russian text: [where, …]} for the texts with two Russian words."""
    seen: dict[str, dict[str, list[str]]] = defaultdict(lambda: defaultdict(list))
    for en, ru, where in _pairs():
        seen[en][ru].append(where)
    return {en: dict(rus) for en, rus in seen.items() if len(rus) > 1}


def test_the_catalogues_are_read():
    pairs = _pairs()
    assert len(pairs) > 500
    wheres = {w.split(":")[0] for _, _, w in pairs}
    assert wheres == set(CATALOGUES) | {"constraint"}


def test_one_english_label_has_one_russian_text():
    found = conflicts()
    report = "\n".join(
        f"{en!r}: " + "; ".join(f"{ru!r} ({', '.join(ws)})" for ru, ws in rus.items())
        for en, rus in sorted(found.items()))
    assert not found, f"{len(found)} English labels with two Russian texts:\n{report}"


def test_ground_speed_is_putevaya_skorost():
    speeds = {ru for en, ru, _ in _pairs() if en == "Ground speed, m/s"}
    assert speeds == {"Путевая скорость, м/с"}
