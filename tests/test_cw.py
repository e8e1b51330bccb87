"""I/Q recordings of CW radars (docs/IQ_FORMAT.md): the reader, the noise read from the echo, detection, and the
analysis end to end on echoes of the simulator written apart from mdpipe's (benchmarks/offmodel/cw.py)."""

import sys
from pathlib import Path

import h5py
import numpy as np
import pytest
from click.testing import CliRunner
from scipy.io import wavfile

from mdpipe.cli import main
from mdpipe.errors import CaptureFormatError, ParameterError
from mdpipe.io.iq import is_iq_recording, probe_iq, read_iq
from mdpipe.params import ProcessParams
from mdpipe.process import cw, selection
from mdpipe.process.doppler import periodic_hann
from mdpipe.process.pipeline import process_capture

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from bench_cw import run_scene  # noqa: E402

SAMPLES = Path(__file__).resolve().parents[1] / "data_samples"


def write_h5(path, data, **attrs):
    with h5py.File(path, "w") as h5:
        for name, value in attrs.items():
            h5.attrs[name] = value
        h5["IQ"] = data
    return path


def noise(n, seed=0, channels=None):
    rng = np.random.default_rng(seed)
    shape = (n,) if channels is None else (n, channels)
    return (rng.standard_normal(shape) + 1j * rng.standard_normal(shape)) / np.sqrt(2)


# ------------------------------------------------------------------ reading

def test_a_stereo_wav_reads_as_i_plus_j_q_and_needs_the_carrier(tmp_path):
    counts = np.array([[1, -2], [3, 4], [-5, 6], [7, -8]], dtype=np.int16)
    path = tmp_path / "rec.wav"
    wavfile.write(path, 48000, counts)
    with pytest.raises(CaptureFormatError, match="--carrier-hz 24.125e9"):
        read_iq(path)
    recording = read_iq(path, overrides={"carrier_hz": 24.125e9})
    assert recording.params.sample_rate_hz == 48000 and recording.params.carrier_hz == 24.125e9
    np.testing.assert_array_equal(recording.samples[:, 0], [1 - 2j, 3 + 4j, -5 + 6j, 7 - 8j])
    assert is_iq_recording(path)


def test_a_four_channel_wav_holds_two_receivers_and_a_mono_one_is_refused(tmp_path):
    counts = np.arange(32, dtype=np.int16).reshape(8, 4)
    wavfile.write(tmp_path / "two.wav", 8000, counts)
    recording = read_iq(tmp_path / "two.wav", overrides={"carrier_hz": 10e9})
    assert recording.params.n_channels == 2
    np.testing.assert_array_equal(recording.samples[:, 1], counts[:, 2] + 1j * counts[:, 3])
    wavfile.write(tmp_path / "mono.wav", 8000, counts[:, 0])
    with pytest.raises(CaptureFormatError, match="1 audio channel.*no Q"):
        read_iq(tmp_path / "mono.wav", overrides={"carrier_hz": 10e9})


@pytest.mark.parametrize("layout", ["complex", "real pairs", "real pairs per channel"])
def test_the_hdf5_layouts_read_the_same_samples(tmp_path, layout):
    z = noise(64, channels=2).astype(np.complex64)
    data = {"complex": z, "real pairs": np.stack([z.real, z.imag], axis=-1)[:, 0],
            "real pairs per channel": np.stack([z.real, z.imag], axis=-1)}[layout]
    path = write_h5(tmp_path / "rec.h5", data, fc=77e9, fs=20e3, FuSca=2.0)
    recording = read_iq(path)
    expected = z if layout != "real pairs" else z[:, :1]
    np.testing.assert_allclose(recording.samples, 2.0 * expected, rtol=1e-6)
    assert is_iq_recording(path) and not is_iq_recording(SAMPLES / "fimi_1rx.h5")
    params, n, _ = probe_iq(path)
    assert (n, params.n_channels, params.wavelength_m) == (64, expected.shape[1], pytest.approx(299792458 / 77e9))


