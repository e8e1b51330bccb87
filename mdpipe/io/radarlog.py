"""The Radarlog HDF5 layout (canonical, as written by ``mdpipe simulate``) and the variants read.

Canonical: SI scalar root attributes ``fStrt fStop TRampUp TRampDo Tp fs N NrChn FuSca Creator``,
int16 datasets ``/Chn1 ... /Chn{NrChn}`` of shape (n_chirps, N) chunked by rows, optional
``/RxPosn`` (NrChn,), an optional ``TxSeq`` root attribute (the transmitter of each chirp, in turn: a MIMO
radar's time-division cycle) and, for simulated files, ``/Truth`` with attributes ``scene_yaml`` and
``expected_json``.

Variants read: ``Cfg_``-prefixed attribute names; one dataset ``/Data`` of shape
(n_chirps, NrChn, N); a frame counter in sample 0 of every chirp (detected or forced; the column
is dropped and N becomes N - 1); float32/float64 samples.

Chunks read from a capture are float32 volts (samples times FuSca), shape (chirps, channels,
samples).
"""

import json
import math
import os
import re
import threading
from dataclasses import dataclass

import h5py
import numpy as np

from mdpipe.errors import CaptureFormatError, ParameterError, PlatformError
from mdpipe.outputs import publish
from mdpipe.io.files import check_regular_file
from mdpipe.params import MAX_TX_SEQUENCE, RADAR_LIMITS, RadarParams

# attribute name -> (RadarParams field, meaning with unit, example CLI override)
ATTRIBUTES = {
    "fStrt": ("f_start_hz", "chirp start frequency, Hz", "--fstrt 76e9"),
    "fStop": ("f_stop_hz", "chirp stop frequency, Hz", "--fstop 76.04e9"),
    "TRampUp": ("ramp_up_s", "up-ramp duration, s", "--trampup 51.2e-6"),
    "Tp": ("chirp_period_s", "chirp repetition interval, s", "--tp 64e-6"),
    "fs": ("sample_rate_hz", "ADC sample rate, Hz", "--fs 40e6"),
    "N": ("n_samples", "samples per chirp", "--n 2048"),
    "NrChn": ("n_channels", "number of RX channels", "--nrchn 16"),
}
OPTIONAL_ATTRIBUTES = {"TRampDo": ("ramp_down_s", 0.0), "FuSca": ("full_scale_v_per_lsb", 1.0)}
SAMPLE_DTYPES = (np.int16, np.float32, np.float64)
INT16_FULL_SCALE = 32767  # int16 samples span -32768 .. 32767 counts
DETECTION_CHIRPS = 256
DEFAULT_CHUNK_CHIRPS = 256
MAX_TEXT_CHARS = 1 << 20  # /Truth attributes (no larger than the file: attributes are not compressed)
MAX_JSON_DEPTH = 32
MAX_LINK_HOPS = 16
MAX_SAMPLE_MAGNITUDE = 1e12  # float samples beyond any ADC's counts or volts: their squares would overflow float32
MAX_FILTERED_CHUNK_BYTES = 64 << 20  # a compressed chunk is decoded whole: a small file could ask for 4 GB
ALLOW_EXTERNAL = "pass --allow-external for a trusted file"


@dataclass(frozen=True)
class Layout:
    """What the reader found in a file."""

    attribute_prefix: str
    sample_datasets: str
    sample_dtype: str
    frame_counter: bool

    def describe(self):
        kind = "canonical" if (self.attribute_prefix, self.sample_datasets, self.sample_dtype,
                               self.frame_counter) == ("", "per-channel", "int16", False) else "variant"
        parts = [f"attributes {'Cfg_' if self.attribute_prefix else 'plain'}",
                 "/Chn1../ChnK datasets" if self.sample_datasets == "per-channel" else "one 3-D /Data dataset",
                 f"{self.sample_dtype} samples",
                 "frame counter in sample 0 (dropped)" if self.frame_counter else "no frame counter"]
        return f"{kind}: " + ", ".join(parts)


def _scalar(value, name, path):
    array = np.asarray(value)
    if array.size != 1 or array.dtype.kind not in "iuf":
        raise CaptureFormatError(f"{path}: attribute {name!r} must be one number, got {value!r}")
    number = array.reshape(()).item()  # a long double stays numpy's: made a Python float
    return number if isinstance(number, (int, float)) else float(number)


