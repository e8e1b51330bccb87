"""Hostile and broken Radarlog files, made with h5py: one builder per class, each ``build(folder) -> path``.

Used by tests/test_hostile_files.py and benchmarks/bench_hostile.py. Every builder writes a capture
that is valid except for one thing. :func:`overdriven`, :func:`interfered`, :func:`leaking`, :func:`rippled` and
:func:`alternated` copy a capture with a receiver impairment of real recordings (tests/test_saturation.py,
benchmarks/bench_impairments.py).
"""

import json
import os

import h5py
import numpy as np
from scipy import signal

ATTRS = {"fStrt": 76e9, "fStop": 76.04e9, "TRampUp": 51.2e-6, "Tp": 64e-6, "fs": 5e6, "N": 256, "NrChn": 1,
         "FuSca": 1e-4}
N_CHIRPS = 128


def noise_counts(n_chirps=N_CHIRPS, n_samples=256, seed=0):
    return np.random.default_rng(seed).integers(-300, 300, size=(n_chirps, n_samples), dtype=np.int16)


def write(path, *, attrs=None, data=None, extra=None):
    """A capture with root ``attrs`` (ATTRS updated), ``/Chn1`` = ``data`` (noise by default), then ``extra(h5)``."""
    with h5py.File(path, "w") as h5:
        for key, value in {**ATTRS, **(attrs or {})}.items():
            h5.attrs[key] = value
        if data is not False:
            h5.create_dataset("Chn1", data=noise_counts() if data is None else data)
        if extra is not None:
            extra(h5)
    return path


def _valid_other(folder):
    return write(folder / "other.h5")


def external_link(folder):
    other = _valid_other(folder)
    return write(folder / "extlink.h5", data=False,
                 extra=lambda h5: h5.__setitem__("Chn1", h5py.ExternalLink(str(other), "/Chn1")))


def soft_link_dangling(folder):
    return write(folder / "dangling.h5", data=False,
                 extra=lambda h5: h5.__setitem__("Chn1", h5py.SoftLink("/nowhere")))


def soft_link_out(folder):
    other = _valid_other(folder)

    def extra(h5):
        h5["ext"] = h5py.ExternalLink(str(other), "/")
        h5["Chn1"] = h5py.SoftLink("/ext/Chn1")
    return write(folder / "softout.h5", data=False, extra=extra)


def virtual_missing_source(folder):
    def extra(h5):
        layout = h5py.VirtualLayout(shape=(N_CHIRPS, 256), dtype=np.int16)
        layout[:] = h5py.VirtualSource(str(folder / "missing.h5"), "Chn1", shape=(N_CHIRPS, 256))
        h5.create_virtual_dataset("Chn1", layout, fillvalue=0)
    return write(folder / "vds.h5", data=False, extra=extra)


def _external_raw(folder, name, target, n_chirps=N_CHIRPS):
    return write(folder / name, data=False, extra=lambda h5: h5.create_dataset(
        "Chn1", shape=(n_chirps, 256), dtype=np.int16, external=[(str(target), 0, n_chirps * 256 * 2)]))


def external_raw_passwd(folder):
    return _external_raw(folder, "passwd.h5", "/etc/passwd")


def external_raw_fifo(folder):
    fifo = folder / "pipe"
    os.mkfifo(fifo)
    return _external_raw(folder, "fifo.h5", fifo)


def external_raw_short(folder):
    raw = folder / "short.raw"
    raw.write_bytes(noise_counts(8).tobytes())  # 8 of the 128 chirps declared
    return _external_raw(folder, "extshort.h5", raw)


def huge_declared_contiguous(folder):
    """2 KB on disk, (1e9, 2048) int16 declared (4 TB), nothing stored."""
    return write(folder / "huge.h5", attrs={"N": 2048, "fs": 40e6}, data=False,
                 extra=lambda h5: h5.create_dataset("Chn1", shape=(10**9, 2048), dtype=np.int16))


