"""Mains hum: lines at the harmonics of the power grid's frequency that a receiver picks up, found and taken out.

A CW radar recorded through a sound card picks up the grid's 50 or 60 Hz and its harmonics (a rectifier's
ripple: the even ones); an FMCW radar's supply ripple modulates its gain, and every strong static echo then
carries the ripple as Doppler lines at ``+-k f_mains`` about 0 Hz. Either way the lines lie at whole multiples
of one frequency within ``GRID_TOLERANCE`` of 50 or 60 Hz (grids hold +-0.2 Hz, a field generator about 1 %),
fixed in the receiver's frame: sharp to the dwell's resolution at every order, where a flying target's lines
ride on its body's Doppler. Read as an echo they are a line comb (mains hum 10 dB over the noise of a 4 s
recording read as a drone at 50 rev/s, ``ok``) or, weak, wings beating.

:func:`find_hum` reads them on the echo as received (not demodulated by any body track), :func:`without_hum`
takes them out by a notch that follows the hum's slow drift. A rotor turning at a multiple of the grid's
frequency and held still (a test stand at 3000 rpm under a 50 Hz grid) gives the same sharp lines: its comb
is taken out with the hum; the row then says so (:data:`STATUS`), and ``--mains-hz none`` skips the search.
"""

from dataclasses import dataclass

import numpy as np

from mdpipe.process.doppler import periodic_hann
from mdpipe.process.filters import parabolic_offset, triangular_average

GRID_TOLERANCE = 0.01    # the grid's frequency within 1 % of its nominal
FIRST_ORDERS = 2         # the frequency is read on lines at the first two orders (a rectifier's ripple: the 2nd)
MAX_ORDERS = 40          # hum harmonics searched up to this order
LINE_RATIO = 30.0        # a hum line's bin over the spectrum's local median (noise passes it w.p. 2^-30)
SHARP_BINS = 3           # ... and sharp: this many resolution bins either side of it, under BESIDE_SHARE of it
BESIDE_SHARE = 0.1       # (a line smeared over a few bins by a body's sway or a rotor's wander holds a third)
BESIDE_NOISE = 8.0       # ... or no more than noise reaches there (8 times its median: w.p. 2^-8)
FLOOR_HZ = 25.0          # the local median is taken over +-this about each order
DRIFT = 2e-4             # the grid's frequency moves about 0.01 Hz over a recording: order k within k times this
MIN_LINES = 3
CHANCE_SIGMAS = 3.0      # hum's lines outnumber those half-way between its orders (other lines met by chance) by
                         # MIN_LINES and this many Poisson deviations of their count
MAX_LINE_STEP = 2        # hum's lines lie at every order, or (a rectifier's ripple) every second one
MIN_CYCLES = 10          # a dwell of at least 10 periods of the grid (0.2 s at 50 Hz): lines resolved apart
NOTCH_BINS = 4           # the notch: each line's envelope averaged over a quarter of the dwell (first null 4 bins)
PAD = 2
STATUS = "mains_hum"     # a chopping comb commensurate with the hum removed: withheld
SEARCH = object()        # analyse_target's default: look for hum in the echo (a caller may have taken it out)


@dataclass(frozen=True)
class Hum:
    """Mains hum found in an echo: the grid frequency ``f0_hz`` and its lines (signed order, frequency Hz)."""

    f0_hz: float
    lines: tuple

    def note(self):
        return (f"mains hum at {self.f0_hz:.2f} Hz: {len(self.lines)} lines at its harmonics taken out before the "
                f"analysis (--mains-hz none keeps them)")

    def commensurate(self, spacing_hz):
        """Whether a comb at ``spacing_hz`` falls on the hum's lines: a whole multiple of ``f0_hz`` or of half of
        it, within the resolution the comb is read to (``GRID_TOLERANCE`` of the spacing)."""
        ratio = 2.0 * spacing_hz / self.f0_hz
        return bool(round(ratio) >= 1 and abs(ratio - round(ratio)) <= GRID_TOLERANCE * ratio)


class _Spectrum:
    """The echo's Hann periodogram (zero-padded ``PAD`` times) and what a hum line is tested against."""

    def __init__(self, signal, prf_hz):
        n = len(signal)
        self.prf_hz, self.resolution_hz = prf_hz, prf_hz / n
        self.power = np.abs(np.fft.fft(signal * periodic_hann(n), PAD * n)) ** 2
        self.bin_hz = prf_hz / len(self.power)

    def _bins(self, low_hz, high_hz):
        return np.arange(int(np.floor(low_hz / self.bin_hz)), int(np.ceil(high_hz / self.bin_hz)) + 1)

    def line(self, low_hz, high_hz, floor_centre_hz):
        """The line (frequency Hz) standing in ``[low_hz, high_hz]``: the strongest bin there, refined by a parabola
        through its log-power neighbours, if it stands ``LINE_RATIO`` over the local median and is sharp; else
        None."""
        m = len(self.power)
        window = self._bins(low_hz, high_hz)
        peak = int(window[np.argmax(self.power[window % m])])
        value = self.power[peak % m]
        floor = np.median(self.power[self._bins(floor_centre_hz - FLOOR_HZ, floor_centre_hz + FLOOR_HZ) % m])
        if value < LINE_RATIO * floor:
            return None
        beside = int(round(SHARP_BINS * self.resolution_hz / self.bin_hz))
        for side in (peak - beside, peak + beside):
            if self.power[side % m] > max(BESIDE_SHARE * value, BESIDE_NOISE * floor):
                return None
        left, mid, right = np.log(self.power[[(peak - 1) % m, peak % m, (peak + 1) % m]] + np.finfo(float).tiny)
        return (peak + float(parabolic_offset(left, mid, right))) * self.bin_hz


