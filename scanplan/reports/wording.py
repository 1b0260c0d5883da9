"""Human wording shared by the PDF and the workbook: parameter names with units, values,
camera/scanner/object names, dates — never a code identifier in a document.

A norm-set parameter is shown by its label ``param_<name>`` (name and unit in the report's
language) and its value in words (a shape by its name, the height formula by its form);
a parameter without a label (a user's norm set) falls back to its note, then its name.
"""

from __future__ import annotations

import datetime as _dt
import re
from typing import Any

from ..i18n.labels import LABELS, t
from ..i18n.messages import Message, localize
from ..norms import NormSet

__all__ = ["camera_title", "display_message", "document_date", "name_title", "object_title",
           "param_name", "param_value", "scanner_title", "sentence", "shape_title"]

_LOWER_WORD = re.compile(r"[a-z]+(?:-[a-z]+)*(?=[\s,:;]|$)")
_SENTENCE_END = ".!?…:"


def sentence(text: str) -> str:
    """An engine sentence as a printed document's sentence: a capital first letter and a
    full stop.

    The terminal prints English engine sentences after a ``!`` mark, lower case and without
    a full stop (``! motion blur 0.68 px …``); a document prints them after a heading or
    alone in a paragraph, where they read as sentences. Only a first word in plain lower
    case letters is capitalised (``motion`` → ``Motion``), never a symbol (``k_R``,
    ``σ_Z``) or a number; a text already ending in a sentence mark keeps it.

    Parameters
    ----------
    text : str
        The sentence (any locale: Russian catalogue sentences are already capitalised).

    Returns
    -------
    str
    """
    text = text.strip()
    if not text:
        return text
    if _LOWER_WORD.match(text):
        text = text[0].upper() + text[1:]
    if text[-1] not in _SENTENCE_END:
        text += "."
    return text


_PAREN_ENGLISH = re.compile(r"\s*\((?=[^)]*[A-Za-z]{4})[^)]*\)")


def _ru_model(name: str) -> str:
    """A catalogue model name for a Russian document: English remarks dropped, units in
    Russian (the model itself stays as the maker writes it)."""
    name = _PAREN_ENGLISH.sub("", name)
    name = re.sub(r"\bwith\b", "с", name)
    name = re.sub(r"(\d)\s*cm\b", r"\1 см", name)
    name = re.sub(r"(\d)\s*mm\b", r"\1 мм", name)
    return re.sub(r"(\d)x(\d)", r"\1×\2", name)


def camera_title(ns: NormSet, camera_id: str, locale: str, name: str = "") -> str:
    """The camera as a reader knows it: the catalogue's model name (not its id).

    Parameters
    ----------
    ns : NormSet
        The norm set whose catalogue holds the camera.
    camera_id : str
        The catalogue id (``""``: none).
    locale : {"en", "ru"}
        In Russian, English remarks in parentheses are dropped and units written in Russian.
    name : str, optional
        A name to show when the id is not in the catalogue (a camera given by its data).

    Returns
    -------
    str
    """
    cam = ns.cameras.get(camera_id) if camera_id else None
    if locale == "ru" and cam is not None and cam.name_ru:  # a Russian model in Cyrillic
        return cam.name_ru
    title = (cam.name if cam is not None else "") or name or camera_id
    return _ru_model(title) if locale == "ru" else title


def scanner_title(ns: NormSet, scanner_id: str, locale: str) -> str:
    """The scanner's model name (not its id)."""
    title = ns.scanner_names.get(scanner_id, "") or scanner_id
    return _ru_model(title) if locale == "ru" else title


def shape_title(ns: NormSet, shape: str, locale: str) -> str:
    """A shape in words: "circle" / "круг" (the norm set's Russian name)."""
    if locale == "ru":
        return ns.shape_rows.get(shape, {}).get("name_ru") or _label_or(
            f"shape_{shape}", locale, shape)
    return shape


def object_title(obj: Any, locale: str) -> str:
    """The object to interpret (anything with ``name`` and ``name_ru``) by name in the
    report's language; an object given only by its size is "the object of the given size".
    """
    return name_title(getattr(obj, "name", "") or "", getattr(obj, "name_ru", "") or "",
                      locale)


def name_title(name: str, name_ru: str, locale: str) -> str:
    """An object's name in the report's language (see :func:`object_title`)."""
    if locale == "ru" and name_ru and name_ru != "объект":
        return name_ru
    if not name or name == "object":  # the engine's placeholder for a size-only object
        return t("obj_unnamed", locale)
    return name  # a norm table's or the user's own name, shown as written


def _label_or(key: str, locale: str, default: str) -> str:
    return t(key, locale) if key in LABELS["en"] else default


def with_status(text: str, status: str, locale: str) -> str:
    """A figure's source with what the figure is: ``"[3] (recommendation)"``.

    >>> with_status("[3]", "estimate", "ru"), with_status("[3]", "", "en")
    ('[3] (оценка)', '[3]')
    """
    if not status:
        return text
    word = t(f"status_{status}", locale)
    return f"{text} ({word})" if text else word


def object_status(ns: NormSet | None, obj: Any) -> str:
    """The status of a map object's norm row (matched by scale, name and size), or ""."""
    for o in getattr(ns, "objects", ()):
        if (o.map_scale, o.name, o.size_m) == (getattr(obj, "map_scale", None),
                                               getattr(obj, "name", None),
                                               getattr(obj, "size_m", None)):
            return o.status
    return ""


