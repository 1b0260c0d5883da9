"""Benchmark: the town plan as the page re-plans it, warm and in a fresh process.

Rows:

- ``plan_warm.cpu_ms`` — ``scanplan.plan("examples/uav-town-2000.toml")`` without reports
  in a warm process (the page's and a notebook's case: the project file read, the KML
  polygon read and projected, the limits, the "auto" direction, strips, photo centres and
  sorties), CPU time of this process (``time.process_time``), median; target 50 ms.
- ``plan_warm.over_shapely`` — that time over a bare shapely baseline run interleaved with
  it in this process: the same projected polygon rotated to the plan's direction, cut into
  the plan's number of parallel strips by one ``shapely.intersection`` of their bands, and
  the plan's number of photo centres spread along the pieces with numpy and rotated back;
  target 10×. Its note adds the warm CPU time of the page's heaviest examples
  (:data:`HEAVY`), without a target of their own (``serve.view_ms`` has the page's).
- ``plan_warm.first_over_bare_s`` — a fresh ``python -c "import scanplan;
  scanplan.plan(...)"`` over a bare ``python -c pass``, both as whole processes, CPU time
  (user + system of the child, ``resource.getrusage``), medians, interleaved; target 0.6 s.
  The note gives the wall times.

Run: ``python benchmarks/bench_plan_warm.py``
"""

from __future__ import annotations

import math
import resource
import statistics
import subprocess
import sys
import time

import numpy as np
from _common import ROOT, Result, child_env

TOWN = ROOT / "examples" / "uav-town-2000.toml"
HEAVY = {"uav-town-valley-2000": "the valley over its DEM, nine plans compared",
         "uav-town-2000-afs": "the town with a schedule's sun windows"}
"""The page's heaviest examples, timed warm for the note."""
WARM_TARGET_MS = 50.0
OVER_SHAPELY_TARGET = 10.0
FIRST_TARGET_S = 0.6


def shapely_baseline(geom: object, direction_deg: float, spacing_m: float,
                     n_photos: int) -> np.ndarray:
    """The least a layout does: the polygon rotated, cut into parallel bands, photo centres
    along the pieces, rotated back (x, y)."""
    import shapely
    from shapely import affinity

    c = geom.centroid  # type: ignore[attr-defined]
    rot = affinity.rotate(geom, direction_deg, origin=(c.x, c.y))
    x0, y0, x1, y1 = rot.bounds
    n = max(1, math.ceil((x1 - x0) / spacing_m))
    u = x0 + (x1 - x0 - n * spacing_m) / 2 + (np.arange(n) + 0.5) * spacing_m
    boxes = shapely.box(u - spacing_m / 2, y0 - 1, u + spacing_m / 2, y1 + 1)
    parts, idx = shapely.get_parts(shapely.intersection(boxes, rot), return_index=True)
    b = shapely.bounds(parts)
    length = b[:, 3] - b[:, 1]
    share = np.maximum(1, np.round(n_photos * length / length.sum())).astype(int)
    part = np.repeat(np.arange(len(parts)), share)
    t = (np.arange(len(part)) - np.repeat(np.cumsum(share) - share, share)) / np.maximum(
        share[part] - 1, 1)
    pu, pv = u[idx[part]], b[part, 1] + t * length[part]
    a = math.radians(direction_deg)
    du, dv = pu - c.x, pv - c.y
    return np.c_[c.x + du * math.cos(a) + dv * math.sin(a),
                 c.y - du * math.sin(a) + dv * math.cos(a)]


def _cpu(fn: object) -> float:
    t = time.process_time()
    fn()  # type: ignore[operator]
    return time.process_time() - t


def warm(repeat: int) -> tuple[float, float, dict[str, object]]:
    """Median CPU seconds of the warm plan and of the baseline (interleaved), and facts."""
    import scanplan

    r = scanplan.plan(TOWN)
    scanplan.plan(TOWN)
    lay = r.uav.job.layout
    spacing = lay.spacing_m * lay.notes.get("grid_scale", 1.0)
    args = (lay.area.geometry, lay.direction_deg, spacing, int(lay.notes["photos"]))
    shapely_baseline(*args)
    plan_t, base_t = [], []
    for _ in range(repeat):
        plan_t.append(_cpu(lambda: scanplan.plan(TOWN)))
        base_t.append(_cpu(lambda: shapely_baseline(*args)))
    facts = {"strips": len(lay.strips), "photos": lay.notes["photos"],
             "direction": lay.direction_deg}
    return statistics.median(plan_t), statistics.median(base_t), facts


