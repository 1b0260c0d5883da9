"""The ``scanplan`` command line (click).

Exit codes: 0 ok; 2 bad usage or invalid input (the message names the option, key or
cell and the allowed range); 1 runtime failure (a message, never a traceback — set
``SCANPLAN_DEBUG=1`` to see one).
"""

from __future__ import annotations

import json
import math
import os
import sys
import traceback
import warnings
from collections.abc import Callable
from typing import Any

import click

from .._version import __version__
from ..errors import InputError, WriteError

# Python names of inputs → the option a user typed
OPTION_NAMES = {
    "map_scale": "--map-scale",
    "photo_scale": "--photo-scale",
    "relief_interval_m": "--relief",
    "focal_mm": "--focal-mm",
    "frame_mm": "--frame-mm",
    "frame_width_mm": "--frame-mm",
    "frame_along_mm": "--frame-mm",
    "resolving_power_lpmm": "--resolving-power",
    "forward_overlap_pct": "--overlap-pct",
    "object_size_m": "--object-size-m",
    "object_name": "--object-name",
    "shape": "--shape",
    "probability": "--probability",
    "height_formula": "--height-formula",
    "pr_coefficient": "--pr-coefficient",
    "recognition_rounding": "--rounding",
    "scanner": "--scanner",
    "camera": "--camera",
    "bands": "--bands",
    "bits_per_band": "--bit-depth",
    "pixel_um": "--pixel-um",
    "sensor_mm": "--sensor-mm",
    "sensor_width_mm": "--sensor-mm",
    "sensor_height_mm": "--sensor-mm",
    "f_number": "--f-number",
    "orientation": "--orientation",
    "height_m": "--height-m",
    "max_height_m": "--max-height-m",
    "gsd_cm": "--gsd-cm",
    "speed_ms": "--speed-ms",
    "exposure_s": "--exposure-s",
    "side_overlap_pct": "--side-overlap-pct",
    "height_tolerance_up_pct": "--height-tolerance-pct",
    "r_min": "--r-min",
    "r_max": "--r-max",
    "k0": "--k0",
    "threshold_k0": "--k0",
    "haze_contrast": "--haze-contrast",
    "shift_factor": "--shift-factor",
    "roll_deg": "--roll-deg",
    "pitch_deg": "--pitch-deg",
    "area_width_m": "--area-m",
    "area_length_m": "--area-m",
    "area_m": "--area-m",
    "file": "--area-file",
    "feature": "--area-feature",
    "layer": "--area-layer",
    "direction_deg": "--direction-deg",
    "max_flight_time_min": "--max-flight-time-min",
    "side_overlap_pct_film": "--side-overlap-pct",
    "random_speed_ms": "--random-speed-ms",
    "roll_rate_rad_s": "--roll-rate",
    "pitch_rate_rad_s": "--pitch-rate",
    "yaw_rate_rad_s": "--yaw-rate",
}


class ScanplanGroup(click.Group):
    """A group that turns :class:`InputError` into exit 2 and crashes into exit 1."""

    def invoke(self, ctx: click.Context) -> Any:
        try:
            with warnings.catch_warnings():
                if not os.environ.get("SCANPLAN_DEBUG"):  # no library's warning on a
                    warnings.simplefilter("ignore")  # user's terminal (the tests raise them)
                return super().invoke(ctx)
        except InputError as exc:
            field = OPTION_NAMES.get(exc.field, exc.field)
            click.echo(f"error: {field}: {exc.message}", err=True)
            ctx.exit(2)
        except (click.exceptions.ClickException, click.exceptions.Exit,
                click.exceptions.Abort, SystemExit):
            raise
        except Exception as exc:  # an environment failure or a bug: no traceback for users
            if os.environ.get("SCANPLAN_DEBUG"):
                traceback.print_exc()
            click.echo(f"error: {_failure_text(exc)}", err=True)
            ctx.exit(1)


def _failure_text(exc: Exception) -> str:
    """The one-line message of a runtime failure (exit 1)."""
    if isinstance(exc, WriteError):  # disk full, no permission, an interrupted rename
        return exc.message
    if isinstance(exc, OSError):  # another environment failure: name the file and the reason
        where = " -> ".join(os.fsdecode(f) if isinstance(f, str | bytes) else str(f)
                            for f in (exc.filename, exc.filename2) if f is not None)
        reason = exc.strerror or str(exc) or type(exc).__name__
        return f"{where + ': ' if where else ''}{reason} (SCANPLAN_DEBUG=1 shows details)"
    return f"{type(exc).__name__}: {exc} (SCANPLAN_DEBUG=1 shows details)"


