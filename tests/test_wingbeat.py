"""The wingbeat of a bird that glides between flapping bursts, read within its bursts only
(:func:`mdpipe.process.wingbeat.gated_pattern_autocorrelation`): known answers on synthetic patterns."""

from types import SimpleNamespace

import numpy as np
import pytest

from mdpipe.process import wingbeat

FRAME_RATE_HZ = 62.5  # a 16 ms hop
WINDOW_S = 0.064      # 4 hops: the frames within 2 of a switch straddle it
WINGBEAT_HZ = 3.0


def stand_in(power, *, row_hz=20.0):
    """A spectrogram stand-in: ``power`` (rows, frames), rows ``row_hz`` apart about 0 Hz."""
    n_rows = power.shape[0]
    return SimpleNamespace(f_hz=row_hz * (np.arange(n_rows) - n_rows // 2), power=power, window_s=WINDOW_S,
                           hop_s=1.0 / FRAME_RATE_HZ)


def bursts_pattern(*, flap_s, glide_s, dwell_s=6.0, n_rows=24, inside="stroke", seed=0):
    """Noise of mean 1 in every cell; while flapping, each row also lit ~30 dB over it: along a stroke
    ``(1 + cos(2 pi f t - phase))^2`` of its own phase (a wing row is lit in part of each beat), or with
    ``inside`` 'stroke, all lit' (``2 + cos``: every cell lit), 'noise' (lit at random) or 'constant' (lit
    evenly): bursts with nothing periodic in them.
    Returns the stand-in spectrogram and the true flapping frames."""
    rng = np.random.default_rng(seed)
    t_s = np.arange(int(dwell_s * FRAME_RATE_HZ)) / FRAME_RATE_HZ
    flapping = np.mod(t_s, flap_s + glide_s) < flap_s
    phase = np.linspace(0, np.pi, n_rows)[:, None]
    lit = {"stroke": 1000.0 * (1 + np.cos(2 * np.pi * WINGBEAT_HZ * t_s - phase)) ** 2 / 4,
           "stroke, all lit": 1000.0 * (2 + np.cos(2 * np.pi * WINGBEAT_HZ * t_s - phase)),
           "noise": 1000.0 * rng.exponential(1.0, (n_rows, len(t_s))),
           "constant": np.full((n_rows, len(t_s)), 1000.0)}[inside]
    power = rng.exponential(1.0, (n_rows, len(t_s))) + flapping * lit
    return stand_in(power), flapping


def burst_segments(spec):
    """The frames read in each burst: the marked bursts less the frames straddling their switches."""
    rows = wingbeat._lit_rows(spec, 1.0, wingbeat.SIGNAL_ROW_PERCENTILES[-1])
    marked = wingbeat.flapping_frames(rows, noise_level=1.0, frame_rate=FRAME_RATE_HZ)
    trim = int(round(WINDOW_S * FRAME_RATE_HZ)) // 2
    return rows, [(a + trim, b - trim) for a, b in wingbeat.bursts(marked) if b - a - 2 * trim >= 2]


def gated(spec):
    return wingbeat.gated_pattern_autocorrelation(spec, noise_level=1.0, frame_rate=FRAME_RATE_HZ)


def period(spec):
    return wingbeat._gated_period(spec, noise_level=1.0, frame_rate=FRAME_RATE_HZ)


def test_flapping_frames_are_the_bursts():
    spec, truth = bursts_pattern(flap_s=1.2, glide_s=0.8)
    marked = wingbeat.flapping_frames(spec.power, noise_level=1.0, frame_rate=FRAME_RATE_HZ)
    assert np.mean(marked != truth) < 0.03  # a frame or two at each switch
    assert [b - a for a, b in wingbeat.bursts(truth)] == [75, 75, 75]


def test_pairs_are_counted_within_each_burst():
    """``pairs`` at lag L: sum over the bursts of B - L (none between bursts: the phase of the strokes does not
    carry across a glide), read as far as a quarter second of pairs remains."""
    spec, _ = bursts_pattern(flap_s=1.2, glide_s=0.8)
    _, segments = burst_segments(spec)
    r, pairs = gated(spec)
    by_hand = [sum(max(b - a - lag, 0) for a, b in segments) for lag in range(len(pairs))]
    assert np.array_equal(pairs, by_hand)
    assert len(r) <= max(b - a for a, b in segments)  # the cycle's lags (pairs across a glide) are not read
    assert pairs[-1] >= wingbeat.FLAP_SMOOTH_S * FRAME_RATE_HZ


def test_r_averages_the_products_within_bursts():
    """Against a lag by lag sum over the bursts, each row less its straight-line trend in the burst."""
    spec, _ = bursts_pattern(flap_s=1.2, glide_s=0.8)
    rows, segments = burst_segments(spec)
    r, pairs = gated(spec)
    products = np.zeros(len(r))
    for a, b in segments:
        x = np.log(rows[:, a:b])
        frames = np.arange(b - a)
        x = x - np.array([np.polyval(np.polyfit(frames, row, 1), frames) for row in x])
        for lag in range(min(len(r), b - a)):
            products[lag] += np.sum(x[:, :b - a - lag] * x[:, lag:])
    expected = products / pairs
    assert r == pytest.approx(expected / expected[0], abs=1e-9)


def test_each_burst_less_its_own_trend():
    """A burst 100 times brighter, another whose level ramps 20 dB: the pattern within them is the same (its
    cells all lit, so that the flapping frames stay the same)."""
    spec, truth = bursts_pattern(flap_s=1.2, glide_s=0.8, inside="stroke, all lit")
    (a, b), (c, d) = wingbeat.bursts(truth)[:2]
    changed = spec.power.copy()
    changed[:, a:b] *= 100.0
    changed[:, c:d] *= 10 ** np.linspace(0.0, 2.0, d - c)
    assert gated(stand_in(changed))[0] == pytest.approx(gated(spec)[0], abs=1e-9)


def test_wingbeat_read_within_bursts_of_three_beats():
    """Bursts of 3.6 beats, glides as long: the gated pattern peaks at the wingbeat and repeats at 2T."""
    spec, _ = bursts_pattern(flap_s=1.2, glide_s=1.2)
    found = period(spec)
    assert found is not None and found.repeats >= 2
    assert 1.0 / found.period_s == pytest.approx(WINGBEAT_HZ, rel=0.02)


def test_bursts_under_two_beats_give_no_wingbeat():
    """Bursts of 1.5 beats: no burst holds two periods, and no period is taken."""
    spec, _ = bursts_pattern(flap_s=0.5, glide_s=0.7)
    assert period(spec) is None


@pytest.mark.parametrize("inside", ["noise", "constant"])
@pytest.mark.parametrize("flap_s, glide_s", [(1.0, 0.5), (0.6, 0.4), (1.5, 0.5)])
def test_bursts_with_nothing_periodic_in_them_give_no_wingbeat(inside, flap_s, glide_s):
    """Rows lit at random or evenly in regular bursts: only the bursts' on and off repeat. Read across the
    glides, with each burst less its mean only and a mask one frame long at each end, this gave the
    flap-glide cycle (0.67 and 0.5 Hz) as a wingbeat."""
    spec, _ = bursts_pattern(flap_s=flap_s, glide_s=glide_s, n_rows=8, inside=inside)
    assert period(spec) is None


def test_one_or_two_lit_rows_are_no_wings():
    spec, _ = bursts_pattern(flap_s=1.2, glide_s=1.2, n_rows=2)
    assert gated(spec) is None


def test_a_bird_that_never_glides_is_not_read_gated():
    spec, _ = bursts_pattern(flap_s=10.0, glide_s=0.1)
    assert gated(spec) is None


def test_flapping_shorter_than_the_smoothing_is_not_read_gated():
    """A record of 0.64 s flapping its first 0.2 s: fewer pairs than the lags need (a quarter second), no
    pattern (and no lag divided by zero pairs)."""
    spec, _ = bursts_pattern(flap_s=0.2, glide_s=1.0, dwell_s=0.64)
    marked = wingbeat.flapping_frames(spec.power, noise_level=1.0, frame_rate=FRAME_RATE_HZ)
    assert 0 < marked.sum() < wingbeat.FLAP_SMOOTH_S * FRAME_RATE_HZ
    assert len(wingbeat._lit_rows(spec, 1.0, 75)) >= wingbeat.MIN_WING_ROWS
    assert gated(spec) is None
