"""UAV flight geometry and motion blur (spec formulas.md §3, seeds 000 and 002).

Pure, vectorised numpy: every function broadcasts over array inputs and does no I/O.
Lengths on the ground are in metres, on the sensor in millimetres (µm where a name
says ``_um``), times in seconds, speeds in m/s, overlaps in per cent.

Invalid physical input raises :class:`~scanplan.errors.FieldValueError` (a ValueError)
with a typed ``field``: the name
of the offending parameter, e.g. ``"pixel_um must be > 0 (got -1)"``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .checks import in_range, nonnegative, positive

__all__ = [
    "JPEG_COMPRESSION_RATIO",
    "HeightBand",
    "actual_overlap_pct",
    "data_volume_bytes",
    "flight_length_m",
    "flight_time_s",
    "footprint_m",
    "ground_sample_distance_m",
    "height_band",
    "jpeg_volume_bytes",
    "line_spacing_m",
    "max_exposure_for_blur_s",
    "max_speed_for_blur_ms",
    "max_speed_for_trigger_ms",
    "motion_blur_px",
    "photo_base_m",
    "photo_interval_s",
    "photos_per_strip",
    "strip_count",
    "trigger_interval_ok",
]

NDArrayFloat = npt.NDArray[np.float64]

#: Largest motion blur, in pixels, that planners accept without a warning.
MAX_BLUR_PX = 0.5


def _overlap(name: str, value: npt.ArrayLike) -> NDArrayFloat:
    return in_range(name, value, 0.0, 100.0, high_inclusive=False)


# ---------------------------------------------------------------------------------
# Ground sample distance, footprint, base, line spacing
# ---------------------------------------------------------------------------------
def ground_sample_distance_m(
    pixel_um: npt.ArrayLike, height_m: npt.ArrayLike, focal_mm: npt.ArrayLike
) -> NDArrayFloat:
    """Ground sample distance GSD = p·H/f.

    Parameters
    ----------
    pixel_um : array_like
        Pixel pitch p [µm].
    height_m : array_like
        Flight height above ground H [m].
    focal_mm : array_like
        Focal length f [mm].

    Returns
    -------
    numpy.ndarray
        GSD [m]: the projection of one pixel pitch on flat ground under a vertical photo.

    Notes
    -----
    Seed 000 (text before eq. 1, "GSD"); spec formulas.md §3. p·H/f with p in mm
    gives metres when H is in metres: GSD = pixel_um·1e-3·H/f.

    Examples
    --------
    >>> round(float(ground_sample_distance_m(4.4, 100.0, 35.0)), 5)
    0.01257
    """
    p = positive("pixel_um", pixel_um)
    h = positive("height_m", height_m)
    f = positive("focal_mm", focal_mm)
    return p * 1e-3 * h / f


def footprint_m(
    sensor_side_mm: npt.ArrayLike, height_m: npt.ArrayLike, focal_mm: npt.ArrayLike
) -> NDArrayFloat:
    """Ground footprint of one sensor side, sensor side × H/f.

    Parameters
    ----------
    sensor_side_mm : array_like
        Sensor side [mm] (width across track or height along track).
    height_m : array_like
        Flight height above ground H [m].
    focal_mm : array_like
        Focal length f [mm].

    Returns
    -------
    numpy.ndarray
        Footprint on flat ground under a vertical photo [m].

    Notes
    -----
    Spec formulas.md §3 "Flight geometry" (the photo scale 1:Mc with Mc = H/f).

    Examples
    --------
    >>> round(float(footprint_m(35.9, 100.0, 35.0)), 2)
    102.57
    """
    s = positive("sensor_side_mm", sensor_side_mm)
    h = positive("height_m", height_m)
    f = positive("focal_mm", focal_mm)
    return s * h / f


def photo_base_m(
    footprint_along_m: npt.ArrayLike, forward_overlap_pct: npt.ArrayLike
) -> NDArrayFloat:
    """Photo base (distance between exposures) B = footprint_along·(1 − p_fwd/100).

    Parameters
    ----------
    footprint_along_m : array_like
        Footprint along track [m].
    forward_overlap_pct : array_like
        Forward overlap p_fwd [%], 0 ≤ p_fwd < 100.

    Returns
    -------
    numpy.ndarray
        Photo base on the ground [m].

    Notes
    -----
    Spec formulas.md §3; the image-side form b = l_y·(1 − p) is seed 001 §1.

    Examples
    --------
    >>> round(float(photo_base_m(68.57, 80.0)), 3)
    13.714
    """
    fp = positive("footprint_along_m", footprint_along_m)
    p = _overlap("forward_overlap_pct", forward_overlap_pct)
    return fp * (1.0 - p / 100.0)


def line_spacing_m(
    footprint_across_m: npt.ArrayLike, side_overlap_pct: npt.ArrayLike
) -> NDArrayFloat:
    """Distance between flight lines = footprint_across·(1 − p_side/100).

    Parameters
    ----------
    footprint_across_m : array_like
        Footprint across track [m].
    side_overlap_pct : array_like
        Side overlap p_side [%], 0 ≤ p_side < 100.

    Returns
    -------
    numpy.ndarray
        Line spacing [m].

    Notes
    -----
    Spec formulas.md §3 "Flight geometry".

    Examples
    --------
    >>> round(float(line_spacing_m(102.57, 70.0)), 3)
    30.771
    """
    fp = positive("footprint_across_m", footprint_across_m)
    p = _overlap("side_overlap_pct", side_overlap_pct)
    return fp * (1.0 - p / 100.0)


# ---------------------------------------------------------------------------------
# Timing and the camera's trigger limit
# ---------------------------------------------------------------------------------
def photo_interval_s(base_m: npt.ArrayLike, speed_ms: npt.ArrayLike) -> NDArrayFloat:
    """Time between exposures, B / w.

    Parameters
    ----------
    base_m : array_like
        Photo base B [m].
    speed_ms : array_like
        Ground speed w [m/s].

    Returns
    -------
    numpy.ndarray
        Photo interval [s].

    Notes
    -----
    Spec formulas.md §3. Compare with the camera's minimum trigger interval using
    :func:`trigger_interval_ok`.

    Examples
    --------
    >>> round(float(photo_interval_s(13.7, 10.0)), 2)
    1.37
    """
    b = positive("base_m", base_m)
    w = positive("speed_ms", speed_ms)
    return b / w


def trigger_interval_ok(
    interval_s: npt.ArrayLike, min_trigger_interval_s: npt.ArrayLike
) -> np.ndarray:
    """True where the planned photo interval is not shorter than the camera can trigger.

    Parameters
    ----------
    interval_s : array_like
        Planned photo interval [s] (:func:`photo_interval_s`).
    min_trigger_interval_s : array_like
        Camera's minimum interval between exposures [s] (catalogue column
        ``min_trigger_interval_s``).

    Returns
    -------
    numpy.ndarray of bool
        ``False`` flags a plan the camera cannot fly: slow down, fly higher or reduce
        the forward overlap (see :func:`max_speed_for_trigger_ms`).

    Notes
    -----
    Spec formulas.md §3 "check against the camera's minimum trigger interval".

    Examples
    --------
    >>> trigger_interval_ok([1.37, 0.5], 0.7).tolist()
    [True, False]
    """
    t = positive("interval_s", interval_s)
    tmin = positive("min_trigger_interval_s", min_trigger_interval_s)
    return t >= tmin


def max_speed_for_trigger_ms(
    base_m: npt.ArrayLike, min_trigger_interval_s: npt.ArrayLike
) -> NDArrayFloat:
    """Largest ground speed at which the camera can still trigger every base, B / t_min.

    Parameters
    ----------
    base_m : array_like
        Photo base B [m].
    min_trigger_interval_s : array_like
        Camera's minimum trigger interval [s].

    Returns
    -------
    numpy.ndarray
        Speed [m/s].

    Notes
    -----
    Inverse of :func:`photo_interval_s` at the trigger limit (spec formulas.md §3).

    Examples
    --------
    >>> round(float(max_speed_for_trigger_ms(13.7, 0.7)), 2)
    19.57
    """
    b = positive("base_m", base_m)
    tmin = positive("min_trigger_interval_s", min_trigger_interval_s)
    return b / tmin


# ---------------------------------------------------------------------------------
# Block layout: strips, photos, length, time, data
# ---------------------------------------------------------------------------------
def strip_count(
    area_width_m: npt.ArrayLike, line_spacing_m: npt.ArrayLike, extra_strips: npt.ArrayLike = 0
) -> np.ndarray:
    """Number of flight lines for a rectangular block, ceil(width / spacing) + extra.

    Parameters
    ----------
    area_width_m : array_like
        Block width across the flight lines [m].
    line_spacing_m : array_like
        Line spacing [m] (:func:`line_spacing_m`).
    extra_strips : array_like, optional
        Additional safety strips [–] (default 0).

    Returns
    -------
    numpy.ndarray of int64
        Number of strips.

    Notes
    -----
    Convention (spec formulas.md §3 leaves it open): the lines are centred at
    (i + ½)·spacing from one edge of the block, i = 0 … n − 1. With n =
    ceil(width/spacing) every point of the block lies within ½·spacing of a line,
    and each footprint reaches ½·footprint ≥ ½·spacing, so the block is covered and
    the outer strips overhang the edges by ½·footprint·p_side. Add ``extra_strips``
    when a margin beyond the block is required.

    Examples
    --------
    >>> int(strip_count(1000.0, 30.0)), int(strip_count(1000.0, 30.0, 1))
    (34, 35)
    """
    w = positive("area_width_m", area_width_m)
    s = positive("line_spacing_m", line_spacing_m)
    e = nonnegative("extra_strips", extra_strips)
    return (np.ceil(w / s - 1e-9) + np.floor(e)).astype(np.int64)


def photos_per_strip(
    area_length_m: npt.ArrayLike, base_m: npt.ArrayLike, extra_per_end: npt.ArrayLike = 1
) -> np.ndarray:
    """Exposures on one strip, ceil(length / B) + 1 + 2·extra_per_end.

    Parameters
    ----------
    area_length_m : array_like
        Block length along the flight lines [m].
    base_m : array_like
        Photo base B [m].
    extra_per_end : array_like, optional
        Exposures added beyond each end of the block [–] (default 1).

    Returns
    -------
    numpy.ndarray of int64
        Number of photos per strip.

    Notes
    -----
    ceil(length/B) + 1 exposures span the block; one more beyond each end (the
    usual rule in Russian aerial-survey practice) makes the end models full stereo
    pairs. Total photos = strips × photos per strip, and the strip is flown over its
    photographed span (photos − 1)·B, not over the block length.

    QGroundControl counts differently: ceil(d/B) images for a transect whose first and
    last trigger points are d apart (SurveyComplexItem, ``_cameraShots``), the transect
    being the polygon's span (plus its turnaround only when images are taken there) —
    that is, no exposures past the ends. For a block length L, scanplan counts
    ceil(L/B) + 3 per strip against QGroundControl's ceil(L/B) (docs/uav-models.md).

    Examples
    --------
    >>> int(photos_per_strip(1000.0, 13.7)), int(photos_per_strip(1000.0, 13.7, 0))
    (76, 74)
    """
    length = positive("area_length_m", area_length_m)
    b = positive("base_m", base_m)
    e = nonnegative("extra_per_end", extra_per_end)
    return (np.ceil(length / b - 1e-9) + 1 + 2 * np.floor(e)).astype(np.int64)


def flight_length_m(
    n_strips: npt.ArrayLike,
    strip_length_m: npt.ArrayLike,
    line_spacing_m: npt.ArrayLike,
    turn_m: npt.ArrayLike | None = None,
) -> NDArrayFloat:
    """Photographic flight length, strips × strip length + (strips − 1) × turn.

    Parameters
    ----------
    n_strips : array_like
        Number of strips [–].
    strip_length_m : array_like
        Flown length of one strip [m]: its photographed span, (photos per strip − 1) × B
        (longer than the block by the exposures past its ends).
    line_spacing_m : array_like
        Line spacing [m].
    turn_m : array_like, optional
        Path flown between two strips [m]. Default: a half circle whose diameter is
        the line spacing, π·spacing/2 (fixed-wing turn at the smallest radius the
        pattern allows); use the spacing itself for a multirotor.

    Returns
    -------
    numpy.ndarray
        Length [m]; transit to and from the block is not included.

    Notes
    -----
    Spec formulas.md §3. Seed 002 notes that light fixed-wing UAVs fly large loops
    ("заход с отворотом") between strips; give ``turn_m`` for such a turn pattern.

    Examples
    --------
    >>> round(float(flight_length_m(34, 1000.0, 30.0)), 1)
    35555.1
    """
    n = positive("n_strips", n_strips)
    length = positive("strip_length_m", strip_length_m)
    s = positive("line_spacing_m", line_spacing_m)
    turn = np.pi * s / 2.0 if turn_m is None else nonnegative("turn_m", turn_m)
    return n * length + (n - 1.0) * turn


def flight_time_s(length_m: npt.ArrayLike, speed_ms: npt.ArrayLike) -> NDArrayFloat:
    """Flight time at constant ground speed, length / w.

    Parameters
    ----------
    length_m : array_like
        Flight length [m].
    speed_ms : array_like
        Ground speed w [m/s].

    Returns
    -------
    numpy.ndarray
        Time [s].

    Notes
    -----
    Spec formulas.md §3 "Flight geometry" (what every UAV planner shows).

    Examples
    --------
    >>> float(flight_time_s(36000.0, 12.0))
    3000.0
    """
    length = nonnegative("length_m", length_m)
    w = positive("speed_ms", speed_ms)
    return length / w


def data_volume_bytes(
    n_photos: npt.ArrayLike,
    image_width_px: npt.ArrayLike,
    image_height_px: npt.ArrayLike,
    bands: npt.ArrayLike = 3,
    bits: npt.ArrayLike = 8,
) -> NDArrayFloat:
    """Uncompressed data volume, photos × pixels × bands × bits / 8.

    Parameters
    ----------
    n_photos : array_like
        Number of photos [–].
    image_width_px, image_height_px : array_like
        Image size [px].
    bands : array_like, optional
        Bands per pixel [–] (3 for a demosaiced RGB image; 1 for a raw Bayer frame).
    bits : array_like, optional
        Bits per band [bit] (8 for JPEG-like output, 12–16 for raw).

    Returns
    -------
    numpy.ndarray
        Bytes (float, to keep large blocks exact enough and broadcastable).

    Notes
    -----
    Spec formulas.md §3 "data volume"; compression (JPEG, lossless raw) is not modelled.

    Examples
    --------
    >>> int(data_volume_bytes(100, 8192, 5460))
    13418496000
    """
    n = nonnegative("n_photos", n_photos)
    w = positive("image_width_px", image_width_px)
    h = positive("image_height_px", image_height_px)
    b = positive("bands", bands)
    bits_ = positive("bits", bits)
    return n * w * h * b * bits_ / 8.0


# ---------------------------------------------------------------------------------
# Motion blur
# ---------------------------------------------------------------------------------
def motion_blur_px(
    speed_ms: npt.ArrayLike, exposure_s: npt.ArrayLike, gsd_m: npt.ArrayLike
) -> NDArrayFloat:
    """Forward-motion blur in pixels, w·t / GSD.

    Parameters
    ----------
    speed_ms : array_like
        Ground speed w [m/s] (0 allowed: hovering).
    exposure_s : array_like
        Exposure time t [s].
    gsd_m : array_like
        Ground sample distance [m].

    Returns
    -------
    numpy.ndarray
        Blur [px]. Planners warn above 0.5 px (:data:`MAX_BLUR_PX`).

    Notes
    -----
    Same quantity as seed 000, eq. 6 (δ_w = w·t·f/H on the image) divided by the
    pixel pitch.

    Examples
    --------
    >>> round(float(motion_blur_px(12.0, 1e-3, 0.0126)), 3)
    0.952
    """
    w = nonnegative("speed_ms", speed_ms)
    t = positive("exposure_s", exposure_s)
    g = positive("gsd_m", gsd_m)
    return w * t / g


def max_exposure_for_blur_s(
    speed_ms: npt.ArrayLike, gsd_m: npt.ArrayLike, max_blur_px: npt.ArrayLike = MAX_BLUR_PX
) -> NDArrayFloat:
    """Longest exposure keeping the blur within ``max_blur_px``: t = blur·GSD / w.

    Parameters
    ----------
    speed_ms : array_like
        Ground speed w [m/s] (> 0).
    gsd_m : array_like
        Ground sample distance [m].
    max_blur_px : array_like, optional
        Accepted blur [px] (default 0.5).

    Returns
    -------
    numpy.ndarray
        Exposure [s].

    Examples
    --------
    >>> round(float(max_exposure_for_blur_s(12.0, 0.0126)), 6)
    0.000525
    """
    w = positive("speed_ms", speed_ms)
    g = positive("gsd_m", gsd_m)
    b = positive("max_blur_px", max_blur_px)
    return b * g / w


def max_speed_for_blur_ms(
    exposure_s: npt.ArrayLike, gsd_m: npt.ArrayLike, max_blur_px: npt.ArrayLike = MAX_BLUR_PX
) -> NDArrayFloat:
    """Fastest ground speed keeping the blur within ``max_blur_px``: w = blur·GSD / t.

    Parameters
    ----------
    exposure_s : array_like
        Exposure time t [s].
    gsd_m : array_like
        Ground sample distance [m].
    max_blur_px : array_like, optional
        Accepted blur [px] (default 0.5).

    Returns
    -------
    numpy.ndarray
        Speed [m/s].

    Examples
    --------
    >>> round(float(max_speed_for_blur_ms(1e-3, 0.0126)), 2)
    6.3
    """
    t = positive("exposure_s", exposure_s)
    g = positive("gsd_m", gsd_m)
    b = positive("max_blur_px", max_blur_px)
    return b * g / t


# ---------------------------------------------------------------------------------
# Height tolerance of light UAVs (seed 002)
# ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class HeightBand:
    """Heights to check when the UAV does not hold the planned height (seed 002).

    Attributes
    ----------
    planned_m : numpy.ndarray
        Planned height above ground [m].
    min_m : numpy.ndarray
        Lowest height flown [m]: check **overlaps** here (the footprint is smallest).
    max_m : numpy.ndarray
        Highest height flown [m]: check **resolution constraints** here (GSD and L
        are largest).
    """

    planned_m: NDArrayFloat
    min_m: NDArrayFloat
    max_m: NDArrayFloat


def height_band(
    height_m: npt.ArrayLike,
    tolerance_up: npt.ArrayLike,
    tolerance_down: npt.ArrayLike | None = None,
) -> HeightBand:
    """Heights at which a plan must hold: H_max = H·(1 + up), H_min = H·(1 − down).

    Parameters
    ----------
    height_m : array_like
        Planned height above ground H [m].
    tolerance_up : array_like
        Relative excess over the plan [–] (0.4 for seed 002: 300 m planned, 420 m flown).
    tolerance_down : array_like, optional
        Relative shortfall [–], 0 ≤ down < 1. Default: equal to ``tolerance_up``
        (symmetric band). Seed 002 reports 300–420 m, i.e. down = 0.

    Returns
    -------
    HeightBand

    Notes
    -----
    Seed 002 (Zverev & Fisenko 2014): a light UAV planned at 300 m flew 300–420 m.
    Constraints on resolution are checked at H_max, overlaps at H_min (spec §3).

    Examples
    --------
    >>> b = height_band(100.0, 0.1)
    >>> round(float(b.max_m), 6), round(float(b.min_m), 6)
    (110.0, 90.0)
    """
    h = positive("height_m", height_m)
    up = nonnegative("tolerance_up", tolerance_up)
    down = up if tolerance_down is None else tolerance_down
    down = in_range("tolerance_down", down, 0.0, 1.0, high_inclusive=False)
    return HeightBand(planned_m=h, min_m=h * (1.0 - down), max_m=h * (1.0 + up))


def actual_overlap_pct(
    planned_overlap_pct: npt.ArrayLike,
    planned_height_m: npt.ArrayLike,
    actual_height_m: npt.ArrayLike,
) -> NDArrayFloat:
    """Overlap actually obtained when the trigger distance is fixed for the planned height.

    p = 1 − (1 − p0)·H0/H (as fractions). Applies to forward overlap (fixed
    distance trigger) and to side overlap (fixed line spacing) alike.

    Parameters
    ----------
    planned_overlap_pct : array_like
        Overlap p0 planned at H0 [%].
    planned_height_m : array_like
        Planned height H0 [m].
    actual_height_m : array_like
        Height actually flown H [m].

    Returns
    -------
    numpy.ndarray
        Overlap [%]. Below the plan it shrinks and may become negative: a negative
        value is a gap between neighbouring footprints (returned, not clipped).

    Notes
    -----
    Derived from :func:`photo_base_m` with the footprint ∝ H (spec §3, seed 002).
    Seed 002 case: 80 % at 300 m flown at 420 m gives 1 − 0.2·300/420 = 85.7 %.

    Examples
    --------
    >>> round(float(actual_overlap_pct(80.0, 300.0, 420.0)), 1)
    85.7
    """
    p0 = _overlap("planned_overlap_pct", planned_overlap_pct)
    h0 = positive("planned_height_m", planned_height_m)
    h = positive("actual_height_m", actual_height_m)
    return 100.0 * (1.0 - (1.0 - p0 / 100.0) * h0 / h)


JPEG_COMPRESSION_RATIO = 9.0
"""Uncompressed 8-bit RGB size / JPEG file size of a camera's finest JPEG [–].