def huge_declared_chunked(folder):
    return write(folder / "hugechunked.h5", attrs={"N": 2048, "fs": 40e6}, data=False,
                 extra=lambda h5: h5.create_dataset("Chn1", shape=(10**9, 2048), dtype=np.int16, chunks=(64, 2048)))


def sparse_chunks(folder):
    """Chunked by 16 rows, only the first chunk written: the rest would read as fill values."""
    def extra(h5):
        ds = h5.create_dataset("Chn1", shape=(N_CHIRPS, 256), dtype=np.int16, chunks=(16, 256))
        ds[:16] = noise_counts(16)
    return write(folder / "sparse.h5", data=False, extra=extra)


def compressed_huge_chunk(folder):
    """128 chirps in one gzip chunk declared (140 000, 256): 72 MB decoded from a few KB."""
    return write(folder / "bomb.h5", data=False, extra=lambda h5: h5.create_dataset(
        "Chn1", data=noise_counts(), chunks=(140_000, 256), maxshape=(None, 256), compression="gzip"))


def _attrs(name, **values):
    return lambda folder: write(folder / f"{name}.h5", attrs=values)


fstop_inf = _attrs("fstopinf", fStop=np.inf)
fs_absurd = _attrs("fs1e15", fs=1e15)
fusca_absurd = _attrs("fusca", FuSca=1e300)
tp_absurd = _attrs("tp", Tp=1.8e19)


def n_two_data(folder):
    return write(folder / "n2.h5", attrs={"N": 2}, data=noise_counts(n_samples=2))


def float_overflowing(folder):
    """float32 samples, one of them 3e38: its square would overflow any arithmetic on it."""
    data = noise_counts().astype(np.float32)
    data[3, 3] = 3e38
    return write(folder / "overflow.h5", data=data)


def rxposn_empty(folder):
    return write(folder / "rxempty.h5", extra=lambda h5: h5.create_dataset("RxPosn", data=h5py.Empty("f8")))


def tp_long_double(folder):
    """Tp stored as a long double (float128), which numpy does not turn into a Python float by itself."""
    return write(folder / "longdouble.h5", attrs={"Tp": np.longdouble(64e-6)})


def big_endian(folder):
    return write(folder / "bigendian.h5", data=noise_counts().astype(">i2"))


def chn1_group(folder):
    return write(folder / "chngroup.h5", data=False, extra=lambda h5: h5.create_group("Chn1"))


def rxposn_group(folder):
    return write(folder / "rxgroup.h5", extra=lambda h5: h5.create_group("RxPosn"))


def rxposn_strings(folder):
    return write(folder / "rxstr.h5", extra=lambda h5: h5.create_dataset("RxPosn", data=np.array([b"a", b"b"])))


def rxposn_wrong_length(folder):
    return write(folder / "rxlen.h5", extra=lambda h5: h5.create_dataset("RxPosn", data=np.zeros(5)))


def _truth(name, expected_json):
    def extra(h5):
        h5.create_group("Truth").attrs["expected_json"] = expected_json
    return lambda folder: write(folder / f"{name}.h5", extra=extra)


truth_invalid = _truth("truthbad", "{not json")
truth_deep = _truth("truthdeep", "[" * 200_000 + "]" * 200_000)
truth_wrong_type = _truth("truthtype", json.dumps([1, 2, 3]))


def truth_dataset(folder):
    return write(folder / "truthds.h5", extra=lambda h5: h5.create_dataset("Truth", data=np.arange(3)))


def _constant(name, value):
    return lambda folder: write(folder / f"{name}.h5", data=np.full((N_CHIRPS, 256), value, dtype=np.int16))


constant_zero = _constant("zeros", 0)
constant_full_scale = _constant("fullscale", 32767)
constant_value = _constant("seven", 7)


