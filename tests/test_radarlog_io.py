"""Radarlog HDF5: canonical write -> read, every variant the reader accepts, and pinned errors."""

import h5py
import numpy as np
import pytest

from mdpipe.errors import CaptureFormatError
from mdpipe.io import CaptureWriter, open_capture
from mdpipe.params import RadarParams

PARAMS = RadarParams(f_start_hz=76e9, f_stop_hz=76.04e9, ramp_up_s=51.2e-6, chirp_period_s=64e-6,
                     sample_rate_hz=5e6, n_samples=256, n_channels=3, ramp_down_s=12.8e-6,
                     full_scale_v_per_lsb=2.5e-6, rx_positions_m=(0.0, 1.948e-3, 3.896e-3))
ATTRS = {"fStrt": 76e9, "fStop": 76.04e9, "TRampUp": 51.2e-6, "Tp": 64e-6, "fs": 5e6, "N": 256, "NrChn": 3}


@pytest.fixture
def samples():
    rng = np.random.default_rng(0)
    return rng.integers(-32768, 32767, size=(3, 40, 256), dtype=np.int16)  # (channel, chirp, sample)


def write_canonical(path, samples, truth=None):
    with CaptureWriter(path, PARAMS, samples.shape[1], creator="test", truth=truth, chunk_rows=16) as w:
        w.write_chirps(0, samples[:, :16])
        w.write_chirps(16, samples[:, 16:])


def write_raw(path, attrs, datasets):
    with h5py.File(path, "w") as h5:
        for key, value in attrs.items():
            h5.attrs[key] = value
        for name, data in datasets.items():
            h5.create_dataset(name, data=data)


def test_canonical_round_trip(tmp_path, samples):
    path = tmp_path / "c.h5"
    write_canonical(path, samples, truth={"scene_yaml": "a: 1\n", "expected": {"targets": [{"x": 1.5}]}})
    with h5py.File(path) as h5:  # the layout itself, as other tools will see it
        assert h5["Chn1"].dtype == np.int16 and h5["Chn3"].shape == (40, 256) and h5["Chn1"].chunks == (16, 256)
        assert h5.attrs["N"].dtype == np.int64 and h5.attrs["fStrt"].dtype == np.float64
        assert sorted(k for k in h5 if k.startswith("Chn")) == ["Chn1", "Chn2", "Chn3"]
    with open_capture(path) as cap:
        assert cap.params == PARAMS
        assert cap.n_chirps == 40
        assert cap.layout.describe().startswith("canonical")
        assert cap.truth == {"scene_yaml": "a: 1\n", "expected": {"targets": [{"x": 1.5}]}}
        block = cap.read_chirps(0, 40)
        assert block.shape == (40, 3, 256) and block.dtype == np.float32
        np.testing.assert_array_equal(block, samples.transpose(1, 0, 2).astype(np.float32) * np.float32(2.5e-6))
        chunks = list(cap.iter_chunks(chunk_chirps=16, channels=[2]))
        assert [first for first, _ in chunks] == [0, 16, 32]
        np.testing.assert_array_equal(np.concatenate([b for _, b in chunks])[:, 0], block[:, 2])


def test_writer_needs_chunk_aligned_writes(tmp_path, samples):
    with pytest.raises(ValueError, match=r"first_chirp=5 must be a multiple of chunk_rows=16"):
        with CaptureWriter(tmp_path / "c.h5", PARAMS, 40, creator="test", chunk_rows=16) as w:
            w.write_chirps(5, samples[:, 5:10])
    assert not (tmp_path / "c.h5").exists()


def test_writer_leaves_no_file_when_interrupted(tmp_path, samples):
    path = tmp_path / "c.h5"
    with pytest.raises(RuntimeError):
        with CaptureWriter(path, PARAMS, 40, creator="test") as w:
            w.write_chirps(0, samples[:, :10])
            raise RuntimeError("stop")
    assert not path.exists() and not (tmp_path / "c.h5.partial").exists()


