"""I/Q recordings of continuous-wave (CW) radars: complex baseband slow time, one I/Q pair per RX, no range.

A CW radar mixes its echo down with the carrier it sends; each I/Q sample is the sum over scatterers of
``a exp(-j 4 pi R(t) / lambda)`` (a receding scatterer turns the phase negative: negative Doppler), the slow
time an FMCW capture yields per range bin, here over every range at once. Two layouts are read
(``docs/IQ_FORMAT.md``):

* WAV (``*.wav``), the way sound-card and SDR front ends record: 2 C channels, I then Q of each RX, PCM
  (8/16/24/32-bit) or float; the sample rate from the header, the carrier from ``--carrier-hz`` (a WAV has
  no field for it).
* HDF5 with a dataset ``/IQ``: complex (n,) or (n, C), or real (n, 2) or (n, C, 2) with I and Q on the last
  axis; root attributes ``fc`` (carrier, Hz) and ``fs`` (I/Q sample rate, Hz), optional ``FuSca`` (V per
  count). The same refusals as a Radarlog capture: links, virtual or external storage, declared shapes the
  bytes cannot hold.

Samples are returned as complex64 volts, shape (n, C).
"""

import io
import os
import warnings as _warnings
from dataclasses import dataclass

import h5py
import numpy as np

from mdpipe.errors import CaptureFormatError, ParameterError
from mdpipe.io.files import check_regular_file
from mdpipe.io.radarlog import _check_storage, _locate, _scalar, check_float_samples
from mdpipe.params import IQ_LIMITS, IqParams

WAV_SUFFIXES = (".wav",)
HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"
WAV_HEADER_BYTES = 65536  # the fmt chunk is searched for within this much of a WAV's start
IQ_DATASET = "IQ"
# override name -> (IqParams field, meaning, example): the options that supply or replace a recording's values
IQ_OVERRIDES = {
    "carrier_hz": ("carrier_hz", "carrier frequency (Hz)", "--carrier-hz 24.125e9"),
    "fs": ("sample_rate_hz", "I/Q sample rate (Hz)", "--fs 48000"),
}
HDF5_ATTRIBUTES = {"fc": "carrier_hz", "fs": "sample_rate_hz"}
INTEGER_KINDS = "iu"
PROBE_FILE_BYTES = 2**31  # a WAV that cannot be mapped, read whole to be described (``mdpipe info``)
CLIPPED_COUNTS = 256  # within this of an integer type's extremes counts as full scale (24-bit PCM fills int32's top)


def _hdf5_signature(path):
    """Whether ``path`` starts with the HDF5 signature at 0 or after a user block (512, 1024, ... bytes: MATLAB's
    v7.3 files hold one)."""
    try:
        with open(path, "rb") as handle:
            offset = 0
            while True:
                handle.seek(offset)
                head = handle.read(len(HDF5_SIGNATURE))
                if head == HDF5_SIGNATURE:
                    return True
                if len(head) < len(HDF5_SIGNATURE):
                    return False
                offset = 512 if offset == 0 else 2 * offset
    except OSError:
        return False


def is_iq_recording(path):
    """Whether ``path`` names an I/Q recording: a ``*.wav`` file, or an HDF5 file whose root holds ``/IQ`` and
    no Radarlog sample dataset (``/Data`` or any ``/ChnK``: a capture missing ``/Chn1`` is the Radarlog reader's to
    refuse). Anything that cannot be told (a missing file, a FIFO) is left to the Radarlog reader, whose errors name
    it."""
    if str(path).lower().endswith(WAV_SUFFIXES):
        return True
    try:
        check_regular_file(path)
    except CaptureFormatError:
        return False
    if not _hdf5_signature(path):
        return False
    try:
        with h5py.File(path, "r") as h5:
            names = set(h5.keys())
    except Exception:  # an unreadable HDF5 file: the Radarlog reader says why
        return False
    return IQ_DATASET in names and "Data" not in names and not any(n.startswith("Chn") for n in names)


