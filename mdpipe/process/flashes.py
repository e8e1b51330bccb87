"""Blade flashes: when they happen, and their period.

A blade seen broadside reflects a short broadband pulse (a flash). With the body removed, the
echo's power is a train of such pulses, N per turn for even N and 2N for odd N.

At 76 GHz a flash lasts less than a chirp interval (~37 us for a 10.5 cm blade at 80 rev/s against
Tp = 64 us) and the flash period is not a whole number of chirps, so the flashes are sampled
stroboscopically: how strongly the range FFT sees one depends on where in the (windowed) ramp it
falls, and that position repeats after a few flashes (6.25 ms = 97.66 Tp: every third flash lands
within 2 us of the same place). Amplitudes and complex correlations then repeat with that longer
period. Flash *times* do not: the events are kept as a binary train, the train's strongest period
T* is found from its autocorrelation, and the shortest T*/k whose lag holds significantly more
pairs of events than a random train would is the flash period.

Flashes too weak to clear the event threshold one by one (a few dB above the noise at low SNR) still
show in the autocorrelation of the echo's power, summed over every flash of the dwell
(:func:`power_period`). That tells that blades flash; how often only where the power repeats whole
(:class:`PowerPeriod`): its period may be a whole multiple of the flash period (the stroboscopic
amplitude pattern above repeats too, and a blade differing repeats once a turn).
"""

import functools
from dataclasses import dataclass

import numpy as np
from mdpipe.process import doppler, mains
from mdpipe.process.doppler import periodic_hann
from mdpipe.process.filters import local_maxima, moving_average, robust_sigma, running_max, running_median
from mdpipe.process.periodicity import (autocorrelation, bartlett_error, find_period, lag_range,
                                         period_from_autocorrelation)

EVENT_SIGMAS = 6.0          # an event stands this many robust sigmas above the median power
FALSE_EVENTS = 0.1          # noise events expected over a whole capture
PAIR_WINDOW_CHIRPS = 1.5    # flash times are known to +-1 chirp
PAIR_SIGMAS = 5.0           # a sub-period needs this many Poisson sigmas of excess pairs
PAIR_SHARE = 0.25           # ... and this share of the excess found at T*
FOLD_SHARE = 0.7            # the folded phase histogram shifted by T*/k keeps this share of its energy
MAX_DIVISOR = 6
MIN_EVENTS = 6
COVERAGE_PARTS = 4          # events must fall in every quarter of the dwell
MIN_PERIOD_CHIRPS = 4.0     # events are local maxima, at least 2 chirps apart: noise alone spaces them 2-3
POWER_SIGMAS = 6.0          # the power's autocorrelation peak over its median in the lags searched, in standard errors
                            # of a power correlated over the lags below them (Bartlett)
POWER_BASELINE = 0.1        # ... standing on an autocorrelation this close to 0 (the power between flashes is
                            # uncorrelated); flash times too (:func:`_falls_between`)
AROUND_PERIOD = 0.5         # ... and over the median of the lags within this share of a period of its own
POWER_PEAK_WIDTH = 0.2      # ... and no wider at half its prominence than this share of its lag: flashes are short
POWER_RECUR_SHARE = 0.25    # ... recurring at 2T and 3T with this share of its prominence: six flash trains whose
                            # phases drift apart smear the recurrences (0.76, 0.42, 0.27 for a 77 GHz hexarotor)
MIN_SHAPE_CHIRPS = 8        # the shortest power period searched: its peak's width must be readable
MAX_POWER_PERIOD_S = 1 / 40.0  # two blades at 20 rev/s flash 40 times a second; a wingbeat's second harmonic
                               # reaches 40 Hz
WHOLE_SPAN = 4.5            # the power's strongest peak past its period, up to this many periods, lies at a multiple
WHOLE_TOLERANCE = 0.1       # ... within this share of a period (rates 1-4 % apart shift the multiples by up to 0.06)
SUB_SHARE = 0.15            # a repeat at period / k (k >= 2, down to the shortest lag read) this strong, of the
                            # period's, may be the flash period. Flashes shorter than a chirp are sampled where
                            # they fall in the ramp, a pattern that repeats after k flashes: their power repeats
                            # whole at k x the flash period, the flash period itself with 0.11-0.9 of it (median
                            # 0.53) in trains of one rotor. Rotors a phase apart left up to 0.27 (once 0.67) where
                            # the period was the flashes' in the sweep: withheld. A rotor with one blade much
                            # weaker than the other (a tag) repeats at the turn, at half of it with
                            # 2 a^2 / (1 + a^4) of that (a: the weaker blade's amplitude share), and noise hides
                            # that: see README
SUB_SIGMAS = 3.0            # ... and stands this many standard errors
RESOLVED_CHIRPS = 4         # a power peak this wide (at half its prominence) or wider: flashes that last chirps, or
                            # periods that wander by chirps; the sampled flash amplitudes do not repeat a pattern.
                            # Over 6860 trains of one rotor's equal flashes (0.3-1.5 chirps, 6-20 dB) this and the
                            # rest gave 1686 whole periods, none wrong (at 3 chirps: 2014, 7 at 2-5x the flashes')
RESOLVED_SIGMAS = 8.0       # ... read only on a peak this many standard errors high (noise widened two single-rotor
                            # trains' peaks at 6.1 and 6.6 standard errors, both read at a multiple of the flashes')
AROUND = 0.03               # a lag period / k is looked for within +-3 %
FLANK_RATIOS = (1.0, 2.0, 0.5)  # two range flanks' flash periods agree at these ratios (a turn and a chopping)
FLANK_LINE_DB = 13.0        # a line both range flanks' powers share stands this far over each one's local median
                            # (noise: 2.6e-5 a bin a flank over a median of 33 bins, measured; both within a bin of
                            # one frequency about 9 times its square, 6e-9 a bin)
COMMON_LINE_DB = 10.0       # ... and what every range bin holds in common stands under this there (else bursts)
LEAK_MARGIN_DB = 15.0       # ... and the flanks hold the line's power (the weaker flank's over the target's own power's)
                            # this far over what the range window's sidelobes carry of the target's own echo into them,
                            # twice their share in dB, a power's power (Hann: -60 dB; a branch's lines -80 dB, its own
                            # beats leaking; the low-PRF sweep's drones read by the line -35 to +11 dB)
BEAT_ORDERS = (1, 2)        # ... nor within a few bins of the body's Doppler, or twice it, folded: the echo beats with
BEAT_BINS = 2               #     a residue of static clutter and with its mirror image (a real IF's negative beat, its
                            #     Doppler reversed) in the flanks, through the range window's far sidelobes ...
BEAT_STEADY_HZ = 50.0       # ... where the body's Doppler, times the order, spreads over at most this (a sparrow
                            #     crossing at K band: 13 Hz; the tracks of drones read by a line: 180-1650 Hz, swaying
                            #     or taken by rotor lines, their beats smeared into no line)