def test_missing_values_name_their_option_and_overrides_replace_the_files(tmp_path):
    path = write_h5(tmp_path / "rec.h5", noise(64), fc=24e9)
    with pytest.raises(CaptureFormatError, match=r"I/Q sample rate \(Hz\) is not in the file.*--fs 48000"):
        read_iq(path)
    assert read_iq(path, overrides={"fs": 5000.0, "carrier_hz": 3.3e9}).params.carrier_hz == 3.3e9
    with pytest.raises(ParameterError, match="--tp applies to Radarlog captures"):
        read_iq(path, overrides={"fs": 5000.0, "Tp": 1e-4})
    with pytest.raises(ParameterError, match="carrier_hz=24.0 .*did you mean 24e9"):
        read_iq(path, overrides={"fs": 5000.0, "carrier_hz": 24.0})


def test_hostile_recordings_are_refused_with_one_line(tmp_path):
    data = noise(64)
    data[5] = np.nan
    with pytest.raises(CaptureFormatError, match="1 of the I/Q samples are not finite"):
        read_iq(write_h5(tmp_path / "nan.h5", data, fc=24e9, fs=1e4))
    with h5py.File(tmp_path / "link.h5", "w") as h5:
        h5.attrs["fc"], h5.attrs["fs"] = 24e9, 1e4
        h5["IQ"] = h5py.ExternalLink("/etc/passwd", "/x")
    with pytest.raises(CaptureFormatError, match="external link.*refused"):
        read_iq(tmp_path / "link.h5")
    with h5py.File(tmp_path / "huge.h5", "w") as h5:  # declares 10^9 samples in chunks it never wrote
        h5.attrs["fc"], h5.attrs["fs"] = 24e9, 1e4
        h5.create_dataset("IQ", shape=(10 ** 9,), dtype=np.complex64, chunks=(4096,))
    with pytest.raises(CaptureFormatError, match="missing chunks would read as invented fill"):
        read_iq(tmp_path / "huge.h5")
    (tmp_path / "bad.wav").write_bytes(b"RIFF\x24\x00\x00\x00WAVEfmt \x10\x00\x00\x00" + b"\x00" * 16)
    with pytest.raises(CaptureFormatError, match="not a readable WAV file"):
        read_iq(tmp_path / "bad.wav", overrides={"carrier_hz": 24e9})


def test_memory_plan_refuses_a_recording_before_its_samples_are_read(tmp_path, monkeypatch):
    path = write_h5(tmp_path / "rec.h5", noise(1 << 16), fc=24e9, fs=1e4)
    read = []
    monkeypatch.setattr(h5py.Dataset, "__getitem__", lambda self, key: read.append(key))
    with pytest.raises(ParameterError, match=r"65,536 I/Q samples x 1 RX .*--max-memory-gb"):
        process_capture(str(path), ProcessParams(max_memory_gb=0.01))
    assert read == []


def test_carrier_option_is_refused_for_a_radarlog_capture():
    with pytest.raises(ParameterError, match="--carrier-hz applies to I/Q"):
        process_capture(str(SAMPLES / "fimi_1rx.h5"), ProcessParams(), overrides={"carrier_hz": 24e9})


# ------------------------------------------------------------------ noise and detection

def test_noise_read_from_the_echo_beside_lines_and_a_band():
    """White noise of power 1 under a line 40 dB up and a band 10 dB over a fifth of the span: within 5 %."""
    n, fs = 50000, 20000.0
    t = np.arange(n) / fs
    band = np.fft.ifft(np.fft.fft(noise(n, seed=3)) * (np.abs(np.fft.fftfreq(n, 1 / fs)) < 2000)) * np.sqrt(50)
    signal = noise(n, seed=4) + 100 * np.exp(2j * np.pi * 1234.5 * t) + band
    estimate = cw.noise_power(signal - signal.mean(), frame=cw.noise_frame(fs))
    assert estimate.power == pytest.approx(1.0, rel=0.05)  # 1.08 when the median kept the band's parts


