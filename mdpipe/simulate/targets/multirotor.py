"""A multirotor drone: a body (one centre scatterer plus any rigid scatterers) and rotors in one plane.

Each rotor turns at its own rate, optionally wandering slowly as attitude control does: rotor i's rate
is ``rev_i (1 + fraction w_i(t))`` with ``w_i`` a seeded smooth process of zero mean and unit rms over
the capture and correlation time ``rate_wander_period_s`` (:mod:`mdpipe.simulate.random_process`); its
blade angle is the integral, ``2 pi rev_i (t + fraction int_0^t w_i) + phase_i``. Blades reflect
uniformly, tapered or as Eq. 1 points (:func:`mdpipe.physics.rotor.blade_echoes`), each scaled by its
``blade_gains`` entry; rotor i's disc is seen at ``elevation_deg + tilt_deg[i]``.
"""

from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from mdpipe.errors import ParameterError
from mdpipe.params import MAX_BLADES
from mdpipe.physics import kinematics, rotor
from mdpipe.physics.radar import SPEED_OF_LIGHT_MPS
from mdpipe.simulate.random_process import SmoothProcess, target_rng
from mdpipe.simulate.schema import NON_NEGATIVE, POSITIVE, Vec3, check
from mdpipe.simulate.targets.common import Echo, Motion, amplitude_bound_v, body_track, carrier  # noqa: F401

MAX_BLADE_LENGTH_M = 2.0
MAX_RATE_WANDER_FRACTION = 0.3


MAX_ROTORS = 16            # a coaxial octocopter's
MAX_POINTS_PER_BLADE = 256


@dataclass(frozen=True)
class Rotors:
    """The rotors of a multirotor; per-rotor entries take one value for all or one per rotor."""

    count: int = field(metadata=check(lambda v: 1 <= v <= MAX_ROTORS, f"from 1 to {MAX_ROTORS}"))
    blade_length_m: float = field(metadata=POSITIVE)
    rev_per_s: tuple[float, ...] = field(metadata=check(lambda v: v != 0, "non-zero (sign = spin direction)"))
    blades: int = field(default=2, metadata=check(lambda v: 1 <= v <= MAX_BLADES, f"from 1 to {MAX_BLADES}"))
    root_m: float = field(default=0.0, metadata=NON_NEGATIVE)
    arm_m: float = field(default=0.0, metadata=NON_NEGATIVE)
    layout_deg: Optional[tuple[float, ...]] = None
    phase_deg: tuple[float, ...] = (0.0,)
    blade_rcs_m2: float = field(default=1e-3, metadata=POSITIVE)
    points_per_blade: Optional[int] = field(default=None, metadata=check(lambda v: 1 <= v <= MAX_POINTS_PER_BLADE,
                                                                          f"from 1 to {MAX_POINTS_PER_BLADE}"))
    blade_profile: Optional[str] = field(default=None, metadata=check(lambda v: v in rotor.BLADE_PROFILES,
                                                                      "one of uniform, tapered, points"))
    tip_reflectivity: float = field(default=0.3, metadata=check(lambda v: 0 <= v <= 1, "within [0, 1]"))
    blade_gains: tuple[float, ...] = field(default=(1.0,), metadata=NON_NEGATIVE)
    tilt_deg: tuple[float, ...] = field(default=(0.0,), metadata=check(lambda v: -90 <= v <= 90,
                                                                       "within [-90, 90]"))
    rate_wander_fraction: float = field(default=0.0, metadata=check(
        lambda v: 0 <= v <= MAX_RATE_WANDER_FRACTION, f"within [0, {MAX_RATE_WANDER_FRACTION}] (more would stop "
                                                      "or reverse a rotor)"))
    rate_wander_period_s: float = field(default=1.0, metadata=POSITIVE)

    def __post_init__(self):
        if self.root_m >= self.blade_length_m:
            raise ParameterError(f"root_m={self.root_m} must be shorter than blade_length_m={self.blade_length_m}")
        for name in ("rev_per_s", "phase_deg", "layout_deg", "tilt_deg"):
            values = getattr(self, name)
            if values is not None and len(values) not in (1, self.count):
                raise ParameterError(f"{name} has {len(values)} entries; give 1 or count={self.count}")
        if len(self.blade_gains) not in (1, self.blades):
            raise ParameterError(f"blade_gains has {len(self.blade_gains)} entries; give 1 or blades={self.blades}")
        if not any(self.blade_gains):
            raise ParameterError("blade_gains are all 0: the blades would not reflect")
        if self.blade_profile == "points" and self.points_per_blade is None:
            raise ParameterError("blade_profile points needs points_per_blade (the Q of Eq. 1)")
        if self.blade_profile not in (None, "points") and self.points_per_blade is not None:
            raise ParameterError(f"points_per_blade applies to blade_profile points, not {self.blade_profile}")
        if self.blade_length_m > MAX_BLADE_LENGTH_M:
            raise ParameterError(f"blade_length_m={self.blade_length_m} m is longer than any drone blade "
                                 f"(at most {MAX_BLADE_LENGTH_M} m); did you mean {self.blade_length_m / 100:g} m?")
        tip_speed = 2.0 * np.pi * float(np.max(np.abs(self.rev_per_s))) * self.blade_length_m
        if tip_speed > rotor.SPEED_OF_SOUND_MPS:
            raise ParameterError(f"blade tips would move at 2 pi x {np.max(np.abs(self.rev_per_s)):g} rev/s x "
                                 f"{self.blade_length_m:g} m = {tip_speed:.0f} m/s, faster than sound "
                                 f"({rotor.SPEED_OF_SOUND_MPS:.0f} m/s); check rev_per_s and blade_length_m")

    @property
    def profile(self):
        """The blade profile: given, else ``points`` when ``points_per_blade`` is set, else ``uniform``."""
        if self.blade_profile is not None:
            return self.blade_profile
        return "uniform" if self.points_per_blade is None else "points"

    @property
    def gains(self):
        """Amplitude factor of each blade, shape (blades,)."""
        return np.broadcast_to(np.asarray(self.blade_gains, dtype=np.float64), (self.blades,))

    def per_rotor(self, name):
        """Values of per-rotor entry ``name`` as an array of length ``count``."""
        values = getattr(self, name)
        if values is None:  # layout: evenly spaced, first arm at 45 deg (an X quad)
            return 45.0 + 360.0 * np.arange(self.count) / self.count
        return np.broadcast_to(np.asarray(values, dtype=np.float64), (self.count,))


