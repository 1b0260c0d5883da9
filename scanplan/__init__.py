"""scanplan — photogrammetric scan and interpretation planner.

The Instruction GKINP (GNTA)-02-036-02 scan-pixel rules (with the corrected P_R
coefficient), the recognition model of Miheeva & Ilushenko (2015), and (for UAV cameras)
the MTF ground resolution of the UAS-FP paper (Russian, on the linear resolution on the
ground of UAV cameras), combined into a plan for a mapping contract.

The top-level functions (:mod:`scanplan.api`) — :func:`plan`, :func:`scan`, :func:`uav`,
:func:`batch` — return results with ``to_dict()`` (the ``--json`` document), ``to_frame()``
(pandas), ``write()`` and a notebook summary; :func:`sweep` returns a grid of UAV plans
as one DataFrame. They are imported on first use, so that
``import scanplan`` (and ``scanplan --help``) stays light: no numpy until a plan is asked
for.
"""

from __future__ import annotations

from typing import Any

from ._version import __version__
from .errors import InputError
from .offline import proj_offline

proj_offline()  # before any CRS is built, in every process that runs scanplan

__all__ = ["BatchResult", "InputError", "ProjectResult", "ScanResult", "UavResult",
           "__version__", "batch", "load_norm_set", "plan", "scan", "sweep", "uav"]

_LAZY = {"plan": "api", "scan": "api", "uav": "api", "sweep": "api", "batch": "api",
         "BatchResult": "api",
         "ProjectResult": "api", "ScanResult": "api", "UavResult": "api",
         "load_norm_set": "norms"}


def __getattr__(name: str) -> Any:
    """Import the API on first use (PEP 562)."""
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'scanplan' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