class ScaleType(click.ParamType):
    """A scale denominator: ``2000`` or ``1:2000``."""

    name = "SCALE"

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None
                ) -> float:
        from ..norms import parse_scale

        try:
            return parse_scale(value, param.opts[0] if param else "scale")
        except InputError as exc:
            self.fail(exc.message, param, ctx)


SCALE = ScaleType()


def _echo_json(doc: Any) -> None:
    click.echo(json.dumps(doc, ensure_ascii=False, indent=2, allow_nan=False))


class _JsonStream:
    """Print ``{"KEY": [item, ...], ...}`` one item at a time, byte-identical to
    :func:`_echo_json` of the whole document: a batch of thousands of projects never holds
    every result in memory (issue 17)."""

    def __init__(self, key: str) -> None:
        self.key, self.n = key, 0

    @staticmethod
    def _dumps(value: Any) -> str:
        return json.dumps(value, ensure_ascii=False, indent=2, allow_nan=False)

    def add(self, item: Any) -> None:
        """Print the next item of the list (flushed: a reader sees it at once)."""
        body = "\n".join("    " + line for line in self._dumps(item).splitlines())
        head = f'{{\n  {self._dumps(self.key)}: [\n' if self.n == 0 else ",\n"
        click.echo(head + body, nl=False)
        sys.stdout.flush()
        self.n += 1

    def close(self, rest: dict[str, Any]) -> None:
        """End the list and print the document's other keys."""
        out = f'{{\n  {self._dumps(self.key)}: []' if self.n == 0 else "\n  ]"
        for key, value in rest.items():
            out += f",\n  {self._dumps(key)}: " + self._dumps(value).replace("\n", "\n  ")
        click.echo(out + "\n}")


def _finite(ctx: click.Context, param: click.Parameter, value: float | None) -> float | None:
    if value is not None and not math.isfinite(value):
        raise click.BadParameter(f"must be a finite number (got {value})", ctx, param)
    return value


def _text(ctx: click.Context, param: click.Parameter, value: str) -> str:
    """Report text from an option: the same rule as in a project file."""
    from ..project.file import text_problem

    problem = text_problem(value) if value else None
    if problem:
        raise click.BadParameter(problem, ctx, param)
    return value


def _text_or_none(ctx: click.Context, param: click.Parameter, value: str | None
                  ) -> str | None:
    return None if value is None else _text(ctx, param, value)


def norm_options(f: Callable[..., Any]) -> Callable[..., Any]:
    """The norm options shared by scan, uav and plan (spec/interface.md)."""
    for opt in reversed([
        click.option("--norms", default="gkinp-02-036-02", show_default=True,
                     help="Norm set name or folder (scanplan norms list)."),
        click.option("--object-size-m", type=float, callback=_finite,
                     help="Size of the smallest object to interpret [m] (default: the norm "
                     "table's for the map scale)."),
        click.option("--shape", help="Object shape: circle|rectangle|angle|square|wall "
                     "(norm table)."),
        click.option("--object-name", callback=_text_or_none,
                     help="Name of your own object (with --object-size-m), as the reports "
                     "show it."),
        click.option("--probability", type=float, callback=_finite,
                     help="Required recognition probability, 0 < P < 1 (default 0.75)."),
        click.option("--height-formula",
                     type=click.Choice(["instruction", "parallax", "normal_case"]),
                     help="Form of the height constraint P_Z (default: the norm set's; "
                     "normal_case for digital cameras only)."),
    ]):
        f = opt(f)
    return f


def area_options(f: Callable[..., Any]) -> Callable[..., Any]:
    """--area-file and its polygon choice (scan, uav)."""
    for opt in reversed([
        click.option("--area-file", type=click.Path(dir_okay=False),
                     help="Contract polygon: KML, KMZ, GeoJSON, GeoPackage or Shapefile "
                     "(strips and photos are laid out over it; not with --area-m)."),
        click.option("--area-feature", help="The polygon's name or number from 1, when the "
                     "file holds several."),
        click.option("--area-layer", help="The file's layer holding the polygon."),
    ]):
        f = opt(f)
    return f


