"""``scanplan serve``: the local web page (imported only when the command runs)."""

from __future__ import annotations

import ipaddress
import secrets

import click

__all__ = ["serve"]


def _loopback(host: str) -> bool:
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


@click.command()
@click.option("--host", default="127.0.0.1", show_default=True,
              help="Address to listen on. Anything but this machine needs --allow-remote.")
@click.option("--port", type=click.IntRange(0, 65535), default=8765, show_default=True,
              help="Port to listen on (0: any free port).")
@click.option("--open", "open_browser", is_flag=True, help="Open the page in the browser.")
@click.option("--allow-remote", is_flag=True,
              help="Listen off this machine; every API call then needs the printed token.")
@click.option("--tiles", default="osm", show_default=True,
              help='Background map of the page: "osm" (OpenStreetMap), "none" (offline) or '
              "a tile URL with {z}/{x}/{y}.")
@click.option("--tiles-attribution", default=None,
              help="The attribution of the --tiles URL's map, shown on the map and printed "
              "(the tile provider's terms ask for it).")
@click.option("--mbtiles", type=click.Path(exists=True, dir_okay=False), default=None,
              help="An MBTiles file of background tiles, offered on the page (offline use).")
@click.option("--tile-cache", type=click.Path(file_okay=False), default=None,
              help="Folder where fetched tiles are kept [default: the user's cache folder, "
              "scanplan/tiles].")
@click.option("--time-limit", "limit_s", type=click.FloatRange(1, 3600), default=30.0,
              show_default=True, help="Longest one plan may run [s] (reports: four times).")
def serve(host: str, port: int, open_browser: bool, allow_remote: bool, tiles: str,
          tiles_attribution: str | None, mbtiles: str | None, tile_cache: str | None,
          limit_s: float) -> None:
    """Plan on a map in the browser: draw or drop the area, choose the camera, see the
    binding constraint and the strips, download the project file, reports and missions.

    The page talks to a JSON API that plans as `scanplan plan` does (the API's
    documentation is at /docs). `scanplan serve --open` also opens the page in the
    browser; Ctrl+C stops the server.
    """
    from ..errors import InputError

    token = None
    if not _loopback(host):
        if not allow_remote:
            raise InputError("--host", f"{host} is reachable from other machines; add "
                             "--allow-remote to serve there (a token is then required)")
        token = secrets.token_urlsafe(18)
    from pathlib import Path

    from ..web.basemap import Basemaps, check_template

    if tiles not in ("osm", "none"):
        check_template(tiles)
    basemaps = Basemaps(tiles, tiles_attribution, Path(mbtiles) if mbtiles else None,
                        Path(tile_cache) if tile_cache else None)
    from ..extras import require

    require("serve", "scanplan serve", "the web page")  # fastapi, uvicorn: an extra of the install
    import uvicorn

    from ..web.app import create_app
    from ..web.worker import Planner

    planner = Planner(limit_s=limit_s, report_limit_s=4 * limit_s)
    app = create_app(token=token, planner=planner, basemaps=basemaps, host=host)
    config = uvicorn.Config(app, host=host, port=port, log_level="warning")
    server = uvicorn.Server(config)
    shown = f"[{host}]" if ":" in host else host

    def announce() -> None:
        bound = server.servers[0].sockets[0].getsockname()[1] if server.servers else port
        url = f"http://{'127.0.0.1' if host in ('0.0.0.0', '::') else shown}:{bound}/"
        click.echo(f"scanplan: the page is at {url}" + (f"?token={token}" if token else ""))
        if token:
            click.echo(f"token (every API call needs it): {token}")
        click.echo("Ctrl+C stops it.")
        if open_browser:
            import webbrowser

            webbrowser.open(url + (f"?token={token}" if token else ""))

    original = server.startup

    async def startup(sockets: object = None) -> None:
        await original(sockets=sockets)  # type: ignore[arg-type]
        if server.started:
            announce()

    server.startup = startup  # type: ignore[method-assign]
    server.run()
