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
range-transformed, and its harmonics over the phases (k at k PRF / 12: 0 the static echo, the others what changes from
chirp to chirp), summed over the blocks with their powers. A static echo's harmonic 0 and a cycle's harmonics are
steady from block to block; noise's and a mover's scatter about their mean (a mover's unless a line of it falls on
k PRF / 12). On the bins whose harmonic 0 stands ``STATIC_COHERENCE`` times over its error (range bin 0, the ADC's
offset, left out), a cycle of 2 is found where its harmonic (6: PRF / 2) stands ``MIN_CONTRAST`` times over its own
error and ``MIN_PURITY`` times over each harmonic no such cycle makes (a rotor whose lines fall on every k PRF / 12
lights them all), and holds ``MIN_SHARE`` of the static echoes' power. The first transmitter's chirps are then read
(:meth:`mdpipe.io.radarlog.RadarlogReader.select_every`): Tp times the cycle, a Doppler span as many times narrower,
the others' chirps unused.

Not found, and to be given (``--transmitters``, or ``TxSeq`` in the file): a cycle on a capture without a static echo
(no clutter, no leakage between the antennas in its range bins), and cycles of 3 or 4 (a rotor held still whose lines
fall on every k PRF / 3 or k PRF / 4, and on none of the other harmonics, makes the same steady change; with 2, its
lines must fall on PRF / 2's multiples only, its chopping PRF / 2 over an odd count 5, 7, 11 ..., which the static
echoes of the tests and benchmarks never showed).
"""

import math
from dataclasses import dataclass

import numpy as np

from mdpipe.params import transmit_cycle

PHASES = 12            # chirp index modulo this
CYCLE = 2              # the cycle found (two transmitters: the Radarlog)
BLOCK_CHIRPS = 8 * PHASES  # the phases' means are taken over blocks of this many chirps ...
MIN_BLOCKS = 8         # ... at least this many (768 chirps), to tell a steady change from noise's and movers'
STATIC_COHERENCE = 100.0   # a static echo: its mean over the blocks this many times their scatter about it
MIN_CONTRAST = 30.0    # a cycle: its harmonics' mean over the blocks this many times their scatter (15 dB), ...
MIN_PURITY = 30.0      # ... each this many times the harmonics no such cycle makes, ...
MIN_SHARE = 1e-3       # ... and this share of the static echoes' power (-30 dB)


class PhaseSums:
    """Per range bin, the harmonics over the chirp phases (index modulo ``PHASES``) of one channel's chirps, taken on
    blocks of ``BLOCK_CHIRPS``: their sums and summed powers over the blocks, fed read by read by pass 0
    (:meth:`add`). Harmonic k lies at k PRF / PHASES: 0 the static echo, the others what changes from chirp to chirp."""

    def __init__(self, window):
        self.window = np.asarray(window, dtype=np.float64)
        bins = len(self.window) // 2 + 1
        self.sums = np.zeros((PHASES, bins), dtype=np.complex128)
        self.powers = np.zeros((PHASES, bins))
        self.blocks = 0

    def add(self, first_chirp, samples):
        """Add the whole blocks (``BLOCK_CHIRPS`` chirps from a multiple of it) within a read: ``samples`` (M, N) of
        chirps ``first_chirp ...``."""
        start = -first_chirp % BLOCK_CHIRPS
        count = (len(samples) - start) // BLOCK_CHIRPS
        if count <= 0:
            return
        blocks = samples[start:start + count * BLOCK_CHIRPS].reshape(count, BLOCK_CHIRPS // PHASES, PHASES, -1)
        echoes = np.fft.rfft(blocks.mean(axis=1, dtype=np.float64) * self.window, axis=2)  # (count, PHASES, B)
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
class CycleTest:
    """What changes steadily within a cycle of ``cycle`` chirps on ``bins`` static range bins: its harmonics' power
    over the power of their error (``contrast``), that error taken off, per harmonic over the power of the harmonics
    no such cycle makes (``purity``), and its ``share`` of the static echoes' power."""

    cycle: int
    contrast: float
    purity: float
    share: float
    bins: int

    @property
    def found(self):
        return (self.bins > 0 and self.contrast >= MIN_CONTRAST and self.purity >= MIN_PURITY
                and self.share >= MIN_SHARE)


def _ratio(numerator, denominator):
    return numerator / denominator if denominator > 0 else (np.inf if numerator > 0 else 0.0)


def cycle_test(sums, cycle=CYCLE):
    """The :class:`CycleTest` of a cycle of ``cycle`` chirps (a divisor of ``PHASES``) on pass 0's
    :class:`PhaseSums`; None with fewer than ``MIN_BLOCKS`` blocks."""
    if sums.blocks < MIN_BLOCKS:
        return None
    power, error = sums.coherence()
    power[:, 0] = error[:, 0] = 0.0  # range bin 0: the ADC's offset, which no transmitter changes
    bins = power[0] > STATIC_COHERENCE * error[0]  # static echoes: steady over the blocks
    static = float(np.sum(power[0][bins]))
    own = np.arange(PHASES // cycle, PHASES, PHASES // cycle)  # the cycle's harmonics, k PRF / cycle
    others = np.setdiff1d(np.arange(1, PHASES), own)
    steady, scatter = float(np.sum(power[own][:, bins])), float(np.sum(error[own][:, bins]))
    elsewhere = float(np.sum(power[others][:, bins])) / len(others)
    return CycleTest(cycle, _ratio(steady, scatter), _ratio((steady - scatter) / len(own), elsewhere),
                     _ratio(steady - scatter, static), int(np.count_nonzero(bins)))


@dataclass(frozen=True)
class TransmitCycle:
    """Chirps per transmit cycle (1: one transmitter) and where that was learnt: ``given`` (``--transmitters``),
    ``file`` (``TxSeq``), ``found`` (static echoes), ``single`` (none of them)."""

    cycle: int
    source: str
    test: CycleTest = None

    def note(self, prf_hz):
        """The capture note on reading one transmitter's chirps at ``prf_hz`` (None for one transmitter)."""
        if self.cycle == 1:
            return None
        how = {"given": "--transmitters", "file": "the file's TxSeq",
               "found": (f"found: the static echoes change from chirp to chirp by "
                         f"{10 * math.log10(max(self.test.share, 1e-30)):.1f} dB of their power"
                         if self.test else "found")}[self.source]
        return (f"the chirps take {self.cycle} transmitters in turn ({how}); the first one's are read, at "
                f"{prf_hz:.5g} Hz (the Doppler span {self.cycle} times narrower)")


def from_file(sequence):
    """The :class:`TransmitCycle` of a file's ``TxSeq`` (``()``: none)."""
    return TransmitCycle(transmit_cycle(sequence), "file") if sequence else None
