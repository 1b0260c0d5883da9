"""The user camera catalogue is as safe as a norm set: one atomic version, readers under
the shared lock, a kill between its replacements recovered, every imported camera usable
by the commands, and no import that leaves a catalogue the commands cannot load."""

from __future__ import annotations

import multiprocessing as mp
import os
import signal
from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.norms import load_norm_set
from scanplan.norms import store as norms_store
from scanplan.project.cameras import import_camera_file, user_catalogue_dir

HEADER = ("id,kind,name,sensor_width_mm,sensor_height_mm,focal_mm,image_width_px,"
          "image_height_px")


def _cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def _cameras(path: Path, *rows: str) -> Path:
    path.write_text("\n".join([HEADER, *rows]) + "\n", encoding="utf-8")
    return path


def _lens(path: Path, camera: str) -> Path:
    rows = ["camera,position,freq_lpmm,mtf,source"]
    rows += [f"{camera},centre,{n},{max(0.0, 1 - 0.006 * n):.3f},chart" for n in (0, 40, 80)]
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    return path


def test_reimporting_a_lens_camera_as_film_never_bricks_the_catalogue(tmp_path, user_dir):
    """Bug: re-importing a user camera that had a lens MTF table as a film camera left
    lens-mtf.csv naming a non-digital camera, and scan, cameras list, init and the
    corrective re-import all exited 2. The film import drops the old lens table (and says
    so); every command still loads the catalogue."""
    digital = _cameras(tmp_path / "cameras.csv", "my-cam,digital,Mine,36,24,35,8000,5333")
    assert _cli("cameras", "import", digital).exit_code == 0
    r = _cli("cameras", "import", _lens(tmp_path / "lens-mtf.csv", "my-cam"))
    assert r.exit_code == 0, r.output
    assert "my-cam" in load_norm_set().lens_mtf
    film = _cameras(tmp_path / "cameras.csv", "my-cam,film,Mine,230,230,153,,")
    r = _cli("cameras", "import", film, "--force")
    assert r.exit_code == 0, r.output
    assert "lens MTF table of 'my-cam' was removed" in r.stderr
    norms_store.forget_read_sets()
    ns = load_norm_set()
    assert ns.cameras["my-cam"].kind == "film" and "my-cam" not in ns.lens_mtf
    for args in (("cameras", "list"), ("cameras", "show", "my-cam"),
                 ("scan", "--map-scale", "2000", "--relief", "0.5", "--photo-scale",
                  "10000", "--camera", "my-cam", "--resolving-power", "40")):
        r = _cli(*args)
        assert r.exit_code == 0, (args, r.output)
    # the file's own lens table of a film camera is still refused (named row)
    r = _cli("cameras", "import", _lens(tmp_path / "lens-mtf.csv", "my-cam"))
    assert r.exit_code == 2 and "lens_mtf row 1 (camera)" in r.stderr
    assert "not a digital camera" in r.stderr


@pytest.mark.parametrize(("row", "cell", "words"), [
    ("tiny,digital,Tiny,1e-300,24,35,8000,5333", "cameras row 1 (sensor_width_mm)",
     "≥ 0.1 and ≤ 1000 mm"),
    ("short,digital,Short,36,24,1e-300,8000,5333", "cameras row 1 (focal_mm)",
     "≥ 1 and ≤ 2000 mm"),
    ("huge,digital,Huge,36,24,35,100000000000000000000,5333", "cameras row 1 (image_width_px)",
     "must be between 36 and 360,000 px"),
    ("tall,digital,Tall,36,24,35,8000,100000000000000000000",
     "cameras row 1 (image_height_px)", "pixel must be ≥ 0.1 and ≤ 1000 µm"),
    ("film-x,film,Film,0.5,230,153,,", "cameras row 1 (sensor_width_mm)",
     "≥ 1 and ≤ 1000 mm"),
])
def test_import_refuses_cameras_no_command_can_use(tmp_path, user_dir, row, cell, words):
    """Bug: cameras with a 1e-300 mm sensor or focal length, 1e20 px images or a 0.0001 µm
    pixel were imported, and later commands failed naming options the user never gave.
    The import applies the planning domains, naming the row, the column and the range."""
    r = _cli("cameras", "import", _cameras(tmp_path / "cameras.csv", row))
    assert r.exit_code == 2, r.output
    assert cell in r.stderr and words in r.stderr, r.stderr
    assert not (user_catalogue_dir() / "cameras.csv").exists()


def test_a_scanner_step_outside_the_domain_is_refused(tmp_path, user_dir):
    f = tmp_path / "scanners.csv"
    f.write_text("scanner,name,pixel_um\nfine,Fine,0.0001\n", encoding="utf-8")
    r = _cli("cameras", "import", f)
    assert r.exit_code == 2 and "scanners row 1 (pixel_um)" in r.stderr
    assert "≥ 0.1 and ≤ 1000 µm" in r.stderr


