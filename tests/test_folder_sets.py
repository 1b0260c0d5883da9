"""An output folder's set of files is swapped in whole (scanplan/io/folderset.py).

Every failure a write can meet — each call that changes the folder (a file created,
written, synced, linked, renamed, unlinked, a folder made or removed) failing in turn with
a full disk, an I/O error or Ctrl+C — leaves what a reader sees exactly the old set (or,
past the commit point, the new one), and the next write leaves nothing behind; a reader
that resolves the set once (``.scanplan-sets/current``) while another process rewrites the
folder copies a whole set every time, which its manifest confirms; a user's own files and
links are never touched. The kill test at every step is in tests/test_output_safety.py."""

from __future__ import annotations

import contextlib
import errno
import hashlib
import json
import multiprocessing as mp
import os
from collections import Counter
from pathlib import Path

import pytest

from scanplan.errors import InputError, WriteError
from scanplan.io import folderset
from scanplan.io.atomic import write_atomic_many
from scanplan.io.targets import check_target, is_managed, link_text

OLD = {**{f"mission-{i:02d}.plan": f"old sortie {i}".encode() * 40 for i in range(1, 6)},
       "spec.pdf": b"%PDF-1.7 /Creator (scanplan) old"}
NEW = {**{f"mission-{i:02d}.plan": f"new sortie {i}".encode() * 30 for i in range(1, 4)},
       "spec.pdf": b"%PDF-1.7 /Creator (scanplan) new", "flight.kml": b"<kml>new</kml>"}


def visible(folder: Path) -> dict[str, bytes]:
    """What a reader finds: name → bytes (a link that leads nowhere is no file)."""
    out = {}
    for p in folder.iterdir():
        if not p.name.startswith("."):
            with contextlib.suppress(FileNotFoundError):
                out[p.name] = p.read_bytes()
    return out


def leftovers(folder: Path) -> list[str]:
    """Anything hidden but the sets' folder, and in it anything but current and previous."""
    sets = folder / folderset.SETS
    keep = {"current", "previous"}
    keep |= {os.readlink(sets / n) for n in keep if (sets / n).is_symlink()}
    inside = [f"{folderset.SETS}/{n}" for n in os.listdir(sets) if n not in keep] \
        if sets.is_dir() else []
    return sorted([n for n in os.listdir(folder) if n.startswith(".")
                   and n != folderset.SETS] + inside)


def write(folder: Path, files: dict[str, bytes], drop: tuple[str, ...] = ()) -> None:
    """The set ``files`` into ``folder``, the names ``drop`` removed, as plan --out does."""
    write_atomic_many({folder / n: d for n, d in files.items()},
                      remove=lambda: [folder / n for n in drop if (folder / n).exists()],
                      as_set=folder)


def old_folder(tmp: Path, plain: bool) -> Path:
    """The old set in a folder of sets, or as plain files (an earlier scanplan's)."""
    folder = tmp / "out"
    if folder.exists():
        import shutil

        shutil.rmtree(folder)
    folder.mkdir()
    (folder / "notes.txt").write_bytes(b"the user's own")
    if plain:
        for name, data in OLD.items():
            (folder / name).write_bytes(data)
    else:
        write(folder, OLD)
    return folder


STALE = ("mission-04.plan", "mission-05.plan")


class Failing:
    """Every os call that changes ``root`` counted; the n-th of one kind raises."""

    OPS = ("open", "write", "fsync", "replace", "rename", "link", "symlink", "unlink",
           "mkdir", "rmdir", "fchmod")

    def __init__(self, monkeypatch: pytest.MonkeyPatch, root: Path) -> None:
        self.root = str(root.resolve())
        self.calls: Counter[str] = Counter()
        self.fail: tuple[str, int, BaseException] | None = None
        self.fds: set[int] = set()
        for op in self.OPS:
            real = getattr(os, op)
            monkeypatch.setattr(os, op, self._wrap(op, real))

    def _ours(self, op: str, args: tuple) -> bool:
        if op in ("write", "fsync", "fchmod"):
            return bool(args) and args[0] in self.fds
        return any(isinstance(a, str | os.PathLike) and
                   os.path.abspath(os.fspath(a)).startswith(self.root) for a in args[:2])

    def _wrap(self, op: str, real):  # type: ignore[no-untyped-def]
        def call(*args, **kw):
            counted = self._ours(op, args) and not (op == "open" and not args[1] & os.O_CREAT)
            if counted:
                self.calls[op] += 1
                if self.fail and self.fail[:2] == (op, self.calls[op]):
                    raise self.fail[2]
            result = real(*args, **kw)
            if op == "open" and counted:
                self.fds.add(result)
            return result
        return call


def _counts(tmp: Path, monkeypatch: pytest.MonkeyPatch, plain: bool) -> Counter[str]:
    folder = old_folder(tmp, plain)
    with monkeypatch.context() as mp_:
        probe = Failing(mp_, folder)
        write(folder, NEW, STALE)
    assert visible(folder) == {**NEW, "notes.txt": b"the user's own"}
    return probe.calls


