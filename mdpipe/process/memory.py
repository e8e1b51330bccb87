"""The memory a capture's processing will take, planned from its layout and the options before pass 1.

The estimate adds the arrays :mod:`mdpipe.process.ranging` and the analysis allocate (see
:func:`plan_bytes`); a capture whose plan exceeds the budget is refused with the estimate and the
option to change, instead of growing until the machine swaps or the kernel kills it.
"""

from dataclasses import replace

import numpy as np

from mdpipe.errors import ParameterError
from mdpipe.params import GIB
from mdpipe.process import filters, flashes, interference, ranging

PASS2_BINS_PER_TARGET = 64  # bins a target's path may cross (a bird at 15 m/s over 1 s at 0.23 m bins)
ANALYSIS_BYTES_PER_CHIRP = 1536  # per target: complex128 copies and spectrograms of the slow-time signal (the flash
                                 # edges' 8x zero-padded at a hop of 1/8 frame: 512 B a chirp, and 8 MB of transforms)
FLASH_VIEW_BYTES = 40  # per chirp and view (parts of the ramp, range sides): complex64, complex128 demodulated, a stack
FLANK_LINE_BYTES = 64  # per chirp, where range flanks are read: the target's own power (8 B) and the spectra of it,
                       # the flanks and the common mode (flashes.flank_line_hz: measured 40 B a chirp, beside the
                       # running median's chunk of windows)
RAMP_SLOT_BYTES = 160  # per slot of the ramp parts' grid: the grid, its mask and trend, the autocorrelation's FFTs
BASE_BYTES = 64 * 2**20  # the interpreter, numpy, h5py and BLAS, before any array (measured: 55-60 MB)