LINE_MEDIAN_SHARE = 1 / 32  # a power spectrum's local median over this share of its bins ...
LINE_MEDIAN_BINS = (33, 257)  # ... and at least and at most this many
NYQUIST_GUARD = 0.02        # lines within this share of PRF / 2 of it not read: chirps alternating (two transmitters
                            # in turn, a switch) swell every bin's power at PRF / 2, a bird's and a branch's too
RAMP_PARTS = 8              # the ramp is cut in this many parts to see where in it a flash falls
RAMP_SUB_SHARE = 0.5        # resolved within the ramp, a flash period repeats with this share of what its seen flashes
                            # would show or more (0.77-0.96 of a multiple's in trains the whole ramps read at 2 and 3
                            # flash periods, four fifths of them seen) ...
RAMP_VISIBLE_SIGMAS = 4.0   # ... read where that stands this many sigmas
RAMP_MIN_SHARE = 0.5        # a ramp sampled over less of the chirp is not read in parts (half the flashes unseen)
RAMP_SETTLE_SHARE = 0.75    # a period / k taken for a period only where it repeats with this share of the period's
                            # (flashes resolved within the ramp repeat alike at their period and its multiples; point
                            # blades' grating flashes a third of a period apart repeated with 0.63 of it)
RAMP_MIN_PERIOD_CHIRPS = 2.0  # a period shorter is not read off the ramp's parts to overrule a reading: each part
                            # is differenced along the chirps before its power, so a flash shows in two differences, a
                            # chirp apart (the parts' correlation at 1 chirp 0.25-0.49 in six drones), and an X-band
                            # 3-blade quadrotor's parts read whole at 1.17 chirps
RAMP_MIN_PAIRS = 0.5        # a lag is read where it pairs half as many parts as lag 0 or more ...
RAMP_LOCKED_PAIRS = 0.2     # ... or this share, for a flash period held at a few places in the ramp
RAMP_MAX_SLOTS = 2 ** 19    # the grid of parts read at most (a bounded memory: about 160 B a slot, 84 MB)
SIDE_BINS = 1.5             # the range sides of a target read this many bins below and above its bin ...
SIDE_SIGMAS = 4.0           # ... their repeats that tell flashes alternating sides stand this many sigmas (the two
                            # sides' repeats at every second flash summed, in the sum's own sigmas) ...
SIDE_SHARE = 0.3            # ... and what flashes on both sides at once would add holds under this share of them ...
SIDE_NEXT_SIGMAS = 2.0      # ... or, on one side's repeat at the next flash, within this many sigmas of the noise
RAMP_DETREND_S = 2 * MAX_POWER_PERIOD_S  # the power resolved within the ramp, less its mean over this time


@dataclass(frozen=True)
class PowerPeriod:
    """The period of an echo's power, ``period_s``, and whether the power repeats ``whole`` at it.

    Whole: the strongest peak of its autocorrelation past the period, up to ``WHOLE_SPAN`` periods, lies at a
    whole multiple of it, and no lag ``period_s / k`` (k >= 2, down to the shortest a flash period can be)
    repeats with ``SUB_SHARE`` of its strength (nor, for flashes that may fall between chirps, could have gone
    unseen). A period that is not whole is a fixed offset between flashes (two rotors a phase apart: 8-point blades read
    537 Hz for 160) or a multiple of the flash period (flashes sampled stroboscopically, or one blade
    differing)."""

    period_s: float
    whole: bool


@dataclass(frozen=True)
class FlashPeriod:
    """A flash period. ``ambiguous`` names a divisor k whose T*/k the event pairs support but the folded
    phases do not; ``period_s`` is then T* and should not be reported as a measurement."""

    period_s: float
    ambiguous: int = 0


def flash_events(power, *, noise_power):
    """Local maxima of ``power`` that neither noise nor the echo's own fluctuation explains (bool array).

    Complex Gaussian noise of mean power p has exponentially distributed power: it exceeds
    ``p ln(n / FALSE_EVENTS)`` in ``FALSE_EVENTS`` samples out of n. Events must clear that and
    ``EVENT_SIGMAS`` robust sigmas above the median of ``power``.
    """
    threshold = max(np.median(power) + EVENT_SIGMAS * robust_sigma(power), noise_power * np.log(len(power) / FALSE_EVENTS))
    peak = (power > np.roll(power, 1)) & (power >= np.roll(power, -1))
    return peak & (power > threshold)


def _pair_excess(times, lag, n_samples):
    """Pairs of events ``lag`` apart (+-PAIR_WINDOW_CHIRPS) minus a random train's expectation, and its sigmas.

    ``times`` sorted; the pairs are counted by binary search, O(n log n), not from all n^2 differences.
    """
    count = int(np.sum(np.searchsorted(times, times + lag + PAIR_WINDOW_CHIRPS, side="right")
                       - np.searchsorted(times, times + lag - PAIR_WINDOW_CHIRPS, side="left")))
    n = len(times)
    expected = (2 * PAIR_WINDOW_CHIRPS) * n * n / n_samples * max(0.0, 1 - lag / n_samples) / 2
    return count - expected, (count - expected) / np.sqrt(max(expected, 1.0))


