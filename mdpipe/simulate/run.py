"""Simulate a scene into a Radarlog file, chunk by chunk (memory bounded by two chunks of chirps)."""

import dataclasses
import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from threadpoolctl import threadpool_limits

from mdpipe import __version__
from mdpipe.errors import ParameterError
from mdpipe.io import INT16_FULL_SCALE, CaptureWriter
from mdpipe.simulate.targets import module_of, target_echo
from mdpipe.simulate.noise import noise_streams, standard_normal_f32
from mdpipe.simulate.synth import CHUNK_CHIRPS, if_factors, plan_targets
from mdpipe.simulate.truth import expected_features

TILE_ROWS = 64
NOISE_PEAK_SIGMAS = 7.0  # P(|n| > 7 sigma) = 2.6e-12 per sample: ~0.002 clipped samples in 1.3 GB
POWER_SAMPLES = 20000


def target_powers_v2(plans, radar, n_chirps):
    """Each target's mean IF power (V^2, per sample and channel; a real IF has |s|^2 / 2): of its whole echo,
    and of its moving part (the echo minus its slow-time mean over the capture), as a list of pairs."""
    t_s = np.linspace(0, n_chirps - 1, min(n_chirps, POWER_SAMPLES)) * radar.chirp_period_s
    powers = []
    for plan in plans:
        signal = target_echo(plan.target, plan.realization, t_s, f0_hz=radar.f_start_hz).signal
        powers.append((0.5 * float(np.mean(np.abs(signal) ** 2)),
                       0.5 * float(np.mean(np.abs(signal - signal.mean()) ** 2))))
    return powers


def peak_signal_v(plans):
    """Bound on the noise-free IF magnitude over the whole capture."""
    return sum(module_of(p.target).peak_amplitude_v(p.target, p.realization, p.min_range_m) for p in plans)


def noise_sigma_v(noise, plans, powers_v2):
    """Noise standard deviation per sample from the scene's ``noise`` block and the targets' powers."""
    if noise.sigma_v is not None:
        return noise.sigma_v
    moving = [power for plan, power in zip(plans, powers_v2) if plan.target.kind != "static"]
    if noise.snr_db is not None:
        power, snr_db, name = sum(whole for whole, _ in moving), noise.snr_db, "snr_db"
    elif noise.moving_snr_db is not None:
        power, snr_db, name = sum(part for _, part in moving), noise.moving_snr_db, "moving_snr_db"
    else:
        return 0.0
    if power == 0.0:
        raise ParameterError(f"noise.{name}: needs a moving target (drone, bird, point or branch) with a moving "
                             "part to refer to; use noise.sigma_v")
    return float(np.sqrt(power / 10 ** (snr_db / 10)))


def synthesize_channel(lhs, rhs, out, *, sigma_lsb, rng):
    """One channel's chunk: IF, noise, rounding and int16, tile by tile; returns the samples clipped.

    Parameters
    ----------
    lhs : ndarray (M, 2K) float32 and rhs : ndarray (2K, N) float32
        Factors of the noise-free IF in LSB (:func:`mdpipe.simulate.synth.if_factors`).
    out : ndarray (M, N) int16
        Where the samples go.

    Each tile of ``TILE_ROWS`` chirps (512 KB of float32) is made, noised, rounded and converted
    while it sits in cache: done whole-chunk, the same steps cross main memory ~15 times.
    """
    clipped = 0
    tile = np.empty((TILE_ROWS, rhs.shape[1]), dtype=np.float32)
    noise = np.empty_like(tile)
    for start in range(0, lhs.shape[0], TILE_ROWS):
        rows = min(TILE_ROWS, lhs.shape[0] - start)
        block = tile[:rows]
        np.matmul(lhs[start:start + rows], rhs, out=block)
        if sigma_lsb > 0:
            block += standard_normal_f32(rng, noise[:rows], scale=sigma_lsb)
        np.rint(block, out=block)
        if block.min() < -INT16_FULL_SCALE - 1 or block.max() > INT16_FULL_SCALE:
            clipped += int(np.count_nonzero(block > INT16_FULL_SCALE)
                           + np.count_nonzero(block < -INT16_FULL_SCALE - 1))
            np.clip(block, -INT16_FULL_SCALE - 1, INT16_FULL_SCALE, out=block)
        np.copyto(out[start:start + rows], block, casting="unsafe")
    return clipped