def _area_of(kwargs: dict[str, Any]) -> Any:
    """The --area-file polygon (None without one); pops the area options."""
    path = kwargs.pop("area_file")
    feature, layer = kwargs.pop("area_feature"), kwargs.pop("area_layer")
    if path is None:
        if feature is not None or layer is not None:
            raise InputError("--area-feature" if feature is not None else "--area-layer",
                             "chooses among the polygons of --area-file; give the file")
        return None
    from ..geo.area import AreaSpec, load_area

    if feature is not None and feature.isdigit():
        feature = int(feature)
    if kwargs.get("area_m") is not None:
        raise InputError("--area-file", "give one area: --area-file or --area-m")
    return load_area(AreaSpec(file=path, feature=feature, layer=layer))


def report_options(f: Callable[..., Any]) -> Callable[..., Any]:
    """--xlsx/--pdf and the title/approval fields of the reports (scan, uav, plan)."""
    for opt in reversed([
        click.option("--xlsx", "xlsx_path", type=click.Path(dir_okay=False),
                     help="Write the Excel report to this file (atomically)."),
        click.option("--pdf", "pdf_path", type=click.Path(dir_okay=False),
                     help="Write the PDF specification to this file (atomically)."),
        click.option("--force", is_flag=True, help="Replace an existing --xlsx/--pdf file "
                     "that scanplan did not write."),
        click.option("--locale", type=click.Choice(["en", "ru"]), default="en",
                     show_default=True, help="Language of the reports."),
        click.option("--project-name", default="", callback=_text,
                     help="Project name for the title block."),
        click.option("--customer", default="", callback=_text,
                     help="Customer for the title block."),
        click.option("--contractor", default="", callback=_text,
                     help="Contractor for the title block."),
        click.option("--approver-position", default="", callback=_text,
                     help="Approval block: position of the person who approves."),
        click.option("--approver-name", default="", callback=_text, help="Approval block: name."),
    ]):
        f = opt(f)
    return f


def _write_reports(opts: dict[str, Any], *, scan: Any = None, uav: Any = None,
                   spec: Any = None) -> None:
    """Write the requested reports as one transaction; say where on stderr (stdout may
    carry --json).

    Both reports are rendered to memory first (a rendering failure touches no file), then
    written with :func:`scanplan.reports.write_atomic_many`: after any failure the previous
    spec.xlsx and spec.pdf are both as they were — never a new workbook beside an old PDF.
    The files ``plan --out`` exports beside them (``opts["exports"]``: path → (kind,
    bytes), the mission, KML, GeoJSON and CSV of issue 11) join the same transaction.
    """
    xlsx, pdf = opts.pop("xlsx_path"), opts.pop("pdf_path")
    exports: dict[str, tuple[str, bytes]] = opts.pop("exports", None) or {}
    force, inputs = opts.pop("force", False), opts.pop("inputs", ())
    fields = opts.pop("fields", {"xlsx": "--xlsx", "pdf": "--pdf"})
    note = opts.pop("note", "")
    from ..outpaths import check_target
    from ..reports import ReportMeta, write_atomic_many

    meta = opts.pop("meta", None) or ReportMeta(
        project=opts.pop("project_name"), customer=opts.pop("customer"),
        contractor=opts.pop("contractor"), locale=opts.pop("locale"),
        approver_position=opts.pop("approver_position"),
        approver_name=opts.pop("approver_name"))
    wanted = [(path, kind) for path, kind in ((xlsx, "xlsx"), (pdf, "pdf")) if path]

    def check() -> None:  # before rendering, and again under the folder lock
        for path, kind in wanted:
            check_target(path, fields[kind], kind, inputs=inputs, force=force)
        for path, (kind, _) in exports.items():
            check_target(path, "--out", kind, inputs=inputs, force=force)

    for path, kind in wanted:
        folder = os.path.dirname(os.path.abspath(path))
        if not os.path.isdir(folder):
            raise InputError(fields[kind], f"folder {folder!r} does not exist")
    if len(wanted) == 2 and (os.path.normcase(os.path.realpath(xlsx))
                             == os.path.normcase(os.path.realpath(pdf))):
        raise InputError("--pdf", f"{pdf!r} is the file --xlsx writes; give another name")
    check()
    extra = {"spec": spec} if spec is not None else {}
    files: dict[str, bytes] = {}
    for path, kind in wanted:
        if kind == "xlsx":
            from ..reports.excel import render_xlsx as render
        else:
            from ..reports.pdf import render_pdf as render
        files[path] = render(scan=scan, uav=uav, meta=meta, **extra)
    files.update({path: data for path, (_, data) in exports.items()})
    write_atomic_many(files, check=check)
    for path in files:
        click.echo(f"wrote {path}{note}", err=True)


