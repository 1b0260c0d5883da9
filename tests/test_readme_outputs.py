"""The terminal output the README and the docs show is what the commands print today (a
newcomer compares them; an outdated sample reads as a bug).

Every ```text block of README.md and docs/*.md that starts with ``$ scanplan …`` is run
(continuation lines ending in ``\\`` joined) in the repository's folder and its output
compared line by line; a block with a line ``...`` is abridged on purpose and only its
shown lines are checked to appear in order.
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main

ROOT = Path(__file__).resolve().parent.parent
_BLOCK = re.compile(r"```text\n(\$ scanplan .*?)```", re.S)


def readme_samples() -> list[tuple[str, list[str]]]:
    """(command, printed lines) of every terminal sample in README.md and docs/*.md."""
    samples = []
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    blocks = [b for page in pages for b in _BLOCK.findall(page.read_text(encoding="utf-8"))]
    for block in blocks:
        lines = block.splitlines()
        cmd = lines.pop(0)[2:]
        while cmd.endswith("\\"):
            cmd = cmd[:-1] + " " + lines.pop(0).strip()
        samples.append((" ".join(cmd.split()), lines))
    return samples


SAMPLES = readme_samples()


def test_readme_has_samples():
    assert len(SAMPLES) >= 3


@pytest.mark.parametrize(("command", "shown"), SAMPLES, ids=[c[:60] for c, _ in SAMPLES])
def test_readme_sample_is_current(command, shown, monkeypatch):
    monkeypatch.chdir(ROOT)
    result = CliRunner().invoke(main, shlex.split(command)[1:], prog_name="scanplan")
    assert result.exit_code == 0, result.output
    printed = result.stdout.rstrip("\n").splitlines()
    if "..." in shown:  # abridged: the lines shown appear in this order
        flat = " ".join(" ".join(printed).split())
        pos = 0
        for part in (p for p in shown if p != "..."):
            want = " ".join(part.split())
            found = flat.find(want, pos)
            assert found >= 0, (want, flat[pos:pos + 400])
            pos = found + len(want)
    else:
        assert printed == [line.rstrip() for line in shown]
