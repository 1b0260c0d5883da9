"""One English label, one Russian word: the same English text under two keys (one per
renderer: workbook, PDF, terminal, CLI listings, web page) must read the same in Russian,
so a surveyor does not meet «Путевая скорость» in the PDF and «Скорость полёта» in the
workbook for the same ground speed.

The catalogues: every one of :func:`scanplan.i18n.catalogues` (the report labels, the
carrier-specific wording, the terminal's templates and words, the page's texts) and the
constraint names of the registry (which :func:`~scanplan.i18n.labels.t` falls back to).
Texts are compared after stripping surrounding whitespace, the Russian with its first
letter in lower case (a table's row starts with a capital, a terminal's line does not); a
trailing unit (", m") is part of the text. Two English labels that mean different things
must differ in English.
"""

from __future__ import annotations

from collections import defaultdict

from scanplan.i18n import catalogues
from scanplan.rules.registry import CONSTRAINTS

CATALOGUES: dict[str, dict[str, dict]] = catalogues()


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
        seen[en][ru[:1].lower() + ru[1:]].append(where)  # «Отношение …» heads a row
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
