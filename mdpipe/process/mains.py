"""Mains hum: lines at the harmonics of the power grid's frequency that a receiver picks up, found and taken out.

A CW radar recorded through a sound card picks up the grid's 50 or 60 Hz and its harmonics (a rectifier's
ripple: the even ones); an FMCW radar's supply ripple modulates its gain, and every strong static echo then
carries the ripple as Doppler lines at ``+-k f_mains`` about 0 Hz. Either way the lines lie at whole multiples
of one frequency within ``GRID_TOLERANCE`` of 50 or 60 Hz (grids hold +-0.2 Hz, a field generator about 1 %),
fixed in the receiver's frame: sharp to the dwell's resolution at every order, where a flying target's lines
ride on its body's Doppler. Read as an echo they are a line comb (mains hum 10 dB over the noise of a 4 s
recording read as a drone at 50 rev/s, ``ok``) or, weak, wings beating.

:func:`find_hum` reads them on the echo as received (not demodulated by any body track), :func:`without_hum`
takes them out by notches. A rotor turning at a multiple of the grid's frequency and held still (a test stand at
3000 rpm under a 50 Hz grid) gives sharp lines at the same orders, but its comb runs on beyond hum's harmonics
(across its tips' Doppler, folded over the span): where the span shows the orders beyond ``MAX_ORDERS`` and the
lines go on there, they are no hum. Where it does not, the comb is taken for hum and out with it; a chopping
comb read on those lines after all is withheld (:data:`STATUS`), and ``--mains-hz none`` skips the search.
"""

from dataclasses import dataclass

import numpy as np

from mdpipe.process.doppler import periodic_hann
from mdpipe.process.filters import parabolic_offset, triangular_average

GRID_TOLERANCE = 0.01    # the grid's frequency within 1 % of its nominal
FIRST_ORDERS = 2         # the frequency is read on lines at the first two orders (a rectifier's ripple: the 2nd)
MAX_ORDERS = 40          # hum harmonics searched up to this order (2 kHz at 50 Hz) ...
CONTINUES_SHARE = 0.5    # ... and a comb whose lines go on beyond it this densely, a share of its upper half's, no hum
LINE_RATIO = 30.0        # a hum line's bin over the spectrum's local median (noise passes it w.p. 2^-30)
SHARP_BINS = 3           # ... and sharp: this many resolution bins either side of it, under BESIDE_SHARE of it
BESIDE_SHARE = 0.1       # (a line smeared over a few bins by a body's sway or a rotor's wander holds a third)
BESIDE_NOISE = 8.0       # ... or no more than noise reaches there (8 times its median: w.p. 2^-8)
FLOOR_HZ = 25.0          # the local median is taken over +-this about each order
DRIFT = 2e-4             # the grid's frequency moves about 0.01 Hz over a recording: order k within k times this
WANDER = 2e-3            # ... and, once hum is found, its orders taken out within k times this, smeared or not
MIN_LINES = 6            # (a hexarotor near 60 rev/s met 3 orders of 60.2 Hz, sharp and on them, by chance)
CHANCE_OFFSETS = (1 / 3, 1 / 2, 2 / 3)  # hum's lines outnumber those at these fractions between its orders (other
CHANCE_SIGMAS = 3.0      # lines met by chance) by MIN_LINES and this many Poisson deviations of the most of them
FINER_SHARE = 0.5        # a comb f0 / m apart (m up to 7) whose every position between the orders holds this share of
                         # the lines at them is a finer comb's (a wingbeat of 10 Hz about a still body: 16 orders)
RIPPLE_ORDERS = 4        # a ripple's lines in a power: at the grid's rate or twice it, and their doubles
MAX_LINE_STEP = 2        # hum's lines lie at every order, or (a rectifier's ripple) every second one
MAX_OFF = 0.25           # ... on them: their median offset from k f0 this share of the reach allowed (lines met by
                         # chance within it: about half; hum's 0.001-0.1, drifting 0.2 Hz over 10 s included)
MIN_CYCLES = 10          # a dwell of at least 10 periods of the grid (0.2 s at 50 Hz): its lines resolved apart
NOTCH_CYCLES = 25        # under 25 (0.5 s), a line's envelope is its mean over the dwell: notches of a bin a side
NOTCH_S = 1.0            # each line's envelope averaged over this (or the dwell): first null max(2 Hz, 2 bins) off
PAD = 2                  # zero-padding of the spectrum lines are read on
TRACK_S = 1.0            # the strongest line's phase followed over this (its wander, within about 1 Hz of it)
PASSES = 3               # hum searched again in what its notches leave, up to this many times
STATUS = "mains_hum"     # a chopping comb on the hum's lines taken out: withheld
SEARCH = object()        # analyse_target's default: look for hum in the echo (a caller may have taken it out)


