"""The share of a target's moving parts' echo that the range FFT puts in its body's range bin.

An FMCW beat holds a scatterer's Doppler shift as well as its range: a blade point at Doppler f_D lands
f_D N / fs range bins from its hub, and a blade that flashes within a part of the ramp spreads over the range
bins as any short tone does. The processing reads a target's slow time at its body's bin, so of the blades it
sees only what lands there: a 94 GHz quadrotor whose tips reach +-74 kHz in a 77 us ramp (5.7 bins) keeps
14 % of its blades' power in the body's bin (-8.5 dB); at X band the same rotor keeps about all of it. The
evaluation's truth scales the moving parts' line SNR by this share (it had counted every blade line as if it
lay in the body's bin).

The share is measured, not modelled: the target's echo without its body is evaluated at every IF sample of
chirps drawn at random over the dwell (seeded; regular chirps could strobe with the flashes), each chirp's
real IF is range-transformed as the processing does (its range window, the DFT at a fractional bin) at the body's
bin, and the power there is divided by what it would be were all of it in that bin (the window's coherent
gain). The body's bin is its range's, moved by its own Doppler shift: ``2 (dR/dt) / lambda * N / fs`` bins
(an approaching body's beat is lower).
"""

import numpy as np

from mdpipe.params import ProcessParams
from mdpipe.physics.radar import SPEED_OF_LIGHT_MPS, beat_frequency_hz
from mdpipe.process.ranging import range_window
from mdpipe.simulate.targets import module_of, target_echo

SHARE_CHIRPS = 256
WINDOW = ProcessParams().range_window  # the processing's default, which the evaluation runs with


def range_dft(if_real, bins):
    """DFT of real IF chirps (M, N) through the processing's range window at fractional ``bins`` (M,): complex
    (M,), one bin per chirp."""
    n_samples = if_real.shape[-1]
    kernel = np.exp(-2j * np.pi * np.asarray(bins)[:, None] * np.arange(n_samples) / n_samples)
    return np.sum(kernel * if_real * range_window(WINDOW, n_samples), axis=-1)


def body_bins(range_m, *, radar, f0_hz):
    """Each chirp's body bin (fractional) from its body's range at the IF samples (M, N): the range's bin plus
    the Doppler shift's, ``2 (dR/dt) / lambda * N / fs``."""
    tau = radar.sample_times_s
    rate_mps = (range_m[:, -1] - range_m[:, 0]) / (tau[-1] - tau[0])  # a scene's chirp holds 2 samples or more
    doppler_bins = 2.0 * rate_mps * f0_hz / SPEED_OF_LIGHT_MPS * radar.sampled_duration_s
    return np.mean(range_m, axis=-1) / radar.range_bin_m + doppler_bins


def in_bin_share(moving, *, radar, seed, index, n_chirps, chirps=SHARE_CHIRPS):
    """Share (0 to ~1) of target ``moving``'s echo power that the range DFT puts in its body's bin.

    Parameters
    ----------
    moving : scene target
        A target without its body scatterers (its moving parts only; its body's track stays).
    radar : :class:`mdpipe.params.RadarParams`
    seed, index, n_chirps :
        The scene's seed, the target's place in the scene and the capture's chirps: they fix its random
        draws (rate wander, rough wings), as in the simulator.
    """
    realization = module_of(moving).realize(moving, seed=seed, index=index, duration_s=radar.duration_s(n_chirps))
    picks = np.sort(np.random.default_rng(0).choice(n_chirps, size=min(chirps, n_chirps), replace=False))
    tau = radar.sample_times_s
    f0_hz = radar.f_start_hz
    echo = target_echo(moving, realization, picks[:, None] * radar.chirp_period_s + tau[None, :], f0_hz=f0_hz)
    centre_m = np.mean(echo.range_m, axis=-1)  # each chirp's beat at its own range (migration included)
    tone = np.exp(-2j * np.pi * beat_frequency_hz(centre_m, slope_hz_per_s=radar.slope_hz_per_s)[:, None] * tau)
    in_bin = np.abs(range_dft(np.real(echo.signal * tone), body_bins(echo.range_m, radar=radar, f0_hz=f0_hz))) ** 2
    all_in_bin = range_window(WINDOW, radar.n_samples).sum() ** 2 / 4 * np.abs(echo.signal) ** 2  # (sum w)^2 |g|^2 / 4
    total = float(np.mean(all_in_bin))
    return float(np.mean(in_bin)) / total if total > 0 else 0.0