def test_the_noise_estimates_error_is_what_it_says():
    """Over 60 recordings of white noise (power 1, 50 000 samples) the estimates scatter as their stated relative
    error says (measured: 1.6 % against 1.8 % stated), about 1 % low (the lower of two readings)."""
    estimates = [cw.noise_power(z - z.mean(), frame=16) for z in (noise(50000, seed=s) for s in range(60))]
    power = np.array([e.power for e in estimates])
    stated = np.mean([e.relative_error for e in estimates])
    assert np.mean(power) == pytest.approx(1.0, abs=0.02)
    assert 0.75 * stated <= np.std(power) <= 1.25 * stated


def test_noise_alone_is_detected_no_more_often_than_the_false_alarm_probability_says():
    """400 noise-only recordings tested at a 5 % false-alarm probability: at most 20 detections (the noise read from
    the recording itself carries an error the thresholds allow for: without that, 23-34 % were detected)."""
    window = periodic_hann(cw.DETECTION_BLOCK)
    detected = 0
    for seed in range(400):
        signal = noise(4096, seed=seed)
        signal = signal - signal.mean()
        estimate = cw.noise_power(signal, frame=cw.noise_frame(20000.0))
        power, blocks = cw.detection_spectrum(signal)
        test = selection.cell_test(power, looks=blocks, noise_cell=estimate.power * np.sum(window ** 2)
                                   / np.sum(window) ** 2, noise_error=estimate.relative_error,
                                   false_alarm_probability=0.05)
        detected += bool(test.score.max() >= 1)
    assert detected <= 20


def test_noise_alone_reads_none(tmp_path):
    path = write_h5(tmp_path / "quiet.h5", noise(20000, seed=9).astype(np.complex64), fc=24e9, fs=2e4)
    row = process_capture(str(path), ProcessParams()).rows[0]
    assert row["class"] == "none" and row["target"] is None
    assert row["notes"].startswith("nothing moving above the noise")


# ------------------------------------------------------------------ echoes of the other simulator

def test_one_rotor_through_a_filtered_receiver(tmp_path):
    """One 2-blade rotor at 83.7 rev/s, 12 cm, X band, 20 dB: the rate within 0.5 %, r within 2 %."""
    _, description, truth, row, _ = run_scene(0, tmp_path, "filtered")
    assert row["class"] == "drone", description
    assert row["rotation_rate_hz_status"] == "ok" and row["rotation_rate_hz"] == pytest.approx(truth["rate"], rel=0.005)
    assert row["blade_length_m_status"] == "ok" and row["blade_length_m"] == pytest.approx(truth["r"], rel=0.02)


def test_four_rotors_at_rates_apart(tmp_path):
    """Four tip-bright 2-blade rotors 3 % apart (X band): their rates resolved, the median within 1 %."""
    _, description, truth, row, _ = run_scene(113, tmp_path, "filtered")
    assert row["class"] == "drone", description
    assert row["rotation_rate_hz_status"] == "ok" and row["rotation_rate_hz"] == pytest.approx(truth["rate"], rel=0.01)
    assert len(row["rotor_rates_hz"]) >= 2


def test_a_bird(tmp_path):
    """A bird approaching at 8 m/s at X band, flapping 6 Hz: a bird, its wingbeat within 0.5 %."""
    _, description, truth, row, _ = run_scene(2, tmp_path, "filtered")
    assert row["class"] == "bird", description
    assert row["wingbeat_freq_hz_status"] == "ok" and row["wingbeat_freq_hz"] == pytest.approx(truth["wb"], rel=0.005)


def test_a_body_velocity_without_range_where_one_alias_is_slow_enough(tmp_path):
    """A K-band rotor receding at 3 m/s sampled at 20 kHz: the span is 124 m/s, one alias of its Doppler lies under
    25 m/s; within 0.05 m/s."""
    _, description, truth, row, _ = run_scene(1, tmp_path, "filtered")
    assert row["body_velocity_mps_status"] == "ok", description
    assert row["body_velocity_mps"] == pytest.approx(truth["body_v"], abs=0.05)


