"""Period of a repeating signal from its autocorrelation, refined over many repeats.

A rotor's echo repeats exactly every 1/(N f_rot) (the blades are interchangeable), whatever the
body Doppler. The autocorrelation ``|r(tau)| / r(0)`` then peaks at every multiple of the period;
the fundamental is the shortest lag whose peak stands within 80 % of the best one (multiples score
as high; the rule keeps them from winning) and that repeats: a peak at 2T (and 3T where the record
allows) at least half as prominent. The repeat test rejects lags that are only a fixed offset
between similar parts of the echo, such as two rotors of one drone. The period is refined by
locating the peaks near k T for k = 1..K (a parabola through each) and fitting ``tau_k = k T``:
the lag step is divided by ~K.
"""

from dataclasses import dataclass

import numpy as np

from mdpipe.process.filters import local_maxima, parabolic_offset, running_min

FUNDAMENTAL_SHARE = 0.8
REPEAT_SHARE = 0.5
FLANK_SHARE = 0.5  # a peak before a higher one dips this share of its prominence towards it, or is its flank
PEAK_SPREAD = 0.03  # a repeat's peak lies within this share of k T: rotors 1-4 % apart split it about k T
MAX_REPEATS = 64


@dataclass(frozen=True)
class Period:
    """A period found in a signal: ``period_s``, and ``strength`` (peak prominence; within [0, 1] for a
    magnitude autocorrelation, up to 2 for a signed one) of the autocorrelation's peak at lag ``peak_lag``
    (samples; the period before its refinement); ``error_s`` the standard error of ``period_s`` from the scatter
    of its ``repeats`` peaks about multiples of it (inf under three)."""

    period_s: float
    strength: float
    repeats: int
    peak_lag: int = 0
    error_s: float = np.inf


def autocorrelation(signal, *, signed=False):
    """Unbiased |autocorrelation| normalised to 1 at lag 0, lags 0 .. len - 1 (FFT based).

    ``signed``: the real part instead of the magnitude (for a real signal, its autocorrelation as it is:
    an envelope that dips between its peaks keeps its negative lobes instead of folding them into peaks).
    """
    x = np.asarray(signal, dtype=np.complex128)
    x = x - x.mean()
    n = len(x)
    spectrum = np.fft.fft(x, 2 * n)
    products = np.fft.ifft(np.abs(spectrum) ** 2)[:n]
    r = (products.real if signed else np.abs(products)) / np.arange(n, 0, -1)
    return r / r[0] if r[0] > 0 else r


def best_near(r, lag, *, half_width, lowest=0):
    """The largest of ``r`` within ``half_width`` lags of ``lag`` (rounded), from lag ``lowest`` on: a repeat read
    where a fractional period, or rates a little apart, put it."""
    centre = int(round(lag))
    return float(r[max(centre - half_width, lowest):centre + half_width + 1].max())


def bartlett_error(correlated, n_products):
    """Bartlett's standard error of an autocorrelation coefficient resting on ``n_products`` products, for a
    signal correlated over the lags whose coefficients are ``correlated`` (and not beyond them):
    ``sqrt((1 + 2 sum r_k^2) / n)``."""
    return float(np.sqrt((1 + 2 * np.sum(np.square(correlated))) / n_products))


def _parabolic_peak(r, index):
    if index <= 0 or index >= len(r) - 1:
        return float(index)
    return index + float(parabolic_offset(r[index - 1], r[index], r[index + 1]))


def _repeats(r, prominence, lag, limit, untestable, share=REPEAT_SHARE, max_order=3):
    """The peak at ``lag`` of ``r`` recurs at 2 lag (and up to ``max_order`` lag below ``limit``) with ``share`` of its
    prominence, and as a peak: a local maximum of ``r`` within ``PEAK_SPREAD`` of k lag (a lag past the window at least),
    not a slope the window's end stops on (a goose seen over 1.3 beats: its rows' autocorrelation rising towards the
    beat past the lags searched, a ripple on it every 0.14 s, the stroke's harmonics, read a 7.1 Hz wingbeat on the
    slope at 2 and 3 times that). Four rotors 1-4 % apart split their repeat at 3 T into two peaks 2 % either side,
    a dip at 3 T itself.

    ``untestable``: what to answer when 2 lag lies beyond ``limit`` (the record holds under three periods).
    """
    for k in range(2, max_order + 1):
        if k * lag >= limit:
            return k > 2 or untestable
        half = max(2, int(0.02 * lag))  # the coarse lag is good to a sample: an offset peak nearby must not count
        if prominence[k * lag - half:k * lag + half + 1].max() < share * prominence[lag]:
            return False
        reach = max(half + 1, int(np.ceil(PEAK_SPREAD * k * lag)))  # local_maxima reads interior samples
        if not len(local_maxima(r[max(k * lag - reach - 1, 0):k * lag + reach + 2])):
            return False  # no peak near k lag: a slope
    return True


def find_period(signal, *, sample_rate_hz, min_period_s, max_period_s):
    """Strongest repeating period of ``signal`` between ``min_period_s`` and ``max_period_s``.

    See :func:`period_from_autocorrelation`. Returns None when nothing repeats in the range.
    """
    return period_from_autocorrelation(autocorrelation(signal), sample_rate_hz=sample_rate_hz,
                                       min_period_s=min_period_s, max_period_s=max_period_s)


