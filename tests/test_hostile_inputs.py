"""Hostile inputs beyond the capture files: folders, outputs, configs, sweeps and options that once hung, replaced a
device, crashed or read a glitch as a target; each is now one line (or a warning) and the right exit code."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest
import yaml
from click.testing import CliRunner
from scipy.io import wavfile

from conftest import XBAND, scene_mapping, simulate
from mdpipe.cli import main
from mdpipe.errors import CaptureFormatError
from mdpipe.io.iq import read_iq
from mdpipe.params import ProcessParams
from mdpipe.process import impulses
from mdpipe.process.pipeline import process_capture
from mdpipe.simulate.scene import load_scene_mapping

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = ROOT / "data_samples"
MDPIPE = str(Path(sys.executable).parent / "mdpipe")


def run(*args, timeout=120):
    return subprocess.run([MDPIPE, *map(str, args)], capture_output=True, text=True, timeout=timeout)


def test_batch_refuses_a_fifo_and_a_device_among_its_inputs_without_hanging(tmp_path):
    folder = tmp_path / "in"
    folder.mkdir()
    shutil.copy(SAMPLES / "gull_flyby.h5", folder / "ok.h5")
    os.mkfifo(folder / "pipe.h5")
    os.symlink("/dev/zero", folder / "zero.h5")
    result = run("batch", folder, "--out", tmp_path / "out", "--no-figures", "-j", "1")
    assert result.returncode == 2 and "1 processed" in result.stdout
    assert f"failed: {folder / 'pipe.h5'}: is a FIFO; captures are read from regular files only" in result.stdout
    assert f"failed: {folder / 'zero.h5'}: is a character device; captures are read from regular files only" \
        in result.stdout


def test_fifo_config_and_fifo_output_are_refused(tmp_path):
    os.mkfifo(tmp_path / "scene.yaml")
    for command in (["simulate", "--config", tmp_path / "scene.yaml"], ["evaluate", tmp_path / "scene.yaml", "--out",
                                                                        tmp_path / "ev"]):
        result = run(*command, timeout=60)
        assert result.returncode == 2
        assert result.stderr.strip() == (f"Error: {tmp_path / 'scene.yaml'}: is a FIFO; scenes and sweeps are read from "
                                         "regular files only")
    os.mkfifo(tmp_path / "out.h5")
    result = run("simulate", "--config", ROOT / "configs" / "samples" / "gull_flyby.yaml", "-o", tmp_path / "out.h5",
                 "--force", timeout=60)
    assert result.returncode == 2 and "is a FIFO; --force replaces files only, choose another -o" in result.stderr
    assert (tmp_path / "out.h5").is_fifo()


def test_a_capture_named_like_the_batchs_own_files_is_refused(tmp_path):
    folder = tmp_path / "in"
    folder.mkdir()
    shutil.copy(SAMPLES / "gull_flyby.h5", folder / "features.csv.h5")
    result = CliRunner().invoke(main, ["batch", str(folder), "--out", str(tmp_path / "out"), "--no-figures"])
    assert result.exit_code == 1
    assert "would be published in OUT/features.csv/, a name of the batch's own files in OUT" in result.output
    (folder / "features.csv.h5").rename(folder / ".mdpipe-partial-a.h5")
    result = CliRunner().invoke(main, ["batch", str(folder), "--out", str(tmp_path / "out"), "--no-figures"])
    assert result.exit_code == 1 and "(or of its temporary ones, .mdpipe-partial-*)" in result.output


def test_batch_summary_holds_this_batchs_captures_and_names_the_others(tmp_path):
    folder, out = tmp_path / "in", tmp_path / "out"
    folder.mkdir()
    shutil.copy(SAMPLES / "phantom4_xband.h5", folder / "a.h5")
    shutil.copy(SAMPLES / "gull_flyby.h5", folder / "b.h5")
    assert CliRunner().invoke(main, ["batch", str(folder), "--out", str(out), "--no-figures", "-j", "1"]).exit_code == 0
    (folder / "b.h5").rename(folder / "gull.h5")
    result = CliRunner().invoke(main, ["batch", str(folder), "--out", str(out), "--no-figures", "-j", "1"])
    assert result.exit_code == 0
    assert "features.csv: 2 target rows from 2 captures (bird 1, drone 1)" in result.output
    assert "1 capture folder in" in result.output and "is not of this batch (earlier runs)" in result.output


def test_an_unreadable_table_fails_its_capture_in_the_summary_not_the_command(tmp_path):
    out = tmp_path / "out"
    assert CliRunner().invoke(main, ["process", str(SAMPLES / "gull_flyby.h5"), "--out", str(out),
                                     "--no-figures"]).exit_code == 0
    table = out / "gull_flyby" / "gull_flyby.features.csv"
    table.write_bytes(table.read_bytes() + b"\xff\xfe")
    result = CliRunner().invoke(main, ["summarize", str(out), "--no-figures"])
    assert result.exit_code == 2 and f"failed: {table}: its table cannot be read (" in result.output


def test_process_warns_before_replacing_another_inputs_outputs(tmp_path):
    for day, sample in (("day1", "gull_flyby.h5"), ("day2", "phantom4_xband.h5")):
        (tmp_path / day).mkdir()
        shutil.copy(SAMPLES / sample, tmp_path / day / "x.h5")
    run("process", tmp_path / "day1" / "x.h5", "--out", tmp_path / "out", "--no-figures")
    result = run("process", tmp_path / "day2" / "x.h5", "--out", tmp_path / "out", "--no-figures")
    assert result.returncode == 0
    assert (f"Warning: {tmp_path / 'out' / 'x'} held the outputs of {tmp_path / 'day1' / 'x.h5'}; now those of "
            f"{tmp_path / 'day2' / 'x.h5'}") in result.stderr


def sweep_with(tmp_path, edit, family_edit=None):
    """configs/sweeps/smoke.yaml with ``edit(sweep)`` and ``family_edit(family)`` on every family."""
    sweep = yaml.safe_load((ROOT / "configs" / "sweeps" / "smoke.yaml").read_text())
    edit(sweep)
    for family in sweep["families"].values():
        (family_edit or (lambda f: None))(family)
    path = tmp_path / "sweep.yaml"
    path.write_text(yaml.safe_dump(sweep))
    return path


def _nothing(sweep):
    pass


@pytest.mark.parametrize("edit, family_edit, message", [
    (_nothing, lambda f: f.update(weight="abc"), ".weight: must be a finite number > 0, got 'abc'"),
    (lambda s: s.update(seed=-1), None, "seed: must be an integer >= 0, got -1"),
    (lambda s: s["bands"].update(X="abc"), None, "bands: expected a mapping of band names to start frequencies in Hz"),
    (_nothing, lambda f: f["radar"].update(prf_hz=0), ".radar.prf_hz: must draw a finite number > 0, drew 0"),
    (_nothing, lambda f: f.setdefault("place", {}).update(range_m={"normal": [10, -1]}),
     ".place.range_m: normal takes [mean, sd] with sd >= 0, got [10, -1]"),
    (_nothing, lambda f: f.setdefault("place", {}).update(range_m={"randint": [0, 1e30]}),
     ".place.range_m: randint takes a list [a, b] of finite numbers"),
    (_nothing, lambda f: f.update(clutter={"count": 1}),
     ".clutter: expected a mapping with count, range_m and rcs_m2"),
])
def test_malformed_sweep_values_are_one_line_naming_the_key(tmp_path, edit, family_edit, message):
    result = CliRunner().invoke(main, ["evaluate", str(sweep_with(tmp_path, edit, family_edit)), "--out",
                                       str(tmp_path / "ev"), "--limit", "1"])
    assert result.exit_code == 2 and message in result.output and "internal error" not in result.output


def test_a_key_given_twice_in_a_scene_is_refused(tmp_path):
    path = tmp_path / "twice.yaml"
    path.write_text("seed: 1\nseed: 2\n")
    with pytest.raises(Exception, match=r"not valid YAML at line 2, column 1 \(duplicate key 'seed'\)"):
        load_scene_mapping(path)


@pytest.mark.parametrize("option, value, message", [
    ("--stft-window-s", "1e300", "stft_window_s=1e+300 must be at most 10000 s"),
    ("--false-alarm-probability", "5e-324", "false_alarm_probability=5e-324 must lie in [1e-12, 1)"),
    ("--threshold-db", "nan", "threshold_db=nan must lie in (0, 100] dB"),
    ("--threshold-db", "-inf", "threshold_db=-inf must lie in (0, 100] dB"),
    ("--blades", "1000000000000000000000", "is neither auto nor a whole number of blades from 1 to 12"),
    ("--doppler-limits", "-1e308,1e308", "must have LOW < HIGH within +-1e+07 Hz"),
])
def test_out_of_range_options_are_usage_errors(tmp_path, option, value, message):
    result = CliRunner().invoke(main, ["process", str(SAMPLES / "gull_flyby.h5"), "--out", str(tmp_path),
                                       f"{option}={value}"])
    assert result.exit_code == 1 and message in result.output and list(tmp_path.iterdir()) == []


def test_a_scene_beyond_the_adc_scale_and_a_blade_count_beyond_a_rotors_are_refused(tmp_path):
    scene = load_scene_mapping(ROOT / "configs" / "fimi.yaml")
    scene["targets"][0]["body_rcs_m2"] = 1e300
    path = tmp_path / "big.yaml"
    path.write_text(yaml.safe_dump(scene))
    result = run("simulate", "--config", path, "-o", tmp_path / "big.h5", "--chirps", "64", "--channels", "1")
    assert result.returncode == 2 and "the ADC would need 2.11e+145 V per count" in result.stderr
    scene["targets"][0]["body_rcs_m2"] = 0.01
    scene["targets"][0]["rotors"]["blades"] = 20000
    path.write_text(yaml.safe_dump(scene))
    result = run("simulate", "--config", path, "-o", tmp_path / "many.h5", "--chirps", "64", "--channels", "1")
    assert result.returncode == 2 and "targets[0].rotors.blades: must be from 1 to 12, got 20000" in result.stderr


def test_info_whose_reader_is_gone_exits_quietly():
    """stdout's reader closes it before anything is written (as `| head -1` does after its line): exit 141, silent."""
    process = subprocess.Popen([MDPIPE, "info", str(SAMPLES / "fimi_1rx.h5")], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE)
    process.stdout.close()
    assert process.wait(timeout=60) == 141 and process.stderr.read() == b""


