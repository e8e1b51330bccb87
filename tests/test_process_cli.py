"""mdpipe process / summarize through CliRunner: outputs, JSON, bad input, batches with a bad file."""

import json
import shutil
from pathlib import Path

import h5py
import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

from mdpipe.cli import main

SAMPLES = Path(__file__).resolve().parents[1] / "data_samples"
ATTRS = {"fStrt": 76e9, "fStop": 76.04e9, "TRampUp": 51.2e-6, "Tp": 64e-6, "fs": 5e6, "N": 256, "NrChn": 1}
REQUIRED_JSON = ["file", "range_m", "class", "doppler_bw_hz", "doppler_bw_mps", "chopping_freq_hz", "rotation_rate_hz",
                 "rotation_period_s", "blade_length_m", "body_velocity_mps", "wingbeat_freq_hz", "aliased", "snr_db",
                 "notes"]


def write_capture(path, data, **attrs):
    with h5py.File(path, "w") as h5:
        for key, value in {**ATTRS, **attrs}.items():
            h5.attrs[key] = value
        h5["Chn1"] = data
    return path


def test_process_samples_json_and_outputs(tmp_path):
    result = CliRunner().invoke(main, ["process", str(SAMPLES / "phantom4_xband.h5"), str(SAMPLES / "gull_flyby.h5"),
                                       "--out", str(tmp_path), "--json"])
    assert result.exit_code == 0, result.output
    records = [json.loads(line) for line in result.stdout.strip().splitlines()]
    assert [r["class"] for r in records] == ["drone", "bird"]
    for record in records:
        assert list(record)[:len(REQUIRED_JSON)] == REQUIRED_JSON
        assert record["mdpipe_version"]
    assert records[0]["rotation_rate_hz"] == pytest.approx(70.0, rel=0.005)
    assert records[0]["blade_length_m"] == pytest.approx(0.13, rel=0.03)
    assert records[1]["blade_length_m"] is None and records[1]["wingbeat_freq_hz"] == pytest.approx(3.0, rel=0.03)
    for stem in ("phantom4_xband", "gull_flyby"):
        for suffix in (".features.csv", ".run.json", "_range.png", "_spectrogram.png", "_spectrum.png"):
            assert (tmp_path / stem / f"{stem}{suffix}").stat().st_size > 0
    table = pd.read_csv(tmp_path / "phantom4_xband" / "phantom4_xband.features.csv")
    # beta not given: r rests on beta = 0 assumed, and the row says so
    assert table.loc[0, "class"] == "drone" and pd.isna(table.loc[0, "elevation_deg"])
    assert table.loc[0, "blade_length_m_status"] == "assumed_blades" and records[0]["n_blades_source"] == "assumed"
    run = json.loads((tmp_path / "phantom4_xband" / "phantom4_xband.run.json").read_text())
    assert run["process_params"]["threshold_db"] == 20.0 and run["radar"]["n_samples"] == 64
    assert not list(tmp_path.rglob(".mdpipe-partial-*"))  # no temporary files left behind


def test_parameters_reach_the_output(tmp_path):
    result = CliRunner().invoke(main, ["process", str(SAMPLES / "phantom4_xband.h5"), "--out", str(tmp_path), "--json",
                                       "--blades", "3", "--elevation-deg", "30", "--threshold-db", "15",
                                       "--stft-window-s", "0.004", "--no-figures"])
    record = json.loads(result.stdout)
    assert record["n_blades"] == 3 and record["elevation_deg"] == 30 and record["threshold_db"] == 15
    assert record["stft_window_s"] == pytest.approx(0.004, rel=0.02)
    # the Phantom's 2 blades flash once per chopping period: an odd N = 3 contradicts the echo, so the
    # 140 Hz chopping stands but no rotation rate (nor r) is derived from the wrong count
    assert record["chopping_freq_hz"] == pytest.approx(140.0, rel=0.005)
    assert record["rotation_rate_hz"] is None and record["rotation_rate_hz_status"] == "blade_conflict"
    assert record["blade_length_m"] is None and record["blade_length_m_status"] == "no_rotation"
    assert not list(tmp_path.rglob("*.png"))


