"""The shape of a norm set: its parameters, its tables and their columns.

This is the one place that declares what a norm set holds, the type and allowed range of
every value, its unit, and the header aliases (English and Russian) a spreadsheet may use.
The loader (:mod:`scanplan.norms`), the spreadsheet importer and the template writer all
read it. It holds *rules about values*, never normative values themselves — those live in
the data files under ``norms/``.

A norm set on disk is a folder::

    set.toml          [set] name, title, title_ru, source, imported_from, imported_at
    parameters.csv    name, value, unit, source, note
    shapes.csv        shape, coefficient, name_ru, source
    objects.csv       map_scale, object, object_ru, size_m, shape, source
    cameras.csv       optional, same columns as norms/catalogue/cameras.csv
    scanners.csv      optional, same columns as norms/catalogue/scanners.csv
"""

from __future__ import annotations

from dataclasses import dataclass, field

CONSTRAINT_IDS = ("PS", "PZ", "PP", "PR", "PD", "GL")
"""Constraints a norm set may switch on (see :mod:`scanplan.rules.registry`); ``GL`` is
the GSD limit per plan scale of the set's ``gsd_limits`` table (ГОСТ Р 59562-2021,
Table Б.1), for digital cameras."""

GSD_AREAS = ("general", "dense_urban")
"""Rows of the ``gsd_limits`` table: the general limit, and the one for towns with dense
multi-storey buildings (ГОСТ Р 59562-2021, Table Б.1, footnote to 1:2000)."""

HEIGHT_FORMULAS = ("instruction", "parallax")
DIGITAL_HEIGHT_FORMULAS = ("normal_case", "instruction", "parallax")
"""Forms of the height constraint for digital (UAV) cameras (:mod:`scanplan.rules.uav`)."""
MULTI_RAY_MODES = ("off", "strip")
LATER_PARAMETERS = ("digital_height_formula", "image_measurement_px", "multi_ray",
                    "uav_max_height_m", "block_relief_flat_pct", "block_relief_hilly_pct",
                    "block_relief_mountain_pct", "min_sun_elevation_deg",
                    "uav_uncontrolled_aerodrome_km")
"""Parameters added after norm sets were first stored: a stored set without them takes
them from the bundled default set (its source says so) instead of failing to load."""
ORIENTATIONS = ("landscape", "portrait")
"""Camera mounting: landscape = image width (sensor width) across track, as QGroundControl."""
ROUNDING_MODES = ("exact", "paper")


@dataclass(frozen=True)
class ValueSpec:
    """Type and allowed range of one value.

    Parameters
    ----------
    kind : {"float", "int", "text", "choice", "list"}
        ``list`` is a comma-separated list of ``choices``.
    min, max : float, optional
        Bounds; ``min_open``/``max_open`` make them exclusive.
    choices : tuple of str
        Allowed words for ``choice`` and ``list``.
    unit : str
        Unit shown in templates and messages.
    required : bool
        Whether an empty value is an error.
    """

    kind: str = "float"
    min: float | None = None
    max: float | None = None
    min_open: bool = False
    max_open: bool = False
    choices: tuple[str, ...] = ()
    unit: str = ""
    required: bool = True

    def describe(self) -> str:
        """Human description of the allowed values, used in error messages."""
        if self.kind in ("choice", "list"):
            words = ", ".join(self.choices)
            if self.kind == "choice":
                return f"one of {words}"
            return f"a comma-separated list of {words}"
        if self.kind == "text":
            return "text"
        lo = "" if self.min is None else f"{'>' if self.min_open else '≥'} {self.min:g}"
        hi = "" if self.max is None else f"{'<' if self.max_open else '≤'} {self.max:g}"
        rng = " and ".join(x for x in (lo, hi) if x)
        kind = "an integer" if self.kind == "int" else "a number"
        return f"{kind} {rng}".strip() + (f" [{self.unit}]" if self.unit else "")

    def check(self, value: object) -> str | None:
        """Return None when ``value`` (already converted) is allowed, else the rule broken."""
        if self.kind in ("float", "int"):
            v = float(value)  # type: ignore[arg-type]
            if v != v:  # NaN
                return f"must be {self.describe()}"
            if self.min is not None and (v <= self.min if self.min_open else v < self.min):
                return f"must be {self.describe()}"
            if self.max is not None and (v >= self.max if self.max_open else v > self.max):
                return f"must be {self.describe()}"
            if self.kind == "int" and v != int(v):
                return f"must be {self.describe()}"
        elif self.kind == "choice" and value not in self.choices:
            return f"must be {self.describe()}"
        elif self.kind == "list":
            items = [x.strip() for x in str(value).split(",") if x.strip()]
            bad = [x for x in items if x not in self.choices]
            if bad or not items:
                return f"must be {self.describe()}"
        return None


