"""Norm sets: the schema, the bundled and user sets, and importing norm spreadsheets.

One module per concept (imports point down this list):

``schema``     the tables, columns, parameters and value rules of a norm set
``paths``      where the bundled sets and the user's norm directory are
``citations``  the papers' old names in norm files, read as authors and year
``recovery``   the norm directory lock; finishing an import a crash interrupted
``store``      finding, loading and caching norm sets and the camera/scanner catalogue
``limits``     the limits of an input file and the file check
``cells``      problems with cell addresses; a raw cell value to a checked value
``grid``       a sheet as cells: the header row and the data rows of a table
``xlsx``       reading .xlsx safely (zip directory first, no DTD, bounded parts)
``csvfile``    reading a one-table CSV
``importer``   a whole file to a checked :class:`ParsedNormSet`
``writer``     a checked set written as a user norm set
``export``     a norm set as plain data
``template``   the template workbook

Everything other modules use is re-exported here (``from scanplan.norms import X``). What
only importing a spreadsheet, writing a set or the template needs (``cells`` … ``template``)
is imported when first asked for, so a plan that only loads a set does not import the
spreadsheet readers.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from .limits import (
    HEADER_SCAN_ROWS,
    MAX_CELL_CHARS,
    MAX_CELLS,
    MAX_COLUMNS,
    MAX_COMPRESSION_RATIO,
    MAX_CSV_ROW_CHARS,
    MAX_ERRORS_SHOWN,
    MAX_FILE_BYTES,
    MAX_MEMBER_BYTES,
    MAX_MERGED,
    MAX_ROWS,
    MAX_SHEET_AREA,
    MAX_TOTAL_UNCOMPRESSED_BYTES,
    MAX_ZIP_DIRECTORY_BYTES,
    MAX_ZIP_MEMBERS,
    META_TABLE,
)
from .paths import CATALOGUE, DEFAULT_NORM_SET, bundled_norms_dir, user_norms_dir
from .recovery import recover_norm_dir
from .store import (
    PITCH_TOLERANCE,
    Camera,
    LensCurve,
    MapObject,
    NormSet,
    ScannerStep,
    cameras,
    did_you_mean,
    is_set_name,
    list_norm_sets,
    load_norm_set,
    parse_scale,
    read_norm_set_folder,
)

if TYPE_CHECKING:
    from .cells import ImportProblem, NormImportError, format_problems, parse_number
    from .export import norm_set_dict
    from .importer import ParsedNormSet, read_norm_file
    from .template import write_template
    from .writer import check_set_name, import_norm_file, write_norm_set

_LATER = {"ImportProblem": "cells", "NormImportError": "cells", "format_problems": "cells",
          "parse_number": "cells", "norm_set_dict": "export", "ParsedNormSet": "importer",
          "read_norm_file": "importer", "write_template": "template",
          "check_set_name": "writer", "import_norm_file": "writer",
          "write_norm_set": "writer"}
"""The re-exports imported on first use: name → module of this package."""


def __getattr__(name: str) -> Any:
    """A re-export of :data:`_LATER`, imported now (PEP 562)."""
    module = _LATER.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value

__all__ = [
    "CATALOGUE",
    "DEFAULT_NORM_SET",
    "HEADER_SCAN_ROWS",
    "MAX_CELLS",
    "MAX_CELL_CHARS",
    "MAX_COLUMNS",
    "MAX_COMPRESSION_RATIO",
    "MAX_CSV_ROW_CHARS",
    "MAX_ERRORS_SHOWN",
    "MAX_FILE_BYTES",
    "MAX_MEMBER_BYTES",
    "MAX_MERGED",
    "MAX_ROWS",
    "MAX_SHEET_AREA",
    "MAX_TOTAL_UNCOMPRESSED_BYTES",
    "MAX_ZIP_DIRECTORY_BYTES",
    "MAX_ZIP_MEMBERS",
    "META_TABLE",
    "PITCH_TOLERANCE",
    "Camera",
    "ImportProblem",
    "LensCurve",
    "MapObject",
    "NormImportError",
    "NormSet",
    "ParsedNormSet",
    "ScannerStep",
    "bundled_norms_dir",
    "cameras",
    "check_set_name",
    "did_you_mean",
    "format_problems",
    "import_norm_file",
    "is_set_name",
    "list_norm_sets",
    "load_norm_set",
    "norm_set_dict",
    "parse_number",
    "parse_scale",
    "read_norm_file",
    "read_norm_set_folder",
    "recover_norm_dir",
    "user_norms_dir",
    "write_norm_set",
    "write_template",
]
