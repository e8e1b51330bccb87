"""Chirps sent by transmitters in turn (a MIMO radar's time-division cycle): read one transmitter's chirps.

A MIMO FMCW radar (the Radarlog has 2 TX and 16 RX) may send its chirps from its transmitters in turn. The
transmitters sit apart on the array and have feeds of their own, so every echo's phase (and amplitude) changes from
one transmitter's chirps to the next: a static echo repeats every L chirps (L the cycle) instead of every chirp, and
its slow time holds lines at k PRF / L. Read as one sequence, static clutter becomes a mover at PRF / 2 and each
target's spectrum gets a copy shifted by PRF / L. On the bundled samples with their odd chirps turned 120 deg and
0.8 times (a second transmitter): the tree behind the FIMI drone read as a target at 11.2 m and the drone lost; the
gull read as a drone; the clutter-only capture read two movers.

The cycle comes from the file's ``TxSeq`` attribute (the transmitter of each chirp, repeating; its shortest repeat,
:func:`mdpipe.params.transmit_cycle`), from ``--transmitters``, or, for two transmitters, is found on the static
echoes (:func:`cycle_test`). Pass 0 (:func:`mdpipe.process.interference.common_mode`) hands one channel's chirps to
:class:`PhaseSums`: on blocks of ``BLOCK_CHIRPS``, the mean chirp of each phase (index modulo ``PHASES``),
range-transformed (Hann), and its harmonics over the phases (k at k PRF / 12: 0 the static echo, the others what
changes from chirp to chirp), summed over the blocks with their powers. A static echo's harmonic 0 and a cycle's
harmonics are steady from block to block; noise's and a mover's scatter about their mean (a mover's unless a line of
it falls on k PRF / 12). Each static echo (:func:`static_echoes`: a peak of the steady harmonic 0, range bin 0, the
ADC's offset, left out) shows a cycle of 2 where, on its peak bin, harmonic 6 (PRF / 2) stands ``MIN_CONTRAST`` times
over its own error and ``MIN_PURITY`` times over each harmonic no such cycle makes (a rotor whose lines fall on every
k PRF / 12 lights them all), and holds ``MIN_SHARE`` of its static power. Transmitters in turn change every static
echo; a hovering rotor whose chopping line falls on PRF / 2 and on no other k PRF / 12 (its chopping PRF / 2 over an
odd count 1, 5, 7, 11 ...) changes its own. So the cycle is found where ``MIN_ECHOES`` static echoes show it, and the
first transmitter's chirps are then read (:meth:`mdpipe.io.radarlog.RadarlogReader.select_every`): Tp times the
cycle, a Doppler span as many times narrower, the others' chirps unused. Where one echo alone shows it, the chirps are
read as they are and a note says to give ``--transmitters 2`` if the radar sends them so (in a first form, found on one
echo, a hovering X-band rotor at 120 rev/s sampled at 2.4 kHz, or the FIMI quadrotor at 156.25 rev/s at the
Radarlog's 15.625 kHz, its line on PRF / 2, had halved the chirp rate and lost the drone).

Not found, and to be given (``--transmitters``, or ``TxSeq`` in the file): a cycle on a capture with one static echo
or none (clutter, leakage between the antennas in the range bins read), and cycles of 3 or 4 (a rotor held still
whose lines fall on every k PRF / 3 or k PRF / 4 makes the same steady change). An echo whose two transmitters'
chirps nearly cancel (their phases 180 deg apart at its angle) has little harmonic 0 and is no static echo here. The
mean chirp's offset over fast time (the ADC's, whose main lobe reaches range bin 1) is taken out of every block.
"""

import math
from dataclasses import dataclass

import numpy as np

from mdpipe.params import transmit_cycle
from mdpipe.process.doppler import periodic_hann

PHASES = 12            # chirp index modulo this
CYCLE = 2              # the cycle found (two transmitters: the Radarlog)
BLOCK_CHIRPS = 8 * PHASES  # the phases' means are taken over blocks of this many chirps ...
MIN_BLOCKS = 8         # ... at least this many (768 chirps), to tell a steady change from noise's and movers'
STATIC_COHERENCE = 100.0   # a static echo: its mean over the blocks this many times their scatter about it
ECHO_SHARE = 1e-3      # a static echo: a peak of the static power this share of the strongest (Hann's sidelobes: under
                       # -31.5 dB) ...
