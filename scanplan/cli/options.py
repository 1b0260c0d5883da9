"""Click options built from the input registry (:mod:`scanplan.project.inputs`).

An option of ``scanplan scan`` / ``scanplan uav`` takes its name, destination, type,
choices, default and help from the input's record; the commands only list which inputs
they take, in the order ``--help`` shows them. Nothing here imports numpy.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Iterable
from typing import Any

import click

from ..errors import InputError
from ..project.inputs import Input, describe, get, records

__all__ = ["DECIMAL", "SCALE", "DecimalType", "ScaleType", "decimal", "finite", "input_option",
           "text", "text_or_none", "unlisted_inputs"]

PLAN_OF = {"scan": "film", "uav": "uav"}
"""The plan (registry scope) of each command."""

NORM_INPUTS = ("norms", "object_size_m", "shape", "object_name", "probability",
               "height_formula")
"""The norm options of ``scan`` and ``uav``, in ``--help`` order."""
REPORT_INPUTS = ("locale", "name", "customer", "contractor", "approver_position",
                 "approver_name")
"""The registry inputs among the report options (title and approval block)."""


def unlisted_inputs(command: str, *listed: Iterable[str]) -> list[str]:
    """The registry's options of ``command`` that none of the ``listed`` groups, the norm
    options and the report options place: a new input record's option joins the command
    without a list to edit (it shows at the end of the command's inputs)."""
    placed = {*NORM_INPUTS, *REPORT_INPUTS}.union(*map(set, listed))
    plan = PLAN_OF[command]
    return list(dict.fromkeys(r.name for r in records(plan) if r.option
                              and plan in r.commands and r.name not in placed))


class ScaleType(click.ParamType):
    """A scale denominator: ``2000`` or ``1:2000``."""

    name = "SCALE"

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None
                ) -> float:
        from ..norms import parse_scale

        try:
            return parse_scale(value, param.opts[0] if param else "scale")
        except InputError as exc:
            self.fail(exc.message, param, ctx)


SCALE = ScaleType()


def decimal(text: str) -> float:
    """``text`` as a number, with a decimal point or one decimal comma (``"12,5"``).

    Raises
    ------
    ValueError
        Not a number.

    >>> decimal("12,5"), decimal(" 7.25 ")
    (12.5, 7.25)
    """
    text = text.strip()
    if text.count(",") == 1 and "." not in text:
        text = text.replace(",", ".")
    return float(text)


class DecimalType(click.ParamType):
    """A number written with a decimal point or a decimal comma (``0.5`` or ``0,5``, as a
    Russian keyboard types it); a comma is read as the decimal sign only when the number
    has no point and one comma (a thousands separator is never guessed).

    >>> DECIMAL.convert("0,5", None, None), DECIMAL.convert("1e3", None, None)
    (0.5, 1000.0)
    """

    name = "float"

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None
                ) -> float:
        if isinstance(value, int | float) and not isinstance(value, bool):
            return float(value)
        try:
            return decimal(str(value))
        except ValueError:
            self.fail(f"{value!r} is not a number (write 0.5 or 0,5)", param, ctx)


DECIMAL = DecimalType()


def finite(ctx: click.Context, param: click.Parameter, value: float | None) -> float | None:
    """A click callback: refuse NaN and infinities."""
    if value is not None and not math.isfinite(value):
        raise click.BadParameter(f"must be a finite number (got {value})", ctx, param)
    return value


def finite_each(ctx: click.Context, param: click.Parameter, values: tuple[float, ...]
                ) -> tuple[float, ...]:
    """:func:`finite` for a repeated option."""
    return tuple(finite(ctx, param, x) for x in values)  # type: ignore[misc]


def text(ctx: click.Context, param: click.Parameter, value: str) -> str:
    """Report text from an option: the same rule as in a project file."""
    from ..project.file import text_problem

    problem = text_problem(value) if value else None
    if problem:
        raise click.BadParameter(problem, ctx, param)
    return value


def text_or_none(ctx: click.Context, param: click.Parameter, value: str | None) -> str | None:
    """:func:`text` for an option without a default."""
    return None if value is None else text(ctx, param, value)


