"""A swaying branch with leaves: wind-driven clutter that moves but is neither a drone nor a bird.

The branch point sways about ``position_m`` (its mean position) as a sum of three sinusoids at
``sway_hz`` times 1, sqrt(2) and sqrt(5) (incommensurate: the motion never repeats exactly) along
seeded random directions with seeded phases. Their amplitudes are
``sway_amplitude_m (0.6, 0.25 / sqrt(2), 0.15 / sqrt(5))``, so the sway speed never exceeds
``2 pi sway_hz sway_amplitude_m``. Each of ``leaves`` leaves sits at a seeded offset within
``leaf_spread_m`` of the branch point, moves with it and flutters along its own direction with
amplitude ``leaf_flutter_m`` at a frequency drawn in ``[0.8, 1] leaf_flutter_hz``. Every motion is a
sum of sinusoids: zero mean velocity, and any scatterer's speed is at most
``2 pi (sway_hz sway_amplitude_m + leaf_flutter_hz leaf_flutter_m)``.
"""

from dataclasses import dataclass, field

import numpy as np

from mdpipe.errors import ParameterError
from mdpipe.physics import kinematics
from mdpipe.simulate.random_process import target_rng
from mdpipe.simulate.schema import NON_NEGATIVE, POSITIVE, Vec3, check
from mdpipe.simulate.targets.common import Echo, amplitude_bound_v, point_signal

SWAY_RATIOS = np.array([1.0, np.sqrt(2.0), np.sqrt(5.0)])
SWAY_SPEED_SHARES = np.array([0.6, 0.25, 0.15])  # of the speed bound 2 pi f A; they sum to 1
LEAF_FREQUENCY_RANGE = (0.8, 1.0)


MAX_LEAVES = 1000


@dataclass(frozen=True)
class Target:
    """A branch (one scatterer) with leaves (point scatterers), swaying in the wind."""

    position_m: Vec3
    name: str = "branch"
    rcs_m2: float = field(default=0.5, metadata=POSITIVE)
    sway_amplitude_m: float = field(default=0.05, metadata=NON_NEGATIVE)
    sway_hz: float = field(default=0.8, metadata=POSITIVE)
    leaves: int = field(default=20, metadata=check(lambda v: 0 <= v <= MAX_LEAVES, f"from 0 to {MAX_LEAVES}"))
    leaf_flutter_hz: float = field(default=4.0, metadata=POSITIVE)
    leaf_flutter_m: float = field(default=0.01, metadata=NON_NEGATIVE)
    leaf_rcs_m2: float = field(default=1e-3, metadata=POSITIVE)
    leaf_spread_m: float = field(default=0.3, metadata=NON_NEGATIVE)
    kind = "branch"
    expected_class = "none"

    def __post_init__(self):
        if np.linalg.norm(self.position_m) == 0:
            raise ParameterError("position_m must not be the radar's own position [0, 0, 0]")

    def speed_bound_mps(self):
        """Largest speed of any scatterer: ``2 pi (sway_hz sway_amplitude_m + leaf_flutter_hz leaf_flutter_m)``."""
        return 2.0 * np.pi * (self.sway_hz * self.sway_amplitude_m + self.leaf_flutter_hz * self.leaf_flutter_m)


def _unit_vectors(rng, n):
    v = rng.normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1, keepdims=True)


@dataclass(frozen=True)
class Realization:
    """Drawn sway directions and phases, leaf offsets, flutter directions, frequencies and phases."""

    sway_directions: np.ndarray  # (3, 3)
    sway_phases_rad: np.ndarray  # (3,)
    leaf_offsets_m: np.ndarray  # (leaves, 3)
    leaf_directions: np.ndarray  # (leaves, 3)
    leaf_freqs_hz: np.ndarray  # (leaves,)
    leaf_phases_rad: np.ndarray  # (leaves,)


def realize(target, *, seed, index, duration_s):
    rng = target_rng(seed, index, 0)
    n = target.leaves
    radius = target.leaf_spread_m * rng.uniform(0.0, 1.0, n) ** (1.0 / 3.0)  # uniform in the ball
    return Realization(
        sway_directions=_unit_vectors(rng, len(SWAY_RATIOS)), sway_phases_rad=rng.uniform(0, 2 * np.pi, 3),
        leaf_offsets_m=radius[:, None] * _unit_vectors(rng, n), leaf_directions=_unit_vectors(rng, n),
        leaf_freqs_hz=target.leaf_flutter_hz * rng.uniform(*LEAF_FREQUENCY_RANGE, n),
        leaf_phases_rad=rng.uniform(0, 2 * np.pi, n))


def _sinusoids(t_s, freqs_hz, phases_rad, amplitudes, directions):
    """Sum of ``a_k d_k sin(2 pi f_k t + phi_k)`` and its derivative, shape ``t.shape + (3,)`` each."""
    arg = 2.0 * np.pi * np.asarray(t_s, dtype=np.float64)[..., None] * freqs_hz + phases_rad
    position = (amplitudes * np.sin(arg)) @ directions
    velocity = (amplitudes * 2.0 * np.pi * freqs_hz * np.cos(arg)) @ directions
    return position, velocity


def body_track(target, realization, t_s):
    """The branch point: mean position plus the sway."""
    freqs = target.sway_hz * SWAY_RATIOS
    amplitudes = target.sway_amplitude_m * SWAY_SPEED_SHARES / SWAY_RATIOS
    sway, velocity = _sinusoids(t_s, freqs, realization.sway_phases_rad, amplitudes, realization.sway_directions)
    return np.asarray(target.position_m) + sway, velocity


def echo(target, realization, t_s, *, f0_hz):
    position, _ = body_track(target, realization, t_s)
    branch_range = kinematics.range_m(position)
    signal = point_signal(branch_range, target.rcs_m2, f0_hz)
    for k in range(target.leaves):
        arg = 2.0 * np.pi * realization.leaf_freqs_hz[k] * t_s + realization.leaf_phases_rad[k]
        flutter = target.leaf_flutter_m * np.sin(arg)[..., None] * realization.leaf_directions[k]
        leaf_range = kinematics.range_m(position + realization.leaf_offsets_m[k] + flutter)
        signal = signal + point_signal(leaf_range, target.leaf_rcs_m2, f0_hz)
    return Echo(signal, branch_range, kinematics.line_of_sight(position))


def micro_doppler_bound_hz(target, realization, *, wavelength_m):
    """Leaves relative to the branch point: ``2 (2 pi leaf_flutter_hz leaf_flutter_m) / lambda``."""
    return 2.0 * 2.0 * np.pi * target.leaf_flutter_hz * target.leaf_flutter_m / wavelength_m if target.leaves else 0.0


def peak_amplitude_v(target, realization, min_range_m):
    total = np.sqrt(target.rcs_m2) + target.leaves * np.sqrt(target.leaf_rcs_m2)
    return amplitude_bound_v(total, target.leaf_spread_m + target.leaf_flutter_m, min_range_m)


def truth(target, realization, *, radar, n_chirps, body_doppler_hz):
    """The speed bound and the Doppler extent it allows (zero-mean motion)."""
    bound_hz = 2.0 * target.speed_bound_mps() / radar.wavelength_m
    return {
        "sway_hz": target.sway_hz,
        "sway_amplitude_m": target.sway_amplitude_m,
        "leaf_flutter_hz": target.leaf_flutter_hz,
        "n_leaves": target.leaves,
        "speed_bound_mps": target.speed_bound_mps(),
        "doppler_extent_hz": [-bound_hz, bound_hz],
    }