@dataclass(frozen=True)
class BodyScatterer:
    """A scatterer rigid with the body, ``offset_m`` from its centre in the radar frame."""

    offset_m: Vec3
    rcs_m2: float = field(metadata=POSITIVE)


@dataclass(frozen=True)
class Target:
    """A multirotor drone: a body scatterer and rotors in one plane seen at elevation beta."""

    motion: Motion
    rotors: Rotors
    name: str = "drone"
    elevation_deg: float = field(default=0.0, metadata=check(lambda v: -90 <= v <= 90, "within [-90, 90]"))
    body_rcs_m2: float = field(default=1e-2, metadata=NON_NEGATIVE)
    body_scatterers: tuple[BodyScatterer, ...] = ()
    kind = "multirotor"
    expected_class = "drone"

    def rotor_elevations_deg(self):
        """Elevation of each rotor's disc: the target's plus the rotor's tilt, shape (count,)."""
        return self.elevation_deg + self.rotors.per_rotor("tilt_deg")


@dataclass(frozen=True)
class RateWander:
    """Realised rate wander of the rotors: ``w_i`` and the bound on ``|w_i|`` over the capture."""

    fraction: float
    process: SmoothProcess
    max_abs: np.ndarray

    def rotor_time_s(self, t_s, index):
        """``t + fraction int_0^t w_i``: the time at which a steady rotor would have turned as far."""
        return t_s + self.fraction * self.process.integral(t_s, index)


def realize(target, *, seed, index, duration_s):
    """The rotors' rate wander (None without wander)."""
    rotors = target.rotors
    if rotors.rate_wander_fraction == 0.0:
        return None
    process = SmoothProcess(target_rng(seed, index, 0), rotors.count, correlation_s=rotors.rate_wander_period_s,
                            duration_s=duration_s)
    return RateWander(rotors.rate_wander_fraction, process,
                      np.array([process.max_abs(i) for i in range(rotors.count)]))


def echo(target, realization, t_s, *, f0_hz):
    """Body scatterers plus every rotor's blades, each rotor at its hub's range."""
    wavelength_m = SPEED_OF_LIGHT_MPS / f0_hz
    position = target.motion.position(t_s)
    body_range = kinematics.range_m(position)
    amplitude = 1.0 / body_range**2
    signal = np.sqrt(target.body_rcs_m2) * carrier(body_range, f0_hz)
    for scatterer in target.body_scatterers:
        signal = signal + np.sqrt(scatterer.rcs_m2) * carrier(
            kinematics.range_m(position + np.asarray(scatterer.offset_m)), f0_hz)
    rotors = target.rotors
    cos_beta = np.cos(np.deg2rad(target.elevation_deg))
    blade_scale = np.sqrt(rotors.blade_rcs_m2) / (rotors.blade_length_m - rotors.root_m)
    gains = None if np.all(rotors.gains == 1.0) else rotors.gains
    for i, (rev, layout, phase, elevation) in enumerate(zip(
            rotors.per_rotor("rev_per_s"), rotors.per_rotor("layout_deg"), rotors.per_rotor("phase_deg"),
            target.rotor_elevations_deg())):
        hub_range = body_range + rotors.arm_m * cos_beta * np.cos(np.deg2rad(layout))
        turn_t = t_s if realization is None else realization.rotor_time_s(t_s, i)
        theta = rotor.blade_angles_rad(turn_t, rotation_rate_hz=rev, n_blades=rotors.blades,
                                       phase0_rad=np.deg2rad(phase))
        blades = rotor.blade_echoes(theta, blade_length_m=rotors.blade_length_m, wavelength_m=wavelength_m,
                                    elevation_deg=elevation, root_m=rotors.root_m, profile=rotors.profile,
                                    tip_reflectivity=rotors.tip_reflectivity,
                                    points_per_blade=rotors.points_per_blade)
        blades = blades.sum(axis=-1) if gains is None else blades @ gains
        signal = signal + blade_scale * blades * carrier(hub_range, f0_hz)
    return Echo(amplitude * signal, body_range, kinematics.line_of_sight(position))


