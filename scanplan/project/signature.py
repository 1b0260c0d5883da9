"""Keyword signatures and numpydoc parameter lists of the Python API, from the input registry.

``scanplan.uav(...)`` and ``scanplan.scan(...)`` take the inputs of the registry
(:mod:`scanplan.project.inputs`) as keywords. Their :class:`inspect.Signature` (what
``help()``, completion and ``inspect.signature`` show) and the *Parameters* section of
their docstrings are generated here from the engine functions' keywords
(:func:`scanplan.project.jobs.uav_job`, ``scan_job``) and the registry's help text and
units, so neither is written twice.

Numbers are taken as :class:`numbers.Real` (``np.int64``, ``np.float32``, ``Fraction``)
and handed to the engine as Python ``int`` / ``float`` (:func:`plain`).

>>> import numpy as np
>>> plain({"height_m": np.int64(100), "photo_scales": [np.float32(8000)]})
{'height_m': 100, 'photo_scales': [8000.0]}
"""

from __future__ import annotations

import inspect
import numbers
import textwrap
from collections.abc import Callable, Mapping
from typing import Any

from .inputs import Input, get

__all__ = ["parameters_doc", "plain", "registry_signature"]

_TYPES = {"number": "Real", "int": "Integral", "scale": "Real or str", "scales":
          "iterable of Real or str", "str": "str", "date": "datetime.date or str"}
_UNITLESS = {"number": "none (a ratio or coefficient)", "int": "none (a count)",
             "scale": "none (a scale denominator)", "scales": "none (scale denominators)"}
_EXTRA = {  # engine keywords that are not registry inputs (objects, not values)
    "area": ("scanplan.geo.layout.Area, optional", "the area to cover as a polygon "
             "(:func:`scanplan.geo.area.load_area`); lays the strips and photo centres out"),
    "layout_options": ("scanplan.project.flightplan.LayoutOptions, optional",
                       "flight direction, turns and sorties of the layout"),
    "curves": ("bool, optional", "False: the plan without its curves for plots (GSD and L "
               "against the height, the MTF at the planned height), where only its figures "
               "are asked; default True"),
}


def plain(value: Any) -> Any:
    """``value`` with every real number as a Python ``int`` (integral) or ``float``, in
    lists, tuples and dicts too; booleans and everything else unchanged."""
    if isinstance(value, bool) or type(value).__name__ == "bool_":
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, numbers.Real):
        return float(value)
    if isinstance(value, list | tuple):
        return type(value)(plain(v) for v in value)
    if isinstance(value, Mapping):
        return {k: plain(v) for k, v in value.items()}
    return value


def _annotation(rec: Input | None, default: Any, original: Any) -> str:
    if rec is None:
        return str(original)
    text = {"number": "numbers.Real", "int": "numbers.Integral",
            "scale": "numbers.Real | str", "scales": "Iterable[numbers.Real | str]"}.get(
        rec.kind, "str")
    if rec.name == "norms":
        text = "str | os.PathLike[str]"
    elif rec.name == "pixel_um" and rec.kind == "number" and default == ():
        text = "Iterable[numbers.Real]"
    return f"{text} | None" if default is None or "None" in str(original) else text


def _record(name: str, plan: str) -> Input | None:
    try:
        return get(name, plan)
    except KeyError:
        return None


def registry_signature(engine: Callable[..., Any], plan: str,
                       returns: str) -> inspect.Signature:
    """The keyword-only signature of ``engine``'s inputs, typed from the registry.

    Parameters
    ----------
    engine : callable
        The engine function whose keywords are the inputs (``uav_job``, ``scan_job``).
    plan : str
        ``"uav"`` or ``"film"``: which registry records the names are read from.
    returns : str
        The return annotation shown.
    """
    params = [inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=p.default,
                                annotation=_annotation(_record(name, plan), p.default,
                                                       p.annotation))
              for name, p in inspect.signature(engine).parameters.items()]
    return inspect.Signature(params, return_annotation=returns)


def _unit(rec: Input) -> str:
    if rec.unit:
        return rec.unit
    return _UNITLESS.get(rec.kind, "")


