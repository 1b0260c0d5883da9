"""The vertical photo's formulas are computed in core/ only (docs/architecture.md).

The photo scale of a frame over its own ground, the ground pixel of a photo at its own
height, the height a GSD allows and what a scan pixel keeps of the resolving power are
named functions of :mod:`scanplan.core.photoscale`, each citing spec/formulas.md. Written
out again anywhere else they drift (two spellings of H = GSD·f/p differed in the last
bit). This test reads every module outside ``core/`` with :mod:`ast` and fails on an
arithmetic expression with the ingredients of one of them:

- a pixel and a focal length (GSD = p·H/f, H = GSD·f/p);
- a focal length and a photo scale, or a focal length and the factor 1000 between mm and m
  (Mc = H/f, H = Mc·f);
- a pixel and a photo scale (the scanned ground pixel P·Mc);
- a sensor or frame side with a height and a focal length, or with a photo scale (the
  footprint l·H/f, l·Mc);
- the resolving-power coefficient divided (R_eff = min(R, k_R/P)).

Arguments of a call are not looked into (passing ``pixel_um`` and ``focal_mm`` to a core
function is the point), nor text.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import scanplan

PKG = Path(scanplan.__file__).parent

#: Names that hold a photo scale denominator (Mc).
SCALE_NAMES = {"photo_scale", "photo_scales", "local_scale", "mc", "mc_min", "mc_max",
               "mc_lo", "mc_hi"}
#: Names that hold a height above ground.
HEIGHT_NAMES = {"height_m", "agl", "agl_m", "h_m", "alt", "altitude_m"}
#: The factor between mm and m, as a focal length in metres spells it.
MM_PER_M = {1000.0, 1e-3}


def _ingredients(node: ast.AST) -> tuple[set[str], set[float], set[str]]:
    """Lower-case names, numeric constants and operators of an expression, not looking
    into calls, subscripts' indices or f-strings."""
    names: set[str] = set()
    consts: set[float] = set()
    ops: set[str] = set()
    stack = [node]
    while stack:
        n = stack.pop()
        if isinstance(n, ast.Call | ast.JoinedStr | ast.Lambda):
            continue
        if isinstance(n, ast.Name):
            names.add(n.id.lower())
        elif isinstance(n, ast.Attribute):
            names.add(n.attr.lower())
        elif isinstance(n, ast.Constant) and isinstance(n.value, int | float) \
                and not isinstance(n.value, bool):
            consts.add(float(n.value))
        elif isinstance(n, ast.BinOp):
            ops.add(type(n.op).__name__)
        stack.extend(ast.iter_child_nodes(n))
    return names, consts, ops


def formula_kind(node: ast.AST) -> str | None:
    """Which core formula the arithmetic ``node`` computes again, or None."""
    names, consts, ops = _ingredients(node)
    focal = any("focal" in n for n in names)
    pixel = any("pixel" in n for n in names)
    scale = bool(names & SCALE_NAMES)
    side = any(n.startswith(("sensor_", "frame_")) or n == "side_mm" for n in names)
    if side and (scale or (focal and names & HEIGHT_NAMES)):
        return "l·H/f or l·Mc: core.photoscale.footprint_side_m / frame_side_on_ground_m"
    if focal and pixel:
        return ("GSD = p·H/f or H = GSD·f/p: core.photoscale.ground_pixel_m / "
                "height_for_ground_pixel_m")
    if focal and (scale or consts & MM_PER_M):
        return ("Mc = H/f or H = Mc·f: core.photoscale.photo_scale_at_height / "
                "height_at_photo_scale_m")
    if pixel and scale:
        return "P·Mc: core.photoscale.scanned_ground_pixel_m"
    if "pr_coefficient" in names and "Div" in ops:
        return "k_R/P: core.photoscale.effective_resolving_power_lpmm"
    return None


def recomputed(text: str) -> list[tuple[int, str, str]]:
    """(line, expression, formula) for every outermost arithmetic expression of the
    source ``text`` that recomputes a core formula."""
    tree = ast.parse(text)
    inner = {id(c) for n in ast.walk(tree) if isinstance(n, ast.BinOp)
             for c in ast.iter_child_nodes(n)}
    return [(n.lineno, ast.unparse(n), kind) for n in ast.walk(tree)
            if isinstance(n, ast.BinOp) and id(n) not in inner
            and (kind := formula_kind(n)) is not None]


OUTSIDE_CORE = sorted(p for p in PKG.rglob("*.py") if p.relative_to(PKG).parts[0] != "core")


@pytest.mark.parametrize("path", OUTSIDE_CORE, ids=lambda p: str(p.relative_to(PKG)))
def test_no_core_formula_outside_core(path):
    found = recomputed(path.read_text(encoding="utf-8"))
    assert not found, "\n".join(f"{path.relative_to(PKG)}:{line}: {expr}  → use {kind}"
                                for line, expr, kind in found)


@pytest.mark.parametrize("line", [
    "gsd = inp.pixel_um / 1000.0 * agl / inp.focal_mm",
    "h = g * inp.focal_mm / (inp.pixel_um / 1000.0)",
    "f_m = focal_mm / 1000.0",
    "mc = (alt - g) / focal_mm * 1000",
    "h_m = ft.mc * focal_mm / 1000.0",
    "gsd_cm = pixel_um * ft.mc / 1e4",
    "r = min(r0, rules.pr_coefficient / (pixel_um / 1000.0))",
    "fp = side_mm / focal_mm * agl * (1.0 - down)",
    "across = frame_width_mm * scenario.photo_scale / 1000.0",
    "b = (1 - p / 100) * inp.sensor_height_mm * inp.height_m / inp.focal_mm",
])
def test_the_scan_finds_a_formula_written_out(line):
    """The check can fail: each formula written out inline is found."""
    assert recomputed(line)


@pytest.mark.parametrize("line", [
    "gsd = ground_pixel_m(inp.pixel_um, agl, inp.focal_mm) * 100.0",
    "per_m = inp.sensor_width_mm / inp.focal_mm",
    "label = f'{inp.pixel_um} µm, f {inp.focal_mm} mm' + suffix",
])
def test_the_scan_leaves_calls_and_other_formulas(line):
    assert not recomputed(line)


def test_the_core_formulas_cite_the_spec():
    """Every public function of core/photoscale.py names its source in spec/formulas.md."""
    from scanplan.core import photoscale

    for name in photoscale.__all__:
        doc = getattr(photoscale, name).__doc__ or ""
        assert "formulas.md §" in doc, name
        assert "\n    Examples\n    --------\n" in doc, name
