"""A CRS is usable only with the grids installed here: PROJ never downloads one for scanplan.

scanplan keeps PROJ's network off (:mod:`scanplan.offline`). A CRS whose every
transformation to WGS 84 needs a grid file that is not installed (a PROJ string with
``+nadgrids=…``, a CRS defined by a grid shift alone) cannot be planned in; without this
check PROJ would fail deep in the planning with an internal message. :func:`require_grids`
refuses it up front, naming the key and the grid, and saying how to install it. A CRS whose
most accurate transformation needs a missing grid but which has another one (a published
Helmert transformation: OSGB 36 without OSTN15) is planned with the best transformation
available, as every PROJ program does.
"""

from __future__ import annotations

import warnings
from typing import Any

from ..errors import InputError
from ..offline import proj_offline

__all__ = ["require_grids"]


def require_grids(crs: Any, field: str) -> None:
    """Refuse ``crs`` when no transformation to WGS 84 is available with the installed
    grids.

    Parameters
    ----------
    crs : pyproj.CRS
        A CRS the user gave (a key of the project, an area file's, a DEM's).
    field : str
        How the message names it (``crs``, ``plan_crs``, the file).

    Raises
    ------
    InputError
        Naming ``field``, the missing grid files and how to install them (exit 2).
    """
    import pyproj
    from pyproj.transformer import TransformerGroup

    proj_offline()
    if crs.is_engineering:
        return  # a local frame: no transformation to the Earth is asked of it
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # "best transformation is not available": said below
        try:
            group = TransformerGroup(crs, pyproj.CRS.from_epsg(4326), always_xy=True)
        except pyproj.exceptions.ProjError as exc:
            raise InputError(field, f"{crs.name} cannot be related to WGS 84: "
                             f"{str(exc)[:200]}".replace("\n", " ")) from None
    if group.transformers:
        return
    grids = sorted({g.short_name for op in group.unavailable_operations
                    for g in op.grids if not g.available})
    if not grids:
        raise InputError(field, f"{crs.name}: PROJ knows no transformation of it to WGS 84 "
                         "(give the CRS by its EPSG code)")
    names = ", ".join(grids)
    first = grids[0]
    label = crs.name if crs.name and crs.name != "unknown" else "the CRS"
    raise InputError(field, f"{label} needs the grid file{'s' if len(grids) > 1 else ''} "
                     f"{names}, which {'are' if len(grids) > 1 else 'is'} not installed here "
                     "(scanplan never downloads one); install it once with `pyproj sync "
                     f"--file {first}` (or PROJ's `projsync --file {first}`), or copy the "
                     f"file into {pyproj.datadir.get_user_data_dir()}, then plan again")