@dataclass(frozen=True)
class ParameterSpec:
    """One norm parameter: its value rule, unit and what it means."""

    name: str
    value: ValueSpec
    description: str
    aliases: tuple[str, ...] = ()


PARAMETERS: dict[str, ParameterSpec] = {
    p.name: p
    for p in (
        ParameterSpec(
            "planimetric_accuracy_mm",
            ValueSpec("float", 0, 10, min_open=True, unit="mm on the map"),
            "V_s, required planimetric accuracy on the map",
            ("V_s", "Vs", "точность в плане"),
        ),
        ParameterSpec(
            "height_accuracy_fraction",
            ValueSpec("float", 0, 1, min_open=True, unit="of h_c"),
            "V_z / h_c, required height accuracy as a fraction of the relief interval",
            ("V_z", "Vz", "точность по высоте"),
        ),
        ParameterSpec(
            "processing_loss_k",
            ValueSpec("float", 1, 10, unit="-"),
            "k, loss of accuracy in scanning, identification, pointing and measuring",
            ("k", "коэффициент потери точности"),
        ),
        ParameterSpec(
            "photoplan_resolution_mm",
            ValueSpec("float", 0, 1, min_open=True, unit="mm on the plan"),
            "resolution of a graphic photo-plan",
            ("разрешение фотоплана",),
        ),
        ParameterSpec(
            "pr_coefficient",
            ValueSpec("float", 0, 2, min_open=True, unit="-"),
            "k_R in P_R = k_R / R (0.5 corrected, 0.4 as printed)",
            ("k_R", "kR", "коэффициент PR"),
        ),
        ParameterSpec(
            "probability",
            ValueSpec("float", 0, 1, min_open=True, max_open=True, unit="-"),
            "recognition probability required for interpretation",
            ("P", "вероятность"),
        ),
        ParameterSpec(
            "shape",
            ValueSpec("text", unit="-"),
            "default shape of the objects to interpret (a row of the shapes table)",
            ("форма",),
        ),
        ParameterSpec(
            "height_formula",
            ValueSpec("choice", choices=HEIGHT_FORMULAS),
            "form of the height constraint P_Z",
            ("формула высот",),
        ),
        ParameterSpec(
            "constraints",
            ValueSpec("list", choices=CONSTRAINT_IDS),
            "constraints the rules engine evaluates",
            ("ограничения",),
        ),
        ParameterSpec(
            "standard_forward_overlap_pct",
            ValueSpec("float", 0, 100, max_open=True, unit="%"),
            "forward overlap the Instruction's height formula assumes",
            ("стандартное перекрытие",),
        ),
        ParameterSpec(
            "recognition_rounding",
            ValueSpec("choice", choices=ROUNDING_MODES),
            "exact sqrt(-ln P), or the paper's rounded 0.53",
            ("округление",),
        ),
        ParameterSpec(
            "interpretation_min_lpmm",
            ValueSpec("float", 0, 1000, min_open=True, unit="lines/mm"),
            "lower end of the image resolving power qualitative interpretation needs",
            ("R min", "разрешающая способность для дешифрирования, от"),
        ),
        ParameterSpec(
            "interpretation_max_lpmm",
            ValueSpec("float", 0, 1000, min_open=True, unit="lines/mm"),
            "upper end of the image resolving power qualitative interpretation needs",
            ("R max", "разрешающая способность для дешифрирования, до"),
        ),
        ParameterSpec(
            "digital_height_formula",
            ValueSpec("choice", choices=DIGITAL_HEIGHT_FORMULAS),
            "form of the height constraint for digital cameras",
            ("формула высот для цифровых камер",),
        ),
        ParameterSpec(
            "image_measurement_px",
            ValueSpec("float", 0, 10, min_open=True, unit="px"),
            "sigma_px, RMS error of a measured parallax in a digital block",
            ("sigma_px", "ошибка измерения параллакса"),
        ),
        ParameterSpec(
            "multi_ray",
            ValueSpec("choice", choices=MULTI_RAY_MODES),
            "multi-ray improvement of the digital height error (off or strip)",
            ("многолучевое уточнение",),
        ),
        ParameterSpec(
            "uav_max_height_m",
            ValueSpec("float", 0, 20000, min_open=True, unit="m"),
            "altitude ceiling of UAV flights above ground",
            ("предельная высота полёта БВС",),
        ),
        ParameterSpec(
            "uav_uncontrolled_aerodrome_km",
            ValueSpec("float", 0, 1000, unit="km"),
            "distance from uncontrolled aerodromes of UAV flights without an airspace-use "
            "permission",
            ("удаление от неконтролируемых аэродромов",),
        ),
        ParameterSpec(
            "block_relief_flat_pct",
            ValueSpec("float", 0, 100, min_open=True, unit="% of the flight height"),
            "largest ground height range of a block flown at one height, flat terrain",
            ("перепад высот, равнинная местность",),
        ),
        ParameterSpec(
            "block_relief_hilly_pct",
            ValueSpec("float", 0, 100, min_open=True, unit="% of the flight height"),
            "largest ground height range of a block flown at one height, hilly terrain",
            ("перепад высот, всхолмлённая местность",),
        ),
        ParameterSpec(
            "block_relief_mountain_pct",
            ValueSpec("float", 0, 100, min_open=True, unit="% of the flight height"),
            "largest ground height range of a block flown at one height, mountainous terrain",
            ("перепад высот, горная местность",),
        ),
        ParameterSpec(
            "min_sun_elevation_deg",
            ValueSpec("float", 0, 90, max_open=True, unit="°"),
            "lowest sun elevation above the horizon at which photos are taken",
            ("высота Солнца", "минимальная высота Солнца"),
        ),
    )
}

