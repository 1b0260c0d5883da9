"""The input registry: one record per thing a user gives scanplan.

Each :class:`Input` holds the Python (API) name, the unit, the domain
(:data:`scanplan.core.domains.DOMAINS`), the default, the command-line option of
``scanplan scan`` / ``scanplan uav``, the project-file section and key, and the help text.
Everything that names an input reads this module:

- the project file's key table and its type checks (:data:`scanplan.project.file.KEYS`);
- the defaults of the Python API (:func:`scanplan.project.jobs.uav_job`, ``scan_job``) and of
  the specification (:mod:`scanplan.project.spec`);
- the options of ``scanplan scan`` and ``scanplan uav`` (``scanplan.cli.main``), their
  help and defaults;
- the error → key mapping: an :class:`~scanplan.errors.InputError` whose ``field`` is a
  Python name is shown with the project key (:func:`project_key`) or the option
  (:func:`option_names`);
- the key tables of ``docs/project-file.md`` (:func:`update_docs`; a test keeps them current).

This module imports nothing heavy (no numpy): ``scanplan --help`` reads it.

>>> INPUTS["uav.speed_ms"].default, INPUTS["uav.speed_ms"].option, INPUTS["uav.speed_ms"].name
(15.0, '--speed-ms', 'speed_ms')
>>> project_key("height_tolerance_up_pct", "uav")
('uav', 'height_tolerance_pct')
"""

from __future__ import annotations

import functools
import re
from dataclasses import dataclass
from typing import Any

from ..core.domains import DOMAINS, Domain

__all__ = ["INPUTS", "PROJECT_DOMAINS", "Input", "by_key", "defaults", "describe", "domain_of",
           "get", "key_table", "option_names", "project_key", "records", "shown",
           "update_docs"]

FILM, UAV = "film", "uav"


@dataclass(frozen=True)
class Input:
    """One user input.

    Attributes
    ----------
    name : str
        The Python name: the keyword of :func:`scanplan.scan` / :func:`scanplan.uav` and the
        error ``field`` the engines raise.
    section, key : str
        Where a project file holds it (``"uav.motion"``, ``"shift_factor"``); empty for an
        input of the command line only.
    kind : str
        Its project-file type: ``"str"``, ``"int"``, ``"number"``, ``"scale"``, ``"scales"``.
    help : str
        What it is, with its unit (English; the project-file table and the option's help).
    unit : str
        Its unit (``"m/s"``, ``"%"``; ``""`` for a pure number or text).
    default : object
        The default the API, the project file and the command line share; ``None`` when
        there is none or it comes from elsewhere (a catalogue, the norm set) — ``note`` then
        says where.
    note : str
        What follows the default in the help (``"required for a camera on an aircraft"``).
    domain : str
        Its key in :data:`~scanplan.core.domains.DOMAINS` or, for a key only the project file
        has (the site, the schedule), in :data:`PROJECT_DOMAINS` (``""``: no numeric domain;
        :func:`domain_of` gives the record).
    option : str
        The option of ``scanplan scan`` / ``uav`` (``""``: none).
    commands : tuple of str
        The commands that take ``option``.
    fields : tuple of str
        Other error fields the engines raise for it (``sensor_width_mm`` for ``sensor_mm``).
    cli_help : str
        The option's help where it must differ from ``help`` (it names other options).
    cli_note : str
        The option's note where ``note`` speaks of project-file keys or norm-set parameter
        names, which a command-line user does not write.
    choices : tuple of str
        The allowed texts, for the option.
    required : bool
        Whether a project file must give it.
    by_carrier : bool
        ``default`` is the UAV's; a camera on a manned aircraft has another (or none), so
        the API and the command line take None and :func:`scanplan.project.jobs.uav_job`
        chooses by carrier.
    digits : int or None
        The decimals a value of it is shown with (as QGroundControl's
        ``FactMetaData::decimalPlaces``): the workbook's Inputs sheet, the survey design
        sheet and ``init``'s written file show it so (:func:`shown`); the page gets it with
        the key (``GET /api/inputs``). None for a text, a date, a CRS or a feature name.
    """

    name: str
    section: str
    key: str
    kind: str
    help: str
    unit: str = ""
    default: Any = None
    note: str = ""
    domain: str = ""
    option: str = ""
    commands: tuple[str, ...] = ()
    fields: tuple[str, ...] = ()
    cli_help: str = ""
    cli_note: str = ""
    choices: tuple[str, ...] = ()
    required: bool = False
    by_carrier: bool = False
    digits: int | None = None

    @property
    def dotted(self) -> str:
        """``section.key`` (``""`` for an input of the command line only)."""
        return f"{self.section}.{self.key}" if self.key else ""

    @property
    def plans(self) -> tuple[str, ...]:
        """The plans (``"film"``, ``"uav"``) the input belongs to."""
        top = self.section.split(".")[0]
        return (top,) if top in (FILM, UAV) else (FILM, UAV)


def _shown(value: Any) -> str:
    """A default as the help shows it: 15.0 → ``15``, ``"en"`` → ``"en"``."""
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, bool):  # as TOML writes it
        return "true" if value else "false"
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
    return f"{value:g}" if isinstance(value, float) else str(value)


