"""Chirp matrices from target echoes: the FMCW synthesis engine.

The real IF of chirp m at fast time tau_n is ``Re{ sum_t s_t(t_m + tau_n) exp(-j 2 pi f_b,t tau_n) }``:
with ``s = exp(-j 4 pi f0 R / c)`` and ``f_b = 2 S R / c`` this is ``cos(2 pi (f0 + S tau) 2 R / c)``, the
beat signal of a point at range R (residual video phase dropped). The range FFT of a stationary point
then carries the phase ``4 pi f_centre R / c``, so its Doppler follows the sweep's centre frequency.
The scatterers of one target share the beat frequency of its reference point; their spread in range
(at most the blade or wing reach) moves the tone by ``2 B reach / c`` of a bin (0.03 for a 10.5 cm
blade at 40 MHz), which is neglected.

Each target's echo is evaluated at K nodes per chirp and interpolated across the ramp by a fixed
(K, N) Lagrange basis (see :mod:`mdpipe.simulate.fidelity`), so a chunk of chirps is one real matrix
product per channel: ``[Re G, -Im G] @ [Re B; Im B]``. Arrays here are (channel, chirp, sample),
the order in which the file stores them.
"""

from dataclasses import dataclass

import numpy as np

from mdpipe.physics import kinematics
from mdpipe.physics.radar import SPEED_OF_LIGHT_MPS, beat_frequency_hz
from mdpipe.simulate.fidelity import choose_model
from mdpipe.simulate.targets import module_of, realize_all, target_echo

CHUNK_CHIRPS = 512


def chebyshev_nodes_s(count, duration_s):
    """``count`` Chebyshev nodes on [0, duration_s]; a single node sits at mid-interval."""
    k = np.arange(count)
    return 0.5 * duration_s * (1.0 - np.cos((2 * k + 1) * np.pi / (2 * count)))


def lagrange_basis(nodes_s, times_s):
    """Matrix (K, N) whose row k is the Lagrange polynomial of node k evaluated at ``times_s``.

    Barycentric form on nodes and times mapped to [-1, 1] (the basis is invariant under that map,
    and the weights stay well scaled).
    """
    nodes = np.asarray(nodes_s, dtype=np.float64)
    times = np.asarray(times_s, dtype=np.float64)
    if len(nodes) == 1:
        return np.ones((1, len(times)))
    centre, half = 0.5 * (nodes.max() + nodes.min()), 0.5 * (nodes.max() - nodes.min())
    x, t = (nodes - centre) / half, (times - centre) / half
    differences = x[:, None] - x[None, :]
    np.fill_diagonal(differences, 1.0)
    weights = 1.0 / differences.prod(axis=1)
    offsets = t[None, :] - x[:, None]
    on_node = offsets == 0.0
    terms = weights[:, None] / np.where(on_node, 1.0, offsets)
    basis = terms / terms.sum(axis=0)
    hit = on_node.any(axis=0)
    basis[:, hit] = on_node[:, hit]
    return basis


@dataclass(frozen=True)
class TargetPlan:
    """A target with its seeded draws, chosen model, interpolation nodes (s within the ramp) and basis (K, N),
    and the mean and smallest range of its body over the capture."""

    target: object
    realization: object
    model: object
    nodes_s: np.ndarray
    basis: np.ndarray
    mean_range_m: float
    min_range_m: float


