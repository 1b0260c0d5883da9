"""What every benchmark script hands to ``benchmarks/run.py``: a list of :class:`Result`.

Each ``bench_*.py`` script has ``measure(quick: bool) -> list[Result]``; ``run.py`` calls
them and prints one table. Importing this module also puts the repository root on
``sys.path``, so the scripts measure the working tree's ``scanplan`` even where the
package is not installed (``python benchmarks/bench_X.py`` from a fresh clone).

The ratio convention
--------------------
``ratio`` is the share of the target used up, so **ratio ≤ 1 means PASS** for every row:

* an upper bound (``comparison == "<="``, e.g. a time): ``ratio = measured / target``;
* a lower bound (``comparison == ">="``, e.g. a speed-up): ``ratio = target / measured``.

A ratio of 0.5 therefore means "twice as good as the target", 2.0 "twice as bad".
"""

from __future__ import annotations

import math
import os
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

COMPARISONS = ("<=", ">=")


@dataclass(frozen=True)
class Result:
    """One measured quantity of a benchmark, with its target.

    Parameters
    ----------
    name : str
        Row name, ``"<benchmark>"`` or ``"<benchmark>.<quantity>"`` (e.g.
        ``"norms_import.xlsx"``).
    value : float
        The measured value, in ``unit``. NaN counts as a failure.
    unit : str
        Unit of ``value`` and ``target`` (``"s"``, ``"ms"``, ``"x"``, ``"lines/mm"`` ...).
    target : float
        The bound the value must meet.
    comparison : {"<=", ">="}
        ``"<="``: ``value`` must not exceed ``target``; ``">="``: it must reach it.
    note : str, optional
        Free text for the notes under the table: the baseline, the sample size, where
        the target comes from.
    error : str or None, optional
        Set (to ``"Type: message"``) when the benchmark raised instead of measuring; the
        row is then shown as ERROR and never passes.
    timing : bool, optional
        True (default) for a speed; False for a correctness check measured alongside
        (e.g. the agreement of two solvers), which ``run.py --timing-advisory`` still
        treats as binding.
    """

    name: str
    value: float
    unit: str
    target: float
    comparison: str
    note: str = ""
    error: str | None = None
    timing: bool = True

    def __post_init__(self) -> None:
        if self.comparison not in COMPARISONS:
            raise ValueError(f"comparison must be one of {COMPARISONS}, got {self.comparison!r}")

    @property
    def ratio(self) -> float:
        """Share of the target used: ``value/target`` for ``<=``, ``target/value`` for ``>=``.

        Returns
        -------
        float
            ≤ 1 when the target is met; NaN when the value is NaN or the row is an error.
        """
        if self.error is not None or math.isnan(self.value):
            return math.nan
        num, den = (
            (self.value, self.target) if self.comparison == "<=" else (self.target, self.value)
        )
        if den == 0:
            return 0.0 if num == 0 else math.inf
        return num / den

    @property
    def passed(self) -> bool:
        """True when the row measured without error and its ratio is ≤ 1."""
        r = self.ratio
        return not math.isnan(r) and r <= 1.0

    @property
    def status(self) -> str:
        """``"PASS"``, ``"FAIL"`` or ``"ERROR"``."""
        if self.error is not None:
            return "ERROR"
        return "PASS" if self.passed else "FAIL"

    def as_dict(self) -> dict[str, Any]:
        """The row as plain JSON-ready data (NaN and infinities become ``None``)."""

        def clean(v: float) -> float | None:
            return v if math.isfinite(v) else None

        return {
            "name": self.name,
            "value": clean(self.value),
            "unit": self.unit,
            "target": clean(self.target),
            "comparison": self.comparison,
            "ratio": clean(self.ratio),
            "passed": self.passed,
            "status": self.status,
            "note": self.note,
            "error": self.error,
            "timing": self.timing,
        }


def error_result(name: str, exc: BaseException) -> Result:
    """The ERROR row for a benchmark ``name`` that raised ``exc``.

    Parameters
    ----------
    name : str
        The benchmark's name.
    exc : BaseException
        What it raised.

    Returns
    -------
    Result
        A row with a NaN value that fails, showing ``exc``'s type and message.
    """
    message = str(exc).strip().splitlines()
    text = f"{type(exc).__name__}: {message[0]}" if message else type(exc).__name__
    return Result(name, math.nan, "", math.nan, "<=", error=text)


def child_env() -> dict[str, str]:
    """The environment of a fresh process as a user's: compiled bytecode kept and used (as
    ``pip install`` leaves it; here in a folder of its own, not beside the sources) even
    where the shell says ``PYTHONDONTWRITEBYTECODE``, and no GDAL options this process set.

    Returns
    -------
    dict
        ``os.environ`` without ``GDAL_*``, ``CPL_*`` and ``PYTHONDONTWRITEBYTECODE``, with
        ``PYTHONPYCACHEPREFIX`` set.
    """
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("GDAL_", "CPL_")) and k != "PYTHONDONTWRITEBYTECODE"}
    env["PYTHONPYCACHEPREFIX"] = str(Path(tempfile.gettempdir()) / "scanplan-bench-pycache")
    return env
