"""The rules of the ground-control layout: ``norms/catalogue/control-rules.csv``.

No Russian norm read gives the number or the layout of ground control points for a UAV
block (docs/control.md lists what was read), so these rules are not part of a norm set:
each row is a foreign recommendation (``foreign``), an estimate of a published study
(``estimate``), common practice (``practice``) or an assumption of scanplan's own
(``assumption``), with its source — the reports print every rule with that status. An
update is an edit of the file, not of the code.

>>> rules = control_rules()
>>> rules["asprs_checkpoints"].value, rules["asprs_checkpoints"].status
(30.0, 'foreign')
>>> rules["eea_control_ratio_min"].value, rules["eea_control_ratio_recommended"].value
(3.0, 5.0)
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass
from functools import lru_cache

from .citations import modern_citation
from .paths import CATALOGUE, bundled_norms_dir

__all__ = ["CONTROL_RULES", "CONTROL_STATUSES", "ControlRule", "control_rules"]

CONTROL_STATUSES = ("foreign", "estimate", "practice", "assumption")
"""What a control rule is: a foreign recommendation, an estimate of a study, practice, or
scanplan's own assumption — never a norm."""

CONTROL_RULES = ("asprs_checkpoints", "asprs_checkpoints_area_km2", "asprs_control_ratio",
                 "eea_control_ratio_min", "eea_control_ratio_recommended",
                 "interior_gcp_per_ha", "inset_footprint", "check_separation",
                 "rtk_interior_gcps", "max_marker_slope_pct")
"""Every rule the layout reads (the file must give each, positive and finite)."""


@dataclass(frozen=True)
class ControlRule:
    """One rule: its value [unit], source, status (:data:`CONTROL_STATUSES`) and note."""

    name: str
    value: float
    unit: str
    source: str
    status: str
    note: str


@lru_cache(maxsize=1)
def control_rules() -> dict[str, ControlRule]:
    """The bundled rules, by name (read once).

    Raises
    ------
    RuntimeError
        The bundled file is broken (a broken installation, not a user error).
    """
    path = bundled_norms_dir() / CATALOGUE / "control-rules.csv"
    text = path.read_text(encoding="utf-8")
    out: dict[str, ControlRule] = {}
    for i, row in enumerate(csv.DictReader(io.StringIO(text, newline="")), start=2):
        name = (row.get("name") or "").strip()
        try:
            value = float(row.get("value") or "nan")
        except ValueError:
            value = math.nan
        status = (row.get("status") or "").strip()
        if name not in CONTROL_RULES or not (math.isfinite(value) and value > 0) \
                or status not in CONTROL_STATUSES:
            raise RuntimeError(f"{path}:{i}: a control rule needs a known name, a positive "
                               f"value and a status of {', '.join(CONTROL_STATUSES)}")
        out[name] = ControlRule(name, value, (row.get("unit") or "").strip(),
                                modern_citation((row.get("source") or "").strip()), status,
                                (row.get("note") or "").strip())
    missing = set(CONTROL_RULES) - set(out)
    if missing:
        raise RuntimeError(f"{path}: missing control rules {sorted(missing)}")
    return out