def test_a_click_in_a_cw_recording_is_an_impulse_not_a_drone(tmp_path):
    """Complex noise with one sample 1000 times the noise's amplitude: every feature withheld as `impulse`, class
    none (a drone before)."""
    rng = np.random.default_rng(0)
    x = (rng.normal(size=20000) + 1j * rng.normal(size=20000)) / np.sqrt(2)
    x[7000] += 1000.0
    path = tmp_path / "click.h5"
    with h5py.File(path, "w") as h5:
        h5.attrs["fc"], h5.attrs["fs"] = 24e9, 20e3
        h5["IQ"] = np.stack([x.real, x.imag], -1)
    row = process_capture(path, ProcessParams()).rows[0]
    assert row["class"] == "none" and row["chopping_freq_hz_status"] == "impulse"
    assert "class: an impulse, not a target: this echo's 2 strongest samples and the 4 beside each stand" in row["notes"]
    assert impulses.impulse(x, 1.0).found
    x[7001:7004] += [300.0, 60.0, -20.0]  # ringing through the receiver's filter
    assert impulses.impulse(x, 1.0).found
    x[7000] += 1e5  # far stronger (in the mean of all samples, it would lift every other one)
    assert impulses.impulse(x, 1.0).found


def test_flashes_caught_in_a_few_samples_are_no_impulse():
    """Two flashes holding most of the power, twenty weaker ones over the noise beside them: a target (as a 94 GHz
    drone's flashes caught at their peaks by a CW receiver, tests/test_cw.py); the two alone: an impulse."""
    rng = np.random.default_rng(1)
    x = (rng.normal(size=4000) + 1j * rng.normal(size=4000)) / np.sqrt(2)
    x[[500, 2500]] += 300.0
    assert impulses.impulse(x, 1.0).found
    x[100::200] += 10.0
    reading = impulses.impulse(x, 1.0)
    assert not reading.found and reading.others_sigmas > impulses.MIN_EXCESS_SIGMAS