def test_a_body_velocity_without_range_is_withheld_where_aliases_are_near(tmp_path):
    """A 77 GHz quadrotor receding at 4.9 m/s sampled at 3.6 kHz: its Doppler folds every 7 m/s and no range track
    tells which; withheld (read -2.3 m/s, `ok`, before)."""
    _, description, truth, row, _ = run_scene(55, tmp_path, "sampled")
    assert row["body_velocity_mps"] is None, description
    assert row["body_velocity_mps_status"] == "velocity_ambiguous"


def test_tips_folded_into_a_floor_that_reads_as_noise_leave_no_comb_unconfirmed(tmp_path):
    """Six 94 GHz rotors at 110-113 rev/s sampled at 6.9 kHz without a filter: their tips fold about 10 times over the
    span and fill it evenly, a floor read as noise 12 dB over the true noise; only a few lines near the body stand over
    it, 31.6 Hz apart. The span's +-5.5 m/s cannot hold a rotor's tips: the band counts as aliased and that comb as a
    folded one, which nothing confirms (a chopping of 31.6 Hz for 223, `ok`, before)."""
    _, description, truth, row, _ = run_scene(232, tmp_path, "sampled")
    assert row["class"] == "drone", description
    assert row["aliased"] is True
    assert row["chopping_freq_hz_status"] != "ok"


def test_a_rotation_read_where_the_span_cannot_hold_the_tips_is_not_stood_behind(tmp_path):
    """Four equal 3-blade rotors at 94 GHz sampled at 12.3 kHz without a filter: the span holds +-9.8 m/s, their tips
    reach 15 m/s at the least; read at half the chopping frequency, given as `undersampled`, not `ok`."""
    _, description, truth, row, _ = run_scene(17, tmp_path, "sampled")
    assert row["class"] == "drone", description
    assert row["chopping_freq_hz"] == pytest.approx(truth["chop"] / 2, rel=0.01)
    assert row["chopping_freq_hz_status"] == "undersampled" and row["rotation_rate_hz_status"] == "undersampled"


def test_wings_are_not_told_from_rotors_a_span_cannot_show(tmp_path):
    """Four 94 GHz rotors 1-4 % apart recorded through a filter at 11.8 kHz: all the span shows of them is their
    blades' inner parts, beating at 11.7 Hz: `none`, that beat `undersampled` (a bird, `ok`, before)."""
    _, description, truth, row, _ = run_scene(175, tmp_path, "filtered")
    assert row["class"] == "none", description
    assert row["wingbeat_freq_hz_status"] == "undersampled"


# ------------------------------------------------------------------ command line

def test_process_a_wav_from_the_command_line(tmp_path):
    _, _, truth, _, _ = run_scene(0, tmp_path, "filtered")
    with h5py.File(tmp_path / "s000_filtered.h5") as h5:
        z, fs, fc = h5["IQ"][()], h5.attrs["fs"], h5.attrs["fc"]
    counts = np.stack([z.real, z.imag], axis=1)
    wavfile.write(tmp_path / "rotor.wav", int(fs), np.round(counts / np.abs(counts).max() * 20000).astype(np.int16))
    runner = CliRunner()
    missing = runner.invoke(main, ["process", str(tmp_path / "rotor.wav"), "--out", str(tmp_path / "o1")])
    assert missing.exit_code == 2 and "supply it with --carrier-hz" in missing.output
    result = runner.invoke(main, ["process", str(tmp_path / "rotor.wav"), "--out", str(tmp_path / "o2"),
                                  "--carrier-hz", str(fc), "--blades", "2"])
    assert result.exit_code == 0, result.output
    assert "drone (CW, no range)" in result.output
    written = sorted(p.name for p in (tmp_path / "o2" / "rotor").iterdir() if not p.name.startswith("."))
    assert written == ["rotor.features.csv", "rotor.run.json", "rotor_spectrogram.png", "rotor_spectrum.png"]
    info = runner.invoke(main, ["info", str(tmp_path / "rotor.wav"), "--carrier-hz", str(fc)])
    assert info.exit_code == 0 and "I/Q WAV, int16" in info.output and "no range" in info.output
