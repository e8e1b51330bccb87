"""Line combs in a rotor's Doppler spectrum: chopping frequency per rotor, blade parity and imbalance.

A rotor's body-free echo is periodic with the chopping period ``1 / (N f_rot)`` (its blades are
interchangeable), so its spectrum is a comb of lines at ``k N f_rot`` (paper Eqs. 2-5); a drone's
rotors, turning at rates a few per cent apart, give one comb each. A comb at candidate spacing f is
scored by its *contrast*: the mean line score at ``k f`` minus that half-way between, at
``(k + 1/2) f``. The true spacing has every comb position on a line and none half-way; its double
2f has every other line half-way (contrast ~0); its half f/2 has half its positions empty (half the
contrast). So the contrast peaks at the fundamental of each comb, not at its multiples or
sub-multiples, and it does not need the rotors to turn at one rate.

Positions are folded into the unambiguous span, so an aliased comb (stroboscopic flashes at 76 GHz)
is scored the same way. Line scores are ``log(1 + P / noise)``: a few strong lines near the body do
not outweigh the many lines of the comb, and noise has a known score.

Beyond the spacing, the comb tells what it can of the blade count N:

* blades of unequal reflectivity (a tag, a repaired blade) make the echo repeat only once a turn:
  weaker lines at ``(k + j / N) f_chop`` for every j. The largest d whose sub-lines are all
  present is N.
* an odd-bladed rotor flashes 2N times a turn, one side of the Doppler span at a time (approaching,
  then receding half a chopping period later); an even one's flashes span both sides at once.
"""

from dataclasses import dataclass

import numpy as np

from mdpipe.process.doppler import noise_level_per_bin, periodic_hann
from mdpipe.process.filters import local_maxima, moving_average

MIN_CHOP_HZ = 20.0           # the lowest comb spacing searched
MIN_FUNDAMENTAL_HZ = 20.0    # a rotor turns faster than 20 rev/s; wings beat up to 20 Hz
MAX_ROTOR_RATE_HZ = 500.0    # 30 000 rpm: a small racing drone's rotors at full throttle
MAX_BLADES = 6
MAX_CHOP_HZ = MAX_BLADES * MAX_ROTOR_RATE_HZ  # 3000 Hz: 6 blades at 500 rev/s
COARSE_SEGMENT_S = 0.25      # Welch segments of the coarse search
MAX_COARSE_HARMONICS = 12
MIN_HARMONICS = 3            # a comb needs this many lines each side within the band
COMB_T = 8.0                 # a comb's contrast in standard errors of its line-by-line differences
MAX_FINE_HARMONICS = 64
MAX_GRID_POINTS = 4096
PAD = 2                      # zero-padding of the spectra
FUNDAMENTAL_SHARE = 0.7      # a sub-multiple spacing this strong is the comb's real fundamental
MULTIPLE_SHARE = 0.6         # a multiple 2f of a comb sums half its contrast: below this share
ROTOR_SHARE = 0.35           # a further rotor's contrast against the strongest rotor's
ROTOR_SPREAD = 0.12          # rotors of one drone turn within +-12 % of each other
MAX_ROTORS = 8
SUBLINE_Z = 5.0              # imbalance sub-lines: z of their mean score over the half-way positions
PATTERN_MARGIN = 1.0         # every N-th line of a turn comb stronger by this (log(1 + SNR)): ~4 dB and more
PATTERN_KNOTS = 5            # ... over a trend: a linear spline with at most this many knots a side
MIN_PATTERN_DOF = 6          # ... fitted with this many degrees of freedom left at least
INNER_SHARE = 0.5            # a comb's lines over their inner half-way points: this share of their t over the outer
EDGE_SHARE = 0.02            # a spacing this close to its search window's edge is not the comb's (it lies beyond)
PARITY_SHARE = 0.5           # blade parity: the flash sides' correlation at the other lag below this share
DOUBLING_SHARE = 0.5         # flashes doubled: the power's contrast at odd multiples below this share of the even
MIN_SIDE_CORRELATION = 0.2   # ... of the lag that tells, at least this
SIDE_INNER = 0.25            # ... read beyond this share of the band (the blades, not the body)


@dataclass(frozen=True)
class LineSpectrum:
    """Line scores ``log(1 + P / noise)`` per bin of a spectrum in FFT order (zero-padded ``PAD`` times)."""

    score: np.ndarray
    prf_hz: float

    @property
    def resolution_hz(self):
        return self.prf_hz / len(self.score)

    def at(self, f_hz):
        """Score at frequencies ``f_hz`` (any shape), folded into the span; the larger of the two nearest bins."""
        n = len(self.score)
        position = (np.asarray(f_hz) / self.resolution_hz) % n
        lower = np.floor(position).astype(np.int64) % n
        return np.maximum(self.score[lower], self.score[(lower + 1) % n])

    def without(self, spacing_hz, orders, *, width_bins=2 * PAD):
        """The same spectrum with the lines at ``k spacing_hz`` (k in ``orders``, both signs) replaced by noise."""
        score = self.score.copy()
        n = len(score)
        centre = np.rint(np.concatenate([orders, -orders]) * spacing_hz / self.resolution_hz).astype(np.int64)
        score[(centre[:, None] + np.arange(-width_bins, width_bins + 1)[None, :]) % n] = NOISE_SCORE
        return LineSpectrum(score=score, prf_hz=self.prf_hz)


