"""The aircraft catalogue and the flight model of a sortie (``norms/catalogue/``).

``aircraft.csv`` holds the carriers of the catalogue's UAV cameras as their makers publish
them — flight time per battery (with the conditions it was measured in), cruise and maximum
speed, wind limit, RTK, the catalogue cameras each carries — every value with its source;
a figure no source at hand gives is left blank and the row's ``note`` says so (docs/
aircraft.md lists the aircraft that were looked for and not found).

``flight-model.csv`` holds the numbers of the sortie time as flown (docs/flight-lines.md):
the battery reserve (the usable flight time of a battery is its published flight time less
the reserve), the acceleration and braking along the path, the lateral acceleration in a
corner and how far a corner is cut, the climb and descent speeds — each with its source and
status (``practice``: a rule of the trade; ``assumption``: an autopilot's default taken
where the maker publishes none).

>>> a = aircraft("dji-m350-rtk")
>>> a.max_flight_time_min, a.usable_flight_time_min(), a.cameras
(55.0, 44.0, ('dji-zenmuse-p1-35', 'dji-zenmuse-l2-rgb'))
>>> [x.id for x in carriers_of("dji-mavic-3e")]
['dji-mavic-3e']
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

from ..errors import InputError
from .paths import CATALOGUE, bundled_norms_dir

__all__ = ["AIRCRAFT_COLUMNS", "FLIGHT_TIME_BASES", "Aircraft", "FlightModelParam", "aircraft",
           "all_aircraft", "carriers_of", "flight_model_params", "load_aircraft"]

AIRCRAFT_COLUMNS = ("id", "name", "kind", "max_flight_time_min", "flight_time_basis",
                    "cruise_speed_ms", "max_speed_ms", "max_wind_ms", "rtk", "cameras", "note",
                    "source", "name_ru")
"""The columns of ``aircraft.csv``, in order."""
_NUMBERS = ("max_flight_time_min", "cruise_speed_ms", "max_speed_ms", "max_wind_ms")
_KINDS = ("multirotor", "fixed_wing", "vtol")
FLIGHT_TIME_BASES = ("no_payload_windless_to_empty", "approximate")
"""How a published flight time was measured (their words: the message catalogue's
``flight_time.<basis>``): DJI's "without payloads in a windless environment until the
battery reached 0 %", or a figure published as approximate."""


@dataclass(frozen=True)
class FlightModelParam:
    """One number of the flight model: value, unit, source, note and status."""

    name: str
    value: float
    unit: str
    source: str
    note: str
    status: str


@dataclass(frozen=True)
class Aircraft:
    """A catalogue aircraft (None: the sources at hand give no value).

    Attributes
    ----------
    id, name, name_ru : str
        Catalogue id and the model's name (English, Russian).
    kind : {"multirotor", "fixed_wing", "vtol"}
    max_flight_time_min : float or None
        The published flight time of one battery [min], measured as ``flight_time_basis``
        says (one of :data:`FLIGHT_TIME_BASES`).
    cruise_speed_ms, max_speed_ms, max_wind_ms : float or None
        Cruise and maximum horizontal speed, and the wind it is rated for [m/s].
    rtk : bool or None
        Whether it carries an RTK receiver.
    cameras : tuple of str
        The catalogue cameras it carries.
    note, source : str
        What is missing and why; where every value comes from.
    """

    id: str
    name: str
    kind: str
    max_flight_time_min: float | None
    flight_time_basis: str = ""
    cruise_speed_ms: float | None = None
    max_speed_ms: float | None = None
    max_wind_ms: float | None = None
    rtk: bool | None = None
    cameras: tuple[str, ...] = ()
    note: str = ""
    source: str = ""
    name_ru: str = ""
    reserve_pct: float = field(default=math.nan, compare=False)

    def usable_flight_time_min(self) -> float | None:
        """The flight time of one sortie [min]: the published flight time less the
        battery reserve (``flight-model.csv``, ``battery_reserve_pct``); None when no
        flight time is published."""
        if self.max_flight_time_min is None:
            return None
        reserve = self.reserve_pct if math.isfinite(self.reserve_pct) else \
            flight_model_params()["battery_reserve_pct"].value
        return self.max_flight_time_min * (1.0 - reserve / 100.0)


