"""``scanplan cameras``: the camera and scanner catalogue — list, show, import."""

from __future__ import annotations

import os

import click


def _echo_json(doc: object) -> None:
    from .main import _echo_json as echo

    echo(doc)


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
              help="Norm set whose cameras to add to the catalogue.")
@click.option("--json", "as_json", is_flag=True,
              help="Print as JSON (a list of cameras; of scanner steps with --kind scanner).")
def cameras_list(kind: str | None, norms: str, as_json: bool) -> None:
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
    if cams:
        rows = [["id", "kind", "carried by", "frame/sensor mm", "image px", "f mm",
                 "pixel µm", "name"]]
        for c in cams:
            px = (f"{c.image_width_px}×{c.image_height_px}"
                  if c.image_width_px and c.image_height_px else "—")
            rows.append([c.id, c.kind, c.carrier,
                         f"{c.sensor_width_mm:g}×{c.sensor_height_mm:g}", px, f"{c.focal_mm:g}",
                         f"{c.pixel_um:.4g}" if c.pixel_um else "—", c.name])
        click.echo(table(rows, align="lllrrrrl"))
        click.echo(f"{len(cams)} cameras")
    if scanners:
        rows = [["scanner", "scan pixels µm", "bit depth", "name"]]
        for sid in scanners:
            steps = ns.scanner_details[sid]
            depth = "; ".join(dict.fromkeys(s.bit_depth for s in steps if s.bit_depth)) or "—"
            rows.append([sid, ", ".join(f"{s.pixel_um:g}" for s in steps), depth,
                         ns.scanner_names.get(sid, sid)])
        if cams:
            click.echo("")
        click.echo(table(rows, align="llll"))
        click.echo(f"{len(scanners)} scanners")


@cameras.command("show")
@click.argument("camera_id")
@click.option("--norms", default="gkinp-02-036-02", show_default=True,
              help="Norm set whose cameras to add to the catalogue.")
@click.option("--json", "as_json", is_flag=True, help="Print as JSON.")
def cameras_show(camera_id: str, norms: str, as_json: bool) -> None:
    """Show one camera or scanner: CAMERA_ID from `scanplan cameras list`."""
    from dataclasses import asdict

    from ..norms import load_norm_set
    from ..reports.text import table

    ns = load_norm_set(norms)
    if camera_id not in ns.cameras and camera_id in ns.scanner_details:
        steps = [asdict(s) for s in ns.scanner_details[camera_id]]
        if as_json:
            _echo_json(steps)
            return
        rows = [["pixel µm", "bit depth", "frame min", "note", "source"]]
        rows += [[f"{s['pixel_um']:g}", s["bit_depth"] or "—",
                  "—" if s["frame_scan_min"] is None else f"{s['frame_scan_min']:g}",
                  s["note"] or "—", s["source"] or "—"] for s in steps]
        click.echo(f"{camera_id}: {ns.scanner_names.get(camera_id, camera_id)}")
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
        f"{pos}: {len(c.freq_lpmm)} points to {c.freq_lpmm[-1]:g} lines/mm ({c.source or '—'})"
        for pos, c in lens.items()) or "— (diffraction formula)"
    click.echo(table([[k, "—" if v in (None, "") else str(v)] for k, v in d.items()],
                     align="ll"))


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