def repeats_with_grid(period_s, mains_hz):
    """Whether a power repeating every ``period_s`` repeats with the grid: a whole number of half periods of one of
    ``mains_hz`` (a supply's ripple on the gain, its fundamental or a rectifier's second harmonic), each within
    ``GRID_TOLERANCE``."""
    for f_hz in mains_hz:
        halves = period_s * 2.0 * f_hz
        if round(halves) >= 1 and abs(halves - round(halves)) <= GRID_TOLERANCE * round(halves):
            return True
    return False


def line_on_grid(f_hz, mains_hz, *, prf_hz, resolution_hz=0.0):
    """Whether a line read at ``f_hz`` in a power's spectrum (0 to PRF / 2, on bins ``resolution_hz`` apart) lies on
    one of the first ``RIPPLE_ORDERS`` harmonics of one of ``mains_hz``, folded by ``prf_hz``, order k within k
    ``GRID_TOLERANCE`` and half a bin: a supply's ripple on the gain (at the grid's rate, or a rectifier's twice it)
    swells the clutter about a target, whose power then holds the ripple's lines and their doubles."""
    orders = np.arange(1, RIPPLE_ORDERS + 1)
    for mains_f_hz in mains_hz:
        folded = np.abs(np.mod(orders * mains_f_hz + prf_hz / 2, prf_hz) - prf_hz / 2)
        if np.any(np.abs(folded - f_hz) <= GRID_TOLERANCE * orders * mains_f_hz + resolution_hz / 2):
            return True
    return False


