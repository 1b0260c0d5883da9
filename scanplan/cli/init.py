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
import re
import sys
import tempfile
from dataclasses import dataclass
from typing import Any

import click

from ..errors import InputError, WriteError
from ..i18n.labels_init import INIT
from ..project.inputs import INPUTS, shown
from .options import DECIMAL

__all__ = ["InitAnswers", "init", "project_text"]

KINDS = ("film", "uav", "both")
DEFAULT_FILM_CAMERA = "rc30-153"
DEFAULT_UAV_CAMERA = "dji-zenmuse-p1-35"
DEFAULT_RESOLVING_POWER = 40.0
CANDIDATE_RATIOS = (3, 4, 5, 6)
"""Candidate photo scales Mc = ratio × Mk when none are given (Miheeva & Ilushenko 2015
study Mc/Mk of about 2.5 to 6: finer ratios cost frames, coarser ones lose the map's small
objects)."""


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
    f_number: float | None = None
    speed_ms: float | None = None
    aircraft: bool = False
    organisation: str = ""
    contract_number: str = ""
    compiled_by: str = ""
    checked_by: str = ""


def _s(text: str) -> str:
    """A TOML basic string (JSON's escapes are TOML's)."""
    return json.dumps(text, ensure_ascii=False)


def _n(x: float) -> str:
    """A value the user gave, exactly (2000.0 → ``2000``, 0.123 → ``0.123``)."""
    return str(int(x)) if float(x).is_integer() else repr(float(x))


def _v(key: str, value: float | None = None) -> str:
    """An example value of ``section.key`` (default: the registry's default) as the input
    registry shows it, with the record's digits (:func:`scanplan.project.inputs.shown`)."""
    inp = INPUTS[key]
    return shown(inp, inp.default if value is None else value)


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




def _optional(key: str, value: str, example: str, comment: str) -> str:
    """``key = value # comment`` when given, else the commented example line."""
    return (f"{key} = {_s(value)}\t# {comment}" if value else
            f"# {key} = {_s(example)}\t# {comment}")


