"""One CLI convention: exit codes, option names and help, inputs, --json without files, no silent clamping,
numbers for people at their resolution."""

import json
import os
import shutil
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

from mdpipe.batch import unit
from mdpipe.cli import _summary_line, main
from mdpipe.report import tables

SAMPLES = Path(__file__).resolve().parents[1] / "data_samples"


def invoke(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_every_option_of_every_command_has_help():
    missing = [f"{name} {param.opts[0]}" for name, command in main.commands.items() for param in command.params
               if isinstance(param, click.Option) and not (param.help or "").strip()]
    assert missing == []


def test_same_option_names_across_commands():
    options = {name: {opt for p in command.params if isinstance(p, click.Option) for opt in p.opts}
               for name, command in main.commands.items()}
    for name in ("process", "batch", "summarize"):
        assert "--no-figures" in options[name], name
    assert not any("--no-figure" in opts for opts in options.values())
    shared = options["process"] - {"--json"}
    assert shared <= options["batch"]  # every process option, declared once


@pytest.mark.parametrize("command", ["simulate", "info", "process", "batch", "summarize", "paper"])
def test_usage_errors_exit_1(command):
    result = invoke(command, "--bogus-option")
    assert result.exit_code == 1 and "No such option" in result.output and "--bogus-option" in result.output


@pytest.mark.parametrize("args, message", [
    (["--zero-pad", "0"], "Invalid value for '--zero-pad': 0 is not in the range 1<=x<=16."),
    (["--min-range-m", "300"], "Error: min_range_m=300.0 must lie in [0, max_range_m=200.0)"),
])
def test_bad_option_values_exit_1(tmp_path, args, message):
    result = invoke("process", SAMPLES / "gull_flyby.h5", "--out", tmp_path, *args)
    assert result.exit_code == 1 and message in result.output
    assert list(tmp_path.iterdir()) == []


def test_unmatched_pattern_is_one_line_and_writes_nothing(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = invoke("process", "*.h5")
    assert result.exit_code == 1
    assert result.output == "Error: *.h5: no such file or folder (a shell pattern that matched no file?)\n"
    assert list(tmp_path.iterdir()) == []


def test_folder_without_captures_is_a_usage_error(tmp_path):
    result = invoke("batch", tmp_path, "--out", tmp_path / "out")
    assert result.exit_code == 1
    assert result.output == f"Error: {tmp_path}: no *.h5 or *.hdf5 capture in this folder or below it\n"


def test_two_inputs_for_one_output_folder_are_refused(tmp_path):
    for sub in ("a", "b"):
        (tmp_path / sub).mkdir()
        shutil.copy(SAMPLES / "gull_flyby.h5", tmp_path / sub / "x.h5")
    result = invoke("process", tmp_path / "a/x.h5", tmp_path / "b/x.h5", "--out", tmp_path / "out")
    assert result.exit_code == 1
    assert result.output == (f"Error: {tmp_path / 'a/x.h5'} and {tmp_path / 'b/x.h5'} would both be published in "
                             "OUT/x/; give the folder that holds both instead of the files\n")
    assert invoke("process", tmp_path, "--out", tmp_path / "out", "--no-figures").exit_code == 0
    assert (tmp_path / "out/a/x/x.features.csv").exists() and (tmp_path / "out/b/x/x.features.csv").exists()


def test_json_writes_no_files_unless_out_is_given(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = invoke("process", SAMPLES / "gull_flyby.h5", "--json")
    assert result.exit_code == 0 and json.loads(result.stdout)["class"] == "bird"
    assert list(tmp_path.iterdir()) == []
    result = invoke("process", SAMPLES / "gull_flyby.h5", "--json", "--out", "o", "--no-figures")
    assert result.exit_code == 0 and (tmp_path / "o/gull_flyby/gull_flyby.features.csv").exists()


def test_a_window_longer_than_the_dwell_is_adjusted_and_said(tmp_path):
    # phantom4_xband: 6250 chirps at Tp = 40 us, a 0.25 s dwell; the window is at most half of it, 0.125 s
    result = invoke("process", SAMPLES / "phantom4_xband.h5", "--json", "--stft-window-s", 10)
    record = json.loads(result.stdout)
    assert record["stft_window_s"] == pytest.approx(0.125, abs=1e-12)
    assert ("spectrogram window 10 s asked, 0.125 s used (the window spans 8 chirps to half the dwell of 0.25 s"
            in record["notes"])
    plain = json.loads(invoke("process", SAMPLES / "phantom4_xband.h5", "--json", "--stft-window-s", 0.004).stdout)
    assert "spectrogram window" not in plain["notes"]  # 100 chirps exactly: no adjustment, no note


def test_numbers_for_people_at_their_resolution():
    # velocity to the Doppler resolution 1 / dwell: lambda / (2 dwell) = 0.0304 / 6 = 0.0051 m/s for 3 s
    row = {"file": "g.h5", "class": "bird", "range_m": 15.0, "snr_db": 18.9, "body_velocity_mps": 0.0007980956,
           "wavelength_m": 0.030435782538071065, "dwell_s": 3.0}
    assert _summary_line(row).endswith("v 0.001 m/s")
    assert _summary_line({**row, "dwell_s": 0.25}).endswith("v 0.00 m/s")  # 0.061 m/s resolution, no "-0.00"
    assert tables.to_resolution(-0.0007, 0.061) == "0.00"
    assert tables.to_resolution(0.0007981, 1e-300) == "0.0007981"  # an absurd dwell: no 300 decimals
    record = json.loads(invoke("process", SAMPLES / "phantom4_xband.h5", "--json").stdout)
    assert record["prf_hz"] == 25000.0  # 1 / 40e-6 in doubles is 24999.999999999996


def test_ctrl_c_exits_130_and_leaves_nothing_half_written(tmp_path, monkeypatch):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(unit, "process_capture", interrupted)
    result = invoke("process", SAMPLES / "gull_flyby.h5", "--out", tmp_path)
    assert result.exit_code == 130 and result.output == "Interrupted.\n"
    assert sorted(os.listdir(tmp_path)) == [".mdpipe.lock"]