NOISE_SCORE = float(np.e * 0.21938393439552029)  # E[log(1 + x)] for x ~ Exp(1): e E1(1)


def line_spectrum(signal, *, prf_hz, noise_power, segment_chirps=None, pad=PAD):
    """Line scores of ``signal``: a Hann periodogram, or the Welch average over ``segment_chirps`` segments.

    The noise level per bin comes from ``noise_power`` (per chirp); a Welch average of M segments has
    the same mean noise level and M times less spread. ``noise_power`` None: the level is taken from
    the median bin (the median of exponential noise power is ln 2 of its mean), for signals whose
    noise is not known, such as a power envelope. ``pad``: zero-padding factor (a line between
    two bins loses at most 0.4 dB at the nearer of the two, against 1.4 dB unpadded).
    """
    x = np.asarray(signal, dtype=np.complex128)
    n = len(x) if segment_chirps is None else int(min(segment_chirps, len(x)))
    window = periodic_hann(n)
    starts = range(0, len(x) - n + 1, max(1, n // 2))
    power = np.zeros(pad * n)
    for count, start in enumerate(starts, 1):
        power += np.abs(np.fft.fft(x[start:start + n] * window, pad * n)) ** 2
    power /= count * np.sum(window) ** 2
    level = np.median(power) / np.log(2) if noise_power is None else noise_level_per_bin(noise_power, n)
    level = max(level, np.finfo(float).tiny)
    return LineSpectrum(score=np.log1p(power / level), prf_hz=prf_hz)


def first_lines_rate_hz(lines, spacing_hz, *, orders=2):
    """The rate (Hz) the first ``orders`` lines of a comb at ``spacing_hz`` centre on, read on the line scores
    ``lines`` (a :class:`LineSpectrum`): each line's mean frequency over its order, weighted by the power over the
    noise (``exp(score) - 2`` in noise units, where positive) within half a spacing of ``+-k spacing_hz``, averaged
    weighted by the lines' powers; None without power over the noise there.

    Rotors turning a few per cent apart overlap within the dwell's resolution at their first orders, which centre on
    their power-weighted mean rate, while a comb read over many orders can follow the one whose lines stand
    strongest (four 4-blade rotors at 78.2-81.7 rev/s seen 0.1 s: a comb at 78.1 Hz, its first lines centring on
    80.0 Hz).
    """
    excess = np.clip(np.expm1(lines.score) - 1.0, 0.0, None)
    f_hz = np.fft.fftfreq(len(lines.score), 1.0 / lines.prf_hz)
    rates, weights = [], []
    for k in range(1, orders + 1):
        for sign in (1, -1):
            near = np.abs(f_hz - sign * k * spacing_hz) <= spacing_hz / 2
            line = excess[near].sum()
            if line > 0:
                rates.append(np.sum(excess[near] * f_hz[near]) / line / (sign * k))
                weights.append(line)
    return float(np.average(rates, weights=weights)) if weights else None


def comb_statistics(lines, spacing_hz, *, half_width_hz, limit, offset=0.5, min_orders=None):
    """Contrast and its t of combs at ``spacing_hz`` (array): scores at ``+-k f`` against ``+-(k + offset) f``.

    Orders k = 1..K with ``K f`` inside ``half_width_hz`` (at most ``limit``). Returns (contrast, t, K);
    spacings with fewer than ``MIN_HARMONICS`` orders get NaN.

    ``min_orders`` given: K is, per spacing, the extent of orders from ``min_orders`` up (or all there are)
    whose t is largest, the comb held as far as its lines do. Rotors turning a few per cent apart, or
    whose rate wanders, smear their k-th line over k times that: their combs stand out to a few orders
    only, and the orders beyond (noise, or the other rotors' lines) would halve their t. The largest of
    several t is biased up: on noise alone its 99.99th percentile is ~5, against 3.7 for all orders,
    both well under ``COMB_T``.
    """
    spacing_hz = np.atleast_1d(np.asarray(spacing_hz, dtype=float))
    n_orders = np.clip(np.floor(half_width_hz / spacing_hz), 0, limit).astype(int)
    top = int(n_orders.max()) if len(n_orders) else 0
    if top < MIN_HARMONICS:
        nan = np.full(len(spacing_hz), np.nan)
        return nan, nan, n_orders
    order = np.arange(1, top + 1, dtype=float)
    k = np.stack([order, -order], axis=1).ravel()  # 1, -1, 2, -2, ...: a prefix of 2K holds the orders 1..K
    difference = lines.at(spacing_hz[:, None] * k) - lines.at(spacing_hz[:, None] * (k + np.sign(k) * offset))
    count = 2.0 * np.arange(1, top + 1)
    mean = np.cumsum(difference, axis=1)[:, 1::2] / count
    variance = (np.cumsum(difference ** 2, axis=1)[:, 1::2] - count * mean ** 2) / np.maximum(count - 1, 1)
    t = mean / np.sqrt(np.maximum(variance, np.finfo(float).tiny) / count)
    rows = np.arange(len(spacing_hz))
    last = np.maximum(n_orders, 1) - 1  # the column of K = n_orders
    if min_orders is None:
        chosen = last
    else:
        extent = np.arange(1, top + 1)[None, :]
        allowed = (extent <= n_orders[:, None]) & (extent >= np.minimum(min_orders, n_orders)[:, None])
        chosen = np.argmax(np.where(allowed, t, -np.inf), axis=1)
    mean, t, used = mean[rows, chosen], t[rows, chosen], chosen + 1
    few = n_orders < MIN_HARMONICS
    mean[few], t[few] = np.nan, np.nan
    return mean, t, np.where(few, n_orders, used)


@dataclass(frozen=True)
class _Candidate:
    spacing_hz: float
    contrast: float
    t: float
    orders: int


def _best(lines, grid, *, half_width_hz, limit):
    """The spacing of ``grid`` with the largest contrast (None when no spacing has enough lines)."""
    values, t, orders = comb_statistics(lines, grid, half_width_hz=half_width_hz, limit=limit)
    if not np.any(np.isfinite(values)):
        return None
    i = int(np.nanargmax(values))
    return _Candidate(float(grid[i]), float(values[i]), float(t[i]), int(orders[i]))


def _search(lines, low_hz, high_hz, *, half_width_hz, max_points=MAX_GRID_POINTS, max_orders=MAX_FINE_HARMONICS):
    """Best spacing in ``[low_hz, high_hz]``: a grid fine enough for the top line, then refined around the best;
    scored on the orders in the band, at most ``max_orders``."""
    limit = int(min(max_orders, max(MIN_HARMONICS, np.floor(half_width_hz / high_hz))))
    step = max(lines.resolution_hz / (4 * limit), (high_hz - low_hz) / max_points)
    best = _best(lines, np.arange(low_hz, high_hz + step, step), half_width_hz=half_width_hz, limit=limit)
    while best is not None and step > lines.resolution_hz / (4 * max(best.orders, 1)):
        low_hz, high_hz = best.spacing_hz - 2 * step, best.spacing_hz + 2 * step
        step = max(lines.resolution_hz / (4 * max(best.orders, 1)), (high_hz - low_hz) / max_points)
        best = _best(lines, np.arange(low_hz, high_hz + step, step), half_width_hz=half_width_hz, limit=limit)
    return best


def _at_edge(spacing_hz, low_hz, high_hz):
    """Whether ``spacing_hz`` lies within ``EDGE_SHARE`` of the search window ``[low_hz, high_hz]``'s edges."""
    return min(spacing_hz - low_hz, high_hz - spacing_hz) < EDGE_SHARE * (high_hz - low_hz)


def _held_search(lines, low_hz, high_hz, *, half_width_hz):
    """:func:`_search` on the orders where the comb holds: the extent (``MAX_COARSE_HARMONICS`` orders and up)
    of the best t at the centre, then at the spacing found (one fixed extent for every spacing compared:
    fewer, stronger low orders would otherwise favour a spacing that misses the higher ones)."""
    spacing_hz = 0.5 * (low_hz + high_hz)
    best = None
    for _ in range(2):
        extent = int(comb_statistics(lines, spacing_hz, half_width_hz=half_width_hz, limit=MAX_FINE_HARMONICS,
                                     min_orders=MAX_COARSE_HARMONICS)[2][0])
        best = _search(lines, low_hz, high_hz, half_width_hz=half_width_hz, max_orders=max(extent, MIN_HARMONICS))
        if best is None or _at_edge(best.spacing_hz, low_hz, high_hz):
            return None  # the best at the window's edge: the comb lies beyond it, if anywhere
        spacing_hz = best.spacing_hz
    return best


def _fundamental_comb(lines, comb, *, half_width_hz, min_hz):
    """``comb``, or the comb at one of its sub-multiples ``f / m`` (m = 2..MAX_BLADES) on the whole-dwell lines.

    The coarse search ranks spacings on short segments, where rotors a per cent apart smear their high
    orders: a multiple 5 f whose few lines happen to be the strongest (a blade's line weights rise and
    fall along the band) can then win. On the whole dwell the summed-contrast rule of the coarse search
    is applied again among ``f / m``, each scored over one Doppler extent: the largest spacing whose comb
    (``t >= COMB_T``) sums ``MULTIPLE_SHARE`` of the best sum is the comb (a K-band quadrotor at 63.6 rev/s
    read 635 Hz for 127).
    """
    spacings = comb.spacing_hz / np.arange(1, MAX_BLADES + 1)
    spacings = spacings[spacings >= min_hz]
    if len(spacings) < 2:
        return comb
    # every candidate scored over one extent (sub-multiples of a comb then sum the same lines)
    extent_hz = min(half_width_hz, MAX_FINE_HARMONICS * spacings[-1])
    contrast, t, orders = comb_statistics(lines, spacings, half_width_hz=extent_hz, limit=MAX_FINE_HARMONICS)
    total = np.where(t >= COMB_T, contrast * orders, np.nan)
    if not np.any(np.isfinite(total[1:])):
        return comb
    chosen = int(np.flatnonzero(np.nan_to_num(total, nan=-np.inf) >= MULTIPLE_SHARE * np.nanmax(total))[0])
    if chosen == 0:
        return comb
    refined = _search(lines, spacings[chosen] - lines.resolution_hz, spacings[chosen] + lines.resolution_hz,
                      half_width_hz=half_width_hz)
    return refined if refined is not None and refined.t >= COMB_T else comb


def max_chop_hz(n_blades=None):
    """The fastest chopping frequency a rotor of ``n_blades`` blades (None: any count) makes, ``N`` times
    ``MAX_ROTOR_RATE_HZ``: a comb spaced wider than that is none of its chopping or turn combs."""
    return MAX_CHOP_HZ if n_blades is None else min(MAX_CHOP_HZ, n_blades * MAX_ROTOR_RATE_HZ)


def find_combs(signal, *, prf_hz, noise_power, half_width_hz, min_hz=MIN_CHOP_HZ, max_hz=MAX_CHOP_HZ, lines=None,
               folded=None):
    """Chopping frequencies (Hz) of the rotors in a body-free echo ``signal``, strongest first; None when no
    comb stands out.

    Parameters
    ----------
    signal : ndarray (n,) complex
        Slow time with the body demodulated to 0 Hz.
    prf_hz, noise_power : float
        Slow-time sample rate; noise power per chirp.
    half_width_hz : float
        Half-width of the micro-Doppler band (lines beyond it are not scored); ``prf_hz / 2`` or more
        when the band is aliased: positions are folded.
    lines : LineSpectrum, optional
        The whole-dwell :func:`line_spectrum` of ``signal``, when the caller has it already.
    folded : bool, optional
        Whether the band folds (lines of high orders wrap into the span); by default where ``half_width_hz``
        reaches ``prf_hz / 2``. An unfolded band searched over the whole span is not folded.

    1. Coarse search over ``min_hz .. max_hz`` on a Welch spectrum of ``COARSE_SEGMENT_S`` segments
       with up to ``MAX_COARSE_HARMONICS`` lines a side, among combs with ``t >= COMB_T``. The comb's
       *summed* contrast ranks them: the true spacing f and its sub-multiples f/m explain every line,
       a multiple m f only 1/m of them; the largest spacing whose sum reaches ``MULTIPLE_SHARE`` of
       the best is taken (the sub-multiples are told apart by their half-empty positions next).
    2. Its fundamental (:func:`fundamental_hz`) must be at least ``MIN_FUNDAMENTAL_HZ``: finer lines
       are a bird's wingbeat (up to 20 Hz) or a swaying branch, not blades (a rotor turns 20 times a
       second and more).
    3. Rotors, on the whole-dwell spectrum: the best comb near the coarse one (within a third of a coarse
       bin; for an unfolded band, where none stands there or the best lies at the window's edge, within a bin:
       the coarse comb of rotors a few per cent apart is their blend, four at 137.5-143.2 Hz read 141.7 Hz in
       4 Hz bins), refined, its lines
       removed; then again within ``+-ROTOR_SPREAD`` while a comb reaches ``ROTOR_SHARE`` of the first
       one's contrast with ``t >= COMB_T``. The combs are scored over every order in the band; when the
       first one then falls short of ``COMB_T``, over the extent of orders (``MAX_COARSE_HARMONICS``
       and up) where it holds best: rotors a few per cent apart smear their high orders into each
       other's (four rotors at 94-101 rev/s seen for 0.16 s at X band stood out to the 8th order only).
    """
    max_hz = min(max_hz, half_width_hz / MIN_HARMONICS)
    if max_hz <= min_hz:
        return None
    segment = int(min(len(signal), round(COARSE_SEGMENT_S * prf_hz)))
    coarse = line_spectrum(signal, prf_hz=prf_hz, noise_power=noise_power, segment_chirps=segment)
    step = coarse.resolution_hz / (2 * MAX_COARSE_HARMONICS)
    grid = np.arange(min_hz, max_hz, step)
    if len(grid) < 16:
        return None
    values, t, _ = comb_statistics(coarse, grid, half_width_hz=half_width_hz, limit=MAX_COARSE_HARMONICS)
    # the lines a comb explains in the whole band: a multiple m f of the comb explains 1/m of them
    total = np.where(t >= COMB_T, values * np.floor(half_width_hz / grid), np.nan)
    if not np.any(np.isfinite(total)):
        return None
    peaks = local_maxima(total)
    peaks = peaks[total[peaks] >= MULTIPLE_SHARE * np.nanmax(total)]
    if len(peaks) == 0:
        return None
    guess = float(grid[peaks.max()])
    if fundamental_hz(coarse, guess, half_width_hz=half_width_hz) < MIN_FUNDAMENTAL_HZ:
        return None
    if lines is None:
        lines = line_spectrum(signal, prf_hz=prf_hz, noise_power=noise_power)
    if folded is None:
        folded = half_width_hz >= prf_hz / 2
    # the coarse comb's spacing, to a third of its bins; or, unfolded, a blend of rotors' up to a bin off: searched
    # there where the third of a bin holds no comb, or one at its edge (the comb lies beyond)
    first = held = None
    for width in (coarse.resolution_hz / MIN_HARMONICS,) + (() if folded else (coarse.resolution_hz,)):
        low_hz, high_hz = guess - width, guess + width
        candidate, candidate_held = _search(lines, low_hz, high_hz, half_width_hz=half_width_hz), False
        if candidate is None or candidate.t < COMB_T:  # the comb may hold to fewer orders than the band has
            candidate, candidate_held = _held_search(lines, low_hz, high_hz, half_width_hz=half_width_hz), True
        if candidate is None or candidate.t < COMB_T:
            continue
        edge = _at_edge(candidate.spacing_hz, low_hz, high_hz)
        if first is None or not edge:
            first, held = candidate, candidate_held
        if not edge:
            break
    if first is None:
        return None
    if not folded and _wingbeat_lines(lines, first.spacing_hz, half_width_hz=half_width_hz,
                                      floor_hz=2 * coarse.resolution_hz):
        return None  # a wingbeat's lines, every multiple of its rate under MIN_FUNDAMENTAL_HZ: no rotor's comb
    if not folded:  # folded lines fall between a comb's and fake its sub-multiples
        first = _fundamental_comb(lines, first, half_width_hz=half_width_hz, min_hz=max(min_hz, MIN_FUNDAMENTAL_HZ))
    if not _stands_on_both_sides(lines, first, half_width_hz=half_width_hz):
        return None  # the falling side of a band, not lines
    found = [first]
    while len(found) < MAX_ROTORS:
        # every line of the comb goes, also beyond the orders it was scored on (their smear is no new rotor)
        lines = lines.without(found[-1].spacing_hz, _orders(found[-1].spacing_hz, half_width_hz, MAX_FINE_HARMONICS)
                              if held else np.arange(1, found[-1].orders + 1))
        best = _search(lines, first.spacing_hz * (1 - ROTOR_SPREAD), first.spacing_hz * (1 + ROTOR_SPREAD),
                       half_width_hz=half_width_hz, max_orders=first.orders if held else MAX_FINE_HARMONICS)
        if best is None or best.t < COMB_T or best.contrast < ROTOR_SHARE * first.contrast:
            break
        found.append(best)
    return tuple(c.spacing_hz for c in found)


def _stands_on_both_sides(lines, comb, *, half_width_hz):
    """Whether the lines of ``comb`` (a :class:`_Candidate`, scored against the half-way points beyond them,
    ``+-(k + 1/2) f``) stand over the half-way points on their inner side too, ``+-(k - 1/2) f``, over the same
    orders: with ``INNER_SHARE`` of the outer t, and ``INNER_SHARE`` of ``COMB_T`` at least.

    Lines stand over both neighbours alike; a band whose power falls away from 0 Hz puts every position above the
    one beyond it, and the outer contrast reads that fall as a comb (a point target whose demodulation left a
    skirt about its body line, a comb at 29.9 Hz: t 12.0 outside, -8.0 inside; a crow's wings at 94 GHz, 301 Hz: 9.6
    and 2.0; a heron's at 77 GHz, 227 Hz: 12.4 and 4.1). The 64 drones' first combs of the default evaluation sweep
    (t 8 and more outside) stood inside with 0.53-2.2 of their outer t, under 0.73 only where the band held 3 orders.
    """
    t_inner = comb_statistics(lines, comb.spacing_hz, half_width_hz=half_width_hz, limit=comb.orders, offset=-0.5)[1][0]
    return bool(t_inner >= INNER_SHARE * max(COMB_T, comb.t))


def _wingbeat_lines(lines, spacing_hz, *, half_width_hz, floor_hz):
    """Whether the whole dwell's ``lines`` hold the comb at ``spacing_hz`` as part of one at a sub-multiple under
    ``MIN_FUNDAMENTAL_HZ`` (down to ``floor_hz``, the coarse test's two bins): its contrast reaching
    ``FUNDAMENTAL_SHARE`` of the comb's (:func:`_strong_divisors`), step 2 of :func:`find_combs` on the whole dwell.

    A wingbeat's echo repeats every 1 / f_wb: lines at every k f_wb, and a comb at any odd multiple m f_wb has its
    half-way positions half-way between them (even m lands them on lines). The coarse test's 0.25 s segments hold
    two or three wingbeats: lines 8-9 Hz apart fall within each other's Hann main lobes (+-8 Hz) and their half-way
    positions read lit, so the contrast at f_wb reads 0.17-0.63 of the multiple's (birds beating 8.4-9.2 Hz read as
    combs at 3, 7 and 11 f_wb), against 0.71-0.95 on the whole dwell. A rotor's comb has nothing between its lines
    but a differing blade's sub-lines at its turn rate (over 20 rev/s): its sub-multiples reach 1/m of its contrast.
    """
    divisors = np.arange(2, int(spacing_hz / floor_hz) + 1)
    divisors = divisors[spacing_hz / divisors < MIN_FUNDAMENTAL_HZ]
    strong = _strong_divisors(lines, spacing_hz, divisors, half_width_hz=half_width_hz)
    return strong is not None and len(strong) > 0


def comb_offset_hz(signal, *, prf_hz, noise_power, half_width_hz):
    """The Doppler about which a rotor's line comb lies when no body line marks it, or None.

    The power envelope ``|s|^2`` does not see a constant Doppler: its spectrum has lines at multiples
    of the flash rate F whatever the body's motion. The chopping frequency is F (N even) or F/2 (N
    odd); the offset is where the complex comb of that spacing lands on its lines (and not half-way)
    best, searched over one spacing in half-bin steps.
    """
    envelope = np.abs(np.asarray(signal)) ** 2
    flashes = find_combs(envelope - envelope.mean(), prf_hz=prf_hz, noise_power=None,
                         half_width_hz=min(2 * half_width_hz, prf_hz / 2))
    if flashes is None:
        return None
    lines = line_spectrum(signal, prf_hz=prf_hz, noise_power=noise_power)
    best_contrast, best_offset = -np.inf, None
    for spacing in (flashes[0], flashes[0] / 2):
        k = np.arange(-min(MAX_FINE_HARMONICS, int(half_width_hz / spacing)),
                      min(MAX_FINE_HARMONICS, int(half_width_hz / spacing)) + 1)
        offsets = np.arange(-spacing / 2, spacing / 2, lines.resolution_hz / 2)
        positions = offsets[:, None] + spacing * k[None, :]
        contrast = (lines.at(positions) - lines.at(positions + spacing / 2)).mean(axis=1)
        i = int(np.argmax(contrast))
        if contrast[i] > best_contrast:
            best_contrast, best_offset = contrast[i], float(offsets[i])
    return best_offset


def fundamental_hz(lines, spacing_hz, *, half_width_hz):
    """The smallest ``spacing_hz / m`` whose comb contrast reaches ``FUNDAMENTAL_SHARE`` of ``spacing_hz``'s.

    Candidates down to two bins of ``lines``. A rotor's comb has nothing between its lines unless a
    blade differs (then the turn rate, m = N); a bird's wingbeat lines continue below 20 Hz.
    """
    strong = _strong_divisors(lines, spacing_hz, np.arange(2, int(spacing_hz / (2 * lines.resolution_hz)) + 1),
                              half_width_hz=half_width_hz)
    if strong is None:
        return spacing_hz
    return float(spacing_hz / strong.max()) if len(strong) else float(spacing_hz)


def _strong_divisors(lines, spacing_hz, divisors, *, half_width_hz, min_orders=None):
    """The ``divisors`` m whose comb at ``spacing_hz / m`` reaches ``FUNDAMENTAL_SHARE`` of the contrast of the comb
    at ``spacing_hz`` (:func:`comb_statistics`, ``min_orders`` passed on), in increasing order; None when there is
    no divisor or no reference contrast."""
    stats = dict(half_width_hz=half_width_hz, limit=MAX_FINE_HARMONICS, min_orders=min_orders)
    reference = comb_statistics(lines, spacing_hz, **stats)[0][0]
    if len(divisors) == 0 or not np.isfinite(reference):
        return None
    values = comb_statistics(lines, spacing_hz / divisors, **stats)[0]
    return divisors[np.nan_to_num(values, nan=-np.inf) >= FUNDAMENTAL_SHARE * reference]


def lines_between(lines, spacing_hz, *, half_width_hz, min_hz):
    """The largest m (2..MAX_BLADES, ``spacing_hz / m >= min_hz``) whose comb at ``spacing_hz / m`` holds lines
    between those of the comb at ``spacing_hz`` as strong as its own, else 0: the comb is then m times the
    echo's fundamental.

    A comb at a multiple m f of a rotor's chopping frequency f has the rotor's lines between its own: f scores
    ``FUNDAMENTAL_SHARE`` of m f's contrast or more, and no every-m-th line of it stands out
    (:func:`blade_count_from_line_pattern`). A true comb's sub-multiple f / m has all but 1/m of its positions
    empty (1/m of the contrast), or, one of m blades differing, weaker lines between: every m-th stands out.
    Each comb is scored over the orders within ``half_width_hz`` where it holds (rotors a few per cent apart
    smear a sub-multiple's higher orders first).
    """
    divisors = np.arange(2, MAX_BLADES + 1)
    strong = _strong_divisors(lines, spacing_hz, divisors[spacing_hz / divisors >= min_hz],
                              half_width_hz=half_width_hz, min_orders=MIN_HARMONICS)
    for m in [] if strong is None else strong[::-1]:
        if blade_count_from_line_pattern(lines, spacing_hz / m, half_width_hz=half_width_hz) != m:
            return int(m)
    return 0


def comb_extent_hz(lines, spacing_hz, *, half_width_hz):
    """How far out (Hz) the comb at ``spacing_hz`` holds: its orders (``MIN_HARMONICS`` up, within
    ``half_width_hz``, at most ``MAX_FINE_HARMONICS``) where its t is largest, times the spacing."""
    orders = comb_statistics(lines, spacing_hz, half_width_hz=half_width_hz, limit=MAX_FINE_HARMONICS,
                             min_orders=MIN_HARMONICS)[2][0]
    return float(orders * spacing_hz)


def _orders(spacing_hz, half_width_hz, limit):
    """Line orders 1..K on each side whose positions lie within the band (at most ``limit``)."""
    return np.arange(1, int(np.clip(np.floor(half_width_hz / spacing_hz), 0, limit)) + 1)


def blade_count_from_sublines(lines, chopping_hz, *, half_width_hz):
    """N from the lines between the chopping lines (blades of unequal reflectivity), or None.

    For each d = MAX_BLADES .. 2 the positions ``(k + j/d) f_chop``, j = 1..d-1, are scored against
    the positions half-way between them; the largest d with every j significant is N.
    """
    order = _orders(chopping_hz, half_width_hz, MAX_FINE_HARMONICS)
    if len(order) < MIN_HARMONICS:
        return None
    k = np.concatenate([order - 1, -order]).astype(float)  # the gaps on both sides of 0 Hz
    for d in range(MAX_BLADES, 1, -1):
        significant = []
        for j in range(1, d):
            on = lines.at((k + j / d) * chopping_hz)
            off = lines.at((k + (j + 0.5) / d) * chopping_hz)
            spread = np.std(off) / np.sqrt(len(off))
            significant.append(spread > 0 and (on.mean() - off.mean()) / spread >= SUBLINE_Z)
        if all(significant):
            return d
    return None


def blade_count_from_line_pattern(lines, spacing_hz, *, half_width_hz):
    """N when every N-th line of the comb at ``spacing_hz`` stands out (the comb is a turn, one blade differs).

    For d = 2 .. MAX_BLADES the line scores are fitted, each side of 0 Hz, by a trend (a linear spline
    with knots about ``2 d`` orders apart or more) plus a step ``delta`` at the orders that are multiples of d
    (:func:`pattern_step`). A comb's scores fall towards the band's edges, and over the handful of orders
    of a rotor seen nearly face-on that fall outweighs the pattern in plain means (a 2-blade rotor with one
    blade 1.7x brighter, eight orders a side: every even line 2.4 stronger than its odd neighbours, yet 1.6
    over the others' mean with a t of 1.1). Of the d whose step is at least ``PATTERN_MARGIN`` (in
    ``log(1 + SNR)``) with a t of ``SUBLINE_Z``, the one with the largest step is N (multiples of 2N also
    stand out, by less: the rest then holds strong lines too). None when the lines carry no such pattern.
    """
    order = _pattern_orders(spacing_hz, half_width_hz)
    best, best_step = None, PATTERN_MARGIN
    for d in range(2, MAX_BLADES + 1):
        found = _multiples_step(lines, spacing_hz, order, d)
        if found is not None and found[0] >= best_step and found[1] >= SUBLINE_Z:
            best, best_step = d, found[0]
    return best


def odd_orders_stand_out(lines, spacing_hz, *, half_width_hz):
    """Whether the comb at ``spacing_hz`` is one at twice it about a Doppler half a spacing off 0 Hz: its odd orders
    stand out over the even ones (the even orders' step under its trend, :func:`pattern_step` with d = 2, at most
    ``-PATTERN_MARGIN`` with a t of ``-SUBLINE_Z``).

    About its own Doppler a rotor's strongest lines are its chopping comb's, from order 0; a differing blade adds
    weaker ones between. Demodulated half a chopping frequency off (no body line marked the hub's Doppler, and a comb
    is as symmetric about the point half-way between two of its lines as about one of them), the chopping lines
    fall at odd multiples of half the chopping frequency, the comb read there (six rotors of an independent
    simulator, 2 blades given, read at half their rate, `ok`). Read only on a comb no body line centred: rotors at one
    rate whose phases cancel their even orders stand so too."""
    found = _multiples_step(lines, spacing_hz, _pattern_orders(spacing_hz, half_width_hz), 2)
    return found is not None and found[0] <= -PATTERN_MARGIN and found[1] <= -SUBLINE_Z


def _pattern_orders(spacing_hz, half_width_hz):
    """The comb's orders a line pattern is read over (:func:`blade_count_from_line_pattern`)."""
    return _orders(spacing_hz, half_width_hz, MAX_FINE_HARMONICS * MAX_BLADES)


def _multiples_step(lines, spacing_hz, order, d):
    """:func:`pattern_step` of the comb's line scores at ``order`` each side of 0 Hz, for the multiples of ``d``; None
    where under ``MIN_HARMONICS`` of the orders are such multiples (or too few scores for a trend)."""
    if np.count_nonzero(order % d == 0) < MIN_HARMONICS:
        return None
    return pattern_step(lines.at(order * spacing_hz), lines.at(-order * spacing_hz), order, d)


def pattern_step(positive, negative, order, d):
    """(step, t) of the scores at multiples of ``d`` over a trend, or None when too few scores for it.

    ``positive``, ``negative``: line scores at orders ``order`` (1..K) above and below 0 Hz. Least squares
    of both sides' scores on a linear spline per side (knots evenly spaced, about ``2 d`` orders apart or more,
    at most ``PATTERN_KNOTS`` a side: the envelope's fall, not the pattern) and one step common to the
    multiples of d; t is the step over its standard error, from the fit's residuals.
    """
    count = len(order)
    n_knots = int(np.clip(count // (2 * d) + 1, 2, PATTERN_KNOTS))
    if 2 * count - (2 * n_knots + 1) < MIN_PATTERN_DOF:
        return None
    knots = np.linspace(order[0], order[-1], n_knots)
    hats = np.clip(1 - np.abs(order[:, None] - knots[None, :]) / (knots[1] - knots[0]), 0, None)
    zero = np.zeros_like(hats)
    step = (order % d == 0).astype(float)
    design = np.vstack([np.hstack([hats, zero, step[:, None]]), np.hstack([zero, hats, step[:, None]])])
    scores = np.concatenate([positive, negative])
    dof = len(scores) - design.shape[1]
    coef, _, rank, _ = np.linalg.lstsq(design, scores, rcond=None)
    if rank < design.shape[1]:
        return None
    residual = scores - design @ coef
    variance = float(residual @ residual) / dof
    unscaled = np.linalg.inv(design.T @ design)[-1, -1]
    error = np.sqrt(variance * unscaled)
    return float(coef[-1]), float(coef[-1] / error) if error > 0 else np.inf


def flashes_doubled(signal, spacing_hz, *, prf_hz, half_width_hz):
    """True when the power envelope repeats twice per comb spacing, False when once, None unclear.

    Twice: an odd N's flashes on a chopping comb (approaching and receding broadside each blade passage),
    or an even N's on its turn comb (one blade differing). The envelope ``|s|^2`` then has lines at even
    multiples of the spacing only. Once tells neither apart from an odd N whose two flashes differ in
    strength (:func:`odd_blades` reads the sides instead).
    """
    envelope = np.abs(np.asarray(signal)) ** 2
    envelope = envelope - envelope.mean()
    spread = np.median(envelope ** 2) ** 0.5
    if not spread > 0:
        return None
    lines = line_spectrum(envelope, prf_hz=prf_hz, noise_power=float(np.mean(envelope ** 2)))
    order = _orders(spacing_hz, min(half_width_hz, prf_hz / 2), 16)
    if len(order) < 2:
        return None
    odd = order[order % 2 == 1].astype(float)
    even = order[order % 2 == 0].astype(float)
    gap = lambda k: lines.at(k * spacing_hz) - lines.at((k + 0.25) * spacing_hz)  # noqa: E731
    even_contrast, odd_contrast = gap(even).mean(), gap(odd).mean()
    if even_contrast <= 0:
        return None
    return bool(odd_contrast < DOUBLING_SHARE * even_contrast)


def odd_blades(signal, chopping_hz, *, prf_hz, half_width_hz):
    """True when the blades flash one side at a time (odd N), False when both sides flash together (even N),
    None when the echo does not tell.

    A blade flashes broadside, approaching on one side of the Doppler span or receding on the other. N even:
    the opposite blade recedes as one approaches, and every flash spans both sides. N odd: the receding
    broadside comes half a chopping period after an approaching one, and the flashes alternate sides. So the
    powers of the outer parts of the two sides (beyond ``SIDE_INNER`` of the band: blades, not the body),
    less their running mean over a chopping period, correlate at lag 0 (even) or at half a chopping period
    (odd); the other lag holds at most ``PARITY_SHARE`` of it and the one that tells ``MIN_SIDE_CORRELATION``.
    This does not ask the power to repeat twice per chopping period (:func:`flashes_doubled`), which an odd
    N's does only where its approaching and receding flashes are alike: those lines read a three-blade drone
    of the default sweep as even and contradicted the 3 blades given, and three 2-blade drones whose combs were
    their turn rates (one blade brighter) as odd. Of the sweep's 37 drones whose combs were read so, this test
    told 26 (the others: both lags or neither) and erred on none.
    """
    x = np.asarray(signal, dtype=np.complex128)
    f_hz = np.fft.fftfreq(len(x), 1.0 / prf_hz)
    spectrum = np.fft.fft(x)
    outer = min(half_width_hz, prf_hz / 2)
    period = prf_hz / chopping_hz
    if period < 8:  # the lags 0 and half a period, each read within +-1 chirp, at least two chirps apart
        return None
    sides = []
    for keep in (f_hz > SIDE_INNER * outer) & (f_hz <= outer), (f_hz < -SIDE_INNER * outer) & (f_hz >= -outer):
        power = np.abs(np.fft.ifft(np.where(keep, spectrum, 0))) ** 2
        sides.append(power - moving_average(power, int(round(period)) | 1, mode="inside"))
    approaching, receding = sides
    norm = np.sqrt(np.mean(approaching ** 2) * np.mean(receding ** 2))
    if not norm > 0:
        return None

    def correlation(lag):  # the largest within +-1 chirp (flash times are known to a chirp)
        k = int(round(lag))
        return max(float(np.mean(approaching * np.roll(receding, -j))) for j in range(k - 1, k + 2)) / norm

    together, alternate = correlation(0), 0.5 * (correlation(period / 2) + correlation(-period / 2))
    if alternate >= MIN_SIDE_CORRELATION and together <= PARITY_SHARE * alternate:
        return True
    if together >= MIN_SIDE_CORRELATION and alternate <= PARITY_SHARE * together:
        return False
    return None
