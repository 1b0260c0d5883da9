"""``scanplan cameras``: the camera and scanner catalogue — list, show, import."""

from __future__ import annotations

import os

import click

from .options import complete_camera, complete_norms


def _echo_json(doc: object) -> None:
    from .main import _echo_json as echo

    echo(doc)


#: ``--locale`` of the listings, spelt as ``scan``, ``uav`` and ``init`` spell it.
LOCALE = click.option("--locale", type=click.Choice(["en", "ru"]), default="en",
                      show_default=True, help="Language of the listing (headers, kinds, "
                      "numbers); names and sources are shown as the catalogue stores them.")


def _num(text: str, locale: str) -> str:
    """A number written by Python's format, with the locale's decimal separator."""
    return text.replace(".", ",") if locale == "ru" else text


def _word(kind: str, value: str, locale: str) -> str:
    """A catalogue value in words: the camera's kind, what carries it."""
    from ..i18n.labels_cli import CLI

    key = f"{kind}_{value}"
    return CLI[locale].get(key, value) if value else value


@click.group()
def cameras() -> None:
    """The camera and scanner catalogue (film, digital on UAVs, digital on aircraft).

    \b
    Examples:
      scanplan cameras list
      scanplan cameras list --kind aircraft
      scanplan cameras show rc30-153
      scanplan cameras show photoscan-td
    """


_CAMERA_KINDS = ("film", "digital", "uav", "aircraft", "scanner")


@cameras.command("list")
@click.option("--kind", type=click.Choice(_CAMERA_KINDS),
              help="Only film or digital cameras, cameras carried by a UAV or an aircraft, "
              "or the scanners.")
@click.option("--norms", default="gkinp-02-036-02", show_default=True,
              shell_complete=complete_norms,
              help="Norm set whose cameras to add to the catalogue.")
@click.option("--json", "as_json", is_flag=True,
              help="Print as JSON (a list of cameras; of scanner steps with --kind scanner).")
@LOCALE
def cameras_list(kind: str | None, norms: str, as_json: bool, locale: str = "en") -> None:
    """List the catalogue cameras, then the scanners and their scan pixels.

    Every row names its source (`scanplan cameras show ID`). A digital camera's pitch is
    sensor width / image width.

    \b
    Example:
      scanplan cameras list --kind digital --json
    """
    from dataclasses import asdict

    from ..norms import load_norm_set
    from ..reports.text import table

    ns = load_norm_set(norms)
    cams = [c for c in sorted(ns.cameras.values(), key=lambda c: (c.kind, c.carrier, c.id))
            if kind in (None, c.kind, c.carrier)]
    scanners = sorted(ns.scanner_details) if kind in (None, "scanner") else []
    if as_json:
        if kind == "scanner":
            _echo_json([asdict(s) for sid in scanners for s in ns.scanner_details[sid]])
        else:
            _echo_json([asdict(c) for c in cams])
        return
    from ..i18n.labels_cli import cli_text as w
    from ..reports.wording import camera_title, scanner_title

    loc = locale
    if cams:
        rows = [[w(k, loc) for k in ("cam_id", "cam_kind", "cam_carried", "cam_frame",
                                     "cam_image", "cam_f", "pixel_um", "cam_name")]]
        for c in cams:
            px = (f"{c.image_width_px}×{c.image_height_px}"
                  if c.image_width_px and c.image_height_px else "—")
            rows.append([c.id, _word("kind", c.kind, loc), _word("by", c.carrier, loc),
                         _num(f"{c.sensor_width_mm:g}×{c.sensor_height_mm:g}", loc), px,
                         _num(f"{c.focal_mm:g}", loc),
                         _num(f"{c.pixel_um:.4g}", loc) if c.pixel_um else "—",
                         camera_title(ns, c.id, loc) if loc == "ru" else c.name])
        click.echo(table(rows, align="lllrrrrl"))
        click.echo(w("cam_count", loc, n=len(cams)))
    if scanners:
        rows = [[w(k, loc) for k in ("scn_scanner", "scn_pixels", "scn_depth", "cam_name")]]
        sep = "; " if loc == "ru" else ", "  # the comma is Russian's decimal separator
        for sid in scanners:
            steps = ns.scanner_details[sid]
            depth = "; ".join(dict.fromkeys(s.bit_depth for s in steps if s.bit_depth)) or "—"
            rows.append([sid, sep.join(_num(f"{s.pixel_um:g}", loc) for s in steps), depth,
                         scanner_title(ns, sid, loc) if loc == "ru"
                         else ns.scanner_names.get(sid, sid)])
        if cams:
            click.echo("")
        click.echo(table(rows, align="llll"))
        click.echo(w("scn_count", loc, n=len(scanners)))


@cameras.command("show")
@click.argument("camera_id", shell_complete=complete_camera)
@click.option("--norms", default="gkinp-02-036-02", show_default=True,
              shell_complete=complete_norms,
              help="Norm set whose cameras to add to the catalogue.")