def _remove_stale_exports(folder: str, written: set[str]) -> None:
    """Remove the exported files of an earlier run that this one replaced by fewer
    (``mission-04.plan`` of six sorties, now three); say so on stderr."""
    from ..outpaths import folder_lock
    from ..reports.exports import stale_exports

    with folder_lock([folder]):  # not while another scanplan run writes there
        for path in stale_exports(folder, written):
            try:
                os.unlink(path)
            except OSError as exc:
                click.echo(f"warning: {path} is left from an earlier plan and could not be "
                           f"removed ({exc.strerror or exc}); do not fly it", err=True)
            else:
                click.echo(f"removed {path} (left from an earlier plan)", err=True)


def _make_folder(path: str) -> list[str]:
    """``os.makedirs(path)``; the folders it created, deepest first (to undo on failure)."""
    created = []
    probe = os.path.abspath(path)
    while probe and not os.path.exists(probe):
        created.append(probe)
        probe = os.path.dirname(probe)
    try:
        os.makedirs(path, exist_ok=True)
    except OSError as exc:
        _remove_empty(created)
        raise WriteError.from_os_error(path, exc, action="create folder") from exc
    return created


def _remove_empty(folders: list[str]) -> None:
    """Remove the folders (deepest first) that are still empty."""
    for folder in folders:
        try:
            os.rmdir(folder)
        except OSError:
            return


REPORT_KEYS = ("xlsx_path", "pdf_path", "force", "locale", "project_name", "customer", "contractor",
               "approver_position", "approver_name")


def _split_report_options(kwargs: dict[str, Any]) -> dict[str, Any]:
    return {k: kwargs.pop(k) for k in REPORT_KEYS}


@click.group(cls=ScanplanGroup, context_settings={"help_option_names": ["-h", "--help"],
                                                   "max_content_width": 100})
@click.version_option(__version__, "--version", prog_name="scanplan")
def main() -> None:
    """scanplan — plan photo scale, scan pixel and UAV flight height for topographic maps.

    \b
    Examples:
      scanplan scan --map-scale 1:2000 --relief 1.0 --photo-scale 10000 --camera afa-te-100
      scanplan scan --map-scale 2000 --relief 0.5 --camera rc30-153 \\
                    --photo-scale 5000 --photo-scale 10000 --photo-scale 15000
      scanplan cameras list
      scanplan norms list
    """


@main.command()
@click.option("--map-scale", type=SCALE, required=True, help="Map scale, 2000 or 1:2000.")
@click.option("--relief", "relief_interval_m", type=float, required=True, callback=_finite,
              help="Relief (contour) interval h_c [m].")
@click.option("--photo-scale", "photo_scales", type=SCALE, multiple=True, required=True,
              help="Photo scale; repeat for a sweep (like seed 001 Tables 6–9).")
@click.option("--camera", help="Catalogue camera id (scanplan cameras list).")
@click.option("--focal-mm", type=float, callback=_finite, help="Focal length [mm] (no --camera).")
@click.option("--frame-mm", help="Frame WxH [mm], across × along track, e.g. 230x230.")
@click.option("--resolving-power", "resolving_power_lpmm", type=float, callback=_finite,
              help="Resolving power of the photos R [lines/mm] (default: the camera's).")
@click.option("--overlap-pct", "forward_overlap_pct", type=float, callback=_finite,
              help="Forward overlap [%] (default: the norm set's, 60).")
@norm_options
@click.option("--pr-coefficient", type=float, callback=_finite,
              help="k_R in P_R = k_R/R (default 0.5; the Instruction prints 0.4).")
@click.option("--rounding", "recognition_rounding", type=click.Choice(["exact", "paper"]),
              help="sqrt(-ln P) exactly, or the paper's rounded 0.53.")