def shown(inp: Input, value: float) -> str:
    """``value`` with at most the record's :attr:`~Input.digits` decimals, trailing zeros
    dropped: how ``init`` writes an example or a default (a number TOML reads back as it
    is written).

    >>> shown(INPUTS["uav.exposure_s"], 0.0005), shown(INPUTS["uav.speed_ms"], 10.0)
    ('0.0005', '10')
    """
    if inp.digits is None:
        raise ValueError(f"{inp.dotted or inp.name} is not a number shown with decimals")
    text = f"{value:.{inp.digits}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


def describe(inp: Input, *, cli: bool = False) -> str:
    """The help of an input: its text, then its default and note in brackets.

    >>> describe(INPUTS["uav.speed_ms"])
    'ground speed [m/s] (default 15; required for a camera on an aircraft)'
    """
    text = (inp.cli_help or inp.help) if cli else inp.help
    extra = [f"default {_shown(inp.default)}"] if inp.default not in (None, "") else []
    note = (inp.cli_note or inp.note) if cli else inp.note
    extra += [note] if note else []
    extra += ["required"] if inp.required and not cli else []
    if not extra:
        return text
    if text.endswith(")"):  # "… (scanplan norms list)" → "… (scanplan norms list; default …)"
        return f"{text[:-1]}; {'; '.join(extra)})"
    return f"{text} ({'; '.join(extra)})"


def _project(key: str, help: str, **kw: Any) -> Input:
    return Input(key, "project", key, "str", help, **kw)


_STR, _NUM, _INT = "str", "number", "int"

PROJECT_DOMAINS: dict[str, Domain] = {
    "lat_deg": Domain(-90, 90, "°"),
    "lon_deg": Domain(-180, 180, "°"),
    "utc_offset_h": Domain(-12, 14, "h"),
    "min_sun_elevation_deg": Domain(0, 89.9, "°"),
    "turnaround_min": Domain(0, 1440, "min"),
    "flying_days": Domain(0, 3660, "days", lo_open=True),
    # one sortie is at most one day; ``meaning`` is what the error calls the value
    "sortie_time_min": Domain(0, 24 * 60.0, "min", lo_open=True, meaning="a flight time"),
    # the turns between strips (the flight layout)
    "turnaround_m": Domain(0, 10_000, "m"),
    "turn_radius_m": Domain(0, 50_000, "m", lo_open=True),
    "bank_deg": Domain(0, 60, "°", lo_open=True),
    # [control]: the survey's precision (RMSE) and the density of the GCP layout
    "gcp_sigma_m": Domain(0, 10, "m", lo_open=True, meaning="a survey precision"),
    "gcp_per_ha": Domain(0, 100, "GCP/ha", lo_open=True),
    "checkpoints": Domain(3, 1000, "points"),
}
"""The domains of keys only a project file has (the site, the schedule, the sortie), beside
the inputs' :data:`~scanplan.core.domains.DOMAINS`: the range a value is read in, checked
once when the file is parsed (:mod:`scanplan.project.model`)."""


def domain_of(inp: Input) -> Domain | None:
    """The domain record of an input (None: no numeric domain).

    >>> domain_of(INPUTS["site.lat_deg"])
    Domain(lo=-90, hi=90, unit='°', lo_open=False, hi_open=False, meaning='')
    """
    if not inp.domain:
        return None
    return DOMAINS.get(inp.domain) or PROJECT_DOMAINS[inp.domain]
_FILM_SIDE_OVERLAP_PCT = 30.0  # film, and a digital camera on a manned aircraft