def test_a_chopping_frequency_the_dwell_holds_under_eight_times_is_withheld(tmp_path):
    """The Phantom 4 of paper config 7 (four 2-blade rotors at 70 rev/s, phases 0/37/71/113 deg) seen 8 ms: its four
    rotors flash about 1.46 ms apart within each 7.1 ms chopping period, a comb at 683 Hz read `ok` before; now
    `ambiguous_period` (a drone still). Seen 0.12 s (17 chopping periods), 140 Hz."""
    scene = load_scene_mapping(ROOT / "configs" / "paper" / "table1_config7.yaml")
    for chirps, expected in ((200, None), (3000, 140.0)):
        scene["radar"]["n_chirps"] = chirps
        path, _ = simulate(tmp_path, scene, f"p4_{chirps}.h5")
        row = process_capture(path, ProcessParams()).rows[0]
        assert row["class"] == "drone"
        if expected is None:
            assert row["chopping_freq_hz"] is None and row["chopping_freq_hz_status"] == "ambiguous_period"
        else:
            assert row["chopping_freq_hz"] == pytest.approx(expected, rel=0.005)


def test_a_wav_header_whose_frame_size_lies_is_refused(tmp_path):
    path = tmp_path / "iq.wav"
    wavfile.write(path, 20000, np.random.default_rng(0).normal(0, 1000, (2000, 2)).astype(np.int16))
    data = bytearray(path.read_bytes())
    fmt = data.index(b"fmt ")
    data[fmt + 20:fmt + 22] = (3).to_bytes(2, "little")  # block align 3 for 2 channels of 16 bits
    path.write_bytes(bytes(data))
    with pytest.raises(CaptureFormatError, match="declares 3 bytes a frame for 2 channel\\(s\\) of 16-bit samples "
                                                 "\\(4\\); the header is damaged or forged"):
        read_iq(path, overrides={"carrier_hz": 24e9})


