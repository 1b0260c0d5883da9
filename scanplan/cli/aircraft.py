"""``scanplan aircraft``: the aircraft catalogue — list, show."""

from __future__ import annotations

import click

from .cameras import LOCALE, _echo_json, _num


@click.group()
def aircraft() -> None:
    """The aircraft catalogue: flight time per battery, speeds, wind, RTK, the cameras.

    Each aircraft's sortie time is its published flight time less the battery reserve;
    `[uav] aircraft = "ID"` (or `--aircraft ID`) sets it for a plan. Every value names
    its source; a value no source gives is left blank.

    \b
    Examples:
      scanplan aircraft list
      scanplan aircraft show dji-m350-rtk
      scanplan aircraft list --json
    """


def _record(a: object) -> dict[str, object]:
    from dataclasses import asdict

    d = asdict(a)  # type: ignore[call-overload]
    d.pop("reserve_pct", None)
    d["usable_flight_time_min"] = a.usable_flight_time_min()  # type: ignore[attr-defined]
    return d


@aircraft.command("list")
@click.option("--camera", help="Only the aircraft that carry this catalogue camera.")
@click.option("--json", "as_json", is_flag=True, help="Print as JSON (a list of aircraft).")
@LOCALE
def aircraft_list(camera: str | None, as_json: bool, locale: str = "en") -> None:
    """List the catalogue aircraft with their sortie time (the flight time less the
    battery reserve).

    \b
    Example:
      scanplan aircraft list --camera dji-zenmuse-p1-35
    """
    from ..i18n.labels_cli import cli_text as w
    from ..norms.aircraft import all_aircraft, carriers_of, flight_model_params
    from ..reports.text import table

    if camera:
        from ..norms import load_norm_set

        load_norm_set("gkinp-02-036-02").camera(camera, "--camera")  # an unknown id: exit 2
    crafts = carriers_of(camera) if camera else [a for _, a in sorted(all_aircraft().items())]
    if as_json:
        _echo_json([_record(a) for a in crafts])
        return
    loc = locale

    def n(v: float | None, fmt: str = "g") -> str:
        return "—" if v is None else _num(format(v, fmt), loc)

    rows = [[w(k, loc) for k in ("ac_id", "cam_kind", "ac_time", "ac_usable", "ac_speed",
                                 "ac_wind", "ac_rtk", "ac_cameras", "cam_name")]]
    for a in crafts:
        rtk = "—" if a.rtk is None else w("ac_yes" if a.rtk else "ac_no", loc)
        rows.append([a.id, w(f"ac_kind_{a.kind}", loc), n(a.max_flight_time_min),
                     n(a.usable_flight_time_min(), ".0f"), n(a.max_speed_ms), n(a.max_wind_ms),
                     rtk, ", ".join(a.cameras) or "—",
                     a.name_ru if loc == "ru" and a.name_ru else a.name])
    click.echo(table(rows, align="llrrrrlll"))
    reserve = flight_model_params()["battery_reserve_pct"]
    click.echo(w("ac_count", loc, n=len(crafts), reserve=reserve.value, status=reserve.status,
                 source=reserve.source))


@aircraft.command("show")
@click.argument("aircraft_id")
@click.option("--json", "as_json", is_flag=True, help="Print as JSON.")
@LOCALE
def aircraft_show(aircraft_id: str, as_json: bool, locale: str = "en") -> None:
    """Show one aircraft: AIRCRAFT_ID from `scanplan aircraft list`, every value with its
    source, and the flight model its sorties are timed with."""
    from ..norms.aircraft import aircraft as get
    from ..norms.aircraft import flight_model_params
    from ..reports.text import table

    a = get(aircraft_id, "AIRCRAFT_ID")
    d = _record(a)
    if as_json:
        d["flight_model"] = {k: {"value": p.value, "unit": p.unit, "source": p.source,
                                 "status": p.status}
                             for k, p in flight_model_params().items()}
        _echo_json(d)
        return
    yes_no = {True: "ac_yes", False: "ac_no"}
    from ..i18n.labels_cli import cli_text as w

    rows = [[k, "—" if v in (None, "", ()) else w(yes_no[v], locale) if isinstance(v, bool)
             else ", ".join(v) if isinstance(v, tuple)
             else _num(f"{v:g}", locale) if isinstance(v, float) else str(v)]
            for k, v in d.items()]
    click.echo(table(rows, align="ll"))
    click.echo("")
    rows = [[p.name, _num(f"{p.value:g}", locale) + " " + p.unit, p.status, p.source]
            for p in flight_model_params().values()]
    click.echo(table(rows, align="lrll"))