@dataclass(frozen=True)
class IqLayout:
    """What was found: the container, the samples' type and shape, and how channels were laid out."""

    container: str
    sample_dtype: str
    shape: tuple
    arrangement: str

    def describe(self):
        return f"I/Q {self.container}, {self.sample_dtype} {self.shape} ({self.arrangement})"


@dataclass(frozen=True)
class IqRecording:
    """An I/Q recording read whole: ``samples`` (n, C) complex64 volts, its :class:`~mdpipe.params.IqParams`,
    the layout, the share of integer samples at full scale (None for float samples) and warnings."""

    path: str
    params: IqParams
    samples: np.ndarray
    layout: IqLayout
    clipped_fraction: object
    warnings: tuple

    @property
    def n_samples(self):
        return self.samples.shape[0]


def _parameters(found, overrides, path, *, how_to):
    """IqParams from the values ``found`` in the file (field -> value) and the ``overrides`` (option name ->
    value), each override replacing the file's; a missing value names the option that supplies it."""
    values = dict(found)
    for name, value in overrides.items():
        if name not in IQ_OVERRIDES:
            raise ParameterError(f"{path}: an I/Q (CW) recording has no {name!r} attribute to replace: the option "
                                 f"--{name.lower()} applies to Radarlog captures; give --carrier-hz and --fs only")
        values[IQ_OVERRIDES[name][0]] = value
    for name, (field, meaning, example) in IQ_OVERRIDES.items():
        if field not in values:
            raise CaptureFormatError(f"{path}: the {meaning} is not in the file ({how_to}); supply it with {example}")
    try:
        return IqParams(**values)
    except ParameterError as exc:
        raise ParameterError(f"{path}: {exc}") from None


def _complex(data, arrangement_axis_last):
    """Complex64 (n, C) from a real (n, 2C) array of I, Q columns (WAV) or a real (..., 2) array (HDF5)."""
    data = np.asarray(data)
    if arrangement_axis_last:
        i, q = data[..., 0], data[..., 1]
    else:
        i, q = data[:, 0::2], data[:, 1::2]
    out = np.empty(i.shape, dtype=np.complex64)
    out.real, out.imag = i, q
    return out.reshape(out.shape[0], -1)


def _full_scale_share(data):
    """Share of integer samples at their type's extremes (clipped): for 32-bit samples within ``CLIPPED_COUNTS`` of
    them, as 24-bit PCM fills the top three bytes; None for float samples."""
    if data.dtype.kind not in INTEGER_KINDS:
        return None
    info = np.iinfo(data.dtype)
    margin = CLIPPED_COUNTS - 1 if data.dtype.itemsize >= 4 else 0
    return float(np.count_nonzero((data >= info.max - margin) | (data <= info.min + margin)) / max(data.size, 1))


