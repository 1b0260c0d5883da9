"""The plan a crew lead would choose: the candidates compared, costed, and the one with the
least flying time that meets every constraint recommended (docs/plan-choice.md).

For a UAV block over an area the specification lays out every plan a crew would consider
and costs each with the figures the reports print — photos, data volume, and the flying
time and sorties of its own layout (:func:`scanplan.project.flightplan.uav_flight_figures`:
the serpentine with its turns, run-in and run-out, packed into sorties by
:mod:`scanplan.geo.sorties`):

- **line direction** (an area on the map): the direction of the least flight length
  (``"auto"``), the area's long axis (:func:`scanplan.geo.direction.long_axis_deg`), over a
  DEM the direction whose strips span the least relief
  (:func:`scanplan.geo.terrain_choice.mode_heights`), and the project's own;
- **altitude mode** (``[terrain]``): ``constant``, ``strip`` and ``follow``, each held
  to the highest height its own layout allows (layout and height iterated to a fixed
  point, :func:`scanplan.project.terrainplan.settle`); over a ground range without a DEM
  only ``constant`` can be laid out, ``follow`` is an estimate;
- **the block split into parts by ground height** where the one-height rule asks for it:
  an estimate (the parts' outlines are not laid out).

A plan meets every constraint when its layout can be flown, its worst photo meets every
limit of the rules (:mod:`scanplan.rules.terrain`), no overlap falls more than
:data:`OVERLAP_SLACK_PCT` short of the planned one, and the one-height rule holds
(:func:`scanplan.project.design.block_rule`; waived when following the terrain). Among those
the project's choices allow (``[terrain] altitude_mode``, ``[area] direction_deg``) the one
with the least flying time, then the fewest photos, is recommended; when none meets every
constraint, the cheapest the choices allow. A pinned choice that costs more than
:data:`PINNED_EXTRA` beyond the best plan meeting every constraint is a warning with the
saving.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from ..core.photoscale import ground_pixel_m
from ..geo.direction import long_axis_deg, same_direction
from ..i18n.messages import Message, params_json
from ..rules.results import PlanWarning
from .design import block_rule, terrain_ground_m
from .flightplan import uav_flight_figures
from .jobs import UavJob, recommended_height_m
from .model import AUTO_MODE, ProjectModel
from .results import Alternative

if TYPE_CHECKING:  # the relief's modules are imported for a plan with [terrain] only
    from ..geo.terrain import TerrainConfig, TerrainResult
    from .terrainplan import Settled

__all__ = ["LARGE_PLAN_PHOTOS", "MAX_PARTS", "OVERLAP_SLACK_PCT", "PINNED_EXTRA", "Candidate",
           "JobAt", "PlanChoice", "alternatives_dicts", "choose_plan", "describe",
           "overlap_findings"]

OVERLAP_SLACK_PCT = 1.0
"""An overlap this many percentage points below the planned one is a finding, not a reason
to reject a plan (a ridge between two strips flown at their own altitudes takes a few
tenths of a point); beyond it the plan is rejected [%]."""
PINNED_EXTRA = 0.25
"""A choice of the project costing this share more flying time than the best plan meeting
every constraint is a warning (below it a note in the plans compared only)."""
MAX_PARTS = 20
"""Most parts a block is split into by ground height."""
LARGE_PLAN_PHOTOS = 100_000
"""A block of more photos is compared along its own direction (the project's, or the least
flight length) only: every mode, not every direction (each plan costs a layout and a check
of every photo)."""

JobAt = Callable[..., UavJob]
"""``job_at(height_m, direction=None, flown_band_m=None, laid_out=None)``: the job at a
planned height, laid out along ``direction`` (None: the project's own, ``"auto"`` or
degrees), its figures at ``flown_band_m`` over relief (keeping the layout ``laid_out``)."""


@dataclass(frozen=True)
class Candidate:
    """A plan to lay out: an altitude mode (None on flat ground), which direction and the
    one asked (None: the least flight length; the project's own for ``project``)."""

    mode: str | None
    direction: str
    direction_deg: float | str | None


@dataclass(frozen=True)
class _Planned:
    """A candidate laid out and checked: its job, and over relief its settled layout."""

    candidate: Candidate
    job: UavJob
    settled: Settled | None
    alternative: Alternative


@dataclass(frozen=True)
class PlanChoice:
    """The specification's UAV plan chosen among the alternatives.

    Attributes
    ----------
    alternatives : tuple of Alternative
        Every plan compared, in the order laid out; one ``recommended``.
    job : UavJob
        The recommended plan (over relief: its figures at the heights really flown,
        its layout with the terrain columns).
    terrain : TerrainResult or None
    height_m : float
        Its planned height above the reference ground [m].
    lowered : Message or None
        Why the height is below the start (over relief), else None.
    choice : Message or None
        Why this plan among the others (None when there was no choice).
    warnings : tuple of PlanWarning
        The recommended plan's terrain findings and the choice's warnings.
    """

    alternatives: tuple[Alternative, ...]
    job: UavJob
    terrain: TerrainResult | None
    height_m: float
    lowered: Message | None
    choice: Message | None
    warnings: tuple[PlanWarning, ...]


def choose_plan(project: ProjectModel, start: UavJob, job_at: JobAt,
                planned_m: float | None) -> PlanChoice:
    """Lay out, check and cost every candidate and choose (the module's rules).

    Parameters
    ----------
    project : ProjectModel
        The parsed project (its ``[terrain]``, ``[area] direction_deg``, norms).
    start : UavJob
        The job at the height to start from (the flat recommendation, or the project's
        height), laid out over the area as the project asks.
    job_at : JobAt
        Jobs at other heights and directions.
    planned_m : float or None
        The height the project gives [m].

    Returns
    -------
    PlanChoice
    """
    terrain = project.terrain
    cfg = terrain.config if terrain is not None else None
    h0 = float(start.plan.inputs.height_m)
    check = _Checks(project, cfg) if cfg is not None else None
    large = start.layout is not None and start.layout.n_photos > LARGE_PLAN_PHOTOS
    cands = _candidates(project, start, job_at, h0, cfg, large)
    done = _Compared(light=large)
    for cand in cands:
        done.add(_plan(project, check, cand, h0, job_at))
    if cfg is not None and cfg.dem is not None and not large:
        relief = _relief_direction(done, start, cfg)
        if relief is not None:
            for mode in _modes(cfg):
                done.add(_plan(project, check, Candidate(mode, "relief", relief), h0, job_at))
    pick = done.best
    assert pick is not None
    estimates = _estimates(project, cfg, start, job_at, h0, done, cands[0])
    alts = tuple(replace(a, recommended=a is pick.alternative) for a in done.alts) + estimates
    rechecked = pick.settled is None and pick.candidate.mode is not None and check is not None
    if rechecked:  # a large block: its chosen plan checked again, with the MTF figures
        assert check is not None
        pick = replace(pick, settled=_rechecked(pick, check, job_at))
    job, res, lowered, warned = _outcome(pick, job_at, planned_m, figures=rechecked)
    choice = _choice_reason(pick.alternative, alts) if len(alts) > 1 else None
    warnings = warned + _choice_warnings(pick.alternative, alts, project)
    return PlanChoice(alts, job, res, float(job.plan.inputs.height_m), lowered, choice,
                      warnings)


def _rank(a: Alternative) -> tuple[bool, bool, tuple[float, float]]:
    """The order of the choice: the project's choices allow it, it meets every constraint,
    the least flying time, then the fewest photos."""
    return (not a.allowed, not a.feasible, a.cost)


class _Compared:
    """The plans laid out so far: every record, and the best one kept whole (its job and
    settled layout) — the others only as their records, so that a block does not hold a
    layout per plan; a large block (``light``) keeps not even the best one's checked
    layout (:func:`_rechecked` checks it again at the end). The ground of the first check:
    its DEM grid (the relief direction) and its lowest and highest ground (the estimates).
    """

    def __init__(self, light: bool = False) -> None:
        self.light = light
        self.alts: list[Alternative] = []
        self.best: _Planned | None = None
        self.ground: Any = None
        self.ground_range: tuple[float, float] | None = None

    def add(self, p: _Planned) -> None:
        self.alts.append(p.alternative)
        if self.ground_range is None and p.settled is not None:
            g = p.settled.first.ground
            self.ground_range = (float(g.low_m), float(g.high_m))
            self.ground = None if self.light else g
        if self.best is None or _rank(p.alternative) < _rank(self.best.alternative):
            self.best = replace(p, settled=None) if self.light else p


def _rechecked(pick: _Planned, check: _Checks, job_at: JobAt) -> Settled:
    """A large block's chosen plan checked again at its settled height (and, when it was
    lowered, at the start: what the height the project gave would miss)."""
    from .terrainplan import Settled

    mode = pick.candidate.mode
    assert mode is not None and pick.alternative.height_m is not None
    tried = pick.alternative.heights_tried
    job = job_at(pick.alternative.height_m, pick.candidate.direction_deg)
    res = check.full(job, mode)
    top = tried[0][0] if tried else pick.alternative.height_m
    first = res if top == pick.alternative.height_m else check.full(
        job_at(top, pick.candidate.direction_deg), mode)
    return Settled(job, res, first, tried)


# --- the candidates ----------------------------------------------------------------------

def _modes(cfg: TerrainConfig | None) -> tuple[str | None, ...]:
    """The altitude modes to lay out: none on flat ground; over a DEM all three; over a
    ground range only ``constant`` (the ground under each photo is unknown: ``strip``
    flies the same, ``follow`` is an estimate)."""
    if cfg is None:
        return (None,)
    if cfg.dem is None:
        return ("constant",)
    return ("constant", "strip", "follow")


def _project_direction(project: ProjectModel) -> float | None:
    """``[area] direction_deg`` when the project gives an angle [°], else None."""
    d = project.area.direction_deg
    return None if d is None or d == "auto" else float(d) % 180.0


def _candidates(project: ProjectModel, start: UavJob, job_at: JobAt, h0: float,
                cfg: TerrainConfig | None, large: bool) -> list[Candidate]:
    """Modes × directions, each direction once (within a degree), the project's own (or
    the least flight length) first; a large block (:data:`LARGE_PLAN_PHOTOS`) along that
    one only."""
    assert start.layout is not None
    area = start.layout.area
    dirs: list[tuple[str, float | str | None, float]] = []
    if not area.georeferenced:
        dirs.append(("block", None, start.layout.direction_deg))
    else:
        given = _project_direction(project)
        if given is not None:
            dirs.append(("project", given, given))
        if given is None or not large:
            auto = start if given is None else job_at(h0, "auto")
            assert auto.layout is not None
            dirs.append(("auto", "auto", auto.layout.direction_deg))
        axis = long_axis_deg(area.geometry) if not large else None
        if axis is not None:
            dirs.append(("long_axis", axis, axis))
    kept: list[tuple[str, float | str | None, float]] = []
    for kind, asked, deg in dirs:
        if not any(same_direction(deg, d) for _, _, d in kept):
            kept.append((kind, asked, deg))
    return [Candidate(mode, kind, asked) for kind, asked, _ in kept for mode in _modes(cfg)]


def _relief_direction(done: _Compared, start: UavJob, cfg: TerrainConfig) -> float | None:
    """Over a DEM, the direction whose strips span the least relief (strip mode's height
    estimate, :func:`scanplan.geo.terrain_choice.mode_heights`), when no direction laid out
    yet is within a degree of it."""
    from ..geo.terrain_choice import DIRECTIONS_DEG, mode_heights

    ground = done.ground
    lay = start.layout
    limit = start.plan.max_height_m
    if ground is None or lay is None or limit is None or ground.grid is None \
            or not lay.n_photos or not lay.area.georeferenced:
        return None
    est = mode_heights(ground.grid, lay.area.geometry, limit, lay.spacing_m,
                       lay.footprint_across_m, cfg.follow_tolerance_m, DIRECTIONS_DEG)
    best, _ = est.best_strip()
    if any(a.direction_deg is not None and same_direction(best, a.direction_deg)
           for a in done.alts):
        return None
    return float(best)


# --- laying a candidate out and costing it ------------------------------------------------

class _Checks:
    """The terrain checks of the plans compared: the ground under each layout read once
    (the modes of one layout share it), the photos' MTF figures left for the one chosen."""

    KEEP = 2
    """Layouts whose ground is kept (the modes of one layout are checked one after the
    other; a DEM grid per layout is large)."""

    def __init__(self, project: ProjectModel, cfg: TerrainConfig) -> None:
        self.project = project
        self.cfg = cfg
        self._ground: list[tuple[Any, Any]] = []  # (layout, its ground), the latest last

    def __call__(self, job: UavJob, mode: str) -> TerrainResult:
        from .terrainplan import ground_of, terrain_check

        assert job.layout is not None
        ground = next((g for lay, g in self._ground if lay is job.layout), None)
        if ground is None:
            ground = ground_of(self.project, self.cfg, job.layout)
            self._ground = [*self._ground[-(self.KEEP - 1):], (job.layout, ground)]
        return terrain_check(self.project, self.cfg, job, mode, ground=ground,
                             figures=False)

    def full(self, job: UavJob, mode: str) -> TerrainResult:
        """The check with every photo's MTF figures (the plan chosen)."""
        from .terrainplan import terrain_check

        return terrain_check(self.project, self.cfg, job, mode)


def _plan(project: ProjectModel, check: _Checks | None, cand: Candidate, h0: float,
          job_at: JobAt) -> _Planned:
    """The candidate laid out at the start height, over relief held to its fixed point,
    costed and checked against every constraint."""
    first = job_at(h0, cand.direction_deg)
    settled = None
    job = first
    res = None
    if check is not None and cand.mode is not None and first.layout is not None:
        from .terrainplan import settle

        mode = cand.mode
        settled = settle(lambda j: check(j, mode), first,
                         lambda h: job_at(h, cand.direction_deg))
        job, res = settled.job, settled.result
    why, notes = _verdict(project, job, res, cand.mode)
    alt = _alternative(cand, job, res, why, _allowed(project, cand.mode, cand.direction))
    tried = settled.tried if settled is not None else ()
    return _Planned(cand, job, settled, replace(alt, findings=notes, heights_tried=tried))


def _allowed(project: ProjectModel, mode: str | None, direction: str, parts: int = 1) -> bool:
    """Whether the project's choices allow a plan: its altitude mode (a split block flies
    each part at one altitude: allowed with ``constant``) and its direction."""
    t = project.terrain
    if t is not None and t.altitude_mode != AUTO_MODE:
        if (mode if parts == 1 else "constant") != t.altitude_mode:
            return False
    given = _project_direction(project)
    return given is None or direction == "project"


def _alternative(cand: Candidate, job: UavJob, res: TerrainResult | None,
                 why: tuple[Message, ...], allowed: bool, *, parts: int = 1,
                 estimate: bool = False, band: tuple[float, float] | None = None
                 ) -> Alternative:
    """The record of a laid-out job: its figures from the layout's flight figures (the
    sorties and flying time of :func:`uav_flight_figures`), its GSD at the heights flown."""
    plan = job.plan
    inp = plan.inputs
    lay = job.layout
    fig = uav_flight_figures(plan, lay) if lay is not None else {}
    if band is None and res is not None:  # over relief: the heights really flown
        from .terrainplan import flown_band_m

        band = flown_band_m(res, inp)
    if band is None:
        band = (plan.heights_m["min"], plan.heights_m["max"])
    gsd = [float(ground_pixel_m(inp.pixel_um, h, inp.focal_mm)) for h in band]
    return Alternative(
        mode=cand.mode, direction=cand.direction,
        direction_deg=lay.direction_deg if lay is not None else None, parts=parts,
        height_m=float(inp.height_m), n_photos=fig.get("photos"), n_strips=fig.get("strips"),
        n_sorties=fig.get("sorties"), flight_length_m=fig.get("flight_length_m"),
        flight_time_s=fig.get("flight_time_s"),
        data_volume_bytes=fig.get("data_volume_bytes"), gsd_min_m=gsd[0], gsd_max_m=gsd[1],
        binding=res.binding if res is not None else plan.binding, feasible=not why,
        rejected_because=why, estimate=estimate, allowed=allowed)


def _verdict(project: ProjectModel, job: UavJob, res: TerrainResult | None,
             mode: str | None) -> tuple[tuple[Message, ...], tuple[Message, ...]]:
    """What a laid-out plan misses — its layout cannot be flown, its worst photo misses a
    limit, an overlap falls short, the one-height rule fails — and what it holds only
    within the overlap allowance (:data:`OVERLAP_SLACK_PCT`)."""
    why: list[Message] = []
    notes: list[Message] = []
    lay = job.layout
    if lay is not None and not lay.feasible:
        why.append(Message("plan_choice.not_feasible", why=lay.reason or ""))
    if res is None:
        return tuple(why), ()
    h = res.height_m
    if res.max_height_m is not None and res.max_height_m < h - 1e-9:
        why.append(Message("plan_choice.limit", cid=res.binding or "",
                           max=max(res.max_height_m, 0.0)))
    short, within = overlap_findings(job.plan.inputs, res)
    why += short
    notes += within
    check, holds = block_rule(project, job.norm_set, terrain_ground_m(project, res), h, mode)
    if not holds and check is not None:
        why.append(Message("plan_choice.block", range=check.range_m, pct=check.range_pct,
                           limit=check.limit_pct, n=check.blocks))
    return tuple(why), tuple(notes)


def overlap_findings(inp: Any, res: TerrainResult
                     ) -> tuple[list[Message], list[Message]]:
    """The overlaps of a plan over relief against the planned ones: (those short by more
    than :data:`OVERLAP_SLACK_PCT`, those short within it), as the terrain check's overlap
    warnings count them (by more than 0.05 %)."""
    out: tuple[list[Message], list[Message]] = ([], [])
    for kind, worst, planned in (("forward", res.min_forward_overlap_pct,
                                  inp.forward_overlap_pct),
                                 ("side", res.min_side_overlap_pct, inp.side_overlap_pct)):
        if not (math.isfinite(worst) and worst < planned - 0.05):
            continue
        short = Message(f"plan_choice.overlap.{kind}", value=worst, planned=planned)
        if worst < planned - OVERLAP_SLACK_PCT:
            out[0].append(short)
        else:
            out[1].append(Message("plan_choice.within", what=short, slack=OVERLAP_SLACK_PCT))
    return out


# --- estimates: what cannot be laid out here ------------------------------------------------

def _estimates(project: ProjectModel, cfg: TerrainConfig | None, start: UavJob,
               job_at: JobAt, h0: float, done: _Compared, own: Candidate
               ) -> tuple[Alternative, ...]:
    """Over a ground range, following the terrain; where the one-height rule fails for
    every plan at one altitude, the block split into parts by ground height: costed from
    the layout at the height each would allow along the first direction compared (``own``),
    not checked photo by photo."""
    limit = start.plan.max_height_m
    if cfg is None or limit is None or start.layout is None:
        return ()
    out: list[Alternative] = []
    direction = own.direction_deg
    ground = cfg.ground_range_m if cfg.dem is None else done.ground_range
    if cfg.dem is None:
        h = recommended_height_m(min(limit - cfg.follow_tolerance_m, h0))
        if h is not None:
            job = job_at(h, direction)
            band = (h * (1.0 - job.plan.inputs.height_tolerance_down_pct / 100.0),
                    (h + cfg.follow_tolerance_m)
                    * (1.0 + job.plan.inputs.height_tolerance_up_pct / 100.0))
            out.append(_alternative(
                Candidate("follow", own.direction, direction), job, None,
                (Message("plan_choice.needs_dem.follow"),),
                _allowed(project, "follow", own.direction), estimate=True, band=band))
    block_fails = any(any(m.code == "plan_choice.block" for m in a.rejected_because)
                      for a in done.alts)
    if block_fails and ground is not None:
        split = _split(project, start, ground, limit, h0)
        if split is not None:
            n, h, band_m = split
            job = job_at(h, direction)
            inp = job.plan.inputs
            flown = (h * (1.0 - inp.height_tolerance_down_pct / 100.0),
                     (h + band_m) * (1.0 + inp.height_tolerance_up_pct / 100.0))
            out.append(_alternative(
                Candidate("constant", own.direction, direction), job, None,
                (Message("plan_choice.needs_parts", n=n),),
                _allowed(project, "constant", own.direction, parts=n), parts=n,
                estimate=True, band=flown))
    return tuple(out)


def _split(project: ProjectModel, start: UavJob, ground: tuple[float, float], limit: float,
           h0: float) -> tuple[int, float, float] | None:
    """The fewest parts of equal ground-height bands, each flown at one altitude over its
    highest ground, that meet the one-height rule at the height each allows: (parts, that
    height [m], the band [m]); None when no split up to :data:`MAX_PARTS` does."""
    lo, hi = (float(x) for x in ground)
    for n in range(2, MAX_PARTS + 1):
        band = (hi - lo) / n
        h = recommended_height_m(min(limit - band, h0))
        if h is None:
            return None
        _, holds = block_rule(project, start.norm_set, [0.0, band], h, "constant")
        if holds:
            return n, h, band
    return None


# --- the choice -----------------------------------------------------------------------------

def _outcome(pick: _Planned, job_at: JobAt, planned_m: float | None, figures: bool = False
             ) -> tuple[UavJob, TerrainResult | None, Message | None, tuple[PlanWarning, ...]]:
    """The recommended plan as the specification carries it: over relief its terrain
    result (with every photo's MTF figures, unless ``figures`` says it has them), the
    reason it was lowered and its findings, and its figures at the heights really flown
    (:func:`scanplan.rules.uav.plan_uav`'s ``flown_band_m``)."""
    if pick.settled is None or pick.candidate.mode is None:
        return pick.job, None, None, ()
    from .terraincheck import with_photo_figures
    from .terrainplan import flown_band_m, terrain_outcome

    settled = pick.settled
    if not figures:  # checked without them
        settled = replace(settled, result=with_photo_figures(settled.result,
                                                             settled.job.plan.inputs))
    res, lowered, warned = terrain_outcome(settled, pick.candidate.mode, planned_m)
    job = pick.job
    band = flown_band_m(res, job.plan.inputs)
    if band is not None:  # the same layout, its figures at the heights really flown
        job = job_at(float(job.plan.inputs.height_m), pick.candidate.direction_deg, band,
                     job.layout)
    return replace(job, layout=res.layout), res, lowered, warned


_MODE_WORDS = {None: "plan_choice.mode.flat", "constant": "plan_choice.mode.constant",
               "strip": "plan_choice.mode.strip", "follow": "plan_choice.mode.follow"}


def describe(alt: Alternative) -> Message:
    """The plan in a few words: how it is flown, its lines and height."""
    mode = (Message("plan_choice.mode.parts", n=alt.parts) if alt.parts > 1
            else Message(_MODE_WORDS[alt.mode]))
    return Message("plan_choice.what", mode=mode, direction=alt.direction_deg or 0.0,
                   height=alt.height_m or 0.0)


def _figures(alt: Alternative) -> Message:
    return Message("plan_choice.figures", photos=alt.n_photos or 0,
                   time=(alt.flight_time_s or 0.0) / 60.0, sorties=alt.n_sorties or 0)


def _choice_reason(chosen: Alternative, alts: tuple[Alternative, ...]) -> Message:
    """Why this plan: of how many, and on what ground."""
    n = len(alts)
    if chosen.feasible and all(a.allowed for a in alts if not a.estimate):
        code = "plan_choice.chosen"
    elif chosen.feasible:
        code = "plan_choice.chosen_allowed"
    else:
        code = "plan_choice.chosen_none"
    return Message(code, n=n, what=describe(chosen), figures=_figures(chosen))


def _choice_warnings(chosen: Alternative, alts: tuple[Alternative, ...],
                     project: ProjectModel) -> tuple[PlanWarning, ...]:
    """A choice of the project that costs far more than the best plan meeting every
    constraint; a plan that would meet it with what the project does not give."""
    out: list[PlanWarning] = []
    best = min((a for a in alts if a.feasible and not a.estimate), key=lambda a: a.cost,
               default=None)
    if best is not None and best is not chosen and _extra(chosen, best) > PINNED_EXTRA:
        out.append(PlanWarning("plan_choice_costs", Message(
            "plan_choice_costs", what=describe(chosen), figures=_figures(chosen),
            keys=_pinned_keys(project), better=describe(best), better_figures=_figures(best),
            pct=_saving(chosen, best) * 100.0)))
    if best is None and not chosen.feasible:  # nothing laid out meets every constraint
        hope = min((a for a in alts if a.estimate and len(a.rejected_because) == 1
                    and a.cost < chosen.cost), key=lambda a: a.cost, default=None)
        if hope is not None:
            out.append(PlanWarning("plan_choice_needs", Message(
                "plan_choice_needs", better=describe(hope), figures=_figures(hope),
                pct=_saving(chosen, hope) * 100.0, needs=hope.rejected_because[0])))
    return tuple(out)


def _extra(a: Alternative, b: Alternative) -> float:
    """How much more ``a`` costs than ``b`` (flying time, else photos) [share]."""
    i = 0 if math.isfinite(a.cost[0]) and math.isfinite(b.cost[0]) and b.cost[0] > 0 else 1
    return a.cost[i] / b.cost[i] - 1.0 if b.cost[i] > 0 else 0.0


def _saving(a: Alternative, b: Alternative) -> float:
    """The share of ``a``'s cost that ``b`` saves [share]."""
    i = 0 if math.isfinite(a.cost[0]) and math.isfinite(b.cost[0]) and a.cost[0] > 0 else 1
    return 1.0 - b.cost[i] / a.cost[i] if a.cost[i] > 0 else 0.0


def _pinned_keys(project: ProjectModel) -> str:
    """The keys by which the project chose (for the warning's remedy)."""
    keys = []
    if project.terrain is not None and project.terrain.altitude_mode != AUTO_MODE:
        keys.append("[terrain] altitude_mode")
    if _project_direction(project) is not None:
        keys.append("[area] direction_deg")
    return ", ".join(keys)


def alternatives_dicts(alts: tuple[Alternative, ...]) -> list[dict[str, Any]]:
    """The plans compared as JSON-ready records (``plan --json``
    ``specification.uav.layout.alternatives``)."""
    return [{"altitude_mode": a.mode, "direction": a.direction,
             "direction_deg": a.direction_deg, "parts": a.parts, "height_m": a.height_m,
             "n_photos": a.n_photos, "n_strips": a.n_strips, "n_sorties": a.n_sorties,
             "flight_length_m": a.flight_length_m, "flight_time_s": a.flight_time_s,
             "data_volume_bytes": a.data_volume_bytes, "gsd_min_m": a.gsd_min_m,
             "gsd_max_m": a.gsd_max_m, "binding": a.binding, "feasible": a.feasible,
             "rejected_because": [{"code": m.code, "message": str(m),
                                   "params": params_json(m.params)}
                                  for m in a.rejected_because],
             "findings": [str(m) for m in a.findings],
             "heights_tried_m": [[h, ok] for h, ok in a.heights_tried], "estimate": a.estimate,
             "allowed": a.allowed, "recommended": a.recommended} for a in alts]