MIN_SEPARATION_BINS = 2    # ... this many range bins from a stronger one
MIN_ECHOES = 2         # a cycle: on this many static echoes, each with ...
MIN_CONTRAST = 30.0    # ... its harmonics' mean over the blocks this many times their scatter (15 dB), ...
MIN_PURITY = 30.0      # ... each this many times the harmonics no such cycle makes, ...
MIN_SHARE = 1e-3       # ... and this share of the echo's static power (-30 dB)


class PhaseSums:
    """Per range bin, the harmonics over the chirp phases (index modulo ``PHASES``) of one channel's chirps, taken on
    blocks of ``BLOCK_CHIRPS`` (counted from the first chirp, across pass 0's reads): their sums and summed powers over
    the blocks, fed read by read by pass 0 (:meth:`add`). Harmonic k lies at k PRF / PHASES: 0 the static echo, the
    others what changes from chirp to chirp. The range transform's window is Hann whatever the analysis uses (its
    sidelobes stay under ``ECHO_SHARE``)."""

    def __init__(self, n_samples):
        self.window = periodic_hann(n_samples)
        self.sums = np.zeros((PHASES, n_samples // 2 + 1), dtype=np.complex128)
        self.powers = np.zeros((PHASES, n_samples // 2 + 1))
        self.blocks = 0
        self._tail = None  # the chirps of a block a read left unfinished

    def add(self, first_chirp, samples):
        """Add a read, ``samples`` (M, N) of chirps ``first_chirp ...`` (reads in order): its whole blocks, the
        chirps of one it leaves unfinished kept for the next read."""
        if self._tail is not None:
            samples = np.concatenate([self._tail, samples])
            first_chirp -= len(self._tail)
        start = -first_chirp % BLOCK_CHIRPS
        count = max((len(samples) - start) // BLOCK_CHIRPS, 0)
        stop = start + count * BLOCK_CHIRPS
        self._tail = samples[stop:].astype(np.float32) if len(samples) > stop >= start else None
        if count == 0:
            return
        blocks = samples[start:stop].reshape(count, BLOCK_CHIRPS // PHASES, PHASES, -1)
        means = blocks.mean(axis=1, dtype=np.float64)
        means -= means.mean(axis=2, keepdims=True)  # the ADC's offset, whose main lobe would reach range bin 1
        echoes = np.fft.rfft(means * self.window, axis=2)  # (count, PHASES, B)
        harmonics = np.fft.fft(echoes, axis=1) / PHASES
        self.sums += harmonics.sum(axis=0)
        self.powers += (harmonics.real ** 2 + harmonics.imag ** 2).sum(axis=0)
        self.blocks += count

    def coherence(self):
        """(mean power, scatter) per harmonic and bin: the blocks' mean's power, and the power of its error (the
        blocks' variance about it over their number)."""
        mean = self.sums / self.blocks
        variance = np.maximum(self.powers / self.blocks - np.abs(mean) ** 2, 0.0)
        return np.abs(mean) ** 2, variance / max(self.blocks - 1, 1)


@dataclass(frozen=True)
class EchoTest:
    """What changes steadily within a cycle on one static echo (its peak range bin ``bin``): its harmonics' power over
    the power of their error (``contrast``); that error taken off, per harmonic over the power of the harmonics no such
    cycle makes (``purity``), and its ``share`` of the echo's static power."""

    bin: int
    contrast: float
    purity: float
    share: float

    @property
    def shows(self):
        return self.contrast >= MIN_CONTRAST and self.purity >= MIN_PURITY and self.share >= MIN_SHARE


@dataclass(frozen=True)
class CycleTest:
    """A cycle of ``cycle`` chirps tested on each static echo (:class:`EchoTest`, strongest first)."""

    cycle: int
    echoes: tuple

    @property
    def showing(self):
        return [echo for echo in self.echoes if echo.shows]

    @property
    def found(self):
        return len(self.showing) >= MIN_ECHOES

    @property
    def share(self):
        """The smallest share among the echoes that show the cycle (0 without one)."""
        return min((echo.share for echo in self.showing), default=0.0)


def _ratio(numerator, denominator):
    return numerator / denominator if denominator > 0 else (np.inf if numerator > 0 else 0.0)


def static_echoes(power, error):
    """The static echoes' peak bins, strongest first: local maxima of the static power (harmonic 0, steady over the
    blocks; bin 0, the ADC's offset, left out), ``ECHO_SHARE`` of the strongest or more, ``MIN_SEPARATION_BINS``
    or more from a stronger one."""
    level = np.where(power[0] > STATIC_COHERENCE * error[0], power[0], 0.0)
    level[0] = 0.0
    if not np.any(level > 0):
        return []
    padded = np.concatenate([[0.0], level, [0.0]])
    peaks = np.flatnonzero((level > 0) & (level >= padded[:-2]) & (level >= padded[2:]) &
                           (level >= ECHO_SHARE * level.max()))
    chosen = []
    for peak in peaks[np.argsort(-level[peaks], kind="stable")]:
        if all(abs(int(peak) - other) >= MIN_SEPARATION_BINS for other in chosen):
            chosen.append(int(peak))
    return chosen


def cycle_test(sums, cycle=CYCLE):
    """The :class:`CycleTest` of a cycle of ``cycle`` chirps (a divisor of ``PHASES``) on pass 0's
    :class:`PhaseSums`, each static echo read on its peak bin (a neighbour's main lobe, ``MIN_SEPARATION_BINS`` away,
    reaches the bins beside it); None with fewer than ``MIN_BLOCKS`` blocks."""
    if sums.blocks < MIN_BLOCKS:
        return None
    power, error = sums.coherence()
    own = np.arange(PHASES // cycle, PHASES, PHASES // cycle)  # the cycle's harmonics, k PRF / cycle
    others = np.setdiff1d(np.arange(1, PHASES), own)
    echoes = []
    for peak in static_echoes(power, error):
        steady, scatter = float(np.sum(power[own, peak])), float(np.sum(error[own, peak]))
        elsewhere = float(np.sum(power[others, peak])) / len(others)
        echoes.append(EchoTest(peak, _ratio(steady, scatter), _ratio((steady - scatter) / len(own), elsewhere),
                               _ratio(steady - scatter, float(power[0, peak]))))
    return CycleTest(cycle, tuple(echoes))


@dataclass(frozen=True)
class TransmitCycle:
    """Chirps per transmit cycle (1: one transmitter) and where that was learnt: ``given`` (``--transmitters``),
    ``file`` (``TxSeq``), ``found`` (static echoes), ``single`` (none of them; ``test`` the cycle test read, where
    one static echo alone showed a cycle of two)."""

    cycle: int
    source: str
    test: CycleTest = None

    def note(self, params):
        """The capture note on the chirps read (``params``: theirs), None for one transmitter without a suspicion."""
        if self.cycle == 1:
            shown = self.test.showing if self.test is not None else []
            if not shown:
                return None
            echo = shown[0]
            others = ("no other static echo does" if len(self.test.echoes) > 1
                      else "the capture holds no other static echo to tell")
            return (f"the static echo at {echo.bin * params.range_bin_m:.3g} m changes from chirp to chirp, at half "
                    f"the chirp rate, by {10 * math.log10(max(echo.share, 1e-30)):.1f} dB of its power, as the chirps "
                    f"of two transmitters in turn would make it, but {others} (a line of a target's own on PRF / 2 "
                    "would do so too): if two transmitters send the chirps in turn, give --transmitters 2")
        how = {"given": "--transmitters", "file": "the file's TxSeq",
               "found": (f"found: {len(self.test.showing)} static echoes change from chirp to chirp by "
                         f"{10 * math.log10(max(self.test.share, 1e-30)):.1f} dB of their power or more"
                         if self.test else "found")}[self.source]
        return (f"the chirps take {self.cycle} transmitters in turn ({how}); the first one's are read, at "
                f"{params.prf_hz:.5g} Hz (the Doppler span {self.cycle} times narrower)")


def from_file(sequence):
    """The :class:`TransmitCycle` of a file's ``TxSeq`` (``()``: none)."""
    return TransmitCycle(transmit_cycle(sequence), "file") if sequence else None