@click.option("--scanner", help="Scanner id: round the pixel down to its steps.")
@click.option("--pixel-um", "pixel_um", type=float, multiple=True, callback=lambda c, p, v: tuple(
    _finite(c, p, x) for x in v), help="A scan pixel you have [µm]: show the largest photo "
              "scale it supports (repeatable).")
@click.option("--bands", type=click.IntRange(1, 16), default=1, show_default=True,
              help="Bands per scanned frame (1 panchromatic, 3 colour).")
@click.option("--bit-depth", "bits_per_band", type=click.Choice(["8", "16"]), default="8",
              show_default=True, help="Bits per band.")
@area_options
@click.option("--side-overlap-pct", "film_side_overlap_pct", type=float, default=30.0,
              show_default=True, callback=_finite,
              help="Side overlap [%] of the flight scheme over --area-file.")
@report_options
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
def scan(as_json: bool, bits_per_band: str, **kwargs: Any) -> None:
    """Film photos: every scan-pixel constraint at one or more photo scales.

    Evaluates the Instruction's P_S, P_Z, P_P, P_R (corrected k_R = 0.5) and the
    interpretation pixel P_D of seed 001, picks the binding one and explains it.

    \b
    Example (the Instruction's worked example):
      scanplan scan --map-scale 1:2000 --relief 1.0 --photo-scale 1:10000 \\
                    --camera afa-te-100 --resolving-power 40
    """
    from ..project.api import scan_job
    from ..reports.jsondoc import scan_plan_dict
    from ..reports.text import format_scan_plan

    report = _split_report_options(kwargs)
    area = _area_of({**kwargs, "area_m": None})
    for key in ("area_file", "area_feature", "area_layer"):
        kwargs.pop(key)
    side = kwargs.pop("film_side_overlap_pct")
    job = scan_job(bits_per_band=int(bits_per_band), **kwargs)
    schemes = _film_schemes(job, area, side) if area is not None else []
    if as_json:
        doc = scan_plan_dict(job.plan, job.norm_set)
        if area is not None:
            from ..reports.jsondoc import area_dict, layout_dict

            doc["area"] = area_dict(area)
            doc["flight_schemes"] = [{"photo_scale": sc.photo_scale, **layout_dict(lay)}
                                     for sc, lay in schemes]
        _echo_json(doc)
    else:
        click.echo(format_scan_plan(job.plan, job.norm_set.name, job.norm_set.title))
        if area is not None:
            from ..reports.text import format_area, format_layout

            click.echo("\n" + format_area(area))
            for sc, lay in schemes:
                click.echo(format_layout(lay, f"1:{sc.photo_scale:g}"))
    _write_reports(report, scan=job)


def _film_schemes(job: Any, area: Any, side: float) -> list[tuple[Any, Any]]:
    """The aerial survey's flight scheme over ``area`` at every photo scale of ``job``."""
    from ..core.domains import check_domain
    from ..project.flightplan import film_layout

    try:
        check_domain("side_overlap_pct", side)
    except InputError as exc:
        raise InputError("--side-overlap-pct", exc.message) from None
    inp = job.plan.inputs
    return [(sc, film_layout(sc, inp.frame_width_mm, inp.frame_along_mm, inp.focal_mm,
                             inp.forward_overlap_pct, side, area))
            for sc in job.plan.scenarios]


@main.command()
@click.option("--camera", help="Digital camera id (scanplan cameras list).")
@click.option("--pixel-um", type=float, callback=_finite, help="Pixel pitch [µm] (no --camera).")
@click.option("--focal-mm", type=float, callback=_finite, help="Focal length [mm].")
@click.option("--sensor-mm", help="Sensor WxH [mm], e.g. 36x24 (W across track when "
              "mounted landscape).")
@click.option("--orientation", type=click.Choice(["landscape", "portrait"]),
              help="Camera mounting: landscape = sensor width across track (default: the "
              "catalogue's, else landscape); portrait turns footprint, spacing and base.")
@click.option("--f-number", type=float, callback=_finite,
              help="Working f-number (default: the catalogue's).")
@click.option("--height-m", type=float, callback=_finite,
              help="Planned flight height above ground [m] (default: the maximum planned "
              "height, rounded down to 5 m; needs --map-scale or --gsd-cm).")