def _check_wav_format(path):
    """Refuse a WAV whose ``fmt `` chunk declares no channel, or a frame size (block align) that is not its channels
    times its sample bytes (scipy would read a 16-bit stereo file declaring 3 bytes a frame as 8-bit samples)."""
    with open(path, "rb") as handle:
        head = handle.read(WAV_HEADER_BYTES)
    if len(head) < 12 or head[:4] not in (b"RIFF", b"RIFX") or head[8:12] != b"WAVE":
        return  # not RIFF/WAVE: scipy's reader says so
    order = "little" if head[:4] == b"RIFF" else "big"

    def number(start, stop):
        return int.from_bytes(head[start:stop], order)

    offset = 12
    while offset + 8 <= len(head):
        size = number(offset + 4, offset + 8)
        if head[offset:offset + 4] == b"fmt " and offset + 24 <= len(head):
            channels, block_align, bits = number(offset + 10, offset + 12), number(offset + 20, offset + 22), \
                number(offset + 22, offset + 24)
            if channels == 0:
                raise CaptureFormatError(f"{path}: the WAV header declares 0 audio channels; an I/Q recording holds "
                                         "an even number, I then Q of each RX")
            if bits and block_align != channels * -(-bits // 8):
                raise CaptureFormatError(f"{path}: the WAV header declares {block_align} bytes a frame for {channels} "
                                         f"channel(s) of {bits}-bit samples ({channels * -(-bits // 8)}); the header "
                                         "is damaged or forged")
            return
        offset += 8 + size + (size & 1)


def _read_wav(path, overrides, check, max_file_bytes):
    from scipy.io import wavfile

    _check_wav_format(path)
    size = os.path.getsize(path)
    with _warnings.catch_warnings(record=True) as caught:
        _warnings.simplefilter("always")  # unknown chunks are read past, as players do; a short file is refused below
        try:
            try:
                rate, data = wavfile.read(path, mmap=True)  # mapped: nothing allocated that the file does not hold
            except ValueError as exc:
                if "greater than file size" in str(exc):
                    raise CaptureFormatError(f"{path}: the WAV header declares more samples than the file holds; "
                                             "the file is truncated or forged") from None
                if "container" not in str(exc):
                    raise
                if size > max_file_bytes:  # 3-byte samples cannot be mapped: read whole, bounded by the file's size
                    raise CaptureFormatError(f"{path}: a {size:,}-byte WAV of samples that cannot be mapped (3 bytes "
                                             f"each) is read whole, over the {max_file_bytes:,} bytes allowed; raise "
                                             "--max-memory-gb") from None
                with open(path, "rb") as handle:
                    rate, data = wavfile.read(io.BytesIO(handle.read()))
                data = np.asarray(data)  # (read whole: counted below as stored bytes)
        except CaptureFormatError:
            raise
        except Exception as exc:  # a header scipy cannot parse
            raise CaptureFormatError(f"{path}: not a readable WAV file ({' '.join(str(exc).split())})") from None
    if any("EOF prematurely" in str(warning.message) for warning in caught):
        raise CaptureFormatError(f"{path}: the WAV header declares more samples than the file holds; the file is "
                                 "truncated or forged")
    if data.ndim != 2 or data.shape[1] % 2:
        channels = 1 if data.ndim == 1 else data.shape[1]
        raise CaptureFormatError(f"{path}: {channels} audio channel(s); an I/Q recording holds an even number, I "
                                 "then Q of each RX (a mono file has no Q: the sign of Doppler is lost)")
    if data.shape[1] // 2 > IQ_LIMITS["n_channels"][1]:
        raise CaptureFormatError(f"{path}: {data.shape[1] // 2} I/Q pairs; at most {IQ_LIMITS['n_channels'][1]} "
                                 "are read")
    params = _parameters({"sample_rate_hz": float(rate), "n_channels": data.shape[1] // 2}, overrides, path,
                         how_to="a WAV header holds the sample rate only")
    if data.shape[0] == 0:
        raise CaptureFormatError(f"{path}: the WAV holds no samples")
    if check is not None:
        check(data.shape[0], params, 0 if isinstance(data, np.memmap) else 2 * data.dtype.itemsize)  # before
        # the mapped samples are read; samples read whole are held beside their conversion
    layout = IqLayout("WAV", str(data.dtype), tuple(data.shape), f"{params.n_channels} RX, I then Q of each")
    return params, data, False, layout


def _read_hdf5(path, overrides, allow_external, check, read=True):
    with h5py.File(path, "r") as h5:
        found = {}
        for name, field in HDF5_ATTRIBUTES.items():
            if name in h5.attrs:
                found[field] = _scalar(h5.attrs[name], name, path)
        if "FuSca" in h5.attrs:
            found["full_scale_v_per_lsb"] = _scalar(h5.attrs["FuSca"], "FuSca", path)
        ds = _locate(h5, f"/{IQ_DATASET}", path, allow_external=allow_external)
        if not isinstance(ds, h5py.Dataset):
            raise CaptureFormatError(f"{path}: '/{IQ_DATASET}' is a group; expected a dataset of I/Q samples")
        kind = ds.dtype.kind
        if kind == "c":
            if ds.ndim not in (1, 2):
                raise CaptureFormatError(f"{path}: complex '/{IQ_DATASET}' has shape {ds.shape}; expected (n,) or "
                                         "(n, C)")
            channels = 1 if ds.ndim == 1 else ds.shape[1]
        elif kind in INTEGER_KINDS + "f" and ds.dtype.itemsize <= 8:
            if ds.ndim not in (2, 3) or ds.shape[-1] != 2:
                raise CaptureFormatError(f"{path}: real '/{IQ_DATASET}' has shape {ds.shape}; expected (n, 2) or "
                                         "(n, C, 2), I and Q on the last axis")
            channels = 1 if ds.ndim == 2 else ds.shape[1]
        else:
            raise CaptureFormatError(f"{path}: '/{IQ_DATASET}' holds {ds.dtype}; expected complex, integer or float "
                                     "samples")
        if not 1 <= channels <= IQ_LIMITS["n_channels"][1]:
            raise CaptureFormatError(f"{path}: '/{IQ_DATASET}' holds {channels} channels; 1 to "
                                     f"{IQ_LIMITS['n_channels'][1]} are read")
        if ds.shape[0] == 0:
            raise CaptureFormatError(f"{path}: '/{IQ_DATASET}' holds no samples")
        _check_storage(ds, IQ_DATASET, path, allow_external=allow_external)
        params = _parameters({**found, "n_channels": channels}, overrides, path,
                             how_to=f"root attributes {', '.join(HDF5_ATTRIBUTES)}")
        arrangement = f"{channels} RX" + ("" if kind == "c" else ", I and Q on the last axis")
        layout = IqLayout("HDF5 /IQ", str(ds.dtype), tuple(ds.shape), arrangement)
        if check is not None:
            check(ds.shape[0], params, ds.dtype.itemsize * (1 if kind == "c" else 2))
        data = ds[()] if read else ds.shape
    return params, data, (None if kind == "c" else True), layout


def _open(path, overrides, allow_external, check, max_file_bytes, read=True):
    path = os.fspath(path)
    check_regular_file(path)
    overrides = dict(overrides or {})
    if path.lower().endswith(WAV_SUFFIXES):
        return path, _read_wav(path, overrides, check, max_file_bytes)
    try:
        return path, _read_hdf5(path, overrides, allow_external, check, read)
    except (CaptureFormatError, ParameterError):
        raise
    except (KeyError, OSError, RuntimeError, TypeError) as exc:  # h5py's errors for a damaged structure
        raise CaptureFormatError(f"{path}: cannot be read as an HDF5 I/Q recording ({' '.join(str(exc).split())})") \
            from None


def probe_iq(path, *, overrides=None, allow_external=False):
    """An I/Q recording's :class:`~mdpipe.params.IqParams`, its samples per channel and its :class:`IqLayout`, the
    samples not read (``mdpipe info``)."""
    _, (params, data, _, layout) = _open(path, overrides, allow_external, None, PROBE_FILE_BYTES, read=False)
    return params, data.shape[0] if hasattr(data, "ndim") else data[0], layout


def read_iq(path, *, overrides=None, allow_external=False, check=None, max_file_bytes=2**31):
    """Read an I/Q recording whole; returns an :class:`IqRecording`.

    ``check(n_samples, params, stored_bytes_per_sample)``, when given, is called once the recording's size and
    parameters are known and before its samples are read (bytes per sample and channel held as read: 0 for a mapped
    WAV) (a memory plan that refuses what it cannot hold); ``max_file_bytes`` bounds a WAV
    that cannot be mapped and is read whole. Raises :class:`CaptureFormatError` (or :class:`ParameterError` for a
    value out of range) with one line naming the problem and the fix.
    """
    path, (params, data, axis_last, layout) = _open(path, overrides, allow_external, check, max_file_bytes)
    clipped = _full_scale_share(data)
    if np.asarray(data).dtype.kind in "fc":  # before the cast to complex64, which they could overflow
        check_float_samples(np.asarray(data), f"{path}: its I/Q data", "recording")
    if axis_last is None:
        samples = np.asarray(data, dtype=np.complex64).reshape(data.shape[0], -1)
    else:
        samples = _complex(data, axis_last)
    del data  # a WAV's map closes with its last reference
    samples *= np.float32(params.full_scale_v_per_lsb)
    notes = []
    if clipped:
        notes.append(f"{clipped:.2%} of the samples sit at full scale (clipped): amplitudes and spectra are distorted")
    return IqRecording(path, params, samples, layout, clipped, tuple(notes))
