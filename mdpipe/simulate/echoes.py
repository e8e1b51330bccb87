"""Baseband echoes of scene targets at arbitrary times.

Each target gives, at times ``t_s`` of any shape, its complex echo ``s(t)`` in the paper's
convention ``sum a exp(-j 4 pi R / lambda0)`` (lambda0 at the chirp start frequency; the range FFT
then puts the Doppler at the sweep centre, see :mod:`mdpipe.simulate.synth`), the range of its
reference point (body centre) and the unit line of sight. Amplitudes follow the radar equation
``sqrt(rcs) / R^2`` in volts (1 V for 1 m^2 at 1 m).
"""

from dataclasses import dataclass

import numpy as np

from mdpipe.physics import bird as bird_physics
from mdpipe.physics import kinematics, rotor
from mdpipe.physics.radar import SPEED_OF_LIGHT_MPS, doppler_hz, two_way_phase_rad


@dataclass(frozen=True)
class Echo:
    """Echo of one target: ``signal`` (complex, V), ``range_m`` and ``los`` (shape + (3,)) at the same times."""

    signal: np.ndarray
    range_m: np.ndarray
    los: np.ndarray


def _carrier(range_m, f0_hz):
    return np.exp(-1j * two_way_phase_rad(range_m, frequency_hz=f0_hz))


def _body(motion, t_s):
    position = kinematics.body_position_m(t_s, **motion.kwargs)
    return position, kinematics.range_m(position)


def multirotor_echo(target, t_s, *, f0_hz):
    """Body scatterer plus every rotor's blades (closed form, or points when ``points_per_blade`` is set)."""
    wavelength_m = SPEED_OF_LIGHT_MPS / f0_hz
    position, body_range = _body(target.motion, t_s)
    amplitude = 1.0 / body_range**2
    signal = np.sqrt(target.body_rcs_m2) * _carrier(body_range, f0_hz)
    rotors = target.rotors
    cos_beta = np.cos(np.deg2rad(target.elevation_deg))
    blade_scale = np.sqrt(rotors.blade_rcs_m2) / (rotors.blade_length_m - rotors.root_m)
    for rev, layout, phase in zip(rotors.per_rotor("rev_per_s"), rotors.per_rotor("layout_deg"),
                                  rotors.per_rotor("phase_deg")):
        hub_range = body_range + rotors.arm_m * cos_beta * np.cos(np.deg2rad(layout))
        blades = rotor.rotor_echo(t_s, rotation_rate_hz=rev, n_blades=rotors.blades,
                                  blade_length_m=rotors.blade_length_m, root_m=rotors.root_m,
                                  wavelength_m=wavelength_m, elevation_deg=target.elevation_deg,
                                  phase0_rad=np.deg2rad(phase), points_per_blade=rotors.points_per_blade)
        signal = signal + blade_scale * blades * _carrier(hub_range, f0_hz)
    return Echo(amplitude * signal, body_range, kinematics.line_of_sight(position))


def bird_points_m(target, t_s):
    """Radar-frame positions of the bird's scatterers, shape ``t_s.shape + (1 + 4Q, 3)`` (body first)."""
    position = kinematics.body_position_m(t_s, **target.motion.kwargs)
    psi1, psi2, phi2 = bird_physics.flap_angles_rad(t_s, **target.flap_kwargs)
    p1, p2 = bird_physics.wing_joints_m(psi1, psi2, phi2, upper_arm_m=target.upper_arm_m,
                                        forearm_m=target.forearm_m)
    wing = bird_physics.wing_points_m(p1, p2, points_per_segment=target.points_per_segment)
    rotation = bird_physics.body_to_radar_rotation(target.heading_rad)
    points = np.concatenate([np.zeros_like(wing[..., :1, :]), wing @ rotation.T], axis=-2)
    return position[..., None, :] + points


