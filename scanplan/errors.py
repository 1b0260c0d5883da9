"""Error types shared by every layer.

``InputError`` is the one exception the command line turns into exit code 2: it always
names the offending field (option, project key or spreadsheet cell) and what is allowed.
"""

from __future__ import annotations


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