def lag_range(n, *, sample_rate_hz, min_period_s, max_period_s, max_lag=None):
    """The lags ``lo .. hi - 1`` (samples) searched for a period in an autocorrelation of ``n`` lags: from
    ``min_period_s`` (2 at least) to ``max_period_s`` or ``max_lag`` (by default half the record: two repeats at
    least)."""
    return (max(2, int(np.ceil(min_period_s * sample_rate_hz))),
            min(int(max_period_s * sample_rate_hz), n // 2 if max_lag is None else max_lag))


def _standing(r, peaks, prominence, reach):
    """The ``peaks`` of ``r`` that stand apart from a later, higher one: a peak lower than a local maximum within
    ``reach`` lags after it (the shortest period searched) stands only where ``r`` dips between the two by
    ``FLANK_SHARE`` of its ``prominence`` or more. Without such a dip it lies on the rising flank of the later
    peak, the two unresolved, and its prominence over the running minimum is the flank's (a gull's wing rows,
    repeating at 18 frames, rose through a plateau at 14 that stood 0.26 over the dip before it and 0.004 over the
    sample after: read 4.18 Hz for 3.47). Only later peaks count: an autocorrelation decays with the lag, and a peak
    lower than an earlier one may be its own, further down the decay."""
    if len(peaks) == 0:
        return peaks
    end = min(len(r), int(peaks.max()) + reach + 2)
    is_maximum = np.zeros(end, dtype=bool)
    is_maximum[local_maxima(r[:end])] = True
    height = r[peaks]
    low = height.copy()  # the least of r from each peak to the lag reached
    dip = np.full(len(peaks), np.nan)  # where a higher maximum is reached: how far r fell on the way
    for step in range(1, reach + 1):  # a few lags each: the peaks are many, the reach short
        lag = peaks + step
        going = (lag < end) & np.isnan(dip)
        lag = np.where(going, lag, 0)
        low = np.where(going, np.minimum(low, r[lag]), low)
        reached = going & is_maximum[lag] & (r[lag] > height)
        dip[reached] = height[reached] - low[reached]
    return peaks[np.isnan(dip) | (dip >= FLANK_SHARE * prominence[peaks])]


def period_from_autocorrelation(r, *, sample_rate_hz, min_period_s, max_period_s, repeat_share=0.5,
                                recur_share=REPEAT_SHARE, max_order=3, max_lag=None):
    """The fundamental period in a normalised autocorrelation ``r`` (lag 0 first).

    Lags up to half the record are searched (two repeats at least), or below ``max_lag`` where given. Strength is
    the peak's height above the running minimum over one shortest candidate period (a baseline that the decay of a
    broadband echo does not raise); a peak on the rising flank of a later one is none (:func:`_standing`). Repeats at
    k T are looked for, and the period refined on them, at lags below ``repeat_share`` of the record (an unbiased
    autocorrelation at lag L rests on ``n - L`` products); a peak at 2T (and up to ``max_order`` T) must stand with
    ``recur_share`` of T's prominence.
    With ``repeat_share`` above 1/2 a period whose double lies beyond it (two or fewer periods in the
    record) is kept with ``repeats = 1``: the caller decides on its strength.
    """
    lo, hi = lag_range(len(r), sample_rate_hz=sample_rate_hz, min_period_s=min_period_s, max_period_s=max_period_s,
                       max_lag=max_lag)
    if hi <= lo + 2:
        return None
    baseline = running_min(r, 2 * lo + 1)
    prominence = r - baseline
    peaks = local_maxima(r[lo - 1:hi]) + lo - 1  # lag lo too is a peak when above lag lo - 1
    if len(peaks) and _parabolic_peak(r, peaks[0]) < min_period_s * sample_rate_hz:
        peaks = peaks[1:]  # a peak at lag lo whose vertex lies below the shortest period searched
    peaks = _standing(r, peaks, prominence, lo)
    if len(peaks) == 0:
        return None
    heights = prominence[peaks]
    limit = int(repeat_share * len(r))
    first = next((p for p in peaks[heights >= FUNDAMENTAL_SHARE * heights.max()]
                  if _repeats(r, prominence, p, limit, untestable=repeat_share > 0.5, share=recur_share,
                                   max_order=max_order)), None)
    if first is None:
        return None
    period_samples, repeats, error = refine_period(r, _parabolic_peak(r, first), limit=limit)
    return Period(period_s=period_samples / sample_rate_hz, strength=float(prominence[first]), repeats=repeats,
                  peak_lag=int(first), error_s=error / sample_rate_hz)


def refine_period(r, coarse, *, limit):
    """The period (lags, fractional) of the peaks of ``r`` near ``k coarse`` for k = 1, 2, .. below ``limit`` (each
    the highest lag within 10 % of ``coarse`` of ``k coarse``, refined by a parabola), fitted as
    ``tau_k = k T``; how many peaks took part; and the fit's standard error of T (lags) from the peaks' scatter
    about ``k T`` (inf under three peaks)."""
    repeats = max(1, min(MAX_REPEATS, int(limit / coarse)))
    lags, ks = [], []
    for k in range(1, repeats + 1):
        centre = int(round(k * coarse))
        half = max(1, int(0.1 * coarse))
        window = r[max(centre - half, 1):min(centre + half + 1, len(r) - 1)]
        if len(window) == 0:
            break
        index = max(centre - half, 1) + int(np.argmax(window))
        lags.append(_parabolic_peak(r, index))
        ks.append(k)
    ks, lags = np.asarray(ks, dtype=float), np.asarray(lags)
    period = float(np.dot(ks, lags) / np.dot(ks, ks))
    if len(ks) < 3:
        return period, len(ks), np.inf
    scatter = np.sum(np.square(lags - ks * period)) / (len(ks) - 1)
    return period, len(ks), float(np.sqrt(scatter / np.dot(ks, ks)))
