"""Range processing, streamed over chunks of chirps, only at the range bins that are needed.

Pass 1 (:func:`gate_statistics`) reads a sample of every chunk (the first ``probe_chirps`` of each
``chunk_chirps``: an eighth by default; all of a capture whose sample would hold fewer than
``MIN_PROBED_CHIRPS``) and evaluates the windowed range DFT at the bins from 0 to
the end of the gate only, as one matrix product. It keeps what selection needs: the static
(slow-time mean) and moving (MTI) power of those bins, each gate bin's channel mean and channel
covariance of its moving part, its moving power in every chunk (for tracking), and the Doppler
power spectrum of each gate bin averaged over the probed blocks (for detection: each block's slow
time, its mean removed, Hann-windowed, summed over channels). Statistics of an eighth of the chirps
are statistics all the same; memory does not grow with the capture.

Pass 2 (:func:`slow_time`) reads every chirp and evaluates the DFT only where the targets are:
each target follows a fractional range-bin track, and in each chunk of chirps the DFT is evaluated
on a grid of ``1 / FINE_STEPS`` bin spanning that chunk's part of the track, the channels combined
with the target's weights, and adjacent grid columns blended linearly per chirp (a track that
hardly moves over the chunk: one column at its mean position). The DFT's phase
reference is the middle sample of the chirp: the response of a symmetric window to a tone is then
real at every evaluation frequency inside its main lobe, so columns near the target share its
phase and the blend changes neither phase nor (to the window's curvature over 1/8 bin, < 0.03 dB
for Hann) amplitude as the target moves across bins: no step enters the Doppler spectrum.

Both work on the stored counts: one int16 -> float conversion, one product with a (N, 2K) real
matrix (real and imaginary parts), the full scale applied to the small result; chunks go to two
worker threads, so one chunk is read while the other is transformed (numpy releases the GIL); BLAS
is held to one thread inside them (two workers each running a two-thread BLAS on two cores cost
~40 % more time).
Slow-time signals follow the paper's Doppler sign (approaching positive): the range FFT of a real IF
carries ``exp(+j 4 pi R / lambda)`` in its positive-frequency bins, so the DFT is conjugated.
Arrays are (channel, chirp, sample) in, (chirp, bin) out.
"""

import functools
import os
import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
from threadpoolctl import threadpool_limits

from mdpipe.io import INT16_FULL_SCALE
from mdpipe.physics import rotor
from mdpipe.process.doppler import periodic_hann

PROBE_CHIRPS = 32
TRANSFORM_ROWS = 128  # 128 x 2048 float32 = 1 MB: stays in L2
READ_CHIRPS = 1024    # pass 2 reads: h5py costs ~0.1 ms a call; 1024 rows a call reach ~4.5 GB/s
MIN_PROBED_CHIRPS = 2048
FINE_STEPS = 8        # pass-2 evaluation grid: 1/8 range bin
STILL_FINE_STEPS = 0.125  # a track moving less than 1/64 bin over a read: one column at its mean position
WORKERS = min(2, os.cpu_count() or 1)  # threads reading and transforming one capture (see share_cores)
FLANK_MIN_REACH_BINS = 4.0  # range flanks read where the fastest tips' flashes land this far off or farther ...
FLANK_MAX_BINS = 64         # ... at most this many bins a side (a bounded memory: 8 B a bin a chirp) ...
FLANK_KERNELS = 4           # ... and their kernels at this many of a track's bins kept at once
MAIN_LOBE_BINS = {"hann": 2.0, "hamming": 2.0, "blackman": 3.0, "boxcar": 1.0}  # each range window's main lobe, +-
LEAK_OFFSETS = 21  # a target's positions within half a bin of its bin at which its sidelobes' share is read


