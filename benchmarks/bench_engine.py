"""Benchmark: the rules engine over 1,000,000 scenarios in one vectorised call.

Compares :func:`scanplan.rules.film.evaluate` (five constraints, binding, scan pixel) with a
bare numpy expression of the same five formulas and a plain ``min`` over them, both run
in this process on the same arrays. Target: engine / bare ≤ 3.

Run: ``python benchmarks/bench_engine.py [--n 1000000] [--repeat 7]``
"""

from __future__ import annotations

import argparse

import numpy as np
from _common import Result
from _timing import best_of

from scanplan.norms import load_norm_set
from scanplan.rules.film import evaluate

TARGET_RATIO = 3.0


def run(n: int = 1_000_000, repeat: int = 7, seed: int = 1) -> dict[str, float]:
    """Time both and return {'n', 'engine_s', 'bare_s', 'ratio', 'target'}."""
    rng = np.random.default_rng(seed)
    mk = rng.choice([500.0, 1000, 2000, 5000, 10000, 25000], n)
    mc = mk * rng.uniform(1.5, 10, n)
    h = rng.choice([0.25, 0.5, 1.0, 2.0, 5.0], n)
    f = rng.choice([100.0, 153.0, 210.0], n)
    ly = rng.choice([180.0, 230.0], n)
    p = rng.uniform(55, 80, n)
    r = rng.uniform(25, 60, n)
    L = rng.uniform(0.2, 2.2, n)
    b = rng.choice([0.97, 1.45, 1.72], n)
    rules = load_norm_set().rules()
    vs, frac, k = rules.planimetric_accuracy_mm, rules.height_accuracy_fraction, \
        rules.processing_loss_k
    pp, kr, prob = rules.photoplan_resolution_mm, rules.pr_coefficient, rules.probability

    def engine():
        return evaluate(rules, map_scale=mk, photo_scale=mc, relief_interval_m=h, focal_mm=f,
                        frame_along_mm=ly, forward_overlap_pct=p, resolving_power_lpmm=r,
                        object_size_m=L, shape_coefficient=b)

    def bare():
        ps = vs * mk / (k * mc) * 1000
        base = ly * (1 - p / 100)
        pz = frac * h * 1000 * f / (k * mc * base) * 1000
        ppx = pp * mk / mc * 1000
        pr = kr / r * 1000
        pd = 2 * kr * L * 1000 * np.sqrt(-np.log(prob)) / (b * mc) * 1000
        return np.minimum(np.minimum(np.minimum(ps, pz), np.minimum(ppx, pr)), pd)

    np.testing.assert_allclose(engine().scan_pixel_um, bare(), rtol=1e-12)
    engine_s = best_of(engine, repeat)
    bare_s = best_of(bare, repeat)
    return {"n": n, "engine_s": engine_s, "bare_s": bare_s, "ratio": engine_s / bare_s,
            "target": TARGET_RATIO}


def measure(quick: bool = False) -> list[Result]:
    """The runner's entry: the engine / bare-numpy ratio as one row.

    Parameters
    ----------
    quick : bool, optional
        Best of 3 instead of 7 (same 1,000,000 scenarios).

    Returns
    -------
    list of Result
        ``engine``: the ratio, target ≤ 3.
    """
    repeat = 3 if quick else 7
    res = run(1_000_000, repeat)
    return [Result(
        "engine", res["ratio"], "x", TARGET_RATIO, "<=",
        note=f"planner.evaluate over {res['n']:,} scenarios {res['engine_s'] * 1000:.1f} ms "
             f"/ a bare numpy expression of the same five formulas "
             f"{res['bare_s'] * 1000:.1f} ms (same process, best of {repeat})",
    )]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=7)
    a = ap.parse_args()
    res = run(a.n, a.repeat)
    verdict = "PASS" if res["ratio"] <= res["target"] else "FAIL"
    print(f"engine, {res['n']:,} scenarios: {res['engine_s'] * 1000:.1f} ms "
          f"(bare numpy {res['bare_s'] * 1000:.1f} ms) ratio {res['ratio']:.2f} "
          f"target ≤ {res['target']:g} {verdict}")


if __name__ == "__main__":
    main()
