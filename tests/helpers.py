"""Helpers shared by the tests (imported as ``helpers``; tests/ is on sys.path)."""

from __future__ import annotations

import contextlib
import dataclasses
import importlib
import sys
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

from scanplan.rules.film import ObjectSpec, ScanInputs, ScanRules


def circle(norms, size_m: float) -> ObjectSpec:
    return ObjectSpec("object", size_m, "circle", norms.shapes["circle"], "test")


def film_inputs(norms, *, map_scale, relief, photo_scales, size_m, frame=230.0, focal=153.0,
                r=40.0, overlap=60.0, **kw) -> ScanInputs:
    """Seed 001 Tables 1, 8, 9 camera by default: 23×23 cm, f 153 mm, R 40, 60 %."""
    return ScanInputs(map_scale=map_scale, relief_interval_m=relief,
                      photo_scales=tuple(photo_scales), focal_mm=focal, frame_width_mm=frame,
                      frame_along_mm=frame, resolving_power_lpmm=r, forward_overlap_pct=overlap,
                      object=circle(norms, size_m) if size_m else None, **kw)


def only(rules: ScanRules, *ids: str) -> ScanRules:
    return dataclasses.replace(rules, constraints=ids)


@contextlib.contextmanager
def script_module(folder: Path, name: str) -> Iterator[ModuleType]:
    """A script of the repository (``tools/``, ``benchmarks/``) imported as a module, its
    folder on ``sys.path`` only while it is in use."""
    sys.path.insert(0, str(folder))
    try:
        yield importlib.import_module(name)
    finally:
        sys.path.remove(str(folder))