def notch_boxcar(n, prf_hz):
    """Samples of each of the two boxcars that average a hum line's envelope: half the dwell, at most
    ``NOTCH_S / 2``."""
    return max(1, min(n // 2, int(round(NOTCH_S * prf_hz / 2))))


def _whole(n, prf_hz, f0_hz):
    """Whether a dwell of ``n`` samples is too short (under ``NOTCH_CYCLES`` periods of ``f0_hz``) for a notch that
    follows a line's envelope, two bins a side of it: each line is then taken out as its mean over the dwell (a
    steady tone's least-squares fit), one bin a side (0.22-0.35 s CW recordings with hum 20 dB over their noise read
    chopping frequencies of 50 Hz, ``ok``, where hum was not searched under 0.5 s)."""
    return n / prf_hz < NOTCH_CYCLES / f0_hz


@dataclass(frozen=True)
class Hum:
    """Mains hum found in an echo: the grid frequency ``f0_hz``, its lines ((signed order, Hz), strongest first)
    and the notches' half-width (Hz: their first null)."""

    f0_hz: float
    lines: tuple
    notch_hz: float

    def note(self):
        return (f"mains hum at {self.f0_hz:.2f} Hz: {len(self.lines)} lines at its harmonics taken out before the "
                f"analysis (--mains-hz none keeps them)")

    def covers(self, body_hz, spacing_hz, *, prf_hz, orders=8):
        """Whether a comb of lines at ``body_hz + k spacing_hz`` (k = +-1..+-``orders``, folded into the span
        ``prf_hz``) fell, half of them or more, within the notches taken out."""
        taken = np.array([f for _, f in self.lines])
        k = np.concatenate([np.arange(1, orders + 1), -np.arange(1, orders + 1)])
        positions = np.mod(body_hz + k * spacing_hz + prf_hz / 2, prf_hz) - prf_hz / 2
        near = np.min(np.abs(positions[:, None] - taken[None, :]), axis=1) < self.notch_hz
        return bool(np.mean(near) >= 0.5)


class _Spectrum:
    """The echo's Hann periodogram (zero-padded ``PAD`` times) and what a hum line is tested against."""

    def __init__(self, signal, prf_hz):
        n = len(signal)
        self.prf_hz, self.resolution_hz = prf_hz, prf_hz / n
        self.power = np.abs(np.fft.fft(signal * periodic_hann(n), PAD * n)) ** 2
        self.bin_hz = prf_hz / len(self.power)

    def _bins(self, low_hz, high_hz):
        return np.arange(int(np.floor(low_hz / self.bin_hz)), int(np.ceil(high_hz / self.bin_hz)) + 1)

    def line(self, low_hz, high_hz, floor_centre_hz, *, sharp=True):
        """The line standing in ``[low_hz, high_hz]``, (Hz, power): the strongest bin there, refined by a parabola
        through its log-power neighbours, if it stands ``LINE_RATIO`` over the local median and is ``sharp``; else
        None."""
        m = len(self.power)
        window = self._bins(low_hz, high_hz)
        peak = int(window[np.argmax(self.power[window % m])])
        value = self.power[peak % m]
        floor = np.median(self.power[self._bins(floor_centre_hz - FLOOR_HZ, floor_centre_hz + FLOOR_HZ) % m])
        if value < LINE_RATIO * floor:
            return None
        beside = int(round(SHARP_BINS * self.resolution_hz / self.bin_hz))
        for side in (peak - beside, peak + beside) if sharp else ():
            if self.power[side % m] > max(BESIDE_SHARE * value, BESIDE_NOISE * floor):
                return None
        left, mid, right = np.log(self.power[[(peak - 1) % m, peak % m, (peak + 1) % m]] + np.finfo(float).tiny)
        return (peak + float(parabolic_offset(left, mid, right))) * self.bin_hz, float(value)


def _fitted(lines):
    """The frequency whose multiples the ``lines`` ((order, Hz, power), ...) lie on: least squares through 0."""
    k, f = np.array([line[:2] for line in lines], dtype=float).T
    return float(np.sum(k * f) / np.sum(k * k))


def _reach(resolution_hz, k, f0_hz, drift=DRIFT):
    """How far from ``k f0_hz`` a line of order ``k`` may lie: half a resolution bin and the grid's ``drift``."""
    return resolution_hz / 2 + abs(k) * drift * f0_hz


def _lines_at(spectrum, f0_hz, orders, *, drift=DRIFT, sharp=True):
    """(order, Hz, power) of the lines standing at ``+-orders`` (may be fractional) times ``f0_hz``, each within
    :func:`_reach` of it (and ``sharp``)."""
    return _lines_within(spectrum, f0_hz, np.concatenate([orders, -orders]),
                         lambda k: _reach(spectrum.resolution_hz, k, f0_hz, drift), sharp=sharp)


def _lines_within(spectrum, f0_hz, signed_orders, reach, *, sharp=True):
    """(order, Hz, power) of the lines standing within ``reach(k)`` of ``k f0_hz``, for each of ``signed_orders``."""
    found = []
    for k in signed_orders:
        line = spectrum.line(k * f0_hz - reach(k), k * f0_hz + reach(k), k * f0_hz, sharp=sharp)
        if line is not None:
            found.append((float(k), *line))
    return found


def _consistent(lines, f0_hz, resolution_hz):
    return [line for line in lines if abs(line[1] - line[0] * f0_hz) <= _reach(resolution_hz, line[0], f0_hz)]


def _top_order(prf_hz, f0_hz):
    """The highest order whose line and local floor lie inside the span."""
    return int(np.floor((prf_hz / 2 - FLOOR_HZ) / (f0_hz * (1 + GRID_TOLERANCE))))


def find_hum(signal, *, prf_hz, mains_hz):
    """:class:`Hum` in a complex slow-time ``signal`` (its mean removed) sampled at ``prf_hz``, or None.

    For each nominal grid frequency F (``mains_hz``, Hz: ``ProcessParams.mains_frequencies_hz``): lines at the
    first ``FIRST_ORDERS`` orders, each sign, within ``GRID_TOLERANCE`` of ``k F``, that agree on one frequency f0
    (two at least: the grid's own line and a rectifier's at twice it are hum's strongest); then a line at each order
    ``+-k`` up to ``MAX_ORDERS`` (and the span's edge) within half a resolution bin and the grid's drift of ``k f0``.
    Hum when f0, refitted on them, stays within ``GRID_TOLERANCE`` of F, and they are ``MIN_LINES`` or more, at
    orders whose greatest common divisor is at most ``MAX_LINE_STEP`` (the grid's harmonics, or a rectifier's ripple
    at the even ones: a rotor of equal blades held still at 100 rev/s, lines every 200 Hz, is no hum), more than the
    lines standing at fractions between the orders, which a spectrum dense with a target's lines meets as often
    (``CHANCE_OFFSETS``: hexarotors at 77 GHz, their folded combs sharp, met 3-14 orders of 50-60 Hz by chance), with
    no finer comb among them (``FINER_SHARE``), and
    they lie on the orders (``MAX_OFF``: a hexarotor's rotors 1-2 % apart about 60 rev/s met 24 orders of 60.2 Hz,
    each line somewhere within the reach allowed), and they do not go on beyond ``MAX_ORDERS``
    (``CONTINUES_SHARE``) where the span shows orders there: a rotor's comb,
    held still at a multiple of the grid's rate, spans its tips' Doppler (one at 60.3 rev/s, its blades unequal, at
    77 GHz, read as hum and lost as a drone). A dwell shorter than ``MIN_CYCLES`` periods is not searched.
    """
    signal = np.asarray(signal, dtype=np.complex128)
    n = len(signal)
    best, spectrum = None, None
    for nominal_hz in mains_hz:
        top = min(MAX_ORDERS, _top_order(prf_hz, nominal_hz))
        if top < MIN_LINES or n / prf_hz < MIN_CYCLES / nominal_hz:
            continue
        spectrum = spectrum or _Spectrum(signal, prf_hz)
        first = _lines_within(spectrum, nominal_hz, [s * k for k in range(1, FIRST_ORDERS + 1) for s in (1, -1)],
                              lambda k: abs(k) * nominal_hz * GRID_TOLERANCE)
        first = _consistent(first, _fitted(first), spectrum.resolution_hz) if len(first) >= 2 else []
        if len(first) < 2:
            continue
        lines = _lines_at(spectrum, _fitted(first), np.arange(1, top + 1))
        lines = _consistent(lines, _fitted(lines), spectrum.resolution_hz) if len(lines) >= MIN_LINES else []
        if len(lines) < MIN_LINES:
            continue
        f0 = _fitted(lines)
        chance = max(len(_lines_at(spectrum, f0, np.arange(top) + offset)) for offset in CHANCE_OFFSETS)
        finer = any(all(len(_lines_at(spectrum, f0, np.arange(top) + j / m)) >= FINER_SHARE * len(lines)
                        for j in range(1, m)) for m in range(2, 8))
        off = np.median([abs(f - k * f0) / _reach(spectrum.resolution_hz, k, f0) for k, f, _ in lines])
        if (abs(f0 / nominal_hz - 1) > GRID_TOLERANCE or np.gcd.reduce([int(round(abs(line[0]))) for line in lines])
                > MAX_LINE_STEP or len(lines) < MIN_LINES + chance + CHANCE_SIGMAS * np.sqrt(chance)
                or off > MAX_OFF or finer or _goes_on(spectrum, f0, lines, top)):
            continue
        if best is None or len(lines) > len(best.lines):
            # taken out: every order standing out, smeared or not (a line's wander smears it k times at order k)
            drifting = {k: (k, f, p) for k, f, p in _lines_at(spectrum, f0, np.arange(1, top + 1), drift=WANDER,
                                                               sharp=False)}
            lines = sorted({**drifting, **{line[0]: line for line in lines}}.values(), key=lambda line: -line[2])
            best = Hum(f0_hz=f0, lines=tuple((k, f) for k, f, _ in lines),
                       notch_hz=prf_hz / (n if _whole(n, prf_hz, f0) else notch_boxcar(n, prf_hz)))
    return best


def _goes_on(spectrum, f0_hz, lines, top):
    """Whether the comb of ``lines`` (orders up to ``top``) goes on beyond ``MAX_ORDERS`` as densely as
    ``CONTINUES_SHARE`` of its upper half, where the span shows ``MIN_LINES`` orders there or more."""
    beyond = np.arange(MAX_ORDERS + 1, min(2 * MAX_ORDERS, _top_order(spectrum.prf_hz, f0_hz)) + 1)
    if top < MAX_ORDERS or len(beyond) < MIN_LINES:
        return False
    upper = sum(abs(line[0]) > MAX_ORDERS / 2 for line in lines) / (MAX_ORDERS - MAX_ORDERS // 2)
    found = len(_lines_at(spectrum, f0_hz, beyond))
    return found / len(beyond) >= max(CONTINUES_SHARE * upper, 1e-9) and found >= MIN_LINES


def without_hum(signal, hum, *, prf_hz):
    """``signal`` (n,) or (n, columns) with each of ``hum``'s lines notched out, strongest first (a weaker line's
    envelope is then not read through a stronger one's): the echo demodulated at the line, its envelope averaged
    over ``NOTCH_S`` (or the dwell; triangular, first null ``hum.notch_hz`` off the line; on a dwell under
    ``NOTCH_CYCLES`` periods its mean), remodulated and subtracted. A steady line goes whole; a tone a quarter and
    half the notch's half-width off the line keeps 5-8 and 36 % of its power, one a half-width off or more 91 % or
    more. The grid's frequency wanders (0.01-0.05 Hz
    over seconds, k times that at order k): on a dwell of over two ``TRACK_S`` the lines are also taken out along
    the strongest one's phase, followed over ``TRACK_S`` and scaled to each order, and of the two the echo left
    weaker is kept (hum drifting 50.00 to 50.05 Hz over 10 s read as a drone, its residue 16 dB under it, with the
    fixed lines alone); a tone within about 1 Hz of the strongest line, which hum's own line outshines there, is
    then followed with it. Columns share the wander (read on their sum) and the choice."""
    out = np.array(signal, dtype=np.complex128)
    n = out.shape[0]
    t = np.arange(n) / prf_hz
    steady = _notched(out, hum, prf_hz=prf_hz)
    if n / prf_hz <= 2 * TRACK_S:
        return steady  # (no wander to follow within the dwell)
    k_strong, f_strong = hum.lines[0]
    envelope = triangular_average(out.reshape(n, -1).sum(axis=1) * np.exp(-2j * np.pi * f_strong * t),
                                  max(1, int(round(TRACK_S * prf_hz / 2))))
    wander = np.unwrap(np.angle(envelope))
    followed = _notched(out, hum, prf_hz=prf_hz, wander=(wander - wander.mean()) / k_strong)
    return steady if np.mean(np.abs(steady) ** 2) <= np.mean(np.abs(followed) ** 2) else followed


def _notched(out, hum, *, prf_hz, wander=None):
    """``out`` less each line of ``hum`` (order k, frequency f) along its phase ``2 pi f t + k wander(t)`` (``wander``:
    the grid's phase wander per order, rad, a value a sample; None: steady). Each line's envelope is averaged on
    blocks of an eighth of the grid's period (at most a sixteenth of the notch's boxcar), then brought back to every
    sample (linearly): a few passes over the echo a line."""
    out = out.copy()
    n = out.shape[0]
    size = notch_boxcar(n, prf_hz)
    block = max(1, min(size // 16, int(prf_hz / (8 * hum.f0_hz))))  # (its neighbours, f0 away, sampled 8 times a turn)
    edges = np.arange(0, n, block)
    centres = np.minimum(edges + (block - 1) / 2, (edges + n - 1) / 2)  # a short last block's centre
    t = np.arange(n) / prf_hz
    index = np.arange(n)
    whole = _whole(n, prf_hz, hum.f0_hz)
    for k, f_hz in hum.lines:
        phase = 2 * np.pi * f_hz * t if wander is None else 2 * np.pi * f_hz * t + k * wander
        carrier = np.exp(1j * phase).reshape((n,) + (1,) * (out.ndim - 1))
        if whole:
            out -= np.mean(out * np.conj(carrier), axis=0) * carrier
            continue
        blocks = np.add.reduceat(out * np.conj(carrier), edges, axis=0) / np.diff(np.append(edges, n)).reshape(
            (-1,) + (1,) * (out.ndim - 1))
        smooth = triangular_average(blocks, max(1, size // block), axis=0).reshape(len(edges), -1)
        level = np.stack([np.interp(index, centres, c.real) + 1j * np.interp(index, centres, c.imag)
                          for c in smooth.T], axis=1).reshape(out.shape)
        out -= level * carrier
    return out


def taken_out(signal, *, prf_hz, mains_hz):
    """(``signal`` with its mains hum taken out, the :class:`Hum` or None): searched again in what the notches
    leave, up to ``PASSES`` times (a strong line's residue at the dwell's ends, where its envelope is averaged over
    half the span), the lines of every pass in the one :class:`Hum` returned."""
    found = None
    for _ in range(PASSES):
        hum = find_hum(signal, prf_hz=prf_hz, mains_hz=mains_hz)
        if hum is None:
            break
        signal = without_hum(signal, hum, prf_hz=prf_hz)
        found = hum if found is None else Hum(found.f0_hz, found.lines + hum.lines, found.notch_hz)
    return signal, found
