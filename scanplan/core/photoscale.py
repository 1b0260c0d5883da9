"""The vertical photo: height above ground, focal length, photo scale and ground pixel.

One vectorised function per relation, so that the photo scale of a frame over its own
ground, the ground pixel of a photo at its own height and the height a limit allows are
computed in one place (the terrain checks evaluate them at every photo of a block).

Sources
-------
- spec/formulas.md §2 (seed 001, eq. 8 and its note "A = Mc/(2R) with Mc = H/f"): the photo
  scale of a vertical photo, Mc = H/f, H the height above the ground photographed.
- spec/formulas.md §3 (seed 000, "GSD"): the ground sample distance GSD = p·H/f; and its
  "Flight geometry": footprint = sensor side × H/f.
- spec/formulas.md §1 (seed 001, eqs. 4–6): P_R = k_R/R, the scan pixel that keeps the
  photo's resolving power R; read the other way, a scan pixel P keeps at most k_R/P.

Pure numpy like :mod:`scanplan.core.formulas`: no validation (the engines validate their
inputs once, naming the field), any array inputs broadcast. Conventions: photo scales are
denominators (1:Mc); focal lengths in mm; pixels in µm; heights and ground lengths in m.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "effective_resolving_power_lpmm",
    "footprint_side_m",
    "frame_side_on_ground_m",
    "ground_pixel_m",
    "height_at_photo_scale_m",
    "height_for_ground_pixel_m",
    "photo_scale_at_height",
    "scanned_ground_pixel_cm",
    "scanned_ground_pixel_m",
]

FloatArray = NDArray[np.float64]

_MM_PER_M = 1000.0
_UM_PER_MM = 1000.0
_UM_PER_M = 1e6
_UM_PER_CM = 1e4


def _f(x: ArrayLike) -> FloatArray:
    return np.asarray(x, dtype=np.float64)


def photo_scale_at_height(height_m: ArrayLike, focal_mm: ArrayLike) -> FloatArray:
    """Photo scale denominator of a vertical photo, Mc = H/f.

    Parameters
    ----------
    height_m : array_like
        Height above the ground photographed H [m].
    focal_mm : array_like
        Focal length f [mm].

    Returns
    -------
    numpy.ndarray
        Mc [-] (the photo scale is 1:Mc).

    Notes
    -----
    spec/formulas.md §2 (seed 001, eq. 8: "A = Mc/(2R) with Mc = H/f"). Over relief the
    height is the aircraft's altitude less the ground under the frame, so every frame has
    its own scale.

    Examples
    --------
    >>> float(photo_scale_at_height(1000.0, 100.0))
    10000.0
    """
    return _f(height_m) / (_f(focal_mm) / _MM_PER_M)


def height_at_photo_scale_m(photo_scale: ArrayLike, focal_mm: ArrayLike) -> FloatArray:
    """Height above ground of a vertical photo at photo scale 1:Mc, H = Mc·f.

    Parameters
    ----------
    photo_scale : array_like
        Photo scale denominator Mc [-].
    focal_mm : array_like
        Focal length f [mm].

    Returns
    -------
    numpy.ndarray
        H [m].

    Notes
    -----
    spec/formulas.md §2 (seed 001, eq. 8: Mc = H/f), solved for H.

    Examples
    --------
    >>> float(height_at_photo_scale_m(8000.0, 153.0))
    1224.0
    """
    return _f(photo_scale) * _f(focal_mm) / _MM_PER_M


def ground_pixel_m(pixel_um: ArrayLike, height_m: ArrayLike, focal_mm: ArrayLike) -> FloatArray:
    """Ground pixel (ground sample distance) of a photo at its height, GSD = p·H/f.

    Parameters
    ----------
    pixel_um : array_like
        Pixel pitch on the sensor (or scan pixel on the photo) p [µm].
    height_m : array_like
        Height above the ground H [m].
    focal_mm : array_like
        Focal length f [mm].

    Returns
    -------
    numpy.ndarray
        GSD [m].

    Notes
    -----
    spec/formulas.md §3 (seed 000, "GSD = p·H/f"). Unlike
    :func:`scanplan.core.flight.ground_sample_distance_m` it does not validate: the
    terrain checks evaluate it at every photo's height above its ground.

    Examples
    --------
    >>> round(float(ground_pixel_m(4.4, 100.0, 35.0)), 5)
    0.01257
    """
    return _f(pixel_um) / _UM_PER_MM * _f(height_m) / _f(focal_mm)


def footprint_side_m(side_mm: ArrayLike, height_m: ArrayLike, focal_mm: ArrayLike) -> FloatArray:
    """One side of a vertical photo's footprint on the ground, footprint = l·H/f.

    Parameters
    ----------
    side_mm : array_like
        The sensor's (or frame's) side l [mm].
    height_m : array_like
        Height above the ground H [m] (1 m gives the footprint per metre of height).
    focal_mm : array_like
        Focal length f [mm].

    Returns
    -------
    numpy.ndarray
        The footprint's side on the ground [m].

    Notes
    -----
    spec/formulas.md §3, "Flight geometry": footprint = sensor side × H/f. Unlike
    :func:`scanplan.core.flight.footprint_m` it does not validate: the terrain checks
    evaluate it at every photo's and every pair's height above its ground.

    Examples
    --------
    >>> round(float(footprint_side_m(24.0, 100.0, 35.0)), 3)
    68.571
    """
    return _f(side_mm) / _f(focal_mm) * _f(height_m)


def frame_side_on_ground_m(side_mm: ArrayLike, photo_scale: ArrayLike) -> FloatArray:
    """One side of a frame on the ground at photo scale 1:Mc, l·Mc.

    Parameters
    ----------
    side_mm : array_like
        The frame's side l [mm].
    photo_scale : array_like
        Photo scale denominator Mc [-].

    Returns
    -------
    numpy.ndarray
        The frame's side on the ground [m].

    Notes
    -----
    spec/formulas.md §3, "Flight geometry": footprint = sensor side × H/f, with H/f = Mc
    (§2, seed 001, eq. 8).

    Examples
    --------
    >>> float(frame_side_on_ground_m(230.0, 8000.0))
    1840.0
    """
    return _f(side_mm) * _f(photo_scale) / _MM_PER_M


def scanned_ground_pixel_m(pixel_um: ArrayLike, photo_scale: ArrayLike) -> FloatArray:
    """Ground pixel of a scanned photo, the scan pixel times the photo scale, P·Mc.

    Parameters
    ----------
    pixel_um : array_like
        Scan pixel on the photo P [µm].
    photo_scale : array_like
        Photo scale denominator Mc [-].

    Returns
    -------
    numpy.ndarray
        The scan pixel on the ground [m].

    Notes
    -----
    spec/formulas.md §3, GSD = p·H/f, with H/f = Mc (§2, seed 001, eq. 8): GSD = p·Mc.

    Examples
    --------
    >>> float(scanned_ground_pixel_m(20.0, 10000.0))
    0.2
    """
    return _f(pixel_um) * _f(photo_scale) / _UM_PER_M


def scanned_ground_pixel_cm(pixel_um: ArrayLike, photo_scale: ArrayLike) -> FloatArray:
    """Ground pixel of a scanned photo in centimetres, P·Mc (the photos table's ``gsd_cm``).

    Parameters
    ----------
    pixel_um : array_like
        Scan pixel on the photo P [µm].
    photo_scale : array_like
        Photo scale denominator Mc [-].

    Returns
    -------
    numpy.ndarray
        The scan pixel on the ground [cm].

    Notes
    -----
    spec/formulas.md §3, GSD = p·H/f, with H/f = Mc (§2, seed 001, eq. 8). The same relation
    as :func:`scanned_ground_pixel_m`, scaled once from µm to cm (not from m, which can
    differ in the last bit).

    Examples
    --------
    >>> float(scanned_ground_pixel_cm(7.0, 8000.0))
    5.6
    """
    return _f(pixel_um) * _f(photo_scale) / _UM_PER_CM


def height_for_ground_pixel_m(ground_pixel_m: ArrayLike, pixel_um: ArrayLike,
                              focal_mm: ArrayLike) -> FloatArray:
    """The height above ground at which a photo's ground pixel is ``ground_pixel_m``,
    H = GSD·f/p.

    Parameters
    ----------
    ground_pixel_m : array_like
        Ground pixel GSD [m].
    pixel_um : array_like
        Pixel pitch p [µm].
    focal_mm : array_like
        Focal length f [mm].

    Returns
    -------
    numpy.ndarray
        H [m].

    Notes
    -----
    spec/formulas.md §3 (seed 000, "GSD = p·H/f"), solved for H: the largest height at
    which a limit on the GSD holds.

    Examples
    --------
    >>> round(float(height_for_ground_pixel_m(0.02, 4.4, 35.0)), 3)
    159.091
    """
    return _f(ground_pixel_m) * _f(focal_mm) / (_f(pixel_um) / _UM_PER_MM)


def effective_resolving_power_lpmm(resolving_power_lpmm: ArrayLike, pixel_um: ArrayLike,
                                   pr_coefficient: ArrayLike) -> FloatArray:
    """Resolving power of a photo after scanning, R_eff = min(R, k_R/P).

    Parameters
    ----------
    resolving_power_lpmm : array_like
        Resolving power of the photo R [line pairs/mm].
    pixel_um : array_like
        Scan pixel P [µm].
    pr_coefficient : array_like
        Resolving-power coefficient k_R [-] (a norm, 0.5 by default).

    Returns
    -------
    numpy.ndarray
        R_eff [line pairs/mm]: the photo's own R, or what the scan pixel keeps when that
        is less.

    Notes
    -----
    spec/formulas.md §1, P_R = k_R/R (seed 001, eqs. 4–6): a pixel P keeps k_R/P.

    Examples
    --------
    >>> float(effective_resolving_power_lpmm(40.0, 20.0, 0.5))
    25.0
    """
    return np.minimum(_f(resolving_power_lpmm),
                      _f(pr_coefficient) / (_f(pixel_um) / _UM_PER_MM))
