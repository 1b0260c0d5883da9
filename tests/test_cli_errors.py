"""The command line's one error policy (scanplan/cli/errors.py): every command of the
click group, given a bad input, exits 2 with ``error: FIELD: …`` and no traceback; a
command's :class:`Failed` and a crash are turned into their exit codes in one place."""

from __future__ import annotations

import json

import click
import pytest
from click.testing import CliRunner

from scanplan.cli import errors
from scanplan.cli.main import main
from scanplan.cli.norms import norms as norms_group
from scanplan.errors import InputError, WriteError

FILM = ["--map-scale", "2000", "--photo-scale", "10000", "--camera", "afa-te-100"]

BAD = {
    "scanplan scan": (["scan", *FILM, "--relief", "-1"], "error: --relief: "),
    "scanplan uav": (["uav", "--camera", "canon-eos-5d-mark-ii-50", "--height-m", "-5"],
                     "error: --height-m: must be a finite number ≥ 1 and ≤ 20000 m"),
    "scanplan plan": (["plan", "nosuch.toml"], "error: nosuch.toml: cannot be read"),
    "scanplan init": (["init", "x.toml", "--map-scale", "2000"], "error: --relief: "),
    "scanplan serve": (["serve", "--tiles", "ftp://x"], "error: --tiles: "),
    "scanplan cameras list": (["cameras", "list", "--norms", "nosuch"],
                              "error: --norms: no norm set 'nosuch'"),
    "scanplan cameras show": (["cameras", "show", "nosuch"], "error: CAMERA_ID: "),
    "scanplan cameras import": (["cameras", "import", "bad.json"], "error: bad.json: "),
    "scanplan norms list": (["norms", "list", "--locale", "xx"], "Usage: "),
    "scanplan norms show": (["norms", "show", "nosuch"], "error: NAME: no norm set"),
    "scanplan norms validate": (["norms", "validate", "bad.csv"], "error: bad.csv: "),
    "scanplan norms import": (["norms", "import", "bad.csv", "--name", "x"],
                              "error: bad.csv: "),
    "scanplan norms template": (["norms", "template", "out.txt"], "error: FILE: "),
    "scanplan aircraft list": (["aircraft", "list", "--camera", "nosuch"], "error: --camera: "),
    "scanplan aircraft show": (["aircraft", "show", "nosuch"],
                               "error: AIRCRAFT_ID: unknown aircraft 'nosuch'"),
}
"""A bad input for every command (``norms list`` takes none but a bad choice)."""


def _leaves(cmd: click.Command, ctx: click.Context) -> list[str]:
    if not isinstance(cmd, click.Group):
        return [ctx.command_path]
    out: list[str] = []
    for name in cmd.list_commands(ctx):
        sub = cmd.get_command(ctx, name)
        assert sub is not None
        out += _leaves(sub, click.Context(sub, info_name=name, parent=ctx))
    return out


COMMANDS = _leaves(main, click.Context(main, info_name="scanplan"))


def test_every_command_has_a_bad_input_here():
    assert sorted(COMMANDS) == sorted(BAD)


@pytest.mark.parametrize("path", COMMANDS)
def test_a_bad_input_is_exit_2_without_a_traceback(path, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "bad.csv").write_text("a,b\n")
    (tmp_path / "bad.json").write_text("{}")
    args, said = BAD[path]
    r = CliRunner().invoke(main, args, input="")
    assert r.exit_code == 2, (r.output, r.exception)
    assert isinstance(r.exception, SystemExit)
    assert "Traceback" not in r.output
    assert r.stderr.startswith(said), r.stderr
    assert r.stdout == ""


@pytest.mark.parametrize("path", COMMANDS)
def test_an_unknown_option_is_exit_2(path):
    r = CliRunner().invoke(main, [*path.split()[1:], "--no-such-option"])
    assert r.exit_code == 2 and "No such option" in r.stderr and "Traceback" not in r.output