def test_variant_cfg_prefix(tmp_path, samples):
    path = tmp_path / "v.h5"
    write_raw(path, {f"Cfg_{k}": v for k, v in ATTRS.items()}, {f"Chn{c + 1}": samples[c] for c in range(3)})
    with open_capture(path) as cap:
        assert cap.layout.attribute_prefix == "Cfg_" and "Cfg_" in cap.layout.describe()
        assert cap.params.chirp_period_s == 64e-6 and cap.params.full_scale_v_per_lsb == 1.0
        np.testing.assert_array_equal(cap.read_chirps(0, 40)[:, 1], samples[1])


def test_variant_3d_data(tmp_path, samples):
    path = tmp_path / "v.h5"
    write_raw(path, ATTRS, {"Data": samples.transpose(1, 0, 2)})
    with open_capture(path) as cap:
        assert cap.layout.sample_datasets == "3-D" and "/Data" in cap.layout.describe()
        np.testing.assert_array_equal(cap.read_chirps(5, 9, channels=[0, 2]),
                                      samples.transpose(1, 0, 2)[5:9][:, [0, 2]])


@pytest.mark.parametrize("start", [0, 32760])  # the second wraps around int16
def test_variant_frame_counter_detected_and_dropped(tmp_path, samples, start):
    counted = samples.copy()
    counted[:, :, 0] = ((start + np.arange(40)) % 65536).astype(np.uint16).view(np.int16)
    path = tmp_path / "v.h5"
    write_raw(path, ATTRS, {f"Chn{c + 1}": counted[c] for c in range(3)})
    with open_capture(path) as cap:
        assert cap.layout.frame_counter and cap.params.n_samples == 255
        np.testing.assert_array_equal(cap.read_chirps(0, 40)[:, 0], samples[0, :, 1:])
    with open_capture(path, frame_counter=False) as cap:
        assert cap.params.n_samples == 256


def test_frame_counter_forced_and_not_detected_in_plain_samples(tmp_path, samples):
    path = tmp_path / "v.h5"
    write_raw(path, ATTRS, {f"Chn{c + 1}": samples[c] for c in range(3)})
    with open_capture(path) as cap:
        assert not cap.layout.frame_counter
    with open_capture(path, frame_counter=True) as cap:
        assert cap.params.n_samples == 255


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_variant_float_samples(tmp_path, samples, dtype):
    path = tmp_path / "v.h5"
    write_raw(path, {**ATTRS, "FuSca": 0.5}, {f"Chn{c + 1}": samples[c].astype(dtype) for c in range(3)})
    with open_capture(path) as cap:
        assert cap.layout.sample_dtype == np.dtype(dtype).name
        np.testing.assert_array_equal(cap.read_chirps(0, 40)[:, 2], samples[2].astype(np.float32) * 0.5)


def test_overrides_supply_missing_attribute(tmp_path, samples):
    path = tmp_path / "v.h5"
    write_raw(path, {k: v for k, v in ATTRS.items() if k != "Tp"}, {f"Chn{c + 1}": samples[c] for c in range(3)})
    with pytest.raises(CaptureFormatError, match=r"attribute 'Tp' \(chirp repetition interval, s\) is missing; "
                                                 r"supply it with --tp 64e-6"):
        open_capture(path)
    with open_capture(path, overrides={"Tp": 80e-6}) as cap:
        assert cap.params.chirp_period_s == 80e-6