def largest_rates_hz(target, realization):
    """Bound on each rotor's |rate| over the capture (rev/s), shape (count,)."""
    rates = np.abs(target.rotors.per_rotor("rev_per_s"))
    return rates if realization is None else rates * (1.0 + realization.fraction * realization.max_abs)


def micro_doppler_bound_hz(target, realization, *, wavelength_m):
    """The fastest blade tip's Doppler (Eq. 6's half-width at the largest rate and smallest elevation)."""
    rotors = target.rotors
    return float(np.max(rotor.tip_doppler_hz(largest_rates_hz(target, realization),
                                             blade_length_m=rotors.blade_length_m, wavelength_m=wavelength_m,
                                             elevation_deg=target.rotor_elevations_deg())))


def peak_amplitude_v(target, realization, min_range_m):
    r = target.rotors
    total = np.sqrt(target.body_rcs_m2) + r.count * float(np.sum(r.gains)) * np.sqrt(r.blade_rcs_m2)
    reach_m = r.arm_m + r.blade_length_m
    for scatterer in target.body_scatterers:
        total = total + np.sqrt(scatterer.rcs_m2)
        reach_m = max(reach_m, float(np.linalg.norm(scatterer.offset_m)))
    return amplitude_bound_v(total, reach_m, min_range_m)


def truth(target, realization, *, radar, n_chirps, body_doppler_hz):
    """Per-rotor rates and chopping, Eq. 6 bandwidth and tip Doppler, the blades' description."""
    rotors = target.rotors
    lam = radar.wavelength_m
    rates = np.abs(rotors.per_rotor("rev_per_s"))  # mean rates: the wander has zero mean over the capture
    rate = float(np.median(rates))
    elevations = target.rotor_elevations_deg()
    tips = rotor.tip_doppler_hz(rates, blade_length_m=rotors.blade_length_m, wavelength_m=lam,
                                elevation_deg=elevations)
    tip = float(np.max(tips))
    bandwidth = 2.0 * tip
    chopping = float(rotor.chopping_frequency_hz(rate, n_blades=rotors.blades))
    gains = rotors.gains
    return {
        "n_blades": rotors.blades,
        "n_rotors": rotors.count,
        "blade_length_m": rotors.blade_length_m,
        "elevation_deg": target.elevation_deg,
        "tilt_deg": rotors.per_rotor("tilt_deg").tolist(),
        "rotor_elevations_deg": elevations.tolist(),
        "rotor_rates_hz": rates.tolist(),
        "rotation_rate_hz": rate,
        "rotation_period_s": 1.0 / rate,
        "chopping_freq_hz": chopping,
        "rotor_chopping_freqs_hz": rotor.chopping_frequency_hz(rates, n_blades=rotors.blades).tolist(),
        "chopping_aliased": bool(chopping > 0.5 * radar.doppler_span_hz),
        "flashes_per_revolution": rotor.flashes_per_revolution(rotors.blades),
        "flash_period_s": float(rotor.flash_period_s(rate, n_blades=rotors.blades)),
        "tip_doppler_hz": tip,
        "doppler_bw_hz": bandwidth,
        "doppler_bw_mps": bandwidth * lam / 2.0,
        "blade_profile": rotors.profile,
        "tip_reflectivity": rotors.tip_reflectivity if rotors.profile == "tapered" else 1.0,
        "points_per_blade": rotors.points_per_blade if rotors.profile == "points" else None,
        "blade_gains": gains.tolist(),
        "blade_imbalance": bool(np.ptp(gains) > 0),
        "rate_wander_fraction": rotors.rate_wander_fraction,
        "rate_wander_period_s": rotors.rate_wander_period_s,
        "rate_wander_rms_hz": (rotors.rate_wander_fraction * rates).tolist(),
        "n_body_scatterers": len(target.body_scatterers),
        "doppler_extent_hz": [float(body_doppler_hz.min() - tip), float(body_doppler_hz.max() + tip)],
    }