def project_text(a: InitAnswers) -> str:
    """The commented TOML text of a project (see docs/project-file.md), its comments in
    the language of its reports."""
    c = INIT["ru" if a.locale == "ru" else "en"]
    name = a.name or c["default_name"].format(mk=_n(a.map_scale))
    out = [
        c["head"],
        "",
        "[project]",
        f"name = {_s(name)}\t# {c['name']}",
        f"customer = {_s(a.customer)}",
        f"contractor = {_s(a.contractor)}",
        f"locale = {_s(a.locale)}\t# {c['locale']}",
        c["signing"],
        _optional("organisation", a.organisation, "", c["organisation"]),
        _optional("contract_number", a.contract_number, "", c["contract"]),
        _optional("compiled_by", a.compiled_by, "", c["compiled"]),
        _optional("checked_by", a.checked_by, "", c["checked"]),
        f"# approver_position = \"\"\t# {c['approver']}",
        f"# approver_name = \"\"\t# {c['approver_name']}",
        "",
        "[map]",
        f"scale = {_n(a.map_scale)}\t# {c['scale'].format(mk=_n(a.map_scale))}",
        f"relief_interval_m = {_n(a.relief_interval_m)}\t# {c['relief']}",
        "",
        "[norms]",
        f"set = {_s(a.norms)}\t# {c['norms']}",
        f"# probability = {_v('norms.probability', 0.75)}\t# {c['probability']}",
        (f"object_name = {_s(a.object_name)}\t# {c['object']}" if a.object_name else
         f"# object_name = \"manhole covers\"\t# {c['object']}"),
        (f"object_size_m = {_n(a.object_size_m)}\t# {c['object_size']}"
         if a.object_size_m is not None else
         f"# object_size_m = {_v('norms.object_size_m', 0.6)}\t# {c['object_size']}"),
        f"# shape = \"circle\"\t# {c['shape']}",
    ]
    if a.kind in ("film", "both"):
        out += ["", f"[film]\t# {c['film']}", f"camera = {_s(a.film_camera)}\t# {c['camera']}",
                f"resolving_power_lpmm = {_n(a.resolving_power_lpmm)}\t# {c['r']}",
                f"forward_overlap_pct = {_v('film.forward_overlap_pct', 60)}\t# {c['forward']}"]
        if a.archive_photo_scale is not None:
            out += [f"photo_scale = {_n(a.archive_photo_scale)}\t# {c['archive']}"]
        else:
            scales = a.photo_scales or default_photo_scales(a.map_scale)
            out += [f"photo_scales = [{', '.join(_n(x) for x in scales)}]\t# {c['scales']}",
                    f"# photo_scale = {_v('film.photo_scale', 12000)}\t# {c['scale_instead']}"]
        out += [f"scanner = {_s(a.scanner)}" if a.scanner else
                f"# scanner = \"photoscan-td\"\t# {c['scanner']}"]
    if a.kind in ("uav", "both"):
        out += _uav_lines(a, c)
    out += ["", f"[area]\t# {c['area']}"]
    if a.area_m is not None:
        out += [f"width_m = {_n(a.area_m[0])}\t# {c['width']}",
                f"length_m = {_n(a.area_m[1])}\t# {c['length']}"]
    else:
        out += [f"# width_m = {_v('area.width_m', 2000)}\t# {c['width']}",
                f"# length_m = {_v('area.length_m', 3000)}\t# {c['length']}"]
    out += [f"# file = \"block.kml\"\t# {c['file']}"]
    if a.kind in ("uav", "both"):
        out += ["", f"# [terrain]\t# {c['terrain']}", f"# dem = \"dem.tif\"\t# {c['dem']}",
                f"# ground_elevation_m = [{_v('terrain.ground_elevation_m', 150)}, "
                f"{_v('terrain.ground_elevation_m', 180)}]\t# {c['ground']}",
                f"# altitude_mode = \"constant\"\t# {c['mode']}",
                "", f"# [site]\t# {c['site']}",
                f"# lat_deg = {_v('site.lat_deg', 55.75)}\t# {c['lat']}",
                f"# lon_deg = {_v('site.lon_deg', 37.62)}\t# {c['lon']}",
                "", f"# [schedule]\t# {c['schedule']}",
                f"# start_date = 2027-06-01\t# {c['start']}",
                f"# end_date = 2027-06-30\t# {c['end']}",
                f"# sortie_time_min = {_v('schedule.sortie_time_min', 25)}\t# {c['sortie']}",
                "", f"# [control]\t# {c['control']}",
                f"# mode = {_s(INPUTS['control.mode'].default)}\t# {c['control_mode']}",
                f"# gcp_sigma_xy_m = {_v('control.gcp_sigma_xy_m')}\t# {c['control_xy']}",
                f"# gcp_sigma_z_m = {_v('control.gcp_sigma_z_m')}\t# {c['control_z']}",
                f"# checkpoints = {_s(INPUTS['control.checkpoints'].default)}\t"
                f"# {c['control_check']}"]
    return "\n".join(_align(line) for line in out) + "\n"


def _aircraft_line(camera: str, c: dict[str, str]) -> str:
    """``aircraft = "…"`` for the camera's one catalogue carrier (the plan's default, said
    so), else a commented example naming the aircraft that carry it."""
    from ..norms.aircraft import carriers_of

    carriers = [x.id for x in carriers_of(camera)]
    if len(carriers) == 1:
        return f"aircraft = {_s(carriers[0])}\t# {c['aircraft_id']}"
    example = carriers[-1] if carriers else "dji-m350-rtk"
    more = f": {', '.join(carriers)}" if len(carriers) > 1 else ""
    return f"# aircraft = {_s(example)}\t# {c['aircraft_id']}{more}"