_RECORDS: tuple[Input, ...] = (
    # [project]: the title, approval and signature blocks
    _project("name", "project name (title block)", option="--project-name",
             commands=(FILM, UAV)),
    _project("customer", "customer (title block)", option="--customer", commands=(FILM, UAV)),
    _project("contractor", "contractor (title block)", option="--contractor",
             commands=(FILM, UAV)),
    _project("locale", '"en" or "ru": language of the reports and of the terminal summary',
             default="en", option="--locale", commands=(FILM, UAV), choices=("en", "ru"),
             cli_help="language of the terminal report and of --xlsx/--pdf"),
    _project("approver_position", "approval block: position", option="--approver-position",
             commands=(FILM, UAV), cli_help="approval block: position of the person who "
             "approves"),
    _project("approver_name", "approval block: name", option="--approver-name",
             commands=(FILM, UAV)),
    _project("organisation", "the contractor's organisation (title block)"),
    _project("contract_number", "contract number (title block)"),
    _project("compiled_by", "compiled by: name (signature block)"),
    _project("checked_by", "checked by: name (signature block)"),
    _project("agreed_position", "agreement block (customer): position"),
    _project("agreed_name", "agreement block (customer): name"),
    _project("agreed_organisation", "agreement block (customer): organisation"),
    _project("purpose", 'purpose of the survey (survey design sheet), e.g. "topographic '
             'plan 1:2000 of the town of Lida"'),
    _project("coordinate_system", "coordinate system of the product, as the contract names "
             'it, e.g. "МСК-50" or "СК-2011" (survey design sheet)'),
    _project("height_system", 'height system, e.g. "Балтийская 1977 г." (survey design '
             "sheet)"),
    # [map]
    Input("map_scale", "map", "scale", "scale",
          'map scale denominator Mk, 2000 or "1:2000"', required=True, domain="map_scale",
          option="--map-scale", commands=(FILM, UAV), cli_help="map scale, 2000 or 1:2000",
          digits=0),
    Input("relief_interval_m", "map", "relief_interval_m", _NUM,
          "relief (contour) interval h_c [m]", "m", required=True,
          domain="relief_interval_m", option="--relief", commands=(FILM, UAV), digits=2),
    Input("basemap", "map", "basemap", _STR, "background of the PDF's map page: an "
          "orthophoto or any GeoTIFF (the `terrain` extra), or an MBTiles file, relative to "
          "the project file; or tiles: \"osm\" or an http(s) URL with {z}, {x} and {y}, "
          "fetched with the plan and kept in the user's tile cache"),
    Input("basemap_attribution", "map", "basemap_attribution", _STR, "the background's "
          "source, printed under the map (default: the file's name; required with a tile "
          "URL; \"osm\": © OpenStreetMap contributors)"),
    # [norms]
    Input("norms", "norms", "set", _STR, "norm set name, or a folder relative to the "
          "project file", default="gkinp-02-036-02", option="--norms", commands=(FILM, UAV),
          fields=("--norms", "recognition_rounding"),
          cli_help="norm set name or folder (scanplan norms list)"),
    Input("pr_coefficient", "norms", "pr_coefficient", _NUM, "k_R in P_R = k_R/R",
          note="default: the set's, 0.5; the Instruction prints 0.4", domain="pr_coefficient",
          option="--pr-coefficient", commands=(FILM,), digits=2),
    Input("height_formula", "norms", "height_formula", _STR, '"instruction" or "parallax": '
          "the film height constraint", note="default: the set's", option="--height-formula",
          commands=(FILM,), choices=("instruction", "parallax"),
          cli_help="form of the height constraint P_Z of film photos"),
    Input("probability", "norms", "probability", _NUM,
          "required recognition probability, 0 < P < 1", note="default: the set's, 0.75",
          domain="probability", option="--probability", commands=(FILM, UAV), digits=3),
    Input("shape", "norms", "shape", _STR, "shape of the object to interpret",
          note="default: the norm table's", option="--shape", commands=(FILM, UAV),
          cli_help="object shape: circle|rectangle|angle|square|wall"),
    Input("object_size_m", "norms", "object_size_m", _NUM, "size of the object to "
          "interpret [m]", "m", note="default: the norm table's for the map scale",
          domain="object_size_m", option="--object-size-m", commands=(FILM, UAV), digits=3),
    Input("object_name", "norms", "object_name", _STR, "name of the project's own object "
          "(with object_size_m); shown in the reports as written", option="--object-name",
          commands=(FILM, UAV), cli_help="name of your own object (with --object-size-m), "
          "as the reports show it"),
    Input("gsd_area", "norms", "gsd_area", _STR, '"general" or "dense_urban": the row of '
          "the largest GSD per plan scale (GOST R 59562-2021 Table B.1; dense_urban: towns "
          "with dense multi-storey buildings, 14 cm at 1:2000)", default="general",
          option="--gsd-area", commands=(UAV,), choices=("general", "dense_urban"),
          cli_help="row of the largest GSD per plan scale (GOST R 59562-2021 Table B.1): "
          "dense_urban = towns with dense multi-storey buildings, 14 cm at 1:2000"),
    Input("gsd_limit_reason", "norms.gsd_limits", "reason", _STR, "sets the recommendation of "
          "GOST R 59562-2021 Table B.1 (largest GSD per plan scale, a recommended appendix) "
          "aside for this project, for the reason given; the specification prints it",
          note="optional", commands=(UAV,)),
    Input("block_relief_reason", "norms.block_relief", "reason", _STR, "sets the one-height "
          "rule of a block (GOST R 59328-2021 §6.2.1, the second draft's 7/15/25 %: a "
          "requirement of the standard's body with an exception) aside for this project, for "
          "the reason given (the exception invoked); the specification prints it", note="optional"),
    Input("recognition_rounding", "", "", _STR, "sqrt(-ln P) exactly, or the paper's "
          "rounded 0.53", option="--rounding", commands=(FILM,), choices=("exact", "paper")),
    # [film]
    Input("camera", "film", "camera", _STR, "catalogue camera id (or focal_mm + frame_mm)",
          option="--camera", commands=(FILM,),
          cli_help="catalogue camera id (scanplan cameras list)"),
    Input("camera_name", "film", "camera_name", _STR, "the camera's name as the documents "
          "show it, for a camera given by focal_mm and frame_mm",
          note="optional; default: the catalogue's model name"),
    Input("focal_mm", "film", "focal_mm", _NUM, "focal length [mm]", "mm",
          domain="focal_mm", option="--focal-mm", commands=(FILM,),
          cli_help="focal length [mm] (no --camera)", digits=2),
    Input("frame_mm", "film", "frame_mm", _STR, 'frame "WxH" [mm], across × along track',
          "mm", option="--frame-mm", commands=(FILM,),
          fields=("frame_width_mm", "frame_along_mm"),
          cli_help="frame WxH [mm], across × along track, e.g. 230x230"),
    Input("resolving_power_lpmm", "film", "resolving_power_lpmm", _NUM,
          "resolving power of the photos R [lines/mm]", "lines/mm",
          note="default: the camera's", domain="resolving_power_lpmm",
          option="--resolving-power", commands=(FILM,), digits=1),
    Input("forward_overlap_pct", "film", "forward_overlap_pct", _NUM, "forward overlap [%]",
          "%", note="default: the norm set's, 60", domain="forward_overlap_pct",
          option="--overlap-pct", commands=(FILM,), digits=1),
    Input("side_overlap_pct", "film", "side_overlap_pct", _NUM, "side overlap [%]", "%",
          default=_FILM_SIDE_OVERLAP_PCT, domain="side_overlap_pct", digits=1),
    Input("photo_scales", "film", "photo_scales", "scales",
          "candidate photo scales Mc to choose from (or photo_scale)", domain="photo_scale",
          option="--photo-scale", commands=(FILM,), fields=("photo_scale",),
          cli_help="photo scale; repeat for a sweep (like Tables 6–9 of Miheeva & "
          "Ilushenko 2015)", digits=0),
    Input("photo_scale", "film", "photo_scale", "scale", "the scale of existing (archive) "
          "photos to scan, e.g. 12000: given, not chosen (instead of photo_scales)",
          domain="photo_scale", digits=0),
    Input("scanner", "film", "scanner", _STR, "scanner id: scan pixels it offers",
          note="optional", option="--scanner", commands=(FILM,),
          cli_help="scanner id: round the pixel down to its steps"),
    Input("pixel_um", "", "", _NUM, "a scan pixel you have [µm]: show the largest photo "
          "scale it supports (repeatable)", "µm", option="--pixel-um", commands=(FILM,), digits=2),
    Input("bands", "film", "bands", _INT, "bands per scanned frame", default=1,
          domain="bands", option="--bands", commands=(FILM,),
          cli_help="bands per scanned frame (1 panchromatic, 3 colour)", digits=0),
    Input("bits_per_band", "film", "bits_per_band", _INT, "bits per band", default=8,
          domain="bits_per_band", option="--bit-depth", commands=(FILM,), choices=("8", "16"),
          digits=0),
    # [uav]
    Input("camera", "uav", "camera", _STR, "digital camera id (or pixel_um + focal_mm + "
          "sensor_mm)", option="--camera", commands=(UAV,),
          cli_help="digital camera id (scanplan cameras list)"),
    Input("camera_name", "uav", "camera_name", _STR, "the camera's name as the documents "
          "show it, for a camera given by pixel_um, focal_mm and sensor_mm",
          note="optional; default: the catalogue's model name", option="--camera-name",
          commands=(UAV,), cli_help="the camera's name in the reports (a camera given by "
          "--pixel-um, --focal-mm and --sensor-mm)"),
    Input("pixel_um", "uav", "pixel_um", _NUM, "pixel pitch [µm]", "µm", domain="pixel_um",
          option="--pixel-um", commands=(UAV,), cli_help="pixel pitch [µm] (no --camera)",
          digits=2),
    Input("focal_mm", "uav", "focal_mm", _NUM, "focal length [mm]", "mm", domain="focal_mm",
          option="--focal-mm", commands=(UAV,), digits=2),
    Input("sensor_mm", "uav", "sensor_mm", _STR, 'sensor "WxH" [mm], W across track when '
          "mounted landscape", "mm", option="--sensor-mm", commands=(UAV,),
          fields=("sensor_width_mm", "sensor_height_mm"),
          cli_help="sensor WxH [mm], e.g. 36x24 (W across track when mounted landscape)"),
    Input("orientation", "uav", "orientation", _STR, '"landscape" (sensor width across '
          'track) or "portrait"', note="default: the catalogue's, else landscape",
          option="--orientation", commands=(UAV,), choices=("landscape", "portrait"),
          cli_help="camera mounting: landscape = sensor width across track; portrait turns "
          "footprint, spacing and base"),
    Input("f_number", "uav", "f_number", _NUM, "working f-number",
          note="default: the catalogue's", domain="f_number", option="--f-number",
          commands=(UAV,), digits=1),
    Input("height_m", "uav", "height_m", _NUM, "planned flight height above ground [m]", "m",
          note="default: the maximum planned height, rounded down to 5 m",
          domain="height_m", option="--height-m", commands=(UAV,),
          cli_help="planned flight height above ground [m]; without it --map-scale or --gsd-cm "
          "give it", digits=1),
    Input("gsd_cm", "uav", "gsd_cm", _NUM, "target ground sample distance [cm]: the flight "
          "must deliver it at the highest flown height", "cm", note="optional",
          domain="gsd_cm", option="--gsd-cm", commands=(UAV,), digits=1),
    Input("parallax_error_px", "uav", "parallax_error_px", _NUM, "RMS error of a measured "
          "x-parallax σ_px in the height-accuracy model [px]: an assumption (tie-point "
          "reprojection errors of processing reports suggest 0.5–1.4 px)", "px",
          note="default: the norm set's image_measurement_px, 0.5",
          cli_note="default: the norm set's image measurement error, 0.5 px",
          domain="parallax_error_px", option="--parallax-error-px", commands=(UAV,), digits=2),
    Input("max_height_m", "uav", "max_height_m", _NUM, "altitude ceiling for the highest "
          "flown height above ground [m]", "m", note="default for a UAV: the norm set's, "
          "150 m; none for an aircraft", domain="max_height_m", option="--max-height-m",
          commands=(UAV,), digits=0),
    Input("height_tolerance_pct", "uav", "height_tolerance_pct", _NUM, "how much higher the "
          "UAV may fly [%]", "%", default=0.0, domain="height_tolerance_up_pct",
          option="--height-tolerance-pct", commands=(UAV,),
          fields=("height_tolerance_up_pct",),
          cli_help="how much higher the UAV may fly than planned [%], e.g. 40: the Ptero-E "
          "flight of 2014 was planned at 300 m and flew up to 420 m", digits=1),
    Input("speed_ms", "uav", "speed_ms", _NUM, "ground speed [m/s]", "m/s", default=15.0,
          by_carrier=True, note="required for a camera on an aircraft", domain="speed_ms",
          option="--speed-ms", commands=(UAV,), digits=1),
    Input("exposure_s", "uav", "exposure_s", _NUM, "exposure time [s]", "s", default=0.001,
          domain="exposure_s", option="--exposure-s", commands=(UAV,), digits=5),
    Input("forward_overlap_pct", "uav", "forward_overlap_pct", _NUM, "forward overlap [%]",
          "%", default=80.0, by_carrier=True, note="on an aircraft the norm set's 60",
          domain="forward_overlap_pct", option="--overlap-pct", commands=(UAV,), digits=1),
    Input("side_overlap_pct", "uav", "side_overlap_pct", _NUM, "side overlap [%]", "%",
          default=60.0, by_carrier=True, note=f"on an aircraft {_FILM_SIDE_OVERLAP_PCT:g}",
          domain="side_overlap_pct", option="--side-overlap-pct", commands=(UAV,), digits=1),
    Input("roll_deg", "uav", "roll_deg", _NUM, "roll for the tilted-frame corner GSD [°]",
          "°", default=0.0, domain="roll_deg", option="--roll-deg", commands=(UAV,), digits=2),
    Input("pitch_deg", "uav", "pitch_deg", _NUM, "pitch for the tilted-frame corner GSD [°]",
          "°", default=0.0, domain="pitch_deg", option="--pitch-deg", commands=(UAV,), digits=2),
    Input("height_formula", "uav", "height_formula", _STR, '"normal_case", "instruction" or '
          '"parallax": the height constraint of the digital block',
          note='default: the set\'s, "normal_case"', option="--height-formula",
          commands=(UAV,), choices=("instruction", "parallax", "normal_case"),
          cli_help="form of the height constraint P_Z (normal_case for digital cameras "
          "only)"),
    Input("r_max", "uav.target", "r_max", _NUM,
          "brightness coefficient of the lightest detail", default=0.3, domain="r_max",
          option="--r-max", commands=(UAV,), digits=3),
    Input("r_min", "uav.target", "r_min", _NUM, "brightness coefficient of the darkest detail",
          default=0.1, domain="r_min", option="--r-min", commands=(UAV,), digits=3),
    Input("threshold_k0", "uav.atmosphere", "threshold_k0", _NUM,
          "sensor threshold contrast at low frequency", default=0.03, domain="threshold_k0",
          option="--k0", commands=(UAV,), fields=("k0",), digits=3),
    Input("haze_contrast", "uav.atmosphere", "haze_contrast", _NUM,
          "contrast transmission of the air column c, 0 < c ≤ 1", default=0.9,
          note="clear air below 500 m", domain="haze_contrast", option="--haze-contrast",
          commands=(UAV,), digits=3),
    Input("shift_factor", "uav.motion", "shift_factor", _NUM,
          "photographic/geometric image shift, 0 < k ≤ 1", default=1.0,
          note="0.6–0.7 summer, 1 bright canopy", domain="shift_factor",
          option="--shift-factor", commands=(UAV,), digits=2),
    Input("random_speed_ms", "uav.motion", "random_speed_ms", _NUM,
          "RMS random linear speed [m/s]", "m/s", default=0.0, domain="random_speed_ms",
          option="--random-speed-ms", commands=(UAV,),
          cli_help="RMS random linear speed of a light UAV [m/s]", digits=2),
    Input("roll_rate_rad_s", "uav.motion", "roll_rate_rad_s", _NUM, "RMS roll rate [rad/s]",
          "rad/s", default=0.0, domain="roll_rate_rad_s", option="--roll-rate",
          commands=(UAV,), cli_help="RMS angular rate about the longitudinal axis [rad/s]",
          digits=4),
    Input("pitch_rate_rad_s", "uav.motion", "pitch_rate_rad_s", _NUM,
          "RMS pitch rate [rad/s]", "rad/s", default=0.0, domain="pitch_rate_rad_s",
          option="--pitch-rate", commands=(UAV,),
          cli_help="RMS angular rate about the transverse axis [rad/s]", digits=4),
    Input("yaw_rate_rad_s", "uav.motion", "yaw_rate_rad_s", _NUM, "RMS yaw rate [rad/s]",
          "rad/s", default=0.0, domain="yaw_rate_rad_s", option="--yaw-rate",
          commands=(UAV,), cli_help="RMS angular rate about the vertical axis [rad/s]", digits=4),
    # [area]
    Input("area_width_m", "area", "width_m", _NUM, "block width across the flight lines [m]",
          "m", domain="area_width_m", digits=1),
    Input("area_length_m", "area", "length_m", _NUM,
          "block length along the flight lines [m]", "m", domain="area_length_m", digits=1),
    Input("file", "area", "file", _STR, "the contract polygon: a KML, KMZ, GeoJSON, "
          "GeoPackage or Shapefile, or a CSV/TXT list of its vertices, relative to the "
          "project file"),
    Input("layer", "area", "layer", _STR, "layer of the file holding the polygon (when it "
          "has several)"),
    Input("feature", "area", "feature", "feature", "the polygon's name, or its number from 1 "
          "(when the file holds several)"),
    Input("polygon", "area", "polygon", "polygon", "the contract polygon inline, [[lon, lat], "
          "...] (WGS 84 unless crs)", digits=7),
    Input("crs", "area", "crs", "crs", 'CRS of the polygon\'s coordinates when not WGS 84, '
          'e.g. "EPSG:28407"'),
    Input("plan_crs", "area", "plan_crs", "crs", "projected CRS to plan in (default: the "
          "polygon's own when projected in metres, else the UTM zone of the area)"),
    Input("direction_deg", "area", "direction_deg", "direction", "flight-line direction "
          'clockwise from grid north [°], or "auto": the least flight length', "°",
          default="auto", option="--direction-deg", commands=(UAV,), digits=1),
    Input("extension_bases", "area", "extension_bases", _INT, "exposures past each end of a "
          "strip, in photo bases", default=1, digits=0),
    Input("turnaround_m", "uav", "turnaround_m", _NUM, "multirotor: distance flown past each "
          "strip end before turning [m]", "m", note="default: a semicircle across the line "
          "spacing", domain="turnaround_m", digits=0),
    Input("turn_radius_m", "uav", "turn_radius_m", _NUM, "fixed-wing: turn radius between "
          "strips [m]", "m", domain="turn_radius_m", digits=0),
    Input("bank_deg", "uav", "bank_deg", _NUM, "fixed-wing: bank angle in the turns [°]; the "
          "radius follows from the speed, r = v²/(g·tan φ)", "°", domain="bank_deg", digits=1),
    Input("takeoff", "flight", "takeoff", "point", "take-off and landing point of every "
          "sortie, [lon, lat] (WGS 84): the missions' home; each sortie's transit to the "
          "block and back is flown within its battery and counted in the flight's length "
          "and time", note="default: none — no transit counted, each mission's home is its "
          "first waypoint", digits=7),
    Input("crosshatch", "uav", "crosshatch", "bool", "fly the area twice, the second pass's "
          "lines at the direction + 90° (a double grid): every point photographed along two "
          "line directions, for 3D models of buildings and a stronger block; the strips, "
          "photos and flying time of both passes", default=False),
    Input("aircraft", "uav", "aircraft", _STR, "the aircraft that carries the camera, a "
          "catalogue id: its battery's usable flight time (the published flight time less "
          "the battery reserve) is the sortie time, its cruise speed the ground speed where "
          "the catalogue gives one",
          note="default: the one catalogue aircraft that carries the camera, when only one "
          "does; else none — give max_flight_time_min",
          cli_note="default: the one catalogue aircraft that carries the camera",
          option="--aircraft", commands=(UAV,),
          cli_help="catalogue aircraft id (scanplan aircraft list)"),
    Input("max_flight_time_min", "uav", "max_flight_time_min", _NUM, "flight time of one "
          "sortie [min]: the aircraft's endurance on one battery less the reserve; the block "
          "is split into sorties of at most this long, and the schedule counts its flying "
          "days from the same sorties", "min",
          note="default: [schedule] sortie_time_min, else the aircraft's usable flight "
          "time; with [schedule] and none of them 25 for a UAV, 180 for an aircraft; else "
          "one flight",
          cli_note="default: one flight over the whole block", option="--max-flight-time-min",
          commands=(UAV,), domain="sortie_time_min", digits=0),
    Input("area_file", "", "", _STR, "contract polygon: KML, KMZ, GeoJSON, GeoPackage, "
          "Shapefile or a CSV/TXT list of its vertices; strips and photos are laid out over "
          "it (not with --area-m)",
          option="--area-file", commands=(FILM, UAV), fields=("file",)),
    Input("area_feature", "", "", _STR, "the polygon's name or number from 1, when the file "
          "holds several", option="--area-feature", commands=(FILM, UAV),
          fields=("feature",)),
    Input("area_layer", "", "", _STR, "the file's layer holding the polygon",
          option="--area-layer", commands=(FILM, UAV), fields=("layer",)),
    Input("film_side_overlap_pct", "", "", _NUM, "side overlap [%] of the flight scheme over "
          "--area-file", "%", note="default 30", option="--side-overlap-pct",
          commands=(FILM,), domain="side_overlap_pct", digits=1),
    # [terrain] (the one-height rule of GOST R 59328-2021 §6.2.1)
    Input("ground_elevation_m", "terrain", "ground_elevation_m", "range", "lowest and "
          "highest ground in the block, buildings included, [min, max] [m], without a DEM: "
          "the plan's ground range, checked against the one-height rule of GOST R 59328-2021 "
          "§6.2.1", "m", digits=1),
    Input("dem", "terrain", "dem", _STR, "digital elevation model: a GeoTIFF in any CRS, "
          "relative to the project file (or ground_elevation_m)"),
    Input("altitude_mode", "terrain", "altitude_mode", _STR, '"auto" (scanplan compares the '
          "modes and flies the one with the least flying time that meets every constraint), "
          '"constant" (one altitude, the planned height over the highest ground), "strip" '
          '(one per strip) or "follow" (terrain following); a mode given is kept',
          default="auto", choices=("auto", "constant", "strip", "follow")),
    Input("follow_tolerance_m", "terrain", "follow_tolerance_m", _NUM, "follow mode: how far "
          "the height above ground may exceed the planned height [m]", "m", default=5.0, digits=1),
    Input("void_fill_radius_m", "terrain", "void_fill_radius_m", _NUM, "no-data in the DEM "
          "within this distance of known ground is filled with the highest known ground "
          "within it plus void_fill_margin_m (farther no-data counts as missing) [m]", "m",
          default=50.0, digits=0),
    Input("void_fill_margin_m", "terrain", "void_fill_margin_m", _NUM, "added to the "
          "highest (taken from the lowest) known ground of a filled void [m]", "m",
          default=10.0, digits=1),
    Input("vertical_unit", "terrain", "vertical_unit", _STR, '"m", "ft", "us-ft", "dm" or '
          '"cm": the unit of the DEM\'s heights', default="m",
          choices=("m", "ft", "us-ft", "dm", "cm")),
    Input("relief_class", "terrain", "relief_class", _STR, '"flat", "hilly" or '
          '"mountainous": the relief class of the one-height rule', default="flat",
          choices=("flat", "hilly", "mountainous")),
    # [site] and [schedule]: the sun window and the flying days
    Input("lat_deg", "site", "lat_deg", _NUM, "latitude of the site, WGS 84 [°], north "
          "positive (sun window)", "°", domain="lat_deg", digits=4),
    Input("lon_deg", "site", "lon_deg", _NUM, "longitude of the site, WGS 84 [°], east "
          "positive (sun window)", "°", domain="lon_deg", digits=4),
    Input("start_date", "schedule", "start_date", "date", "first planned flying date, e.g. "
          "2025-06-01"),
    Input("end_date", "schedule", "end_date", "date", "last planned flying date",
          note="default: 30 days after start_date"),
    Input("utc_offset_h", "schedule", "utc_offset_h", _NUM, "local time = UTC + offset [h]",
          "h", note="default: the legal time of the site's time zone, found from lat/lon, "
          "summer time included", domain="utc_offset_h", digits=2),
    Input("sortie_time_min", "schedule", "sortie_time_min", _NUM, "flight time of one sortie "
          "(battery or fuel) [min]: the same number as [uav] max_flight_time_min (give one, "
          "or both equal; two different values are an error); it also splits the flight "
          "layout, so the layout and the schedule count the same sorties", "min",
          note="default: [uav] max_flight_time_min, else the aircraft's usable flight time, "
          "else 25 for a UAV, 180 for an aircraft",
          domain="sortie_time_min", digits=0),
    Input("max_flying_days", "flight", "max_flying_days", _INT, "the most flying days the "
          "crew can give the job: a plan that needs more is warned about (the survey "
          "design's flying days when [site] and [schedule] are given, else a lower bound: "
          "the flight time and the ground time between sorties, flown around the clock)",
          "days", default=30, domain="flying_days", digits=0),
    Input("turnaround_min", "schedule", "turnaround_min", _NUM, "ground time between "
          "sorties [min]", "min", note="default 15 for a UAV, 60 for an aircraft",
          domain="turnaround_min", digits=0),
    Input("min_sun_elevation_deg", "schedule", "min_sun_elevation_deg", _NUM, "lowest sun "
          "elevation for photography [°]", "°", note="default: the norm set's, 30°",
          domain="min_sun_elevation_deg", digits=0),
    # [control]: ground control and checkpoints (docs/control.md)
    Input("control_mode", "control", "mode", _STR, '"gcp" (ground control points over the '
          'block), "rtk" or "ppk" (the camera positions control the block: GCPs at its '
          'corners and one near its centre), or "direct" (no GCPs): the layout of the '
          "markers, control.csv and the error budget", default="gcp",
          choices=("gcp", "rtk", "ppk", "direct")),
    Input("gcp_sigma_xy_m", "control", "gcp_sigma_xy_m", _NUM, "horizontal precision (RMSE_H) "
          "of the survey of the GCPs and checkpoints [m]", "m", default=0.02,
          note="an assumption, typical of a network-RTK survey: give your survey's",
          domain="gcp_sigma_m", digits=3),
    Input("gcp_sigma_z_m", "control", "gcp_sigma_z_m", _NUM, "vertical precision (RMSE_Z) of "
          "the survey of the GCPs and checkpoints [m]", "m", default=0.03,
          note="an assumption, typical of a network-RTK survey: give your survey's",
          domain="gcp_sigma_m", digits=3),
    Input("checkpoints", "control", "checkpoints", "checkpoints", 'independent checkpoints: '
          '"asprs" (the count of ASPRS Positional Accuracy Standards, Edition 2, for the '
          "area: a foreign recommendation) or a number", default="asprs",
          domain="checkpoints", digits=0),
    Input("gcp_per_ha", "control", "gcp_per_ha", _NUM, "density of the GCP layout [GCP/ha]: "
          "the spacing along the boundary and of the interior grid is 100 m divided by the "
          "square root of the density",
          "GCP/ha", note="default 0.5: an estimate, the lower end of Martínez-Carricondo et "
          "al. 2018 on their site", domain="gcp_per_ha", digits=2),
    Input("area_m", "", "", _STR, "block to cover, WIDTHxLENGTH [m], e.g. 2000x3000", "m",
          option="--area-m", commands=(UAV,),
          fields=("area", "area_width_m", "area_length_m")),
)