Canon publishes the file sizes of its cameras' image-quality settings: the EOS 7D Mark II
writes a 20.2-megapixel Large/Fine JPEG of about 6.6 MB (Canon U.S.A., "Photo capacity
and movie recording time on memory cards – EOS 7D Mark II", support article ART168772,
2017; Canon's test conditions: ISO 100, Standard picture style), while the same frame
uncompressed (3 bands × 8 bits) is 60.6 MB: 9.2:1, rounded to 9:1. Detailed scenes (forest,
town roofs) compress less, so this is an estimate, not a bound; the uncompressed volume is
the one to size storage for."""


def jpeg_volume_bytes(uncompressed_bytes: npt.ArrayLike,
                      ratio: float = JPEG_COMPRESSION_RATIO) -> NDArrayFloat:
    """An estimate of the same photos stored as JPEG: uncompressed bytes / ``ratio``.

    Parameters
    ----------
    uncompressed_bytes : array_like
        Uncompressed volume [bytes] (:func:`data_volume_bytes`).
    ratio : float, optional
        Compression ratio [–] (default :data:`JPEG_COMPRESSION_RATIO`, 9:1, with its source).

    Returns
    -------
    numpy.ndarray
        Bytes.

    Examples
    --------
    >>> float(jpeg_volume_bytes(9e9))
    1000000000.0
    """
    return np.asarray(uncompressed_bytes, dtype=np.float64) / ratio
