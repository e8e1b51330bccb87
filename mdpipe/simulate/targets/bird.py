"""A flapping bird on a level straight flight (paper Eqs. 7-15; angles in degrees).

Realism beyond the paper's steady flapping, each off by default:

* ``flap_glide``: bursts of ``flap_s`` flapping and ``glide_s`` gliding with the wings held at the mean
  pose, smooth transitions (:func:`mdpipe.physics.bird.flap_glide_envelope`);
* ``wingbeat_drift_fraction`` d: the wingbeat changes linearly by ``d wingbeat_hz`` across the capture,
  its mean over the capture staying ``wingbeat_hz`` (phase integrated,
  :func:`mdpipe.physics.bird.wingbeat_phase_rad`);
* ``wing_roughness`` r: every wing scatterer's amplitude and phase fluctuate as ``exp(r (a_q(t) + j b_q(t)))``
  with ``a_q``, ``b_q`` seeded smooth processes of unit rms and one wingbeat's correlation time
  (a rough, not mirror-smooth wing: log-amplitude and phase each of rms r).
"""

from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from mdpipe.physics import bird as bird_physics
from mdpipe.physics import kinematics
from mdpipe.physics.radar import doppler_hz
from mdpipe.simulate.random_process import SmoothProcess, target_rng
from mdpipe.simulate.schema import NON_NEGATIVE, POSITIVE, check
from mdpipe.simulate.targets.common import Echo, Motion, amplitude_bound_v, body_track, carrier  # noqa: F401

MAX_DRIFT_FRACTION = 1.0
STROKE_GRID = 2049


@dataclass(frozen=True)
class FlapGlide:
    """Flap-glide bursts: ``flap_s`` of flapping, then ``glide_s`` of gliding, repeated."""

    flap_s: float = field(metadata=POSITIVE)
    glide_s: float = field(metadata=POSITIVE)


@dataclass(frozen=True)
class Target:
    """A flapping bird: body point and two two-segment wings."""

    motion: Motion
    wingbeat_hz: float = field(metadata=POSITIVE)
    upper_arm_m: float = field(metadata=POSITIVE)
    forearm_m: float = field(metadata=POSITIVE)
    name: str = "bird"
    a1_deg: float = 40.0
    a2_deg: Optional[float] = None
    psi10_deg: float = 15.0
    psi20_deg: float = 20.0
    c2_deg: float = 20.0
    phi20_deg: float = 0.0
    heading_deg: Optional[float] = None
    body_rcs_m2: float = field(default=1e-2, metadata=NON_NEGATIVE)
    wing_rcs_m2: float = field(default=5e-3, metadata=POSITIVE)
    points_per_segment: int = field(default=3, metadata=check(lambda v: v >= 1, ">= 1"))
    flap_glide: Optional[FlapGlide] = None
    wingbeat_drift_fraction: float = field(default=0.0, metadata=check(
        lambda v: -MAX_DRIFT_FRACTION <= v <= MAX_DRIFT_FRACTION, f"within [-{MAX_DRIFT_FRACTION:g}, "
                                                                  f"{MAX_DRIFT_FRACTION:g}]"))
    wing_roughness: float = field(default=0.0, metadata=NON_NEGATIVE)
    kind = "bird"
    expected_class = "bird"

    @property
    def flap_kwargs(self):
        """Keyword arguments of :func:`mdpipe.physics.bird.flap_angles_rad` (A2 defaults to A1)."""
        return dict(wingbeat_hz=self.wingbeat_hz, **self.pose_kwargs)

    @property
    def pose_kwargs(self):
        """Keyword arguments of :func:`mdpipe.physics.bird.flap_angles_from_beat_rad`."""
        return dict(a1_deg=self.a1_deg, a2_deg=self.a1_deg if self.a2_deg is None else self.a2_deg,
                    psi10_deg=self.psi10_deg, psi20_deg=self.psi20_deg, c2_deg=self.c2_deg,
                    phi20_deg=self.phi20_deg)

    @property
    def heading_rad(self):
        """Flight direction in the horizontal plane: given, else along the horizontal velocity, else +x."""
        if self.heading_deg is not None:
            return np.deg2rad(self.heading_deg)
        vx, vy, _ = self.motion.velocity_mps
        return float(np.arctan2(vy, vx)) if (vx, vy) != (0.0, 0.0) else 0.0

    @property
    def steady(self):
        """True for the paper's steady flapping (no bursts, no drift)."""
        return self.flap_glide is None and self.wingbeat_drift_fraction == 0.0

    def ramp_s(self):
        """Flap-glide transition length (s)."""
        fg = self.flap_glide
        return bird_physics.flap_glide_ramp_s(wingbeat_hz=self.wingbeat_hz, flap_s=fg.flap_s, glide_s=fg.glide_s)


