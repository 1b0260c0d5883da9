"""Quaternion of seed 002 eq. 30, rotation matrix, GSD of a tilted frame."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanplan.core import orientation as ori

angles = st.floats(-2 * np.pi, 2 * np.pi, allow_nan=False)


def _eq30_by_hand(alpha, omega, chi):
    """Eq. 30 typed again from the seed, term by term."""
    ca, sa = np.cos(alpha / 2), np.sin(alpha / 2)
    cw, sw = np.cos(omega / 2), np.sin(omega / 2)
    cc, sc = np.cos(chi / 2), np.sin(chi / 2)
    return np.array(
        [
            ca * cw * cc - sa * sw * sc,
            ca * sw * cc - sa * cw * sc,
            -sa * sw * cc - ca * cw * sc,
            -sa * cw * cc - ca * sw * sc,
        ]
    )


@settings(max_examples=100, deadline=None)
@given(angles, angles, angles)
def test_eq30_equals_qz_of_minus_alpha_times_qx_of_omega_times_qy_of_minus_chi(a, w, c):
    """Seed 002 eq. 30 is the Hamilton product q_z(−α) ⊗ q_x(ω) ⊗ q_y(−χ) (exactly, not ±)."""
    q = ori.quaternion_eq30(a, w, c)
    np.testing.assert_allclose(q, _eq30_by_hand(a, w, c), atol=1e-14)
    prod = ori.quaternion_multiply(
        ori.quaternion_multiply(
            ori.elementary_quaternion("z", -a), ori.elementary_quaternion("x", w)
        ),
        ori.elementary_quaternion("y", -c),
    )
    np.testing.assert_allclose(q, prod, atol=1e-12)
    # and its matrix is R_z(−α)·R_x(ω)·R_y(−χ)
    r = ori.elementary_rotation("z", -a) @ ori.elementary_rotation("x", w)
    r = r @ ori.elementary_rotation("y", -c)
    np.testing.assert_allclose(ori.rotation_matrix(q), r, atol=1e-12)


def test_eq30_ordering_is_unique():
    """Of all 6·27·8 products of three elementary rotations (any axes, any angle order,
    any signs), only q_z(−α) ⊗ q_x(ω) ⊗ q_y(−χ) reproduces eq. 30 (up to ±q)."""
    rng = np.random.default_rng(30)
    sample = rng.uniform(-3.0, 3.0, size=(8, 3))
    target = ori.quaternion_eq30(sample[:, 0], sample[:, 1], sample[:, 2])
    matches = []
    for perm in itertools.permutations(range(3)):
        for axes in itertools.product("xyz", repeat=3):
            for signs in itertools.product((1.0, -1.0), repeat=3):
                q = np.array([1.0, 0.0, 0.0, 0.0])
                for k in range(3):
                    q = ori.quaternion_multiply(
                        q, ori.elementary_quaternion(axes[k], signs[k] * sample[:, perm[k]])
                    )
                same = np.allclose(q, target, atol=1e-12) or np.allclose(q, -target, atol=1e-12)
                if same:
                    matches.append((perm, axes, signs))
    assert matches == [((0, 1, 2), ("z", "x", "y"), (-1.0, 1.0, -1.0))]


@settings(max_examples=100, deadline=None)
@given(angles, angles, angles)
def test_quaternion_is_unit_and_matrix_orthonormal_with_det_plus_one(a, w, c):
    q = ori.quaternion_eq30(a, w, c)
    assert np.linalg.norm(q) == pytest.approx(1.0, abs=1e-14)
    r = ori.rotation_matrix(q)
    np.testing.assert_allclose(r @ r.T, np.eye(3), atol=1e-12)
    assert np.linalg.det(r) == pytest.approx(1.0, abs=1e-12)


def test_matrix_rotates_like_the_quaternion_sandwich():
    rng = np.random.default_rng(1)
    q = ori.quaternion_eq30(*rng.uniform(-3, 3, (3, 5)))
    v = rng.normal(size=(5, 3))
    qv = np.concatenate([np.zeros((5, 1)), v], axis=-1)
    conj = q * np.array([1, -1, -1, -1])
    rotated = ori.quaternion_multiply(ori.quaternion_multiply(q, qv), conj)[:, 1:]
    np.testing.assert_allclose(np.einsum("nij,nj->ni", ori.rotation_matrix(q), v), rotated)


def test_vectorised_shapes():
    a = np.zeros((2, 3))
    assert ori.quaternion_eq30(a, 0.1, 0.2).shape == (2, 3, 4)
    assert ori.rotation_matrix(ori.quaternion_eq30(a, 0.1, 0.2)).shape == (2, 3, 3, 3)
    assert ori.corner_gsd(np.array([300.0, 420.0]), 50, 6.41, 36, 24).gsd_max_m.shape == (2, 4)


def test_nadir_eq30_is_identity_and_vertical_corners_equal_gsd():
    """Aerial camera with ω = −90°: optical axis to the nadir; flat ground: GSD = pH/f."""
    np.testing.assert_allclose(ori.camera_matrix_eq30(0.0, -np.pi / 2, 0.0), np.eye(3), atol=1e-15)
    c = ori.corner_gsd(300.0, 50.0, 6.41, 36.0, 24.0, ori.camera_matrix_eq30(0, -np.pi / 2, 0))
    np.testing.assert_allclose(c.gsd_max_m, 6.41e-3 * 300 / 50)
    np.testing.assert_allclose(c.gsd_mean_m, 6.41e-3 * 300 / 50)
    assert c.gsd_nadir_m == pytest.approx(6.41e-3 * 300 / 50)


@pytest.mark.parametrize("tilt_deg", [2.0, 10.0, 30.0])
def test_principal_point_gsd_of_a_tilted_photo(tilt_deg):
    """At the principal point of a photo tilted by θ: scale H/(f·cos²θ) along the tilt,
    H/(f·cosθ) across it."""
    th = np.radians(tilt_deg)
    r = ori.attitude_matrix(0.0, th, 0.0)
    gmax, gmean = ori.image_point_gsd(0.0, 0.0, 300.0, 50.0, 5.0, r)
    base = 5e-3 * 300 / 50
    assert gmax == pytest.approx(base / np.cos(th) ** 2)
    assert gmean == pytest.approx(base / np.cos(th) ** 1.5)


def test_roll_makes_the_raised_side_coarser():
    r = ori.attitude_matrix(np.radians(5.0), 0.0, 0.0)  # optical axis tilts to the left (+y)
    c = ori.corner_gsd(300.0, 50.0, 6.41, 36.0, 24.0, r)
    left = c.gsd_max_m[[0, 3]]  # front-left, rear-left
    right = c.gsd_max_m[[1, 2]]
    assert np.all(left > c.gsd_nadir_m) and np.all(left > right)
    np.testing.assert_allclose(left[0], left[1])
    assert c.worst_m == pytest.approx(left.max())


def test_ray_above_horizon_gives_nan_not_a_number():
    r = ori.attitude_matrix(0.0, np.radians(80.0), 0.0)  # wide frame tilted 80°
    c = ori.corner_gsd(300.0, 20.0, 4.4, 35.9, 24.0, r)
    assert np.isnan(c.gsd_max_m).any() and np.isfinite(c.gsd_max_m).any()


def test_invalid_input():
    with pytest.raises(ValueError, match=r"^alpha_rad must be finite"):
        ori.quaternion_eq30(np.nan, 0, 0)
    with pytest.raises(ValueError, match=r"^height_m must be > 0"):
        ori.corner_gsd(-1.0, 50, 6.41, 36, 24)
    with pytest.raises(ValueError, match=r"^axis must be"):
        ori.elementary_quaternion("w", 0.1)