def _group(body):
    @click.group(cls=errors.PolicyGroup)
    def g() -> None:
        """A group."""

    @g.command()
    @click.option("--json", "as_json", is_flag=True)
    @errors.json_errors
    def run(as_json: bool) -> None:
        body()
    return g


@pytest.mark.parametrize(("raised", "code", "said"), [
    (InputError("--x", "must be > 0"), 2, "error: --x: must be > 0\n"),
    (errors.Failed(["a.toml: bad", "the batch stopped"]), 1,
     "error: a.toml: bad\nerror: the batch stopped\n"),
    (errors.Failed(["a.toml: bad"], code=2), 2, "error: a.toml: bad\n"),
    (WriteError("out/spec.pdf", "No space left on device", 28), 1,
     "error: cannot write out/spec.pdf: No space left on device\n"),
    (RuntimeError("boom"), 1, "error: RuntimeError: boom (SCANPLAN_DEBUG=1 shows details)\n"),
])
def test_the_policy_maps_what_a_command_raises(raised, code, said, monkeypatch):
    monkeypatch.delenv("SCANPLAN_DEBUG", raising=False)

    def body():
        raise raised
    r = CliRunner().invoke(_group(body), ["run"])
    assert (r.exit_code, r.stderr, r.stdout) == (code, said, "")


def test_json_errors_are_one_document(monkeypatch):
    def body():
        raise InputError("'Sheet'!B3", "must be a number")
    r = CliRunner().invoke(_group(body), ["run", "--json"])
    assert r.exit_code == 2 and r.stderr == ""
    doc = json.loads(r.stdout)
    assert doc["ok"] is False and doc["error_count"] == 1 and doc["errors_omitted"] == 0
    assert doc["errors"][0]["address"] == "'Sheet'!B3"
    r = CliRunner().invoke(norms_group, ["show", "nosuch", "--json"])
    assert r.exit_code == 2 and json.loads(r.stdout)["ok"] is False


def test_a_closed_pipe_and_an_interrupt():
    def pipe():
        raise BrokenPipeError
    assert CliRunner().invoke(_group(pipe), ["run"]).exit_code == 141

    def interrupt():
        raise KeyboardInterrupt
    r = CliRunner().invoke(_group(interrupt), ["run"])
    assert r.exit_code == 1 and r.stderr == "\nAborted!\n"


@pytest.mark.parametrize(("args", "said"), [
    (["scan", *FILM, "--relief", "1", "--side-overlap-pct", "-5"],
     "error: --side-overlap-pct: must be a finite number ≥ 10"),
    (["scan", *FILM, "--relief", "1", "--side-overlap-pct", "30"],
     "error: --side-overlap-pct: sets the side overlap of the flight lines over --area-file"),
    (["uav", "--camera", "canon-eos-5d-mark-ii-50", "--height-m", "100", "--relief", "0.5"],
     "error: --relief: goes with the map scale"),
])
def test_an_option_that_would_do_nothing_is_refused(args, said):
    """Bug: ``scan --side-overlap-pct -5`` without an area file printed its report and
    exit 0 (the value was checked only with --area-file, where it shapes the flight
    lines), and ``uav --relief`` without ``--map-scale`` was dropped unsaid. A value is
    checked whenever it is given, and an option that would change nothing says what it
    needs."""
    r = CliRunner().invoke(main, args)
    assert r.exit_code == 2 and said in r.stderr, r.output


def test_scan_offers_only_the_height_formulas_of_film_photos():
    """Bug: ``scan --help`` offered ``--height-formula normal_case`` (the digital block's
    form, which the project's shared key may name) and ``scan`` then refused it."""
    from scanplan.norms.schema import HEIGHT_FORMULAS

    option = next(p for p in main.commands["scan"].params if p.name == "height_formula")
    assert tuple(option.type.choices) == HEIGHT_FORMULAS
    uav = next(p for p in main.commands["uav"].params if p.name == "height_formula")
    assert "normal_case" in uav.type.choices