DIGITAL_ONLY_PARAMETERS = frozenset({"digital_height_formula", "image_measurement_px",
                                     "multi_ray", "uav_max_height_m",
                                     "uav_uncontrolled_aerodrome_km"})
"""Parameters only a digital camera's plan uses: a film specification does not list them."""
"""Every parameter a norm set must define."""


@dataclass(frozen=True)
class ColumnSpec:
    """One column of a norm table."""

    name: str
    value: ValueSpec
    description: str
    aliases: tuple[str, ...] = ()


@dataclass(frozen=True)
class TableSpec:
    """One table of a norm set: file name, key column and columns."""

    name: str
    file: str
    key: tuple[str, ...]
    columns: tuple[ColumnSpec, ...]
    required: bool = True
    title_ru: str = ""
    description: str = ""
    extra: dict[str, str] = field(default_factory=dict)

    def column(self, name: str) -> ColumnSpec:
        """The column called ``name``."""
        for c in self.columns:
            if c.name == name:
                return c
        raise KeyError(name)


_TEXT = ValueSpec("text")
_TEXT_OPT = ValueSpec("text", required=False)
_SOURCE = ColumnSpec("source", _TEXT_OPT, "where the value comes from", ("источник",))
FIGURE_STATUSES = ("norm", "recommendation", "estimate", "practice", "requirement_draft")
"""What a norm figure is: a requirement of a norm, a recommendation (a recommended appendix: a
project may set it aside with a reason), an estimate, practice, or a requirement of a
standard's body with an exception known in a draft's wording only (``requirement_draft``:
the approved text not read; a project may invoke the exception with a reason)."""
_STATUS = ColumnSpec("status", ValueSpec("choice", choices=FIGURE_STATUSES, required=False),
                     "what the figure is: norm, recommendation, estimate, practice or "
                     "requirement_draft",
                     ("статус",))