INPUTS: dict[str, Input] = {(r.dotted or r.name): r for r in _RECORDS}
"""``section.key`` (or, for an input of the command line only, its Python name) → its
record."""


@functools.cache
def get(name: str, plan: str) -> Input:
    """The record of Python name ``name`` in ``plan`` (``"film"`` or ``"uav"``); the
    plan's own section wins over a shared one. Looked up once per name and plan (a plan
    asks for its inputs hundreds of times; the records never change).

    >>> get("forward_overlap_pct", "uav").default
    80.0
    """
    found = [r for r in records(plan) if r.name == name]
    if not found:
        raise KeyError(name)
    own = [r for r in found if r.section.split(".")[0] == plan]  # [uav] over [norms]
    return (own or found)[0]


@functools.cache
def records(plan: str | None = None) -> tuple[Input, ...]:
    """Every record, or those of one plan (``"film"``, ``"uav"``), in registry order (the
    tuple made once per plan)."""
    return tuple(r for r in _RECORDS if plan is None or plan in r.plans)


def by_key(section: str, key: str) -> Input:
    """The record of a project-file key.

    >>> by_key("uav", "speed_ms").default
    15.0
    """
    for r in _RECORDS:
        if r.section == section and r.key == key:
            return r
    raise KeyError(f"{section}.{key}")


