"""Another radar's chirps crossing ours: find the bursts they leave in the IF and take them out before any transform.

When another FMCW radar's chirp sweeps across ours, its beat with our LO runs through the IF band in a few samples: a
short, broadband burst in one chirp. Repeated every few chirps (two radars whose chirp rates differ), every range
bin's slow time carries the same train of impulses, which the flash and power-period paths read as blade flashes: the
bundled X-band Phantom crossed by a burst every 9.71 chirps gained two phantom drones at 172 and 195 m
(``benchmarks/bench_impairments.py``).

What tells a burst from an echo is its breadth in range. The range spectrum of a chirp about the chirps' mean (static
clutter out) holds the moving echoes in a few bins, a blade flash shorter than the ramp included (a flash of a share
``q`` of the ramp spreads over about ``2 / q`` bins, under a tenth of them for a W-band flash of 20 us in an 80 us
ramp); a burst of a few samples lifts every bin. So a chirp is interfered when the median over range bins of that
spectrum's power stands ``DETECTION_RATIO`` times above the median of the same over the chirps around it: with the
noise alone (an exponential power per bin, B bins), the median of B bins passes 3x its typical value with a
probability under 1e-12 per chirp for B >= 63 (more than half of the bins above 3 ln 2 times their mean, each with a
probability of 1/8).

In an interfered chirp, the burst is placed in fast time on the chirp's spectrum with the bins of the moving echoes
taken out (the bins whose median power over the chirps around stands ``ECHO_RATIO`` over the noise): the envelope of
what is left (analytic, slightly smoothed) stands ``LOCATE_RATIO`` over its median where the burst is. Those samples,
a sample more on each side, are replaced in every channel by the mean of the same samples of the nearest clean chirp
before and after (static clutter and slowly changing echoes continue through them; an aliased blade's echo, new in
each chirp, loses half its power there). A chirp whose burst covers more than ``WHOLE_CHIRP_SHARE`` of it is replaced
whole. Blanking the samples instead (zeros) would leave each interfered chirp with a dip of the echo's power, a
train of dips as periodic as the bursts.

Detection and placement read one channel (bursts reach all RX at once), in reads of ``READ_CHIRPS``: one more read of
a sixteenth of a 16-RX capture, and one real FFT of each chirp.
"""

from dataclasses import dataclass

import numpy as np

from mdpipe.io.radarlog import RadarlogReader

READ_CHIRPS = 1024
TAPER_SHARE = 0.25       # the detection's window: flat but for half-cosine tapers over 12.5 % of the chirp a side
QUANTILE = 0.25          # of a chirp's power over range bins, each bin against its own median over the read's chirps
DETECTION_SPREADS = 12.0  # a chirp is interfered: its quantile this many robust spreads over the read's median ...
MIN_RISE = 2.0           # ... and at least this many times the median
LOCATE_RATIO = 8.0       # a burst sample: the whitened envelope over its median in the chirp
PEAK_SHARE = 0.01        # ... and over a hundredth of its peak (the envelope's filtering spreads a strong burst)
MARGIN = 3               # samples replaced beyond the run on each side (the burst's tapered ends)
WHOLE_CHIRP_SHARE = 0.5
MIN_BINS = 15            # fewer range bins than this: the quantile over bins is too loose to detect on
LOCATE_EVERY = 4         # the whitening's per-bin median is taken on every 4th chirp of a read


@dataclass(frozen=True)
class Bursts:
    """Interfered chirps of a capture and the samples their bursts cover.

    Attributes
    ----------
    chirps : ndarray (K,) of int
        Interfered chirps, ascending.
    spans : ndarray (K, 2) of int
        Per interfered chirp, the first and one-past-last sample replaced.
    n_chirps, n_samples : int
    """

    chirps: np.ndarray
    spans: np.ndarray
    n_chirps: int
    n_samples: int

    @property
    def chirp_share(self):
        """Share of the chirps interfered."""
        return len(self.chirps) / self.n_chirps if self.n_chirps else 0.0

    @property
    def sample_share(self):
        """Share of all samples replaced."""
        return float(np.sum(self.spans[:, 1] - self.spans[:, 0])) / (self.n_chirps * self.n_samples) \
            if self.n_chirps else 0.0

    def note(self):
        """A sentence for the rows' notes; None without bursts."""
        if not len(self.chirps):
            return None
        lengths = self.spans[:, 1] - self.spans[:, 0]
        return (f"another radar's chirps crossed {self.chirp_share:.2%} of the chirps (broadband bursts of "
                f"{int(lengths.min())}-{int(lengths.max())} of {self.n_samples} samples); those samples were replaced "
                "by the neighbouring chirps' before the range transform")

    def excise(self, block, first):
        """Replace, in place, the burst samples of the chirps ``first .. first + M`` of ``block`` (C, M, N), each by
        the mean of the same samples of the nearest chirps of the block before and after that are not interfered (one
        only at the block's edge). Returns ``block``."""
        m = block.shape[1]
        inside = (self.chirps >= first) & (self.chirps < first + m)
        if not np.any(inside):
            return block
        local = self.chirps[inside] - first
        bad = np.zeros(m, dtype=bool)
        bad[local] = True
        clean = np.flatnonzero(~bad)
        if not len(clean):
            return block
        for chirp, (start, stop) in zip(local, self.spans[inside]):
            k = np.searchsorted(clean, chirp)
            around = [clean[j] for j in (k - 1, k) if 0 <= j < len(clean)]
            fill = np.mean([block[:, j, start:stop].astype(np.float64) for j in around], axis=0)
            if block.dtype.kind in "iu":
                info = np.iinfo(block.dtype)
                fill = np.clip(np.rint(fill), info.min, info.max)
            block[:, chirp, start:stop] = fill
        return block