def share_cores(processes):
    """Read and transform each capture in this process's share of the cores, ``processes`` of mdpipe running
    at once (a pool's workers): ``WORKERS`` becomes max(1, min(2, cores // processes)). A pool of two on two
    cores ran the samples 2 % sooner with one thread a worker than with two."""
    global WORKERS
    WORKERS = max(1, min(2, (os.cpu_count() or 1) // max(1, processes)))


RANGE_WINDOW_FUNCTIONS = {"hann": np.hanning, "hamming": np.hamming, "blackman": np.blackman, "boxcar": np.ones}


def range_window(name, n_samples):
    """Symmetric window of ``n_samples`` for the range FFT."""
    return RANGE_WINDOW_FUNCTIONS[name](n_samples)


def bin_range_m(bins, params, zero_pad):
    """Range of (fractional) FFT bins of a ``zero_pad`` times padded range FFT."""
    return np.asarray(bins, dtype=np.float64) * params.range_bin_m / zero_pad


def dft_matrix(n_samples, bins, *, window, zero_pad, dtype):
    """Real (N, 2K) matrix: ``counts @ m`` gives the conjugated windowed DFT at (fractional) ``bins``, real parts
    then imaginary; phase referred to the middle sample ``(N - 1) / 2``."""
    n = np.arange(n_samples) - (n_samples - 1) / 2
    dft = range_window(window, n_samples)[:, None] * np.exp(
        2j * np.pi * np.outer(n, bins) / (zero_pad * n_samples))
    return np.concatenate([dft.real, dft.imag], axis=1).astype(dtype)


def range_response(offset_bins, *, window, n_samples, zero_pad):
    """Amplitude response of the windowed range DFT to a tone ``offset_bins`` (padded grid) away, 1 at 0.

    Real, since the window is symmetric about the phase reference; shape of ``offset_bins``.
    """
    n = np.arange(n_samples) - (n_samples - 1) / 2
    w = range_window(window, n_samples)
    d = np.asarray(offset_bins, dtype=np.float64)
    return (np.cos(2 * np.pi * np.multiply.outer(d, n) / (zero_pad * n_samples)) @ w) / w.sum()


def transform(counts, matrix, dtype):
    """DFT of counts (C, M, N) at the matrix's K bins: complex (C, M, K), in counts.

    Rows are converted and multiplied ``TRANSFORM_ROWS`` at a time, so the float copy stays in
    cache (one large temporary instead costs ~4x the time, in page faults and memory traffic).
    """
    c, m, n = counts.shape
    product = np.empty((c, m, matrix.shape[1]), dtype=matrix.dtype)
    for channel in range(c):  # one channel's rows are contiguous even in a partial view of a buffer
        for start in range(0, m, TRANSFORM_ROWS):
            np.matmul(counts[channel, start:start + TRANSFORM_ROWS].astype(dtype), matrix,
                      out=product[channel, start:start + TRANSFORM_ROWS])
    k = matrix.shape[1] // 2
    unit = np.array(1j, dtype=np.result_type(matrix.dtype, np.complex64))  # keeps float32 single precision
    return product[..., :k] + unit * product[..., k:]


@dataclass(frozen=True)
class GateStatistics:
    """Pass-1 summary of a capture (powers per chirp and channel, in V^2).

    Attributes
    ----------
    range_m : ndarray (n_bins,)
        Range of the bins from 0 to the gate's end (padded grid).
    static_power, moving_power : ndarray (n_bins,)
        Power of the slow-time mean, and mean power about it (MTI).
    gate_bins : ndarray (B,) of int
        Bins inside the range gate.
    mean : ndarray (B, C) complex
        Slow-time mean of each gate bin and channel (V).
    covariance : ndarray (B, C, C) complex
        Channel covariance of the moving part of each gate bin.
    chunk_power : ndarray (n_chunks, B)
        Moving power (about the chunk's own mean) of each gate bin in each chunk, summed over channels.
    chunk_centres : ndarray (n_chunks,)
        Chirp index (fractional) at the middle of the chirps each chunk's power was measured on.
    doppler_power : ndarray (B, L)
        Per gate bin, the Doppler power spectrum (FFT order, L = chirps per probed block) of each
        block's slow time about its mean, periodic Hann window, scaled so a tone of amplitude a
        gives a^2, summed over channels and averaged over the ``doppler_blocks`` full blocks.
    doppler_blocks : int
        Blocks averaged in ``doppler_power``.
    n_chirps : int
        Chirps in the capture.
    clipped_fraction : float
        Share of the sampled counts at the int16 full scale (0 for float samples).
    """

    range_m: np.ndarray
    static_power: np.ndarray
    moving_power: np.ndarray
    gate_bins: np.ndarray
    mean: np.ndarray
    covariance: np.ndarray
    chunk_power: np.ndarray
    chunk_centres: np.ndarray
    doppler_power: np.ndarray
    doppler_blocks: int
    n_chirps: int
    clipped_fraction: float = 0.0

    @property
    def gate_range_m(self):
        return self.range_m[self.gate_bins]

    @property
    def gate_moving_power(self):
        """Moving power per chirp summed over channels, per gate bin."""
        return np.real(np.trace(self.covariance, axis1=1, axis2=2))


_buffers = threading.local()


def read_reused(reader, first, stop):
    """``reader.read_counts`` into a buffer kept per thread (fresh 16 MB arrays cost page faults every chunk)."""
    shape = (reader.params.n_channels, stop - first, reader.params.n_samples + reader.layout.frame_counter)
    buffer = getattr(_buffers, "counts", None)
    if buffer is None or buffer.shape[0] != shape[0] or buffer.shape[1] < shape[1] or buffer.shape[2] != shape[2] \
            or buffer.dtype != np.dtype(reader.layout.sample_dtype):
        buffer = _buffers.counts = np.empty(shape, dtype=reader.layout.sample_dtype)
    return reader.read_counts(first, stop, out=buffer[:, :shape[1]])


def _probe(reader, first, rows, matrix, gate, clip, full_rows):
    """One chunk's sums for :func:`gate_statistics`; its Doppler power only for a full block of ``full_rows`` (a
    shorter last one is not averaged in, and one chirp's Hann window is all zeros)."""
    counts = read_reused(reader, first, first + rows)
    x = transform(counts, matrix, np.float32)  # (C, M, bins)
    g = x[:, :, gate].transpose(2, 0, 1)  # (B, C, M)
    local = g - g.mean(axis=-1, keepdims=True)
    clipped = 0 if clip is None else int(np.count_nonzero(counts >= clip) + np.count_nonzero(counts <= -clip - 1))
    doppler = None
    if rows == full_rows:
        window = periodic_hann(rows).astype(np.float32)
        doppler = np.sum(np.abs(np.fft.fft(local * window, axis=-1)) ** 2, axis=1) / np.sum(window) ** 2
    return (x.sum(axis=1).T, np.einsum("cmb,cmb->b", x, x.conj()).real, g @ g.conj().transpose(0, 2, 1),
            np.sum(np.abs(local) ** 2, axis=(1, 2)) / rows, clipped, counts.size, doppler)


def gate_statistics(reader, *, window="hann", zero_pad=1, min_range_m=0.0, max_range_m=np.inf, chunk_chirps=256,
                    probe_chirps=PROBE_CHIRPS):
    """Pass 1 over ``reader`` (a :class:`mdpipe.io.RadarlogReader`); see :class:`GateStatistics`."""
    params = reader.params
    ranges = bin_range_m(np.arange(zero_pad * params.n_samples // 2 + 1), params, zero_pad)
    ranges = ranges[ranges <= max_range_m]
    gate = np.flatnonzero((ranges >= min_range_m) & (np.arange(len(ranges)) > 0))
    matrix = dft_matrix(params.n_samples, np.arange(len(ranges)), window=window, zero_pad=zero_pad, dtype=np.float32)
    clip = INT16_FULL_SCALE if reader.layout.sample_dtype == "int16" else None
    firsts = range(0, reader.n_chirps, chunk_chirps)
    if reader.n_chirps * min(probe_chirps, chunk_chirps) / chunk_chirps < MIN_PROBED_CHIRPS:
        probe_chirps = chunk_chirps
    rows = [min(probe_chirps, chunk_chirps, reader.n_chirps - first) for first in firsts]
    n_ch = params.n_channels
    total = np.zeros((len(ranges), n_ch), dtype=np.complex128)
    power = np.zeros(len(ranges))
    cross = np.zeros((len(gate), n_ch, n_ch), dtype=np.complex128)
    chunk_power, clipped, counted = [], 0, 0
    doppler, blocks = np.zeros((len(gate), rows[0])), 0
    with threadpool_limits(limits=1, user_api="blas"), ThreadPoolExecutor(WORKERS) as pool:
        for part in pool.map(lambda job: _probe(reader, *job, matrix, gate, clip, rows[0]), zip(firsts, rows)):
            total += part[0]  # summed as they come: memory does not grow with the capture
            power += part[1]
            cross += part[2]
            chunk_power.append(part[3])
            clipped += part[4]
            counted += part[5]
            if part[6] is not None:  # full blocks only (the last may be shorter)
                doppler += part[6]
                blocks += 1
    scale = params.full_scale_v_per_lsb
    n = sum(rows)
    mean = total * (scale / n)
    static = np.sum(np.abs(mean) ** 2, axis=1) / n_ch
    moving = power * (scale ** 2 / (n * n_ch)) - static
    gmean = mean[gate]
    covariance = cross * (scale ** 2 / n) - gmean[:, :, None] * gmean[:, None, :].conj()
    return GateStatistics(range_m=ranges, static_power=static, moving_power=np.maximum(moving, 0.0), gate_bins=gate,
                          mean=gmean, covariance=covariance,
                          chunk_power=np.array(chunk_power).reshape(-1, len(gate)) * scale ** 2,
                          chunk_centres=np.array(firsts) + (np.array(rows) - 1) / 2,
                          doppler_power=doppler * (scale ** 2 / blocks), doppler_blocks=blocks,
                          n_chirps=reader.n_chirps, clipped_fraction=clipped / counted)


def fine_columns(track_bins):
    """Grid columns (integers, in units of ``1 / FINE_STEPS`` bin) that bracket every position of ``track_bins``."""
    fine = np.asarray(track_bins) * FINE_STEPS
    return np.arange(int(np.floor(fine.min())), int(np.floor(fine.max())) + 2)


def blend(columns_signal, first_column, track_bins):
    """Linear blend of adjacent grid columns at each chirp's track position.

    Parameters
    ----------
    columns_signal : ndarray (M, J) complex
        Slow time at grid columns ``first_column .. first_column + J - 1``.
    track_bins : ndarray (M,)
        Target position (padded-grid bins) at each chirp.

    Returns
    -------
    ndarray (M,) complex
    """
    fine = np.asarray(track_bins) * FINE_STEPS - first_column
    left = np.clip(np.floor(fine).astype(int), 0, columns_signal.shape[1] - 2)
    frac = (fine - left).astype(columns_signal.real.dtype)
    rows = np.arange(len(fine))
    return columns_signal[rows, left] * (1 - frac) + columns_signal[rows, left + 1] * frac


def slow_time(reader, tracks, weights, *, window="hann", zero_pad=1, chunk_chirps=READ_CHIRPS, dtype="float32",
              all_bins=False):
    """Pass 2: complex slow-time signals of targets that follow fractional range-bin ``tracks``.

    Parameters
    ----------
    tracks : ndarray (T, n_chirps)
        Each target's position at each chirp, in padded-grid bins (fractional).
    weights : ndarray (T, C) complex
        Signal of target t is ``sum_c weights[t, c] * X[c]`` at its track.
    dtype : {"float32", "float64"}
        Precision of the transform.
    all_bins : bool
        Take the full FFT (``FINE_STEPS`` times more padded) and pick the grid columns, instead of
        the DFT at those columns only.

    The static part of each column (the mean chirp's transform) is taken out along the same track,
    so static clutter near a moving target's path leaves no line. Where a track moves less than
    ``STILL_FINE_STEPS / FINE_STEPS`` bin over a read (a hovering target), the DFT is evaluated at one
    column, its mean position there (half the GEMM of two
    grid columns): the position then steps by less than 1/64 bin between reads, an amplitude
    change below 1e-3 near the response's peak and no phase step.

    Returns
    -------
    ndarray, complex, shape (n_chirps, T), V
    """
    params = reader.params
    real = np.dtype(dtype)
    tracks = np.atleast_2d(np.asarray(tracks, dtype=np.float64))
    n = params.n_samples
    win = range_window(window, n).astype(real)
    n_fft = FINE_STEPS * zero_pad * n
    w = np.asarray(weights) * params.full_scale_v_per_lsb
    out = np.empty((reader.n_chirps, len(tracks)), dtype=np.result_type(real, np.complex64))

    plans, sums = {}, []

    def columns_of(first, stop):
        parts = [track[first:stop] for track in tracks]
        still = [not all_bins and np.ptp(part) * FINE_STEPS < STILL_FINE_STEPS for part in parts]
        columns = [np.array([part.mean() * FINE_STEPS]) if fixed else fine_columns(part)
                   for part, fixed in zip(parts, still)]
        return parts, still, columns

    def along_tracks(x, first, stop):
        """Each target's slow time from the grid columns ``x`` (C, M, K) of chirps ``first .. stop``."""
        parts, still, columns = plans[first]
        start = 0
        for t, (part, cols, fixed) in enumerate(zip(parts, columns, still)):
            combined = np.einsum("cmk,c->mk", x[:, :, start:start + len(cols)], w[t])
            if combined.shape[0] != stop - first:  # the static profile, one row for every chirp
                combined = np.broadcast_to(combined, (stop - first, combined.shape[1]))
            yield t, combined[:, 0] if fixed else blend(combined, cols[0], part)
            start += len(cols)

    def grid_transform(counts, grid):
        if all_bins:
            centre = np.exp(1j * np.pi * grid * (n - 1) / n_fft)  # phase reference to the middle sample
            return np.conj(np.fft.rfft(counts.astype(real) * win, n=n_fft, axis=-1)[..., grid.astype(int)] * centre)
        return transform(counts, dft_matrix(n, grid / FINE_STEPS, window=window, zero_pad=zero_pad, dtype=real), real)

    def chunk(first):
        counts = read_reused(reader, first, min(first + chunk_chirps, reader.n_chirps))
        stop = first + counts.shape[1]
        sums.append(counts.sum(axis=1, dtype=np.float64))
        plans[first] = columns_of(first, stop)
        x = grid_transform(counts, np.concatenate(plans[first][2]))
        for t, signal in along_tracks(x, first, stop):
            out[first:stop, t] = signal

    with threadpool_limits(limits=1, user_api="blas"), ThreadPoolExecutor(WORKERS) as pool:
        list(pool.map(chunk, range(0, reader.n_chirps, chunk_chirps)))
    # Static clutter is constant in each range column, but not along a moving track: the blend of
    # columns would modulate it into a moving line. Its part, the mean chirp taken along the same
    # columns and blend, is subtracted.
    mean = (np.sum(sums, axis=0) / reader.n_chirps)[:, None, :]
    for first in plans:
        stop = min(first + chunk_chirps, reader.n_chirps)
        x = grid_transform(mean, np.concatenate(plans[first][2]))
        for t, static in along_tracks(x, first, stop):
            out[first:stop, t] -= static
    return out


def centred_rows(taper, bins, *, zero_pad=1):
    """Rows (len(bins), N) of the ``taper``-windowed, conjugated DFT at (fractional) ``bins`` of a ``zero_pad`` times
    padded grid, each sample's phase referred to the middle one (:func:`dft_matrix`'s convention, complex)."""
    n = len(taper)
    centred = np.arange(n) - (n - 1) / 2
    return taper * np.exp(2j * np.pi * np.atleast_1d(bins)[:, None] / (zero_pad * n) * centred)


@dataclass(frozen=True)
class FlashViews:
    """A target's slow time seen two more ways (:func:`flash_views`): ``parts`` (n_chirps, S), each of S equal
    parts of every ramp; ``sides`` (n_chirps, 2), the whole ramp at the track's bin less and more ``side_bins``."""

    parts: np.ndarray
    sides: np.ndarray


def flash_views(reader, track_bins, weight, *, segments, side_bins, window="hann", zero_pad=1, chunk_chirps=256):
    """Pass 2b: the slow time that tells blade flashes apart, one more read of the capture: a
    :class:`FlashViews`, V.

    * Parts: each of ``segments`` equal parts of the IF is windowed on its own (``window`` of its length) and
      transformed at the track's bin (``track_bins``, padded grid, its mean over each read), its phase referred
      to the part's own middle sample (a window symmetric about it answers a tone in its main lobe with a real
      gain: the bin's steps between reads change no phase). They see the range ``segments`` times coarser; they
      tell where in the ramp a flash shorter than a chirp fell, which the whole ramp's transform (one sample per
      chirp) does not.
    * Sides: the whole ramp transformed ``side_bins`` (padded grid) below and above the track's bin. A blade's
      Doppler shift moves its beat (f_D N / fs bins, the approaching blade's down, the receding one's up): the two
      sides weigh the two blades of a flash unequally.

    The channels are combined with ``weight`` (C,); static clutter, the mean chirp's transform by the same
    kernels, is taken out of every read, as :func:`slow_time` does.
    """
    params = reader.params
    n = params.n_samples
    length = n // segments
    taper = range_window(window, length)
    whole = range_window(window, n)
    m = np.arange(n)
    weight = np.asarray(weight, dtype=np.complex64)
    parts_of_weight = np.stack([weight.real, weight.imag])  # (2, C): the real chirps combined by real products
    views = np.empty((reader.n_chirps, segments + 2), dtype=np.complex64)
    total = np.zeros(n, dtype=np.complex128)

    def side(bin_):
        return centred_rows(whole, bin_, zero_pad=zero_pad)[0]

    def kernels(first, stop):
        """The parts' kernels at the read's mean track, and each side's at its nearest and farthest track with
        each chirp's share between them: off the main lobe's peak the response's slope would turn a step of the
        bin between reads into a step of the body's leak."""
        track = np.asarray(track_bins[first:stop], dtype=np.float64)
        kernel = np.zeros((segments + 4, n), dtype=np.complex64)
        for s in range(segments):
            inside = m[s * length:(s + 1) * length]
            kernel[s, inside] = taper * np.exp(2j * np.pi * track.mean() / (zero_pad * n) * (inside - inside.mean()))
        low, high = track.min(), track.max()
        kernel[segments:] = [side(low - side_bins), side(high - side_bins), side(low + side_bins),
                             side(high + side_bins)]
        share = (track - low) / (high - low) if high > low else np.zeros_like(track)
        return kernel, share[:, None].astype(np.float32)

    def place(first, raw, share):
        stop = first + len(share)
        views[first:stop, :segments] += raw[..., :segments]
        views[first:stop, segments:] += raw[..., segments::2] * (1 - share) + raw[..., segments + 1::2] * share

    for first, block in reader.iter_chunks(chunk_chirps=chunk_chirps):
        # (chirps, samples): one real batched product, 7x faster than a complex tensordot that upcasts the block
        real_imag = np.matmul(parts_of_weight, block)
        combined = (real_imag[:, 0] + 1j * real_imag[:, 1]).astype(np.complex64)
        kernel, share = kernels(first, first + block.shape[0])
        views[first:first + block.shape[0]] = 0
        place(first, combined @ kernel.T, share)
        total += combined.sum(axis=0)
    mean = total / max(reader.n_chirps, 1)  # the mean chirp: static clutter, taken out by the same kernels
    for first in range(0, reader.n_chirps, chunk_chirps):
        kernel, share = kernels(first, min(first + chunk_chirps, reader.n_chirps))
        place(first, -(kernel @ mean).astype(np.complex64), share)
    return FlashViews(views[:, :segments], views[:, segments:])


@dataclass(frozen=True)
class Flanks:
    """A target's range flanks read (:func:`flank_powers`): ``power`` (n_chirps, 2), and beside it what every range bin
    of the capture holds in common per chirp (``common``, (n_chirps,),
    :attr:`mdpipe.process.interference.CommonMode.series`; None: not known), against which flashes local to the
    target are told."""

    power: np.ndarray
    common: np.ndarray = None
    leak_db: float = None  # the range window's sidelobes' share of the target's power in one flank, at most (dB)


def flank_bins(params, window):
    """(inner, outer): how far (range bins) a target's range flanks reach, past its main lobe (``MAIN_LOBE_BINS`` of
    ``window``) and half a bin of its track, out to where a long ramp moves the flashes of the fastest rotor tips
    (``rotor.MAX_ROTOR_TIP_MPS``: their Doppler times the sampled ramp) and a main lobe beyond; None where that reach
    is under ``FLANK_MIN_REACH_BINS``: the flashes stay in the target's own bin and its sides (:func:`flash_views`)."""
    reach = 2.0 * rotor.MAX_ROTOR_TIP_MPS / params.wavelength_m * params.sampled_duration_s
    if reach < FLANK_MIN_REACH_BINS:
        return None
    lobe = MAIN_LOBE_BINS[window]
    return lobe + 0.5, reach + lobe


@functools.lru_cache(maxsize=16)
def flank_leak_db(window, n_samples, inner_bins, outer_bins, *, offsets=LEAK_OFFSETS):
    """The greater share (dB) of a target's power that the range ``window``'s sidelobes put in one of its flanks (the
    bins :func:`flank_offsets` reads, either side), the target anywhere within half a bin of the bin its track is
    rounded to (``offsets`` positions): the flank powers hold a target's own echo at this share or less (Hann over
    3-66 bins: -30.1 dB, the target half a bin off; a boxcar's: -6.3 dB)."""
    taper = range_window(window, n_samples)
    bins = flank_offsets(inner_bins, outer_bins)
    worst = 0.0
    for offset in np.linspace(-0.5, 0.5, offsets):  # a tone off its bin read by the flanks' kernels (centred_rows)
        response = np.abs(centred_rows(taper, np.concatenate([[0], bins, -bins]) - offset).sum(axis=1)) ** 2
        own, near, far = response[0], response[1:len(bins) + 1].sum(), response[len(bins) + 1:].sum()
        worst = max(worst, near / own, far / own)
    return float(10 * np.log10(max(worst, np.finfo(float).tiny)))


def flank_offsets(inner_bins, outer_bins):
    """The bins a flank reads, off the target's (rounded) bin: from ``ceil(inner_bins)`` to ``floor(outer_bins)``, at
    most ``FLANK_MAX_BINS`` of them."""
    first = int(np.ceil(inner_bins))
    return np.arange(first, min(int(np.floor(outer_bins)), first + FLANK_MAX_BINS - 1) + 1)


def flank_powers(reader, track_bins, weight, *, inner_bins, outer_bins, window="hann", zero_pad=1, chunk_chirps=256):
    """Pass 2c: the moving power, per chirp, of the range bins either side of a target (:func:`flank_offsets` of
    ``inner_bins`` and ``outer_bins``, not padded, off its track ``track_bins``, padded grid, rounded to a bin at its
    mean over each read): (n_chirps, 2) in V^2, the nearer range's flank first. One more read of the capture.

    A long ramp moves a blade's flash in range by its Doppler times the sampled ramp (an up-chirp's beat holds both):
    at a low PRF the flashes of tips that fold many times in slow time land metres off their drone, on both sides,
    and its own bin holds little of them. The flanks gather them. The DFT is conjugated and the channels combined with
    ``weight`` (C,) as in :func:`slow_time`; static clutter, the mean chirp's transform by the same kernels, is taken
    out of every read; bins outside the FFT's positive half are left out. The flanks stay put within a read: a target
    moving a bin or more over one brings its main lobe's edge into them (a power that swells, not flashes).
    """
    params = reader.params
    n = params.n_samples
    taper = range_window(window, n)
    offsets = flank_offsets(inner_bins, outer_bins)
    offsets = np.concatenate([-offsets[::-1], offsets])  # the nearer flank, then the farther
    near = len(offsets) // 2
    weight = np.asarray(weight, dtype=np.complex64)
    parts_of_weight = np.stack([weight.real, weight.imag])  # (2, C): the real chirps combined by real products
    columns = np.zeros((reader.n_chirps, len(offsets)), dtype=np.complex64)
    total = np.zeros(n, dtype=np.complex128)

    @functools.lru_cache(maxsize=FLANK_KERNELS)
    def at(centre):
        bins = centre + offsets
        k = centred_rows(taper, bins).astype(np.complex64)
        k[(bins < 1) | (bins > n // 2 - 1)] = 0.0
        return k

    def kernel(first, stop):  # at the read's mean track, rounded to a bin: the reads' bins come in order, a few kept
        return at(int(round(float(np.mean(track_bins[first:stop])) / zero_pad)))

    for first, block in reader.iter_chunks(chunk_chirps=chunk_chirps):
        real_imag = np.matmul(parts_of_weight, block)
        combined = (real_imag[:, 0] + 1j * real_imag[:, 1]).astype(np.complex64)
        columns[first:first + block.shape[0]] = combined @ kernel(first, first + block.shape[0]).T
        total += combined.sum(axis=0)
    mean = total / max(reader.n_chirps, 1)
    power = np.zeros((reader.n_chirps, 2))
    for first in range(0, reader.n_chirps, chunk_chirps):
        stop = min(first + chunk_chirps, reader.n_chirps)
        read = np.abs(columns[first:stop] - (kernel(first, stop) @ mean).astype(np.complex64)).astype(np.float64) ** 2
        power[first:stop] = np.stack([read[:, :near].sum(axis=1), read[:, near:].sum(axis=1)], axis=1)
    return power