def defaults(plan: str) -> dict[str, Any]:
    """Python name → default of every input of ``plan`` that has one."""
    return {r.name: r.default for r in records(plan) if r.default is not None
            and r.section != "project"}


def project_key(field: str, plan: str) -> tuple[str, str] | None:
    """(section, key) of the project-file key behind an error ``field`` of ``plan``.

    Parameters
    ----------
    field : str
        An :class:`~scanplan.errors.InputError` field: a Python name or one of a record's
        ``fields``.
    plan : str
        ``"film"`` or ``"uav"``.
    """
    found = [r for r in records(plan) if r.key and (field == r.name or field in r.fields)]
    own = [r for r in found if r.section.split(".")[0] == plan]  # [uav] over [norms]
    if own or found:
        return (own or found)[0].section, (own or found)[0].key
    if field in ("area", "area_m") and plan == UAV:
        return "", "area"
    return None


def option_names() -> dict[str, str]:
    """Python name (and every other error field) → the option a user typed."""
    out = {r.name: r.option for r in reversed(_RECORDS) if r.option}
    for r in _RECORDS:  # a record's own name wins over another's extra field
        for name in r.fields:
            if r.option and not name.startswith("-"):
                out.setdefault(name, r.option)
    return out


KINDS = ("str", "bool", "int", "number", "scale", "scales", "range", "date", "feature", "polygon",
         "crs", "direction", "point", "checkpoints")


