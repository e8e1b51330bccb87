"""Simulate a scene into a Radarlog file, chunk by chunk (memory bounded by two chunks of chirps)."""

import dataclasses
import os
import shutil
import stat
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from threadpoolctl import threadpool_limits

from mdpipe import __version__
from mdpipe.errors import ParameterError
from mdpipe.params import GIB, RADAR_LIMITS
from mdpipe.io import INT16_FULL_SCALE, CaptureWriter
from mdpipe.io.files import file_kind
from mdpipe.simulate.targets import module_of, target_echo
from mdpipe.simulate.noise import noise_streams, standard_normal_f32
from mdpipe.simulate.synth import CHUNK_CHIRPS, if_factors, plan_targets
from mdpipe.simulate.truth import expected_features

TILE_ROWS = 64
TRACK_BYTES_PER_CHIRP = 16 + 128  # chirp times, and per target its body track (measured: <= 112 B per chirp)
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


def _check_budget(needed, budget_gb, what):
    if needed > budget_gb * GIB:
        raise ParameterError(f"simulating would need about {needed / GIB:.3g} GB of memory ({what}), over the "
                             f"{budget_gb:g} GB budget; use fewer chirps (--chirps), RX channels (--channels) or "
                             "targets, or raise --max-memory-gb")


def check_output(scene, out_path, *, overwrite, chunk_chirps=CHUNK_CHIRPS, max_memory_gb=2.0):
    """Refuse, before anything is allocated, a capture that cannot be written to ``out_path``.

    Checks that the folder exists, that ``out_path`` is free (unless ``overwrite``), that the file
    fits in the free disk space and that the chirp-long arrays (body tracks, ``TRACK_BYTES_PER_CHIRP``
    per chirp and target) and the two chunk buffers fit in ``max_memory_gb``.
    """
    radar, n_chirps = scene.radar.params, scene.radar.n_chirps
    folder = os.path.dirname(os.path.abspath(out_path))
    if not os.path.isdir(folder):
        raise ParameterError(f"{out_path}: the folder {folder} does not exist; create it or choose another -o")
    if os.path.isdir(out_path):
        raise ParameterError(f"{out_path}: is a folder; name the output file")
    if os.path.lexists(out_path) and not overwrite:
        raise ParameterError(f"{out_path}: exists; pass --force to replace it")
    mode = os.lstat(out_path).st_mode if os.path.lexists(out_path) else None
    if mode is not None and not (stat.S_ISREG(mode) or stat.S_ISLNK(mode)):
        raise ParameterError(f"{out_path}: is {file_kind(mode)}; --force replaces files only, choose another -o")
    size = n_chirps * radar.n_samples * radar.n_channels * 2  # int16 samples
    free = shutil.disk_usage(folder).free
    if size > free:
        raise ParameterError(
            f"{out_path}: the capture would take {size:,} bytes ({size / GIB:.3g} GB: {n_chirps} chirps x "
            f"{radar.n_samples} samples x {radar.n_channels} RX x 2 B) but {folder} has {free / GIB:.3g} GB free; "
            "use fewer chirps (--chirps) or RX channels (--channels)")
    tracks = n_chirps * TRACK_BYTES_PER_CHIRP * max(1, len(scene.targets))
    buffers = 2 * radar.n_channels * min(chunk_chirps, n_chirps) * radar.n_samples * 2
    _check_budget(tracks + buffers, max_memory_gb,
                  f"{tracks / GIB:.3g} GB of body tracks for {n_chirps} chirps x {len(scene.targets)} targets, "
                  f"{buffers / GIB:.3g} GB of int16 chunk buffers")


def _check_factor_memory(plans, radar, rows, max_memory_gb):
    """The IF factors of two chunks (float32, 2K columns a target) and the echoes behind them (complex128)."""
    nodes = sum(len(plan.nodes_s) for plan in plans)
    factors = 2 * (radar.n_channels * rows * 2 * nodes * 4 + rows * nodes * 64 + 2 * nodes * radar.n_samples * 4)
    _check_budget(factors, max_memory_gb, f"IF factors of {rows} chirps x {radar.n_channels} RX x {nodes} nodes")


