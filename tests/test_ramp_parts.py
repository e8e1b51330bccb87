"""The flash views of a target: a tone in one part of every chirp shows in that part's transform only; a tone off
the track's bin in the side it lies on; what every chirp holds alike (static clutter) in none."""

from types import SimpleNamespace

import numpy as np
import pytest

from mdpipe.process import ranging


class _Chirps:
    """A reader of (chirps, channels, samples) volts held in memory."""

    def __init__(self, data):
        self.data = data
        self.n_chirps = data.shape[0]
        self.params = SimpleNamespace(n_samples=data.shape[2])

    def iter_chunks(self, *, chunk_chirps):
        for first in range(0, self.n_chirps, chunk_chirps):
            yield first, self.data[first:first + chunk_chirps]


def test_a_tone_in_one_part_of_the_ramp_shows_in_that_part():
    """A real tone at bin 20.0 of 128 samples, 1 V, in samples 64-95 (the third of four parts) of every chirp, on
    the second of two channels, its phase turning once over the 10 chirps (a mover: the mean chirp, static
    clutter, holds none of it): the third part's Hann-windowed DFT at bin 20 reads sum(w) / 2 = 7.75 (the
    positive-frequency half of a real tone), the other parts, which hold none of its samples, nothing (a part
    reaching into its neighbour's samples would read some)."""
    n, chirps = 128, 10
    data = np.zeros((chirps, 2, n), dtype=np.float32)
    samples = np.arange(n)
    for k in range(chirps):
        data[k, 1, 64:96] = np.cos(2 * np.pi * 20.0 * samples[64:96] / n + 2 * np.pi * k / chirps)
    parts = ranging.flash_views(_Chirps(data), np.full(chirps, 20.0), np.array([0.0, 1.0]), segments=4,
                                side_bins=1.5, chunk_chirps=4).parts
    assert parts.shape == (chirps, 4)
    assert np.abs(parts[:, 2]) == pytest.approx(np.hanning(32).sum() / 2, rel=1e-3)
    assert np.all(np.abs(parts[:, [0, 1, 3]]) < 1e-6)


def test_the_range_sides_weigh_a_tone_by_its_offset():
    """A tone over the whole ramp at bin 21.5, its phase turning once over the 6 chirps: the upper side
    (20 + 1.5) reads sum(w) / 2 = 31.75 of a 128-sample Hann window, the lower one (18.5, three bins off) its
    leakage only (under 1 %)."""
    n, chirps = 128, 6
    data = np.zeros((chirps, 1, n), dtype=np.float32)
    for k in range(chirps):
        data[k, 0, :] = np.cos(2 * np.pi * 21.5 * np.arange(n) / n + 2 * np.pi * k / chirps)
    views = ranging.flash_views(_Chirps(data), np.full(chirps, 20.0), np.array([1.0]), segments=4, side_bins=1.5,
                                chunk_chirps=4)
    assert np.abs(views.sides[:, 1]) == pytest.approx(np.hanning(n).sum() / 2, rel=1e-3)
    assert np.all(np.abs(views.sides[:, 0]) < 1e-2 * np.abs(views.sides[:, 1]))


def test_what_every_chirp_holds_alike_is_taken_out():
    """A tone identical in every chirp (static clutter at bin 20) leaves nothing in the parts or the sides."""
    n, chirps = 128, 8
    data = np.zeros((chirps, 1, n), dtype=np.float32)
    data[:, 0, :] = 5.0 * np.cos(2 * np.pi * 20.0 * np.arange(n) / n + 0.3)
    views = ranging.flash_views(_Chirps(data), np.full(chirps, 20.0), np.array([1.0]), segments=8, side_bins=1.5,
                                chunk_chirps=3)
    assert np.abs(views.parts).max() < 1e-4 and np.abs(views.sides).max() < 1e-4


def test_the_flanks_gather_a_moving_tones_power_on_its_side_and_leave_static_clutter_out():
    """Range flanks of a target at bin 20 of 128 samples, from 2.5 to 6 bins off: a moving tone (its phase turning
    once over the chirps) at bin 25 lands in the farther flank only, its power there (sum(w) / 2)^2 = 31.75^2 (one
    bin of the flank holds it; its leakage into the neighbours' bins adds the window's squared response: Hann's
    at +-1 bin, 1/4 each); a static tone at bin 16 (in the nearer flank) is taken out; a tone at bin 21, inside the
    main lobe, stays out of both."""
    n, chirps = 128, 12
    data = np.zeros((chirps, 1, n), dtype=np.float32)
    samples = np.arange(n)
    for k in range(chirps):
        data[k, 0] = (np.cos(2 * np.pi * 25.0 * samples / n + 2 * np.pi * k / chirps)
                      + 3.0 * np.cos(2 * np.pi * 16.0 * samples / n + 0.4)
                      + 2.0 * np.cos(2 * np.pi * 21.0 * samples / n + 2 * np.pi * k / chirps))
    flanks = ranging.flank_powers(_Chirps(data), np.full(chirps, 20.0), np.array([1.0]), inner_bins=2.5,
                                  outer_bins=6.0, chunk_chirps=5)
    assert flanks.shape == (chirps, 2)
    peak = (np.hanning(n).sum() / 2) ** 2
    assert flanks[:, 1] == pytest.approx(peak * 1.5, rel=0.02)  # bins 24, 25, 26 of the farther flank (23-26)
    assert np.all(flanks[:, 0] < 1e-3 * peak)