def _uav_lines(a: InitAnswers, c: dict[str, str]) -> list[str]:
    """The ``[uav]`` section: a UAV's defaults, or a manned aircraft's speed with the norm
    set's overlaps; the f-number when the catalogue has none for the camera."""
    out = ["", f"[uav]\t# {c['aircraft' if a.aircraft else 'uav']}",
           f"camera = {_s(a.uav_camera)}\t# {c['camera']}",
           *([] if a.aircraft else [_aircraft_line(a.uav_camera, c)]),
           (f"height_m = {_n(a.height_m)}\t# {c['height']}" if a.height_m is not None else
            f"# height_m = {_v('uav.height_m', 100)}\t# {c['height_default']}")]
    if a.f_number is not None:
        out.append(f"f_number = {_n(a.f_number)}\t# {c['f_number']}")
    if a.aircraft:
        return [*out, f"speed_ms = {_n(a.speed_ms or 0)}\t# {c['speed']}",
                f"# forward_overlap_pct = {_v('uav.forward_overlap_pct', 60)}\t"
                f"# {c['overlaps_default']}",
                f"# side_overlap_pct = {_v('film.side_overlap_pct')}\t# {c['overlaps_default']}"]
    speed = _n(a.speed_ms) if a.speed_ms is not None else _v("uav.speed_ms", 10)
    return [*out, f"height_tolerance_pct = {_v('uav.height_tolerance_pct', 10)}\t"
            f"# {c['tolerance']}",
            f"speed_ms = {speed}\t# {c['speed']}",
            f"exposure_s = {_v('uav.exposure_s', 0.0005)}\t# {c['exposure']}",
            f"forward_overlap_pct = {_v('uav.forward_overlap_pct')}\t# {c['forward']}",
            f"side_overlap_pct = {_v('uav.side_overlap_pct')}\t# {c['side']}",
            f"# crosshatch = false\t# {c['crosshatch']}"]


def check_answers(text: str, path: str) -> None:
    """Parse and plan the text as ``scanplan plan`` would; :class:`InputError` if it fails."""
    from ..project.file import parse_project
    from ..project.spec import plan_project

    plan_project(parse_project(text, path))


def _check_replaceable(path: str) -> None:
    """What ``--force`` may replace: a regular file that is not write-protected (as for
    reports: a protection is its owner's statement; a link would be replaced, not the file
    it points to)."""
    import stat

    try:
        st = os.lstat(path)
    except FileNotFoundError:
        return
    except OSError as exc:
        raise InputError("PROJECT", f"{path!r} cannot be checked: {exc.strerror or exc}"
                         ) from None
    if stat.S_ISLNK(st.st_mode):
        raise InputError("PROJECT", f"{path!r} is a symbolic link (to {os.readlink(path)!r});"
                         " scanplan replaces files, not links — name the file itself")
    if not stat.S_ISREG(st.st_mode):
        from ..io.files import file_kind

        raise InputError("PROJECT", f"{path!r} is {file_kind(st.st_mode)}; give a file name")
    if not os.access(path, os.W_OK) or not st.st_mode & 0o222:  # root too: no write bit
        raise InputError("PROJECT", f"{path!r} is write-protected; scanplan leaves it alone "
                         "even with --force (make it writable, or give another name)")


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
        from ..io.atomic import write_atomic

        _check_replaceable(path)
        write_atomic(path, data)
        return
    folder = os.path.dirname(os.path.abspath(path))
    tmp = None
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{os.path.basename(path)}.", suffix=".tmp",
                                   dir=folder)
        try:
            from ..io.files import write_all

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


class _Checked(click.ParamType):
    """An answer at the prompt, checked as it is read (a value out of its range is said
    and asked again, not found wrong after the whole interview): ``check(text)`` returns
    the value or raises :class:`InputError`."""

    name = "answer"

    def __init__(self, check: Any) -> None:
        self.check = check

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None
                ) -> Any:
        try:
            return self.check(value)
        except InputError as exc:
            self.fail(exc.message, param, ctx)


def _scale_answer(text: Any) -> float:
    from ..core.domains import check_domain
    from ..norms import parse_scale

    scale = parse_scale(text, "--map-scale")
    check_domain("map_scale", scale)
    return scale


def _relief_answer(text: Any) -> float:
    from ..core.domains import check_domain

    try:
        value = DECIMAL.convert(text, None, None)
    except click.BadParameter as exc:
        raise InputError("--relief", exc.message) from None
    check_domain("relief_interval_m", value)
    return value


def _camera_answer(kind: str, norms: str) -> Any:
    """A check of a camera id: in the catalogue, and film or digital as asked."""
    def check(text: Any) -> str:
        from ..norms import load_norm_set

        cam = load_norm_set(norms).camera(str(text).strip(), "camera")
        if (cam.kind == "film") != (kind == "film"):
            raise InputError("camera", f"{cam.id!r} is a {cam.kind} camera; give a "
                             f"{'film' if kind == 'film' else 'digital'} camera "
                             "(scanplan cameras list)")
        return cam.id
    return check


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
    from ..project.jobs import parse_area_m

    return None if not text else parse_area_m(text, "--area-m")


