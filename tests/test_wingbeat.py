"""The wingbeat of a bird that glides between flapping bursts, read over its bursts only
(:func:`mdpipe.process.wingbeat.gated_pattern_autocorrelation`): known answers on a synthetic pattern."""

from types import SimpleNamespace

import numpy as np
import pytest

from mdpipe.process import wingbeat

FRAME_RATE_HZ = 62.5  # a 16 ms hop
WINGBEAT_HZ = 3.0


def bursts_pattern(*, flap_s, glide_s, dwell_s=6.0, n_rows=24, seed=0):
    """A spectrogram-like (rows, frames) power: noise of mean 1 in every cell; while flapping, each row also
    lit 30 dB over it along a stroke ``1 + cos(2 pi f t - phase)`` of its own phase (a wing row is lit in part
    of each beat). Returns the stand-in spectrogram and the true flapping frames."""
    rng = np.random.default_rng(seed)
    t_s = np.arange(int(dwell_s * FRAME_RATE_HZ)) / FRAME_RATE_HZ
    flapping = np.mod(t_s, flap_s + glide_s) < flap_s
    phase = np.linspace(0, np.pi, n_rows)[:, None]
    stroke = 1000.0 * (1 + np.cos(2 * np.pi * WINGBEAT_HZ * t_s - phase)) ** 2
    power = rng.exponential(1.0, (n_rows, len(t_s))) + flapping * stroke
    f_hz = 20.0 * (np.arange(n_rows) - n_rows // 2)
    return SimpleNamespace(f_hz=f_hz, power=power), flapping


def pairs_counted_by_hand(flapping, lag):
    return int(np.sum(flapping[:len(flapping) - lag] & flapping[lag:]))


def test_flapping_frames_are_the_bursts():
    spec, truth = bursts_pattern(flap_s=1.2, glide_s=0.8)
    marked = wingbeat.flapping_frames(spec.power, noise_level=1.0, frame_rate=FRAME_RATE_HZ)
    assert np.mean(marked != truth) < 0.03  # a frame or two at each switch


def test_paired_share_counts_the_flapping_pairs_of_each_lag():
    """``paired`` at lag L is the share of flapping frames whose frame L on flaps too: for bursts of B frames,
    (B - L) / B, summed over the bursts (counted here frame by frame)."""
    spec, _ = bursts_pattern(flap_s=1.2, glide_s=0.8)
    marked = wingbeat.flapping_frames(spec.power, noise_level=1.0, frame_rate=FRAME_RATE_HZ)
    r, paired = wingbeat.gated_pattern_autocorrelation(spec, noise_level=1.0, frame_rate=FRAME_RATE_HZ)
    assert len(r) == len(paired) and r[0] == 1.0
    for lag in (1, 10, 21, 40, len(paired) - 1):
        assert paired[lag] == pytest.approx(pairs_counted_by_hand(marked, lag) / marked.sum())


def test_wingbeat_read_within_bursts_of_three_beats():
    """Bursts of 3.6 beats, glides as long: the gated pattern peaks at the wingbeat, which repeats at 2T."""
    spec, _ = bursts_pattern(flap_s=1.2, glide_s=1.2)
    found = wingbeat._gated_period(spec, noise_level=1.0, frame_rate=FRAME_RATE_HZ)
    assert found is not None and found.repeats >= 2
    assert 1.0 / found.period_s == pytest.approx(WINGBEAT_HZ, rel=0.02)


def test_bursts_under_two_beats_give_no_wingbeat():
    """Bursts of 1.5 beats: under half the flapping frames see a beat repeat, and no period is taken (the lags
    read end where the pairs within a burst run out; the scene tests in test_off_model.py hold a bird whose
    bursts merge at the mask's edges, where only the paired share stops a wrong period)."""
    spec, _ = bursts_pattern(flap_s=0.5, glide_s=0.7)
    r, paired = wingbeat.gated_pattern_autocorrelation(spec, noise_level=1.0, frame_rate=FRAME_RATE_HZ)
    period_frames = int(round(FRAME_RATE_HZ / WINGBEAT_HZ))
    assert paired[period_frames] < wingbeat.MIN_PAIRED_SHARE
    assert wingbeat._gated_period(spec, noise_level=1.0, frame_rate=FRAME_RATE_HZ) is None


def test_a_bird_that_never_glides_is_not_read_gated():
    spec, _ = bursts_pattern(flap_s=10.0, glide_s=0.1)
    assert wingbeat.gated_pattern_autocorrelation(spec, noise_level=1.0, frame_rate=FRAME_RATE_HZ) is None


def test_flapping_shorter_than_the_smoothing_is_not_read_gated():
    """A record of 0.64 s flapping its first 0.2 s: fewer flapping frames than the lags need (a quarter second
    of pairs), no pattern (and no lag divided by zero pairs)."""
    spec, _ = bursts_pattern(flap_s=0.2, glide_s=1.0, dwell_s=0.64)
    marked = wingbeat.flapping_frames(spec.power, noise_level=1.0, frame_rate=FRAME_RATE_HZ)
    assert 0 < marked.sum() < wingbeat.FLAP_SMOOTH_S * FRAME_RATE_HZ and len(wingbeat._lit_rows(spec, 1.0, 75))
    assert wingbeat.gated_pattern_autocorrelation(spec, noise_level=1.0, frame_rate=FRAME_RATE_HZ) is None