def gate_bin_counts(params, process):
    """Bins from 0 to the gate's end (K) and inside the gate (B) on the padded grid, as in ``gate_statistics``."""
    ranges = ranging.bin_range_m(np.arange(process.zero_pad * params.n_samples // 2 + 1), params, process.zero_pad)
    ranges = ranges[ranges <= min(process.max_range_m, params.max_range_m)]
    return len(ranges), int(np.count_nonzero(ranges[1:] >= process.min_range_m))


def plan_bytes(*, n_chirps, n_channels, n_samples, sample_itemsize, read_chunk_bytes, params, process):
    """Estimated peak bytes of processing one capture, by part.

    Parameters
    ----------
    n_chirps, n_channels, n_samples : int
        The capture's layout (``n_samples`` as stored, with a frame counter column).
    sample_itemsize : int
        Bytes per stored sample (2 for int16).
    read_chunk_bytes : int
        Bytes HDF5 decompresses at once (``RadarlogReader.read_chunk_bytes``).
    params : RadarParams
    process : ProcessParams

    Returns
    -------
    dict
        ``{part: bytes}``; the peak is ``max(pass 0, pass 1, pass 2) + analysis + base`` and the common mode
        per chirp. Pass 0 (:func:`mdpipe.process.interference.common_mode`) holds one read of one channel and its
        transforms. Pass 1 holds, in each of
        the ``ranging.WORKERS`` threads that have a chunk, a read buffer of a chunk's probed chirps and
        its DFT at the K bins (real product and complex result, 24 B per chirp, channel and bin; then
        the result, the gate's slow-time copies and a conjugate, 8 B per bin and 24 B per gate bin)
        with their channel products; beside them the range DFT matrix while it is built (40 B per
        sample and bin: complex128 exponential, its windowed copy, float64 real and imaginary parts
        and the float32 result) and the accumulators. Pass 2 reads ``ranging.READ_CHIRPS`` chirps per
        thread, transforms them at the grid columns the targets' tracks cross, and keeps each target's
        slow time (bounded here by n_chirps x bins, complex64). The analysis holds each target's copies and
        spectrograms, and one target's flash views (``ranging.flash_views``) with their grid of ramp parts
        (at most ``flashes.RAMP_MAX_SLOTS`` slots) and its range flanks where a long ramp has them read
        (``ranging.flank_powers``: at most ``ranging.FLANK_MAX_BINS`` bins a side).
    """
    c, n = n_channels, n_samples
    k, b = gate_bin_counts(params, process)
    fft_bins = ranging.FINE_STEPS * process.zero_pad * params.n_samples // 2 + 1  # range_bins "all": fine grid
    probe = min(ranging.PROBE_CHIRPS, process.chunk_chirps)  # rows read of each chunk, as gate_statistics does
    if n_chirps * probe / process.chunk_chirps < ranging.MIN_PROBED_CHIRPS:
        probe = process.chunk_chirps
    workers = min(ranging.WORKERS, -(-n_chirps // process.chunk_chirps))  # threads with a chunk at once
    reads = workers * read_chunk_bytes
    pass1 = (workers * (c * probe * n * sample_itemsize + c * probe * max(24 * k, 8 * k + 24 * b) + 8 * b * c * c)
             + 40 * params.n_samples * k                                  # DFT matrix while it is built
             + 16 * k * c + 16 * b * c * c                                # accumulators
             + 8 * b * (-(-n_chirps // process.chunk_chirps)) + reads)   # per-chunk power of the gate bins
    n_bins = min(b, process.max_targets * PASS2_BINS_PER_TARGET)
    real = np.dtype(process.dtype).itemsize
    rows = ranging.READ_CHIRPS
    per_thread = c * rows * n * sample_itemsize + (
        c * rows * (fft_bins * 4 * real + n * 2 * real) if process.range_bins == "all"  # rfft, conj, windowed
        else c * rows * n_bins * 8 * real)
    workers = min(ranging.WORKERS, -(-n_chirps // rows))
    pass2 = workers * per_thread + 2 * n_chirps * n_bins * 2 * real + 8 * params.n_samples * n_bins + reads
    # one target's flash views at a time (read only where the features ask), and its bounded grid of ramp parts;
    # its range flanks' bins (complex64) where a long ramp has them read, their power (float64, both flanks) and its
    # line spectra, and their kernels (complex64, the last few bins' kept, each built through complex128)
    flanks = ranging.flank_bins(params, process.range_window)
    side = 0 if flanks is None else len(ranging.flank_offsets(*flanks))
    views = n_chirps * ((flashes.RAMP_PARTS + 2) * FLASH_VIEW_BYTES + (2 * side * 8 + 16 + FLANK_LINE_BYTES if side
                                                                      else 0))
    views += 2 * side * params.n_samples * (8 * ranging.FLANK_KERNELS + 16)
    views += filters.MEDIAN_CHUNK * flashes.LINE_MEDIAN_BINS[1] * 8 if side else 0  # the line spectra's median
    share = max(params.sampled_duration_s / params.chirp_period_s, flashes.RAMP_MIN_SHARE)
    slots = min(n_chirps * flashes.RAMP_PARTS / share, flashes.RAMP_MAX_SLOTS)
    analysis = process.max_targets * n_chirps * ANALYSIS_BYTES_PER_CHIRP + views + int(slots) * RAMP_SLOT_BYTES
    pass0 = interference.read_chirps(params.n_samples) * n * (sample_itemsize + interference.READ_BYTES_PER_SAMPLE)
    common = 24 * n_chirps  # the common mode per chirp, kept to the end, and its float64 copy when rows are read
    return {"pass 0": pass0, "pass 1": pass1, "pass 2": pass2, "analysis": analysis, "base": BASE_BYTES,
            "peak": max(pass0, pass1, pass2) + analysis + common + BASE_BYTES}


def check_memory(reader, process):
    """Refuse ``reader``'s capture when the plan for ``process`` exceeds ``process.max_memory_gb``.

    Raises
    ------
    ParameterError
        Naming the estimate, its largest part and the options that bring it down.
    """
    layout = dict(n_chirps=reader.n_chirps, n_channels=reader.params.n_channels,
                  n_samples=reader.params.n_samples + reader.layout.frame_counter,
                  sample_itemsize=np.dtype(reader.layout.sample_dtype).itemsize,
                  read_chunk_bytes=reader.read_chunk_bytes, params=reader.params)
    plan = plan_bytes(**layout, process=process)
    budget = process.max_memory_gb * GIB
    if plan["peak"] <= budget:
        return plan
    k, b = gate_bin_counts(reader.params, process)
    hints = []
    if process.zero_pad > 1:
        smaller = plan_bytes(**layout, process=replace(process, zero_pad=1))["peak"]
        hints.append(f"--zero-pad 1 ({smaller / GIB:.2f} GB)")
    hints.append(f"a shorter --max-range-m ({k} range bins up to {min(process.max_range_m, reader.params.max_range_m):g} m)")
    largest = max(("pass 1", "pass 2", "analysis"), key=plan.get)
    raise ParameterError(
        f"{reader.path}: processing would need about {plan['peak'] / GIB:.2f} GB ({largest} {plan[largest] / GIB:.2f} GB "
        f"for {reader.params.n_channels} RX x {reader.params.n_samples} samples x {b} gate bins, "
        f"{reader.n_chirps} chirps), over the {process.max_memory_gb:g} GB budget; use "
        f"{' or '.join(hints)}, or raise --max-memory-gb")


def iq_plan_bytes(n_samples, n_channels, stored_bytes_per_sample):
    """Estimated peak bytes of analysing an I/Q recording (:mod:`mdpipe.process.cw`), by part: its samples as read
    (``stored_bytes_per_sample`` per sample and channel: a WAV's are mapped, not read, and count nothing), as
    complex64 volts, the channels combined (complex128, and a complex64 product), and one target's analysis (as a
    capture's, per sample)."""
    read = stored_bytes_per_sample * n_samples * n_channels
    samples = 8 * n_samples * n_channels
    combined = 24 * n_samples
    analysis = n_samples * ANALYSIS_BYTES_PER_CHIRP
    return {"read": read, "samples": samples, "combined": combined, "analysis": analysis, "base": BASE_BYTES,
            "peak": read + samples + combined + analysis + BASE_BYTES}


def check_iq_memory(path, n_samples, params, process, *, stored_bytes_per_sample=0):
    """Refuse an I/Q recording whose plan (:func:`iq_plan_bytes`) exceeds ``process.max_memory_gb``, before its
    samples are read."""
    plan = iq_plan_bytes(n_samples, params.n_channels, stored_bytes_per_sample)
    if plan["peak"] > process.max_memory_gb * GIB:
        raise ParameterError(
            f"{path}: analysing {n_samples:,} I/Q samples x {params.n_channels} RX "
            f"({params.duration_s(n_samples):.4g} s) would need about {plan['peak'] / GIB:.2f} GB, over the "
            f"{process.max_memory_gb:g} GB budget; raise "
            "--max-memory-gb or analyse a shorter recording")
    return plan