def _number(text: str, where: str) -> float | None:
    text = (text or "").strip()
    if not text:
        return None
    try:
        value = float(text)
    except ValueError:
        raise InputError(where, f"must be a number (got {text!r})") from None
    if not math.isfinite(value) or value <= 0:
        raise InputError(where, f"must be a positive number (got {text!r})")
    return value


def load_aircraft(path: Path) -> dict[str, Aircraft]:
    """The aircraft of a catalogue file (``file:row (column)`` errors).

    Parameters
    ----------
    path : Path
        An ``aircraft.csv`` with :data:`AIRCRAFT_COLUMNS`.
    """
    text = path.read_text(encoding="utf-8-sig")
    rows = csv.DictReader(io.StringIO(text))
    if tuple(rows.fieldnames or ()) != AIRCRAFT_COLUMNS:
        raise InputError(str(path), f"must have the columns {', '.join(AIRCRAFT_COLUMNS)}")
    out: dict[str, Aircraft] = {}
    for i, r in enumerate(rows, start=2):
        where = f"{path}:{i}"
        if r["id"] in out:
            raise InputError(f"{where} (id)", f"aircraft id {r['id']!r} appears twice")
        if r["kind"] not in _KINDS:
            raise InputError(f"{where} (kind)", f"must be one of {', '.join(_KINDS)}")
        nums = {k: _number(r[k], f"{where} ({k})") for k in _NUMBERS}
        rtk = {"yes": True, "no": False, "": None}.get(r["rtk"].strip())
        if r["rtk"].strip() not in ("yes", "no", ""):
            raise InputError(f"{where} (rtk)", "must be yes, no or empty")
        cams = tuple(c.strip() for c in r["cameras"].split(";") if c.strip())
        if r["flight_time_basis"] not in (*FLIGHT_TIME_BASES, ""):
            raise InputError(f"{where} (flight_time_basis)",
                             f"must be one of {', '.join(FLIGHT_TIME_BASES)}")
        out[r["id"]] = Aircraft(
            id=r["id"], name=r["name"], kind=r["kind"], **nums,
            flight_time_basis=r["flight_time_basis"], rtk=rtk, cameras=cams,
            note=r["note"], source=r["source"], name_ru=r["name_ru"])
    return out


@lru_cache(maxsize=1)
def all_aircraft() -> dict[str, Aircraft]:
    """The bundled aircraft catalogue, by id."""
    return load_aircraft(bundled_norms_dir() / CATALOGUE / "aircraft.csv")


def aircraft(aircraft_id: str, field_name: str = "aircraft") -> Aircraft:
    """One catalogue aircraft; an unknown id is an :class:`InputError` naming the known
    ones."""
    known = all_aircraft()
    if aircraft_id not in known:
        raise InputError(field_name, f"unknown aircraft {aircraft_id!r}; the catalogue has "
                         f"{', '.join(sorted(known))} (scanplan aircraft list)")
    return known[aircraft_id]


def carriers_of(camera_id: str | None) -> list[Aircraft]:
    """The catalogue aircraft that carry the camera ``camera_id``, by id."""
    if not camera_id:
        return []
    return [a for _, a in sorted(all_aircraft().items()) if camera_id in a.cameras]


@lru_cache(maxsize=1)
def flight_model_params() -> dict[str, FlightModelParam]:
    """The flight model's numbers (``flight-model.csv``), by name."""
    path = bundled_norms_dir() / CATALOGUE / "flight-model.csv"
    out = {}
    for i, r in enumerate(csv.DictReader(io.StringIO(path.read_text(encoding="utf-8-sig"))),
                          start=2):
        value = _number(r["value"], f"{path}:{i} (value)")
        assert value is not None, f"{path}:{i}: a flight-model number is required"
        out[r["name"]] = FlightModelParam(r["name"], value, r["unit"], r["source"], r["note"],
                                          r["status"])
    return out
