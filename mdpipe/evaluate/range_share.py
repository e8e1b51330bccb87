"""The share of a target's moving parts' echo that the range FFT puts in its body's range bin.

An FMCW beat holds a scatterer's Doppler shift as well as its range: a blade point at Doppler f_D lands
f_D T range bins from its hub (T = N / fs, the span of the samples), and a blade that flashes within a part
of the ramp spreads over the range bins as any short tone does. The processing reads a target's slow time
at its body's bin, so of the blades it sees only what lands there: a 94 GHz quadrotor whose tips reach
+-74 kHz in a 77 us ramp (5.7 bins) keeps 13 % of its blades' power in the body's bin (-8.9 dB). At X
band the same rotor keeps about all of it. This is the factor by which the evaluation's truth scales the
moving parts' line SNR (the former truth counted every blade line as if it lay in the body's bin).

The share is measured, not modelled: the target's echo with and without its body is evaluated at every IF
sample of chirps drawn at random over the dwell (seeded; regular chirps could strobe with the flashes),
each chirp's real IF is range-transformed as the processing does (Hann window, the DFT evaluated at
fractional bins), the body's bin found as the peak of the body's own transform (which moves with its
Doppler shift too), and the moving parts' power there divided by what it would be were all of it in
that bin (the window's coherent gain).
"""

import numpy as np

from mdpipe.physics.radar import beat_frequency_hz
from mdpipe.simulate.targets import module_of, target_echo

SHARE_CHIRPS = 256
BODY_SEARCH_BINS = 3.0   # the body's peak searched this far (bins) either side of its range's bin
BODY_SEARCH_STEPS = 16   # on a grid of 1 / 16 bin


def range_dft(if_real, bins):
    """Hann-windowed DFT of real IF chirps (M, N) at fractional ``bins`` (M, K): complex (M, K)."""
    n_samples = if_real.shape[-1]
    n = np.arange(n_samples)
    window = np.hanning(n_samples)
    kernel = np.exp(-2j * np.pi * bins[..., None] * n / n_samples)  # (M, K, N)
    return np.einsum("mkn,mn->mk", kernel, if_real * window)


def in_bin_share(target, bodiless, *, radar, seed, index, duration_s, chirps=SHARE_CHIRPS):
    """Share (0 to ~1) of ``bodiless``'s echo power that the range DFT puts in ``target``'s body bin.

    Parameters
    ----------
    target, bodiless : scene targets
        The target, and the same target without its body scatterers (its moving parts only).
    radar : :class:`mdpipe.params.RadarParams`
    seed, index, duration_s :
        The scene's seed, the target's place in the scene and the capture's length: they fix its random
        draws (rate wander, rough wings), as in the simulator.

    A target without a body is read at its range's bin.
    """
    module = module_of(target)
    realization = module.realize(target, seed=seed, index=index, duration_s=duration_s)
    bare = module_of(bodiless).realize(bodiless, seed=seed, index=index, duration_s=duration_s)
    n_chirps = max(1, int(round(duration_s / radar.chirp_period_s)))
    picks = np.sort(np.random.default_rng(0).choice(n_chirps, size=min(chirps, n_chirps), replace=False))
    tau = radar.sample_times_s
    times = picks[:, None] * radar.chirp_period_s + tau[None, :]
    f0_hz = radar.f_start_hz
    whole = target_echo(target, realization, times, f0_hz=f0_hz)
    moving = target_echo(bodiless, bare, times, f0_hz=f0_hz).signal
    body = whole.signal - moving
    range_m = np.mean(whole.range_m, axis=-1)  # (M,): each chirp's beat at its own range (migration included)
    tone = np.exp(-2j * np.pi * beat_frequency_hz(range_m, slope_hz_per_s=radar.slope_hz_per_s)[:, None] * tau)
    range_bins = range_m / radar.range_bin_m
    if np.any(np.abs(body) > 0):
        grid = np.arange(-BODY_SEARCH_BINS, BODY_SEARCH_BINS + 1e-9, 1.0 / BODY_SEARCH_STEPS)
        candidates = range_bins[:, None] + grid[None, :]
        body_power = np.abs(range_dft(np.real(body * tone), candidates)) ** 2
        bins = candidates[np.arange(len(picks)), np.argmax(body_power, axis=1)]
    else:
        bins = range_bins
    in_bin = np.abs(range_dft(np.real(moving * tone), bins[:, None])[:, 0]) ** 2
    all_in_bin = np.hanning(radar.n_samples).sum() ** 2 / 4 * np.abs(moving) ** 2  # a tone's peak: (sum w)^2 |g|^2 / 4
    total = float(np.mean(all_in_bin))
    return float(np.mean(in_bin)) / total if total > 0 else 0.0
