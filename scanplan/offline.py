"""What scanplan keeps offline for itself: PROJ's network.

PROJ fetches the transformation grids it lacks from a CDN when its network is on — by
``PROJ_NETWORK=ON`` in the environment, a ``proj.ini``, or a program that switched it on.
scanplan makes no network request (docs/reliability.md): :func:`proj_offline` switches
PROJ's network off for the whole process — the environment (read by every PROJ context made
afterwards: pyproj's, and those of the GDAL inside pyogrio and rasterio, and inherited by
every worker and child process) and pyproj's own switch when pyproj is already imported —
whatever the environment said. ``import scanplan`` calls it, so it holds before any CRS is
built in any process that runs scanplan; the readers of user CRSs call it again
(:mod:`scanplan.geo.grids`), in case a program switched the network on after importing
scanplan.

A CRS whose transformation needs a grid that is not installed is then refused, naming it
(:func:`scanplan.geo.grids.require_grids`); a user who wants grids installs them once
(``pyproj sync --file NAME``, PROJ's ``projsync``) — docs/project-file.md.
"""

from __future__ import annotations

import os
import sys

__all__ = ["proj_offline"]


def proj_offline() -> None:
    """Switch PROJ's network off for this process and its children (idempotent, cheap:
    pyproj is not imported for it)."""
    os.environ["PROJ_NETWORK"] = "OFF"
    if "pyproj" in sys.modules:
        try:
            from pyproj.network import set_network_enabled
        except ImportError:  # pragma: no cover - a pyproj without the switch
            return
        set_network_enabled(False)
