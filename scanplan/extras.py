"""Optional parts of the install: what each extra brings and the check a feature makes
before it needs one.

``pip install scanplan`` (or ``pip install .``) plans film and UAV jobs over blocks and
contract polygons and writes every report and mission file. Two features bring large
libraries of their own and are extras:

- ``terrain`` — a DEM under the plan (``[terrain] dem``): rasterio reads the GeoTIFF,
  scipy builds its min/max pyramid and fills its voids;
- ``serve`` — the local web page (``scanplan serve``): fastapi, uvicorn, tomli-w.

``pip install "scanplan[terrain,serve]"`` (``".[test]"`` in a clone) brings both. A
feature whose extra is missing stops with exit code 2, naming the option or key that asked
for it, the extra and the pip command (:func:`require`).
"""

from __future__ import annotations

import importlib.util

from .errors import InputError

__all__ = ["EXTRAS", "missing", "require"]

EXTRAS = {
    "terrain": {"rasterio": "rasterio", "scipy": "scipy"},
    "serve": {"fastapi": "fastapi", "uvicorn": "uvicorn", "tomli_w": "tomli-w"},
}
"""Each extra → its modules: import name → the package's name on PyPI (pyproject.toml
lists the same packages under ``[project.optional-dependencies]``)."""


def missing(extra: str) -> list[str]:
    """The packages of ``extra`` that are not installed (empty: the extra is there)."""
    out = []
    for module, package in EXTRAS[extra].items():
        try:
            found = importlib.util.find_spec(module) is not None
        except (ImportError, ValueError):  # a module set to None, a broken package
            found = False
        if not found:
            out.append(package)
    return out


def require(extra: str, field: str, feature: str) -> None:
    """Stop (exit 2) unless every module of ``extra`` is installed.

    Parameters
    ----------
    extra : str
        ``"terrain"`` or ``"serve"`` (:data:`EXTRAS`).
    field : str
        The option or key that asked for the feature (``"[terrain] dem"``, ``"serve"``).
    feature : str
        What needs it, for the message ("a DEM").

    Raises
    ------
    InputError
        Naming ``field``, the missing modules, the extra and how to install it.
    """
    gone = missing(extra)
    if gone:
        raise InputError(field, f"{feature} needs scanplan's optional {extra!r} "
                         f"dependencies ({', '.join(gone)} not installed): "
                         f"pip install \"scanplan[{extra}]\" (in a clone: "
                         f"pip install \".[{extra}]\")")
