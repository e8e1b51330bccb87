"""Flapping bird: the two-segment wing of the paper's Eqs. 7-15 (after Chen).

Body frame: x along the flight direction, y along one wing's span (the other wing mirrors it), z up. The upper arm
(shoulder to elbow, length L1) swings in the y-z plane at ``psi1`` from the y axis; the forearm
(elbow to tip, length L2) is lifted by ``psi1 - psi2`` in that plane and swept back by the twist
``phi2``.

The paper writes the joints with ``tan`` (Eqs. 12, 13, 15), which diverges when a wing segment is
vertical. Here they are built by rotations of rigid segments:

``P1 = L1 (0, cos psi1, sin psi1)``,
``P2 = P1 + L2 (-sin phi2, cos phi2 cos(psi1 - psi2), cos phi2 sin(psi1 - psi2))``.

This equals Eqs. 10-12, 14 and 15 wherever their tangents are finite. Eq. 13's
``x2 = -(y2 - y1) tan(phi2 / cos(psi1 - psi2))`` does not keep the forearm length fixed once
``psi1 != psi2``; the rigid forearm agrees with it exactly when ``psi1 = psi2`` and to third order
in ``phi2`` otherwise.
"""

import numpy as np


def flap_angles_rad(t_s, *, wingbeat_hz, a1_deg, a2_deg, psi10_deg, psi20_deg, c2_deg, phi20_deg):
    """Harmonic wing angles of Eqs. 7-9, with A2 as its own amplitude (Eq. 8 reuses A1).

    Returns
    -------
    psi1, psi2, phi2 : ndarray, rad, shape of ``t_s``
    """
    beat = np.cos(2.0 * np.pi * wingbeat_hz * np.asarray(t_s, dtype=np.float64))
    return flap_angles_from_beat_rad(beat, a1_deg=a1_deg, a2_deg=a2_deg, psi10_deg=psi10_deg, psi20_deg=psi20_deg,
                                     c2_deg=c2_deg, phi20_deg=phi20_deg)


def flap_angles_from_beat_rad(beat, *, a1_deg, a2_deg, psi10_deg, psi20_deg, c2_deg, phi20_deg):
    """Wing angles of Eqs. 7-9 for a given stroke ``beat`` in [-1, 1] (``cos(2 pi f t)`` for steady flapping;
    ``envelope(t) cos(phase(t))`` for flap-glide bursts and drifting wingbeats; 0 is the mean pose)."""
    psi1 = np.deg2rad(a1_deg * beat + psi10_deg)
    psi2 = np.deg2rad(a2_deg * beat + psi20_deg)
    phi2 = np.deg2rad(c2_deg * beat + phi20_deg)
    return psi1, psi2, phi2


def wingbeat_rate_hz(t_s, *, wingbeat_hz, drift_fraction, duration_s):
    """Wingbeat frequency drifting linearly, ``f(t) = f0 (1 + d (t / D - 1/2))``.

    It changes by ``d f0`` across the dwell ``[0, D]`` and its mean over the dwell is ``f0``.
    """
    return wingbeat_hz * (1.0 + drift_fraction * (np.asarray(t_s, dtype=np.float64) / duration_s - 0.5))


def wingbeat_phase_rad(t_s, *, wingbeat_hz, drift_fraction, duration_s):
    """Integral of :func:`wingbeat_rate_hz` times 2 pi from 0 to ``t_s``: ``2 pi f0 (t + d (t^2 / (2 D) - t / 2))``."""
    t = np.asarray(t_s, dtype=np.float64)
    return 2.0 * np.pi * wingbeat_hz * (t + drift_fraction * (t * t / (2.0 * duration_s) - 0.5 * t))


def flap_glide_ramp_s(*, wingbeat_hz, flap_s, glide_s):
    """Length of the smooth transition between flapping and gliding: one wingbeat, at most half a burst."""
    return min(1.0 / wingbeat_hz, 0.5 * flap_s, 0.5 * glide_s)


def flap_glide_envelope(t_s, *, flap_s, glide_s, ramp_s):
    """Stroke envelope of flap-glide flight: 1 while flapping, 0 while gliding (wings at the mean pose).

    Bursts repeat every ``flap_s + glide_s``: flapping on ``[0, flap_s)`` of each cycle. Each switch is
    a raised-sine ramp ``(1 +- sin(pi s / ramp_s)) / 2`` over ``|s| <= ramp_s / 2`` around it, so the
    envelope and its slope are continuous, it crosses 1/2 exactly at the switches (the time spent
    above 1/2 is ``flap_s`` a cycle) and ``|d envelope / dt| <= pi / (2 ramp_s)``.
    """
    period = flap_s + glide_s
    u = np.mod(np.asarray(t_s, dtype=np.float64), period)
    to_start = np.mod(u + 0.5 * period, period) - 0.5 * period  # signed time from the nearest burst start
    to_end = u - flap_s
    half = 0.5 * ramp_s
    envelope = np.where(u < flap_s, 1.0, 0.0)
    envelope = np.where(np.abs(to_end) <= half, 0.5 * (1.0 - np.sin(np.pi * to_end / ramp_s)), envelope)
    return np.where(np.abs(to_start) <= half, 0.5 * (1.0 + np.sin(np.pi * to_start / ramp_s)), envelope)


def flapping_share(duration_s, *, flap_s, glide_s):
    """Fraction of ``[0, duration_s]`` spent flapping (envelope above 1/2) in :func:`flap_glide_envelope`."""
    period = flap_s + glide_s
    cycles, rest = divmod(duration_s, period)
    return (cycles * flap_s + min(rest, flap_s)) / duration_s


def wing_joints_m(psi1_rad, psi2_rad, phi2_rad, *, upper_arm_m, forearm_m):
    """Elbow P1 and tip P2 of the +y wing in the body frame, built from rotations.

    Returns
    -------
    p1, p2 : ndarray, shape (..., 3), m
    """
    psi1 = np.asarray(psi1_rad, dtype=np.float64)
    lift = psi1 - np.asarray(psi2_rad, dtype=np.float64)
    phi2 = np.asarray(phi2_rad, dtype=np.float64)
    p1 = upper_arm_m * np.stack([np.zeros_like(psi1), np.cos(psi1), np.sin(psi1)], axis=-1)
    forearm = np.stack([-np.sin(phi2), np.cos(phi2) * np.cos(lift), np.cos(phi2) * np.sin(lift)], axis=-1)
    return p1, p1 + forearm_m * forearm


def wing_points_m(p1_m, p2_m, *, points_per_segment):
    """Scattering points along both segments of both wings, body frame.

    Each segment (shoulder-elbow, elbow-tip) carries ``points_per_segment`` points at the mid-points
    of equal pieces; the second wing mirrors the first in y.

    Returns
    -------
    ndarray, shape (..., 4 * points_per_segment, 3), m
    """
    frac = (np.arange(points_per_segment) + 0.5) / points_per_segment
    upper = frac[:, None] * p1_m[..., None, :]
    fore = p1_m[..., None, :] + frac[:, None] * (p2_m - p1_m)[..., None, :]
    wing = np.concatenate([upper, fore], axis=-2)
    return np.concatenate([wing, wing * np.array([1.0, -1.0, 1.0])], axis=-2)


def body_to_radar_rotation(heading_rad):
    """Rotation matrix (3, 3) from the bird's body frame to the radar frame for a level flight heading.

    ``heading_rad`` is the flight direction's angle from the radar x axis towards +y.
    """
    c, s = np.cos(heading_rad), np.sin(heading_rad)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
