"""``scanplan init``: write a commented project file from a few answers or options.

The file is built as text (every key with a comment: meaning, unit, default), checked the
way ``scanplan plan`` reads it — the project is parsed *and planned* before anything is
written, so ``init`` never leaves a file that ``plan`` refuses — and written atomically.
An existing file is replaced only with ``--force``; without it the file is created with
a hard link from a temporary file, which fails if the name exists (no race).
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
from dataclasses import dataclass
from typing import Any

import click

from ..errors import InputError, WriteError

__all__ = ["InitAnswers", "init", "project_text"]

KINDS = ("film", "uav", "both")
DEFAULT_FILM_CAMERA = "rc30-153"
DEFAULT_UAV_CAMERA = "dji-zenmuse-p1-35"
DEFAULT_RESOLVING_POWER = 40.0
CANDIDATE_RATIOS = (3, 4, 5, 6)
"""Candidate photo scales Mc = ratio × Mk when none are given (seed 001 studies Mc/Mk of
about 2.5 to 6: finer ratios cost frames, coarser ones lose the map's small objects)."""


@dataclass
class InitAnswers:
    """What ``init`` asks: enough for a project that plans."""

    kind: str
    map_scale: float
    relief_interval_m: float
    name: str = ""
    customer: str = ""
    contractor: str = ""
    locale: str = "en"
    norms: str = "gkinp-02-036-02"
    film_camera: str = DEFAULT_FILM_CAMERA
    resolving_power_lpmm: float = DEFAULT_RESOLVING_POWER
    photo_scales: tuple[float, ...] = ()
    archive_photo_scale: float | None = None
    scanner: str = ""
    uav_camera: str = DEFAULT_UAV_CAMERA
    height_m: float | None = None
    area_m: tuple[float, float] | None = None
    object_name: str = ""
    object_size_m: float | None = None


def _s(text: str) -> str:
    """A TOML basic string (JSON's escapes are TOML's)."""
    return json.dumps(text, ensure_ascii=False)


def _n(x: float) -> str:
    return str(int(x)) if float(x).is_integer() else repr(float(x))


def default_photo_scales(map_scale: float) -> tuple[float, ...]:
    """Candidate photo scales ``CANDIDATE_RATIOS × Mk`` (within 1:100 … 1:1 000 000)."""
    return tuple(float(r * map_scale) for r in CANDIDATE_RATIOS
                 if 100 <= r * map_scale <= 1_000_000)


COMMENT_COLUMN = 36


def _align(line: str) -> str:
    """``key = value\t# comment`` → the comment at :data:`COMMENT_COLUMN` (a value is
    JSON-escaped, so a tab in it is never a raw tab)."""
    code, sep, comment = line.partition("\t")
    return f"{code.ljust(COMMENT_COLUMN - 1)} {comment}" if sep else line


def project_text(a: InitAnswers) -> str:
    """The commented TOML text of a project (see docs/project-file.md)."""
    name = a.name or f"Topographic plan 1:{_n(a.map_scale)}"
    out = [
        "# scanplan project: one mapping contract. Plan it with",
        "#   scanplan plan THIS-FILE.toml --out out/",
        "# Every key is described in docs/project-file.md; unknown keys are errors.",
        "",
        "[project]",
        f"name = {_s(name)}\t# title of the reports",
        f"customer = {_s(a.customer)}",
        f"contractor = {_s(a.contractor)}",
        f"locale = {_s(a.locale)}\t# \"en\" or \"ru\": language of the reports",
        "# approver_position = \"Chief engineer\"\t# approval block",
        "# approver_name = \"\"",
        "",
        "[map]",
        f"scale = {_n(a.map_scale)}\t# map scale denominator Mk (1:{_n(a.map_scale)})",
        f"relief_interval_m = {_n(a.relief_interval_m)}\t# relief (contour) interval h_c [m]",
        "",
        "[norms]",
        f"set = {_s(a.norms)}\t# norm set (scanplan norms list)",
        "# probability = 0.75\t# required recognition probability",
        (f"object_name = {_s(a.object_name)}\t# your own object to interpret, with its size"
         if a.object_name else
         "# object_name = \"manhole covers\"\t# your own object to interpret, with its size:"),
        (f"object_size_m = {_n(a.object_size_m)}\t# [m] (default: the norm table's for the "
         "map scale)" if a.object_size_m is not None else
         "# object_size_m = 0.6\t#   (default: the norm table's for the map scale)"),
        "# shape = \"circle\"\t# circle | rectangle | angle | square | wall",
    ]
    if a.kind in ("film", "both"):
        out += [
            "",
            "[film]\t# film camera photos, scanned",
            f"camera = {_s(a.film_camera)}\t# scanplan cameras list",
            f"resolving_power_lpmm = {_n(a.resolving_power_lpmm)}\t"
            "# resolving power of the photos R [lines/mm]",
            "forward_overlap_pct = 60\t# [%], 50 or more (stereo)",
        ]
        if a.archive_photo_scale is not None:
            out += [f"photo_scale = {_n(a.archive_photo_scale)}\t"
                    "# existing (archive) photos: their scale is given, not chosen"]
        else:
            scales = a.photo_scales or default_photo_scales(a.map_scale)
            out += [f"photo_scales = [{', '.join(_n(x) for x in scales)}]\t"
                    "# candidate photo scales Mc to choose from",
                    "# photo_scale = 12000\t# instead: the scale of existing photos"]
        out += [f"scanner = {_s(a.scanner)}" if a.scanner else
                "# scanner = \"photoscan-td\"\t# round the scan pixel to a scanner's steps"]
    if a.kind in ("uav", "both"):
        out += [
            "",
            "[uav]\t# digital camera on a UAV",
            f"camera = {_s(a.uav_camera)}\t# scanplan cameras list",
            (f"height_m = {_n(a.height_m)}\t# planned height above ground [m]"
             if a.height_m is not None else
             "# height_m = 100\t# planned height [m] (default: the highest allowed)"),
            "height_tolerance_pct = 10\t# how much higher the UAV may fly [%]",
            "speed_ms = 10\t# ground speed [m/s]",
            "exposure_s = 0.0005\t# exposure time [s]",
            "forward_overlap_pct = 80\t# [%], 50 or more (stereo)",
            "side_overlap_pct = 60\t# [%], 10 or more",
        ]
    out += ["", "[area]\t# the block to cover (both sides, or neither)"]
    if a.area_m is not None:
        out += [f"width_m = {_n(a.area_m[0])}\t# across the flight lines [m]",
                f"length_m = {_n(a.area_m[1])}\t# along the flight lines [m]"]
    else:
        out += ["# width_m = 2000\t# across the flight lines [m]",
                "# length_m = 3000\t# along the flight lines [m]"]
    out += ['# file = "block.kml"\t# or the contract polygon instead: KML, KMZ, GeoJSON, '
            "GeoPackage, Shapefile, a CSV of its vertices"]
    return "\n".join(_align(line) for line in out) + "\n"


def check_answers(text: str, path: str) -> None:
    """Parse and plan the text as ``scanplan plan`` would; :class:`InputError` if it fails."""
    from ..project.file import parse_project
    from ..project.spec import plan_project

    plan_project(parse_project(text, path))


def write_new(path: str, data: bytes, *, force: bool) -> None:
    """Write ``data`` to ``path`` atomically; an existing file only with ``force``.

    Raises
    ------
    InputError
        The file exists and ``force`` is not set.
    WriteError
        The write failed (nothing is left behind).
    """
    if not force and os.path.lexists(path):
        raise InputError("PROJECT", f"{path!r} exists; give --force to replace it")
    if force:
        from ..safeio import write_atomic

        write_atomic(path, data)
        return
    folder = os.path.dirname(os.path.abspath(path))
    tmp = None
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{os.path.basename(path)}.", suffix=".tmp",
                                   dir=folder)
        try:
            from ..safeio import write_all

            write_all(fd, data)
            os.fsync(fd)
        finally:
            os.close(fd)
        os.chmod(tmp, 0o666 & ~_umask())
        os.link(tmp, path)  # fails if the name appeared meanwhile: never overwrites
    except FileExistsError:
        raise InputError("PROJECT", f"{path!r} exists; give --force to replace it") from None
    except OSError as exc:
        raise WriteError.from_os_error(path, exc) from exc
    finally:
        if tmp is not None:
            try:
                os.unlink(tmp)
            except OSError:
                pass


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _interactive() -> bool:
    """Ask for missing answers only when a person is at a terminal."""
    return sys.stdin.isatty() and sys.stdout.isatty()