@pytest.mark.parametrize("make, message", [
    (lambda p: p.write_text("not hdf5"), r"not a readable HDF5 file"),
    (lambda p: write_capture(p, np.zeros((100, 256), np.int32)), r"samples are int32; Radarlog samples must be int16"),
    (lambda p: write_capture(p, np.zeros((100, 200), np.int16)), r"attribute N=256 but chirps hold 200 samples"),
    (lambda p: write_capture(p, np.zeros((0, 256), np.int16)), r"the capture holds no chirps"),
    (lambda p: write_capture(p, np.ones((1, 256), np.int16)), r"1 chirp\(s\); the analysis needs at least 64"),
    (lambda p: write_capture(p, np.zeros((100, 256), np.int16)), r"every sample read is 0 \(constant data, such as a fill value\); the recording holds no signal$"),
    (lambda p: write_capture(p, np.full((100, 256), np.nan, np.float32)), r"hold NaN or Inf samples"),
])
def test_bad_input_is_one_line_and_exit_2(tmp_path, make, message):
    path = tmp_path / "bad.h5"
    make(path)
    result = CliRunner().invoke(main, ["process", str(path), "--out", str(tmp_path / "out")])
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("Error: ") and "Traceback" not in result.output
    assert __import__("re").search(message, lines[0])
    assert (tmp_path / "out" / "bad" / "bad.error.txt").exists()


def test_missing_attribute_names_the_override(tmp_path):
    data = np.random.default_rng(0).normal(0, 100, (128, 256)).astype(np.int16)
    path = write_capture(tmp_path / "no_tp.h5", data)
    with h5py.File(path, "a") as h5:
        del h5.attrs["Tp"]
    result = CliRunner().invoke(main, ["process", str(path), "--out", str(tmp_path)])
    assert result.exit_code == 2 and "supply it with --tp 64e-6" in result.stderr
    result = CliRunner().invoke(main, ["process", str(path), "--out", str(tmp_path), "--tp", "64e-6"])
    assert result.exit_code == 0 and "none" in result.output


def test_clipped_capture_is_flagged(tmp_path):
    rng = np.random.default_rng(1)
    t = np.arange(256) / 5e6
    chirps = 40000 * np.cos(2 * np.pi * 2.1e5 * t + 0.3 * np.arange(256)[:, None] / 256 * np.arange(256))[:, :256]
    data = np.clip(chirps + rng.normal(0, 50, chirps.shape), -32768, 32767).astype(np.int16)
    path = write_capture(tmp_path / "clipped.h5", data)
    result = CliRunner().invoke(main, ["process", str(path), "--out", str(tmp_path), "--json", "--no-figures"])
    assert result.exit_code == 0, result.output
    assert "sit at the int16 full scale (clipped)" in json.loads(result.stdout.splitlines()[0])["notes"]


def test_batch_folder_with_a_corrupt_file(tmp_path):
    folder = tmp_path / "captures"
    (folder / "day2").mkdir(parents=True)
    shutil.copy(SAMPLES / "phantom4_xband.h5", folder / "a_phantom.h5")
    shutil.copy(SAMPLES / "gull_flyby.h5", folder / "day2" / "gull.h5")
    (folder / "b_corrupt.h5").write_bytes((SAMPLES / "phantom4_xband.h5").read_bytes()[:4000])
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["process", str(folder), "--out", str(out), "--no-figures"])
    assert result.exit_code == 2
    assert "b_corrupt.h5: the HDF5 file is truncated" in result.stderr
    assert (out / "a_phantom" / "a_phantom.features.csv").exists()  # the others finished
    assert (out / "day2" / "gull" / "gull.features.csv").exists()
    summary = CliRunner().invoke(main, ["summarize", str(out), "--no-figures"])
    assert summary.exit_code == 2
    assert "2 target rows from 2 captures (bird 1, drone 1); 1 failed" in summary.output
    assert "failed: " in summary.output and "b_corrupt.h5" in summary.output
    gathered = pd.read_csv(out / "features.csv")
    assert sorted(gathered["class"]) == ["bird", "drone"]