def _read_attributes(attrs, path, overrides):
    prefix = "Cfg_" if any(f"Cfg_{k}" in attrs for k in ATTRIBUTES) and not any(k in attrs for k in ATTRIBUTES) else ""
    values = {}
    for name, (field_name, meaning, example) in ATTRIBUTES.items():
        if name in overrides:
            values[field_name] = overrides[name]
        elif prefix + name in attrs:
            values[field_name] = _scalar(attrs[prefix + name], prefix + name, path)
        else:
            raise CaptureFormatError(
                f"{path}: attribute {prefix + name!r} ({meaning}) is missing; supply it with {example}")
    for name, (field_name, default) in OPTIONAL_ATTRIBUTES.items():
        key = prefix + name
        values[field_name] = _scalar(attrs[key], key, path) if key in attrs else default
    return prefix, values


def check_float_samples(samples, where, what="capture"):
    """Raise :class:`CaptureFormatError` for float (or complex) ``samples`` that are NaN, infinite, or beyond
    ``MAX_SAMPLE_MAGNITUDE`` (read before any arithmetic, which they would overflow); ``where`` names them, ``what``
    the file."""
    largest = float(np.max(np.abs(samples), initial=0.0))  # NaN if any is
    if not math.isfinite(largest):
        raise CaptureFormatError(f"{where} hold NaN or Inf samples; the {what} is corrupt")
    if largest > MAX_SAMPLE_MAGNITUDE:
        raise CaptureFormatError(f"{where} hold a sample of magnitude {largest:.3g}, beyond any ADC's counts or "
                                 f"volts ({MAX_SAMPLE_MAGNITUDE:.0e}); the {what} is corrupt")


def _locate(h5, name, path, *, allow_external, shown=None, hops=0):
    """The object at absolute ``name``, its links followed without leaving the file.

    External links (anywhere on the way) are refused unless ``allow_external``; a soft link that
    dangles or loops is an error. Nothing outside the file is opened before it is allowed.
    """
    shown = shown or name
    parts = [part for part in name.split("/") if part]
    obj = h5["/"]
    for index, part in enumerate(parts):
        where = "/" + "/".join(parts[:index + 1])
        if not isinstance(obj, h5py.Group):
            raise CaptureFormatError(f"{path}: '{shown}' leads through '{obj.name}', which is not a group")
        group = obj
        link = group.get(part, getlink=True)
        if link is None:
            raise CaptureFormatError(f"{path}: '{shown}' leads to '{where}', which does not exist (a dangling link)")
        if isinstance(link, h5py.ExternalLink):
            if not allow_external:
                how = "is" if where == shown else f"is a soft link that leaves the file through '{where}',"
                raise CaptureFormatError(f"{path}: '{shown}' {how} an external link to {link.filename}:{link.path}; "
                                         f"refused: it reads another file ({ALLOW_EXTERNAL})")
            obj = group[part]
        elif isinstance(link, h5py.SoftLink):
            if hops >= MAX_LINK_HOPS:
                raise CaptureFormatError(f"{path}: '{shown}' is a chain of more than {MAX_LINK_HOPS} soft links")
            target = link.path if link.path.startswith("/") else f"{group.name.rstrip('/')}/{link.path}"
            obj = _locate(h5, target, path, allow_external=allow_external, shown=shown, hops=hops + 1)
        else:
            obj = group[part]
    return obj


def _filtered(ds):
    """True when ``ds`` is stored through filters (compression): its chunks are decoded whole."""
    return ds.chunks is not None and ds.id.get_create_plist().get_nfilters() > 0