def edited(repeat: int) -> float:
    """Median CPU seconds of a warm plan whose polygon changed since the last one: the town
    given inline, one vertex moved 1 m further at each plan (a drag on the page), so the
    area is read and projected again and the strips laid out anew."""
    import tomllib

    import scanplan

    r = scanplan.plan(TOWN)
    area = r.uav.job.layout.area
    ring = [list(p) for p in area.geometry.exterior.coords[:-1]]
    proj = tomllib.loads(TOWN.read_text(encoding="utf-8"))
    proj = {**proj, "area": {**{k: v for k, v in proj["area"].items() if k != "file"},
                             "polygon": ring, "crs": area.plan_crs}}
    times = []
    for i in range(repeat + 1):
        ring[0] = [ring[0][0] + 1.0, ring[0][1]]
        t = _cpu(lambda: scanplan.plan({**proj, "area": {**proj["area"],
                                                          "polygon": [list(p) for p in ring]}}))
        if i:
            times.append(t)
    return statistics.median(times)


def heavy(repeat: int) -> dict[str, float]:
    """Median CPU seconds of a warm plan of each of :data:`HEAVY` (after two warm-ups)."""
    import scanplan

    out = {}
    for name in HEAVY:
        path = ROOT / "examples" / f"{name}.toml"
        scanplan.plan(path)
        scanplan.plan(path)
        out[name] = statistics.median(_cpu(lambda p=path: scanplan.plan(p))
                                      for _ in range(repeat))
    return out


def _child(code: str) -> tuple[float, float]:
    """(wall, CPU) seconds of a fresh ``python -c code``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT, env=child_env())
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def first(repeat: int) -> dict[str, float]:
    """Medians of a fresh process's first plan and of bare Python, wall and CPU [s]."""
    code = f"import scanplan; scanplan.plan({str(TOWN)!r})"
    plans, bares = [], []
    _child(code)  # bytecode compiled and the page cache warm, as for a user's second run
    for _ in range(repeat):
        plans.append(_child(code))
        bares.append(_child("pass"))
    return {"plan_wall": statistics.median(w for w, _ in plans),
            "plan_cpu": statistics.median(c for _, c in plans),
            "bare_wall": statistics.median(w for w, _ in bares),
            "bare_cpu": statistics.median(c for _, c in bares)}


def measure(quick: bool = False) -> list[Result]:
    """The runner's entry: the warm plan, its ratio to the baseline, the first plan.

    Parameters
    ----------
    quick : bool, optional
        Medians of 5 warm plans and 3 fresh processes instead of 21 and 7.

    Returns
    -------
    list of Result
    """
    plan_s, base_s, facts = warm(5 if quick else 21)
    edit_s = edited(5 if quick else 21)
    f = first(3 if quick else 7)
    others = "; ".join(f"{HEAVY[k]} ({k}) {v * 1000:,.0f} ms"
                       for k, v in heavy(3 if quick else 7).items())
    return [
        Result("plan_warm.cpu_ms", plan_s * 1000, "ms", WARM_TARGET_MS, "<=",
               note=f"warm scanplan.plan of uav-town-2000 (no reports): {facts['strips']} "
               f"strips, {facts['photos']:,} photo centres, direction "
               f"{facts['direction']:.1f}°; CPU time, median. With a vertex moved before "
               f"each plan (the area read and projected again): {edit_s * 1000:.1f} ms. "
               f"The heaviest examples, warm, CPU, median: {others}"),
        Result("plan_warm.over_shapely", plan_s / base_s, "x", OVER_SHAPELY_TARGET, "<=",
               note=f"over a bare shapely cut of the same polygon into the same strips and "
               f"photo centres, interleaved: {base_s * 1000:.1f} ms CPU"),
        Result("plan_warm.first_over_bare_s", f["plan_cpu"] - f["bare_cpu"], "s",
               FIRST_TARGET_S, "<=",
               note=f"fresh `python -c 'import scanplan; scanplan.plan(town)'` "
               f"{f['plan_cpu']:.2f} s CPU ({f['plan_wall']:.2f} s wall) over bare python "
               f"{f['bare_cpu']:.3f} s CPU ({f['bare_wall']:.3f} s wall); medians"),
    ]


if __name__ == "__main__":
    for row in measure(quick="--quick" in sys.argv):
        print(f"{row.name}: {row.value:.3g} {row.unit} (target {row.comparison} "
              f"{row.target:g}) {row.status} — {row.note}")
