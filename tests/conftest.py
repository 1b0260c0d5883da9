"""Shared fixtures: the bundled norm sets and a helper to build engine inputs."""

from __future__ import annotations

import pytest

from scanplan.norms import load_norm_set
from scanplan.norms import store as norms_mod
from scanplan.rules.film import ScanRules


@pytest.fixture()
def user_dir(tmp_path, monkeypatch):
    """An empty user norm directory (``$SCANPLAN_NORMS_DIR``), the loader cache cleared."""
    d = tmp_path / "user-norms"
    d.mkdir()
    monkeypatch.setenv("SCANPLAN_NORMS_DIR", str(d))
    norms_mod._load_path.cache_clear()
    yield d
    norms_mod._load_path.cache_clear()


@pytest.fixture(scope="session")
def norms():
    """The bundled default norm set (GKINP with k_R = 0.5 and P_D)."""
    return load_norm_set("gkinp-02-036-02")


@pytest.fixture(scope="session")
def printed_norms():
    """The Instruction exactly as printed (k_R = 0.4, no P_D)."""
    return load_norm_set("gkinp-02-036-02-printed")


@pytest.fixture(scope="session")
def rules(norms) -> ScanRules:
    return norms.rules()


@pytest.fixture(scope="session")
def paper_rules(norms) -> ScanRules:
    """Seed 001's arithmetic: sqrt(-ln 0.75) taken as 0.53 (its constant 1.8302)."""
    return norms.rules(recognition_rounding="paper")




def pytest_terminal_summary(terminalreporter, exitstatus, config):
    """Print how many generated inputs the fuzz suite ran (issue 7: at least 1,000)."""
    import sys

    fuzz = sys.modules.get("test_fuzz")
    counts = getattr(fuzz, "COUNTS", None)
    if not counts:
        return
    total = sum(counts.values())
    profile = "long" if getattr(fuzz, "LONG", False) else "fast"
    terminalreporter.write_sep("-", f"fuzz: {total:,} generated inputs ({profile} profile)")
    for family, n in sorted(counts.items()):
        terminalreporter.write_line(f"  {family:<36} {n:>6,}")


@pytest.fixture(autouse=True)
def no_user_configuration(tmp_path_factory, monkeypatch):
    """No test reads the developer's own configuration file (organisation, locale)."""
    if "SCANPLAN_CONFIG" not in __import__("os").environ:
        missing = tmp_path_factory.getbasetemp() / "no-user-config.toml"
        monkeypatch.setenv("SCANPLAN_CONFIG", str(missing))
