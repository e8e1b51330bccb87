"""Another radar's chirps crossing ours: detections whose echo is the bursts they leave, read as such.

When another FMCW radar's chirp crosses ours, the beat of the two sweeps runs through the IF band in a few samples: a
short burst, broadband in range, in one chirp. Repeated every few chirps (two radars whose chirp rates differ), every
range bin's slow time carries the same train of impulses, which reads as blade flashes: in
``benchmarks/bench_impairments.py`` a burst every 37.3 chirps gave 36 phantom drones and birds in 28 captures.

A burst lifts most range bins of its chirp at once; an echo lifts the bins of its target. Pass 0 reads one channel of
every chirp (bursts reach all RX at once), transforms it with the range window and keeps, per chirp, the common mode:
the ``QUANTILE`` (a quarter) over range bins of each bin's power about the read's mean chirp over that bin's median
over the read's chirps. A chirp whose common mode stands ``SPIKE_SPREADS`` robust spreads (1.4826 median absolute
deviations) over the read's median, and ``MIN_RISE`` times it, is a spike. Measured on 445 unimpaired captures (4.5
million chirps: the ``make offmodel`` captures and 49 default-sweep scenes, drones at X to W band among them): no
spike. The median over the bins instead of the quarter spiked on 173 of those chirps (a 64-sample chirp's 31 bins
are too few for it to be tight); a window flat but for short tapers (a Tukey window, 0.25), on 5 with the quarter,
on 983 with the median: an echo's sidelobes. A strong 77 GHz drone whose blade tips move its beat by 13 bins lights
every bin in its flashes, spiking now and then.

A capture with ``MIN_SPIKES`` spikes or more is crossed. A detection of a crossed capture whose power follows the
common mode (their correlation over the chirps ``CROSSED_CORRELATION`` or more), or a drone whose only sign of a rotor
is blade flashes of an ambiguous period (bursts repeat as flashes do; spikes are the strongest of them, the weaker
ones lift a weak echo's power periodically too: a branch and two moving points of the bench, correlating 0.03-0.19,
read as drones), is the bursts' echo, unless the spikes add the most power to its own bin (``SOURCE_RATIO`` times
what they add to the median bin: a flash, or a clipped echo, seen in every bin, whose source this target is; a burst
adds alike to every bin). It is read as ``none``, every feature but its SNR withheld as ``interference``; a genuine
target whose echo the bursts outweigh, or a drone seen only by its flashes, is withheld
with them; a row read ``none`` already is left as it is. Correlations measured on the bench's 28 captures crossed
every 9.71 chirps: phantoms 0.42-0.91; the targets 0.0-0.71 (over 0.4: two sparrows read as drones, two drones);
unimpaired, 0.34 at most (a gull whose wings light other bins). The 77 GHz drone's own rows correlate 0.43 (its
capture is not crossed: one spike), the top hundredth of its chirps by common mode adding 230 times more power to its
bins than to the median bin.
"""

from dataclasses import dataclass

import numpy as np

from mdpipe.process.classify import ROTOR_EVIDENCE
from mdpipe.process.features import read_as, withheld_row
from mdpipe.process.ranging import range_window

READ_SAMPLES = 2**21      # samples of a read: 1024 chirps of 2048 (at least MIN_READ_CHIRPS, at most MAX_READ_CHIRPS)
MIN_READ_CHIRPS, MAX_READ_CHIRPS = 64, 1024
READ_BYTES_PER_SAMPLE = 64  # a read's float32 samples, residual and windowed copy, complex128 spectrum, float64 power,
                            # ratio and the partition's copy, and 8 B to spare (the spikes' excess)
TYPICAL_EVERY = 4         # each bin's median over every 4th chirp of a read
QUANTILE = 0.25           # the common mode: this quantile over the range bins (an echo lights fewer than 3/4 of them)
SPIKE_SPREADS = 12.0      # a spike: the common mode this many robust spreads over the read's median ...
MIN_RISE = 2.0            # ... and this many times it
MIN_SPIKES = 8            # a capture with this many spikes is crossed by another radar's chirps
CROSSED_CORRELATION = 0.4  # a detection of it whose power follows the common mode this closely is the bursts' echo ...
SOURCE_RATIO = 10.0       # ... unless the spikes add this many times more power to its bin than to the median bin


@dataclass(frozen=True)
class CommonMode:
    """What the chirps of a capture hold in common across range (pass 0).

    Attributes
    ----------
    series : ndarray (n_chirps,)
        Per chirp, the ``QUANTILE`` over range bins of each bin's power over its median over the read's chirps.
    spikes : int
        Chirps whose common mode stands out (bursts).
    profile : ndarray (n_bins,)
        Mean over the spikes of each range bin's power over its median over the chirps (counts^2; bins of the
        unpadded grid, 0 .. N/2); None without spikes.
    range_bin_m : float
    """

    series: np.ndarray
    spikes: int
    profile: np.ndarray
    range_bin_m: float

    @property
    def crossed(self):
        return self.spikes >= MIN_SPIKES

    @property
    def spike_share(self):
        return self.spikes / len(self.series) if len(self.series) else 0.0