@pytest.mark.parametrize("plain", [False, True], ids=["sets", "plain-files"])
def test_every_failing_call_leaves_the_old_set_or_the_new(tmp_path, monkeypatch, plain):
    counts = _counts(tmp_path, monkeypatch, plain)
    assert counts["symlink"] and counts["replace"] and counts["link"] >= (4 if plain else 0)
    old = {**OLD, "notes.txt": b"the user's own"}
    new = {**NEW, "notes.txt": b"the user's own"}
    seen = Counter()
    for op, n in sorted(counts.items()):
        for k in range(1, n + 1):
            for exc in (OSError(errno.ENOSPC, "No space left on device"), KeyboardInterrupt()):
                folder = old_folder(tmp_path, plain)
                with monkeypatch.context() as mp_:
                    Failing(mp_, folder).fail = (op, k, exc)
                    try:
                        write(folder, NEW, STALE)
                        raised = False
                    except WriteError as err:
                        assert isinstance(exc, OSError) and err.errno == exc.errno
                        assert str(err).startswith("cannot write ")
                        raised = True
                    except KeyboardInterrupt:  # also just after the commit point
                        raised = True
                after = visible(folder)
                assert after in (old, new), (op, k, exc)
                outcome = "new" if after == new else "old"
                assert raised or outcome == "new", (op, k, exc)
                assert outcome == "old" or not isinstance(exc, OSError) or not raised
                seen[outcome] += 1
                write(folder, NEW, STALE)  # the next write puts everything right
                assert visible(folder) == new and leftovers(folder) == [], (op, k, exc)
    assert seen["old"] and seen["new"]  # failures before and after the commit point
    assert sum(seen.values()) == 2 * sum(counts.values())
    print(f"{sum(seen.values())} failures injected: {dict(counts)}")


def test_the_manifest_names_every_file_of_the_set(tmp_path):
    folder = old_folder(tmp_path, plain=False)
    write(folder, NEW, STALE)
    current = folderset.current_set(folder)
    manifest = folderset.read_manifest(current)
    assert set(manifest) == set(NEW)
    for name, data in NEW.items():
        assert manifest[name] == {"size": len(data), "sha256": hashlib.sha256(data).hexdigest()}
        assert (folder / name).is_symlink() and os.readlink(folder / name) == link_text(name)
    assert not (folder / "notes.txt").is_symlink()  # the user's own file: untouched
    assert folderset.read_manifest(folder / folderset.SETS / "previous") == {
        n: {"size": len(d), "sha256": hashlib.sha256(d).hexdigest()} for n, d in OLD.items()}


def test_a_users_link_is_still_refused_and_scanplans_own_is_a_file(tmp_path):
    folder = old_folder(tmp_path, plain=False)
    assert is_managed(folder / "spec.pdf")
    check_target(str(folder / "spec.pdf"), "--out", "pdf")  # scanplan's own link: its file
    (folder / "mine.pdf").write_bytes(b"%PDF-1.7 mine")
    (folder / "link.pdf").symlink_to("mine.pdf")
    with pytest.raises(InputError, match="is a symbolic link"):
        check_target(str(folder / "link.pdf"), "--out", "pdf")
    fake = folder / "spec2.pdf"  # a user's link that only looks like scanplan's
    fake.symlink_to(f"{folderset.SETS}/current/spec.pdf")
    assert not is_managed(fake)
    with pytest.raises(InputError, match="is a symbolic link"):
        check_target(str(fake), "--out", "pdf")


def test_without_links_the_journal_writes_plain_files_and_links_adopt_them(tmp_path,
                                                                           monkeypatch):
    folder = tmp_path / "out"
    folder.mkdir()
    monkeypatch.setattr(folderset, "supported", lambda f: False)  # FAT, a share
    write(folder, OLD)
    assert not any(p.is_symlink() for p in folder.iterdir())
    assert not (folder / folderset.SETS).exists() and visible(folder) == OLD
    monkeypatch.undo()
    write(folder, NEW, STALE)
    assert visible(folder) == NEW and leftovers(folder) == []


# --------------------------------------------------------------------------------------
# A reader copying the folder while it is rewritten
# --------------------------------------------------------------------------------------
def _writer(folder: str, rounds: int) -> None:
    for i in range(rounds):
        files, drop = (NEW, STALE) if i % 2 else (OLD, ("flight.kml",))
        write(Path(folder), files, drop)
    os._exit(0)


def _reader(folder: str, rounds: int, q: mp.Queue) -> None:
    """Copy the set the way docs/reliability.md says: resolve ``current`` once, copy that
    set folder, read its manifest last and check the copy against it (else copy again)."""
    whole = mixed = again = 0
    sets = Path(folder) / folderset.SETS
    for _ in range(rounds):
        try:
            chosen = sets / os.readlink(sets / "current")
            names = [n for n in os.listdir(chosen) if not n.startswith(".")]
            copy = {n: (chosen / n).read_bytes() for n in names}
            manifest = json.loads((chosen / folderset.MANIFEST).read_bytes())["files"]
        except FileNotFoundError:
            again += 1  # the set became two writes old meanwhile: copy again
            continue
        if {n: {"size": len(d), "sha256": hashlib.sha256(d).hexdigest()}
                for n, d in copy.items()} != manifest:
            again += 1  # seen by the check: copy again
            continue
        whole += copy in (OLD, NEW)
        mixed += copy not in (OLD, NEW)  # a copy the check passed that is no set
    q.put((whole, mixed))
    q.close()
    q.join_thread()  # the answer is sent before the process ends
    os._exit(0)


def test_a_reader_copying_the_current_set_always_gets_a_whole_set(tmp_path):
    folder = old_folder(tmp_path, plain=False)
    ctx = mp.get_context("fork")
    q: mp.Queue = ctx.Queue()
    procs = [ctx.Process(target=_writer, args=(str(folder), 60)),
             ctx.Process(target=_reader, args=(str(folder), 400, q))]
    for p in procs:
        p.start()
    for p in procs:
        p.join(300)
        assert p.exitcode == 0
    whole, mixed = q.get(timeout=10)
    assert whole > 0 and mixed == 0
    print(f"{whole} whole copies of 400")
