"""The Radarlog HDF5 layout (canonical, as written by ``mdpipe simulate``) and the variants read.

Canonical: SI scalar root attributes ``fStrt fStop TRampUp TRampDo Tp fs N NrChn FuSca Creator``,
int16 datasets ``/Chn1 ... /Chn{NrChn}`` of shape (n_chirps, N) chunked by rows, optional
``/RxPosn`` (NrChn,) and, for simulated files, ``/Truth`` with attributes ``scene_yaml`` and
``expected_json``.

Variants read: ``Cfg_``-prefixed attribute names; one dataset ``/Data`` of shape
(n_chirps, NrChn, N); a frame counter in sample 0 of every chirp (detected or forced; the column
is dropped and N becomes N - 1); float32/float64 samples.

Chunks read from a capture are float32 volts (samples times FuSca), shape (chirps, channels,
samples).
"""

import json
import os
from dataclasses import dataclass

import h5py
import numpy as np

from mdpipe.errors import CaptureFormatError, ParameterError, PlatformError
from mdpipe.params import RadarParams

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
    return array.reshape(()).item()


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


def _sample_datasets(h5, path):
    if "Data" in h5 and isinstance(h5["Data"], h5py.Dataset):
        data = h5["Data"]
        if data.ndim != 3:
            raise CaptureFormatError(
                f"{path}: dataset '/Data' has shape {data.shape}; expected (n_chirps, NrChn, N)")
        return "3-D", [data]
    names = sorted((k for k in h5 if k.startswith("Chn") and k[3:].isdigit()), key=lambda k: int(k[3:]))
    if not names:
        raise CaptureFormatError(
            f"{path}: no sample datasets (expected /Chn1 ... /Chn{{NrChn}} or one /Data); is this a Radarlog capture?")
    expected = [f"Chn{i + 1}" for i in range(len(names))]
    if names != expected:
        raise CaptureFormatError(f"{path}: channel datasets {names} are not numbered Chn1..Chn{len(names)}")
    datasets = [h5[n] for n in names]
    for name, ds in zip(names, datasets):
        if ds.ndim != 2 or ds.shape != datasets[0].shape:
            raise CaptureFormatError(
                f"{path}: dataset '/{name}' has shape {ds.shape}; every /ChnK must be (n_chirps, N) "
                f"like /Chn1 {datasets[0].shape}")
    return "per-channel", datasets


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
    """

    def __init__(self, path, *, frame_counter="auto", overrides=None):
        self.path = os.fspath(path)
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
            self._open(frame_counter, dict(overrides or {}))
        except BaseException:
            self._h5.close()
            raise

    def _open(self, frame_counter, overrides):
        h5, path = self._h5, self.path
        prefix, values = _read_attributes(h5.attrs, path, overrides)
        kind, datasets = _sample_datasets(h5, path)
        self._datasets = datasets
        if kind == "3-D":
            n_chirps, n_channels, row_length = datasets[0].shape
        else:
            (n_chirps, row_length), n_channels = datasets[0].shape, len(datasets)
        self._n_channels = n_channels
        dtype = datasets[0].dtype
        if dtype not in SAMPLE_DTYPES:
            raise CaptureFormatError(
                f"{path}: samples are {dtype}; Radarlog samples must be int16 (or float32/float64)")
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
        if frame_counter == "auto":
            first = self._raw(0, min(n_chirps, DETECTION_CHIRPS), [0])[0, :, 0]
            frame_counter = _is_frame_counter(first)
        self._skip = 1 if frame_counter else 0
        values["n_samples"] -= self._skip
        positions = ()
        if "RxPosn" in h5:
            positions = tuple(np.asarray(h5["RxPosn"][()], dtype=np.float64).ravel())
            if len(positions) != n_channels:
                raise CaptureFormatError(
                    f"{path}: /RxPosn lists {len(positions)} positions for {n_channels} channels")
        try:
            self.params = RadarParams(**values, rx_positions_m=positions)
        except ParameterError as exc:
            raise CaptureFormatError(f"{path}: {exc}") from None
        self.n_chirps = int(n_chirps)
        self.layout = Layout(prefix, kind, str(dtype), bool(frame_counter))
        self.truth = None
        if "Truth" in h5:
            attrs = h5["Truth"].attrs
            self.truth = {"scene_yaml": str(attrs.get("scene_yaml", "")),
                          "expected": json.loads(attrs.get("expected_json", "{}"))}

    def _raw(self, start, stop, channels=None, out=None):
        """Stored samples of chirps ``start:stop``, channel-major (C, M, N_stored), read into ``out`` if given."""
        channels = list(range(self._n_channels) if channels is None else channels)
        try:
            if self._datasets[0].ndim == 3:
                block = self._datasets[0][start:stop][:, channels, :].transpose(1, 0, 2)
                if out is None:
                    return np.ascontiguousarray(block)
                out[...] = block
                return out
            if out is None:
                out = np.empty((len(channels), stop - start, self._datasets[0].shape[1]), self._datasets[0].dtype)
            for row, channel in zip(out, channels):
                self._datasets[channel].read_direct(row, np.s_[start:stop])
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
        if block.dtype.kind == "f" and not np.all(np.isfinite(block)):
            raise CaptureFormatError(
                f"{self.path}: chirps {start}..{stop - 1} hold NaN or Inf samples; the capture is corrupt")
        return block

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


def open_capture(path, *, frame_counter="auto", overrides=None):
    """Open a Radarlog capture for reading.

    Parameters
    ----------
    path : str or os.PathLike
    frame_counter : {"auto", True, False}
        Whether sample 0 of each chirp is a frame counter; "auto" detects a strictly increasing
        integer sequence in the first chirps.
    overrides : mapping, optional
        Attribute values (by canonical name, e.g. ``{"Tp": 64e-6}``) that replace or supply the file's.
    """
    return RadarlogReader(path, frame_counter=frame_counter, overrides=overrides)


class CaptureWriter:
    """Write a canonical Radarlog capture chunk by chunk; the file appears only when complete.

    Use as a context manager; data goes to ``<path>.partial`` and is renamed on success.

    HDF5 allocates every row chunk of every channel when the datasets are made (early allocation,
    no fill); the chunks' byte offsets are looked up once, and :meth:`write_chirps` writes the rows
    straight to them with ``os.pwrite``, which, unlike h5py, releases the GIL: the simulation
    threads keep running while a chunk is written (through h5py, the writes serialised them and
    cost 2 s of a 4.5 s full-size run). Uncompressed chunks hold exactly the rows' bytes, so the
    file is ordinary HDF5. No object records its creation time, so a scene and seed always give
    the same bytes.
    """

    def __init__(self, path, params, n_chirps, *, creator, truth=None, chunk_rows=64):
        if not hasattr(os, "pwrite"):
            raise PlatformError("writing a capture needs os.pwrite, which this platform lacks (Windows): run "
                                "mdpipe simulate on Linux, macOS or WSL (reading and processing do not need it)")
        self.path = os.fspath(path)
        self.params, self.n_chirps = params, int(n_chirps)
        self.chunk_rows = max(1, min(chunk_rows, self.n_chirps))
        self._partial = self.path + ".partial"
        self._truth = truth
        with h5py.File(self._partial, "w") as h5:
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
            self._offsets = [self._allocate(h5, f"Chn{c + 1}") for c in range(params.n_channels)]
            if params.rx_positions_m:
                h5.create_dataset("RxPosn", data=np.asarray(params.rx_positions_m, dtype=np.float64),
                                  track_times=False)
        self._fd = os.open(self._partial, os.O_WRONLY)

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
        os.close(self._fd)
        if exc_type is not None:
            os.remove(self._partial)
            return
        if self._truth is not None:
            with h5py.File(self._partial, "r+") as h5:
                gcpl = h5py.h5p.create(h5py.h5p.GROUP_CREATE)
                gcpl.set_obj_track_times(False)
                group = h5py.Group(h5py.h5g.create(h5.id, b"Truth", gcpl=gcpl))
                group.attrs["scene_yaml"] = self._truth["scene_yaml"]
                group.attrs["expected_json"] = json.dumps(self._truth["expected"], indent=1)
        os.replace(self._partial, self.path)