def fill_value_only(folder):
    """Contiguous, allocated early, never written: every sample is the fill value 7."""
    def extra(h5):
        dcpl = h5py.h5p.create(h5py.h5p.DATASET_CREATE)
        dcpl.set_alloc_time(h5py.h5d.ALLOC_TIME_EARLY)
        dcpl.set_fill_value(np.array(7, dtype=np.int16))
        h5py.h5d.create(h5.id, b"Chn1", h5py.h5t.STD_I16LE, h5py.h5s.create_simple((N_CHIRPS, 256)), dcpl=dcpl)
    return write(folder / "fill.h5", data=False, extra=extra)


def path_is_fifo(folder):
    path = folder / "capture_fifo.h5"
    os.mkfifo(path)
    return path


def big_layout(name, *, n_samples, n_channels, n_chirps, fs_hz):
    """A plausible capture of a large layout (noise samples), in ``/Data`` (n_chirps, NrChn, N)."""
    def build(folder):
        rng = np.random.default_rng(1)
        data = rng.integers(-300, 300, size=(n_chirps, n_channels, n_samples), dtype=np.int16)
        return write(folder / f"{name}.h5", attrs={"N": n_samples, "NrChn": n_channels, "fs": fs_hz,
                                                   "fStop": 77e9}, data=False,
                     extra=lambda h5: h5.create_dataset("Data", data=data, chunks=(16, n_channels, n_samples)))
    return build


# N = 4096 at 80 MHz in 51.2 us over 1 GHz: 0.15 m bins, a 200 m gate holds 1333 bins (21 000 with --zero-pad 16)
n4096 = big_layout("n4096", n_samples=4096, n_channels=1, n_chirps=2048, fs_hz=80e6)
n32768 = big_layout("n32768", n_samples=32768, n_channels=1, n_chirps=128, fs_hz=640e6)
ch2048 = big_layout("ch2048", n_samples=256, n_channels=2048, n_chirps=64, fs_hz=5e6)
ch64 = big_layout("ch64", n_samples=2048, n_channels=64, n_chirps=256, fs_hz=40e6)


def _rewritten(path, out, change, *, gain=1.0):
    """``path`` copied to ``out`` with every sample dataset's counts passed through ``change(counts, attrs)`` (float
    counts, a dataset's (chirps, samples)) and clipped to int16 as an ADC does; FuSca divided by ``gain``."""
    with h5py.File(path, "r") as src, h5py.File(out, "w") as dst:
        for key, value in src.attrs.items():
            dst.attrs[key] = value
        dst.attrs["FuSca"] = src.attrs.get("FuSca", 1.0) / gain
        for name in src:
            if name.startswith("Chn"):
                counts = np.clip(np.round(change(src[name][...].astype(np.float64), src.attrs)), -32768, 32767)
                dst.create_dataset(name, data=counts.astype(np.int16))
            else:
                src.copy(name, dst)
    return out


def overdriven(path, out, share):
    """``path`` copied to ``out`` with its int16 samples scaled (the receiver gain raised) until a share ``share`` of
    them sits at the full scale, clipped there as an ADC does; FuSca scaled back (the volts unchanged)."""
    with h5py.File(path, "r") as src:
        magnitude = np.concatenate([np.abs(src[name][...].astype(np.int32)).ravel() for name in src
                                    if name.startswith("Chn")])
    gain = 32767 / max(float(np.quantile(magnitude, 1.0 - share)), 1.0)
    return _rewritten(path, out, lambda counts, attrs: counts * gain, gain=gain)