def plan_targets(scene, *, chunk_chirps=CHUNK_CHIRPS):
    """Choose each target's model and precompute its nodes and basis."""
    radar = scene.radar.params
    n_chirps = scene.radar.n_chirps
    tau = radar.sample_times_s
    plans = []
    t_s = np.arange(n_chirps) * radar.chirp_period_s
    for target, realization in zip(scene.targets, realize_all(scene)):
        # the body track once per target; the model and the plan share it
        position, velocity = module_of(target).body_track(target, realization, t_s)
        ranges = kinematics.range_m(position)
        model = choose_model(target, realization, radar=radar, position_m=position, velocity_mps=velocity,
                             fidelity=scene.fidelity, chunk_chirps=chunk_chirps)
        if model.nodes_per_chirp >= radar.n_samples:
            nodes, basis = tau, np.eye(radar.n_samples)
        else:
            nodes = chebyshev_nodes_s(model.nodes_per_chirp, tau[-1])
            basis = lagrange_basis(nodes, tau)
        plans.append(TargetPlan(target, realization, model, nodes, basis, float(ranges.mean()), float(ranges.min())))
    return plans


def if_factors(plans, first_chirp, n_chirps, *, radar, channels=None, scale=1.0, tx_phase_rad=None):
    """The two factors of the noise-free IF of chirps ``first_chirp ... first_chirp + n_chirps - 1``.

    ``tx_phase_rad(chirps, los_y)``, where the chirps take transmitters in turn
    (:meth:`mdpipe.simulate.scene.RadarConfig.tx_phase_rad`), gives the phase each chirp's transmitter adds.

    Returns
    -------
    lhs : ndarray, float32, shape (n_channels, n_chirps, 2 sum K)
    rhs : ndarray, float32, shape (2 sum K, n_samples)
        ``lhs @ rhs`` is the IF in volts times ``scale``.
    """
    channels = np.arange(radar.n_channels) if channels is None else np.asarray(channels)
    rx_y_m = np.asarray(radar.rx_positions_m or np.zeros(radar.n_channels))[channels]
    f0_hz = radar.f_start_hz
    tau = radar.sample_times_s
    t_m = (first_chirp + np.arange(n_chirps)) * radar.chirp_period_s
    if not plans:
        return np.zeros((len(channels), n_chirps, 0), np.float32), np.zeros((0, radar.n_samples), np.float32)
    g_blocks, b_blocks = [], []
    for plan in plans:
        echo = target_echo(plan.target, plan.realization, t_m[:, None] + plan.nodes_s, f0_hz=f0_hz)
        g = echo.signal
        if plan.model.range_migration:
            reference_m = float(echo.range_m.mean())
            residual_hz = beat_frequency_hz(echo.range_m - reference_m, slope_hz_per_s=radar.slope_hz_per_s)
            g = g * np.exp(-2j * np.pi * residual_hz * plan.nodes_s)
        else:
            reference_m = plan.mean_range_m
        tone = np.exp(-2j * np.pi * beat_frequency_hz(reference_m, slope_hz_per_s=radar.slope_hz_per_s) * tau)
        steering = np.exp(2j * np.pi * f0_hz / SPEED_OF_LIGHT_MPS * rx_y_m[:, None, None] * echo.los[..., 1])
        if tx_phase_rad is not None:
            steering = steering * np.exp(1j * tx_phase_rad(first_chirp + np.arange(n_chirps), echo.los[..., 1]))
        g_blocks.append(g * steering)
        b_blocks.append(plan.basis * tone)
    g_all = np.concatenate(g_blocks, axis=-1)
    b_all = np.concatenate(b_blocks, axis=0)
    lhs = np.concatenate([g_all.real, -g_all.imag], axis=-1).astype(np.float32)
    rhs = (scale * np.concatenate([b_all.real, b_all.imag], axis=0)).astype(np.float32)
    return lhs, rhs


def noise_free_if(plans, first_chirp, n_chirps, *, radar, channels=None, scale=1.0, tx_phase_rad=None):
    """Noise-free IF of chirps ``first_chirp ... first_chirp + n_chirps - 1``, in volts times ``scale``.

    Returns
    -------
    ndarray, float32, shape (n_channels, n_chirps, n_samples)
    """
    lhs, rhs = if_factors(plans, first_chirp, n_chirps, radar=radar, channels=channels, scale=scale,
                          tx_phase_rad=tx_phase_rad)
    return lhs @ rhs
