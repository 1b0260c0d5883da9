"""Bundled norm sets: loaded at run time, normative numbers from data, not code."""

from __future__ import annotations

import ast
import shutil
from pathlib import Path

import pytest

import scanplan
from scanplan.errors import InputError, NotFoundError
from scanplan.norms import bundled_norms_dir, list_norm_sets, load_norm_set

PKG = Path(scanplan.__file__).parent
ENGINE = ["rules/film.py", "rules/uav.py", "rules/registry.py", "rules/constraints.py",
          "rules/results.py"]
CORE = ["core/formulas.py", "norms/schema.py", "errors.py", *ENGINE]


def test_bundled_sets_load(norms, printed_norms):
    assert norms.parameters["pr_coefficient"] == 0.5
    assert printed_norms.parameters["pr_coefficient"] == 0.4
    assert norms.parameters["constraints"] == ("PS", "PZ", "PP", "PR", "PD", "GL")
    assert printed_norms.parameters["constraints"] == ("PS", "PZ", "PP", "PR")
    assert norms.shapes == {"circle": 0.97, "rectangle": 1.45, "angle": 1.58, "square": 1.72,
                            "wall": 2.78}
    assert [(o.map_scale, o.size_m) for o in norms.objects] == [
        (500, 0.15), (1000, 0.2), (2000, 0.2), (5000, 1.5), (10000, 2.2), (25000, 2.2)]
    assert all(norms.parameter_sources[k] for k in norms.parameters)
    names = {n for n, _ in list_norm_sets()}
    assert {"gkinp-02-036-02", "gkinp-02-036-02-printed"} <= names


def test_engine_reads_its_numbers_from_the_norm_set(tmp_path):
    """Change V_s and the 1:2000 object in a copy of the set: P_S and P_D follow."""
    src = bundled_norms_dir() / "gkinp-02-036-02"
    dst = tmp_path / "mine"
    shutil.copytree(src, dst)
    p = dst / "parameters.csv"
    p.write_text(p.read_text(encoding="utf-8").replace("planimetric_accuracy_mm,0.2,",
                                                        "planimetric_accuracy_mm,0.4,"),
                 encoding="utf-8")
    o = dst / "objects.csv"
    o.write_text(o.read_text(encoding="utf-8").replace(",0.20,circle", ",0.40,circle"),
                 encoding="utf-8")
    from scanplan.project.jobs import scan

    a = scan(map_scale=2000, relief_interval_m=0.5, photo_scales=[10000], camera="rc30-153")
    b = scan(map_scale=2000, relief_interval_m=0.5, photo_scales=[10000], camera="rc30-153",
             norms=str(dst))
    sa, sb = a.scenarios[0], b.scenarios[0]
    assert sb.constraint("PS").pixel_um == pytest.approx(2 * sa.constraint("PS").pixel_um)
    assert sb.constraint("PD").pixel_um == pytest.approx(2 * sa.constraint("PD").pixel_um)


def test_broken_user_set_names_file_and_row(tmp_path):
    dst = tmp_path / "bad"
    shutil.copytree(bundled_norms_dir() / "gkinp-02-036-02", dst)
    p = dst / "shapes.csv"
    p.write_text(p.read_text(encoding="utf-8").replace("1.45", "-1"), encoding="utf-8")
    with pytest.raises(InputError) as exc:
        load_norm_set(str(dst))
    assert "shapes.csv:3" in exc.value.field and "coefficient" in exc.value.field


def test_unknown_set():
    with pytest.raises(NotFoundError) as exc:
        load_norm_set("nope")
    assert "gkinp-02-036-02" in exc.value.message


def _imports(path: Path) -> set[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            out.add(node.module.split(".")[0])
    return out


@pytest.mark.parametrize("module", CORE)
def test_core_is_pure(module):
    """The core imports no I/O, CLI or report libraries (house style, after prysm)."""
    forbidden = {"click", "openpyxl", "weasyprint", "jinja2", "pandas", "matplotlib", "csv",
                 "tomllib", "json"}
    assert not (_imports(PKG / module) & forbidden)


def test_no_normative_numbers_in_the_engine():
    """The norm values (0.2 mm, k = 2, 70 µm, 0.5/0.4, 0.75, shape coefficients, object sizes)
    do not appear as literals in the formulas or the rules engine."""
    norm_literals = {0.2, 0.07, 0.4, 0.75, 0.97, 1.45, 1.58, 1.72, 2.78, 1.5, 2.2, 60.0,
                     150.0}
    for module in ("core/formulas.py", "rules/film.py", "rules/registry.py",
                   "rules/constraints.py"):
        tree = ast.parse((PKG / module).read_text(encoding="utf-8"))
        found = {n.value for n in ast.walk(tree)
                 if isinstance(n, ast.Constant) and isinstance(n.value, float)}
        assert not (found & norm_literals), (module, found & norm_literals)
