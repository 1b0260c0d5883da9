"""Error types shared by every layer.

``InputError`` is the one exception the command line turns into exit code 2: it always
names the offending field (option, project key or spreadsheet cell) and what is allowed.
``WriteError`` (disk full, no permission, an interrupted rename) is exit code 1: it names
the file being written and the operating system's reason.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TypeVar

T = TypeVar("T")


class InputError(ValueError):
    """Invalid user input.

    Parameters
    ----------
    field : str
        The option, key or cell the user must fix (``--photo-scale``, ``map.scale``,
        ``'Objects'!C7``).
    message : str
        What is wrong, including the allowed range.
    """

    def __init__(self, field: str, message: str) -> None:
        self.field = field
        self.message = message
        super().__init__(f"{field}: {message}")


class FieldValueError(ValueError):
    """A value a numeric model refuses, with the input it belongs to as a typed field.

    Raised by the array checks of the core (``height_m must be > 0 (got -1)``); the layers
    above turn it into an :class:`InputError` from ``field`` and ``message`` — never by
    splitting the text.

    Parameters
    ----------
    field : str
        The model argument (``pixel_um``, ``r_min``).
    message : str
        What is wrong, without the name (``must be > 0 (got -1)``).
    """

    def __init__(self, field: str, message: str) -> None:
        self.field = field
        self.message = message
        super().__init__(f"{field} {message}")


class NotFoundError(InputError):
    """A named thing (norm set, camera, scanner, shape) does not exist."""


class WriteError(OSError):
    """A report, template or norm set could not be written; the previous one is intact.

    An :class:`OSError` (``errno``, ``strerror`` and ``filename`` are set), so code that
    catches ``OSError`` keeps working; its message names what the user asked to write, not
    a temporary file: ``cannot write out/spec.pdf: No space left on device``.

    Parameters
    ----------
    path : str
        What was being written, as the user named it.
    reason : str
        The operating system's reason (``strerror``), e.g. ``No space left on device``.
    errno : int, optional
        The error number of the underlying :class:`OSError`.
    action : str
        The verb phrase before ``path`` (``"write"``, ``"write norm set 'x' to"``).
    note : str
        A further sentence, e.g. where a backup was kept when putting it back failed.
    """

    def __init__(self, path: str, reason: str, errno: int | None = None, *,
                 action: str = "write", note: str = "") -> None:
        super().__init__(errno, reason, path)
        self.path = path
        self.reason = reason
        self.action = action
        self.note = note

    @property
    def message(self) -> str:
        """``cannot ACTION PATH: REASON[; NOTE]``."""
        text = f"cannot {self.action} {self.path}: {self.reason}"
        return f"{text}; {self.note}" if self.note else text

    def __str__(self) -> str:
        return self.message

    @classmethod
    def from_os_error(cls, path: str, exc: OSError, *, action: str = "write",
                      note: str = "") -> WriteError:
        """Wrap ``exc`` (its ``strerror``, else its text) for ``path``."""
        reason = exc.strerror or str(exc) or type(exc).__name__
        return cls(path, reason, exc.errno, action=action, note=note)


class PdfEngineError(RuntimeError):
    """The PDF engine (WeasyPrint) cannot load here — the system's Pango library is
    missing — so no PDF can be made; every other document still can.

    Parameters
    ----------
    reason : str
        The library's own first line: what could not be loaded.
    how : str
        How to install what is missing on this platform.
    """

    def __init__(self, reason: str, how: str) -> None:
        super().__init__(reason, how)
        self.reason = reason
        self.how = how

    @property
    def message(self) -> str:
        """``no PDF written: the PDF engine (WeasyPrint) could not load (REASON); HOW``."""
        return (f"no PDF written: the PDF engine (WeasyPrint) could not load "
                f"({self.reason}); {self.how}")

    def __str__(self) -> str:
        return self.message


def pick_method(methods: Mapping[str, T], name: str, label: str = "method") -> T:
    """``methods[name]`` for a model dispatch table, or a ValueError listing the names.

    Parameters
    ----------
    methods : mapping
        Name → implementation (e.g. ``HEIGHT_PIXEL_METHODS``).
    name : str
        The requested method.
    label : str
        How the message names the choice (``"height formula"``).
    """
    try:
        return methods[name]
    except KeyError:
        raise ValueError(f"{label} must be one of {sorted(methods)} (got {name!r})") from None