@dataclass(frozen=True)
class Realization:
    """The capture length (the drift is defined over it) and the wing roughness processes (or None)."""

    duration_s: float
    roughness: Optional[SmoothProcess]
    max_log_gain: float


def realize(target, *, seed, index, duration_s):
    if target.wing_roughness == 0.0:
        return Realization(duration_s, None, 0.0)
    n_points = 4 * target.points_per_segment
    process = SmoothProcess(target_rng(seed, index, 0), 2 * n_points, correlation_s=1.0 / target.wingbeat_hz,
                            duration_s=duration_s)
    return Realization(duration_s, process, max(process.max_abs(q) for q in range(n_points)))


def stroke(target, realization, t_s):
    """The stroke ``envelope(t) cos(phase(t))`` in [-1, 1] (0 = the mean pose, the glide)."""
    phase = bird_physics.wingbeat_phase_rad(t_s, wingbeat_hz=target.wingbeat_hz,
                                            drift_fraction=target.wingbeat_drift_fraction,
                                            duration_s=realization.duration_s)
    beat = np.cos(phase)
    if target.flap_glide is not None:
        beat = beat * bird_physics.flap_glide_envelope(t_s, flap_s=target.flap_glide.flap_s,
                                                       glide_s=target.flap_glide.glide_s, ramp_s=target.ramp_s())
    return beat


def _wing_body_frame_m(target, angles):
    p1, p2 = bird_physics.wing_joints_m(*angles, upper_arm_m=target.upper_arm_m, forearm_m=target.forearm_m)
    return bird_physics.wing_points_m(p1, p2, points_per_segment=target.points_per_segment)


def points_m(target, realization, t_s, *, steady=False):
    """Radar-frame positions of the bird's scatterers, shape ``t_s.shape + (1 + 4Q, 3)`` (body first).

    ``steady`` flaps at ``wingbeat_hz`` throughout, ignoring bursts and drift.
    """
    position = target.motion.position(t_s)
    if steady or target.steady:
        angles = bird_physics.flap_angles_rad(t_s, **target.flap_kwargs)
    else:
        angles = bird_physics.flap_angles_from_beat_rad(stroke(target, realization, t_s), **target.pose_kwargs)
    wing = _wing_body_frame_m(target, angles)
    rotation = bird_physics.body_to_radar_rotation(target.heading_rad)
    points = np.concatenate([np.zeros_like(wing[..., :1, :]), wing @ rotation.T], axis=-2)
    return position[..., None, :] + points


def echo(target, realization, t_s, *, f0_hz):
    """Body point plus ``points_per_segment`` points on each wing segment, each at its own range."""
    points = points_m(target, realization, t_s)
    ranges = kinematics.range_m(points)
    q = target.points_per_segment
    weights = np.concatenate([[np.sqrt(target.body_rcs_m2)], np.full(4 * q, np.sqrt(target.wing_rcs_m2) / (2 * q))])
    terms = weights / ranges**2 * carrier(ranges, f0_hz)
    if realization.roughness is not None:
        r, n = target.wing_roughness, 4 * q
        for k in range(n):
            log_gain = realization.roughness.value(t_s, k) + 1j * realization.roughness.value(t_s, n + k)
            terms[..., 1 + k] *= np.exp(r * log_gain)
    return Echo(np.sum(terms, axis=-1), ranges[..., 0], kinematics.line_of_sight(points[..., 0, :]))


def wing_speed_max_mps(target, *, samples=2048):
    """Largest speed of a wing point relative to the body over one steady wingbeat at ``wingbeat_hz`` (numerical)."""
    t = np.linspace(0.0, 1.0 / target.wingbeat_hz, samples + 1)
    points = points_m(target, None, t, steady=True)
    still = points - points[:, :1, :]
    speed = np.linalg.norm(np.gradient(still, t, axis=0), axis=-1)
    return float(speed.max())


