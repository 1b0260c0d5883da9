"""Exterior orientation by quaternion (seed 002, eq. 30) and GSD of a tilted frame.

Quaternions are Hamilton quaternions q = (a0, a1, a2, a3) = a0 + a1·i + a2·j + a3·k,
stored in the last axis of an array (shape ``(..., 4)``); rotation matrices in the last
two axes (shape ``(..., 3, 3)``). The rotation matrix of a unit quaternion is the
*active* rotation v' = q v q*, i.e. it maps camera-frame vectors to ground-frame
vectors.

**The convention of eq. 30, found numerically** (every ordering of three elementary
rotations about the coordinate axes, each with ±angle, was tried; exactly one
matches for all angles, see tests/test_orientation.py)::

    q(α, ω, χ) = q_z(−α) ⊗ q_x(ω) ⊗ q_y(−χ)
    R(α, ω, χ) = R_z(−α) · R_x(ω) · R_y(−χ)

with q_u(θ) = (cos θ/2, sin θ/2 · u). This is the angle system of terrestrial
photogrammetry: at zero angles the optical axis is the horizontal **+y** axis;
α (direction angle of the optical axis) turns it about the vertical z, ω (tilt of
the optical axis) about x, χ (rotation of the photo) about the optical axis y. The
negative signs of α and χ mean those two angles are counted clockwise (as direction
angles are), ω counter-clockwise. For an aerial camera (optical axis −z at zero
attitude) :func:`camera_matrix_eq30` appends the fixed turn R_x(+90°): a nadir photo
is ω = −90°.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
import numpy.typing as npt

from scanplan.core.checks import finite, positive

__all__ = [
    "CORNER_NAMES",
    "CornerGSD",
    "attitude_matrix",
    "camera_matrix_eq30",
    "corner_gsd",
    "elementary_quaternion",
    "elementary_rotation",
    "image_point_gsd",
    "quaternion_eq30",
    "quaternion_multiply",
    "rotation_matrix",
]

NDArrayFloat = npt.NDArray[np.float64]
Axis = Literal["x", "y", "z"]
_AXES = {"x": 0, "y": 1, "z": 2}

#: Order of the corners in :class:`CornerGSD` (x along track forward, y to the left).
CORNER_NAMES: tuple[str, str, str, str] = ("front-left", "front-right", "rear-right", "rear-left")


def quaternion_eq30(
    alpha_rad: npt.ArrayLike, omega_rad: npt.ArrayLike, chi_rad: npt.ArrayLike
) -> NDArrayFloat:
    """Orientation quaternion from the angles α, ω, χ, exactly as printed in eq. 30.

    a0 = cos(α/2)cos(ω/2)cos(χ/2) − sin(α/2)sin(ω/2)sin(χ/2)
    a1 = cos(α/2)sin(ω/2)cos(χ/2) − sin(α/2)cos(ω/2)sin(χ/2)
    a2 = −sin(α/2)sin(ω/2)cos(χ/2) − cos(α/2)cos(ω/2)sin(χ/2)
    a3 = −sin(α/2)cos(ω/2)cos(χ/2) − cos(α/2)sin(ω/2)sin(χ/2)

    Parameters
    ----------
    alpha_rad : array_like
        Direction angle of the optical axis α [rad].
    omega_rad : array_like
        Tilt of the optical axis ω [rad].
    chi_rad : array_like
        Rotation (swing) of the photo χ [rad].

    Returns
    -------
    numpy.ndarray
        Unit quaternion (a0, a1, a2, a3), shape broadcast(α, ω, χ) + (4,).

    Notes
    -----
    Seed 002, eq. 30 (spec formulas.md §4). Numerically identical to the Hamilton
    product q_z(−α) ⊗ q_x(ω) ⊗ q_y(−χ) (module docstring); the seed's own sentence
    on the rotations ("counter-clockwise by π − α/2, ω, π − χ/2") is garbled in the
    extracted text and is not used.

    Examples
    --------
    >>> (np.round(quaternion_eq30(0.0, 0.0, 0.0), 6) + 0.0).tolist()
    [1.0, 0.0, 0.0, 0.0]
    """
    a = finite("alpha_rad", alpha_rad) / 2.0
    w = finite("omega_rad", omega_rad) / 2.0
    c = finite("chi_rad", chi_rad) / 2.0
    ca, sa, cw, sw, cc, sc = np.cos(a), np.sin(a), np.cos(w), np.sin(w), np.cos(c), np.sin(c)
    a0 = ca * cw * cc - sa * sw * sc
    a1 = ca * sw * cc - sa * cw * sc
    a2 = -sa * sw * cc - ca * cw * sc
    a3 = -sa * cw * cc - ca * sw * sc
    return np.stack(np.broadcast_arrays(a0, a1, a2, a3), axis=-1)


def elementary_quaternion(axis: Axis, angle_rad: npt.ArrayLike) -> NDArrayFloat:
    """Quaternion of a rotation by ``angle_rad`` about a coordinate axis.

    Parameters
    ----------
    axis : {"x", "y", "z"}
    angle_rad : array_like
        Counter-clockwise angle seen from the positive axis [rad].

    Returns
    -------
    numpy.ndarray
        (cos θ/2, sin θ/2 · e_axis), shape + (4,).

    Examples
    --------
    >>> np.round(elementary_quaternion("z", np.pi / 2), 6).tolist()
    [0.707107, 0.0, 0.0, 0.707107]
    """
    if axis not in _AXES:
        raise ValueError(f"axis must be 'x', 'y' or 'z' (got {axis!r})")
    t = finite("angle_rad", angle_rad) / 2.0
    q = np.zeros((*t.shape, 4))
    q[..., 0] = np.cos(t)
    q[..., 1 + _AXES[axis]] = np.sin(t)
    return q


def quaternion_multiply(p: npt.ArrayLike, q: npt.ArrayLike) -> NDArrayFloat:
    """Hamilton product p ⊗ q of quaternions stored in the last axis.

    Parameters
    ----------
    p, q : array_like
        Quaternions (w, x, y, z), shapes broadcastable, last axis 4.

    Returns
    -------
    numpy.ndarray
        p ⊗ q = (p0 q0 − p·q, p0 q + q0 p + p × q).

    Examples
    --------
    >>> qz = elementary_quaternion("z", np.pi / 2)
    >>> np.round(quaternion_multiply(qz, qz), 6).tolist()
    [0.0, 0.0, 0.0, 1.0]
    """
    p_ = finite("p", p)
    q_ = finite("q", q)
    pw, pv = p_[..., 0], p_[..., 1:]
    qw, qv = q_[..., 0], q_[..., 1:]
    w = pw * qw - np.sum(pv * qv, axis=-1)
    v = pw[..., None] * qv + qw[..., None] * pv + np.cross(pv, qv)
    return np.concatenate([w[..., None], v], axis=-1)


def rotation_matrix(q: npt.ArrayLike) -> NDArrayFloat:
    """Rotation matrix of a quaternion (Hamilton, active: v' = q v q*).

    Parameters
    ----------
    q : array_like
        Quaternion(s) (a0, a1, a2, a3), last axis 4; normalised here.

    Returns
    -------
    numpy.ndarray
        Orthonormal matrices with det +1, shape (..., 3, 3).

    Notes
    -----
    Standard form, e.g. R11 = a0² + a1² − a2² − a3², R12 = 2(a1a2 − a0a3), …
    (spec formulas.md §4: "derive the rotation matrix from it").

    Examples
    --------
    >>> np.round(rotation_matrix([1.0, 0.0, 0.0, 0.0]), 6).tolist()
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    """
    q_ = finite("q", q)
    norm = np.linalg.norm(q_, axis=-1, keepdims=True)
    if np.any(norm == 0):
        raise ValueError("q must be a non-zero quaternion (got norm 0)")
    w, x, y, z = np.moveaxis(q_ / norm, -1, 0)
    r = np.stack(
        [
            w * w + x * x - y * y - z * z,
            2 * (x * y - w * z),
            2 * (x * z + w * y),
            2 * (x * y + w * z),
            w * w - x * x + y * y - z * z,
            2 * (y * z - w * x),
            2 * (x * z - w * y),
            2 * (y * z + w * x),
            w * w - x * x - y * y + z * z,
        ],
        axis=-1,
    )
    return r.reshape((*r.shape[:-1], 3, 3))


def elementary_rotation(axis: Axis, angle_rad: npt.ArrayLike) -> NDArrayFloat:
    """Matrix of a counter-clockwise rotation about a coordinate axis, shape (..., 3, 3).

    Examples
    --------
    >>> np.round(elementary_rotation("z", np.pi / 2) @ [1.0, 0.0, 0.0], 6).tolist()
    [0.0, 1.0, 0.0]
    """
    return rotation_matrix(elementary_quaternion(axis, angle_rad))


def camera_matrix_eq30(
    alpha_rad: npt.ArrayLike, omega_rad: npt.ArrayLike, chi_rad: npt.ArrayLike
) -> NDArrayFloat:
    """Camera-to-ground matrix of an aerial camera whose orientation is given by eq. 30.

    Parameters
    ----------
    alpha_rad, omega_rad, chi_rad : array_like
        Angles of eq. 30 [rad]; ω = −π/2 points the optical axis to the nadir.

    Returns
    -------
    numpy.ndarray
        R_eq30 · R_x(+90°), shape (..., 3, 3): maps the aerial camera frame (x along
        track, y to the left, optical axis −z) to the ground frame (z up).

    Notes
    -----
    Seed 002, eq. 30 with the convention of the module docstring. R_x(+90°) turns
    the aerial camera's −z (optical axis) into eq. 30's +y.

    Examples
    --------
    >>> np.round(camera_matrix_eq30(0.0, 0.0, 0.0), 6).tolist()
    [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]]
    """
    r30 = rotation_matrix(quaternion_eq30(alpha_rad, omega_rad, chi_rad))
    return r30 @ elementary_rotation("x", np.pi / 2)


def attitude_matrix(
    roll_rad: npt.ArrayLike, pitch_rad: npt.ArrayLike, yaw_rad: npt.ArrayLike = 0.0
) -> NDArrayFloat:
    """Camera-to-ground matrix of a UAV camera from roll, pitch and yaw.

    Parameters
    ----------
    roll_rad : array_like
        Rotation about the longitudinal (flight) axis x [rad].
    pitch_rad : array_like
        Rotation about the transverse axis y [rad].
    yaw_rad : array_like, optional
        Rotation about the vertical axis z (heading/drift) [rad].

    Returns
    -------
    numpy.ndarray
        R_z(yaw) · R_y(pitch) · R_x(roll), shape (..., 3, 3); the identity is a
        vertical photo (optical axis −z).

    Notes
    -----
    Aerospace z-y-x order; not a seed formula. Seed 002 reports large roll, pitch and
    drift of a light UAV: feed them here and to :func:`corner_gsd`.

    Examples
    --------
    >>> np.round(attitude_matrix(0.0, 0.0, 0.0), 6).tolist()
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    """
    return (
        elementary_rotation("z", yaw_rad)
        @ elementary_rotation("y", pitch_rad)
        @ elementary_rotation("x", roll_rad)
    )


def image_point_gsd(
    x_mm: npt.ArrayLike,
    y_mm: npt.ArrayLike,
    height_m: npt.ArrayLike,
    focal_mm: npt.ArrayLike,
    pixel_um: npt.ArrayLike,
    rotation: npt.ArrayLike | None = None,
) -> tuple[NDArrayFloat, NDArrayFloat]:
    """GSD at an image point of a tilted frame over flat ground.

    Parameters
    ----------
    x_mm, y_mm : array_like
        Image coordinates of the point from the principal point [mm] (x along
        track, y to the left).
    height_m : array_like
        Height of the projection centre above the ground plane H [m].
    focal_mm : array_like
        Focal length f [mm].
    pixel_um : array_like
        Pixel pitch p [µm].
    rotation : array_like, optional
        Camera-to-ground matrix, shape (..., 3, 3) (:func:`attitude_matrix`,
        :func:`camera_matrix_eq30`). Default: vertical photo (identity).

    Returns
    -------
    gsd_max_m : numpy.ndarray
        Largest ground distance spanned by a one-pixel step in any image direction
        at that point [m] (p × the largest singular value of the Jacobian).
    gsd_mean_m : numpy.ndarray
        Square root of the ground area of one pixel there [m] (p × sqrt|det J|).
        Both are NaN where the ray through the point does not reach the ground
        (points at or above the horizon).

    Notes
    -----
    Definition (spec formulas.md §3 asks for the corner GSD of a tilted frame; the
    papers give no formula): the ray d = R·(x, y, −f) from the projection centre is
    intersected with the plane H below it, G(x, y) = −H·(d_x, d_y)/d_z. The 2×2
    Jacobian J = ∂G/∂(x, y) maps an image step to a ground step, so a pixel (a
    p × p square) lands on a parallelogram with sides p·J·e_x, p·J·e_y. For a
    vertical photo J = (H/f)·I and both values equal p·H/f everywhere.

    Examples
    --------
    >>> gmax, gmean = image_point_gsd(0.0, 0.0, 100.0, 35.0, 4.4)
    >>> round(float(gmax), 5), round(float(gmean), 5)
    (0.01257, 0.01257)
    >>> tilted = image_point_gsd(0.0, 0.0, 100.0, 35.0, 4.4, attitude_matrix(np.radians(10.0), 0.0))
    >>> round(float(tilted[0]), 5)
    0.01296
    """
    x = finite("x_mm", x_mm)
    y = finite("y_mm", y_mm)
    h = positive("height_m", height_m)
    f = positive("focal_mm", focal_mm)
    p = positive("pixel_um", pixel_um) * 1e-3
    r = np.eye(3) if rotation is None else finite("rotation", rotation)
    if r.shape[-2:] != (3, 3):
        raise ValueError(f"rotation must have shape (..., 3, 3) (got {r.shape})")
    xb, yb, fb = np.broadcast_arrays(x, y, -f)
    v = np.stack([xb, yb, fb], axis=-1)
    d = np.einsum("...ij,...j->...i", r, v)
    dz = d[..., 2]
    hits = dz < 0
    dz_safe = np.where(hits, dz, -1.0)
    # J = −H (R[:2,:2]·d_z − d_xy ⊗ R[2,:2]) / d_z²   [m per mm on the image]
    r_xy = r[..., :2, :2]
    r_z = r[..., 2, :2]
    outer = d[..., :2, None] * r_z[..., None, :]
    jac = -(h[..., None, None]) * (r_xy * dz_safe[..., None, None] - outer)
    jac = jac / (dz_safe**2)[..., None, None]
    sv = np.linalg.svd(jac, compute_uv=False)
    gsd_max = np.where(hits, p * sv[..., 0], np.nan)
    gsd_mean = np.where(hits, p * np.sqrt(np.abs(np.linalg.det(jac))), np.nan)
    return gsd_max, gsd_mean


@dataclass(frozen=True, eq=False)
class CornerGSD:
    """GSD at the four corners of a (tilted) frame.

    Attributes
    ----------
    gsd_max_m : numpy.ndarray
        Shape (..., 4), corners in the order of :data:`CORNER_NAMES`; see
        :func:`image_point_gsd` for the definition. NaN: the corner ray misses the
        ground.
    gsd_mean_m : numpy.ndarray
        Shape (..., 4): sqrt of the pixel's ground area.
    gsd_nadir_m : numpy.ndarray
        p·H/f of the vertical photo at the same height [m], for comparison.
    """

    gsd_max_m: NDArrayFloat
    gsd_mean_m: NDArrayFloat
    gsd_nadir_m: NDArrayFloat

    @property
    def worst_m(self) -> NDArrayFloat:
        """Largest corner GSD [m] (NaN if any corner misses the ground)."""
        return np.max(self.gsd_max_m, axis=-1)


def corner_gsd(
    height_m: npt.ArrayLike,
    focal_mm: npt.ArrayLike,
    pixel_um: npt.ArrayLike,
    sensor_width_mm: npt.ArrayLike,
    sensor_height_mm: npt.ArrayLike,
    rotation: npt.ArrayLike | None = None,
) -> CornerGSD:
    """GSD at the four image corners of a frame tilted by the attitude.

    Parameters
    ----------
    height_m : array_like
        Height above flat ground H [m].
    focal_mm : array_like
        Focal length f [mm].
    pixel_um : array_like
        Pixel pitch p [µm].
    sensor_width_mm : array_like
        Sensor side across track (image y) [mm].
    sensor_height_mm : array_like
        Sensor side along track (image x) [mm].
    rotation : array_like, optional
        Camera-to-ground matrix (..., 3, 3); default vertical photo.

    Returns
    -------
    CornerGSD

    Notes
    -----
    Spec formulas.md §3 ("corner GSD of a tilted frame from the exterior
    orientation") and §4; seed 002 (large roll/pitch/drift of light UAVs). Corners
    at (x, y) = (±b/2, ±a/2) in the order of :data:`CORNER_NAMES`.

    Examples
    --------
    >>> c = corner_gsd(100.0, 35.0, 4.4, 35.9, 24.0, attitude_matrix(np.radians(5.0), 0.0))
    >>> np.round(c.gsd_max_m, 5).tolist()
    [0.01395, 0.01214, 0.01214, 0.01395]
    >>> round(float(c.gsd_nadir_m), 5)
    0.01257
    """
    a = positive("sensor_width_mm", sensor_width_mm)
    b = positive("sensor_height_mm", sensor_height_mm)
    sx = np.array([1.0, 1.0, -1.0, -1.0])
    sy = np.array([1.0, -1.0, -1.0, 1.0])
    x = (b[..., None] / 2.0) * sx
    y = (a[..., None] / 2.0) * sy
    h = positive("height_m", height_m)
    f = positive("focal_mm", focal_mm)
    p = positive("pixel_um", pixel_um)
    r = None if rotation is None else np.asarray(rotation, dtype=float)[..., None, :, :]
    gmax, gmean = image_point_gsd(x, y, h[..., None], f[..., None], p[..., None], r)
    return CornerGSD(gsd_max_m=gmax, gsd_mean_m=gmean, gsd_nadir_m=p * 1e-3 * h / f)