def test_a_header_only_csv_imports_nothing_with_exit_2(tmp_path, user_dir):
    """Bug: a CSV with only its header imported nothing with exit 0."""
    r = _cli("cameras", "import", _cameras(tmp_path / "cameras.csv"))
    assert r.exit_code == 2 and "has no cameras" in r.stderr, r.output
    assert not user_catalogue_dir().exists()


def _killed_import(step: int, csv_path: Path) -> int:
    """Import in a child killed (SIGKILL) before its ``step``-th rename in the norm
    directory; its exit code (0: it finished)."""
    def child() -> None:
        count = [0]
        real = os.replace

        def op(src, dst, **kw):
            count[0] += 1
            if count[0] == step:
                os.kill(os.getpid(), signal.SIGKILL)
            return real(src, dst, **kw)

        os.replace = op
        import_camera_file(csv_path, force=True)
        os._exit(0)

    p = mp.get_context("fork").Process(target=child)
    p.start()
    p.join(60)
    return p.exitcode


def test_a_kill_between_the_replacements_is_recovered(tmp_path, user_dir):
    """Bug: a kill -9 between the catalogue's replacements left cameras of one import
    with scanners of another for good, and its temporary was never cleaned. Killed before
    each rename, the next load sees the old catalogue or the new one, whole, and nothing
    is left behind."""
    old = tmp_path / "old.xlsx"
    new = tmp_path / "new.xlsx"
    from openpyxl import Workbook

    for path, tag, step in ((old, "old", 5), (new, "new", 10)):
        wb = Workbook()
        ws = wb.active
        ws.title = "cameras"
        ws.append(["id", "kind", "name", "sensor_width_mm", "sensor_height_mm", "focal_mm",
                   "image_width_px", "image_height_px"])
        ws.append(["cam", "digital", f"Camera {tag}", 36, 24, 35, 8000, 5333])
        ws2 = wb.create_sheet("scanners")
        ws2.append(["scanner", "name", "pixel_um"])
        ws2.append(["scn", f"Scanner {tag}", step])
        wb.save(path)
    import_camera_file(old)
    seen = set()
    for step in range(1, 20):
        code = _killed_import(step, new)
        norms_store.forget_read_sets()
        ns = load_norm_set()  # a load puts a set-aside catalogue back
        state = (ns.cameras["cam"].name, ns.scanners["scn"])
        assert state in {("Camera old", (5.0,)), ("Camera new", (10.0,))}, (step, state)
        seen.add(state[0])
        left = [p.name for p in user_dir.iterdir() if p.name.startswith(".")]
        if code == 0:
            break
        assert code == -signal.SIGKILL
        import_camera_file(old, force=True)  # the next import cleans up and starts over
        assert [p.name for p in user_dir.iterdir() if p.name.startswith(".")] == []
    assert code == 0 and left == [] and seen == {"Camera old", "Camera new"}


def _importer(paths: list[str], rounds: int) -> None:
    for i in range(rounds):
        import_camera_file(paths[i % 2], force=True)


def _reader(rounds: int, out: mp.Queue) -> None:
    mixed = 0
    for _ in range(rounds):
        norms_store.forget_read_sets()
        ns = load_norm_set()
        tag = ns.cameras["cam"].name.split()[-1]
        mixed += ns.scanner_names["scn"].split()[-1] != tag
    out.put(mixed)


def test_reads_during_imports_never_mix_two_imports(tmp_path, user_dir):
    """Bug: 131 of 51,923 loads during imports saw the cameras of one import with the
    scanners of another. Loads hold the shared lock while imports swap the catalogue."""
    paths = []
    for tag in ("A", "B"):
        f = tmp_path / f"{tag}.xlsx"
        from openpyxl import Workbook

        wb = Workbook()
        ws = wb.active
        ws.title = "cameras"
        ws.append(["id", "kind", "name", "sensor_width_mm", "sensor_height_mm", "focal_mm",
                   "image_width_px", "image_height_px"])
        ws.append(["cam", "digital", f"Camera {tag}", 36, 24, 35, 8000, 5333])
        ws2 = wb.create_sheet("scanners")
        ws2.append(["scanner", "name", "pixel_um"])
        ws2.append(["scn", f"Scanner {tag}", 5 if tag == "A" else 10])
        wb.save(f)
        paths.append(str(f))
    import_camera_file(paths[0])
    ctx = mp.get_context("fork")
    q: mp.Queue = ctx.Queue()
    procs = [ctx.Process(target=_importer, args=(paths, 20)),
             ctx.Process(target=_reader, args=(150, q))]
    for p in procs:
        p.start()
    for p in procs:
        p.join(300)
        assert p.exitcode == 0
    assert q.get(timeout=10) == 0