@click.option("--gsd-cm", type=float, callback=_finite,
              help="Target ground sample distance [cm]: the highest flown height must "
              "deliver it.")
@click.option("--max-height-m", type=float, callback=_finite,
              help="Altitude ceiling for the highest flown height above ground [m] "
              "(default: the norm set's, 150 m).")
@click.option("--height-tolerance-pct", type=float, default=0.0, show_default=True,
              callback=_finite, help="How much higher the UAV may fly than planned [%] "
              "(seed 002: 300 m planned, 420 m flown = 40).")
@click.option("--speed-ms", type=float, callback=_finite,
              help="Ground speed [m/s] (default 15 for a UAV; required for a camera on an "
              "aircraft).")
@click.option("--exposure-s", type=float, default=0.001, show_default=True, callback=_finite,
              help="Exposure time [s].")
@click.option("--overlap-pct", "forward_overlap_pct", type=float, callback=_finite,
              help="Forward overlap [%] (default 80 for a UAV, the norm set's 60 for a camera "
              "on an aircraft).")
@click.option("--side-overlap-pct", type=float, callback=_finite,
              help="Side overlap [%] (default 60 for a UAV, 30 for a camera on an aircraft).")
@click.option("--map-scale", type=SCALE, help="Map scale: adds the constraints and max height.")
@click.option("--relief", "relief_interval_m", type=float, callback=_finite,
              help="Relief interval h_c [m] (with --map-scale).")
@norm_options
@click.option("--r-max", type=float, default=0.3, show_default=True, callback=_finite,
              help="Brightness coefficient of the lightest detail.")
@click.option("--r-min", type=float, default=0.1, show_default=True, callback=_finite,
              help="Brightness coefficient of the darkest detail.")
@click.option("--haze-contrast", type=float, callback=_finite,
              help="Contrast transmission of the air column c, 0 < c ≤ 1 (default 0.9: "
              "clear air below 500 m).")
@click.option("--k0", "threshold_k0", type=float, callback=_finite,
              help="Sensor threshold contrast at low frequency (default 0.03).")
@click.option("--shift-factor", type=float, default=1.0, show_default=True, callback=_finite,
              help="Photographic/geometric image shift, 0 < k ≤ 1 (0.6–0.7 summer, "
              "1 bright canopy).")
@click.option("--random-speed-ms", type=float, default=0.0, callback=_finite,
              help="RMS random linear speed of a light UAV [m/s].")
@click.option("--roll-rate", "roll_rate_rad_s", type=float, default=0.0, callback=_finite,
              help="RMS angular rate about the longitudinal axis [rad/s].")
@click.option("--pitch-rate", "pitch_rate_rad_s", type=float, default=0.0, callback=_finite,
              help="RMS angular rate about the transverse axis [rad/s].")
@click.option("--yaw-rate", "yaw_rate_rad_s", type=float, default=0.0, callback=_finite,
              help="RMS angular rate about the vertical axis [rad/s].")
@click.option("--area-m", help="Block to cover, WIDTHxLENGTH [m], e.g. 2000x3000.")
@area_options
@click.option("--direction-deg", help='Flight-line direction over --area-file, clockwise from '
              'grid north [°], or "auto" (default): the least flight length.')
@click.option("--max-flight-time-min", type=float, callback=_finite,
              help="Longest sortie on one battery [min]: the block is split into sorties.")
@click.option("--roll-deg", type=float, default=0.0, callback=_finite,
              help="Roll for the tilted-frame corner GSD [°].")
@click.option("--pitch-deg", type=float, default=0.0, callback=_finite,
              help="Pitch for the tilted-frame corner GSD [°].")
