"""Coordinate frames (docs/reference/conventions.md): ground G, body B, hub H.

All frames are right-handed with z up: G and B have x forward and y to port; H has z along
the thrust, x toward the body's aft direction projected onto the rotor plane.
Matrices ``R_AB`` take vector components in frame B to components in frame A.
"""

from __future__ import annotations

import numpy as np


def rot_x(angle_rad: float) -> np.ndarray:
    """Right-handed rotation by ``angle_rad`` about +x."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(angle_rad: float) -> np.ndarray:
    """Right-handed rotation by ``angle_rad`` about +y."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(angle_rad: float) -> np.ndarray:
    """Right-handed rotation by ``angle_rad`` about +z."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def body_to_ground(pitch_rad: float, roll_rad: float) -> np.ndarray:
    """R_GB for nose-up pitch ``pitch_rad`` and starboard-down roll ``roll_rad``.

    Roll is applied first about the body x axis, then pitch (nose up = rotation about -y).
    """
    return rot_y(-pitch_rad) @ rot_x(roll_rad)


def shaft_axis_body(tilt_forward_rad: float, tilt_port_rad: float, base_axis=(0.0, 0.0, 1.0)) -> np.ndarray:
    """Unit thrust axis in B: ``base_axis`` tilted forward (toward +x_B) and to port (+y_B).

    For a main rotor ``base_axis`` is +z_B; a forward tilt of i_s gives (sin i_s, 0, cos i_s).
    """
    axis = np.asarray(base_axis, dtype=float)
    axis = axis / np.linalg.norm(axis)
    tilted = rot_x(-tilt_port_rad) @ rot_y(tilt_forward_rad) @ axis
    return tilted / np.linalg.norm(tilted)


def hub_to_body(thrust_axis_body: np.ndarray) -> np.ndarray:
    """R_BH: columns are x_H, y_H, z_H expressed in B.

    z_H is the thrust axis; x_H is the body aft direction (-x_B) projected onto the rotor
    plane (or -z_B when the shaft is along x_B); y_H = z_H x x_H.
    """
    z_h = np.asarray(thrust_axis_body, dtype=float)
    z_h = z_h / np.linalg.norm(z_h)
    reference = np.array([-1.0, 0.0, 0.0])
    if abs(np.dot(reference, z_h)) > 0.99:
        reference = np.array([0.0, 0.0, -1.0])
    x_h = reference - np.dot(reference, z_h) * z_h
    x_h /= np.linalg.norm(x_h)
    y_h = np.cross(z_h, x_h)
    return np.column_stack([x_h, y_h, z_h])


def blade_span_unit_hub(psi_rad, rotation_sign: int) -> np.ndarray:
    """Unit span vector e_r = (cos psi, s sin psi, 0) in H, shape (..., 3)."""
    psi = np.asarray(psi_rad, dtype=float)
    return np.stack([np.cos(psi), rotation_sign * np.sin(psi), np.zeros_like(psi)], axis=-1)


def observer_direction(azimuth_rad, elevation_rad) -> np.ndarray:
    """Unit vector in G for a map azimuth (0 behind, pi/2 starboard) and elevation (up +).

    d = (-cos az cos el, -sin az cos el, sin el), shape (..., 3).
    """
    az = np.asarray(azimuth_rad, dtype=float)
    el = np.asarray(elevation_rad, dtype=float)
    return np.stack([-np.cos(az) * np.cos(el), -np.sin(az) * np.cos(el), np.sin(el) + 0.0 * az], axis=-1)