def largest_wingbeat_hz(target):
    return target.wingbeat_hz * (1.0 + 0.5 * abs(target.wingbeat_drift_fraction))


def wing_speed_bound_mps(target):
    """Bound on the speed of a wing point relative to the body.

    Steady flapping: the numerical maximum over a wingbeat, scaled by the largest wingbeat over the
    drift. Flap-glide: every angle is ``mean + amplitude s(t)`` with the stroke ``s = e cos(phase)``, so
    the speed is at most ``max_s |dP/ds| (max |e'| + 2 pi f_max)``, ``max |e'| = pi / (2 ramp)``.
    """
    if target.flap_glide is None:
        return wing_speed_max_mps(target) * (largest_wingbeat_hz(target) / target.wingbeat_hz)
    s = np.linspace(-1.0, 1.0, STROKE_GRID)
    wing = _wing_body_frame_m(target, bird_physics.flap_angles_from_beat_rad(s, **target.pose_kwargs))
    per_stroke = float(np.linalg.norm(np.gradient(wing, s, axis=0), axis=-1).max())
    return per_stroke * (np.pi / (2.0 * target.ramp_s()) + 2.0 * np.pi * largest_wingbeat_hz(target))


def micro_doppler_bound_hz(target, realization, *, wavelength_m):
    """Wing points relative to the body, plus the roughness's own modulation rate."""
    bound = 2.0 * wing_speed_bound_mps(target) / wavelength_m
    if realization.roughness is not None:
        n = 4 * target.points_per_segment
        slopes = [realization.roughness.slope_bound(k) + realization.roughness.slope_bound(n + k) for k in range(n)]
        bound += target.wing_roughness * max(slopes) / (2.0 * np.pi)
    return bound


def peak_amplitude_v(target, realization, min_range_m):
    total = np.sqrt(target.body_rcs_m2) + 2 * np.sqrt(target.wing_rcs_m2) * np.exp(
        target.wing_roughness * realization.max_log_gain)
    return amplitude_bound_v(total, target.upper_arm_m + target.forearm_m, min_range_m)


def truth(target, realization, *, radar, n_chirps, body_doppler_hz):
    """Wingbeat (mean over the capture), flapping share, and the scatterers' Doppler spread and extent."""
    duration_s = n_chirps * radar.chirp_period_s
    step_s = min(radar.chirp_period_s * max(1, n_chirps // 20000), 1.0 / (200.0 * largest_wingbeat_hz(target)))
    t_s = np.arange(0.0, duration_s, step_s)
    ranges = kinematics.range_m(points_m(target, realization, t_s))
    point_doppler = doppler_hz(np.gradient(ranges, t_s, axis=0), wavelength_m=radar.wavelength_m)
    spread = point_doppler.max(axis=1) - point_doppler.min(axis=1)
    drift = target.wingbeat_drift_fraction
    start_hz, end_hz = bird_physics.wingbeat_rate_hz([0.0, duration_s], wingbeat_hz=target.wingbeat_hz,
                                                     drift_fraction=drift, duration_s=duration_s)
    fg = target.flap_glide
    return {
        "wingbeat_freq_hz": target.wingbeat_hz,
        "wingbeat_period_s": 1.0 / target.wingbeat_hz,
        "wingbeat_drift_fraction": drift,
        "wingbeat_start_hz": float(start_hz),
        "wingbeat_end_hz": float(end_hz),
        "flapping_share": 1.0 if fg is None else bird_physics.flapping_share(duration_s, flap_s=fg.flap_s,
                                                                             glide_s=fg.glide_s),
        "flap_s": None if fg is None else fg.flap_s,
        "glide_s": None if fg is None else fg.glide_s,
        "a1_deg": target.a1_deg,
        "a2_deg": target.pose_kwargs["a2_deg"],
        "wing_roughness": target.wing_roughness,
        "micro_doppler_spread_hz": float(spread.max()),
        "micro_doppler_spread_mps": float(spread.max() * radar.wavelength_m / 2.0),
        "doppler_extent_hz": [float(point_doppler.min()), float(point_doppler.max())],
    }
