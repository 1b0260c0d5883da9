"""The command line's one error policy: commands raise, :func:`policy` turns what they
raise into the message a user reads and the exit code (docs/cli.md):

=====================================  ====  =============================================
raised                                 exit  said (stderr)
=====================================  ====  =============================================
:class:`~scanplan.errors.InputError`   2     ``error: FIELD: MESSAGE`` — the option, key or
                                             cell, and the allowed range; a norm import's
                                             problems one a line below it
:class:`Failed`                        its   ``error: LINE`` for each of its lines (a batch
                                       code  with bad projects, a PDF asked for and not made)
:class:`~scanplan.errors.WriteError`   1     ``error: cannot write PATH: REASON``
another exception (a bug, the          1     ``error: TYPE: TEXT (SCANPLAN_DEBUG=1 shows
environment)                                 details)`` — never a traceback, unless
                                             ``SCANPLAN_DEBUG`` is set
:class:`BrokenPipeError`               141   nothing (``| head`` went away)
:class:`KeyboardInterrupt`             1     ``Aborted!`` (as click says it)
click's usage errors                   2     click's own message
=====================================  ====  =============================================

With ``--json``, a command marked :func:`json_errors` (the ``norms`` commands) prints an
invalid input as a JSON document on stdout instead (:func:`error_document`: ``{"ok":
false, "error_count": N, "errors": [...], "errors_omitted": M}``, docs/norms.md), and a
failed write as that document before its message.

The policy is applied by the groups (:class:`PolicyGroup`: ``scanplan`` and ``scanplan
norms``, which also runs on its own); nothing else in the command line calls
``sys.exit``.
"""

from __future__ import annotations

import contextlib
import functools
import json
import os
from collections.abc import Callable, Iterator, Mapping
from typing import Any

import click

from ..errors import InputError, WriteError
from . import console

__all__ = ["EXIT_FAILURE", "EXIT_INPUT", "Failed", "PolicyGroup", "error_document",
           "failure_text", "json_errors", "policy"]

EXIT_INPUT = 2
"""Bad usage or invalid input."""
EXIT_FAILURE = 1
"""A runtime failure: a write, the environment, a bug."""

_JSON_KEY = "scanplan.json_errors"  # in click's ctx.meta, shared by every nested context


class Failed(Exception):
    """A command's outcome that is a failure, with its lines and exit code (the lines are
    said as ``error: LINE``)."""

    def __init__(self, lines: list[str], code: int = EXIT_FAILURE) -> None:
        super().__init__("; ".join(lines))
        self.lines, self.code = list(lines), code


def failure_text(exc: BaseException) -> str:
    """The one-line message of a runtime failure (exit 1)."""
    if isinstance(exc, WriteError):  # disk full, no permission, an interrupted rename
        return exc.message
    if isinstance(exc, OSError):  # another environment failure: name the file and the reason
        where = " -> ".join(os.fsdecode(f) if isinstance(f, str | bytes) else str(f)
                            for f in (exc.filename, exc.filename2) if f is not None)
        reason = exc.strerror or str(exc) or type(exc).__name__
        return f"{where + ': ' if where else ''}{reason} (SCANPLAN_DEBUG=1 shows details)"
    return f"{type(exc).__name__}: {exc} (SCANPLAN_DEBUG=1 shows details)"


def error_document(exc: BaseException) -> dict[str, Any]:
    """The ``--json`` error document of an :class:`InputError` (every problem of a norm
    import) or a :class:`WriteError`."""
    from .. import norms

    if isinstance(exc, norms.NormImportError):
        problems, total = list(exc.problems), exc.total
    elif isinstance(exc, InputError):
        problems, total = [norms.ImportProblem(exc.field, exc.message)], 1
    elif isinstance(exc, WriteError):
        reason = "; ".join(x for x in (exc.reason, exc.note) if x)
        problems, total = [norms.ImportProblem(exc.path, reason)], 1
    else:
        problems, total = [norms.ImportProblem("", failure_text(exc))], 1
    return {"ok": False, "error_count": total, "errors": [p.as_dict() for p in problems],
            "errors_omitted": total - len(problems)}


def _input_lines(exc: InputError, field_names: Mapping[str, str]) -> list[str]:
    """What an InputError says: the field as the user typed it, the message; a norm
    import's problems below it."""
    field = field_names.get(exc.field, exc.field)
    from ..norms import NormImportError  # the norm sets, only once a command failed

    if not isinstance(exc, NormImportError):
        return [f"error: {field}: {exc.message}"]
    from ..norms import format_problems

    head = exc.message.split("\n", 1)[0]
    return [f"error: {field}: {head}",
            *(f"  {line}" for line in format_problems(list(exc.problems), exc.total))]


def _debug_traceback() -> None:
    if os.environ.get("SCANPLAN_DEBUG"):
        import traceback

        traceback.print_exc()


@contextlib.contextmanager
def policy(ctx: click.Context, field_names: Mapping[str, str] | None = None) -> Iterator[None]:
    """Run a command's body under the policy (the module docstring's table).

    Parameters
    ----------
    ctx : click.Context
        The group's context (exits through it).
    field_names : mapping, optional
        An error's field → the option a user typed (``scanplan``'s commands: the input
        registry's names).
    """
    names = field_names or {}
    try:
        yield
    except BrokenPipeError:  # stdout's reader has gone (| head): stop quietly
        ctx.exit(console.closed_pipe())
    except KeyboardInterrupt:  # as click says it
        click.echo(err=True)
        raise click.exceptions.Abort() from None
    except (click.exceptions.ClickException, click.exceptions.Exit,
            click.exceptions.Abort, SystemExit):
        raise
    except InputError as exc:
        if not _said_as_json(ctx, exc):  # the document says it all
            for line in _input_lines(exc, names):
                click.echo(line, err=True)
        ctx.exit(EXIT_INPUT)
    except Failed as exc:
        for line in exc.lines:
            click.echo(f"error: {line}", err=True)
        ctx.exit(exc.code)
    except Exception as exc:  # a write, the environment or a bug: no traceback for users
        _debug_traceback()
        if isinstance(exc, WriteError):
            _said_as_json(ctx, exc)
        click.echo(f"error: {failure_text(exc)}", err=True)
        ctx.exit(EXIT_FAILURE)


def _said_as_json(ctx: click.Context, exc: BaseException) -> bool:
    """Print the error document on stdout when the command was run with ``--json`` (and
    marked :func:`json_errors`); whether it was."""
    if not ctx.meta.get(_JSON_KEY):
        return False
    click.echo(json.dumps(error_document(exc), ensure_ascii=False, indent=2))
    return True


def json_errors(command: Callable[..., Any]) -> Callable[..., Any]:
    """Mark a command whose ``--json`` (its ``as_json`` argument) also carries its errors,
    as :func:`error_document`."""
    @functools.wraps(command)
    def run(*args: Any, **kwargs: Any) -> Any:
        click.get_current_context().meta[_JSON_KEY] = bool(kwargs.get("as_json"))
        return command(*args, **kwargs)
    return run


class PolicyGroup(click.Group):
    """A group whose commands run under :func:`policy`; ``field_names`` name the fields of
    its errors as the user typed them."""

    field_names: Mapping[str, str] = {}

    def invoke(self, ctx: click.Context) -> Any:
        with policy(ctx, self.field_names):
            return super().invoke(ctx)