def simulate_to_file(scene, out_path, *, scene_yaml, progress=None, chunk_chirps=CHUNK_CHIRPS):
    """Write the capture of ``scene`` to ``out_path`` and return the truth stored with it.

    Parameters
    ----------
    scene : Scene
    out_path : str or os.PathLike
    scene_yaml : str
        The scene as given, stored in ``/Truth``.
    progress : callable, optional
        Called with the number of chirps finished after each chunk.
    """
    radar, n_chirps = scene.radar.params, scene.radar.n_chirps
    plans = plan_targets(scene, chunk_chirps=chunk_chirps)
    powers_v2 = target_powers_v2(plans, radar, n_chirps)
    sigma_v = noise_sigma_v(scene.noise, plans, powers_v2)
    if scene.adc.full_scale_v is not None:
        lsb_v = scene.adc.full_scale_v / INT16_FULL_SCALE
    else:
        peak_v = peak_signal_v(plans) + NOISE_PEAK_SIGMAS * sigma_v
        lsb_v = peak_v / INT16_FULL_SCALE if peak_v > 0 else 1.0
    streams = noise_streams(scene.seed, radar.n_channels)
    sigma_lsb = sigma_v / lsb_v
    clipped = 0
    writer_params = dataclasses.replace(radar, full_scale_v_per_lsb=lsb_v)
    # two int16 buffers: one being written to the file while the next chunk is made in the other
    int16_buffers = np.empty((2, radar.n_channels, min(chunk_chirps, n_chirps), radar.n_samples), dtype=np.int16)

    # Chunk i is made channel by channel on both cores (BLAS held to one thread in each) while a writer
    # thread stores chunk i - 1 and a third makes chunk i + 1's factors; two chunks of int16 in memory.
    def factors(first):
        return if_factors(plans, first, min(chunk_chirps, n_chirps - first), radar=radar, scale=1.0 / lsb_v)

    firsts = list(range(0, n_chirps, chunk_chirps))
    with CaptureWriter(out_path, writer_params, n_chirps, creator=f"mdpipe {__version__} simulate") as writer, \
            threadpool_limits(limits=1, user_api="blas"), \
            ThreadPoolExecutor(max_workers=min(radar.n_channels, os.cpu_count() or 1)) as pool, \
            ThreadPoolExecutor(max_workers=1) as io, ThreadPoolExecutor(max_workers=1) as ahead:
        pending = None
        upcoming = ahead.submit(factors, firsts[0])
        for index, first in enumerate(firsts):
            rows = min(chunk_chirps, n_chirps - first)
            lhs, rhs = upcoming.result()
            if index + 1 < len(firsts):  # the next chunk's factors are made while this one is synthesised
                upcoming = ahead.submit(factors, firsts[index + 1])
            out = int16_buffers[index % 2, :, :rows]
            clipped += sum(pool.map(lambda c: synthesize_channel(lhs[c], rhs, out[c], sigma_lsb=sigma_lsb,
                                                                 rng=streams[c]), range(radar.n_channels)))
            if pending is not None:
                pending.result()  # chunk i - 1 is in the file; its buffer is free for chunk i + 1
            pending = io.submit(writer.write_chirps, first, out)
            if progress is not None:
                progress(rows)
        if pending is not None:
            pending.result()
        truth = expected_features(scene, plans, powers_v2=powers_v2, sigma_v=sigma_v)
        truth["simulation"] = {
            "mdpipe_version": __version__, "seed": scene.seed, "noise_sigma_v": sigma_v,
            "snr_db_per_sample": scene.noise.snr_db, "moving_snr_db_per_sample": scene.noise.moving_snr_db,
            "lsb_v": lsb_v, "clipped_samples": clipped,
            "n_channels": radar.n_channels,
        }
        writer.write_truth(scene_yaml=scene_yaml, expected=truth)
    return truth
