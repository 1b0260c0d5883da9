"""Every example printed by a ``--help`` runs (issue 13: ``plan --help`` advertised a
missing example file).

The examples are collected from the help text of every command and subcommand (lines
starting with ``scanplan``, ``\\`` continuations joined) and run in order in a scratch
folder holding a copy of ``examples/``, with an empty user norm directory. The files an
example presupposes the user has (``objects.csv``: a table they edited) are put there
first (also QGroundControl's ``CameraMetaData.json`` and a camera workbook); examples
that build on each other (template → validate → import → use) run in
that order.
"""

from __future__ import annotations

import json
import shlex
import shutil
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.norms import store as norms_mod

ROOT = Path(__file__).resolve().parent.parent


def _commands(cmd: click.Command, ctx: click.Context) -> list[tuple[str, click.Command]]:
    out = [(ctx.command_path, cmd)]
    if isinstance(cmd, click.Group):
        for name in cmd.list_commands(ctx):
            sub = cmd.get_command(ctx, name)
            assert sub is not None
            out += _commands(sub, click.Context(sub, info_name=name, parent=ctx))
    return out


def help_examples() -> list[tuple[str, str]]:
    """(command path, example line) for every example in every --help."""
    found: list[tuple[str, str]] = []
    root = click.Context(main, info_name="scanplan")
    for path, cmd in _commands(main, root):
        text = cmd.help or ""
        joined = text.replace("\\\n", " ")
        for raw in joined.splitlines():
            line = " ".join(raw.split())
            if raw[:1].isspace() and line.startswith("scanplan "):  # an indented example
                found.append((path, line))
    return found


EXAMPLES = help_examples()

# the order a user follows: write a template, check it, import it, then use it
_STAGES = (" norms template ", " norms validate ", " norms import ")


def _stage(line: str) -> int:
    for i, key in enumerate(_STAGES):
        if key in f" {line} ":
            return i
    return len(_STAGES)


def test_help_examples_are_found():
    paths = {p for p, _ in EXAMPLES}
    # every command that computes something shows an example
    for command in ("scanplan", "scanplan scan", "scanplan uav", "scanplan plan",
                    "scanplan init", "scanplan norms", "scanplan cameras"):
        assert command in paths, command
    assert len(EXAMPLES) >= 20


def test_every_help_example_runs(tmp_path, monkeypatch):
    work = tmp_path / "work"
    work.mkdir()
    shutil.copytree(ROOT / "examples", work / "examples")
    shutil.copy(ROOT / "norms" / "gkinp-02-036-02" / "objects.csv", work / "objects.csv")
    monkeypatch.chdir(work)
    monkeypatch.setenv("SCANPLAN_NORMS_DIR", str(tmp_path / "user-norms"))
    norms_mod.forget_read_sets()
    runner = CliRunner()
    # files the user brings: QGroundControl's camera list, a camera workbook of their own
    (work / "CameraMetaData.json").write_text(json.dumps([{
        "canonicalName": "Sony a7r IV 35mm", "brand": "Sony", "model": "a7r IV 35mm",
        "sensorWidth": 35.7, "sensorHeight": 23.8, "imageWidth": 9504, "imageHeight": 6336,
        "focalLength": 35, "landscape": True, "fixedOrientation": False,
        "minTriggerInterval": 1.0, "deprecatedTranslatedName": ""}]), encoding="utf-8")
    made = runner.invoke(main, ["norms", "template", "our-cameras.xlsx"], prog_name="scanplan")
    assert made.exit_code == 0, made.output
    seen: set[str] = set()
    ran = 0
    try:
        for _path, line in sorted(EXAMPLES, key=lambda e: _stage(e[1])):
            if line in seen:  # the same example in a group's and a command's help
                continue
            seen.add(line)
            argv = shlex.split(line)[1:]
            result = runner.invoke(main, argv, prog_name="scanplan")
            assert result.exit_code == 0, (line, result.output, result.exception)
            ran += 1
    finally:
        norms_mod.forget_read_sets()
    assert ran >= 20
    assert (work / "out" / "spec.pdf").is_file()  # plan ... --out out/


@pytest.mark.parametrize("missing", ["examples/lida-2000-film.toml"])
def test_no_help_names_a_missing_example(missing):
    for _path, line in EXAMPLES:
        for word in shlex.split(line):
            if word.startswith("examples/") and word.endswith(".toml"):
                assert (ROOT / word).is_file(), (line, word)
    assert missing not in " ".join(line for _, line in EXAMPLES)