def test_the_flanks_follow_the_track_in_zero_padded_bins():
    """The same moving tone at bin 25, the track given on a 4x padded grid (80.0 = bin 20): the farther flank."""
    n, chirps = 128, 6
    data = np.zeros((chirps, 1, n), dtype=np.float32)
    for k in range(chirps):
        data[k, 0] = np.cos(2 * np.pi * 25.0 * np.arange(n) / n + 2 * np.pi * k / chirps)
    flanks = ranging.flank_powers(_Chirps(data), np.full(chirps, 80.0), np.array([1.0]), inner_bins=2.5,
                                  outer_bins=6.0, zero_pad=4, chunk_chirps=4)
    assert np.all(flanks[:, 1] > 1e3 * flanks[:, 0])


@pytest.mark.parametrize("weight, gain", [(np.array([1.0, -1.0j]) / np.sqrt(2), 1.0),
                                          (np.array([1.0, 1.0j]) / np.sqrt(2), 0.0)])
def test_the_flanks_combine_channels_as_the_slow_time_does(weight, gain):
    """A moving tone at bin 23 on two channels, the second a quarter turn behind in the IF (so a quarter turn ahead
    in the conjugated DFT): the farther flank's power 3 bins off a target at bin 20 equals |range side|^2 read 3 bins
    off by :func:`ranging.flash_views` (the slow time's DFT convention and channel weights). The weight (1, -j)
    adds the channels (power 2 x 31.75^2), (1, j) cancels them; an unconjugated DFT would swap the two."""
    n, chirps = 128, 8
    data = np.zeros((chirps, 2, n), dtype=np.float32)
    samples = np.arange(n)
    for k in range(chirps):
        data[k, 0] = np.cos(2 * np.pi * 23.0 * samples / n + 2 * np.pi * k / chirps)
        data[k, 1] = np.cos(2 * np.pi * 23.0 * samples / n + 2 * np.pi * k / chirps - np.pi / 2)
    flanks = ranging.flank_powers(_Chirps(data), np.full(chirps, 20.0), weight, inner_bins=3.0, outer_bins=3.0,
                                  chunk_chirps=3)
    sides = ranging.flash_views(_Chirps(data), np.full(chirps, 20.0), weight, segments=4, side_bins=3.0,
                                chunk_chirps=3).sides
    assert flanks[:, 1] == pytest.approx(np.abs(sides[:, 1]) ** 2, rel=1e-4, abs=1e-3)
    peak = 2 * (np.hanning(n).sum() / 2) ** 2
    assert flanks[:, 1] == pytest.approx(np.full(chirps, gain * peak), rel=1e-3, abs=1e-6 * peak)


def test_the_flanks_reach_the_fastest_tips_past_the_main_lobe_of_every_range_window():
    """A 94 GHz ramp of 219 us sampled: tips at 150 m/s land 2 x 150 / 3.19 mm x 219 us = 20.6 bins off, so a Hann
    window's flanks run from 2.5 to 22.6 bins (its main lobe +-2 beyond either end); the bundled Radarlog captures'
    ramp, 2048 samples at 40 MHz (51.2 us) at 76.5 GHz, reaches 3.9 bins, under the 4 read. Every range window has a
    main lobe."""
    from mdpipe.params import RANGE_WINDOWS
    long_ramp = SimpleNamespace(wavelength_m=299792458.0 / 94e9, sampled_duration_s=219e-6)
    inner, outer = ranging.flank_bins(long_ramp, "hann")
    assert inner == 2.5 and outer == pytest.approx(20.6 + 2.0, abs=0.05)
    assert list(ranging.flank_offsets(inner, outer)) == list(range(3, 23))
    assert ranging.flank_bins(long_ramp, "blackman")[0] == 3.5
    radarlog = SimpleNamespace(wavelength_m=299792458.0 / 76.5e9, sampled_duration_s=2048 / 40e6)
    assert ranging.flank_bins(radarlog, "hann") is None
    assert set(ranging.MAIN_LOBE_BINS) == set(RANGE_WINDOWS)
    assert len(ranging.flank_offsets(2.5, 500.0)) == ranging.FLANK_MAX_BINS