def test_an_hdf5_recording_after_a_user_block_is_an_iq_recording(tmp_path):
    path = tmp_path / "matlab73.h5"
    with h5py.File(path, "w", userblock_size=512) as h5:
        h5.attrs["fc"], h5.attrs["fs"] = 24e9, 20e3
        h5["IQ"] = np.random.default_rng(0).normal(size=(20000, 2))
    row = process_capture(path, ProcessParams()).rows[0]
    assert row["wavelength_m"] == pytest.approx(299792458.0 / 24e9)


def test_evaluate_keeps_this_runs_captures_only(tmp_path):
    sweep = ROOT / "configs" / "sweeps" / "smoke.yaml"
    for limit in ("2", "1"):
        assert CliRunner().invoke(main, ["evaluate", str(sweep), "--out", str(tmp_path), "--limit", limit,
                                         "--keep-captures"]).exit_code == 0
    assert [p.name[:5] for p in (tmp_path / "captures").glob("*.h5")] == ["0000_"]
    assert (tmp_path / "captures" / "simulator.sha256").exists()  # the simulator's digest, for --reuse-captures


def test_scene_bounds_on_rotor_and_leaf_counts():
    radar = XBAND
    mapping = scene_mapping(radar, [{"type": "branch", "name": "b", "position_m": [20.0, 0.0, 0.0], "leaves": 5000}])
    from mdpipe.errors import ParameterError
    from mdpipe.simulate.scene import scene_from_mapping
    with pytest.raises(ParameterError, match=r"leaves: must be from 0 to 1000, got 5000"):
        scene_from_mapping(mapping)