@report_options
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
def uav(as_json: bool, **kwargs: Any) -> None:
    """Digital camera on a UAV: GSD, real ground resolution L from the MTF chain, blur,
    flight geometry; with --map-scale/--relief the constraints and the maximum planned height
    (its highest flown height within the altitude ceiling --max-height-m).

    \b
    Example (seed 002's flight):
      scanplan uav --camera canon-eos-5d-mark-ii-50 --f-number 8 --height-m 300 \\
                   --height-tolerance-pct 40 --speed-ms 25 --map-scale 2000 --relief 0.5
    """
    from ..project.api import uav_job
    from ..project.flightplan import LayoutOptions
    from ..reports.jsondoc import uav_plan_dict
    from ..reports.text import format_uav_plan

    report = _split_report_options(kwargs)
    area = _area_of(kwargs)
    direction = kwargs.pop("direction_deg")
    if direction is not None and direction != "auto":
        try:
            direction = float(direction)
        except ValueError:
            raise InputError("--direction-deg", f'must be an angle in degrees or "auto" (got '
                             f"{direction!r})") from None
    opts = LayoutOptions(direction_deg=direction,
                         max_flight_time_min=kwargs.pop("max_flight_time_min"))
    if area is None and kwargs.get("area_m") is None and (
            direction is not None or opts.max_flight_time_min is not None):
        raise InputError("--direction-deg" if direction is not None
                         else "--max-flight-time-min", "applies to an area: give --area-file "
                         "or --area-m")
    job = uav_job(**kwargs, area=area, layout_options=opts)
    if as_json:
        doc = uav_plan_dict(job.plan, job.norm_set)
        if job.layout is not None:
            from ..reports.jsondoc import area_dict, layout_dict

            doc["area"] = area_dict(job.layout.area)
            doc["layout"] = layout_dict(job.layout)
        _echo_json(doc)
    else:
        click.echo(format_uav_plan(job.plan, job.norm_set.name))
        if job.layout is not None:
            from ..reports.text import format_area, format_layout

            click.echo("\n" + format_area(job.layout.area))
            click.echo(format_layout(job.layout))
    _write_reports(report, uav=job)


@main.command()
@click.argument("projects", nargs=-1, required=True, type=click.Path())
@click.option("--out", "out_dir", type=click.Path(file_okay=False),
              help="Write spec.xlsx and spec.pdf into this folder (batch: NAME.xlsx/.pdf, "
              "NAME-2.xlsx/.pdf for a second project named NAME); for an area given as a "
              "polygon also mission.plan (QGroundControl), flight.kml, flight.geojson and "
              "photos.csv (film: film-flight.kml, film-flight.geojson, film-frames.csv).")
@click.option("--xlsx", "xlsx_path", type=click.Path(dir_okay=False),
              help="Write the Excel report to this file (one project; not with --out).")
@click.option("--pdf", "pdf_path", type=click.Path(dir_okay=False),
              help="Write the PDF specification to this file (one project; not with --out).")
@click.option("--force", is_flag=True,
              help="Replace existing report files that scanplan did not write.")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
def plan(projects: tuple[str, ...], out_dir: str | None, xlsx_path: str | None,
         pdf_path: str | None, force: bool, as_json: bool) -> None:
    """The main job: the scan / flight specification for a mapping contract.

    PROJECTS are project files (TOML) or folders of them; several give a batch with one
    summary table, and a bad file is reported while the others still run.

    \b
    Examples:
      scanplan plan examples/instruction-2000-film.toml --out out/
      scanplan plan examples/archive-12000-for-2000.toml
      scanplan plan examples/ --json
    """
    files: list[str] = []
    for item in projects:
        if os.path.isdir(item):
            files += sorted(os.path.join(item, f) for f in os.listdir(item)
                            if f.endswith(".toml"))
        else:
            files.append(item)
    if not files:
        raise InputError("PROJECTS", "no project files (*.toml) found")
    batch = len(files) > 1
    if out_dir and (xlsx_path or pdf_path):
        raise InputError("--out", "give either --out (a folder for both reports) or "
                         "--xlsx/--pdf (file names), not both")
    if batch and (xlsx_path or pdf_path):
        raise InputError("--xlsx", "--xlsx/--pdf name one file; with several projects use --out")
    created: list[str] = []
    if out_dir:
        if os.path.exists(out_dir) and not os.path.isdir(out_dir):
            raise InputError("--out", f"{out_dir!r} is not a folder")
        created = _make_folder(out_dir)
    try:
        _plan_files(files, batch, out_dir, xlsx_path, pdf_path, as_json, force)
    finally:  # a folder --out created stays only if something was written into it
        _remove_empty(created)


def batch_stems(files: list[str]) -> list[str]:
    """One report name per project of a batch: the file's stem, ``STEM-2``, ``STEM-3`` …
    for later projects with the same stem (compared without case: some file systems ignore
    it), so that no project's reports replace another's."""
    used: set[str] = set()
    out = []
    for path in files:
        stem = os.path.splitext(os.path.basename(path))[0] or "spec"
        name, n = stem, 1
        while name.casefold() in used:
            n += 1
            name = f"{stem}-{n}"
        used.add(name.casefold())
        out.append(name)
    return out