@click.command("init")
@click.argument("project", type=click.Path(dir_okay=False))
@click.option("--kind", type=click.Choice(KINDS), help="film, uav or both (asked if missing "
              "at a terminal; default both).")
@click.option("--map-scale", help="Map scale, 2000 or 1:2000 (required without a terminal).")
@click.option("--relief", "relief_interval_m", type=DECIMAL,
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
@click.option("--resolving-power", "resolving_power_lpmm", type=DECIMAL,
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
@click.option("--height-m", type=DECIMAL, help="Planned UAV height [m] (default: the highest "
              "the constraints allow).")
@click.option("--area-m", help="Block WIDTHxLENGTH [m], e.g. 2000x3000 (optional).")
@click.option("--object-name", default="", help="Name of your own object to interpret "
              "(with --object-size-m).")
@click.option("--object-size-m", type=DECIMAL, help="Size of your own object to interpret [m] "
              "(default: the norm table's smallest object for the map scale).")
@click.option("--f-number", type=float, help="Working f-number of the UAV camera's lens (needed "
              "when the catalogue has none for the camera; asked at a terminal).")
@click.option("--speed-ms", type=float, help="Ground speed [m/s] (default 10 for a UAV; "
              "needed for a camera on a manned aircraft, asked at a terminal).")
@click.option("--organisation", default="", help="The contractor's organisation (title block).")
@click.option("--contract-number", default="", help="Contract number (title block).")
@click.option("--compiled-by", default="", help="Compiled by: name (signature block).")
@click.option("--checked-by", default="", help="Checked by: name (signature block).")
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
    map_scale = (parse_scale(opts["map_scale"], "--map-scale") if opts["map_scale"] is not None
                 else click.prompt("Map scale (e.g. 2000 or 1:2000)",
                                   type=_Checked(_scale_answer)))
    relief = opts["relief_interval_m"]
    if relief is None:
        relief = click.prompt("Relief (contour) interval, m", type=_Checked(_relief_answer))
    name = opts["name"]
    if name is None:
        name = click.prompt("Project name", default="") if ask else ""
    locale = opts["locale"] or (click.prompt("Report language", type=click.Choice(["en", "ru"]),
                                             default="en") if ask else "en")
    film_camera = opts["film_camera"]
    if film_camera is None:
        film_camera = (click.prompt("Film camera id (scanplan cameras list)",
                                    default=DEFAULT_FILM_CAMERA,
                                    type=_Checked(_camera_answer("film", opts["norms"])))
                       if ask and kind != "uav" else DEFAULT_FILM_CAMERA)
    uav_camera = opts["uav_camera"]
    if uav_camera is None:
        uav_camera = (click.prompt("UAV camera id (scanplan cameras list)",
                                   default=DEFAULT_UAV_CAMERA,
                                   type=_Checked(_camera_answer("digital", opts["norms"])))
                      if ask and kind != "film" else DEFAULT_UAV_CAMERA)
    f_number, speed_ms, aircraft = opts["f_number"], opts["speed_ms"], False
    if kind != "film":
        f_number, speed_ms, aircraft = _camera_needs(uav_camera, opts["norms"], f_number,
                                                     speed_ms, ask)
    archive = _film_scales(opts, ask and kind != "uav", map_scale)
    answers = InitAnswers(
        kind=kind, map_scale=map_scale, relief_interval_m=relief, name=name,
        customer=opts["customer"], contractor=opts["contractor"], locale=locale,
        norms=opts["norms"], film_camera=film_camera,
        resolving_power_lpmm=opts["resolving_power_lpmm"],
        photo_scales=_scales(opts["photo_scales"]), archive_photo_scale=archive,
        scanner=opts["scanner"], uav_camera=uav_camera, height_m=opts["height_m"],
        area_m=_area(opts["area_m"]), object_name=opts["object_name"],
        object_size_m=opts["object_size_m"], f_number=f_number, speed_ms=speed_ms,
        aircraft=aircraft, organisation=opts["organisation"],
        contract_number=opts["contract_number"], compiled_by=opts["compiled_by"],
        checked_by=opts["checked_by"])
    text = project_text(answers)
    try:
        check_answers(text, project)
    except InputError as exc:  # name the option that gave the key, never the unwritten file
        raise InputError(_option_for(exc.field), exc.message) from None
    folder = os.path.dirname(os.path.abspath(project))
    if not os.path.isdir(folder):
        raise InputError("PROJECT", f"folder {folder!r} does not exist")
    write_new(project, text.encode("utf-8"), force=force)
    click.echo(f"wrote {project}; plan it with: scanplan plan {project}", err=True)


def _film_scales(opts: dict[str, Any], ask: bool, map_scale: float) -> float | None:
    """The scale of existing photos, or None with the candidates left in
    ``opts["photo_scales"]`` (asked at a terminal when neither option is given)."""
    from ..norms import parse_scale

    if opts["photo_scales"] and opts["archive_photo_scale"]:
        raise InputError("--photo-scale", "give either --photo-scale (existing photos) or "
                         "--photo-scales (candidates), not both")
    archive = (parse_scale(opts["archive_photo_scale"], "--photo-scale")
               if opts["archive_photo_scale"] else None)
    if ask and not opts["photo_scales"] and archive is None:
        if click.confirm("Scan existing (archive) photos of a given scale?", default=False):
            archive = parse_scale(click.prompt("Scale of the existing photos (e.g. 12000)"),
                                  "--photo-scale")
        else:
            default = ",".join(f"{x:g}" for x in default_photo_scales(map_scale))
            opts["photo_scales"] = click.prompt("Candidate photo scales, comma-separated",
                                                default=default)
    return archive


def _camera_needs(camera: str, norms: str, f_number: float | None, speed_ms: float | None,
                  ask: bool) -> tuple[float | None, float | None, bool]:
    """The f-number and speed a catalogue camera needs beyond the catalogue: asked at a
    terminal, else an error naming the option; and whether it flies on an aircraft."""
    from ..norms import load_norm_set

    cam = load_norm_set(norms).camera(camera, "--uav-camera")
    aircraft = cam.carrier == "aircraft"
    if f_number is None and cam.f_number is None:
        if not ask:
            raise InputError("--f-number", f"the catalogue has no f-number for {camera!r}: "
                             "give the lens's working f-number (> 0), e.g. --f-number 5.6")
        f_number = click.prompt(f"Working f-number of the lens of {camera} (e.g. 5.6)",
                                type=DECIMAL)
    if speed_ms is None and aircraft:
        if not ask:
            raise InputError("--speed-ms", f"{camera!r} is flown on a manned aircraft: give "
                             "its ground speed in m/s (> 0), e.g. --speed-ms 70")
        speed_ms = click.prompt(f"Ground speed of the aircraft carrying {camera}, m/s",
                                type=DECIMAL)
    return f_number, speed_ms, aircraft


_KEY_OPTIONS = {
    "map.scale": "--map-scale", "map.relief_interval_m": "--relief",
    "film.camera": "--film-camera", "uav.camera": "--uav-camera",
    "film.photo_scales": "--photo-scales", "film.photo_scale": "--photo-scale",
    "film.scanner": "--scanner", "film.resolving_power_lpmm": "--resolving-power",
    "uav.height_m": "--height-m", "norms.set": "--norms", "area.width_m": "--area-m",
    "area.length_m": "--area-m", "project.name": "--name", "project.customer": "--customer",
    "project.contractor": "--contractor", "norms.object_size_m": "--object-size-m",
    "norms.object_name": "--object-name", "uav.f_number": "--f-number",
    "uav.speed_ms": "--speed-ms", "project.organisation": "--organisation",
    "project.contract_number": "--contract-number", "project.compiled_by": "--compiled-by",
    "project.checked_by": "--checked-by",
}


def _option_for(field: str) -> str:
    """``x.toml: film.camera (line 27)`` → ``--film-camera`` (the option a user typed); a
    key no option gives is named as the key, without the file that was never written."""
    for key, option in _KEY_OPTIONS.items():
        if f": {key}" in field or field.startswith(key):
            return option
    return re.sub(r"^.*?: ", "", re.sub(r" \(line \d+\)$", "", field))