def parameters_doc(engine: Callable[..., Any], plan: str) -> str:
    """The numpydoc *Parameters* section of ``engine``'s inputs: type, help, unit, default.

    Every numeric input states its unit (``Unit: m``; a ratio says so).
    """
    lines = ["Parameters", "----------"]
    for name, p in inspect.signature(engine).parameters.items():
        rec = _record(name, plan)
        if rec is None:
            kind, text = _EXTRA.get(name, ("object, optional", ""))
            lines.append(f"{name} : {kind}")
            lines += textwrap.wrap(text, 84, initial_indent="    ", subsequent_indent="    ")
            continue
        optional = p.default is not inspect.Parameter.empty
        kind = ("iterable of Real" if p.default == () else _TYPES.get(rec.kind, "str")) + (
            ", optional" if optional else "")
        text = rec.help[0].upper() + rec.help[1:]
        unit = _unit(rec)
        if unit:
            text += f". Unit: {unit}"
        if rec.choices:
            text += ". One of " + ", ".join(f'"{c}"' for c in rec.choices)
        if rec.by_carrier and rec.default is not None:
            text += f". Default {rec.default!r} on a UAV" + (f"; {rec.note}" if rec.note
                                                            else "")
        elif p.default not in (None, inspect.Parameter.empty, ()):
            text += f". Default {p.default!r}"
        elif rec.note:
            text += f". {rec.note[0].upper()}{rec.note[1:]}"
        lines.append(f"{name} : {kind}")
        lines += textwrap.wrap(text + ".", 84, initial_indent="    ",
                               subsequent_indent="    ")
    return "\n".join(lines)


#: The static type of each kind of input, as a type checker reads it (numbers as any
#: ``SupportsFloat``: ``int``, ``float``, ``np.float32``, ``Fraction``).
_STATIC = {"number": "SupportsFloat", "int": "SupportsIndex", "scale": "SupportsFloat | str",
           "scales": "Iterable[SupportsFloat | str]", "date": "datetime.date | str"}
_STATIC_EXTRA = {"area": "Area | None", "layout_options": "LayoutOptions | None",
                 "flown_band_m": "tuple[float, float] | None",
                 "laid_out": "FlightLayout | None", "limits": "UavPlan | None",
                 "curves": "bool"}
MARKERS = ("    # <typed signatures: python -m scanplan.project.signature scanplan/api.py>",
           "    # </typed signatures>")
"""The lines around the generated signatures in :mod:`scanplan.api`."""


def _static(name: str, plan: str, default: Any, original: Any) -> str:
    rec = _record(name, plan)
    if rec is None:
        return _STATIC_EXTRA.get(name, "Any")
    if rec.name == "norms":
        text = "str | os.PathLike[str]"
    elif rec.name == "pixel_um" and default == ():
        text = "Iterable[SupportsFloat]"
    elif rec.choices and rec.kind == "str":
        text = "Literal[" + ", ".join(repr(c) for c in rec.choices) + "]"
    else:
        text = _STATIC.get(rec.kind, "str")
    return f"{text} | None" if default is None or "None" in str(original) else text


def typed_stub(engine: Callable[..., Any], plan: str, name: str, returns: str) -> str:
    """The definition a type checker reads of the API function ``name``: every keyword
    of ``engine`` with its static type (from the registry) and ``...`` for its default.

    Parameters
    ----------
    engine : callable
        The engine function (``uav_job``, ``scan_job``).
    plan : str
        ``"uav"`` or ``"film"``.
    name : str
        The API function's name.
    returns : str
        Its return type.

    Returns
    -------
    str
        ``def name(*, kw: type = ..., …) -> returns: ...`` over lines of at most 100
        characters, indented for the ``if TYPE_CHECKING:`` block of :mod:`scanplan.api`.
    """
    params = []
    for key, p in inspect.signature(engine).parameters.items():
        default = "" if p.default is inspect.Parameter.empty else " = ..."
        params.append(f"{key}: {_static(key, plan, p.default, p.annotation)}{default}")
    lines = [f"    def {name}(", "            *,"]
    for param in params:
        lines.append(f"            {param},")
    lines.append(f"    ) -> {returns}: ...")
    return "\n".join(lines)


def typed_block() -> str:
    """The generated block of :mod:`scanplan.api`: the typed signatures of ``scan`` and
    ``uav`` between :data:`MARKERS`."""
    from .jobs import scan_job, uav_job

    return "\n".join([MARKERS[0], typed_stub(scan_job, "film", "scan", "ScanResult"),
                      "", typed_stub(uav_job, "uav", "uav", "UavResult"), MARKERS[1]])


if __name__ == "__main__":  # pragma: no cover - maintenance: regenerate the api's block
    import sys
    from pathlib import Path

    target = Path(sys.argv[1])
    text = target.read_text(encoding="utf-8")
    start = text.index(MARKERS[0])
    end = text.index(MARKERS[1]) + len(MARKERS[1])
    target.write_text(text[:start] + typed_block() + text[end:], encoding="utf-8")