def _help(inp: Input) -> str:
    words = describe(inp, cli=True)
    if re.match(r"[a-z]+[ ,:;]", words):  # "k_R in …" and "sqrt(…" stay as written
        words = words[:1].upper() + words[1:]
    return words + "."


def _type(inp: Input) -> tuple[Any, Callable[..., Any] | None]:
    """The click type and callback of an input's kind."""
    if inp.choices:
        return click.Choice(list(inp.choices)), None
    if inp.kind in ("scale", "scales"):
        return SCALE, None
    if inp.kind == "number":
        return DECIMAL, finite
    if inp.kind == "int":
        from ..core.domains import DOMAINS

        d = DOMAINS[inp.domain]
        return click.IntRange(int(d.lo), int(d.hi)), None
    if inp.section == "project":
        return str, text
    return str, text_or_none if inp.name == "object_name" else None


def input_option(command: str, name: str, **overrides: Any) -> Callable[..., Any]:
    """The click option of input ``name`` for ``command`` (``"scan"`` or ``"uav"``).

    Parameters
    ----------
    command : str
        The command the option belongs to.
    name : str
        The input's Python name (the registry's).
    **overrides
        Click arguments that only this command needs (``required=True``).
    """
    inp = get(name, PLAN_OF[command])
    if command not in ("scan", "uav") or PLAN_OF[command] not in inp.commands:
        raise KeyError(f"{name} is not an option of {command}")
    kind, callback = _type(inp)
    default = None if inp.by_carrier else inp.default  # uav_job chooses by carrier
    if inp.choices and default is not None:
        default = str(default)
    if inp.section == "project" and default is None:
        default = ""
    kw: dict[str, Any] = {"type": kind, "help": _help(inp)}
    if callback is not None:
        kw["callback"] = callback
    if default is not None:
        kw["default"] = default
    if inp.kind == "scales":
        kw["multiple"] = True
    if inp.name == "pixel_um" and command == "scan":
        kw.update(multiple=True, callback=finite_each)
    if inp.name in COMPLETIONS:
        kw["shell_complete"] = COMPLETIONS[inp.name]
    kw.update(overrides)
    dest = inp.option.lstrip("-").replace("-", "_")
    same = dest == inp.name or inp.section == "project"  # --project-name → project_name
    decls = [inp.option] if same else [inp.option, inp.name]
    return click.option(*decls, **kw)


# -- shell completion ---------------------------------------------------------------------
# click completes the commands and options by itself (docs/cli.md, "Shell completion");
# these complete the values a user would otherwise look up: a camera id, a norm set, the
# outputs of --formats. Each imports what it reads only when a value is completed.


def complete_camera(ctx: Any, param: Any, incomplete: str) -> list[Any]:
    """The ids of the catalogue's cameras and scanners (``scanplan cameras list``)
    starting with ``incomplete``."""
    from click.shell_completion import CompletionItem

    from ..norms import load_norm_set

    norms = (ctx.params.get("norms") if ctx is not None else None) or "gkinp-02-036-02"
    try:
        ns = load_norm_set(norms)
    except Exception:
        return []
    ids = sorted(set(ns.cameras) | set(ns.scanner_details))
    return [CompletionItem(i, help=getattr(ns.cameras.get(i), "name", "")) for i in ids
            if i.startswith(incomplete)]


def complete_norms(ctx: Any, param: Any, incomplete: str) -> list[Any]:
    """The names of the bundled and the user's norm sets (``scanplan norms list``)."""
    from click.shell_completion import CompletionItem

    from ..norms.store import list_norm_sets

    return [CompletionItem(name) for name, _ in list_norm_sets()
            if name.startswith(incomplete)]


def complete_formats(ctx: Any, param: Any, incomplete: str) -> list[Any]:
    """``--formats``: the outputs not yet in the comma-separated list, after it."""
    from click.shell_completion import CompletionItem

    from .outputs import FORMATS

    done, _, last = incomplete.rpartition(",")
    given = {x.strip() for x in done.split(",") if x.strip()}
    head = done + "," if done else ""
    return [CompletionItem(head + f) for f in FORMATS
            if f not in given and f.startswith(last.strip())]


#: The completion of an input's values, by its Python name.
COMPLETIONS = {"camera": complete_camera, "norms": complete_norms}
