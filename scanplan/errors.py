"""Error types shared by every layer.

``InputError`` is the one exception the command line turns into exit code 2: it always
names the offending field (option, project key or spreadsheet cell) and what is allowed.
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


class NotFoundError(InputError):
    """A named thing (norm set, camera, scanner, shape) does not exist."""


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
