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
    norms_mod.forget_read_sets()
    yield d
    norms_mod.forget_read_sets()


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




def _fuzz_counts() -> dict[str, int]:
    """This process's count of generated inputs per fuzz family (none: not run here)."""
    import sys

    return dict(getattr(sys.modules.get("test_fuzz"), "COUNTS", None) or {})


def _campaign() -> dict[str, dict[str, int]]:
    """This process's hostile-input campaign: inputs per kind, and outcomes
    (tests/test_campaign.py; none: not run here)."""
    import sys

    module = sys.modules.get("test_campaign")
    return {"campaign_counts": dict(getattr(module, "COUNTS", None) or {}),
            "campaign_outcomes": dict(getattr(module, "OUTCOMES", None) or {})}


def pytest_collection_modifyitems(config, items):
    """Mark the slow profile (tests/slow_profile.py) ``slow``; a listed test that its
    collected module does not define is a usage error (the list follows renames)."""
    from slow_profile import SLOW_MODULES, SLOW_TESTS

    modules = {}
    for item in items:
        module = item.path.stem
        modules.setdefault(module, getattr(item, "module", None))
        name = getattr(item, "originalname", item.name)
        if module in SLOW_MODULES or name in SLOW_TESTS.get(module, ()):
            item.add_marker(pytest.mark.slow)
    missing = [f"{m}::{n}" for m, obj in modules.items() if obj is not None
               for n in sorted(SLOW_TESTS.get(m, ())) if not hasattr(obj, n)]
    if missing:
        raise pytest.UsageError(f"tests/slow_profile.py names tests that do not exist: {missing}")


def pytest_sessionfinish(session, exitstatus):
    """A pytest-xdist worker hands its fuzz and campaign counts to the controller."""
    if hasattr(session.config, "workeroutput"):
        session.config.workeroutput["fuzz_counts"] = _fuzz_counts()
        session.config.workeroutput.update(_campaign())


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error):
    """The controller adds up the fuzz and campaign counts of its pytest-xdist workers."""
    output = getattr(node, "workeroutput", None) or {}
    for key, stash in (("fuzz_counts", _WORKER_COUNTS), ("campaign_counts", _CAMPAIGN),
                       ("campaign_outcomes", _OUTCOMES)):
        counts = node.config.stash.setdefault(stash, {})
        for family, n in output.get(key, {}).items():
            counts[family] = counts.get(family, 0) + n


_WORKER_COUNTS = pytest.StashKey[dict]()
_CAMPAIGN = pytest.StashKey[dict]()
_OUTCOMES = pytest.StashKey[dict]()


def _campaign_summary(terminalreporter, config) -> None:
    """Print the hostile-input campaign: inputs per kind and every outcome counted."""
    own = _campaign()
    totals = []
    for key, stash in (("campaign_counts", _CAMPAIGN), ("campaign_outcomes", _OUTCOMES)):
        counts = dict(own[key])
        for family, n in config.stash.get(stash, {}).items():
            counts[family] = counts.get(family, 0) + n
        totals.append(counts)
    counts, outcomes = totals
    if not counts:
        return
    terminalreporter.write_sep("-", f"hostile-input campaign: {sum(counts.values()):,} inputs")
    for family, n in sorted(counts.items()):
        terminalreporter.write_line(f"  {family:<36} {n:>6,}")
    for name in ("tracebacks", "connections", "bytes lost", "litter left"):
        outcomes.setdefault(name, 0)
    terminalreporter.write_line("  outcomes: " + ", ".join(
        f"{name} {n:,}" for name, n in sorted(outcomes.items())))


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    """Print how many generated inputs the fuzz suite ran (at least 1,000), over all
    workers when the tests run in parallel (``-n``)."""
    import os

    _campaign_summary(terminalreporter, config)
    counts = _fuzz_counts()
    for family, n in config.stash.get(_WORKER_COUNTS, {}).items():
        counts[family] = counts.get(family, 0) + n
    if not counts:
        return
    total = sum(counts.values())
    profile = "long" if os.environ.get("SCANPLAN_FUZZ") == "long" else "fast"  # test_fuzz.LONG
    terminalreporter.write_sep("-", f"fuzz: {total:,} generated inputs ({profile} profile)")
    for family, n in sorted(counts.items()):
        terminalreporter.write_line(f"  {family:<36} {n:>6,}")


@pytest.fixture(autouse=True)
def no_user_configuration(tmp_path_factory, monkeypatch):
    """No test reads the developer's own configuration file (organisation, locale)."""
    if "SCANPLAN_CONFIG" not in __import__("os").environ:
        missing = tmp_path_factory.getbasetemp() / "no-user-config.toml"
        monkeypatch.setenv("SCANPLAN_CONFIG", str(missing))