def interfered(path, out, period_chirps, *, burst_samples=6, amplitude=13000.0, seed=0):
    """``path`` with another FMCW radar's chirps crossing ours (the receiver gain 6 dB lower to make room): its k-th
    chirp crosses ours at ``k * period_chirps`` chirp periods (no whole number: the two radars repeat at rates apart),
    at that fraction of our chirp. The beat of the two sweeps passes through 0 Hz at the crossing, its frequency
    changing at the difference of their slopes; the receiver's anti-alias filter passes it from the Nyquist frequency
    down to 0 and back up: a burst of ``burst_samples`` samples (the filter's band over the slopes' difference) centred
    on the crossing, ``amplitude`` counts, its envelope flat but for the filter's roll-off over the outer 20 % (a
    Tukey taper), its spectrum flat over the IF band. A crossing near either end of our ramp leaves part of a burst."""
    rng = np.random.default_rng(seed)

    def change(counts, attrs):
        counts = 0.5 * counts
        n_chirps, n_samples = counts.shape
        n = np.arange(n_samples)
        for crossing in np.arange(period_chirps, n_chirps, period_chirps):
            chirp, centre = int(crossing), (crossing % 1) * n_samples
            u = (n - centre) / burst_samples + 0.5  # 0 .. 1 across the burst
            inside = (u >= 0) & (u <= 1)
            edge = np.minimum(u, 1 - u)[inside]
            envelope = np.where(edge < 0.1, 0.5 * (1 - np.cos(np.pi * edge / 0.1)), 1.0)
            counts[chirp, inside] += amplitude * envelope * np.cos(
                np.pi * (n[inside] - centre) ** 2 / burst_samples + rng.uniform(0, 2 * np.pi))
        return counts
    return _rewritten(path, out, change, gain=0.5)


def leaking(path, out, *, beat_share=0.02, amplitude=13000.0, drift=0.01, dc=300.0):
    """``path`` with TX-RX leakage (the receiver gain 6 dB lower to make room): a beat at ``beat_share`` of the sample
    rate (a range of some tens of cm), ``amplitude`` counts, its amplitude drifting by ``drift`` at 0.7 Hz and its
    phase by 0.05 rad at 0.4 Hz (the radar warming), and a DC offset of ``dc`` counts."""
    def change(counts, attrs):
        n_chirps, n_samples = counts.shape
        t_s = np.arange(n_chirps)[:, None] * float(attrs["Tp"])
        sample_s = np.arange(n_samples)[None, :] / float(attrs["fs"])
        beat = np.cos(2 * np.pi * beat_share * float(attrs["fs"]) * sample_s + 0.05 * np.sin(2 * np.pi * 0.4 * t_s))
        return 0.5 * counts + amplitude * (1 + drift * np.sin(2 * np.pi * 0.7 * t_s)) * beat + dc
    return _rewritten(path, out, change, gain=0.5)


def alternated(path, out, phase_deg=120.0, gain=0.8):
    """``path`` as a MIMO radar's capture would be whose second transmitter sends every other chirp: the odd chirps'
    echoes turned by its feed's ``phase_deg`` and scaled by ``gain`` (each chirp's analytic signal turned; the same
    for every echo, as for one on boresight), the whole 2 dB lower to make room."""
    turn = gain * np.exp(1j * np.deg2rad(phase_deg))

    def change(counts, attrs):
        counts = 0.8 * counts
        counts[1::2] = np.real(signal.hilbert(counts[1::2], axis=1) * turn)
        return counts
    return _rewritten(path, out, change, gain=0.8)


RIPPLE_ORDERS = ((1, 0.5, 0.3), (2, 1.0, 0.0), (3, 0.3, 2.0), (4, 0.5, 1.0))  # (harmonic of 50 Hz, weight, phase rad)


def rippled(path, out, depth, *, mains_hz=50.0):
    """``path`` with the receiver's gain rippling by ``depth`` (its largest harmonic's share) at the supply's
    ``mains_hz`` and harmonics (a rectifier's 2nd strongest), the gain ``1 / (1 + 1.6 depth)`` lower to make room:
    each strong static echo then carries the ripple's Doppler lines about 0 Hz."""
    gain = 1.0 / (1.0 + 1.6 * depth)

    def change(counts, attrs):
        t_s = np.arange(counts.shape[0])[:, None] * float(attrs["Tp"])
        ripple = sum(w * np.cos(2 * np.pi * k * mains_hz * t_s + phase) for k, w, phase in RIPPLE_ORDERS)
        return gain * counts * (1 + depth * ripple)
    return _rewritten(path, out, change, gain=gain)