def simulate_to_file(scene, out_path, *, scene_yaml, progress=None, chunk_chirps=CHUNK_CHIRPS, overwrite=True,
                     max_memory_gb=2.0):
    """Write the capture of ``scene`` to ``out_path`` and return the truth stored with it.

    Parameters
    ----------
    scene : Scene
    out_path : str or os.PathLike
    scene_yaml : str
        The scene as given, stored in ``/Truth``.
    progress : callable, optional
        Called with the number of chirps finished after each chunk.
    overwrite : bool
        Replace an existing ``out_path``; if False it is kept and :class:`ParameterError` raised.
    max_memory_gb : float
        Memory budget (GiB) checked before the arrays are made (:func:`check_output`).

    The capture is written to a new hidden file beside ``out_path`` (see
    :class:`mdpipe.io.CaptureWriter`), renamed when complete and removed on any error or interrupt.
    """
    radar, n_chirps = scene.radar.params, scene.radar.n_chirps
    check_output(scene, out_path, overwrite=overwrite, chunk_chirps=chunk_chirps, max_memory_gb=max_memory_gb)
    plans = plan_targets(scene, chunk_chirps=chunk_chirps)
    _check_factor_memory(plans, radar, min(chunk_chirps, n_chirps), max_memory_gb)
    powers_v2 = target_powers_v2(plans, radar, n_chirps)
    sigma_v = noise_sigma_v(scene.noise, plans, powers_v2)
    if scene.adc.full_scale_v is not None:
        lsb_v = scene.adc.full_scale_v / INT16_FULL_SCALE
    else:
        peak_v = peak_signal_v(plans) + NOISE_PEAK_SIGMAS * sigma_v
        lsb_v = peak_v / INT16_FULL_SCALE if peak_v > 0 else 1.0
    low, high = RADAR_LIMITS["full_scale_v_per_lsb"][:2]
    if not low <= lsb_v <= high:  # the file's FuSca could not hold it
        why = ("adc.full_scale_v" if scene.adc.full_scale_v is not None
               else f"the echoes and noise reaching {lsb_v * INT16_FULL_SCALE:.3g} V")
        raise ParameterError(f"the ADC would need {lsb_v:.3g} V per count ({why}), outside {low:g}-{high:g} V; check "
                             "the targets' rcs_m2, noise.sigma_v and adc.full_scale_v")
    streams = noise_streams(scene.seed, radar.n_channels)
    sigma_lsb = sigma_v / lsb_v
    clipped = 0
    writer_params = dataclasses.replace(radar, full_scale_v_per_lsb=lsb_v)
    # two int16 buffers: one being written to the file while the next chunk is made in the other
    int16_buffers = np.empty((2, radar.n_channels, min(chunk_chirps, n_chirps), radar.n_samples), dtype=np.int16)

    # Chunk i is made channel by channel on both cores (BLAS held to one thread in each) while a writer
    # thread stores chunk i - 1 and a third makes chunk i + 1's factors; two chunks of int16 in memory.
    def factors(first):
        return if_factors(plans, first, min(chunk_chirps, n_chirps - first), radar=radar, scale=1.0 / lsb_v,
                          tx_phase_rad=tx_phase_rad)

    # chirps sent by transmitters in turn: each one's position and feed turn the echoes' phases
    tx_phase_rad = scene.radar.tx_phase_rad if scene.radar.transmit_cycle > 1 else None
    firsts = list(range(0, n_chirps, chunk_chirps))
    with CaptureWriter(out_path, writer_params, n_chirps, creator=f"mdpipe {__version__} simulate",
                       overwrite=overwrite, tx_sequence=scene.radar.tx_sequence) as writer, \
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