def _check_storage(ds, name, path, *, allow_external):
    """Refuse data stored outside the file, and a declared shape the stored bytes cannot hold.

    A virtual dataset or external raw storage reads other files (a missing source reads as fill
    values, a FIFO hangs); missing chunks or a short contiguous block would read as invented fill.
    """
    if ds.shape is None:
        raise CaptureFormatError(f"{path}: '/{name}' holds no data (an empty dataspace)")
    declared = int(np.prod(ds.shape, dtype=object)) * ds.dtype.itemsize
    shape = f"{ds.shape} {ds.dtype} ({declared:,} bytes)"
    if ds.is_virtual:
        if not allow_external:
            sources = sorted({source.file_name for source in ds.virtual_sources()})
            raise CaptureFormatError(f"{path}: '/{name}' is a virtual dataset reading {', '.join(sources)}; "
                                     f"refused: it reads other files ({ALLOW_EXTERNAL})")
        return
    if ds.external:
        files = [os.fsdecode(entry[0]) for entry in ds.external]
        if not allow_external:
            raise CaptureFormatError(f"{path}: '/{name}' keeps its samples outside the file, in "
                                     f"{', '.join(files)} (external raw storage); refused ({ALLOW_EXTERNAL})")
        available = 0
        for file_name, offset, size in ds.external:  # relative names are found from the working folder, as HDF5 does
            external_path = os.path.abspath(os.fsdecode(file_name))
            check_regular_file(external_path)
            available += max(0, min(int(size), os.path.getsize(external_path) - int(offset)))
        if available < declared:
            raise CaptureFormatError(f"{path}: '/{name}' declares {shape} but its external files hold {available:,} "
                                     "bytes of it; the rest would read as invented zeros")
        return
    stored = ds.id.get_storage_size()
    if ds.chunks is not None:
        expected = int(np.prod([-(-n // c) for n, c in zip(ds.shape, ds.chunks)], dtype=object))
        allocated = ds.id.get_num_chunks()
        if allocated < expected:
            raise CaptureFormatError(
                f"{path}: '/{name}' declares {shape} in {expected:,} chunks but stores {allocated:,} "
                f"({stored:,} bytes); the missing chunks would read as invented fill values")
        if not _filtered(ds) and stored < declared:
            raise CaptureFormatError(f"{path}: '/{name}' declares {shape} but stores {stored:,} bytes")
        chunk_bytes = int(np.prod(ds.chunks, dtype=object)) * ds.dtype.itemsize
        if _filtered(ds) and chunk_bytes > MAX_FILTERED_CHUNK_BYTES:
            raise CaptureFormatError(
                f"{path}: '/{name}' is compressed in chunks of {ds.chunks} ({chunk_bytes:,} bytes), each decoded "
                f"whole; at most {MAX_FILTERED_CHUNK_BYTES:,} bytes a chunk are read")
        return
    offset = ds.id.get_offset()
    file_size = os.path.getsize(ds.file.filename)  # the file holding it: another one through an allowed link
    if stored < declared or (offset is not None and offset + declared > file_size):
        raise CaptureFormatError(
            f"{path}: '/{name}' declares {shape} but the file stores {min(stored, max(file_size - (offset or 0), 0)):,} "
            f"bytes of it; the file is truncated or forged")


def _sample_datasets(h5, path, *, allow_external):
    if h5.get("Data", getlink=True) is not None:
        data = _locate(h5, "/Data", path, allow_external=allow_external)
        if not isinstance(data, h5py.Dataset):
            raise CaptureFormatError(f"{path}: '/Data' is a group; expected a dataset (n_chirps, NrChn, N)")
        if data.ndim != 3:
            raise CaptureFormatError(f"{path}: dataset '/Data' has shape {data.shape}; expected (n_chirps, NrChn, N)")
        datasets, names = [data], ["Data"]
    else:
        names = sorted((k for k in h5 if k.startswith("Chn") and k[3:].isdigit()), key=lambda k: int(k[3:]))
        if not names:
            raise CaptureFormatError(f"{path}: no sample datasets (expected /Chn1 ... /Chn{{NrChn}} or one /Data); "
                                     "is this a Radarlog capture?")
        expected = [f"Chn{i + 1}" for i in range(len(names))]
        if names != expected:
            raise CaptureFormatError(f"{path}: channel datasets {names[:8]} are not numbered Chn1..Chn{len(names)}")
        if len(names) > RADAR_LIMITS["n_channels"][1]:
            raise CaptureFormatError(f"{path}: {len(names)} channel datasets; at most "
                                     f"{RADAR_LIMITS['n_channels'][1]} RX channels are read")
        datasets = [_locate(h5, f"/{n}", path, allow_external=allow_external) for n in names]
        for name, ds in zip(names, datasets):
            if not isinstance(ds, h5py.Dataset):
                raise CaptureFormatError(f"{path}: '/{name}' is a group; every /ChnK must be a dataset (n_chirps, N)")
            if ds.ndim != 2 or ds.shape != datasets[0].shape:
                raise CaptureFormatError(
                    f"{path}: dataset '/{name}' has shape {ds.shape}; every /ChnK must be (n_chirps, N) "
                    f"like /Chn1 {datasets[0].shape}")
    for name, ds in zip(names, datasets):
        if ds.dtype.newbyteorder("=") not in SAMPLE_DTYPES or ds.dtype != datasets[0].dtype:
            raise CaptureFormatError(
                f"{path}: samples are {ds.dtype}; Radarlog samples must be int16 (or float32/float64), "
                f"the same in every channel ('/{name}')")
        _check_storage(ds, name, path, allow_external=allow_external)
    return ("3-D" if names == ["Data"] else "per-channel"), datasets


def _name_attribute(exc):
    """A :class:`RadarParams` error with the file attribute and the CLI override of the field it names."""
    message = str(exc)
    for name, (field_name, _meaning, example) in ATTRIBUTES.items():
        if message.startswith(field_name + "="):
            return f"{message}; attribute {name!r}, or override with {example.split()[0]}"
    for name, (field_name, _default) in OPTIONAL_ATTRIBUTES.items():
        if message.startswith(field_name + "="):
            return f"{message}; attribute {name!r}"
    return message


def _text_attribute(attrs, name):
    """A string attribute of at most ``MAX_TEXT_CHARS``, or None when absent."""
    if name not in attrs:
        return None
    value = attrs[name]
    if isinstance(value, bytes):
        value = value.decode("utf-8")
    if not isinstance(value, str):
        raise TypeError(f"attribute {name} is not a string")
    if len(value) > MAX_TEXT_CHARS:
        raise ValueError(f"attribute {name} holds {len(value):,} characters (more than {MAX_TEXT_CHARS:,})")
    return value


def parse_json_bounded(text, *, max_depth=MAX_JSON_DEPTH):
    """``json.loads`` of trusted shape only: at most ``max_depth`` levels of nesting, no NaN or Infinity."""
    codes = np.frombuffer(re.sub(r'"(?:[^"\\]|\\.)*"', '""', text).encode(), dtype=np.uint8)  # strings out
    steps = np.isin(codes, list(b"[{")).astype(np.int64) - np.isin(codes, list(b"]}"))
    if len(steps) and np.cumsum(steps).max() > max_depth:
        raise ValueError(f"JSON nested deeper than {max_depth} levels")

    def refuse(constant):
        raise ValueError(f"JSON holds {constant}")
    try:
        return json.loads(text, parse_constant=refuse)
    except json.JSONDecodeError as exc:
        raise ValueError(f"invalid JSON ({exc})") from None


def _is_frame_counter(column):
    """True when ``column`` is a strictly increasing integer sequence (int16 counters may wrap)."""
    values = np.asarray(column, dtype=np.float64)
    if len(values) < 3 or not np.all(values == np.round(values)):
        return False
    steps = np.diff(values)
    if column.dtype == np.int16:
        steps = np.mod(steps, 65536)
        return bool(np.all((steps > 0) & (steps < 32768)))
    return bool(np.all(steps > 0))


class RadarlogReader:
    """An open Radarlog capture; use :func:`open_capture`.

    Attributes
    ----------
    params : RadarParams
        Chirp parameters (N after dropping a frame counter).
    n_chirps : int
    layout : Layout
    truth : dict or None
        ``{"scene_yaml": str, "expected": dict}`` for simulated files.
    warnings : list of str
        Non-essential content that was malformed and ignored (``/RxPosn``, ``TxSeq``, ``/Truth``), one line each.
    tx_sequence : tuple of int
        The ``TxSeq`` root attribute (``Cfg_TxSeq``): the transmitter of each chirp, repeating; () without one.
    stride : int
        Every stride-th stored chirp is read (:meth:`select_every`; 1 until then): ``params`` and ``n_chirps`` are
        those of the chirps read.
    read_chunk_bytes : int
        Bytes HDF5 decompresses at once to read a row (the largest chunk of a filtered dataset; 0 when
        the samples are stored uncompressed and read straight into the caller's buffer).
    """

    def __init__(self, path, *, frame_counter="auto", overrides=None, allow_external=False):
        self.path = os.fspath(path)
        self.warnings = []
        self._first_chirp = None  # of every channel, to tell constant data (a fill value) from a signal
        self._varies = False
        self._lock = threading.Lock()
        self.stride = 1
        check_regular_file(self.path)
        try:
            self._h5 = h5py.File(self.path, "r")
        except FileNotFoundError:
            raise CaptureFormatError(f"{self.path}: no such file") from None
        except OSError as exc:
            if "truncated" in str(exc):
                raise CaptureFormatError(
                    f"{self.path}: the HDF5 file is truncated; the recording or copy did not finish") from None
            raise CaptureFormatError(
                f"{self.path}: not a readable HDF5 file ({str(exc).split('(')[0].strip()}); "
                "check that the file is complete and is a Radarlog capture") from None
        try:
            self._open(frame_counter, dict(overrides or {}), allow_external)
        except (KeyError, OSError, RuntimeError, TypeError) as exc:  # h5py's errors for a damaged structure
            self._h5.close()
            raise CaptureFormatError(f"{self.path}: the HDF5 structure is damaged ({str(exc).split('(')[0].strip()}); "
                                     "the file is not a readable Radarlog capture") from None
        except BaseException:
            self._h5.close()
            raise

    def _open(self, frame_counter, overrides, allow_external):
        h5, path = self._h5, self.path
        if overrides.pop("carrier_hz", None) is not None:  # (a batch may mix captures and I/Q recordings)
            self.warnings.append("--carrier-hz applies to I/Q (CW) recordings, not to this capture, whose carrier is "
                                 "its chirp's centre (--fstrt, --fstop)")
        prefix, values = _read_attributes(h5.attrs, path, overrides)
        kind, datasets = _sample_datasets(h5, path, allow_external=allow_external)
        self._datasets = datasets
        if kind == "3-D":
            n_chirps, n_channels, row_length = datasets[0].shape
        else:
            (n_chirps, row_length), n_channels = datasets[0].shape, len(datasets)
        self._n_channels = n_channels
        dtype = self._dtype = datasets[0].dtype.newbyteorder("=")  # big-endian samples read as native ones
        self.read_chunk_bytes = max(
            (int(np.prod(ds.chunks)) * dtype.itemsize for ds in datasets if _filtered(ds)), default=0)
        if values["n_samples"] != row_length:
            raise CaptureFormatError(
                f"{path}: attribute N={values['n_samples']} but chirps hold {row_length} samples; "
                f"fix N or pass --n {row_length}")
        if values["n_channels"] != n_channels:
            raise CaptureFormatError(
                f"{path}: attribute NrChn={values['n_channels']} but the file holds {n_channels} channels; "
                f"fix NrChn or pass --nrchn {n_channels}")
        if n_chirps < 1:
            raise CaptureFormatError(f"{path}: the capture holds no chirps")
        try:  # the numbers are checked before any sample is read
            RadarParams(**values)
        except ParameterError as exc:
            raise CaptureFormatError(f"{path}: {_name_attribute(exc)}") from None
        if frame_counter == "auto":
            first = self._raw(0, min(n_chirps, DETECTION_CHIRPS), [0])[0, :, 0]
            frame_counter = _is_frame_counter(first)
        self._skip = 1 if frame_counter else 0
        values["n_samples"] -= self._skip
        if self._skip and values["n_samples"] < RADAR_LIMITS["n_samples"][0]:
            raise CaptureFormatError(f"{path}: {values['n_samples']} samples a chirp are left once the frame counter is "
                                     f"dropped, under the {RADAR_LIMITS['n_samples'][0]} read; this capture holds no "
                                     "frame counter (--frame-counter no)")
        try:
            self.params = RadarParams(**values, rx_positions_m=self._rx_positions(n_channels, allow_external))
        except ParameterError as exc:
            raise CaptureFormatError(f"{path}: {_name_attribute(exc)}") from None
        self.n_chirps = self._stored_chirps = int(n_chirps)
        self._stored_params = self.params
        self.layout = Layout(prefix, kind, str(dtype), bool(frame_counter))
        self.tx_sequence = self._tx_sequence()
        self.truth = self._truth(allow_external)

    def select_every(self, stride):
        """Read every ``stride``-th stored chirp from the first on (one transmitter's of a cycle of ``stride``):
        ``params`` (Tp times ``stride``) and ``n_chirps`` become theirs."""
        try:
            params = self._stored_params.every(int(stride))
        except ParameterError:
            longest_s = RADAR_LIMITS["chirp_period_s"][1]
            raise ParameterError(f"{self.path}: one transmitter's chirps, one in {stride} (its cycle), lie "
                                 f"{stride * self._stored_params.chirp_period_s:.3g} s apart, over the {longest_s:g} s "
                                 "read; check --transmitters and TxSeq") from None
        self.stride, self.params = int(stride), params
        self.n_chirps = len(range(0, self._stored_chirps, self.stride))

    def _tx_sequence(self):
        """The ``TxSeq`` (or ``Cfg_TxSeq``) root attribute as a tuple of transmitter numbers (1 and up), or () with a
        warning when it is anything else; its shape is checked before it is read."""
        name = next((n for n in ("TxSeq", "Cfg_TxSeq") if n in self._h5.attrs), None)
        if name is None:
            return ()
        problem = None
        try:
            attribute = self._h5.attrs.get_id(name)
            shape, dtype = attribute.shape or (1,), attribute.dtype
            if dtype.kind not in "iuf" or len(shape) != 1 or not 1 <= shape[0] <= MAX_TX_SEQUENCE:
                problem = f"it is not a list of 1 to {MAX_TX_SEQUENCE} transmitter numbers ({dtype}, shape {shape})"
            else:
                values = np.atleast_1d(np.asarray(self._h5.attrs[name], dtype=np.float64))
                if not np.all(np.isfinite(values)) or np.any(values < 1) or np.any(values != np.round(values)):
                    problem = "its entries must be whole transmitter numbers from 1 up"
        except (OSError, TypeError, ValueError, KeyError) as exc:
            problem = f"unreadable ({str(exc).split('(')[0].strip()})"
        if problem:
            self.warnings.append(f"ignored attribute {name}: {problem}")
            return ()
        return tuple(int(v) for v in values)

    def _optional(self, name, allow_external, kind):
        """The object ``/name`` if present, safe to read and of ``kind``; otherwise None and a warning."""
        if self._h5.get(name, getlink=True) is None:
            return None
        try:
            obj = _locate(self._h5, f"/{name}", self.path, allow_external=allow_external)
            if isinstance(obj, h5py.Dataset):
                _check_storage(obj, name, self.path, allow_external=allow_external)
        except CaptureFormatError as exc:
            self.warnings.append(f"ignored /{name}: {str(exc).removeprefix(self.path + ': ')}")
            return None
        if not isinstance(obj, kind):
            self.warnings.append(f"ignored /{name}: it is a {type(obj).__name__.lower()}, not a {kind.__name__.lower()}")
            return None
        return obj

    def _rx_positions(self, n_channels, allow_external):
        """``/RxPosn`` as a tuple of NrChn finite positions (m), or () with a warning when it is anything else."""
        ds = self._optional("RxPosn", allow_external, h5py.Dataset)
        if ds is None:
            return ()
        problem = None
        if ds.dtype.kind not in "iuf":
            problem = f"it holds {ds.dtype} values, not positions in m"
        elif ds.size != n_channels:
            problem = f"it lists {ds.size} positions for {n_channels} channels"
        else:
            positions = np.asarray(ds[()], dtype=np.float64).ravel()
            if not np.all(np.isfinite(positions)):
                problem = "it holds NaN or Inf"
        if problem:
            self.warnings.append(f"ignored /RxPosn: {problem}")
            return ()
        return tuple(positions)

    def _truth(self, allow_external):
        """``/Truth`` of a simulated capture, or None (with a warning when it is present but malformed)."""
        group = self._optional("Truth", allow_external, h5py.Group)
        if group is None:
            return None
        try:
            scene_yaml = _text_attribute(group.attrs, "scene_yaml")
            expected = parse_json_bounded(_text_attribute(group.attrs, "expected_json") or "{}")
            if not isinstance(expected, dict):
                raise ValueError(f"expected_json is a {type(expected).__name__}, not an object")
        except (ValueError, TypeError, KeyError, OSError) as exc:
            self.warnings.append(f"ignored /Truth: {exc}")
            return None
        return {"scene_yaml": scene_yaml or "", "expected": expected}

    def _raw(self, start, stop, channels=None, out=None):
        """Stored samples of chirps ``start:stop`` (of those read: every ``stride``-th stored), channel-major
        (C, M, N_stored), read into ``out`` if given."""
        channels = list(range(self._n_channels) if channels is None else channels)
        rows = np.s_[start * self.stride:max(start, stop - 1) * self.stride + (stop > start):self.stride]
        try:
            if self._datasets[0].ndim == 3:
                block = self._datasets[0][rows][:, channels, :].transpose(1, 0, 2).astype(self._dtype, copy=False)
                if out is None:
                    return np.ascontiguousarray(block)
                out[...] = block
                return out
            if out is None:
                out = np.empty((len(channels), stop - start, self._datasets[0].shape[1]), self._dtype)
            for row, channel in zip(out, channels):
                self._datasets[channel].read_direct(row, rows)
            return out
        except OSError as exc:
            raise CaptureFormatError(
                f"{self.path}: chirps {start}..{stop - 1} cannot be read ({str(exc).split('(')[0].strip()}); "
                "the file is corrupt") from None

    def read_counts(self, start, stop, *, channels=None, out=None):
        """Chirps ``start:stop`` as stored (ADC counts, or floats), shape (channels, chirps, samples).

        The fast path: no scaling (multiply by ``params.full_scale_v_per_lsb`` for volts) and no copy
        beyond the read; ``out`` (C, M, N + frame-counter column) is reused when given. NaN or Inf in
        float samples is an error.
        """
        block = self._raw(start, stop, channels, out)[..., self._skip:]
        if block.dtype.kind == "f":
            check_float_samples(block, f"{self.path}: chirps {start}..{stop - 1}")
        if channels is None and not self._varies:
            with self._lock:
                if self._first_chirp is None:
                    self._first_chirp = block[:, 0].copy()
            if np.any(block != self._first_chirp[:, None, :]):
                self._varies = True
        return block

    def constant_description(self):
        """None once two chirps read (all channels, by :meth:`read_counts`) differ; otherwise what every chirp holds.

        Constant data (all zeros, a fill value, one chirp repeated) carry no signal: their noise
        estimate is zero and would pass every detection threshold.
        """
        if self._varies or self._first_chirp is None:
            return None
        values = np.unique(self._first_chirp)
        if len(values) == 1:
            return f"every sample read is {values[0].item()!r} (constant data, such as a fill value)"
        return "every chirp read repeats the same samples (zero variance across chirps in every channel)"

    def read_chirps(self, start, stop, *, channels=None):
        """Chirps ``start:stop`` as float32 volts, shape (chirps, channels, samples)."""
        out = self.read_counts(start, stop, channels=channels).transpose(1, 0, 2).astype(np.float32)
        out *= np.float32(self.params.full_scale_v_per_lsb)
        return out

    def iter_chunks(self, *, chunk_chirps=DEFAULT_CHUNK_CHIRPS, channels=None, start=0, stop=None):
        """Yield ``(first_chirp, block)`` over the capture, ``block`` as in :meth:`read_chirps`."""
        stop = self.n_chirps if stop is None else min(stop, self.n_chirps)
        for first in range(start, stop, chunk_chirps):
            yield first, self.read_chirps(first, min(first + chunk_chirps, stop), channels=channels)

    def close(self):
        self._h5.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def open_capture(path, *, frame_counter="auto", overrides=None, allow_external=False):
    """Open a Radarlog capture for reading.

    Parameters
    ----------
    path : str or os.PathLike
    frame_counter : {"auto", True, False}
        Whether sample 0 of each chirp is a frame counter; "auto" detects a strictly increasing
        integer sequence in the first chirps.
    overrides : mapping, optional
        Attribute values (by canonical name, e.g. ``{"Tp": 64e-6}``) that replace or supply the file's;
        they are checked like the file's.
    allow_external : bool
        Read samples from other files (external links, virtual datasets, external raw storage) for a
        trusted file; by default such a capture is refused, since a file from the field could make
        the reader read any file on the machine or block on a FIFO.

    Raises
    ------
    CaptureFormatError
        With one line naming the problem: not a regular file, data outside the file, a declared shape
        the stored bytes cannot hold, parameters out of range (see ``mdpipe.params.RADAR_LIMITS``).
    """
    return RadarlogReader(path, frame_counter=frame_counter, overrides=overrides, allow_external=allow_external)


def create_hdf5_exclusive(path, *, attempts=100):
    """A new HDF5 file under a unique hidden name beside ``path``; returns ``(h5py.File, name)``.

    HDF5 creates it with ``O_CREAT | O_EXCL`` (mode ``"x"``), which never follows a symlink and fails
    on any existing name, and with the umask's mode, like any new file.
    """
    folder, name = os.path.split(os.path.abspath(path))
    for _ in range(attempts):
        candidate = os.path.join(folder, f".{name}.{os.urandom(6).hex()}.partial")
        try:  # without HDF5's file lock, so that the file can be reopened while its descriptor is held
            return h5py.File(candidate, "x", locking=False), candidate
        except FileExistsError:
            continue
    raise FileExistsError(f"{folder}: no free temporary name after {attempts} attempts")


class CaptureWriter:
    """Write a canonical Radarlog capture chunk by chunk; the file appears only when complete.

    Use as a context manager. Data go to a new hidden file beside ``path``, created exclusively
    (:func:`create_hdf5_exclusive`: a symlink or file planted there is never followed), written
    through a descriptor of that file (``/Truth`` reopens it by name and checks it is the same file),
    and renamed to ``path`` on success; on any exception, KeyboardInterrupt and SystemExit included,
    it is removed. With ``overwrite=False`` an existing ``path`` is kept and :class:`FileExistsError`
    raised.

    HDF5 allocates every row chunk of every channel when the datasets are made (early allocation,
    no fill); the chunks' byte offsets are looked up once, and :meth:`write_chirps` writes the rows
    straight to them with ``os.pwrite``, which, unlike h5py, releases the GIL: the simulation
    threads keep running while a chunk is written (through h5py, the writes serialised them and
    cost 2 s of a 4.5 s full-size run). Uncompressed chunks hold exactly the rows' bytes, so the
    file is ordinary HDF5. No object records its creation time, so a scene and seed always give
    the same bytes.
    """

    def __init__(self, path, params, n_chirps, *, creator, truth=None, chunk_rows=64, overwrite=True,
                 tx_sequence=None):
        if not hasattr(os, "pwrite"):
            raise PlatformError("writing a capture needs os.pwrite, which this platform lacks (Windows): run "
                                "mdpipe simulate on Linux, macOS or WSL (reading and processing do not need it)")
        self.path = os.fspath(path)
        self.params, self.n_chirps = params, int(n_chirps)
        self.chunk_rows = max(1, min(chunk_rows, self.n_chirps))
        self._overwrite = overwrite
        self._truth = truth
        h5 = None
        try:
            h5, self.partial_path = create_hdf5_exclusive(self.path)
            self._fd = os.dup(h5.id.get_vfd_handle())  # the writes go to this file, never to a name
            attrs = h5.attrs
            attrs["fStrt"] = np.float64(params.f_start_hz)
            attrs["fStop"] = np.float64(params.f_stop_hz)
            attrs["TRampUp"] = np.float64(params.ramp_up_s)
            attrs["TRampDo"] = np.float64(params.ramp_down_s)
            attrs["Tp"] = np.float64(params.chirp_period_s)
            attrs["fs"] = np.float64(params.sample_rate_hz)
            attrs["N"] = np.int64(params.n_samples)
            attrs["NrChn"] = np.int64(params.n_channels)
            attrs["FuSca"] = np.float64(params.full_scale_v_per_lsb)
            attrs["Creator"] = creator
            if tx_sequence is not None:
                attrs["TxSeq"] = np.asarray(tx_sequence, dtype=np.int64)
            self._offsets = [self._allocate(h5, f"Chn{c + 1}") for c in range(params.n_channels)]
            if params.rx_positions_m:
                h5.create_dataset("RxPosn", data=np.asarray(params.rx_positions_m, dtype=np.float64),
                                  track_times=False)
            h5.close()
        except BaseException:
            if h5 is not None:
                h5.close()
                self._discard()
            raise

    def _discard(self):
        if getattr(self, "_fd", None) is not None:
            os.close(self._fd)
            self._fd = None
        if os.path.exists(self.partial_path):
            os.remove(self.partial_path)

    def _allocate(self, h5, name):
        """Make a row-chunked int16 dataset with all chunks allocated; return the chunks' byte offsets."""
        shape = (self.n_chirps, self.params.n_samples)
        dcpl = h5py.h5p.create(h5py.h5p.DATASET_CREATE)
        dcpl.set_chunk((self.chunk_rows, self.params.n_samples))
        dcpl.set_alloc_time(h5py.h5d.ALLOC_TIME_EARLY)
        dcpl.set_fill_time(h5py.h5d.FILL_TIME_NEVER)
        dcpl.set_obj_track_times(False)  # no creation times: the same scene gives the same bytes
        dataset = h5py.h5d.create(h5.id, name.encode(), h5py.h5t.STD_I16LE, h5py.h5s.create_simple(shape),
                                  dcpl=dcpl)
        return [dataset.get_chunk_info_by_coord((row, 0)).byte_offset
                for row in range(0, self.n_chirps, self.chunk_rows)]

    def write_chirps(self, first_chirp, block):
        """Store ``block`` (channels, chirps, samples) of int16 at ``first_chirp`` (a multiple of ``chunk_rows``)."""
        if first_chirp % self.chunk_rows:
            raise ValueError(f"first_chirp={first_chirp} must be a multiple of chunk_rows={self.chunk_rows}")
        block = np.asarray(block, dtype="<i2")
        for offsets, rows in zip(self._offsets, block):
            for start in range(0, rows.shape[0], self.chunk_rows):
                piece = np.ascontiguousarray(rows[start:start + self.chunk_rows])
                os.pwrite(self._fd, memoryview(piece).cast("B"), offsets[(first_chirp + start) // self.chunk_rows])

    def write_truth(self, *, scene_yaml, expected):
        """Keep the truth for ``/Truth``, written when the capture is complete."""
        self._truth = {"scene_yaml": scene_yaml, "expected": expected}

    def __enter__(self):
        return self

    def __exit__(self, exc_type, exc, tb):
        if exc_type is not None:
            self._discard()
            return
        try:
            if self._truth is not None:
                with h5py.File(self.partial_path, "r+", locking=False) as h5:
                    if not os.path.samestat(os.fstat(h5.id.get_vfd_handle()), os.fstat(self._fd)):
                        raise OSError(f"{self.partial_path}: the temporary file was replaced while being written")
                    gcpl = h5py.h5p.create(h5py.h5p.GROUP_CREATE)
                    gcpl.set_obj_track_times(False)
                    group = h5py.Group(h5py.h5g.create(h5.id, b"Truth", gcpl=gcpl))
                    group.attrs["scene_yaml"] = self._truth["scene_yaml"]
                    group.attrs["expected_json"] = json.dumps(self._truth["expected"], indent=1)
            publish(self.partial_path, self.path, overwrite=self._overwrite)
        except BaseException:
            self._discard()
            raise
        os.close(self._fd)