def _scales(text: str | None) -> tuple[float, ...]:
    from ..norms import parse_scale

    if not text:
        return ()
    return tuple(parse_scale(x, "--photo-scales") for x in text.replace(";", ",").split(",")
                 if x.strip())


def _area(text: str | None) -> tuple[float, float] | None:
    from ..project.api import parse_area_m

    return None if not text else parse_area_m(text, "--area-m")


@click.command("init")
@click.argument("project", type=click.Path(dir_okay=False))
@click.option("--kind", type=click.Choice(KINDS), help="film, uav or both (asked if missing "
              "at a terminal; default both).")
@click.option("--map-scale", help="Map scale, 2000 or 1:2000 (required without a terminal).")
@click.option("--relief", "relief_interval_m", type=float,
              help="Relief (contour) interval h_c [m] (required without a terminal).")
@click.option("--name", default=None, help="Project name for the title block.")
@click.option("--customer", default="", help="Customer for the title block.")
@click.option("--contractor", default="", help="Contractor for the title block.")
@click.option("--locale", type=click.Choice(["en", "ru"]), default=None,
              help="Language of the reports (default en).")
@click.option("--norms", default="gkinp-02-036-02", show_default=True,
              help="Norm set name or folder.")
@click.option("--film-camera", default=None,
              help=f"Film camera id (default {DEFAULT_FILM_CAMERA}).")