TABLES: dict[str, TableSpec] = {
    t.name: t
    for t in (
        TableSpec(
            "parameters",
            "parameters.csv",
            ("name",),
            (
                ColumnSpec("name", _TEXT, "parameter name", ("parameter", "параметр", "имя")),
                ColumnSpec("value", _TEXT, "value (rule depends on the parameter)", ("значение",)),
                ColumnSpec("unit", _TEXT_OPT, "unit", ("единица", "ед. изм.")),
                _SOURCE,
                ColumnSpec("note", _TEXT_OPT, "note", ("примечание",)),
                _STATUS,
            ),
            title_ru="Параметры",
            description="coefficients of the technical instruction",
        ),
        TableSpec(
            "shapes",
            "shapes.csv",
            ("shape",),
            (
                ColumnSpec("shape", _TEXT, "shape id", ("форма", "форма объекта")),
                ColumnSpec(
                    "coefficient",
                    ValueSpec("float", 0, 10, min_open=True, unit="-"),
                    "shape recognition coefficient B",
                    ("B", "коэффициент", "коэффициент распознавания формы"),
                ),
                ColumnSpec("name_ru", _TEXT_OPT, "Russian name", ("название",)),
                _SOURCE,
            ),
            title_ru="Коэффициенты формы",
            description="shape coefficients B of the recognition model "
            "(Miheeva & Ilushenko 2015, Table 2)",
        ),
        TableSpec(
            "objects",
            "objects.csv",
            ("map_scale",),
            (
                ColumnSpec(
                    "map_scale",
                    ValueSpec("int", 1, None, unit="1:Mk"),
                    "map scale denominator",
                    (
                        "scale",
                        "Mk",
                        "масштаб",
                        "масштаб карты",
                        "масштаб карты (плана)",
                        "знаменатель масштаба",
                    ),
                ),
                ColumnSpec("object", _TEXT, "object", ("наименование объекта", "объект")),
                ColumnSpec(
                    "object_ru",
                    _TEXT_OPT,
                    "object (Russian)",
                    ("object (Russian)", "наименование объекта (рус.)", "объект (рус.)"),
                ),
                ColumnSpec(
                    "size_m",
                    ValueSpec("float", 0, 1000, min_open=True, unit="m"),
                    "size of the smallest object shown at that scale",
                    (
                        "size",
                        "L",
                        "размер",
                        "размер объекта",
                        "размер объекта L, м",
                        "минимальный размер объекта",
                    ),
                ),
                ColumnSpec("shape", _TEXT, "shape id (a row of the shapes table)", ("форма",)),
                _SOURCE,
                _STATUS,
            ),
            title_ru="Минимальные объекты",
            description="smallest map objects per map scale (Miheeva & Ilushenko 2015, Table 3)",
        ),
        TableSpec(
            "cameras",
            "cameras.csv",
            ("id",),
            (
                ColumnSpec("id", _TEXT, "camera id", ("камера",)),
                ColumnSpec(
                    "kind",
                    ValueSpec("choice", choices=("film", "digital")),
                    "film or digital",
                    ("тип",),
                ),
                ColumnSpec(
                    "platform",
                    ValueSpec("choice", choices=("uav", "aircraft"), required=False),
                    "what carries it: uav, or aircraft (manned aerial survey); default: uav "
                    "for digital, aircraft for film",
                    ("носитель",),
                ),
                ColumnSpec("name", _TEXT, "model", ("модель", "наименование")),
                ColumnSpec(
                    "sensor_width_mm",
                    ValueSpec("float", 0, 1000, min_open=True, unit="mm"),
                    "frame/sensor side across track",
                    ("ширина кадра",),
                ),
                ColumnSpec(
                    "sensor_height_mm",
                    ValueSpec("float", 0, 1000, min_open=True, unit="mm"),
                    "frame/sensor side along track",
                    ("высота кадра",),
                ),
                ColumnSpec(
                    "focal_mm",
                    ValueSpec("float", 0, 2000, min_open=True, unit="mm"),
                    "focal length",
                    ("фокусное расстояние",),
                ),
                ColumnSpec(
                    "pixel_um",
                    ValueSpec("float", 0, 1000, min_open=True, unit="µm", required=False),
                    "published pixel pitch (digital); with the image width the pitch used "
                    "is sensor width / image width, which must agree within 2 %",
                    ("размер пикселя",),
                ),
                ColumnSpec(
                    "image_width_px",
                    ValueSpec("int", 1, None, unit="px", required=False),
                    "image width",
                    ("ширина изображения",),
                ),
                ColumnSpec(
                    "image_height_px",
                    ValueSpec("int", 1, None, unit="px", required=False),
                    "image height",
                    ("высота изображения",),
                ),
                ColumnSpec(
                    "f_number",
                    ValueSpec("float", 0, 100, min_open=True, unit="-", required=False),
                    "f-number",
                    ("диафрагма",),
                ),
                ColumnSpec("shutter", _TEXT_OPT, "shutter type", ("затвор",)),
                ColumnSpec(
                    "min_trigger_interval_s",
                    ValueSpec("float", 0, 3600, unit="s", required=False),
                    "minimum interval between exposures",
                    ("минимальный интервал между снимками",),
                ),
                ColumnSpec(
                    "resolving_power_lpmm",
                    ValueSpec("float", 0, 1000, min_open=True, unit="lines/mm", required=False),
                    "resolving power of the photo (film)",
                    ("разрешающая способность",),
                ),
                ColumnSpec(
                    "orientation",
                    ValueSpec("choice", choices=ORIENTATIONS, required=False),
                    "mounting: landscape (image width across track, the default) or portrait",
                    ("ориентация",),
                ),
                ColumnSpec("note", _TEXT_OPT, "why an entry exists twice, caveats",
                           ("примечание",)),
                ColumnSpec("name_ru", _TEXT_OPT, "the model's name in Russian documents, "
                           "where the maker writes it in Cyrillic (АФА-ТЭ-100)",
                           ("название по-русски",)),
                _SOURCE,
            ),
            required=False,
            title_ru="Камеры",
            description="camera catalogue",
        ),
        TableSpec(
            "scanners",
            "scanners.csv",
            ("scanner", "pixel_um"),
            (
                ColumnSpec("scanner", _TEXT, "scanner id", ("сканер",)),
                ColumnSpec("name", _TEXT_OPT, "model", ("модель",)),
                ColumnSpec(
                    "pixel_um",
                    ValueSpec("float", 0, 1000, min_open=True, unit="µm"),
                    "a scan pixel the scanner offers",
                    ("размер пикселя",),
                ),
                ColumnSpec("bit_depth", _TEXT_OPT, "radiometric resolution as published, "
                           "e.g. '10 internal, 8 or 12 output' [bit]",
                           ("разрядность",)),
                ColumnSpec(
                    "frame_scan_min",
                    ValueSpec("float", 0, 1440, min_open=True, unit="min", required=False),
                    "time to scan one 23×23 cm frame at this pixel, as published",
                    ("время сканирования кадра",),
                ),
                ColumnSpec("note", _TEXT_OPT, "colour or black-and-white, caveats",
                           ("примечание",)),
                _SOURCE,
            ),
            required=False,
            title_ru="Сканеры",
            description="scan pixel sizes offered by each scanner",
        ),
        TableSpec(
            "lens_mtf",
            "lens-mtf.csv",
            ("camera", "position", "freq_lpmm"),
            (
                ColumnSpec("camera", _TEXT, "camera id (a row of the cameras table)",
                           ("камера",)),
                ColumnSpec(
                    "position",
                    ValueSpec("choice", choices=("centre", "corner")),
                    "image point the curve describes: centre, or corner (tangential)",
                    ("положение", "точка поля"),
                ),
                ColumnSpec(
                    "freq_lpmm",
                    ValueSpec("float", 0, 2000, unit="lines/mm"),
                    "spatial frequency on the image",
                    ("частота", "пространственная частота"),
                ),
                ColumnSpec(
                    "mtf",
                    ValueSpec("float", 0, 1, unit="-"),
                    "lens MTF at that frequency (at the working f-number of the flight)",
                    ("ЧКХ", "MTF"),
                ),
                _SOURCE,
            ),
            required=False,
            title_ru="ЧКХ объективов",
            description="manufacturer's lens MTF per camera (frequency → MTF); replaces the "
            "diffraction formula in the MTF chain",
        ),
        TableSpec(
            "gsd_limits",
            "gsd-limits.csv",
            ("map_scale", "area"),
            (
                ColumnSpec(
                    "map_scale",
                    ValueSpec("int", 1, None, unit="1:Mk"),
                    "plan or map scale denominator",
                    ("scale", "Mk", "масштаб", "масштаб плана или карты",
                     "масштаб топографического плана или карты"),
                ),
                ColumnSpec(
                    "area",
                    ValueSpec("choice", choices=GSD_AREAS),
                    "general, or dense_urban (towns with dense multi-storey buildings)",
                    ("территория", "тип территории"),
                ),
                ColumnSpec(
                    "max_gsd_cm",
                    ValueSpec("float", 0, 1000, min_open=True, unit="cm"),
                    "largest ground sample distance of the photos",
                    ("GSD", "max GSD", "размер пикселя на местности",
                     "рекомендуемый размер пикселя на местности (не более)"),
                ),
                _SOURCE,
                _STATUS,
            ),
            required=False,
            title_ru="Предельный размер пикселя",
            description="largest GSD of digital aerial photos per plan scale "
            "(ГОСТ Р 59562-2021, Table Б.1)",
        ),
    )
}
"""Every table a norm set may hold (``required=False``: optional)."""
