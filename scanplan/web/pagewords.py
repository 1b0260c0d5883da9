"""An input error as the page says it: next to the field, in the page's language, in the
documents' words rather than the project file's.

The command line's message names the project file, the key and its line
(``project.toml: uav.speed_ms (line 9): must be a finite number ≥ 0 and ≤ 500 m/s (got
-5)``): right in a terminal, wrong beside a field labelled *Ground speed*. The page gets,
with the command line's ``detail`` unchanged, ``key`` (``uav.speed_ms``, the field to mark),
``label`` (the field's name as the page shows it) and ``text`` (the message without the
file, the line, TOML syntax or Python's quotes, in the page's language). The common forms
of the checks' messages (:func:`scanplan.core.domains.check_range`,
:mod:`scanplan.project.keys`) are worded in both languages here; another message keeps the
command line's English words, its file and line taken out.
"""

from __future__ import annotations

import re
from typing import Any

__all__ = ["page_error"]

_FIELD = re.compile(r"(?:^|: )\[?([a-z_]+(?:\.[a-z_]+)*)\]?\.([a-z_0-9]+)(?: \(line \d+\))?$")
_SECTION = re.compile(r"(?:^|: )\[([a-z_.]+)\](?: \(line \d+\))?$")
_NUM = r"-?[\d.]+(?:e[-+]?\d+)?"
_RANGE = re.compile(rf"^must be a finite number (?P<rng>[>≥<≤] {_NUM}(?: and [<≤] {_NUM})?)"
                    r"(?: (?P<unit>[^()]+?))? \(got (?P<got>.*?)\)(?P<rest>.*)$", re.S)
_GOT = re.compile(r" \(got (.*)\)")

#: message → (English, Russian) for the fixed messages of the project file's type checks
_FIXED: dict[str, tuple[str, str]] = {
    "must be text (in quotes)": ("must be text", "должно быть текстом"),
    "must be a whole number": ("must be a whole number", "должно быть целым числом"),
    "must be a number": ("must be a number", "должно быть числом"),
    "must be a finite number (at most about 1.8e308)": (
        "must be a finite number", "должно быть конечным числом"),
    "must be a finite scale denominator like 2000": (
        "must be a scale denominator, e.g. 2000", "должен быть знаменатель масштаба, "
        "например 2000"),
    'must be a scale denominator like 2000 or "1:2000"': (
        "must be a scale denominator, e.g. 2000 or 1:2000",
        "должен быть знаменатель масштаба, например 2000 или 1:2000"),
    'must be a CRS like "EPSG:32637" or 32637': (
        "must be a coordinate system, e.g. EPSG:32637", "должна быть система координат, "
        "например EPSG:32637"),
    'must be an angle in degrees or "auto"': (
        "must be an angle in degrees, or auto", "должен быть угол в градусах или auto"),
    "must be a non-empty list of scales, e.g. [5000, 10000]": (
        "must be one or more scales, e.g. 5000, 10000",
        "должны быть один или несколько масштабов, например 5000, 10000"),
    'must be a list of finite scales like [5000, "1:10000"]': (
        "must be one or more scales, e.g. 5000, 10000",
        "должны быть один или несколько масштабов, например 5000, 10000"),
    "must be two finite numbers [lowest, highest], e.g. [120, 185]": (
        "must be two numbers, lowest and highest, e.g. 120, 185",
        "должны быть два числа, наименьшее и наибольшее, например 120, 185"),
    "must be [lowest, highest]: the first value may not exceed the second": (
        "must be the lowest, then the highest: the first may not exceed the second",
        "должны быть наименьшее, затем наибольшее: первое не может превышать второе"),
    "must be a date YYYY-MM-DD, e.g. 2025-06-01": (
        "must be a date YYYY-MM-DD, e.g. 2025-06-01",
        "должна быть дата ГГГГ-ММ-ДД, например 2025-06-01"),
}
_UNITS_RU = {"m": "м", "m/s": "м/с", "min": "мин", "s": "с", "mm": "мм", "µm": "мкм",
             "cm": "см", "h": "ч", "%": "%", "°": "°", "rad/s": "рад/с", "lines/mm": "мм⁻¹",
             "px": "пикс."}


def _key(field: str) -> str | None:
    """``section.key`` of an error's field (``project.toml: uav.speed_ms (line 9)``)."""
    m = _FIELD.search(field)
    return f"{m.group(1)}.{m.group(2)}" if m else None


def _label(key: str | None, locale: str) -> str:
    """The field's name as the page shows it (its label, else the key's words)."""
    if key is None:
        return ""
    from .page import TEXTS
    from .registry import input_rows

    section, _, name = key.rpartition(".")
    page = TEXTS.get(locale, TEXTS["en"]).get(f"lbl.{key}")
    if page:
        return page
    for row in input_rows(locale):
        if (row["section"], row["key"]) == (section, name):
            return str(row["label"] or label_from_help(row["help"]))
    return name.replace("_", " ")


def label_from_help(help_text: str) -> str:
    """A field's name from its help where the reports have no label: the help up to its
    unit, default or example, capitalised.

    >>> label_from_help("agreement block (customer): position")
    'Agreement block (customer): position'
    >>> label_from_help("bits per band (default 8)")
    'Bits per band'
    """
    head = re.split(r" \[| \(default|, e\.g\.|; | \(GOST", help_text, maxsplit=1)[0].strip()
    return head[:1].upper() + head[1:]


def _got(text: str) -> str:
    """A value as the user typed it: Python's quotes and list brackets taken away."""
    text = text.strip()
    if len(text) >= 2 and text[0] == text[-1] and text[0] in "'\"":
        text = text[1:-1]
    return text.replace("[", "").replace("]", "").replace("'", "")


def _words(message: str, locale: str) -> str:
    """The message in the page's language and words (see the module docstring)."""
    ru = locale == "ru"
    for fixed, (en_text, ru_text) in _FIXED.items():
        if message.startswith(fixed):
            got = _GOT.search(message[len(fixed):])
            tail = (f" ({'введено' if ru else 'got'} {_got(got.group(1))})" if got else "")
            return (ru_text if ru else en_text) + tail
    m = _RANGE.match(message)
    if m:
        rng = m.group("rng")
        unit = m.group("unit") or ""
        if ru:
            rng = rng.replace(" and ", " и ")
            unit = _UNITS_RU.get(unit, unit)
        head = f"{'должно быть' if ru else 'must be'} {rng}{' ' + unit if unit else ''}"
        got = _got(m.group("got"))
        return f"{head} ({'введено' if ru else 'got'} {got}){m.group('rest')}"
    return message


def page_error(field: str, message: str, locale: str) -> dict[str, Any]:
    """``key``, ``label`` and ``text`` of an input error for the page (module docstring).

    >>> e = page_error("project.toml: uav.speed_ms (line 9)",
    ...                "must be a finite number ≥ 0 and ≤ 500 m/s (got -5)", "ru")
    >>> e["key"], e["label"], e["text"]
    ('uav.speed_ms', 'Путевая скорость', 'должно быть ≥ 0 и ≤ 500 м/с (введено -5)')
    >>> page_error("project.toml: film.photo_scales (line 3)",
    ...            "must be a non-empty list of scales, e.g. [5000, 10000] (got [])", "en")["text"]
    'must be one or more scales, e.g. 5000, 10000 (got )'
    """
    key = _key(field)
    if key is None:
        m = _SECTION.search(field)
        key = None if m is None else m.group(1)
    return {"key": key, "label": _label(key, locale) if key and "." in key else "",
            "text": _words(message, locale)}