@click.option("--resolving-power", "resolving_power_lpmm", type=float,
              default=DEFAULT_RESOLVING_POWER, show_default=True,
              help="Resolving power of the photos R [lines/mm].")
@click.option("--photo-scales", help="Candidate photo scales, comma-separated, e.g. "
              "6000,8000,10000 (default 3, 4, 5 and 6 × the map scale).")
@click.option("--photo-scale", "archive_photo_scale",
              help="The scale of existing (archive) photos to scan, e.g. 12000: given, not "
              "chosen (instead of --photo-scales).")
@click.option("--scanner", default="", help="Scanner id (optional).")
@click.option("--uav-camera", default=None,
              help=f"Digital camera id (default {DEFAULT_UAV_CAMERA}).")
@click.option("--height-m", type=float, help="Planned UAV height [m] (default: the highest "
              "the constraints allow).")
@click.option("--area-m", help="Block WIDTHxLENGTH [m], e.g. 2000x3000 (optional).")
@click.option("--object-name", default="", help="Name of your own object to interpret "
              "(with --object-size-m).")
@click.option("--object-size-m", type=float, help="Size of your own object to interpret [m] "
              "(default: the norm table's smallest object for the map scale).")
@click.option("--force", is_flag=True, help="Replace an existing file.")
def init(project: str, force: bool, **opts: Any) -> None:
    """Write a commented project file that `scanplan plan` runs as it is.

    Give the answers as options, or run it at a terminal and answer the questions. The
    file is checked by planning it before it is written; an existing file is replaced
    only with --force.

    \b
    Examples:
      scanplan init town-500.toml --kind uav --map-scale 500 --relief 0.5
      scanplan init plan-1000.toml --kind film --map-scale 1000 --relief 0.5 \\
                    --photo-scales 4000,5000,6000,8000 --scanner photoscan-td
      scanplan init archive.toml --kind film --map-scale 2000 --relief 1 \\
                    --photo-scale 12000 --locale ru --name "План 1:2000"
    """
    from ..norms import parse_scale

    ask = _interactive()
    kind = opts["kind"] or (click.prompt("Kind of survey", type=click.Choice(KINDS),
                                         default="both") if ask else "both")
    if opts["map_scale"] is None and not ask:
        raise InputError("--map-scale", "is required (or run at a terminal to be asked), "
                         "e.g. --map-scale 2000")
    if opts["relief_interval_m"] is None and not ask:
        raise InputError("--relief", "is required (or run at a terminal to be asked), e.g. "
                         "--relief 0.5")
    map_scale = parse_scale(opts["map_scale"] if opts["map_scale"] is not None else
                            click.prompt("Map scale (e.g. 2000 or 1:2000)"), "--map-scale")
    relief = opts["relief_interval_m"]
    if relief is None:
        relief = click.prompt("Relief (contour) interval, m", type=float)
    name = opts["name"]
    if name is None:
        name = click.prompt("Project name", default="") if ask else ""
    locale = opts["locale"] or (click.prompt("Report language", type=click.Choice(["en", "ru"]),
                                             default="en") if ask else "en")
    film_camera = opts["film_camera"]
    if film_camera is None:
        film_camera = (click.prompt("Film camera id (scanplan cameras list)",
                                    default=DEFAULT_FILM_CAMERA)
                       if ask and kind != "uav" else DEFAULT_FILM_CAMERA)
    uav_camera = opts["uav_camera"]
    if uav_camera is None:
        uav_camera = (click.prompt("UAV camera id (scanplan cameras list)",
                                   default=DEFAULT_UAV_CAMERA)
                      if ask and kind != "film" else DEFAULT_UAV_CAMERA)
    if opts["photo_scales"] and opts["archive_photo_scale"]:
        raise InputError("--photo-scale", "give either --photo-scale (existing photos) or "
                         "--photo-scales (candidates), not both")
    archive = (parse_scale(opts["archive_photo_scale"], "--photo-scale")
               if opts["archive_photo_scale"] else None)
    if ask and kind != "uav" and not opts["photo_scales"] and archive is None:
        if click.confirm("Scan existing (archive) photos of a given scale?", default=False):
            archive = parse_scale(click.prompt("Scale of the existing photos (e.g. 12000)"),
                                  "--photo-scale")
        else:
            default = ",".join(f"{x:g}" for x in default_photo_scales(map_scale))
            opts["photo_scales"] = click.prompt("Candidate photo scales, comma-separated",
                                                default=default)
    answers = InitAnswers(
        kind=kind, map_scale=map_scale, relief_interval_m=relief, name=name,
        customer=opts["customer"], contractor=opts["contractor"], locale=locale,
        norms=opts["norms"], film_camera=film_camera,
        resolving_power_lpmm=opts["resolving_power_lpmm"],
        photo_scales=_scales(opts["photo_scales"]), archive_photo_scale=archive,
        scanner=opts["scanner"], uav_camera=uav_camera, height_m=opts["height_m"],
        area_m=_area(opts["area_m"]), object_name=opts["object_name"],
        object_size_m=opts["object_size_m"])
    text = project_text(answers)
    try:
        check_answers(text, project)
    except InputError as exc:  # name the option that gave the key
        raise InputError(_option_for(exc.field), exc.message) from None
    folder = os.path.dirname(os.path.abspath(project))
    if not os.path.isdir(folder):
        raise InputError("PROJECT", f"folder {folder!r} does not exist")
    write_new(project, text.encode("utf-8"), force=force)
    click.echo(f"wrote {project}; plan it with: scanplan plan {project}", err=True)


_KEY_OPTIONS = {
    "map.scale": "--map-scale", "map.relief_interval_m": "--relief",
    "film.camera": "--film-camera", "uav.camera": "--uav-camera",
    "film.photo_scales": "--photo-scales", "film.photo_scale": "--photo-scale",
    "film.scanner": "--scanner", "film.resolving_power_lpmm": "--resolving-power",
    "uav.height_m": "--height-m", "norms.set": "--norms", "area.width_m": "--area-m",
    "area.length_m": "--area-m", "project.name": "--name", "project.customer": "--customer",
    "project.contractor": "--contractor", "norms.object_size_m": "--object-size-m",
    "norms.object_name": "--object-name",
}


def _option_for(field: str) -> str:
    """``x.toml: film.camera (line 27)`` → ``--film-camera`` (the option a user typed)."""
    for key, option in _KEY_OPTIONS.items():
        if f": {key}" in field or field.startswith(key):
            return option
    return field
