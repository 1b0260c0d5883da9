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
    "normal_case_height_error_m",
    "stereo_base_fraction",
    "stereo_height_ground_limit_m",
    "strip_multi_ray_factor",
]

_OVERLAP_EPS = 1e-9


def stereo_base_fraction(
    forward_overlap_pct: ArrayLike, min_stereo_overlap_pct: ArrayLike
) -> FloatArray:
    """Widest stereo base with standard overlap, as a fraction of the along-track footprint.

    A block flown with forward overlap p has exposures every (1 − p)·footprint. The photos
    i and i + n overlap by 1 − n·(1 − p); the widest base whose pair still has the standard
    stereo overlap p_min is n = floor((1 − p_min)/(1 − p)) steps (at least one step):
    B / footprint = n·(1 − p).

    Parameters
    ----------
    forward_overlap_pct : array_like
        Forward overlap p flown [%], 0 ≤ p < 100.
    min_stereo_overlap_pct : array_like
        Standard stereo overlap p_min [%] (norm parameter ``standard_forward_overlap_pct``,
        60 % in GKINP (GNTA)-02-036-02).

    Returns
    -------
    ndarray
        B / footprint_along [-]: 0.4 for 60 %, 80 % and 90 % blocks (1, 2 and 4 steps),
        0.3 for 70 % and 85 % (1 and 2 steps).

    Notes
    -----
    An 80 % UAV block keeps every second photo as a 60 % pair, so its stereo base is the
    standard one; the single-step base (20 % of the footprint) halves B/H and doubles
    σ_Z, which is why the parallax form with the single-step base is so pessimistic.

    Examples
    --------
    >>> round(float(stereo_base_fraction(80.0, 60.0)), 4)
    0.4
    """
    step = 1.0 - _f(forward_overlap_pct) / 100.0
    room = 1.0 - _f(min_stereo_overlap_pct) / 100.0
    n = np.maximum(np.floor(room / step + _OVERLAP_EPS), 1.0)
    return n * step


def strip_multi_ray_factor(
    forward_overlap_pct: ArrayLike, min_stereo_overlap_pct: ArrayLike
) -> FloatArray:
    """σ_Z of a point intersected from every photo of its strip, over σ_Z of the widest pair.

    A ground point lies in at least m = floor(1/(1 − p)) photos of its strip, taken every
    s = (1 − p)·footprint. A least-squares intersection of the m rays (equal weights, image
    error σ_x per photo, σ_px = √2·σ_x for a parallax) gives
    σ_Z = σ_x·H²/(c·s·sqrt(m(m² − 1)/12)); the widest standard pair (n steps, see
    :func:`stereo_base_fraction`) gives σ_Z = √2·σ_x·H²/(c·n·s). Their ratio is

        f = n·sqrt(6 / (m·(m² − 1)))   (f = 1 for m = 2 or 3 with n = 1 or 2).

    Parameters
    ----------
    forward_overlap_pct, min_stereo_overlap_pct : array_like
        As :func:`stereo_base_fraction` [%].

    Returns
    -------
    ndarray
        f ≤ 1 [-]: 0.447 for an 80 % block (m = 5, n = 2), 1 for 60 %.

    Notes
    -----
    Derived here from the collinearity equations of the normal case (Kraus 2007; Luhmann et
    al. 2014: the precision of a multi-image intersection grows with the square root of the
    sum of squared base components). It assumes independent, equal image errors, ignores
    the neighbouring strips (a conservative omission) and ignores the errors of the
    orientation and of the ground control, which the check-point accuracy of real blocks
    contains: that is why the norm sets leave it off (``multi_ray = off``).

    Examples
    --------
    >>> round(float(strip_multi_ray_factor(80.0, 60.0)), 4)
    0.4472
    """
    step = 1.0 - _f(forward_overlap_pct) / 100.0
    m = np.maximum(np.floor(1.0 / step + _OVERLAP_EPS), 2.0)
    room = 1.0 - _f(min_stereo_overlap_pct) / 100.0
    n = np.maximum(np.floor(room / step + _OVERLAP_EPS), 1.0)
    return np.minimum(n * np.sqrt(6.0 / (m * (m * m - 1.0))), 1.0)


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
