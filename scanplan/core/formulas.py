"""The published formulas, one vectorised function each.

Sources
-------
- GKINP (GNTA)-02-036-02, *Instruction for photogrammetric works when producing digital
  topographic maps and plans* (2002) — the scan-pixel formulas, quoted in seed 001.
- Seed 001: A. Miheeva, A. Ilushenko, "Resolution calculation during scanning for
  high-grade interpretation of images", Vestnik of Polotsk State University, ser. F, 2015
  — eqs. 1–16: the corrected P_R coefficient and the recognition model.
- K. Kraus, *Photogrammetry: Geometry from Images and Laser Scans*, 2nd ed., Berlin: de
  Gruyter, 2007 — accuracy of the stereo normal case, σ_Z = (H/B)·(H/c)·σ_px
  (:mod:`scanplan.core.stereo`).
- T. Luhmann, S. Robson, S. Kyle, J. Boehm, *Close-Range Photogrammetry and 3D Imaging*,
  2nd ed., Berlin: de Gruyter, 2014 — the same normal-case relation, σ_Z = q·m·σ_px' with
  q = h/b and m = h/c, and the precision of image matching.

Every function is pure numpy: it broadcasts over any array inputs and does no I/O and no
validation (the rules engine in :mod:`scanplan.rules.film` validates once, with messages that
name the field). Normative numbers (V_s, k, 70 µm, k_R, P, shape coefficients) are
arguments: they come from a norm set, never from here.

Conventions: scales are denominators (map 1:Mk, photo 1:Mc); lengths on the photo are in
mm unless the name says ``_um``; lengths on the ground are in mm where the paper uses mm
(A, L) and in m where the name says ``_m``; resolving power in line pairs per mm.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import pick_method

__all__ = [
    "HEIGHT_PIXEL_METHODS",
    "height_pixel_instruction_um",
    "height_pixel_parallax_um",
    "height_pixel_um",
    "interpretation_pixel_um",
    "photo_base_mm",
    "photoplan_pixel_um",
    "planimetric_pixel_um",
    "probability_root",
    "recognisable_size_mm",
    "recognition_probability",
    "required_resolving_power_lpmm",
    "resolution_on_ground_mm",
    "resolving_power_pixel_um",
    "scanned_frame_bytes",
    "transfer_size_mm",
]

FloatArray = NDArray[np.float64]
Rounding = Literal["exact", "paper"]

_UM_PER_MM = 1000.0
_MM_PER_M = 1000.0


def _f(x: ArrayLike) -> FloatArray:
    return np.asarray(x, dtype=np.float64)


# ---------------------------------------------------------------------------------------
# §1 The Instruction's scan-pixel formulas (seed 001, eqs. 1–6)
# ---------------------------------------------------------------------------------------


def photo_base_mm(frame_along_mm: ArrayLike, forward_overlap_pct: ArrayLike) -> FloatArray:
    """Photo base on the image, b = l_y·(1 − p/100).

    Parameters
    ----------
    frame_along_mm : array_like
        Frame side along the flight line, l_y [mm].
    forward_overlap_pct : array_like
        Forward overlap p [%] (60 % standard).

    Returns
    -------
    ndarray
        Base b [mm on the image]; 92 mm for a 23 cm frame at 60 %.

    Notes
    -----
    The Instruction's b in seed 001, eq. 2.

    Examples
    --------
    >>> float(photo_base_mm(230.0, 60.0))
    92.0
    """
    return _f(frame_along_mm) * (1.0 - _f(forward_overlap_pct) / 100.0)


def planimetric_pixel_um(
    map_scale: ArrayLike,
    photo_scale: ArrayLike,
    *,
    planimetric_accuracy_mm: ArrayLike,
    processing_loss_k: ArrayLike,
) -> FloatArray:
    """Scan pixel that keeps planimetric accuracy, P_S = V_s·Mk / (k·Mc).

    Parameters
    ----------
    map_scale : array_like
        Map scale denominator Mk [-].
    photo_scale : array_like
        Photo scale denominator Mc [-].
    planimetric_accuracy_mm : array_like
        V_s, required planimetric accuracy on the map [mm] (norm: 0.2 mm).
    processing_loss_k : array_like
        k, loss of accuracy in processing [-] (norm: 2).

    Returns
    -------
    ndarray
        P_S [µm on the photo].

    Notes
    -----
    GKINP (GNTA)-02-036-02; seed 001, eq. 1.

    Examples
    --------
    >>> float(planimetric_pixel_um(2000, 10000, planimetric_accuracy_mm=0.2,
    ...                            processing_loss_k=2.0))
    20.0
    """
    return (
        _f(planimetric_accuracy_mm) * _f(map_scale) / (_f(processing_loss_k) * _f(photo_scale))
    ) * _UM_PER_MM


def height_pixel_instruction_um(
    relief_interval_m: ArrayLike,
    photo_scale: ArrayLike,
    focal_mm: ArrayLike,
    base_mm: ArrayLike,
    *,
    height_accuracy_fraction: ArrayLike,
    processing_loss_k: ArrayLike,
) -> FloatArray:
    """Scan pixel that keeps height accuracy, Instruction form P_Z = V_z·f / (k·Mc·b).

    Parameters
    ----------
    relief_interval_m : array_like
        Relief (contour) interval h_c [m].
    photo_scale : array_like
        Photo scale denominator Mc [-].
    focal_mm : array_like
        Focal length f [mm].
    base_mm : array_like
        Photo base on the image b [mm] (:func:`photo_base_mm`).
    height_accuracy_fraction : array_like
        V_z / h_c [-] (norm: 0.2).
    processing_loss_k : array_like
        k [-] (norm: 2).

    Returns
    -------
    ndarray
        P_Z [µm on the photo].

    Notes
    -----
    GKINP (GNTA)-02-036-02 as printed; seed 001, eq. 2 and all its tables. V_z is taken
    on the ground in mm. Parallax theory gives the reciprocal ratio b/f
    (:func:`height_pixel_parallax_um`); the printed form lets a *larger* overlap (smaller
    b) allow a *coarser* pixel, which is why scanplan warns when the overlap is not the
    Instruction's 60 %.

    Examples
    --------
    >>> round(float(height_pixel_instruction_um(
    ...     1.0, 10000, 152.0, 92.0, height_accuracy_fraction=0.2, processing_loss_k=2.0)), 2)
    16.52
    """
    vz_mm = _f(height_accuracy_fraction) * _f(relief_interval_m) * _MM_PER_M
    return (
        vz_mm * _f(focal_mm) / (_f(processing_loss_k) * _f(photo_scale) * _f(base_mm))
    ) * _UM_PER_MM


def height_pixel_parallax_um(
    relief_interval_m: ArrayLike,
    photo_scale: ArrayLike,
    focal_mm: ArrayLike,
    base_mm: ArrayLike,
    *,
    height_accuracy_fraction: ArrayLike,
    processing_loss_k: ArrayLike,
) -> FloatArray:
    """Scan pixel that keeps height accuracy, parallax form P_Z = V_z·b / (k·Mc·f).

    Parameters
    ----------
    relief_interval_m, photo_scale, focal_mm, base_mm, height_accuracy_fraction, processing_loss_k
        As :func:`height_pixel_instruction_um`.

    Returns
    -------
    ndarray
        P_Z [µm on the photo].

    Notes
    -----
    From dZ = (H/b)·dp with H = f·Mc: a parallax error dp = k·P gives a height error
    V_z when P = V_z·b/(k·Mc·f). Miheeva & Medvedev (Vestnik PSU ser. F, 2010, no. 12,
    pp. 103–108) call the printed Instruction form (seed 001, eq. 2) an error.

    Examples
    --------
    >>> round(float(height_pixel_parallax_um(
    ...     1.0, 10000, 152.0, 92.0, height_accuracy_fraction=0.2, processing_loss_k=2.0)), 2)
    6.05
    """
    vz_mm = _f(height_accuracy_fraction) * _f(relief_interval_m) * _MM_PER_M
    return (
        vz_mm * _f(base_mm) / (_f(processing_loss_k) * _f(photo_scale) * _f(focal_mm))
    ) * _UM_PER_MM


HEIGHT_PIXEL_METHODS = {
    "instruction": height_pixel_instruction_um,
    "parallax": height_pixel_parallax_um,
}
"""Height-constraint forms by name (a norm-set choice)."""


def height_pixel_um(
    relief_interval_m: ArrayLike,
    photo_scale: ArrayLike,
    focal_mm: ArrayLike,
    base_mm: ArrayLike,
    *,
    height_accuracy_fraction: ArrayLike,
    processing_loss_k: ArrayLike,
    method: Literal["instruction", "parallax"] = "instruction",
) -> FloatArray:
    """P_Z by the named form (``"instruction"`` or ``"parallax"``).

    Parameters
    ----------
    relief_interval_m, photo_scale, focal_mm, base_mm, height_accuracy_fraction, processing_loss_k
        As :func:`height_pixel_instruction_um`.
    method : {"instruction", "parallax"}
        Which form; see :data:`HEIGHT_PIXEL_METHODS`.

    Returns
    -------
    ndarray
        P_Z [µm on the photo].

    Raises
    ------
    ValueError
        For an unknown method.

    Examples
    --------
    >>> round(float(height_pixel_um(1.0, 10000, 152.0, 92.0, height_accuracy_fraction=0.2,
    ...                                processing_loss_k=2.0, method="parallax")), 2)
    6.05
    """
    fn = pick_method(HEIGHT_PIXEL_METHODS, method, "height formula")
    return fn(
        relief_interval_m,
        photo_scale,
        focal_mm,
        base_mm,
        height_accuracy_fraction=height_accuracy_fraction,
        processing_loss_k=processing_loss_k,
    )


def photoplan_pixel_um(
    map_scale: ArrayLike, photo_scale: ArrayLike, *, photoplan_resolution_mm: ArrayLike
) -> FloatArray:
    """Scan pixel for a graphic photo-plan, P_P = 0.070·Mk / Mc.

    Parameters
    ----------
    map_scale, photo_scale : array_like
        Mk and Mc [-].
    photoplan_resolution_mm : array_like
        Resolution of a graphic photo-plan [mm on the plan] (norm: 0.070 mm).

    Returns
    -------
    ndarray
        P_P [µm on the photo].

    Notes
    -----
    GKINP (GNTA)-02-036-02; seed 001, eq. 3.

    Examples
    --------
    >>> round(float(photoplan_pixel_um(2000, 10000, photoplan_resolution_mm=0.07)), 2)
    14.0
    """
    return _f(photoplan_resolution_mm) * _f(map_scale) / _f(photo_scale) * _UM_PER_MM


def resolving_power_pixel_um(
    resolving_power_lpmm: ArrayLike, *, pr_coefficient: ArrayLike
) -> FloatArray:
    """Scan pixel that preserves the photo's resolving power, P_R = k_R / R.

    Parameters
    ----------
    resolving_power_lpmm : array_like
        Resolving power of the photo R [lines/mm].
    pr_coefficient : array_like
        k_R [-]. The Instruction prints 0.4 (seed 001, eq. 4); the corrected value is 0.5
        (seed 001, eq. 5 and its ref. [2]).

    Returns
    -------
    ndarray
        P_R [µm on the photo]: 12.5 µm for R = 40 with 0.5 (10 µm with 0.4).

    Notes
    -----
    Seed 001, eqs. 4–6: a pixel P keeps 1/(2P) lines/mm, so 12.5 µm keeps 40 lines/mm
    and 0.5 is the coefficient that preserves R.

    Examples
    --------
    >>> round(float(resolving_power_pixel_um(40.0, pr_coefficient=0.5)), 2)
    12.5
    """
    return _f(pr_coefficient) / _f(resolving_power_lpmm) * _UM_PER_MM


def scanned_frame_bytes(
    frame_width_mm: ArrayLike,
    frame_height_mm: ArrayLike,
    pixel_um: ArrayLike,
    *,
    bands: ArrayLike = 1,
    bits_per_band: ArrayLike = 8,
) -> FloatArray:
    """Uncompressed size of one scanned frame: pixels × bands × bit depth.

    Parameters
    ----------
    frame_width_mm, frame_height_mm : array_like
        Scanned frame size [mm].
    pixel_um : array_like
        Scan pixel [µm].
    bands : array_like
        1 for panchromatic film, 3 for colour.
    bits_per_band : array_like
        Bit depth per band (8 or 16).

    Returns
    -------
    ndarray
        Bytes (the pixel count per side is rounded up).

    Notes
    -----
    Seed 001's cost argument (conclusion 3): volume ∝ 1/pixel², so the 10–12.5 µm that P_R
    demands costs (P_other/P_R)² times the data of the pixel the map actually needs.

    Examples
    --------
    >>> int(scanned_frame_bytes(230.0, 230.0, 14.0))
    269912041
    """
    px = _f(pixel_um) / _UM_PER_MM
    n_w = np.ceil(_f(frame_width_mm) / px)
    n_h = np.ceil(_f(frame_height_mm) / px)
    return n_w * n_h * _f(bands) * _f(bits_per_band) / 8.0


# ---------------------------------------------------------------------------------------
# §2 The recognition model (seed 001, eqs. 7–16)
# ---------------------------------------------------------------------------------------


def probability_root(probability: ArrayLike, rounding: Rounding = "exact") -> FloatArray:
    """sqrt(−ln P), the recognition model's link between A/L and P.

    Parameters
    ----------
    probability : array_like
        Recognition probability P in (0, 1).
    rounding : {"exact", "paper"}
        ``"exact"`` computes sqrt(−ln P) (0.5364 for P = 0.75). ``"paper"`` reproduces
        seed 001's arithmetic: −ln P truncated to two decimals (0.28 for 0.75), then the
        root rounded to two decimals (0.53), which gives its constant 1.8302 = 0.97/0.53.

    Returns
    -------
    ndarray
        sqrt(−ln P) [-].

    Notes
    -----
    Seed 001, eqs. 9–10. The paper's rounding makes its L and P_D about 1.2 % smaller
    than exact; scanplan computes exactly by default (a documented deviation).

    Examples
    --------
    >>> round(float(probability_root(0.75)), 4), round(float(probability_root(0.75, "paper")), 4)
    (0.5364, 0.53)
    """
    neg_ln = -np.log(_f(probability))
    if rounding == "exact":
        return np.sqrt(neg_ln)
    if rounding == "paper":
        return np.round(np.sqrt(np.floor(neg_ln * 100.0 + 1e-9) / 100.0), 2)
    raise ValueError(f"rounding must be 'exact' or 'paper' (got {rounding!r})")


def resolution_on_ground_mm(
    photo_scale: ArrayLike, resolving_power_lpmm: ArrayLike
) -> FloatArray:
    """Resolution of the photo on the ground, A = Mc / (2R).

    Parameters
    ----------
    photo_scale : array_like
        Mc [-].
    resolving_power_lpmm : array_like
        R [lines/mm].

    Returns
    -------
    ndarray
        A, the smallest object still imaged separately [mm on the ground].

    Notes
    -----
    Seed 001, eq. 8, Table 4 (125 mm at 1:10000 and R = 40). For a digital camera the
    same quantity is the MTF ground resolution L = H/(2Rf) with Mc = H/f.

    Examples
    --------
    >>> float(resolution_on_ground_mm(10000, 40.0))
    125.0
    """
    return _f(photo_scale) / (2.0 * _f(resolving_power_lpmm))


def recognition_probability(
    object_size_mm: ArrayLike, resolution_mm: ArrayLike, shape_coefficient: ArrayLike
) -> FloatArray:
    """Probability of recognising a simple object, P = exp(−(B·A/L)²).

    Parameters
    ----------
    object_size_mm : array_like
        L, size of the object (diameter, diagonal, length) [mm on the ground].
    resolution_mm : array_like
        A, resolution on the ground [mm] (:func:`resolution_on_ground_mm`).
    shape_coefficient : array_like
        B, shape recognition coefficient [-] (norm table: circle 0.97 … wall 2.78).

    Returns
    -------
    ndarray
        P in [0, 1].

    Notes
    -----
    Seed 001, eqs. 7 and 9.

    Examples
    --------
    >>> round(float(recognition_probability(228.8, 125.0, 0.97)), 3)
    0.755
    """
    ratio = _f(shape_coefficient) * _f(resolution_mm) / _f(object_size_mm)
    return np.exp(-(ratio * ratio))


def recognisable_size_mm(
    resolution_mm: ArrayLike,
    shape_coefficient: ArrayLike,
    probability: ArrayLike,
    *,
    rounding: Rounding = "exact",
) -> FloatArray:
    """Size recognisable with probability P, L_P = B·A / sqrt(−ln P).

    Parameters
    ----------
    resolution_mm : array_like
        A [mm on the ground].
    shape_coefficient : array_like
        B [-].
    probability : array_like
        P in (0, 1).
    rounding : {"exact", "paper"}
        See :func:`probability_root`.

    Returns
    -------
    ndarray
        L_P [mm on the ground].

    Notes
    -----
    Seed 001, eqs. 10–11, Table 5 (paper rounding: L = 1.8302·A for a circle at 0.75).

    Examples
    --------
    >>> round(float(recognisable_size_mm(125.0, 0.97, 0.75, rounding="paper")), 1)
    228.8
    """
    return (
        _f(shape_coefficient) * _f(resolution_mm) / probability_root(probability, rounding)
    )


def transfer_size_mm(
    size_mm: ArrayLike, from_photo_scale: ArrayLike, to_photo_scale: ArrayLike
) -> FloatArray:
    """Recognisable size at another photo scale, L' = L·Mc'/Mc.

    Parameters
    ----------
    size_mm : array_like
        L at ``from_photo_scale`` [mm].
    from_photo_scale, to_photo_scale : array_like
        Mc and Mc' [-].

    Returns
    -------
    ndarray
        L' [mm].

    Notes
    -----
    Seed 001, eq. 12: 228.8 mm at 1:10000 → 114.4 mm at 1:5000.

    Examples
    --------
    >>> float(transfer_size_mm(228.8, 10000, 5000))
    114.4
    """
    return _f(size_mm) * _f(to_photo_scale) / _f(from_photo_scale)


def required_resolving_power_lpmm(
    object_size_mm: ArrayLike,
    photo_scale: ArrayLike,
    shape_coefficient: ArrayLike,
    probability: ArrayLike,
    *,
    rounding: Rounding = "exact",
) -> FloatArray:
    """Resolving power needed to recognise L with probability P, R = B·Mc / (2·L·sqrt(−ln P)).

    Parameters
    ----------
    object_size_mm : array_like
        L [mm on the ground].
    photo_scale : array_like
        Mc [-].
    shape_coefficient : array_like
        B [-].
    probability : array_like
        P in (0, 1).
    rounding : {"exact", "paper"}
        See :func:`probability_root`.

    Returns
    -------
    ndarray
        R_needed [lines/mm].

    Notes
    -----
    Seed 001, eqs. 13–15: R = Mc/(2A) with A = L·sqrt(−ln P)/B.

    Examples
    --------
    >>> round(float(required_resolving_power_lpmm(200.0, 10000, 0.97, 0.75)), 2)
    45.21
    """
    return (
        _f(shape_coefficient)
        * _f(photo_scale)
        / (2.0 * _f(object_size_mm) * probability_root(probability, rounding))
    )


def interpretation_pixel_um(
    object_size_mm: ArrayLike,
    photo_scale: ArrayLike,
    shape_coefficient: ArrayLike,
    probability: ArrayLike,
    *,
    pr_coefficient: ArrayLike,
    rounding: Rounding = "exact",
) -> FloatArray:
    """Interpretation scan pixel, P_D = k_R / R_needed = 2·k_R·L·sqrt(−ln P) / (B·Mc).

    Parameters
    ----------
    object_size_mm : array_like
        L, size of the object to recognise [mm on the ground].
    photo_scale : array_like
        Mc [-].
    shape_coefficient : array_like
        B [-].
    probability : array_like
        P in (0, 1).
    pr_coefficient : array_like
        k_R [-] (0.5 corrected).
    rounding : {"exact", "paper"}
        See :func:`probability_root`.

    Returns
    -------
    ndarray
        P_D [µm on the photo].

    Notes
    -----
    Seed 001, eq. 16: with k_R = 0.5 it is P_D = L·sqrt(−ln P)/(B·Mc), and with the
    paper's rounding and B = 0.97, P_D = L/(1.8302·Mc) (Tables 6–9). Writing it as
    k_R/R_needed keeps P_D < P_R equivalent to R_needed > R for any k_R.

    Examples
    --------
    >>> round(float(interpretation_pixel_um(200.0, 10000, 0.97, 0.75, pr_coefficient=0.5)), 2)
    11.06
    """
    return (
        2.0
        * _f(pr_coefficient)
        * _f(object_size_mm)
        * probability_root(probability, rounding)
        / (_f(shape_coefficient) * _f(photo_scale))
    ) * _UM_PER_MM