def tukey(n, share):
    """Tukey window of ``n`` samples, flat but for half-cosine tapers over ``share / 2`` of it a side
    (``scipy.signal.windows.tukey(n, share)``; the processing path does not import scipy)."""
    x = np.arange(n) / max(n - 1, 1)
    edge = np.minimum(x, 1 - x)
    return np.where(edge < share / 2, 0.5 * (1 - np.cos(2 * np.pi * edge / share)), 1.0)


def _smoothed(envelope, taps=3):
    return np.convolve(envelope, np.ones(taps) / taps, mode="same")


def bin_typical(power):
    """Each bin's median of ``power`` (M, B) over the M chirps; a bin without power gets the smallest positive one."""
    typical = np.median(power, axis=0)
    positive = typical[typical > 0]
    return np.maximum(typical, positive.min() if len(positive) else 1.0)


def burst_span(whitened, n_samples):
    """The samples a burst covers in one chirp, from its range spectrum about the mean, each bin over its typical
    amplitude (``whitened``: the unwindowed real FFT, bins 1 .. N/2): the run of samples around the peak of its
    analytic envelope (3-sample smoothed) that stands ``LOCATE_RATIO`` times over the envelope's median and over ``PEAK_SHARE`` of the peak, a sample more
    ``MARGIN`` samples more on each side (the transform is circular: the ends of a chirp are not a burst's for lying next to each other).
    Returns ``(start, stop)``; the whole chirp when the burst covers more than ``WHOLE_CHIRP_SHARE`` of it."""
    one_sided = np.zeros(n_samples, dtype=np.complex128)
    one_sided[1:1 + len(whitened)] = whitened
    envelope = _smoothed(np.abs(np.fft.ifft(one_sided)) ** 2)
    peak = int(np.argmax(envelope))
    lit = envelope > max(LOCATE_RATIO * np.median(envelope), envelope[peak] * PEAK_SHARE)
    if not lit[peak]:
        return 0, n_samples
    dark = np.flatnonzero(~lit)
    start = dark[dark < peak].max(initial=-1) + 1
    stop = dark[dark > peak].min(initial=n_samples)
    start, stop = max(0, start - MARGIN), min(n_samples, stop + MARGIN)
    return (0, n_samples) if stop - start > WHOLE_CHIRP_SHARE * n_samples else (int(start), int(stop))


def interfered_chirps(power):
    """Indices of the interfered chirps of a read, from their range spectra's power ``power`` (M, B) about the read's
    mean: a chirp's ``QUANTILE`` over bins of each bin's power over its median over the chirps, against the same of
    the read's other chirps."""
    stat = np.quantile(power / bin_typical(power), QUANTILE, axis=1)
    centre = np.median(stat)
    spread = 1.4826 * np.median(np.abs(stat - centre))
    return np.flatnonzero(stat > max(MIN_RISE * centre, centre + DETECTION_SPREADS * spread))


def _read_bursts(samples, window):
    """Interfered chirps (indices into ``samples``, (M, N) float) and their spans."""
    n = samples.shape[1]
    residual = samples - samples.mean(axis=0)
    hit = interfered_chirps(np.abs(np.fft.rfft(residual * window, axis=1)[:, 1:]) ** 2)
    if not len(hit):
        return hit, np.zeros((0, 2), dtype=int)
    scale = np.sqrt(bin_typical(np.abs(np.fft.rfft(residual[::LOCATE_EVERY], axis=1)[:, 1:]) ** 2))
    spans = [burst_span(spectrum / scale, n) for spectrum in np.fft.rfft(residual[hit], axis=1)[:, 1:]]
    return hit, np.array(spans, dtype=int).reshape(-1, 2)


def find_bursts(reader, *, read_chirps=READ_CHIRPS, channel=0):
    """Pass 0 over ``reader``'s channel ``channel``: the :class:`Bursts` of the capture (none when the chirps hold
    fewer than ``2 * MIN_BINS`` samples)."""
    n, m = reader.params.n_samples, reader.n_chirps
    empty = Bursts(np.array([], dtype=int), np.zeros((0, 2), dtype=int), m, n)
    if n // 2 < MIN_BINS:
        return empty
    reads = max(1, int(np.ceil(m / read_chirps)))
    edges = np.linspace(0, m, reads + 1).astype(int)  # reads of near-equal length: no short last one
    window = tukey(n, TAPER_SHARE)
    chirps, spans = [], []
    for first, stop in zip(edges[:-1], edges[1:]):
        samples = reader.read_counts(first, stop, channels=[channel])[0].astype(np.float32)
        hit, span = _read_bursts(samples, window)
        chirps.append(hit + first)
        spans.append(span)
    return Bursts(np.concatenate(chirps).astype(int), np.concatenate(spans).astype(int), m, n)


class ExcisingReader:
    """``reader`` whose reads come with the bursts of ``bursts`` taken out (:meth:`Bursts.excise`); everything else
    is the reader's."""

    def __init__(self, reader, bursts):
        self._reader = reader
        self.bursts = bursts

    def __getattr__(self, name):
        return getattr(self._reader, name)

    def read_counts(self, start, stop, *, channels=None, out=None):
        return self.bursts.excise(self._reader.read_counts(start, stop, channels=channels, out=out), start)

    read_chirps = RadarlogReader.read_chirps  # both read through this class's read_counts
    iter_chunks = RadarlogReader.iter_chunks
