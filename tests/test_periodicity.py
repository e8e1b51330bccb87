"""The fundamental period in an autocorrelation (:func:`mdpipe.process.periodicity.period_from_autocorrelation`)
at the edges of the searched lags."""

import numpy as np
import pytest

from mdpipe.process.filters import local_maxima, running_min
from mdpipe.process.periodicity import _standing, period_from_autocorrelation


def cosine_autocorrelation(period_samples, n=400):
    return np.cos(2 * np.pi * np.arange(n) / period_samples)


def test_a_period_whose_peak_is_the_shortest_lag_searched():
    """A period of 4.3 samples with 3.5 the shortest searched: its peak is lag 4, the first lag searched. Taken
    only between two neighbours inside the range, the peak was missed and the period read at 2T (8.6)."""
    found = period_from_autocorrelation(cosine_autocorrelation(4.3), sample_rate_hz=1.0, min_period_s=3.5,
                                        max_period_s=50.0)
    assert found.period_s == pytest.approx(4.3, rel=0.01)


def test_no_peak_below_the_shortest_lag_searched():
    """A period of 3 samples, 3.5 the shortest searched: the lag-3 peak is not one (its multiple 6 is)."""
    found = period_from_autocorrelation(cosine_autocorrelation(3.0), sample_rate_hz=1.0, min_period_s=3.5,
                                        max_period_s=50.0)
    assert found.peak_lag >= 4 and found.period_s == pytest.approx(6.0, rel=0.01)


def test_a_peak_whose_vertex_lies_below_the_shortest_period_is_not_one():
    """A period of 3.6 samples, 4 the shortest searched: the lag-4 peak's vertex lies at 3.6, under the range
    (it read 3.65); its multiple, 7.2, is the shortest period in range."""
    found = period_from_autocorrelation(cosine_autocorrelation(3.6), sample_rate_hz=1.0, min_period_s=4.0,
                                        max_period_s=50.0)
    assert found.period_s == pytest.approx(7.2, rel=0.01)


def test_lags_searched_past_half_the_record_only_where_asked():
    """A period of 51.5 samples in 100 lags: its peak (lag 51 or 52) lies past half the record (lags up to 49
    searched by default, a peak found up to 48), and no period is found; with ``max_lag`` 54 the lags run past it,
    and it is found once (its double lies past ``repeat_share``: one repeat)."""
    r = cosine_autocorrelation(51.5, n=100)
    kwargs = dict(sample_rate_hz=1.0, min_period_s=2.0, max_period_s=80.0, repeat_share=0.8)
    assert period_from_autocorrelation(r, **kwargs) is None
    found = period_from_autocorrelation(r, max_lag=54, **kwargs)
    assert found.repeats == 1 and found.period_s == pytest.approx(51.5, rel=0.01)


def test_a_plateau_on_the_flank_of_a_higher_peak_is_no_period():
    """A period of 18 lags whose rising flank holds a plateau at 14-15 (a gull's wing rows: 0.44, 0.44, then up to
    0.72 at 18). Searched to lag 16 the plateau is the only local maximum, and its prominence over the running minimum
    is the flank's: it read a period of 14.x (4.18 Hz for 3.47). A higher maximum lies within a shortest period after
    it: no period; with the lags run to 20, the peak at 18."""
    r = cosine_autocorrelation(18.0, n=35)
    r[15] = r[14]
    kwargs = dict(sample_rate_hz=1.0, min_period_s=4.0, max_period_s=30.0, repeat_share=0.8)
    assert period_from_autocorrelation(r, **kwargs) is None
    found = period_from_autocorrelation(r, max_lag=20, **kwargs)
    assert found.peak_lag == 18 and found.period_s == pytest.approx(18.0, rel=0.01)


def test_a_peak_before_a_higher_one_stands_where_it_dips_towards_it():
    """Within 3 lags (the shortest period) before a higher peak: the peak at 4 dips 0.6 towards the one at 6, its
    prominence 1.0, and stands; the plateau at 10-11 rises to 12 without a dip, and is its flank. The peak at 6, higher
    than the one at 4 before it, is not compared with it (an autocorrelation decays)."""
    r = np.array([1.0, 0.2, -0.4, 0.1, 0.6, 0.0, 0.9, 0.1, -0.5, 0.0, 0.5, 0.5, 0.8, 0.2, -0.3])
    peaks = local_maxima(r)
    assert list(peaks) == [4, 6, 10, 12]
    prominence = r - running_min(r, 7)
    assert list(_standing(r, peaks, prominence, 3)) == [4, 6, 12]
