"""The ``scanplan`` command line (click).

Exit codes: 0 ok; 2 bad usage or invalid input (the message names the option, key or
cell and the allowed range); 1 runtime failure (a message, never a traceback — set
``SCANPLAN_DEBUG=1`` to see one). The commands raise; one policy turns what they raise into
the message and the exit code (:mod:`scanplan.cli.errors`).
"""

from __future__ import annotations

import contextlib
import functools
import os
import sys
import warnings
from collections.abc import Callable, Iterator
from typing import Any

import click

from .._version import __version__
from ..errors import InputError, WriteError
from ..project.inputs import option_names
from . import console, outputs
from .errors import Failed, PolicyGroup
from .options import (
    NORM_INPUTS,
    REPORT_INPUTS,
    complete_formats,
    decimal,
    input_option,
    unlisted_inputs,
)
from .outset import batch_text, say_export_notes, write_reports, write_set
from .projects import check_stdin

OPTION_NAMES = option_names()
"""Python names of inputs (error fields) → the option a user typed (the input registry's)."""


LAZY_COMMANDS = {
    "aircraft": ("scanplan.cli.aircraft", "aircraft",
                 "The aircraft catalogue: flight time per battery, speeds, wind,..."),
    "cameras": ("scanplan.cli.cameras", "cameras",
                "The camera and scanner catalogue (film, digital on UAVs,..."),
    "init": ("scanplan.cli.init", "init",
             "Write a commented project file that `scanplan plan` runs as it..."),
    "norms": ("scanplan.cli.norms", "norms",
              "Norm sets: list, show, validate and import spreadsheets,..."),
    "serve": ("scanplan.cli.serve", "serve", "Plan on a map in the browser: a local web page."),
}
"""Commands imported only when they run (``scanplan --help`` must not import numpy):
name → (module, attribute, the short help ``--help`` lists)."""


class ScanplanGroup(PolicyGroup):
    """The ``scanplan`` group: its commands run under the command line's error policy
    (:mod:`scanplan.cli.errors`; errors name the option a user typed), and the heavy
    subcommands (:data:`LAZY_COMMANDS`) are imported only when they are used."""

    field_names = OPTION_NAMES

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(set(self.commands) | set(LAZY_COMMANDS))

    def get_command(self, ctx: click.Context, name: str) -> click.Command | None:
        if name in LAZY_COMMANDS and name not in self.commands:
            import importlib

            module, attr, _ = LAZY_COMMANDS[name]
            self.add_command(getattr(importlib.import_module(module), attr), name)
        return super().get_command(ctx, name)

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        """The command list, without importing the lazy ones."""
        limit = formatter.width - 6 - max(len(n) for n in self.list_commands(ctx))
        rows = []
        for name in self.list_commands(ctx):
            if name in self.commands:
                cmd = self.commands[name]
                if cmd.hidden:
                    continue
                rows.append((name, cmd.get_short_help_str(limit)))
            else:
                rows.append((name, LAZY_COMMANDS[name][2]))
        if rows:
            with formatter.section("Commands"):
                formatter.write_dl(rows)

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        console.set_verbosity()  # each run starts at the default; -q/-v then set it
        outputs.reset()  # and with no PDF engine failure of an earlier run
        return super().parse_args(ctx, args)

    def invoke(self, ctx: click.Context) -> Any:
        console.setup_streams()  # every character written, in any terminal encoding
        with warnings.catch_warnings():
            if not os.environ.get("SCANPLAN_DEBUG"):  # no library's warning on a
                warnings.simplefilter("ignore")  # user's terminal (the tests raise them)
            return super().invoke(ctx)


def _echo_json(doc: Any) -> None:
    import json

    click.echo(json.dumps(doc, ensure_ascii=False, indent=2, allow_nan=False))


class _JsonStream:
    """Print ``{"KEY": [item, ...], ...}`` one item at a time, byte-identical to
    :func:`_echo_json` of the whole document: a batch of thousands of projects never holds
    every result in memory."""

    def __init__(self, key: str) -> None:
        self.key, self.n = key, 0

    @staticmethod
    def _dumps(value: Any) -> str:
        import json

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


