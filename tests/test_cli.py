"""The command line through click's CliRunner: good paths, and bad input as one line with exit code 2."""

import json

import h5py
import numpy as np
import yaml
from click.testing import CliRunner

from mdpipe.cli import main

SMALL = {"radar": {"f_start_hz": 76e9, "f_stop_hz": 76.04e9, "ramp_up_s": 51.2e-6, "chirp_period_s": 64e-6,
                   "sample_rate_hz": 5e6, "n_samples": 256, "n_chirps": 64, "n_channels": 2},
         "noise": {"snr_db": 10.0},
         "targets": [{"type": "multirotor", "name": "quad", "motion": {"position_m": [6.0, 0, 0]},
                      "rotors": {"count": 4, "blade_length_m": 0.1, "rev_per_s": 80}},
                     {"type": "static", "name": "tree", "range_m": 11.0}]}


def write_config(tmp_path, data, name="scene.yaml"):
    path = tmp_path / name
    path.write_text(yaml.safe_dump(data))
    return path


def test_simulate_then_info(tmp_path):
    config = write_config(tmp_path, SMALL)
    out = tmp_path / "cap.h5"
    result = CliRunner().invoke(main, ["simulate", "--config", str(config), "-o", str(out), "--chirps", "32",
                                       "--channels", "3", "--snr-db", "0", "--seed", "4"])
    assert result.exit_code == 0, result.output
    assert "wrote" in result.output and "32 chirps x 256 samples x 3 RX" in result.output
    with h5py.File(out) as h5:
        assert h5["Chn3"].shape == (32, 256) and yaml.safe_load(h5["Truth"].attrs["scene_yaml"])["seed"] == 4
    info = CliRunner().invoke(main, ["info", str(out)])
    assert info.exit_code == 0, info.output
    for text in ["canonical", "range bin 3.747 m", "Doppler span 15625 Hz", "quad (multirotor)",
                 "chopping 160.0 Hz", "tree (static)", "0.002048 s"]:
        assert text in info.output
    as_json = json.loads(CliRunner().invoke(main, ["info", str(out), "--json"]).output)
    assert as_json["derived"]["n_channels"] == 3 and as_json["truth"]["targets"][0]["rotation_rate_hz"] == 80.0


def test_default_output_name(tmp_path, monkeypatch):
    config = write_config(tmp_path, SMALL, "myscene.yaml")
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(main, ["simulate", "--config", str(config)])
    assert result.exit_code == 0 and (tmp_path / "myscene.h5").exists()


def test_bad_configs_one_line_exit_2(tmp_path):
    cases = [
        ({**SMALL, "radar": {**SMALL["radar"], "n_samplez": 3}}, "Error: radar.n_samplez: unknown key"),
        ({**SMALL, "radar": {**SMALL["radar"], "n_chirps": "lots"}}, "Error: radar.n_chirps: expected an integer, got 'lots'"),
        ({k: v for k, v in SMALL.items() if k != "radar"}, "Error: radar: missing"),
        ({**SMALL, "targets": [{**SMALL["targets"][0], "rotors": {"count": 4, "blade_length_m": -1, "rev_per_s": 80}}]},
         "Error: targets[0].rotors.blade_length_m: must be > 0, got -1.0"),
    ]
    for data, message in cases:
        result = CliRunner().invoke(main, ["simulate", "--config", str(write_config(tmp_path, data)), "-o",
                                           str(tmp_path / "x.h5")])
        assert result.exit_code == 2, result.output
        assert result.output.strip().splitlines() == [result.output.strip()] and message in result.output
        assert "Traceback" not in result.output
        assert not (tmp_path / "x.h5").exists()


def test_info_on_bad_file_and_override(tmp_path):
    bad = tmp_path / "junk.h5"
    bad.write_bytes(b"\x00" * 100)
    result = CliRunner().invoke(main, ["info", str(bad)])
    assert result.exit_code == 2 and "junk.h5: not a readable HDF5 file" in result.output
    path = tmp_path / "no_tp.h5"
    with h5py.File(path, "w") as h5:
        for k, v in {"fStrt": 76e9, "fStop": 76.04e9, "TRampUp": 51.2e-6, "fs": 5e6, "N": 256, "NrChn": 1}.items():
            h5.attrs[k] = v
        h5["Chn1"] = np.zeros((10, 256), np.int16)
    result = CliRunner().invoke(main, ["info", str(path)])
    assert result.exit_code == 2 and "supply it with --tp 64e-6" in result.output
    result = CliRunner().invoke(main, ["info", str(path), "--tp", "100e-6"])
    assert result.exit_code == 0 and "Doppler span 10000 Hz" in result.output