@pytest.mark.parametrize("attrs, datasets, message", [
    ({**ATTRS, "N": 300}, "chn", r"attribute N=300 but chirps hold 256 samples; fix N or pass --n 256"),
    ({**ATTRS, "NrChn": 4}, "chn", r"attribute NrChn=4 but the file holds 3 channels; fix NrChn or pass --nrchn 3"),
    (ATTRS, {}, r"no sample datasets \(expected /Chn1 \.\.\. /Chn\{NrChn\} or one /Data\)"),
    (ATTRS, {"Chn1": np.zeros((4, 256), np.int16), "Chn3": np.zeros((4, 256), np.int16)},
     r"channel datasets \['Chn1', 'Chn3'\] are not numbered Chn1\.\.Chn2"),
    (ATTRS, {"Chn1": np.zeros((4, 256), np.int16), "Chn2": np.zeros((5, 256), np.int16),
             "Chn3": np.zeros((4, 256), np.int16)}, r"dataset '/Chn2' has shape \(5, 256\)"),
    (ATTRS, {"Data": np.zeros((4, 256), np.int16)}, r"dataset '/Data' has shape \(4, 256\); expected \(n_chirps, NrChn, N\)"),
    (ATTRS, {f"Chn{c}": np.zeros((4, 256), np.int32) for c in (1, 2, 3)}, r"samples are int32; Radarlog samples must be int16"),
    ({**ATTRS, "Tp": -1.0}, "chn", r"chirp_period_s=-1.0 must be a finite number in \[1e-07, 1\] s \(chirp repetition interval: 100 ns to 1 s\); "
                                   r"attribute 'Tp', or override with --tp$"),
    ({**ATTRS, "fStop": 75e9}, "chn", r"f_stop_hz=75000000000.0 must exceed f_start_hz=76000000000.0"),
    ({**ATTRS, "fs": 1e6}, "chn", r"n_samples / sample_rate_hz = 0.000256 s exceeds ramp_up_s=5.12e-05"),
    ({**ATTRS, "Tp": np.array([1.0, 2.0])}, "chn", r"attribute 'Tp' must be one number"),
    (ATTRS, {f"Chn{c}": np.zeros((0, 256), np.int16) for c in (1, 2, 3)}, r"the capture holds no chirps"),
])
def test_format_errors_name_the_problem(tmp_path, samples, attrs, datasets, message):
    path = tmp_path / "bad.h5"
    write_raw(path, attrs, {f"Chn{c + 1}": samples[c] for c in range(3)} if datasets == "chn" else datasets)
    with pytest.raises(CaptureFormatError, match=message):
        open_capture(path)


def test_not_hdf5_and_missing_file(tmp_path):
    bad = tmp_path / "notes.h5"
    bad.write_text("not a capture")
    with pytest.raises(CaptureFormatError, match=r"notes.h5: not a readable HDF5 file .*check that the file is complete"):
        open_capture(bad)
    with pytest.raises(CaptureFormatError, match=r"absent.h5: no such file"):
        open_capture(tmp_path / "absent.h5")


def test_truncated_file(tmp_path, samples):
    path = tmp_path / "c.h5"
    write_canonical(path, samples)
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])
    with pytest.raises(CaptureFormatError, match=r"c.h5: the HDF5 file is truncated; the recording or copy did not finish"):
        open_capture(path)


def test_corrupt_chunk_is_an_error(tmp_path):
    path = tmp_path / "c.h5"
    rng = np.random.default_rng(1)
    with h5py.File(path, "w") as h5:
        for key, value in {**ATTRS, "NrChn": 1}.items():
            h5.attrs[key] = value
        h5.create_dataset("Chn1", data=rng.integers(-999, 999, (40, 256), dtype=np.int16), chunks=(8, 256),
                          compression="gzip")
        offset = h5["Chn1"].id.get_chunk_info(2).byte_offset
    with open(path, "r+b") as fh:
        fh.seek(offset)
        fh.write(b"\xff" * 64)
    with pytest.raises(CaptureFormatError, match=r"chirps 0\.\.39 cannot be read .*the file is corrupt"):
        with open_capture(path, frame_counter=False) as cap:
            cap.read_chirps(0, 40)


def test_nan_samples_are_an_error(tmp_path, samples):
    bad = samples[0].astype(np.float32)
    bad[7, 3] = np.nan
    path = tmp_path / "nan.h5"
    write_raw(path, {**ATTRS, "NrChn": 1}, {"Chn1": bad})
    with open_capture(path) as cap:
        with pytest.raises(CaptureFormatError, match=r"chirps 0\.\.39 hold NaN or Inf samples; the capture is corrupt"):
            cap.read_chirps(0, 40)
