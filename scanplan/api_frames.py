"""The Python API's tables as :class:`pandas.DataFrame` (:mod:`scanplan.api`): the photo
centres of a flight layout and a batch summary's rows — typed columns, units in the names.

pandas is imported inside the functions only: ``import scanplan`` stays light.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

    from .project.spec import PlanResult

__all__ = ["SUMMARY_COLUMNS", "photos_frame", "summary_frame", "summary_row", "typed"]


def typed(frame: pd.DataFrame, strings: Iterable[str] = (), floats: Iterable[str] = (),
           flags: Iterable[str] = ()) -> pd.DataFrame:
    """Columns cast to pandas ``string``, ``float64`` (None → NaN) and ``boolean``: no
    object column, so frames of many results concatenate cleanly."""
    for col in strings:
        frame[col] = frame[col].astype("string")
    for col in floats:
        frame[col] = frame[col].astype("float64")
    for col in flags:
        frame[col] = frame[col].astype("boolean")
    return frame


def photos_frame(layout: Any) -> pd.DataFrame:
    """The photo centres of a flight layout, one row each (the columns of ``photos.csv``:
    :data:`scanplan.geo.layout.PHOTO_COLUMNS`, units in the names); numbering columns as
    integers. Empty, with those columns, when there is no layout.

    Examples
    --------
    >>> import scanplan
    >>> r = scanplan.uav(camera="dji-zenmuse-p1-35", height_m=100, area_m="300x400")
    >>> photos = r.photos
    >>> len(photos) == r.plan.flight["photos"], str(photos["strip"].dtype)
    (True, 'int64')
    """
    import numpy as np
    import pandas as pd

    from .geo.export.gis import photo_columns
    from .geo.layout import PHOTO_COLUMNS

    if layout is None:
        return pd.DataFrame({c: pd.Series(dtype="float64") for c in PHOTO_COLUMNS})
    ph = layout.photos
    frame = pd.DataFrame({c: np.asarray(ph[c]) for c in photo_columns(ph)})
    for col in ("photo", "strip", "index", "sortie"):
        if col in frame:
            frame[col] = frame[col].astype("int64")
    return frame


SUMMARY_COLUMNS = (
    "project", "file", "map_scale", "film_photo_scale", "film_scan_pixel_um",
    "film_scanner_pixel_um", "film_binding", "film_frames", "film_scanned_gigabytes",
    "uav_recommended_height_m", "uav_max_planned_height_m", "uav_binding", "uav_gsd_cm",
    "uav_photos", "warnings", "warning_codes")
"""The columns of a batch summary (``summary.csv``, ``summary.xlsx``, :meth:`BatchResult.
to_frame`): the headline figures of each specification, its warnings in words (in the
project's language) and, for a program that reads the summary, their codes."""


def summary_frame(rows: list[dict[str, Any]], columns: Iterable[str] = SUMMARY_COLUMNS
                  ) -> pd.DataFrame:
    """The summary rows as a DataFrame; whole-number columns (scales, frames, photos) as
    integers, blank where a project has none.

    Examples
    --------
    >>> frame = summary_frame([{"project": "A", "map_scale": 2000.0, "uav_photos": None}])
    >>> str(frame["map_scale"].dtype), frame.shape
    ('Int64', (1, 16))
    """
    import pandas as pd

    frame = pd.DataFrame(rows, columns=list(columns))
    whole = ("map_scale", "film_photo_scale", "film_frames", "uav_photos")
    for col in whole:
        values = frame[col].dropna()
        if all(isinstance(v, int | float) and float(v).is_integer() for v in values):
            frame[col] = frame[col].astype("Int64")
        else:
            frame[col] = frame[col].astype("float64")
    text = ("project", "file", "film_binding", "uav_binding", "warnings", "warning_codes",
            "error")
    return typed(frame, strings=[c for c in text if c in frame],
                  floats=[c for c in frame.columns if c not in text and c not in whole])


def summary_row(result: PlanResult) -> dict[str, Any]:
    """The batch summary row of one specification (:data:`SUMMARY_COLUMNS`).

    Examples
    --------
    >>> import scanplan
    >>> r = scanplan.plan({"map": {"scale": 2000, "relief_interval_m": 1.0},
    ...                    "uav": {"camera": "dji-zenmuse-p1-35"}})
    >>> row = summary_row(r.spec)
    >>> row["map_scale"], row["uav_binding"], row["film_photo_scale"]
    (2000, 'HC', None)
    """
    f, u = result.film, result.uav
    rec = f.recommended if f else None
    p = u.job.plan if u else None
    return {
        "project": result.meta.project, "file": str(result.project.path),
        "map_scale": result.project.map.scale,
        "film_photo_scale": rec.photo_scale if rec else None,
        "film_scan_pixel_um": rec.scan_pixel_um if rec else None,
        "film_scanner_pixel_um": rec.scanner_pixel_um if rec else None,
        "film_binding": rec.binding if rec else None,
        "film_frames": f.frames if f else None,
        "film_scanned_gigabytes": f.scanned_gigabytes if f else None,
        "uav_recommended_height_m": u.recommended_height_m if u else None,
        "uav_max_planned_height_m": u.max_height_m if u else None,
        "uav_binding": p.binding if p else None,
        "uav_gsd_cm": p.gsd_m * 100 if p else None,
        "uav_photos": p.flight.get("photos") if p else None,
        "warnings": _warning_words(result),
        "warning_codes": " ".join(dict.fromkeys(w.code for w in result.warnings)),
    }


def _warning_words(result: PlanResult) -> str:
    """The warnings of a specification as sentences in the project's language, each once,
    for the people who read a batch summary (the codes are a column of their own)."""
    from .reports.wording import sentence

    said = (sentence(w.text(result.meta.locale)) for w in result.warnings)
    return " ".join(dict.fromkeys(t for t in said if t))
