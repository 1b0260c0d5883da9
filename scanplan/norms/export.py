"""A norm set as plain data (``scanplan norms show --json``)."""

from __future__ import annotations

import csv
from pathlib import Path
from typing import Any

from .citations import modern_citation
from .schema import PARAMETERS, TABLES, ValueSpec

# =========================================================================================
# Showing a set, and the template
# =========================================================================================


def raw_csv(path: Path) -> list[dict[str, str]]:
    if not path.is_file():
        return []
    with path.open(encoding="utf-8", newline="") as fh:
        return [{k: modern_citation(v) if isinstance(v, str) else v for k, v in r.items()}
                for r in csv.DictReader(fh)]


def _typed(text: object, spec: ValueSpec) -> Any:
    """A canonical text as the value a cell should hold (number or text)."""
    if text is None or text == "":
        return None
    if spec.kind == "int":
        return int(float(str(text)))
    if spec.kind == "float":
        return float(str(text))
    if spec.kind == "list" and isinstance(text, tuple | list):
        return ",".join(text)
    return str(text)


def _set_rows(ns: Any, catalogue: bool = True) -> dict[str, list[dict[str, Any]]]:
    """Table name → rows of typed values (numbers as numbers) of a loaded norm set."""
    raw_params = {r.get("name", ""): r for r in raw_csv(ns.path / "parameters.csv")}
    out: dict[str, list[dict[str, Any]]] = {"parameters": [], "shapes": [], "objects": []}
    for pname, spec in PARAMETERS.items():
        v = ns.parameters[pname]
        raw = raw_params.get(pname, {})
        out["parameters"].append(
            {
                "name": pname,
                "value": _typed(v, spec.value),
                "unit": raw.get("unit") or spec.value.unit,
                "source": ns.parameter_sources.get(pname, ""),
                "note": raw.get("note", ""),
                "status": ns.parameter_status.get(pname) or None,
            }
        )
    sh = TABLES["shapes"]
    for row in ns.shape_rows.values():
        out["shapes"].append({c.name: _typed(row.get(c.name, ""), c.value) for c in sh.columns})
    for o in ns.objects:
        out["objects"].append(
            {
                "map_scale": o.map_scale,
                "object": o.name,
                "object_ru": o.name_ru or None,
                "size_m": o.size_m,
                "shape": o.shape,
                "source": o.source or None,
                "status": o.status or None,
            }
        )
    if ns.gsd_limits:
        out["gsd_limits"] = [
            {"map_scale": g.map_scale, "area": g.area, "max_gsd_cm": g.max_gsd_cm,
             "source": g.source or None, "status": g.status or None}
            for g in ns.gsd_limits
        ]
    if not catalogue:
        return out
    cam_cols = [c.name for c in TABLES["cameras"].columns]
    out["cameras"] = [
        {k: (v if v != "" else None) for k, v in c.row().items() if k in cam_cols}
        for c in sorted(ns.cameras.values(), key=lambda c: c.id)
    ]
    out["scanners"] = [
        {
            "scanner": st.scanner,
            "name": st.name or None,
            "pixel_um": st.pixel_um,
            "bit_depth": st.bit_depth or None,
            "frame_scan_min": st.frame_scan_min,
            "note": st.note or None,
            "source": st.source or None,
        }
        for s in sorted(ns.scanner_details)
        for st in ns.scanner_details[s]
    ]
    return out


def norm_set_dict(ns: Any) -> dict[str, Any]:
    """A loaded :class:`scanplan.norms.NormSet` as plain JSON-ready data.

    Parameters
    ----------
    ns : NormSet

    Returns
    -------
    dict
        ``name``, ``title``, ``title_ru``, ``source``, ``path``, ``bundled``,
        ``imported_from``, ``imported_at``, ``parameters`` (name → value, unit, source,
        description) and ``shapes``, ``objects``, ``cameras``, ``scanners`` as row lists.
    """
    rows = _set_rows(ns)
    params = {
        r["name"]: {
            "value": (
                list(ns.parameters[r["name"]])
                if isinstance(ns.parameters[r["name"]], tuple)
                else ns.parameters[r["name"]]
            ),
            "unit": r["unit"],
            "source": r["source"],
            "description": PARAMETERS[r["name"]].description,
        }
        for r in rows.pop("parameters")
    }
    return {
        "name": ns.name,
        "title": ns.title,
        "title_ru": ns.title_ru,
        "source": ns.source,
        "path": str(ns.path),
        "bundled": ns.bundled,
        "imported_from": ns.imported_from,
        "imported_at": ns.imported_at,
        "parameters": params,
        **rows,
    }