def _plan_files(files: list[str], batch: bool, out_dir: str | None, xlsx_path: str | None,
                pdf_path: str | None, as_json: bool, force: bool = False) -> None:
    """``plan`` after its arguments are checked: run one project or a batch."""
    from ..project.file import load_project
    from ..project.spec import plan_project
    from ..reports.jsondoc import plan_result_dict
    from ..reports.text import format_plan_result

    stems = dict(zip(files, batch_stems(files), strict=True)) if batch else {}

    def run_one(path: str) -> Any:
        targets = {"xlsx_path": xlsx_path, "pdf_path": pdf_path}
        fields = {"xlsx": "--xlsx", "pdf": "--pdf"}
        note = ""
        if out_dir:
            stem = stems[path] if batch else "spec"
            targets = {"xlsx_path": os.path.join(out_dir, stem + ".xlsx"),
                       "pdf_path": os.path.join(out_dir, stem + ".pdf")}
            fields = {"xlsx": "--out", "pdf": "--out"}
            if batch:
                base = os.path.splitext(os.path.basename(path))[0]
                note = f" (for {path}" + (f"; the name {base} is taken by another project "
                                          "of this batch" if stem != base else "") + ")"
        result = plan_project(load_project(path))
        exports = {}
        if out_dir:
            from ..reports.exports import export_files

            exports = export_files(result, out_dir, prefix=f"{stem}-" if batch else "")
        film = result.film.job if result.film else None
        uav_ = result.uav.job if result.uav else None
        _write_reports({**targets, "force": force, "inputs": files, "fields": fields,
                        "note": note, "locale": result.meta.locale,
                        "project_name": result.meta.project, "customer": result.meta.customer,
                        "contractor": result.meta.contractor,
                        "approver_position": result.meta.approver_position,
                        "approver_name": result.meta.approver_name,
                        "meta": result.meta, "exports": exports}, scan=film, uav=uav_,
                       spec=result)
        if out_dir and not batch:  # never leave a stale sortie of an earlier plan behind
            _remove_stale_exports(out_dir, set(exports))
        return result

    if not batch:
        result = run_one(files[0])
        if as_json:
            _echo_json(plan_result_dict(result))
        else:
            click.echo(format_plan_result(result))
        return
    done: list[tuple[str, Any]] = []  # with --json the results are streamed, not kept
    failed: list[tuple[str, str]] = []
    stream = _JsonStream("projects") if as_json else None
    stopped = ""  # a write failure (disk full) stops the batch: the project it stopped at
    with click.progressbar(files, label="planning", file=sys.stderr) as bar:
        for path in bar:
            try:
                result = run_one(path)
                if stream is not None:
                    stream.add(plan_result_dict(result))
                    result = None
                done.append((path, result))
            except InputError as exc:  # a bad project: report it, run the others
                failed.append((path, f"{exc.field}: {exc.message}"))
            except WriteError as exc:
                failed.append((path, exc.message))
                stopped = path
                break
    not_run = files[len(done) + len(failed):]
    if stream is not None:
        stream.close({"errors": [{"file": f, "message": m} for f, m in failed]
                      + [{"file": f, "message": "not planned: the batch stopped"}
                         for f in not_run]})
    else:
        from ..reports.text import batch_summary, batch_warnings

        click.echo(batch_summary(done, failed))
        warned = batch_warnings(done)
        if warned:
            click.echo(warned)
    for _path, msg in failed:
        click.echo(f"error: {msg}", err=True)
    if stopped:
        click.echo(f"error: the batch stopped at {stopped} ({len(done)} of {len(files)} "
                   "projects written" + (f"; not planned: {', '.join(not_run)}" if not_run
                                         else "") + ")", err=True)
        sys.exit(1)
    if failed:
        sys.exit(2)


from .cameras import cameras  # noqa: E402
from .norms import norms  # noqa: E402  (the group needs `main` defined first)

main.add_command(cameras)
main.add_command(norms)

from .init import init  # noqa: E402

main.add_command(init)


def run() -> None:  # pragma: no cover - console entry used by python -m scanplan
    main(prog_name="scanplan")


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