def norm_options(command: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """The norm options of ``command`` (scan or uav), from the input registry."""
    def decorate(f: Callable[..., Any]) -> Callable[..., Any]:
        for name in reversed(NORM_INPUTS):
            f = input_option(command, name)(f)
        return f
    return decorate


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
    try:
        return load_area(AreaSpec(file=path, feature=feature, layer=layer))
    except InputError as exc:
        if exc.field != path:  # a feature, a layer: named already
            raise
        raise InputError("--area-file", f"{path}: {exc.message}") from None


def report_options(f: Callable[..., Any]) -> Callable[..., Any]:
    """--xlsx/--pdf and the title/approval fields of the reports (scan, uav, plan)."""
    for opt in reversed([
        click.option("--xlsx", "xlsx_path", type=click.Path(dir_okay=False),
                     help="Write the Excel report to this file (atomically)."),
        click.option("--pdf", "pdf_path", type=click.Path(dir_okay=False),
                     help="Write the PDF specification to this file (atomically)."),
        click.option("--force", is_flag=True, help="Replace an existing --xlsx/--pdf file "
                     "that scanplan did not write."),
        *(input_option("uav", name) for name in REPORT_INPUTS),
    ]):
        f = opt(f)
    return f


def _write_reports(opts: dict[str, Any], *, scan: Any = None, uav: Any = None) -> None:
    """``scan``/``uav``'s --xlsx/--pdf (``opts``: :data:`REPORT_KEYS`), as one transaction
    (:func:`scanplan.cli.outset.write_reports`)."""
    from ..reports import ReportMeta

    meta = ReportMeta(project=opts["project_name"], customer=opts["customer"],
                      contractor=opts["contractor"], locale=opts["locale"],
                      approver_position=opts["approver_position"],
                      approver_name=opts["approver_name"])
    write_reports(xlsx=opts["xlsx_path"], pdf=opts["pdf_path"], meta=meta, scan=scan, uav=uav,
                  force=opts["force"], pdf_worker=opts["pdf_worker"])


REPORT_KEYS = ("xlsx_path", "pdf_path", "force", "locale", "project_name", "customer", "contractor",
               "approver_position", "approver_name", "pdf_worker")


def _report_folders(xlsx_path: str | None, pdf_path: str | None) -> None:
    """``--xlsx``/``--pdf`` point into existing folders (and not at one file): said before
    the plan is made, not after it has been printed."""
    from ..reports.documents import Target, refuse_targets

    refuse_targets([Target(p, k, f"--{k}") for p, k in ((xlsx_path, "xlsx"), (pdf_path, "pdf"))
                    if p])


@contextlib.contextmanager
def _pdf_worker(wanted: bool) -> Iterator[Any]:
    """The PDF worker (:class:`scanplan.reports.pdfworker.PdfWorker`) when a PDF is
    ``wanted``, else None; started first of all, so that it imports the renderer while this
    process imports the engine and plans, and stopped (reaped) however the command ends."""
    worker = None
    if wanted:
        from ..reports.pdfworker import PdfWorker

        worker = PdfWorker.start()
    try:
        yield worker
    finally:
        if worker is not None:
            worker.stop()


def _writes_reports(command: Callable[..., Any]) -> Callable[..., Any]:
    """A command with ``--xlsx``/``--pdf``: their folders checked first, then its
    ``pdf_worker`` argument is :func:`_pdf_worker`'s."""
    @functools.wraps(command)
    def run(**kwargs: Any) -> Any:
        _report_folders(kwargs.get("xlsx_path"), kwargs.get("pdf_path"))
        with _pdf_worker(bool(kwargs.get("pdf_path"))) as worker:
            command(pdf_worker=worker, **kwargs)
        outputs.pdf_failure_exit(bool(kwargs.get("pdf_path")))
    return run


def _split_report_options(kwargs: dict[str, Any]) -> dict[str, Any]:
    return {k: kwargs.pop(k) for k in REPORT_KEYS}


@click.group(cls=ScanplanGroup, context_settings={"help_option_names": ["-h", "--help"],
                                                   "max_content_width": 100})
@click.version_option(__version__, "--version", prog_name="scanplan")
@console.verbosity_options
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
    from ..io.rundir import run_scope

    # the command's temporary folder: every temporary file of the run (and of the libraries
    # it drives) lives there, removed however the command ends (SIGTERM included)
    click.get_current_context().with_resource(run_scope())


def _inputs(command: str, names: list[str], **per_name: dict[str, Any]
            ) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """The registry's options of ``command`` for ``names``, in that order."""
    def decorate(f: Callable[..., Any]) -> Callable[..., Any]:
        for name in reversed(names):
            f = (norm_options(command) if name == "<norms>"
                 else input_option(command, name, **per_name.get(name, {})))(f)
        return f
    return decorate


_SCAN_INPUTS = ["map_scale", "relief_interval_m", "photo_scales", "camera", "focal_mm", "frame_mm",
                "resolving_power_lpmm", "forward_overlap_pct", "<norms>", "pr_coefficient",
                "recognition_rounding", "scanner", "pixel_um", "bands", "bits_per_band"]
_SCAN_AREA = ["area_file", "area_feature", "area_layer", "film_side_overlap_pct"]


@main.command()
@console.verbosity_options
@_inputs("scan", _SCAN_INPUTS + unlisted_inputs("scan", _SCAN_INPUTS, _SCAN_AREA),
         map_scale={"required": True}, relief_interval_m={"required": True},
         photo_scales={"required": True})
@_inputs("scan", _SCAN_AREA)
@report_options
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
@_writes_reports
def scan(as_json: bool, bits_per_band: str, **kwargs: Any) -> None:
    """Film photos: every scan-pixel constraint at one or more photo scales.

    Evaluates the Instruction's P_S, P_Z, P_P, P_R (corrected k_R = 0.5) and the
    interpretation pixel P_D (Miheeva & Ilushenko 2015), picks the binding one and explains it.

    \b
    Example (the Instruction's worked example):
      scanplan scan --map-scale 1:2000 --relief 1.0 --photo-scale 1:10000 \\
                    --camera afa-te-100 --resolving-power 40
    """
    from ..project.jobs import scan_job
    from ..reports.jsondoc import scan_plan_dict
    from ..reports.text import format_scan_plan

    report = _split_report_options(kwargs)
    area = _area_of({**kwargs, "area_m": None})
    for key in ("area_file", "area_feature", "area_layer"):
        kwargs.pop(key)
    side = kwargs.pop("film_side_overlap_pct")
    if side is not None and area is None:  # checked, never silently unused
        from ..core.domains import check_domain

        check_domain("--side-overlap-pct", side, "side_overlap_pct")
        raise InputError("--side-overlap-pct", "sets the side overlap of the flight lines "
                         "over --area-file; give the file")
    if side is None:
        from ..project.inputs import by_key

        side = by_key("film", "side_overlap_pct").default
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
        loc = report["locale"] or "en"  # --locale: the terminal speaks the reports' language
        click.echo(format_scan_plan(job.plan, job.norm_set.name, job.norm_set.title,
                                    locale=loc, norm_set=job.norm_set))
        if area is not None:
            from ..i18n.messages import scale_text
            from ..reports.text import format_area, format_layout

            click.echo("\n" + format_area(area, loc))
            for sc, lay in schemes:
                click.echo(format_layout(lay, scale_text(sc.photo_scale, loc), loc))
    _write_reports(report, scan=job)


def _film_schemes(job: Any, area: Any, side: float) -> list[tuple[Any, Any]]:
    """The aerial survey's flight scheme over ``area`` at every photo scale of ``job``."""
    from ..core.domains import check_domain
    from ..project.flightplan import film_layout

    check_domain("--side-overlap-pct", side, "side_overlap_pct")
    inp = job.plan.inputs
    return [(sc, film_layout(sc, inp.frame_width_mm, inp.frame_along_mm, inp.focal_mm,
                             inp.forward_overlap_pct, side, area))
            for sc in job.plan.scenarios]


_UAV_INPUTS = ["camera", "camera_name", "pixel_um", "focal_mm", "sensor_mm", "orientation",
               "f_number", "height_m", "gsd_cm", "max_height_m", "gsd_area", "height_tolerance_pct",
               "speed_ms", "exposure_s", "forward_overlap_pct", "side_overlap_pct", "map_scale",
               "relief_interval_m", "<norms>", "r_max", "r_min", "haze_contrast", "threshold_k0",
               "shift_factor", "random_speed_ms", "roll_rate_rad_s", "pitch_rate_rad_s",
               "yaw_rate_rad_s", "area_m", "roll_deg", "pitch_deg", "parallax_error_px"]
_UAV_AREA = ["area_file", "area_feature", "area_layer", "direction_deg", "max_flight_time_min",
             "aircraft"]


@main.command()
@console.verbosity_options
@_inputs("uav", _UAV_INPUTS + unlisted_inputs("uav", _UAV_INPUTS, _UAV_AREA),
         map_scale={"help": "Map scale, 2000 or 1:2000: adds the constraints and the maximum "
                    "planned height."},
         relief_interval_m={"help": "Relief (contour) interval h_c [m] (with --map-scale)."})
@_inputs("uav", _UAV_AREA)
@report_options
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
@_writes_reports
def uav(as_json: bool, **kwargs: Any) -> None:
    """Digital camera on a UAV: GSD, real ground resolution L from the MTF chain, blur,
    flight geometry; with --map-scale/--relief the constraints and the maximum planned height
    (its highest flown height within the altitude ceiling --max-height-m).

    \b
    Example (the Ptero-E flight of 2014, flown at 300–420 m):
      scanplan uav --camera canon-eos-5d-mark-ii-50 --f-number 8 --height-m 300 \\
                   --height-tolerance-pct 40 --speed-ms 25 --shift-factor 0.65 \\
                   --map-scale 2000 --relief 0.5
    """
    from ..project.flightplan import LayoutOptions
    from ..project.jobs import uav_job
    from ..reports.jsondoc import uav_plan_dict
    from ..reports.text import format_uav_plan

    report = _split_report_options(kwargs)
    area = _area_of(kwargs)
    direction = kwargs.pop("direction_deg")
    if direction == "auto":
        direction = None  # the default: "auto" over a polygon, along the block's length
    if direction is not None:
        try:
            direction = decimal(direction)  # 12.5 or 12,5
        except ValueError:
            raise InputError("--direction-deg", f'must be an angle in degrees or "auto" (got '
                             f"{direction!r})") from None
    sortie_min = kwargs.pop("max_flight_time_min")
    craft = kwargs.pop("aircraft")
    if sortie_min is None and (area is not None or kwargs.get("area_m") is not None):
        from ..norms.aircraft import aircraft as catalogue_aircraft
        from ..norms.aircraft import carriers_of

        if craft is None:  # the camera's one carrier, if only one carries it
            carriers = carriers_of(kwargs.get("camera"))
            craft = carriers[0].id if len(carriers) == 1 else None
        if craft is not None:  # the aircraft's battery, less the reserve
            sortie_min = catalogue_aircraft(craft, "--aircraft").usable_flight_time_min()
    opts = LayoutOptions(direction_deg=direction, max_flight_time_min=sortie_min)
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
        loc = report["locale"] or "en"  # --locale: the terminal speaks the reports' language
        click.echo(format_uav_plan(job.plan, job.norm_set.name, locale=loc,
                                   norm_set=job.norm_set))
        if job.layout is not None:
            from ..reports.text import format_area, format_layout

            click.echo("\n" + format_area(job.layout.area, loc))
            click.echo(format_layout(job.layout, locale=loc))
    _write_reports(report, uav=job)


@main.command()
@console.verbosity_options
@click.argument("projects", nargs=-1, required=True, type=click.Path())
@click.option("--out", "out_dir", type=click.Path(file_okay=False),
              help="Write spec.xlsx and spec.pdf into this folder (batch: NAME.xlsx/.pdf, "
              "NAME-2.xlsx/.pdf for a second project named NAME); for an area given as a "
              "polygon also the mission: mission.plan (QGroundControl), mission.waypoints "
              "(Mission Planner) and, for a DJI camera, mission-dji.kmz (DJI Pilot 2) — "
              "mission-01.plan, mission-01.waypoints, mission-dji-01.kmz … when it needs "
              "several sorties — "
              "and flight.kml, flight.geojson, flight.gpkg and photos.csv (film: "
              "film-flight.kml, film-flight.geojson, film-flight.gpkg, film-frames.csv).")
@click.option("--xlsx", "xlsx_path", type=click.Path(dir_okay=False),
              help="Write the Excel report to this file (one project; not with --out).")
@click.option("--pdf", "pdf_path", type=click.Path(dir_okay=False),
              help="Write the PDF specification to this file (one project; not with --out).")
@click.option("--force", is_flag=True,
              help="Replace existing report files that scanplan did not write.")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
@click.option("--formats", callback=outputs.parse_formats, metavar="LIST",
              shell_complete=complete_formats,
              help="The outputs --out writes, comma-separated: xlsx, pdf, missions, gis "
              "(default: all). Without a PDF engine the others are still written.")
@click.option("--jobs", type=click.IntRange(1, 256), default=None,
              help="Projects planned at once in worker processes (default: the machine's "
              "cores); the output is the same for any number.")
@click.option("--locale", type=click.Choice(["en", "ru"]), default=None,
              help="Language of the documents and the terminal summary, over the project's "
              "[project] locale (default: the project's).")
def plan(projects: tuple[str, ...], out_dir: str | None, xlsx_path: str | None,
         pdf_path: str | None, force: bool, as_json: bool, formats: tuple[str, ...] | None,
         jobs: int | None, locale: str | None) -> None:
    """The main job: the scan / flight specification for a mapping contract.

    PROJECTS are project files (TOML) or folders of them; several give a batch with one
    summary table, and a bad file is reported while the others still run. - reads one
    project from standard input.

    \b
    Examples:
      scanplan plan examples/instruction-2000-film.toml --out out/
      scanplan plan examples/uav-town-2000.toml --locale ru --out out-ru/
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
    check_stdin(files)
    batch = len(files) > 1
    if out_dir and (xlsx_path or pdf_path):
        raise InputError("--out", "give either --out (a folder for both reports) or "
                         "--xlsx/--pdf (file names), not both")
    if batch and (xlsx_path or pdf_path):
        raise InputError("--xlsx", "--xlsx/--pdf name one file; with several projects use --out")
    if formats is not None and not out_dir:  # never silently unused
        raise InputError("--formats", "chooses the files --out writes; give --out")
    _report_folders(xlsx_path, pdf_path)
    from ..reports.documents import make_folder, refuse_folder, remove_empty

    created: list[str] = []
    if out_dir:
        refuse_folder(out_dir, "--out")
        created = make_folder(out_dir)
    try:
        _plan_files(files, batch, out_dir, xlsx_path, pdf_path, as_json, force,
                    jobs or os.cpu_count() or 1, formats, locale)
    finally:  # a folder --out created stays only if something was written into it
        remove_empty(created)
    outputs.pdf_failure_exit(bool(pdf_path) or "pdf" in (formats or ()))


def batch_stems(files: list[str]) -> list[str]:
    """:func:`scanplan.io.targets.batch_stems` (imported when a batch runs)."""
    from ..io.targets import batch_stems as stems

    return stems(files)


def _run_project(path: str, out_dir: str | None, stem: str | None, xlsx_path: str | None,
                 pdf_path: str | None, files: list[str], force: bool,
                 say: Callable[[str], None] | None = None, pdf_worker: Any = None,
                 formats: tuple[str, ...] | None = None,
                 locale: str | None = None) -> tuple[Any, Any]:
    """Plan one project and write its reports (both or neither); the PlanResult and its
    tables (one ``ResultTables``: the documents' view holds them, and the terminal summary
    lays them out). ``say`` receives the ``wrote FILE`` lines (default: stderr);
    ``pdf_worker`` (a :class:`scanplan.reports.pdfworker.PdfWorker`) renders the PDF on
    another core."""
    from ..project.spec import plan_project
    from ..reports.documents import plan_outputs, project_inputs
    from ..reports.views import ResultTables
    from .projects import read_project

    fields = ("--xlsx", "--pdf")
    note = ""
    explicit = bool(pdf_path) or "pdf" in (formats or ())  # its absence fails at the end
    if out_dir and stem is not None:
        base = os.path.splitext(os.path.basename(path))[0]
        taken = ("the batch summary" if base.casefold() == "summary"
                 else "another project of this batch")
        note = f" (for {path}" + (f"; the name {base} is taken by {taken}"
                                  if stem != base else "") + ")"
    result = plan_project(read_project(path))
    if locale is not None:  # --locale: the documents' and the terminal's language
        import dataclasses

        result = dataclasses.replace(result, meta=dataclasses.replace(result.meta,
                                                                      locale=locale))
    # the project's own input files are never replaced either (an area saved as
    # OUT/flight.kml), even with --force
    files = [*files, *project_inputs(result)]
    exports = {}
    if out_dir:  # the documents and the mission and GIS files: one transaction
        chosen = plan_outputs(result, out_dir, formats, stem=stem, note=say or console.info)
        docs = {t.kind: t.path for t in chosen.targets}
        xlsx_path, pdf_path = docs.get("xlsx"), docs.get("pdf")
        exports = chosen.exports
        fields = ("--out", "--out")
    from ..reports.exports import with_exports

    # the result as this run's documents see it (the files written beside them): one object
    result = with_exports(result, (kind for kind, _ in exports.values()))
    film = result.film.job if result.film else None
    uav_ = result.uav.job if result.uav else None
    tables = ResultTables.of_jobs(film, uav_, result)
    write_reports(xlsx=xlsx_path, pdf=pdf_path, meta=result.meta, scan=film, uav=uav_,
                  spec=result, fields=fields, force=force, inputs=files, exports=exports,
                  note=note, say=say, pdf_worker=pdf_worker,
                  # never leave a stale sortie of an earlier plan behind
                  sweep=out_dir if out_dir and stem is None else None,
                  pdf_explicit=explicit, tables=tables)
    if out_dir:  # a mission or photo table not written is said, with the reason
        say_export_notes(result, say)
    return result, tables


def _batch_worker(task: tuple[Any, ...]) -> tuple[str, str, Any, list[str]]:
    """One project of a batch, in a worker process or in this one: (path, outcome,
    payload, the ``wrote FILE`` lines for stderr) — ``"ok"`` with (text: the summary
    table's row and the warnings, or None with --json; JSON document or None; summary
    row), ``"input"`` or ``"write"`` with the error text. No PlanResult leaves it: a batch
    of thousands keeps only these."""
    path, out_dir, stem, files, force, as_json, formats, locale = task
    import json

    from ..api import summary_row
    from ..reports.jsondoc import plan_result_dict

    said: list[str] = []
    try:
        with warnings.catch_warnings():
            if not os.environ.get("SCANPLAN_DEBUG"):
                warnings.simplefilter("ignore")
            result, _ = _run_project(path, out_dir, stem, None, None, files, force,
                                     said.append, formats=formats, locale=locale)
        doc = json.loads(json.dumps(plan_result_dict(result), ensure_ascii=False,
                                    allow_nan=False)) if as_json else None
        text = None if as_json else batch_text(path, result)  # not the result itself
        return path, "ok", (text, doc, summary_row(result)), said
    except InputError as exc:  # a bad project: report it, run the others
        return path, "input", f"{exc.field}: {exc.message}", said
    except WriteError as exc:
        return path, "write", exc.message, said


def _batch_outcomes(tasks: list[tuple[Any, ...]], jobs: int):  # type: ignore[no-untyped-def]
    """The outcomes of the batch's projects, in the order of the files."""
    if jobs <= 1 or len(tasks) <= 1:
        for task in tasks:
            yield _batch_worker(task)
        return
    from concurrent.futures import ProcessPoolExecutor

    try:
        pool = ProcessPoolExecutor(max_workers=min(jobs, len(tasks)))
    except (OSError, NotImplementedError):  # no worker processes here: plan one by one
        yield from _batch_outcomes(tasks, 1)
        return
    with pool:
        try:
            yield from pool.map(_batch_worker, tasks, chunksize=1)
        finally:
            pool.shutdown(cancel_futures=True)


def _write_summary(out_dir: str, rows: list[dict[str, Any]], force: bool,
                   files: list[str]) -> None:
    """summary.csv and summary.xlsx of a batch (one row per project), as one transaction."""
    from ..api import SUMMARY_COLUMNS, summary_frame
    from ..io.targets import check_target
    from ..reports.documents import render_summary

    frame = summary_frame(rows, [*SUMMARY_COLUMNS, "error"])
    targets = {kind: os.path.join(out_dir, f"summary.{kind}") for kind in ("csv", "xlsx")}

    def check() -> None:
        for kind, path in targets.items():
            check_target(path, "--out", kind, inputs=files, force=force)

    check()
    rendered = render_summary(frame)
    write_set({targets[kind]: rendered[kind] for kind in ("csv", "xlsx")},
              check=check, sweep=None, say=console.info)


def _plan_files(files: list[str], batch: bool, out_dir: str | None, xlsx_path: str | None,
                pdf_path: str | None, as_json: bool, force: bool = False,
                jobs: int = 1, formats: tuple[str, ...] | None = None,
                locale: str | None = None) -> None:
    """``plan`` after its arguments are checked: run one project or a batch."""
    if not batch:
        pdf = bool(pdf_path or (out_dir and outputs.selected(formats, "pdf")))
        with _pdf_worker(pdf) as worker, console.stage_bars():
            result, tables = _run_project(files[0], out_dir, None, xlsx_path, pdf_path,
                                          files, force, pdf_worker=worker, formats=formats,
                                          locale=locale)
        from ..reports.jsondoc import plan_result_dict
        from ..reports.text import format_plan_result

        if as_json:
            _echo_json(plan_result_dict(result))
        else:
            click.echo(format_plan_result(result, tables=tables))
        return
    stems = batch_stems(files)
    tasks = [(path, out_dir, stem, files, force, as_json, formats, locale)
             for path, stem in zip(files, stems, strict=True)]
    done: list[str] = []  # results are not kept: --json streams them, text keeps its lines
    lines: list[list[str]] = []  # the summary table's row of each project
    warned: list[str] = []  # the warnings of each project, as text
    failed: list[tuple[str, str]] = []
    rows: list[dict[str, Any]] = []
    stream = _JsonStream("projects") if as_json else None
    stopped = ""  # a write failure (disk full) stops the batch: the project it stopped at
    progress = console.Progress(len(files), "planning", "projects")
    for n, (path, outcome, payload, said) in enumerate(_batch_outcomes(tasks, jobs), start=1):
        progress.clear()
        for line in said:  # in the order of the files, whichever worker ran them
            console.info(line)
        console.detail(f"{n}/{len(files)} {path}: {outcome}")
        progress.step(n)
        if outcome == "ok":
            text, doc, row = payload
            if stream is not None:
                stream.add(doc)
            else:
                lines.append(text[0])
                if text[1]:
                    warned.append(text[1])
            done.append(path)
            rows.append({**row, "error": ""})
        else:
            failed.append((path, payload))
            rows.append({"file": path, "error": payload})
            if outcome == "write":
                stopped = path
                break
    progress.close()
    not_run = files[len(done) + len(failed):]
    if out_dir and not stopped:
        _write_summary(out_dir, rows, force, files)
    if stream is not None:
        stream.close({"errors": [{"file": f, "message": m} for f, m in failed]
                      + [{"file": f, "message": "not planned: the batch stopped"}
                         for f in not_run]})
    else:
        from ..reports.text import batch_table

        click.echo(batch_table(lines, failed))
        if warned:
            click.echo("\n".join(warned))
    errors = [msg for _path, msg in failed]
    if stopped:
        raise Failed([*errors, f"the batch stopped at {stopped} ({len(done)} of {len(files)} "
                      "projects written" + (f"; not planned: {', '.join(not_run)}" if not_run
                                            else "") + ")"])
    if failed:
        raise Failed(errors, code=2)


def run() -> None:  # pragma: no cover - console entry used by python -m scanplan
    main(prog_name="scanplan")


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
