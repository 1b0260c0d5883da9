"""Benchmark: refusing disguised zip bombs as area files costs less than reading a real one.

Three hostile area files are built in a temporary folder — a zip of 256 MB of zeros named
``.kml``, the same named ``.geojson``, and a KMZ whose ``doc.kml`` is that zip stored — and
each is refused by ``load_area`` from its zip directory. The baseline, in the same process,
is reading the town boundary of the examples (``examples/areas/town-uav.kml``), read and
projected anew each time (the polygons kept read are forgotten before each read): the row is
the slowest refusal over the baseline's median (target ≤ 1: a bomb costs no more than a
real polygon). A second row is the largest Python allocation peak of a refusal [MB]
(tracemalloc): nothing is inflated, so it stays near the file's compressed size.

Run: ``python benchmarks/bench_hostile_gis.py``
"""

from __future__ import annotations

import statistics
import tempfile
import time
import tracemalloc
import zipfile
from pathlib import Path

from _common import ROOT, Result

INFLATED_BYTES = 256 * 2**20
TARGET_RATIO = 1.0
TARGET_PEAK_MB = 16.0


def _bombs(folder: Path) -> list[Path]:
    kml = folder / "bomb.kml"
    member = zipfile.ZipInfo("doc.kml")
    member.compress_type = zipfile.ZIP_DEFLATED
    with zipfile.ZipFile(kml, "w", zipfile.ZIP_DEFLATED, compresslevel=9) as zf, \
            zf.open(member, "w", force_zip64=True) as fh:
        chunk = b"\0" * (1 << 24)
        for _ in range(INFLATED_BYTES // len(chunk)):
            fh.write(chunk)
    geojson = folder / "bomb.geojson"
    geojson.write_bytes(kml.read_bytes())
    nested = folder / "nested.kmz"
    with zipfile.ZipFile(nested, "w", zipfile.ZIP_STORED) as zf:
        zf.writestr("doc.kml", kml.read_bytes())
    return [kml, geojson, nested]


def _time(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def measure(quick: bool) -> list[Result]:
    """The slowest refusal over reading the town KML, and the refusals' allocation peak."""
    from scanplan.errors import InputError
    from scanplan.geo.area import AreaSpec, forget_read_areas, load_area

    repeat = 3 if quick else 7
    town = AreaSpec(file=ROOT / "examples" / "areas" / "town-uav.kml")
    load_area(town)  # imports and GDAL's first open out of the timing

    def read_town() -> None:  # a real read: not the polygon kept from the read before
        forget_read_areas()
        load_area(town)

    baseline = _time(read_town, repeat)
    with tempfile.TemporaryDirectory() as tmp:
        bombs = _bombs(Path(tmp))

        def refuse(path: Path) -> None:
            try:
                load_area(AreaSpec(file=path))
            except InputError:
                return
            raise AssertionError(f"{path.name} was not refused")

        for p in bombs:  # refused as a zip bomb, not for its size on disk
            if p.stat().st_size > INFLATED_BYTES // 100:
                raise AssertionError(f"{p.name} is not a bomb ({p.stat().st_size} bytes)")

        times = {p.name: _time(lambda p=p: refuse(p), repeat) for p in bombs}
        peaks = []
        for p in bombs:
            tracemalloc.start()
            refuse(p)
            peaks.append(tracemalloc.get_traced_memory()[1] / 2**20)
            tracemalloc.stop()
    worst = max(times.values())
    listed = ", ".join(f"{k} {v * 1000:.2f} ms" for k, v in times.items())
    return [
        Result("hostile_gis.bomb_over_town_kml", worst / baseline, "x", TARGET_RATIO, "<=",
               note=f"slowest refusal of a {INFLATED_BYTES // 2**20} MB zip bomb as an area "
               f"file over reading the town KML ({baseline * 1000:.0f} ms), medians of "
               f"{repeat}: {listed}"),
        Result("hostile_gis.bomb_peak_mb", max(peaks), "MB", TARGET_PEAK_MB, "<=",
               timing=False, note="largest Python allocation peak of a refusal "
               "(tracemalloc): nothing is inflated"),
    ]


if __name__ == "__main__":
    for r in measure(quick=False):
        print(r)