def _fitted(lines):
    """The frequency whose multiples the ``lines`` ((order, Hz), ...) lie on: least squares through 0."""
    k, f = np.array(lines, dtype=float).T
    return float(np.sum(k * f) / np.sum(k * k))


def _lines_at(spectrum, f0_hz, orders):
    """(order, Hz) of the lines standing at ``+-orders`` (may be fractional) times ``f0_hz``, each within half a
    resolution bin and the grid's drift of it."""
    found = []
    for k in np.concatenate([orders, -orders]):
        reach = spectrum.resolution_hz / 2 + abs(k) * DRIFT * f0_hz
        f = spectrum.line(k * f0_hz - reach, k * f0_hz + reach, k * f0_hz)
        if f is not None:
            found.append((float(k), f))
    return found


def _consistent(lines, f0_hz, resolution_hz):
    return [(k, f) for k, f in lines if abs(f - k * f0_hz) <= resolution_hz / 2 + abs(k) * DRIFT * f0_hz]


def find_hum(signal, *, prf_hz, mains_hz):
    """:class:`Hum` in a complex slow-time ``signal`` (its mean removed) sampled at ``prf_hz``, or None.

    For each nominal grid frequency F (``mains_hz``, Hz: ``ProcessParams.mains_frequencies_hz``): lines at the
    first ``FIRST_ORDERS`` orders, each sign, within ``GRID_TOLERANCE`` of ``k F``, that agree on one frequency f0
    (two at least: the grid's own line and a rectifier's at twice it are hum's strongest); then a line at each order
    ``+-k`` up to ``MAX_ORDERS`` (and the span's edge) within half a resolution bin and the grid's drift of ``k f0``.
    Hum when f0, refitted on them, stays within ``GRID_TOLERANCE`` of F, and they are ``MIN_LINES`` or more, at
    orders whose greatest common divisor is at most ``MAX_LINE_STEP`` (the grid's harmonics, or a rectifier's ripple
    at the even ones: a rotor held still at 100 rev/s, 2 blades, lines every 200 Hz, is no hum; one at 50 rev/s,
    every 100 Hz, reads as hum), and more than the lines standing half-way between the orders, which a spectrum
    dense with a target's lines meets as often (``CHANCE_SIGMAS``: hexarotors at 77 GHz, their folded combs sharp,
    met 3-14 orders of 50-60 Hz by chance). A dwell shorter than ``MIN_CYCLES`` periods is not searched.
    """
    signal = np.asarray(signal, dtype=np.complex128)
    n = len(signal)
    best, spectrum = None, None
    for nominal_hz in mains_hz:
        top = int(min(MAX_ORDERS, np.floor(prf_hz / 2 / (nominal_hz * (1 + GRID_TOLERANCE) + FLOOR_HZ))))
        if top < 1 or n / prf_hz < MIN_CYCLES / nominal_hz:
            continue
        spectrum = spectrum or _Spectrum(signal, prf_hz)
        first = []
        for k in [s * k for k in range(1, min(FIRST_ORDERS, top) + 1) for s in (1, -1)]:
            reach = abs(k) * nominal_hz * GRID_TOLERANCE
            f = spectrum.line(k * nominal_hz - reach, k * nominal_hz + reach, k * nominal_hz)
            if f is not None:
                first.append((k, f))
        if len(first) < 2:
            continue
        f0 = _fitted(first)
        first = _consistent(first, f0, spectrum.resolution_hz)
        if len(first) < 2:
            continue
        f0 = _fitted(first)
        lines = _lines_at(spectrum, f0, np.arange(1, top + 1))
        lines = _consistent(lines, _fitted(lines), spectrum.resolution_hz) if len(lines) >= MIN_LINES else []
        if len(lines) < MIN_LINES:
            continue
        f0 = _fitted(lines)
        chance = len(_lines_at(spectrum, f0, np.arange(top) + 0.5))  # a dense spectrum's lines, met anywhere
        if (abs(f0 / nominal_hz - 1) > GRID_TOLERANCE or np.gcd.reduce([int(round(abs(k))) for k, _ in lines]) > MAX_LINE_STEP
                or len(lines) < MIN_LINES + chance + CHANCE_SIGMAS * np.sqrt(chance)):
            continue  # (lines every third order or wider: a rotor's comb, 200 Hz at 100 rev/s and 2 blades, no hum)
        if best is None or len(lines) > len(best.lines):
            best = Hum(f0_hz=f0, lines=tuple(lines))
    return best


def without_hum(signal, hum, *, prf_hz):
    """``signal`` (n,) or (n, columns) with each of ``hum``'s lines notched out: the echo demodulated at the line,
    its envelope averaged over a quarter of the dwell (triangular: first null ``NOTCH_BINS`` resolution bins
    off the line), remodulated and subtracted. A steady line goes whole (the average holds a constant); one
    drifting within the notch goes too; the echo more than a few bins off the line stays."""
    out = np.array(signal, dtype=np.complex128)
    n = out.shape[0]
    size = max(1, n // (2 * NOTCH_BINS))  # two boxcars of n / 8: the triangle spans a quarter of the dwell
    t = np.arange(n) / prf_hz
    for _, f_hz in hum.lines:
        carrier = np.exp(2j * np.pi * f_hz * t).reshape((n,) + (1,) * (out.ndim - 1))
        envelope = out * np.conj(carrier)
        smoothed = np.stack([triangular_average(c, size) for c in envelope.reshape(n, -1).T], axis=1)
        out -= smoothed.reshape(out.shape) * carrier
    return out