def bird_echo(target, t_s, *, f0_hz):
    """Body point plus ``points_per_segment`` points on each wing segment, each at its own range."""
    points = bird_points_m(target, t_s)
    ranges = kinematics.range_m(points)
    q = target.points_per_segment
    weights = np.concatenate([[np.sqrt(target.body_rcs_m2)], np.full(4 * q, np.sqrt(target.wing_rcs_m2) / (2 * q))])
    signal = np.sum(weights / ranges**2 * _carrier(ranges, f0_hz), axis=-1)
    return Echo(signal, ranges[..., 0], kinematics.line_of_sight(points[..., 0, :]))


def point_echo(target, t_s, *, f0_hz):
    """A moving point scatterer."""
    position, body_range = _body(target.motion, t_s)
    signal = np.sqrt(target.rcs_m2) / body_range**2 * _carrier(body_range, f0_hz)
    return Echo(signal, body_range, kinematics.line_of_sight(position))


def static_echo(target, t_s, *, f0_hz):
    """A fixed point: constant echo."""
    shape = np.shape(t_s)
    position = target.position_m
    value = np.sqrt(target.rcs_m2) / target.range_m**2 * _carrier(target.range_m, f0_hz)
    return Echo(np.full(shape, value, dtype=np.complex128), np.full(shape, target.range_m),
                np.broadcast_to(position / target.range_m, shape + (3,)))


ECHO_MODELS = {"multirotor": multirotor_echo, "bird": bird_echo, "point": point_echo, "static": static_echo}


def target_echo(target, t_s, *, f0_hz):
    """Echo of any scene target at times ``t_s``."""
    return ECHO_MODELS[target.kind](target, np.asarray(t_s, dtype=np.float64), f0_hz=f0_hz)


def body_track(target, t_s):
    """Reference-point position (len(t), 3) and velocity of a target at times ``t_s``."""
    if target.kind == "static":
        shape = np.shape(t_s) + (3,)
        return np.broadcast_to(target.position_m, shape), np.zeros(shape)
    kwargs = target.motion.kwargs
    return kinematics.body_position_m(t_s, **kwargs), kinematics.body_velocity_mps(t_s, **kwargs)


def wing_speed_max_mps(target, *, samples=2048):
    """Largest speed of a wing point relative to the body over one wingbeat (numerical)."""
    t = np.linspace(0.0, 1.0 / target.wingbeat_hz, samples + 1)
    points = bird_points_m(target, t)
    still = points - points[:, :1, :]
    speed = np.linalg.norm(np.gradient(still, t, axis=0), axis=-1)
    return float(speed.max())


def max_doppler_hz(target, position_m, velocity_mps, *, wavelength_m):
    """Bound on |Doppler| of any scatterer of the target along its body track (Hz).

    ``position_m`` and ``velocity_mps`` (T, 3) are the track from :func:`body_track`.
    """
    body = float(np.max(np.abs(doppler_hz(kinematics.range_rate_mps(position_m, velocity_mps),
                                           wavelength_m=wavelength_m)), initial=0.0))
    if target.kind == "multirotor":
        rotors = target.rotors
        return body + float(np.max(rotor.tip_doppler_hz(rotors.per_rotor("rev_per_s"),
                                                        blade_length_m=rotors.blade_length_m,
                                                        wavelength_m=wavelength_m,
                                                        elevation_deg=target.elevation_deg)))
    if target.kind == "bird":
        return body + 2.0 * wing_speed_max_mps(target) / wavelength_m
    return body


def peak_amplitude_v(target, min_range_m):
    """Upper bound of |echo| (triangle inequality over the scatterers, each at its closest possible range)."""
    if target.kind == "multirotor":
        r = target.rotors
        total = np.sqrt(target.body_rcs_m2) + r.count * r.blades * np.sqrt(r.blade_rcs_m2)
        reach_m = r.arm_m + r.blade_length_m
    elif target.kind == "bird":
        total = np.sqrt(target.body_rcs_m2) + 2 * np.sqrt(target.wing_rcs_m2)
        reach_m = target.upper_arm_m + target.forearm_m
    else:  # point, static
        total, reach_m = np.sqrt(target.rcs_m2), 0.0
    return float(total / max(min_range_m - reach_m, 0.5 * min_range_m) ** 2)