def bin_typical(power):
    """Each bin's median of ``power`` (M, B) over every ``TYPICAL_EVERY``-th of the M chirps (256 of a read: the
    median's spread is that of 256 draws); a bin without power gets the smallest positive one."""
    typical = np.median(power[::TYPICAL_EVERY], axis=0)
    positive = typical[typical > 0]
    return np.maximum(typical, positive.min() if len(positive) else 1.0)


def read_common_mode(samples, window):
    """Common mode (per chirp) and spikes (bool, per chirp) of a read, and the spikes' power in each bin over the bin's
    median over the read's chirps (spikes, B: counts^2), from its samples (M, N) of one channel."""
    residual = samples - samples.mean(axis=0)
    spectrum = np.fft.rfft(residual * window, axis=1)
    power = spectrum.real ** 2 + spectrum.imag ** 2
    typical = bin_typical(power)
    ratio = power[:, 1:] / typical[1:]
    k = int(QUANTILE * (ratio.shape[1] - 1))  # the order statistic (no interpolation: 3x faster than np.quantile)
    series = np.partition(ratio, k, axis=1)[:, k]
    centre = np.median(series)
    spread = 1.4826 * np.median(np.abs(series - centre))
    spiked = series > max(MIN_RISE * centre, centre + SPIKE_SPREADS * spread)
    return series, spiked, power[spiked] - typical


def read_chirps(n_samples):
    """Chirps a read of pass 0 holds (its memory: ``READ_BYTES_PER_SAMPLE`` per sample)."""
    return int(np.clip(READ_SAMPLES // max(n_samples, 1), MIN_READ_CHIRPS, MAX_READ_CHIRPS))


def common_mode(reader, *, window="hann", channel=0, phase_sums=None):
    """Pass 0 over ``reader``'s channel ``channel``: its :class:`CommonMode`. Each read is also added to
    ``phase_sums`` where given (a :class:`mdpipe.process.transmitters.PhaseSums`: the chirps by index, for their
    transmit cycle)."""
    n, m = reader.params.n_samples, reader.n_chirps
    taper = range_window(window, n)
    rows = read_chirps(n)
    edges = np.linspace(0, m, max(1, int(np.ceil(m / rows))) + 1).astype(int)  # reads of near-equal length
    series, spikes, profile = [], 0, np.zeros(n // 2 + 1)
    for first, stop in zip(edges[:-1], edges[1:]):
        samples = reader.read_counts(first, stop, channels=[channel])[0].astype(np.float32)
        part, spiked, excess = read_common_mode(samples, taper)
        if phase_sums is not None:
            phase_sums.add(first, samples)
        series.append(part)
        spikes += int(spiked.sum())
        profile += excess.sum(axis=0)
    return CommonMode(np.concatenate(series), spikes, profile / spikes if spikes else None, reader.params.range_bin_m)


def correlation(a, b):
    """Pearson correlation of two series (0 when either is constant)."""
    a, b = a - a.mean(), b - b.mean()
    norm = np.sqrt(np.dot(a, a) * np.dot(b, b))
    return float(np.dot(a, b) / norm) if norm > 0 else 0.0


def source_ratio(common, range_m):
    """How much more power the spikes add to the bin at ``range_m`` than to the median bin (a burst adds alike to
    every bin; a flash or a clipped echo most to its own)."""
    index = int(np.clip(round(range_m / common.range_bin_m), 0, len(common.profile) - 1))
    return float(common.profile[index] / max(np.median(common.profile[1:]), np.finfo(float).tiny))


def crossed_rows(rows, signals, common, capture_notes=()):
    """The target rows of one capture (``signals``: each target's slow time along its track) read for another
    radar's bursts (``common``: the capture's :class:`CommonMode`); rows read ``none`` stay as they are. Returns new
    rows; a capture not crossed keeps its rows as they are."""
    if not common.crossed:
        return rows
    series = common.series.astype(np.float64)
    out = []
    for row, signal in zip(rows, signals):
        if row["class"] == "none":  # claims no target (a clipping image among them)
            out.append(row)
            continue
        follows = correlation((np.abs(signal) ** 2).astype(np.float64), series)
        flashes_only = row["class"] == "drone" and row["chopping_freq_hz_status"] in ROTOR_EVIDENCE
        if source_ratio(common, row["range_m"]) < SOURCE_RATIO and (follows >= CROSSED_CORRELATION or flashes_only):
            why = (f"this echo's power follows them (correlation {follows:.2f})" if follows >= CROSSED_CORRELATION
                   else "they repeat as blade flashes do, and this echo's only sign of a rotor is flashes of an "
                        "ambiguous period")
            note = (f"class: possibly the echo of another radar's chirps: {common.spike_share:.1%} of the chirps "
                    f"hold a burst lighting most range bins at once, and {why}; {read_as(row)}")
            row = withheld_row(row, status="interference", note=note, capture_notes=capture_notes)
        out.append(row)
    return out
