"""The ``scanplan`` command line (click): the top layer, it only parses options, calls the
project layer and prints or writes what the reports layer renders.

- :mod:`~scanplan.cli.main` — the ``scanplan`` group, ``scan``, ``uav`` and ``plan``;
- :mod:`~scanplan.cli.norms` — ``scanplan norms …``;
- :mod:`~scanplan.cli.cameras` — ``scanplan cameras …``;
- :mod:`~scanplan.cli.init` — ``scanplan init``.
"""

from .main import main

__all__ = ["main"]