#: The label of each norm-set parameter (one without: its note, else its name).
_PARAM_LABELS = {
    "block_relief_flat_pct": "param_block_relief_flat_pct",
    "block_relief_hilly_pct": "param_block_relief_hilly_pct",
    "block_relief_mountain_pct": "param_block_relief_mountain_pct",
    "constraints": "param_constraints",
    "digital_height_formula": "param_digital_height_formula",
    "height_accuracy_fraction": "param_height_accuracy_fraction",
    "height_formula": "height_formula",
    "image_measurement_px": "image_measurement_px",
    "interpretation_max_lpmm": "param_interpretation_max_lpmm",
    "interpretation_min_lpmm": "param_interpretation_min_lpmm",
    "min_sun_elevation_deg": "param_min_sun_elevation_deg",
    "multi_ray": "param_multi_ray",
    "photoplan_resolution_mm": "param_photoplan_resolution_mm",
    "planimetric_accuracy_mm": "param_planimetric_accuracy_mm",
    "pr_coefficient": "param_pr_coefficient",
    "probability": "param_probability",
    "processing_loss_k": "param_processing_loss_k",
    "recognition_rounding": "param_recognition_rounding",
    "shape": "param_shape",
    "standard_forward_overlap_pct": "param_standard_forward_overlap_pct",
    "uav_max_height_m": "param_uav_max_height_m",
    "uav_uncontrolled_aerodrome_km": "param_uav_uncontrolled_aerodrome_km",
}
#: The label of each worded value of a norm-set parameter (another: as it is).
_VALUE_LABELS = {
    ("digital_height_formula", "normal_case"): "value_digital_height_formula_normal_case",
    ("digital_height_formula", "instruction"): "value_height_formula_instruction",
    ("digital_height_formula", "parallax"): "value_height_formula_parallax",
    ("height_formula", "instruction"): "value_height_formula_instruction",
    ("height_formula", "parallax"): "value_height_formula_parallax",
    ("multi_ray", "off"): "value_multi_ray_off",
    ("multi_ray", "strip"): "value_multi_ray_strip",
    ("recognition_rounding", "exact"): "value_recognition_rounding_exact",
    ("recognition_rounding", "paper"): "value_recognition_rounding_paper",
}


def param_name(ns: NormSet, key: str, locale: str) -> str:
    """A norm-set parameter by its human name with unit (its label, :data:`_PARAM_LABELS`).

    Parameters
    ----------
    ns : NormSet
        The norm set (for a parameter without a label: its note).
    key : str
        The parameter's schema name.
    locale : {"en", "ru"}

    Returns
    -------
    str
    """
    if key in _PARAM_LABELS:
        return t(_PARAM_LABELS[key], locale)
    note = getattr(ns, "parameter_notes", {}).get(key, "") if ns is not None else ""
    return note or key.replace("_", " ")


def _plain_number(x: Any, locale: str) -> str:
    """A number as it is (``g``), with the decimal comma in Russian."""
    text = f"{x:g}" if isinstance(x, float) else str(x)
    return text.replace(".", ",") if locale == "ru" else text


def param_value(ns: NormSet, key: str, value: Any, locale: str,
                number: Any = None) -> str:
    """A norm-set parameter's value in words (shape with its coefficient, height formula,
    rounding; a number through ``number``).

    Parameters
    ----------
    ns : NormSet
    key : str
        The parameter's schema name.
    value : object
        Its value.
    locale : {"en", "ru"}
    number : callable, optional
        Formats a number in the report's convention (default ``str``).

    Returns
    -------
    str
    """
    if number is None:  # the report's decimal sign all the same: 0.97 / 0,97
        number = lambda x: _plain_number(x, locale)  # noqa: E731
    if key == "shape" and isinstance(value, str):
        coef = ns.shapes.get(value)
        title = shape_title(ns, value, locale)
        return f"{title} (B = {number(coef) if number else coef})" if coef else title
    if isinstance(value, str):
        label = _VALUE_LABELS.get((key, value))
        return t(label, locale) if label else value
    if isinstance(value, list | tuple):
        return ("; " if locale == "ru" else ", ").join(
            number(v) if isinstance(v, int | float) and not isinstance(v, bool) else str(v)
            for v in value)
    if isinstance(value, bool):
        return t("yes" if value else "no", locale)
    return number(value) if number else str(value)


def display_message(msg: Any, ns: NormSet | None, locale: str) -> str:
    """An engine sentence in ``locale`` with ids (scanner, camera) shown by their names.

    Parameters
    ----------
    msg : Message or str
        The sentence (a plain string is returned as it is).
    ns : NormSet or None
        Where the ids are looked up (None: ids stay).
    locale : {"en", "ru"}

    Returns
    -------
    str
    """
    if isinstance(msg, Message) and ns is not None:
        params = dict(msg.params)
        changed = False
        if isinstance(params.get("scanner"), str) and params["scanner"]:
            params["scanner"] = scanner_title(ns, params["scanner"], locale)
            changed = True
        if isinstance(params.get("camera"), str) and params["camera"]:
            params["camera"] = camera_title(ns, params["camera"], locale)
            changed = True
        if changed:
            msg = Message(msg.code, params)
    return localize(msg, locale)


def document_date(when: _dt.date | str, locale: str) -> str:
    """A date as the document's convention writes it: 23.11.2026 (ru), 2026-11-23 (en)."""
    if isinstance(when, str):
        try:
            when = _dt.date.fromisoformat(when)
        except ValueError:
            return when
    return when.strftime("%d.%m.%Y") if locale == "ru" else when.isoformat()
