"""Height accuracy of a digital (UAV) block: the stereo normal case, one vectorised
function each (split from :mod:`scanplan.core.formulas`, whose conventions it follows).

Sources
-------
- K. Kraus, *Photogrammetry: Geometry from Images and Laser Scans*, 2nd ed., Berlin: de
  Gruyter, 2007 — accuracy of the stereo normal case, σ_Z = (H/B)·(H/c)·σ_px.
- T. Luhmann, S. Robson, S. Kyle, J. Boehm, *Close-Range Photogrammetry and 3D Imaging*,
  2nd ed., Berlin: de Gruyter, 2014 — the same normal-case relation, σ_Z = q·m·σ_px' with
  q = h/b and m = h/c, and the precision of image matching.

Pure numpy, no validation (the rules engine validates); normative numbers (the standard
stereo overlap, σ_px) are arguments from the norm set.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .formulas import _UM_PER_MM, FloatArray, _f

__all__ = [
    "multi_ray_base_fraction",
    "normal_case_height_error_m",
    "stereo_base_fraction",
    "stereo_height_ground_limit_m",
    "strip_multi_ray_factor",
]

_OVERLAP_EPS = 1e-9


def stereo_base_fraction(
    forward_overlap_pct: ArrayLike, min_stereo_overlap_pct: ArrayLike
) -> FloatArray:
    """Base of the standard stereo pair, as a fraction of the along-track footprint.

    A block flown with forward overlap p ≥ p_min (the standard stereo overlap) is held to
    the precision of one stereo pair with exactly the standard overlap,
    B / footprint = 1 − p_min, a real (not a whole) multiple of the photo step
    (1 − p)·footprint. Below the standard overlap no pair has it; the block is held to the
    same share of the least-squares intersection of every ray of the strip
    (:func:`multi_ray_base_fraction`, B_eff) as at p_min:

        B / footprint = 1 − p_min                                  (p ≥ p_min),
        B / footprint = (1 − p_min) · B_eff(max(p, 50 %)) / B_eff(p_min)   (p < p_min).

    Continuous in p and never falling as p rises: B_eff never falls from 50 % on, and the
    pair is constant from p_min on, so a higher overlap never lowers the height that meets
    an accuracy.

    Parameters
    ----------
    forward_overlap_pct : array_like
        Forward overlap p [%], 0 ≤ p < 100: the overlap actually flown at the height
        checked (:func:`scanplan.core.flight.actual_overlap_pct` for a trigger distance
        fixed at the planned height).
    min_stereo_overlap_pct : array_like
        Standard stereo overlap p_min [%] (norm parameter ``standard_forward_overlap_pct``,
        60 % in GKINP (GNTA)-02-036-02).

    Returns
    -------
    ndarray
        B / footprint_along [-]: 0.4 for every block flown at 60 % or more with
        p_min = 60 %; 0.3897 at 50–55 %, rising to 0.4 at 60 %.

    Notes
    -----
    Why one standard pair, whatever the overlap above p_min: the least-squares
    intersection of every ray of the strip (:func:`multi_ray_base_fraction`) is at
    least as precise as this pair for every p ≥ 50 % (its effective base is 0.493 of
    the footprint at 50–55 %, 0.506 at 60 %, and never falls with p), so the pair is a
    conservative bound of the multi-view block, with no jump where the widest whole-step
    pair changes (the model before this one allowed 437 m at 80 % and 229 m at 79 % for
    the same camera).

    Why not the single step below p_min (the model before this one, B = 1 − p): it made
    the base fall from 0.45 at 55 % to 0.40 at 60 % — the height allowed fell by 11 %
    as the overlap rose, while the least-squares intersection of the same rays gains
    2.6 % (0.493 → 0.506). Scaling the pair with B_eff below p_min keeps the model's
    ratio to the multi-ray block, 0.4/0.506 = 0.79, the same at every overlap up to
    p_min, so it rises where the block's precision rises (docs/deviations.md).

    Examples
    --------
    >>> [round(float(x), 4) for x in stereo_base_fraction([50.0, 55.0, 58.0, 60.0, 80.0],
    ...                                                    60.0)]
    [0.3897, 0.3897, 0.3929, 0.4, 0.4]
    """
    p = _f(forward_overlap_pct)
    p_min = _f(min_stereo_overlap_pct)
    room = 1.0 - p_min / 100.0
    floor = 50.0  # below it some ground is seen by one photo only: no stereo there
    below = room * (multi_ray_base_fraction(np.maximum(p, floor))
                    / multi_ray_base_fraction(np.maximum(p_min, floor)))
    return np.where(p >= p_min, room, np.minimum(below, room))


def _dip_end(n: FloatArray) -> FloatArray:
    """Where the RMS multi-ray base stops falling above n whole rays: m = n + (4 − n)/9."""
    return n + np.maximum(4.0 - n, 0.0) / 9.0


def _ray_base(m: FloatArray, n: FloatArray) -> FloatArray:
    """B_eff / footprint for m exposures per footprint, n = ⌊m⌋ ≥ 2 (see
    :func:`multi_ray_base_fraction`)."""
    r = np.clip(m - n, 0.0, 1.0)
    s2 = 1.0 / (m * m)
    inv = (12.0 / s2) * ((1.0 - r) / (n * (n * n - 1.0)) + r / ((n + 1.0) * n * (n + 2.0)))
    return np.sqrt(2.0 / inv)


def multi_ray_base_fraction(forward_overlap_pct: ArrayLike) -> FloatArray:
    """Effective base of the least-squares intersection of every ray of a strip, as a
    fraction of the along-track footprint (RMS over the points of the strip).

    Exposures every s = footprint/m, m = 1/(1 − p) (a real number). A ground point is seen
    by n = ⌊m⌋ photos on a fraction 1 − r of the strip and by n + 1 on the rest, r = m − ⌊m⌋.
    The least-squares intersection of n rays equally spaced by s (equal, independent image
    errors σ_x per photo; parallax error σ_px = √2·σ_x) gives

        σ_Z = σ_x·H²/(c·sqrt(S_n)),   S_n = s²·n(n² − 1)/12,

    and a pair of base B gives σ_Z = σ_px·H²/(c·B). The RMS of σ_Z over the strip is that
    of a pair of effective base

        B_eff = sqrt(2 / ((1 − r)/S_n + r/S_{n+1})).

    It is continuous in p and equals the all-ray value at whole m (75 %, 80 %, 90 %:
    0.791, 0.894, 1.285 × footprint). Just above a whole m the spacing grows faster than
    the rays are added and B_eff dips (by ≤ 1.5 % for n = 2, ≤ 0.2 % for n = 3; none for
    n ≥ 4, where the dip condition 9r < 4 − n cannot hold): the function returns its lowest
    value at this or any higher overlap, B_eff(max(m, n + (4 − n)/9)), so that more overlap
    never lowers it: min(B_eff(max(m, n + (4 − n)/9)), B_eff at the end of the next
    dip). Below m = 2 (p < 50 %) some ground is seen by one photo only and the
    single step s is returned.

    Parameters
    ----------
    forward_overlap_pct : array_like
        Forward overlap p flown [%], 0 ≤ p < 100.

    Returns
    -------
    ndarray
        B_eff / footprint_along [-].

    Notes
    -----
    Derived from the collinearity equations of the normal case (Kraus 2007; Luhmann et
    al. 2014: the precision of a multi-image intersection grows with the spread of the
    projection centres); ``tests/test_height_accuracy.py`` checks it against an explicit
    least-squares adjustment averaged over point positions. It ignores the neighbouring
    strips (a conservative omission) and everything that is not image noise (orientation,
    ground control, calibration, the surface).

    Examples
    --------
    >>> [round(float(x), 4) for x in multi_ray_base_fraction([60.0, 75.0, 80.0])]
    [0.506, 0.7906, 0.8944]
    """
    step = 1.0 - _f(forward_overlap_pct) / 100.0
    m = 1.0 / step
    n = np.maximum(np.floor(m + _OVERLAP_EPS), 2.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        here = _ray_base(np.maximum(m, _dip_end(n)), n)
        after = _ray_base(_dip_end(n + 1.0), n + 1.0)  # the next dip's lowest value
        eff = np.minimum(here, after)
    return np.where(m < 2.0 - _OVERLAP_EPS, step, eff)


def strip_multi_ray_factor(
    forward_overlap_pct: ArrayLike, min_stereo_overlap_pct: ArrayLike
) -> FloatArray:
    """σ_Z of the strip's multi-ray intersection over σ_Z of the standard pair (≤ 1).

    f = min(1, :func:`stereo_base_fraction` / :func:`multi_ray_base_fraction`).

    Parameters
    ----------
    forward_overlap_pct, min_stereo_overlap_pct : array_like
        As :func:`stereo_base_fraction` [%].

    Returns
    -------
    ndarray
        f ≤ 1 [-]: 0.447 for an 80 % block, 0.79 for 60 %.

    Notes
    -----
    The norm sets leave it off (``multi_ray = off``): check-point accuracy of real blocks
    also contains orientation, control and calibration errors that more rays do not
    remove (docs/uav-models.md §9).

    Examples
    --------
    >>> round(float(strip_multi_ray_factor(80.0, 60.0)), 4)
    0.4472
    """
    return np.minimum(stereo_base_fraction(forward_overlap_pct, min_stereo_overlap_pct)
                      / multi_ray_base_fraction(forward_overlap_pct), 1.0)


def normal_case_height_error_m(
    height_m: ArrayLike,
    base_m: ArrayLike,
    focal_mm: ArrayLike,
    pixel_um: ArrayLike,
    image_error_px: ArrayLike,
    multi_ray_factor: ArrayLike = 1.0,
) -> FloatArray:
    """RMS height error of the stereo normal case, σ_Z = (H/B)·(H/c)·σ_px·f.

    Parameters
    ----------
    height_m : array_like
        Flight height above ground H [m].
    base_m : array_like
        Stereo base B on the ground [m] (the widest standard pair:
        :func:`stereo_base_fraction` × footprint along track).
    focal_mm : array_like
        Principal distance c [mm].
    pixel_um : array_like
        Pixel pitch [µm].
    image_error_px : array_like
        σ_px, RMS error of the measured x-parallax [pixels] (norm parameter
        ``image_measurement_px``).
    multi_ray_factor : array_like, optional
        f ≤ 1 for a multi-ray intersection (:func:`strip_multi_ray_factor`); 1 = one pair.

    Returns
    -------
    ndarray
        σ_Z [m], one standard deviation.

    Notes
    -----
    Kraus (2007), accuracy of the normal case: σ_Z = (Z/B)·(Z/c)·σ_px; Luhmann et al.
    (2014): σ_Z = q·m·σ_px' with q = h/b, m = h/c. With GSD = p·H/c it is
    σ_Z = GSD·σ_px·f / (B/H): monotone decreasing in B, increasing in H and in p.
    The Instruction's parallax form (Miheeva & Medvedev 2010) is the same relation with
    the single-step base and σ_px = k pixels.

    Examples
    --------
    >>> round(float(normal_case_height_error_m(100.0, 40.0, 35.0, 4.4, 0.5)), 4)
    0.0157
    """
    h = _f(height_m)
    gsd_m = _f(pixel_um) / _UM_PER_MM * h / _f(focal_mm)
    return (h / _f(base_m)) * gsd_m * _f(image_error_px) * _f(multi_ray_factor)


def stereo_height_ground_limit_m(
    height_accuracy_m: ArrayLike,
    base_to_height: ArrayLike,
    image_error_px: ArrayLike,
    multi_ray_factor: ArrayLike = 1.0,
) -> FloatArray:
    """Largest GSD whose normal-case height error meets the required accuracy.

    σ_Z = GSD·σ_px·f/(B/H) ≤ V_z  ⇔  GSD ≤ V_z·(B/H)/(σ_px·f).

    Parameters
    ----------
    height_accuracy_m : array_like
        Required RMS height error V_z [m] (the Instruction's 0.2·h_c, read as an RMS).
    base_to_height : array_like
        B/H of the widest standard pair [-] (independent of H for a given camera and
        overlap: :func:`stereo_base_fraction` × sensor side along / c).
    image_error_px, multi_ray_factor : array_like
        As :func:`normal_case_height_error_m`.

    Returns
    -------
    ndarray
        The GSD limit [m on the ground]; the height limit is GSD·c/p.

    Examples
    --------
    >>> round(float(stereo_height_ground_limit_m(0.1, 0.4, 0.5)), 4)
    0.08
    """
    return (_f(height_accuracy_m) * _f(base_to_height)
            / (_f(image_error_px) * _f(multi_ray_factor)))
