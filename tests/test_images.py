"""Range-Doppler images: a drone's blade flashes detected off its range are no second target."""

import pytest

from mdpipe.params import RadarParams
from mdpipe.process.images import image_owners, image_reach_m


def test_the_reach_of_a_tip_at_the_speed_of_sound_is_its_doppler_times_the_sampled_ramp_in_bins():
    """77 GHz, 64 samples at 855.5 kHz (T_s = 74.8 us) over 250 MHz of the sampled sweep: bins of 0.6 m; a tip at
    343 m/s flashes at 2 v / lambda = 176 kHz, 13.2 bins: 7.9 m."""
    params = RadarParams(f_start_hz=76.5e9, f_stop_hz=76.75e9, ramp_up_s=74.81e-6, chirp_period_s=93.5e-6,
                         sample_rate_hz=855504.0, n_samples=64, n_channels=1)
    doppler_hz = 2 * 343.0 / params.wavelength_m
    assert doppler_hz == pytest.approx(176.0e3, rel=0.01)
    assert image_reach_m(params) == pytest.approx(doppler_hz * 64 / 855504.0 * params.range_bin_m, rel=1e-12)
    assert image_reach_m(params) == pytest.approx(7.9, rel=0.01)


def row(range_m, chopping_hz):
    return {"range_m": range_m, "chopping_freq_hz": chopping_hz}


def test_a_weaker_comb_within_reach_and_two_per_cent_is_the_strongers_image():
    rows = [row(14.39, 150.34), row(12.59, 150.85)]
    assert image_owners(rows, reach_m=5.0) == [None, 0]


@pytest.mark.parametrize("rows, reach_m", [
    ([row(14.39, 150.34), row(12.59, 154.0)], 5.0),   # combs 2.4 % apart: two drones
    ([row(14.39, 150.34), row(8.0, 150.34)], 5.0),    # beyond a tip's reach
    ([row(14.39, 150.34), row(12.59, None)], 5.0),    # no comb in the weaker: a bird, a point
    ([row(14.39, None), row(12.59, 150.34)], 5.0),    # no comb in the stronger
])
def test_targets_that_differ_in_comb_or_lie_beyond_reach_stay_targets(rows, reach_m):
    assert image_owners(rows, reach_m=reach_m) == [None, None]


def test_an_image_owns_no_image_of_its_own():
    """Three detections in a row, each within reach of the next: the second is the first's image, and the third,
    within reach of the second only, stays a target."""
    rows = [row(10.0, 150.0), row(13.0, 150.5), row(16.0, 150.2)]
    assert image_owners(rows, reach_m=4.0) == [None, 0, None]