@click.option("--json", "as_json", is_flag=True, help="Print as JSON.")
@LOCALE
def cameras_show(camera_id: str, norms: str, as_json: bool, locale: str = "en") -> None:
    """Show one camera or scanner: CAMERA_ID from `scanplan cameras list`."""
    from dataclasses import asdict

    from ..i18n.labels_cli import cli_text as w
    from ..norms import load_norm_set
    from ..reports.text import table
    from ..reports.wording import scanner_title

    loc = locale
    ns = load_norm_set(norms)
    if camera_id not in ns.cameras and camera_id in ns.scanner_details:
        steps = [asdict(s) for s in ns.scanner_details[camera_id]]
        if as_json:
            _echo_json(steps)
            return
        rows = [[w(k, loc) for k in ("pixel_um", "scn_depth", "scn_frame_min", "scn_note",
                                     "source")]]
        rows += [[_num(f"{s['pixel_um']:g}", loc), s["bit_depth"] or "—",
                  "—" if s["frame_scan_min"] is None else _num(f"{s['frame_scan_min']:g}", loc),
                  s["note"] or "—", s["source"] or "—"] for s in steps]
        name = (scanner_title(ns, camera_id, loc) if loc == "ru"
                else ns.scanner_names.get(camera_id, camera_id))
        click.echo(f"{camera_id}: {name}")
        click.echo(table(rows, align="rllll"))
        return
    cam = ns.camera(camera_id, "CAMERA_ID")
    d = asdict(cam)
    d["carried_by"] = cam.carrier
    lens = ns.lens_mtf.get(cam.id, {})
    d["lens_mtf"] = {pos: asdict(curve) for pos, curve in lens.items()} or None
    if as_json:
        _echo_json(d)
        return
    d["lens_mtf"] = "; ".join(
        w("lens_mtf_points", loc, pos=w(f"pos_{pos}", loc) if f"pos_{pos}" in
          _positions() else pos, n=len(c.freq_lpmm), f=_num(f"{c.freq_lpmm[-1]:g}", loc),
          source=c.source or "—")
        for pos, c in lens.items()) or w("lens_mtf_none", loc)
    click.echo(table([[_key(k, loc), _value(k, v, ns, cam.id, loc)] for k, v in d.items()],
                     align="ll"))


def _positions() -> set[str]:
    return {"pos_centre", "pos_corner"}


#: The terminal's word of a catalogue column's unit (the schema's unit, in English).
_UNIT_WORDS = {"mm": "mm", "µm": "um", "px": "px", "s": "s", "lines/mm": "lpmm", "m": "m"}


def _key(key: str, locale: str) -> str:
    """A camera field by name: the schema's key (English; its unit in the name), the norm
    workbook's Russian header (``scanplan norms template --locale ru``) with its unit in
    Russian."""
    if locale != "ru":
        return key
    from ..i18n.labels_cli import CLI
    from ..norms.schema import TABLES

    for col in TABLES["cameras"].columns:
        if col.name == key and col.aliases:
            unit = _UNIT_WORDS.get(col.value.unit)
            return col.aliases[0] + (f", {CLI['ru'][unit]}" if unit else "")
    if key == "published_pixel_um":
        return f"{CLI['ru']['published_pixel']}, {CLI['ru']['um']}"
    extra = {"carried_by": "carried_effective", "lens_mtf": "lens_mtf"}.get(key, key)
    return CLI["ru"].get(extra, extra)


def _value(key: str, value: object, ns: object, camera_id: str, locale: str) -> str:
    """A camera field's value in the listing's language."""
    if value in (None, ""):
        return "—"
    if locale != "ru":
        return str(value)
    if key == "kind":
        return _word("kind", str(value), locale)
    if key in ("platform", "carried_by"):
        return _word("by", str(value), locale)
    if key == "shutter":
        return _word("shutter", str(value), locale)
    if key == "orientation":
        from ..i18n.labels import t

        return t(f"orientation_{value}", locale)
    if key == "name":
        from ..reports.wording import camera_title

        return camera_title(ns, camera_id, locale)  # type: ignore[arg-type]
    if isinstance(value, float):
        return _num(str(value), locale)
    return str(value)


@cameras.command("import")
@click.argument("file", type=click.Path(dir_okay=False))
@click.option("--force", is_flag=True, help="Replace user cameras/scanners with the same id.")
@click.option("--source", default="", help="Where the values come from (added to each row).")
@click.option("--table", type=click.Choice(["cameras", "scanners", "lens_mtf"]),
              help="The table a CSV holds (default: from its name or headers).")
@click.option("--json", "as_json", is_flag=True, help="Print what was imported as JSON.")
def cameras_import(file: str, force: bool, source: str, table: str | None,
                   as_json: bool) -> None:
    """Add cameras and scanners from FILE to the user catalogue.

    FILE is QGroundControl's camera list (CameraMetaData.json), a workbook (.xlsx) with a
    "cameras"/"Камеры" and/or "scanners"/"Сканеры" sheet (headers in English or Russian,
    as in `scanplan norms template`), or a CSV of one of those tables. Nothing is written
    unless the whole file is valid; every norm set then sees the cameras.

    \b
    Examples:
      scanplan cameras import CameraMetaData.json --source "QGroundControl 4.4"
      scanplan cameras import our-cameras.xlsx --force
    """
    from ..project.cameras import import_camera_file

    folder, parsed = import_camera_file(file, force=force, source=source, table=table)
    if as_json:
        _echo_json({"path": str(folder), "cameras": [r["id"] for r in parsed.cameras],
                    "scanners": sorted({r["scanner"] for r in parsed.scanners}),
                    "warnings": list(parsed.warnings)})
        return
    steps = len(parsed.scanners)
    click.echo(f"imported {len(parsed.cameras)} cameras and {steps} scanner steps from "
               f"{os.path.basename(file)} into the user catalogue ({folder})")
    for w in parsed.warnings:
        click.echo(f"note: {w}", err=True)
    if parsed.cameras:
        click.echo(f"use them with: scanplan uav --camera {parsed.cameras[0]['id']} ...")