def flash_period(micro_signal, *, prf_hz, min_period_s, max_period_s, noise_power):
    """Flash period of a body-free rotor echo ``micro_signal`` (noise of mean power ``noise_power``); None
    when no periodic flashes are found.

    Periods under ``MIN_PERIOD_CHIRPS`` are not searched: local maxima of any fluctuating power fall every
    2-3 chirps (an aliased wing band, its energy near PRF/2 after the difference, read as flashes every
    2.04 chirps: a bird called a drone). Nor is a period taken where the power does not fall to its floor between
    the events (:func:`_falls_between`): the events then ride a power that swells and ebbs.
    """
    min_period_s = max(min_period_s, MIN_PERIOD_CHIRPS / prf_hz)
    power = np.abs(micro_signal) ** 2
    events = flash_events(power, noise_power=noise_power)
    times = np.flatnonzero(events).astype(float)
    if len(times) < MIN_EVENTS or len(np.unique(times * COVERAGE_PARTS // len(events))) < COVERAGE_PARTS:
        return None  # a rotor flashes all through the dwell; a burst of glitches does not
    train = moving_average(events.astype(float), 3)
    found = find_period(train, sample_rate_hz=prf_hz, min_period_s=min_period_s, max_period_s=max_period_s)
    if found is None:
        return None
    n = len(events)
    longest = found.period_s * prf_hz
    excess_longest, sigmas_longest = _pair_excess(times, longest, n)
    if sigmas_longest < PAIR_SIGMAS:
        return None
    period, ambiguous = longest, 0
    for divisor in range(MAX_DIVISOR, 1, -1):
        candidate = longest / divisor
        if candidate < min_period_s * prf_hz:
            continue
        tests = [_pair_excess(times, j * candidate, n) for j in range(1, divisor)]
        if not all(sig >= PAIR_SIGMAS and excess >= PAIR_SHARE * excess_longest for excess, sig in tests):
            continue
        if _fold_share(times, longest, divisor) >= FOLD_SHARE:
            period, ambiguous = candidate, 0
            break
        ambiguous = ambiguous or divisor
    piled = longest / ambiguous if ambiguous else period  # where the pairs pile up
    if _stronger_elsewhere(times, piled, n, sigmas=sigmas_longest, shortest=min_period_s * prf_hz, longest=longest):
        return None
    if not _falls_between(power, period):
        return None
    return FlashPeriod(period_s=period / prf_hz, ambiguous=ambiguous)


def _falls_between(power, period):
    """Whether ``power`` falls to an uncorrelated floor between events ``period`` lags (chirps, 2 or more: the flash
    period read, or where an ambiguity leaves it, the longer of the two) apart, as flashes' does: its signed
    autocorrelation, at its least over the lags within half the period (rounded) either side of it, stays under
    ``POWER_BASELINE``. A flash train whose whole echo swells and ebbs slowly still falls to the floor between its
    flashes (the echo scaled, not lifted); a power that varies slowly under the events correlates over the whole
    period: a 94 GHz pigeon's wing band, folded over a span of 3.4 kHz, lifted events every 7.5 chirps (flash
    times at 457 Hz: it was called a drone) where its power's autocorrelation stood 0.24 or more at every lag within
    half a period; at the 119 flash periods read on drones of the default, seed 777, seed 4321 and held-out sweeps,
    it dips under -0.02. Flashes riding a slowly ramping line that the difference leaves 3-14 dB under them (a
    residual body line off its demodulation, its power quadrupling over the dwell) stand 0.1-0.35 there, and are not
    read either (in synthetic trains; none such in the sweeps or `make offmodel`).
    """
    r = autocorrelation(power, signed=True)
    lag = int(round(period))
    return bool(np.min(r[max(1, lag - lag // 2):min(len(r), lag + lag // 2 + 1)]) < POWER_BASELINE)


def _stronger_elsewhere(times, period, n_samples, *, sigmas, shortest, longest):
    """Whether pairs of events at a lag off the multiples of ``period`` (by over two pair windows), from ``shortest``
    to twice ``longest``, stand ``sigmas`` or more: then the train has no period. One rotor's flashes, or those of
    rotors at one rate, pile their pairs at the multiples (rotors a phase apart add the offsets between them, each
    with a share of the pairs); rotors far apart in rate spread theirs over every lag (four at 125-136 rev/s,
    sampled at PRF / 40-44, read a period of 102.3 chirps at 6.2 sigmas among lags at 6-7.1)."""
    lags = np.arange(int(np.ceil(shortest)), int(2 * longest) + 1, dtype=float)
    off = np.abs(lags - period * np.round(lags / period)) > 2 * PAIR_WINDOW_CHIRPS
    return any(_pair_excess(times, lag, n_samples)[1] >= sigmas for lag in lags[off])


def _fold_share(times, period, divisor):
    """Correlation of the phase histogram of ``times`` modulo ``period`` with itself shifted by period / divisor.

    One bin per chirp, smoothed over +-1 chirp (the flash times' jitter); 1 for a histogram that
    repeats with period / divisor.
    """
    bins = max(divisor, int(round(period)))
    histogram = np.bincount(np.floor((times % period) / period * bins).astype(int) % bins, minlength=bins)
    histogram = moving_average(histogram.astype(float), 3, mode="wrap")
    histogram = histogram - histogram.mean()
    energy = np.dot(histogram, histogram)
    if energy <= 0:
        return 0.0
    return float(np.dot(histogram, np.roll(histogram, int(round(bins / divisor)))) / energy)


def power_period(micro_signal, *, prf_hz, min_period_s):
    """The period of a body-free echo's power (a :class:`PowerPeriod`) when it is blade flashes', else None.

    The power's autocorrelation must peak at a lag between ``min_period_s`` (and ``MIN_SHAPE_CHIRPS``) and
    ``MAX_POWER_PERIOD_S``, recur at its multiples (``POWER_RECUR_SHARE``), and have the shape of short
    flashes: a narrow peak (``POWER_PEAK_WIDTH``) on a baseline near zero (``POWER_BASELINE``),
    ``POWER_SIGMAS`` standard errors above the median of the lags searched and of those about its own (within
    ``AROUND_PERIOD`` of a period: a power correlated over many lags, a wing's echo beating slowly, lifts the short
    lags over the median of all, and a crow's noise peak at 1.19 ms stood 7.2 standard errors over that median, 2.3
    over its neighbours'). The standard error is
    Bartlett's for a power correlated over the lags below them, ``sqrt((1 + 2 sum r_k^2) / (n - lag))``:
    a speckled echo (a Doppler band a few hundred Hz wide) has a power correlated over a few chirps, whose
    autocorrelation strays twice as far as a white power's (its peaks reached 8-10 white standard errors).
    What else repeats in a power fails the shape: two lines beating (the power a sinusoid: a peak half its
    lag wide), a wing's echo (slowly modulated: a baseline of 0.2-0.7 at these lags).
    """
    return period_of_power(np.abs(micro_signal) ** 2, prf_hz=prf_hz, min_period_s=min_period_s)


def period_of_power(power, *, prf_hz, min_period_s):
    """:func:`power_period` of a ``power`` (per chirp) already formed."""
    if not _varies(power):
        return None  # a constant power (its rounding would be normalised to unit variance)
    r = autocorrelation(power, signed=True)
    min_period_s = max(min_period_s, MIN_SHAPE_CHIRPS / prf_hz)
    found = period_from_autocorrelation(r, sample_rate_hz=prf_hz, max_period_s=MAX_POWER_PERIOD_S,
                                        min_period_s=min_period_s, recur_share=POWER_RECUR_SHARE)
    if found is None:
        return None
    lag = found.peak_lag
    baseline = r[lag] - found.strength
    lo, hi = lag_range(len(r), sample_rate_hz=prf_hz, min_period_s=min_period_s, max_period_s=MAX_POWER_PERIOD_S)
    standard_error = bartlett_error(r[1:lo], len(r) - lag)
    around = r[max(lo, int(lag * (1 - AROUND_PERIOD))):max(int(np.ceil(lag * (1 + AROUND_PERIOD))), lag + 2)]
    sigmas = (r[lag] - max(np.median(r[lo:hi]), np.median(around))) / standard_error
    if sigmas < POWER_SIGMAS or baseline > POWER_BASELINE:
        return None
    below = np.flatnonzero(r < baseline + found.strength / 2)
    left, right = below[below < lag], below[below > lag]
    width = right[0] - left[-1] - 1 if len(left) and len(right) else np.inf
    if width > POWER_PEAK_WIDTH * lag:
        return None
    sampled = width < RESOLVED_CHIRPS or sigmas < RESOLVED_SIGMAS  # flashes that may fall between chirps
    return PowerPeriod(found.period_s, _repeats_whole(r, lag, floor=SUB_SIGMAS * standard_error, sampled=sampled,
                                                      shortest=max(MIN_SHAPE_CHIRPS, width / POWER_PEAK_WIDTH)))


def flank_flash_period(flanks, *, prf_hz, min_period_s):
    """The period (s) of blade flashes in both range flanks of a target (``flanks`` (n_chirps, 2), the power of
    each per chirp: :func:`mdpipe.process.ranging.flank_powers`), else None.

    Each flank holds one side's flashes (an up-chirp's beat moves the approaching blades' one way and the receding
    blades' the other), which come once per chopping period whatever the blade count; their power recurs there, or
    once a turn where one blade differs, or, flashes shorter than a chirp, where the chirps catch them alike again
    (trains every 5.3-12.7 chirps read at 3 and 4 periods). Both flanks must show such a period
    (:func:`period_of_power`: short flashes on a floor, not a swell), at ``FLANK_RATIOS`` of each other within
    ``AROUND``; the shorter is returned: a whole multiple of the chopping period, which one untold. That they are one
    train is not shown: trains 4:3 apart, sampled so, both recur at their common multiple and pass (flashes still),
    and one drone's two sides may recur at multiples not alike (a side seen differing at 4 periods, the other at 3)
    and fail."""
    periods = []
    for power in np.asarray(flanks, dtype=np.float64).T:
        found = period_of_power(power, prf_hz=prf_hz, min_period_s=min_period_s)
        if found is None:
            return None
        periods.append(found.period_s)
    ratio = periods[0] / periods[1]
    if not any(abs(ratio / r - 1) <= AROUND for r in FLANK_RATIOS):
        return None
    return min(periods)


def _varies(power):
    """Whether a power (per chirp) varies: a constant one's rounding would read as a repeat, or as lines."""
    return len(power) >= 2 and np.var(power) > 1e-12 * np.mean(power) ** 2


def _envelope_spectrum(power):
    """A power's (per chirp) Hann periodogram, its mean taken out, from 0 to PRF / 2; None for a power that does not
    vary."""
    x = np.asarray(power, dtype=np.float64)
    if not _varies(x):
        return None
    return np.abs(np.fft.rfft((x - x.mean()) * periodic_hann(len(x)))) ** 2


def _over_median(spectrum):
    """A spectrum over its running median (``LINE_MEDIAN_SHARE`` of the bins, within ``LINE_MEDIAN_BINS``): noise
    stands about ``Exp(1) / ln 2`` there, a line far over it."""
    width = int(np.clip(len(spectrum) * LINE_MEDIAN_SHARE, *LINE_MEDIAN_BINS)) | 1
    return spectrum / np.maximum(running_median(spectrum, width), np.finfo(float).tiny)


def line_contrast(power, *, prf_hz):
    """(f_hz, contrast): a power's :func:`_envelope_spectrum` over its running median (:func:`_over_median`); None for
    a power that does not vary."""
    spectrum = _envelope_spectrum(power)
    if spectrum is None:
        return None
    return np.fft.rfftfreq(len(power), 1.0 / prf_hz), _over_median(spectrum)


def _lit(power, *, prf_hz):
    """A callable: the line contrast of ``power`` (:func:`line_contrast`) within a bin of a frequency (Hz); 0 where the
    power does not vary."""
    read = line_contrast(power, prf_hz=prf_hz)
    if read is None:
        return lambda f_hz: 0.0
    f_read_hz, contrast = read[0], running_max(read[1], 3)
    return lambda f_hz: float(np.interp(f_hz, f_read_hz, contrast))


def _leaked(flank_spectra, own_spectrum, line, *, leak_db):
    """Whether the line at bin ``line`` holds no more power in the weaker flank (its most within a bin) than
    ``LEAK_MARGIN_DB`` over twice ``leak_db`` of the target's own power's there: its own echo's share."""
    near = slice(max(line - 1, 0), line + 2)
    in_flanks = min(spectrum[near].max() for spectrum in flank_spectra)
    return in_flanks < 10 ** ((2 * leak_db + LEAK_MARGIN_DB) / 10) * own_spectrum[near].max()


def flank_line_hz(flanks, *, prf_hz, min_hz, max_hz, common=None, own=None, leak_db=None, body_hz=None,
                  body_spread_hz=0.0, mains_hz=()):
    """The frequency (Hz) of the strongest line that the powers of both range flanks of a target share and that is
    a blade flashes' (``flanks`` (n_chirps, 2): :func:`mdpipe.process.ranging.flank_powers`), else None.

    Flashes recur at the chopping frequency c; the power of their train holds lines at its multiples k c, folded
    by the PRF, each flank's (one side's flashes) at the same frequencies. Rotors a few per cent apart, their trains
    interleaved, repeat in the power's autocorrelation hardly at all (:func:`flank_flash_period`), but each one's
    lines stand apart in its spectrum (low-PRF seeds 555-556: of 43 drones whose lines stand 13 dB or more over the
    noise read ``none`` or ``bird``, 38 with flanks read, the flanks of 9 shared a line 13.4-20.1 dB high, each within
    0.8 % of the chopping frequency or twice it; the 136 flank reads of birds, branches and moving points of the
    default and held-out bird sweeps shared none over 10.9 dB between 40 Hz and 3 kHz).

    A line stands ``FLANK_LINE_DB`` over each flank's local median (:func:`line_contrast`) within a bin of one
    frequency, between ``min_hz`` and ``max_hz`` and off ``PRF / 2`` (``NYQUIST_GUARD``), and is none of these:
    what every range bin holds in common (``common`` (n_chirps,)) lit ``COMMON_LINE_DB`` there (another radar's
    bursts light every bin alike; a drone whose flashes light every bin keeps the reading of its own); a line whose
    power in the weaker flank stands under ``LEAK_MARGIN_DB`` over what the range window's sidelobes carry into a
    flank of the target's own power's line (``own`` (n_chirps,), its bin's power; ``leak_db``, the sidelobes' share
    of its echo in one flank, :func:`mdpipe.process.ranging.flank_leak_db`, twice in dB for a power's power): the
    target's own beats (a branch's lines, two birds in one range cell) leaking into the flanks, where flashes a ramp
    moves off the target stand in them as strong as in its bin or stronger; within ``BEAT_BINS`` bins (and half the
    body's spread ``body_spread_hz`` times the order) of the body's Doppler ``body_hz`` or twice it, folded
    (``BEAT_ORDERS``: a bird's echo beats there with a residue of static clutter and with its mirror image, a Hamming
    window's far sidelobes bringing both into the flanks), where that spread, times the order, is ``BEAT_STEADY_HZ``
    or under; a harmonic of the grid (:func:`mdpipe.process.mains.line_on_grid` of ``mains_hz``: a supply's ripple
    on the gain of the clutter about the target). Which multiple of c (or fold of one) the line is the flanks do not
    tell."""
    powers = np.asarray(flanks, dtype=np.float64).T
    flank_spectra = [_envelope_spectrum(power) for power in powers]
    if any(spectrum is None for spectrum in flank_spectra):
        return None
    contrasts = [_over_median(spectrum) for spectrum in flank_spectra]
    f_hz = np.fft.rfftfreq(powers.shape[1], 1.0 / prf_hz)
    searched = (f_hz >= min_hz) & (f_hz <= min(max_hz, prf_hz / 2 * (1 - NYQUIST_GUARD)))
    shared = np.minimum.reduce([running_max(np.where(searched, contrast, 0.0), 3) for contrast in contrasts])
    lines = np.flatnonzero(searched & (shared >= 10 ** (FLANK_LINE_DB / 10)))
    if len(lines) == 0:  # most flanks: the vetoes' spectra (the common mode's median over half the chirps) not wanted
        return None
    common_lit = None if common is None else _lit(common, prf_hz=prf_hz)
    own_spectrum = None if own is None or leak_db is None else _envelope_spectrum(own)
    resolution_hz = prf_hz / powers.shape[1]
    beats = [] if body_hz is None else [
        (abs(float(doppler.fold_hz(order * body_hz, prf_hz=prf_hz))),
         BEAT_BINS * resolution_hz + order * body_spread_hz / 2) for order in BEAT_ORDERS
        if order * body_spread_hz <= BEAT_STEADY_HZ]
    read = set()
    for best in lines[np.argsort(shared[lines])[::-1]]:
        near = np.arange(max(best - 1, 0), min(best + 2, len(f_hz)))  # the line's own bin: both flanks' most there
        line = int(near[np.argmax(np.prod([contrast[near] for contrast in contrasts], axis=0))])
        if line in read or not searched[line]:
            continue
        read.add(line)
        line_hz = float(f_hz[line])
        if ((common_lit is not None and common_lit(line_hz) >= 10 ** (COMMON_LINE_DB / 10))
                or (own_spectrum is not None and _leaked(flank_spectra, own_spectrum, line, leak_db=leak_db))
                or any(abs(line_hz - beat_hz) <= reach_hz for beat_hz, reach_hz in beats)
                or mains.line_on_grid(line_hz, mains_hz, prf_hz=prf_hz, resolution_hz=resolution_hz)):
            continue
        return line_hz
    return None


def whole_ratio_apart(a, b, *, most=MAX_DIVISOR):
    """Whether periods ``a`` and ``b`` are a whole number of times (up to ``most``) one another, within ``AROUND``."""
    ratio = max(a, b) / min(a, b)
    k = round(ratio)
    return 1 <= k <= most and abs(ratio / k - 1) <= AROUND


def _repeats_whole(r, lag, *, floor, sampled, shortest):
    """Whether the autocorrelation ``r`` repeats whole at ``lag`` (see :class:`PowerPeriod`).

    Divisors of ``lag`` are read down to ``shortest`` lags: a flash period passes the shape test there (its
    peak, as wide as this one, no wider than ``POWER_PEAK_WIDTH`` of it); shorter lags lie within the flash.

    A repeat at a divisor of ``lag`` counts from ``floor`` up (a few standard errors: noise's local maxima
    do not). Flashes that may fall between chirps (``sampled``: a peak narrower than ``RESOLVED_CHIRPS``, or
    too weak for its width to be read) repeat whole at a multiple of their period, their own period holding
    as little as a tenth of it; such a period too weak for a repeat of ``SUB_SHARE`` of its strength to clear
    ``floor`` is not whole: nothing rules out that the flashes come more often.
    """
    if sampled and SUB_SHARE * r[lag] < floor:
        return False
    last = min(int(WHOLE_SPAN * lag), len(r) // 2)  # an unbiased autocorrelation past half the record is noise
    later = local_maxima(r[lag:last + 1]) + lag
    strongest = later[np.argmax(r[later])] if len(later) else lag
    if abs(strongest / lag - round(strongest / lag)) > WHOLE_TOLERANCE:
        return False
    for divisor in range(2, int(lag / shortest) + 1):
        lo, hi = int(np.floor(lag / divisor * (1 - AROUND))), int(np.ceil(lag / divisor * (1 + AROUND)))
        peaks = local_maxima(r[lo - 1:hi + 2]) + lo - 1
        peaks = peaks[(peaks >= lo) & (peaks <= hi)]
        if len(peaks) and r[peaks].max() >= max(SUB_SHARE * r[lag], floor):
            return False
    return True


@dataclass(frozen=True)
class RampTrain:
    """A body-free echo's power at the parts of every ramp (:func:`ramp_train`): ``power`` on a grid of
    ``slot_chirps`` (a part's length, in chirp periods), ``seen`` where a part was sampled (the gaps between ramps
    are not)."""

    power: np.ndarray
    seen: np.ndarray
    slot_chirps: float
    ramp_share: float
    part: np.ndarray  # each slot's part of the ramp (0 .. S - 1), -1 between ramps

    @functools.cached_property
    def _lag_sums(self):
        """The power's products and the pairs of seen slots at every lag (:func:`_lag_sums`): one pair of FFTs
        however many periods are tried on it, and for both readings below."""
        return _lag_sums(self.power, self.seen, len(self.power) - 1)

    @functools.cached_property
    def correlation(self):
        """The power's autocorrelation over the seen slots, every lag (:func:`_masked_autocorrelation`)."""
        return _masked_autocorrelation(*self._lag_sums)

    @functools.cached_property
    def sparse_correlation(self):
        """:attr:`correlation` read at lags pairing ``RAMP_LOCKED_PAIRS`` of lag 0's parts or more."""
        return _masked_autocorrelation(*self._lag_sums, min_pairs=RAMP_LOCKED_PAIRS)


def ramp_readable(ramp_share):
    """Whether a ramp sampled over ``ramp_share`` of the chirp period is read in parts (``RAMP_MIN_SHARE``)."""
    return ramp_share >= RAMP_MIN_SHARE


def ramp_train(parts, *, ramp_share, prf_hz):
    """:class:`RampTrain` of ``parts`` (n_chirps, S): the body-demodulated slow time of each of S equal parts of
    the ramp (:func:`mdpipe.process.ranging.flash_views`), the ramp's sampled part ``ramp_share`` of the chirp
    period; None where that is under ``RAMP_MIN_SHARE`` (flashes between ramps could hide any shorter period:
    nothing would be settled) or the parts hold under 3 chirps. Of a long capture only the first
    ``RAMP_MAX_SLOTS`` parts' length is read (a bounded grid).

    Each part is first-differenced along the chirps (the body, demodulated to 0 Hz, and the clutter taken out), its
    power divided by its median over the dwell (what leaks into one part more than another, the same in every
    chirp, would repeat every chirp), placed at its part's time, less its mean over ``RAMP_DETREND_S`` about it: what changes
    slower than any flash period read (``MAX_POWER_PERIOD_S``: the target crossing the range bin, the rotors'
    phases drifting through each other) would otherwise raise the power's correlation at every lag."""
    n_chirps, n_parts = parts.shape
    if not ramp_readable(ramp_share) or n_chirps < 3:
        return None
    n_chirps = min(n_chirps, int(RAMP_MAX_SLOTS * ramp_share / n_parts))
    power = np.abs(np.diff(parts[:n_chirps], axis=0)) ** 2
    power = power / np.maximum(np.median(power, axis=0), np.finfo(float).tiny)  # each part's own level
    slot = ramp_share / n_parts
    index = np.floor(np.arange(n_chirps - 1)[:, None] / slot + np.arange(n_parts)[None, :] + 0.5).astype(int).ravel()
    grid, seen = np.zeros(index.max() + 1), np.zeros(index.max() + 1, dtype=bool)
    grid[index], seen[index] = power.ravel(), True
    part = np.full(len(grid), -1, dtype=np.int16)
    part[index] = np.broadcast_to(np.arange(n_parts), power.shape).ravel()
    size = max(1, int(round(RAMP_DETREND_S * prf_hz / slot)))
    local = moving_average(grid, size) / np.maximum(moving_average(seen.astype(float), size), 1e-12)
    return RampTrain(np.where(seen, grid - local, 0.0), seen, slot, ramp_share, part)


def _lag_sums(x, seen, max_lag):
    """The sums of products of ``x`` (mean removed) over the pairs of samples ``seen`` at lags 0 .. max_lag, and the
    number of those pairs."""
    v = np.where(seen, x - np.mean(x[seen]), 0.0)
    size = 1 << int(np.ceil(np.log2(2 * len(x))))
    products = np.fft.irfft(np.abs(np.fft.rfft(v, size)) ** 2, size)[:max_lag + 1]
    pairs = np.round(np.fft.irfft(np.abs(np.fft.rfft(seen.astype(float), size)) ** 2, size)[:max_lag + 1])
    return products, pairs


def _masked_autocorrelation(products, pairs, *, min_pairs=RAMP_MIN_PAIRS):
    """Autocorrelation from a signal's lag sums (:func:`_lag_sums`: each lag averaged over its pairs of seen samples),
    1 at lag 0; NaN at lags with under ``min_pairs`` of lag 0's pairs (a lag that falls from ramps into the gaps
    between them more often than not: averaged over few products)."""
    r = np.where(pairs >= min_pairs * pairs[0], products / np.maximum(pairs, 1.0), np.nan)
    return r / r[0] if r[0] > 0 else np.where(np.isnan(r), np.nan, 0.0)


def ramp_repeats_whole(train, period_chirps, *, shortest_chirps, over_floor=False):
    """Whether the echo's power, resolved within the ramp (``train``, a :class:`RampTrain`), repeats whole at
    ``period_chirps``: True, False (it repeats at ``period / k`` too: the flashes come k times as often), or None
    (it cannot tell).

    Flashes shorter than a chirp caught by the whole ramp's transform weigh by where they fall in its window,
    and that pattern repeats after k flashes: the power repeats whole at k flash periods, the flash period
    holding as little as a tenth of it (:class:`PowerPeriod`). Resolved within the ramp each flash is caught
    in its part whole, unless it falls between the ramps: the flash period repeats with the share of the
    flashes seen (0.77-0.96 of the period's repeat for one and four rotors 37.25-37.5 chirps a flash, four fifths
    seen, whose whole ramps repeated at 2 and 3 flash periods). Down to ``shortest_chirps`` (the shortest flash
    period searched):

    * the repeat at the period (its best within +-``AROUND``) stands ``POWER_SIGMAS`` robust sigmas of the
      autocorrelation over the lags read, and, ``over_floor``, over their floor (:func:`ramp_floor`: two drones'
      parts read flat at 0.02 and about 0.1, each lag "whole" against 0);
    * no ``period / k`` repeats with ``RAMP_SUB_SHARE`` of the period's repeat (else False; rotors a phase apart
      repeat in part at many lags, 0.3-0.45 of the period's in a hexarotor), nor with that share of what flashes
      there would show, the share of them that falls within a ramp times the period's repeat, which must stand
      ``RAMP_VISIBLE_SIGMAS`` sigmas (else None: flashes there could go unseen, or under the noise). The repeat at
      ``period / k`` is read at its first multiple whose lag pairs enough parts, and for k >= 4 as the lesser of
      that and a multiple an offset between rotors would not repeat at (:func:`_sub_period_repeat`, read by both
      tests); a period held on the chirps' grid reads ``period / k`` alone, on fewer pairs;
    * the power's strongest peak past the period, up to ``WHOLE_SPAN`` periods, lies at a whole multiple of it
      (else False);
    * the share within a ramp is that of the times ``i period / k`` after the power's flashes that falls within
      a ramp, each flash anywhere in its part (the parts weighed by :func:`_pair_profile`): flashes that drift
      through the ramp put about 0.8 of them there for a ramp 0.8 of the chirp; flashes held at one place none or
      all, or, where their part's times straddle the gap, some.
    """
    lag = period_chirps / train.slot_chirps
    last = int(np.ceil(WHOLE_SPAN * lag)) + 2
    if last >= len(train.power) // 2:
        return None
    r = train.correlation[:last + 1]
    read = _lags_read(train, period_chirps)
    sigma = robust_sigma(read) if len(read) > 2 else 0.0
    peak_lag = _best_lag(r, lag)
    peak = np.nan if peak_lag is None else float(r[peak_lag])
    floor = ramp_floor(train, period_chirps) if over_floor else 0.0
    if not sigma > 0 or not peak - floor >= POWER_SIGMAS * sigma:
        return None
    later = local_maxima(r[int(1.5 * lag):last + 1]) + int(1.5 * lag)
    if len(later):
        strongest = later[np.argmax(r[later])] / lag
        if r[later].max() > peak and abs(strongest - round(strongest)) > WHOLE_TOLERANCE:
            return False
    profile = _pair_profile(train, peak_lag)  # where in the ramp the repeating flashes fall
    if not profile.sum() > 0:
        return None
    divisors = range(2, int(period_chirps / shortest_chirps) + 1)
    locked = on_chirp_grid(period_chirps, dwell_chirps=len(train.power) * train.slot_chirps)
    sub_r = train.sparse_correlation[:last + 1] if locked else r  # a locked period's lags read on fewer pairs
    subs = [_sub_period_repeat(sub_r, lag, divisor, locked=locked) for divisor in divisors]
    if any(sub >= RAMP_SUB_SHARE * peak for sub in subs):
        return False
    starts = np.arange(len(profile)) * train.slot_chirps  # a flash lies anywhere in its part
    for divisor, sub in zip(divisors, subs):
        shifted = (starts[:, None] + period_chirps / divisor * np.arange(1, divisor)) % 1.0
        within = _ramp_overlap(shifted, train.slot_chirps, train.ramp_share)
        expected = float(profile @ np.mean(within, axis=1) / profile.sum()) * peak  # what seen flashes would show
        if np.isnan(sub) or expected < RAMP_VISIBLE_SIGMAS * sigma or sub >= RAMP_SUB_SHARE * expected:
            return None  # flashes there could go unseen, or under the noise (or no pairs of parts that far apart)
    return True


def _lags_read(train, period_chirps):
    """The autocorrelation of the echo resolved within the ramp (``train``) at the lags :func:`ramp_repeats_whole`
    reads about ``period_chirps``: from a quarter of it to ``WHOLE_SPAN`` times it, where read (finite)."""
    lag = period_chirps / train.slot_chirps
    read = train.correlation[int(lag / 4):int(np.ceil(WHOLE_SPAN * lag)) + 2]
    return read[np.isfinite(read)]


def ramp_floor(train, period_chirps):
    """The floor the echo resolved within the ramp (``train``) sits on about ``period_chirps``: its autocorrelation's
    median over the lags read there (:func:`_lags_read`) where positive, else 0. Slow swings of the parts' power that
    outlast the trend taken out lift every lag so (two drones' parts: 0.02 and about 0.1)."""
    read = _lags_read(train, period_chirps)
    return max(float(np.median(read)), 0.0) if len(read) else 0.0


def on_chirp_grid(period_chirps, *, dwell_chirps):
    """Whether a period of ``period_chirps`` drifts less than a chirp from a whole number of chirps over
    ``dwell_chirps``: flashes at it are held at the same places in the ramp (and a whole multiple of its rate folds
    onto it)."""
    return chirp_grid_drift(period_chirps, dwell_chirps=dwell_chirps) <= 1.0


def chirp_grid_drift(period_chirps, *, dwell_chirps):
    """How far (chirps) a period of ``period_chirps`` drifts from the nearest whole number of chirps M over
    ``dwell_chirps``: its offset from M times the periods the dwell holds. For a comb spacing f at PRF M f + e it is
    also the offset e of the comb's M-th order from the PRF in dwell-spectrum bins (``e dwell_s``)."""
    return abs(period_chirps - round(period_chirps)) * dwell_chirps / period_chirps


def _sub_period_repeat(r, lag, divisor, *, locked=False):
    """How strongly the autocorrelation ``r`` (of flashes resolved within the ramp) repeats at ``lag / divisor`` as a
    period would: NaN where it cannot be read.

    Flashes every ``lag / divisor`` repeat at each of its multiples ``j lag / divisor``; flashes every ``lag`` only at
    the multiples of ``lag`` (``j`` a multiple of ``divisor``). A multiple is read where its own lag pairs enough
    parts (:func:`_masked_autocorrelation`), at its best within +-``AROUND`` (:func:`_repeat_at`): a ramp over 0.55-0.65
    of the chirp leaves lags some fractions of a chirp apart unread (at a ramp of 0.6 and 7.5 chirps a flash, every
    other flash falls between ramps), and the best readable lag near an unread one is noise: single trains were read
    whole at 2-5 times their flash period (178 of 1600 at ramps of 0.55-0.7) where that noise stood for the repeat
    at the flash period. So the first multiple whose lag is read, up to ``WHOLE_SPAN`` periods, stands for the
    sub-period (``lag / divisor`` itself wherever the ramp covers 0.75 of the chirp or more).

    For a divisor of 4 or more it counts as the lesser of that and the next multiple read that an offset could not
    repeat at: a fixed offset d between two trains of the period (two rotors a phase apart) repeats at d and
    ``lag - d`` and their sums with multiples of ``lag``, so at ``j lag / divisor`` with ``j`` = +-d modulo the divisor
    only (two quadrotors of the default sweep, four rotors a phase apart, repeated at a fifth and a seventh of their
    flash period with 0.85 and 0.70 of it, and at twice those lags with 0.35 and 0.06). For divisors 2 and 3 every
    multiple is +-1 modulo the divisor: an offset is not told from a period there.

    A ``locked`` period (:func:`on_chirp_grid`), ``r`` then read on fewer pairs (:attr:`RampTrain.sparse_correlation`),
    has the repeat at ``lag / divisor`` alone, NaN where that lag is unread. Its flashes are held at a few places in the
    ramp, each part weighed by its own median, and repeat unalike at its multiples. Held in place, they pair at a lag
    only where both places lie in the ramp, whatever share of the other parts pair there: the lag is read on fewer
    pairs, and where the places it would pair them with lie between the ramps, the share seen
    (:func:`ramp_repeats_whole`) says so."""
    def read(j):
        return np.isfinite(r[int(round(j * lag / divisor))])

    if locked:
        return _repeat_at(r, lag / divisor) if read(1) else np.nan
    multiples = [j for j in range(1, int(WHOLE_SPAN * divisor) + 1)
                 if j % divisor and j * lag / divisor + 2 < len(r) and read(j)]
    if not multiples:
        return np.nan
    first = multiples[0]
    sub = _repeat_at(r, first * lag / divisor)
    if divisor < 4:
        return sub
    other = next((j for j in multiples if (j - first) % divisor and (j + first) % divisor), None)
    return sub if other is None else min(sub, _repeat_at(r, other * lag / divisor))


def ramp_repeat(train, period_chirps):
    """How strongly the echo resolved within the ramp (``train``) repeats after ``period_chirps``: its power's
    autocorrelation at its best within +-``AROUND`` (NaN where no lag there pairs enough parts)."""
    lag = period_chirps / train.slot_chirps
    if int(np.ceil(lag * (1 + AROUND))) + 1 >= len(train.power) // 2:
        return np.nan
    return _repeat_at(train.correlation, lag)


def _best_lag(r, lag):
    """The lag at which the autocorrelation ``r`` is best within +-``AROUND`` (and a slot) of ``lag`` slots, None
    where none of those lags is read."""
    first = max(int(np.floor(lag * (1 - AROUND))) - 1, 1)
    window = r[first:int(np.ceil(lag * (1 + AROUND))) + 2]
    return first + int(np.nanargmax(window)) if np.isfinite(window).any() else None


def _repeat_at(r, lag):
    """The autocorrelation ``r`` at its best within +-``AROUND`` (and a slot) of ``lag`` slots, NaN where none of
    those lags is read."""
    best = _best_lag(r, lag)
    return np.nan if best is None else float(r[best])


def _pair_profile(train, lag):
    """Where in the ramp the power's repeat at ``lag`` slots lies: for each part, the sum of the products of the
    power (its mean out) with itself ``lag`` later, over the slots of that part paired with a seen one, none
    negative. Flashes that repeat put their products in the parts they fall in; noise's average out (the top of the
    power, read instead, held a tenth of the flashes' share in every part)."""
    seen = train.seen[:len(train.seen) - lag] & train.seen[lag:]
    products = np.where(seen, train.power[:len(seen)] * train.power[lag:lag + len(seen)], 0.0)
    n_parts = int(train.part.max()) + 1
    sums = np.bincount(np.maximum(train.part[:len(seen)], 0), weights=products, minlength=n_parts)
    return np.maximum(sums, 0.0)


def _ramp_overlap(start, length, ramp_share):
    """Share of ``[start, start + length)`` (chirps, start in [0, 1)) that falls within the ramp, ``[0, ramp_share)``
    of each chirp."""
    end = start + length
    inside = np.clip(np.minimum(end, ramp_share) - start, 0.0, None) + np.clip(end - 1.0, 0.0, ramp_share)
    return inside / length


def standardized_correlations(power, *, last):
    """The correlations of the columns of ``power`` (n, m), each standardised, over lags 0 .. ``last``: a function of
    two columns ``(a, b)`` giving ``sum_t a[t + lag] b[t] / n`` (``(b, a)``: the negative lags); None where a column
    is constant."""
    n = power.shape[0]
    std = power.std(axis=0)
    if not np.all(std > 0):
        return None
    power = (power - power.mean(axis=0)) / std
    size = 1 << int(np.ceil(np.log2(2 * n)))
    spectra = np.fft.rfft(power, size, axis=0)

    def correlation(a, b):
        return np.fft.irfft(spectra[:, a] * np.conj(spectra[:, b]), size)[:last + 1] / n

    return correlation


def correlation_near(r, lag):
    """The largest of correlations ``r`` within a chirp of a fractional ``lag`` (a flash caught a chirp early or
    late)."""
    return float(np.max(r[max(int(np.floor(lag)) - 1, 0):int(np.ceil(lag)) + 2]))


def sides_alternate(sides, flash_period_chirps):
    """Whether blade flashes every ``flash_period_chirps`` alternate between the two range sides of the target
    (``sides`` (n_chirps, 2): the body-demodulated slow time ``SIDE_BINS`` below and above its bin,
    :func:`mdpipe.process.ranging.flash_views`): an odd blade count's.

    A blade's Doppler shift moves its beat, the approaching blade's one way, the receding one's the other. Equal
    blades of an odd N flash one side at a time: an approaching blade, then, half a chopping period later, a
    receding one; an even N's flash on both at once. Each side's power (first-differenced, standardised) then
    repeats every second flash and not at the next, and the two sides' powers correlate one flash apart and not
    at once. The two sides' summed correlation at the second flash stands ``SIDE_SIGMAS`` robust sigmas of the sum
    (over the lags from a quarter flash period to three), as one side's would stand ``SIDE_SIGMAS`` of its own (a
    target off its range bin's centre lights one side less: a K-band 3-blade quadrotor at -3.8 dB per IF sample
    repeated 3.4 and 5.4 sigmas there, of the correlations' sigma, their sum 5.2 of its own); each side's repeat at the
    next flash holds under ``SIDE_SHARE`` of its own at the second, or within ``SIDE_NEXT_SIGMAS`` of the noise (that
    quadrotor's weaker side: 0.33 of 3.4 sigmas; a side that weak is not told apart from noise, and the call rests on
    the other side and on the sides one flash apart); the sides one flash apart stand ``SIDE_SIGMAS`` and at once under
    ``SIDE_SHARE`` of that. Where the beat moves little (under a bin at X band) each side sees both blades and the
    sides tell nothing: flashes on both sides at once are never concluded (an even N is not told from that).
    Measured on 3-blade rotors at K, 77 and 94 GHz: each side at the next flash 0.0-0.19 of its repeat at the second
    (two sides 0.33-0.34, of 3.4 and 5.3 sigmas), the sides one flash apart 4-27 sigmas and at once under 1; 2-blade
    rotors' sides repeated at the next flash 0.8-1.8 times the second.
    """
    lag = float(flash_period_chirps)
    repeats = _side_repeats(sides, lag)
    if repeats is None:
        return False
    lo, hi, across, back, sigma, both, both_sigma = repeats
    apart, together = (max(correlation_near(across, lag), correlation_near(back, lag)),
                       max(correlation_near(across, 0), correlation_near(back, 0)))
    if not correlation_near(both, 2 * lag) >= SIDE_SIGMAS * both_sigma:
        return False
    if any(_repeats_next(own, lag, sigma) for own in (lo, hi)):
        return False
    return apart >= SIDE_SIGMAS * sigma and together <= SIDE_SHARE * apart


def sides_flash_apart(sides, flash_period_chirps):
    """Whether flash times every ``flash_period_chirps`` are each range side's own (``sides`` as
    :func:`sides_alternate`'s): the sides' summed correlation at the next flash stands ``SIDE_SIGMAS`` robust sigmas
    of the sum, each side repeats there beyond what :func:`sides_alternate` allows an alternating side (over
    ``SIDE_SHARE`` of its own at the second flash and ``SIDE_NEXT_SIGMAS`` of the noise), and the two sides correlate
    neither at once nor one flash apart (under ``SIDE_SIGMAS``): each side flashes at every flash time, not at the
    same flashes as the other. That is not what an odd N's flashes by turns show at their own period (each side at
    every second flash), nor an even N's on both sides at once; it is what an odd N's show at twice their period, its
    chopping period, each side flashing once in it (the other side half a period later where one rotor flashes).
    On 31 low-PRF 3-blade quadrotors read from flash times (3 given): the two whose flash times were their chopping,
    not twice it, repeated at the next flash 3.2-5.7 sigmas on each side, the sides at once and one flash apart -0.8
    to 2.3 sigmas; of the other 29 (25 at twice the chopping), one side or both did not repeat at the next flash
    beyond the noise and 0.3 of its second, or, in one (a 77 GHz quadrotor seen 0.12 s), the sides shared its
    flashes, 15 sigmas one flash apart."""
    lag = float(flash_period_chirps)
    repeats = _side_repeats(sides, lag)
    if repeats is None:
        return False
    lo, hi, across, back, sigma, both, both_sigma = repeats
    shared = max(correlation_near(r, at) for r in (across, back) for at in (0.0, lag))
    return (correlation_near(both, lag) >= SIDE_SIGMAS * both_sigma
            and all(_repeats_next(own, lag, sigma) for own in (lo, hi)) and shared < SIDE_SIGMAS * sigma)


def _repeats_next(own, lag, sigma):
    """Whether one side's correlation ``own`` repeats at the next flash (``lag`` chirps) as no alternating side's
    does: over ``SIDE_SHARE`` of its repeat at the second flash and ``SIDE_NEXT_SIGMAS`` times the noise ``sigma``."""
    return correlation_near(own, lag) > max(SIDE_SHARE * correlation_near(own, 2 * lag), SIDE_NEXT_SIGMAS * sigma)


def _side_repeats(sides, lag):
    """The range sides' standardised power correlations up to three flashes of ``lag`` chirps (``lo``, ``hi``,
    ``across``, ``back``), their robust sigma beyond a quarter flash, the two sides' sum and its sigma; None where
    the dwell holds under six flashes, the lag is under 2 chirps, or a power or a sigma is constant."""
    n = sides.shape[0] - 1
    last = int(np.ceil(3 * lag)) + 2
    if lag < 2 or last >= n // 2:
        return None
    correlation = standardized_correlations(np.abs(np.diff(sides, axis=0)) ** 2, last=last)
    if correlation is None:
        return None
    lo, hi, across, back = correlation(0, 0), correlation(1, 1), correlation(0, 1), correlation(1, 0)
    sigma = robust_sigma(np.concatenate([r[int(lag / 4):] for r in (lo, hi, across, back)]))
    both = lo + hi
    both_sigma = robust_sigma(both[int(lag / 4):])
    if not (sigma > 0 and both_sigma > 0):
        return None
    return lo, hi, across, back, sigma, both, both_sigma
