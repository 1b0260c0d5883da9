"""Limits of a norm file (module constants so tests and embedders can tighten them),
the file-size check, and the optional ``set`` sheet."""

from __future__ import annotations

from .schema import ColumnSpec, TableSpec, ValueSpec

# --- limits (module constants so tests and embedders can tighten them) --------------------
MAX_FILE_BYTES = 20 * 1024 * 1024
"""Largest input file accepted [bytes]."""
MAX_MEMBER_BYTES = 100 * 1024 * 1024
"""Largest uncompressed size of one member of an .xlsx (zip) [bytes]."""
MAX_TOTAL_UNCOMPRESSED_BYTES = 200 * 1024 * 1024
"""Largest total uncompressed size of an .xlsx [bytes]."""
MAX_COMPRESSION_RATIO = 200
"""Largest uncompressed/compressed ratio of a member bigger than 1 MB (zip bombs)."""
MAX_ROWS = 200_000
"""Most rows one sheet or CSV may have."""
MAX_ERRORS_SHOWN = 20
"""Problem lines a message shows before "+N more"."""
MAX_ERRORS_KEPT = 1000
"""Problems kept for ``--json`` (the total is always counted)."""
HEADER_SCAN_ROWS = 20
"""Rows searched for the header row."""
MAX_COLUMNS = 256
"""Rightmost column a value may be in (IV, Excel 2003's last); a norm table has 14 at most."""
MAX_CELLS = 3_000_000
"""Most filled cells one workbook or CSV may have (bounds the memory a file can take)."""
MAX_SHEET_AREA = 5_000_000
"""Most cells of one sheet's rectangle from A1 to its last row and column holding a value
(the spreadsheet library holds that rectangle whole: 200,000 rows × 25 columns)."""
MAX_MERGED = 1_000
"""Most merged cell ranges one sheet may have."""
MAX_CELL_CHARS = 32_767
"""Longest text one cell may hold (Excel's own limit)."""
MAX_CSV_ROW_CHARS = 1_000_000
"""Longest row of a CSV, all its lines [characters]."""
MAX_ZIP_MEMBERS = 10_000
"""Most parts (zip members) an .xlsx may have."""
MAX_PART_ELEMENTS = 100_000
"""Most XML elements in a workbook part other than a worksheet or the shared strings
(styles, workbook, relationships, ...; Excel itself keeps at most 64,000 cell styles)."""
MAX_STRINGS_ELEMENTS = 600_000
"""Most XML elements in the shared strings part: 200,000 distinct texts of up to three
elements each (about 5 s and 100 MB to read)."""
MAX_ZIP_DIRECTORY_BYTES = 2 * 1024 * 1024
"""Largest zip directory of an .xlsx [bytes] (checked before it is parsed)."""

XLSX_SUFFIXES = (".xlsx", ".xlsm")
CSV_SUFFIXES = (".csv", ".txt", ".tsv")

META_TABLE = TableSpec(
    "set",
    "set.toml",
    ("key",),
    (
        ColumnSpec("key", ValueSpec("text"), "title, title_ru or source", ("ключ", "поле")),
        ColumnSpec("value", ValueSpec("text", required=False), "its text", ("значение",)),
    ),
    required=False,
    title_ru="Набор",
    description="title, Russian title and source of the norm set",
)
"""The optional ``set`` sheet of a workbook: the set's title, title_ru and source."""
META_KEYS = ("title", "title_ru", "source")