def key_table() -> dict[str, dict[str, tuple[str, str]]]:
    """section → key → (type, description): every key a project file may hold."""
    table: dict[str, dict[str, tuple[str, str]]] = {}
    for r in _RECORDS:
        if r.key:
            table.setdefault(r.section, {})[r.key] = (r.kind, describe(r))
    return table


_DOC_NOTES = {("norms", "object_name"): ' (an unnamed own object is "object of the given '
                                          'size" / «объект заданного размера»)'}
_BLOCK = re.compile(r"(<!-- keys: (?P<section>[a-z._]+) -->\n)(.*?)(<!-- /keys -->)", re.DOTALL)


def markdown_table(section: str) -> str:
    """The key table of one section of ``docs/project-file.md`` (Markdown)."""
    rows = ["| key | type | meaning, unit, default |", "|---|---|---|"]
    for r in _RECORDS:
        if r.key and r.section == section:
            desc = describe(r) + _DOC_NOTES.get((r.section, r.key), "")
            rows.append(f"| `{r.key}` | {r.kind} | {desc} |")
    return "\n".join(rows) + "\n"


def update_docs(text: str) -> str:
    """``text`` (docs/project-file.md) with every ``<!-- keys: SECTION -->`` … ``<!-- /keys
    -->`` block regenerated from the registry (``python -m scanplan.project.inputs FILE``)."""
    return _BLOCK.sub(lambda m: m.group(1) + markdown_table(m.group("section")) + m.group(4),
                      text)


if __name__ == "__main__":  # pragma: no cover - maintenance: regenerate the docs' tables
    import sys
    from pathlib import Path

    for arg in sys.argv[1:]:
        path = Path(arg)
        path.write_text(update_docs(path.read_text(encoding="utf-8")), encoding="utf-8")
