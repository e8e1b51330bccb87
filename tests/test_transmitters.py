"""Chirps sent by transmitters in turn (a MIMO radar's time-division cycle): simulated by the transmitters' positions
and feeds, recorded as TxSeq, found on the static echoes when the file does not say, and read one transmitter at a
time."""

from pathlib import Path

import h5py
import numpy as np
import pytest
from click.testing import CliRunner

from conftest import RADARLOG_SMALL, XBAND, range_profiles, scene_mapping, simulate
from mdpipe.cli import main
from mdpipe.errors import ParameterError
from mdpipe.io import open_capture
from mdpipe.params import ProcessParams, transmit_cycle
from mdpipe.physics.radar import SPEED_OF_LIGHT_MPS
from mdpipe.process import interference, transmitters
from mdpipe.process.pipeline import process_capture
from mdpipe.simulate.scene import load_scene_mapping, scene_from_mapping

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = ROOT / "data_samples"
MIMO = ROOT / "configs" / "realism" / "mimo_two_tx.yaml"


def mimo_mapping(**radar):
    """The MIMO scene (configs/realism/mimo_two_tx.yaml) on 256 samples a chirp (the same 3.75 m range bins), its SNR
    per sample 9 dB up (the range FFT integrating 8 times fewer)."""
    mapping = load_scene_mapping(MIMO)
    mapping["radar"] |= {"n_samples": 256, "sample_rate_hz": 5.0e6} | radar
    mapping["noise"] = {"snr_db": mapping["noise"]["snr_db"] + 9.0}
    return mapping


def cycle_tests(path, cycles=(2, 3, 4)):
    """Pass 0 over ``path`` with its chirps summed by phase: the :class:`~mdpipe.process.transmitters.CycleTest` of
    each cycle."""
    with open_capture(path) as reader:
        sums = transmitters.PhaseSums(reader.params.n_samples)
        interference.common_mode(reader, phase_sums=sums)
    return {cycle: transmitters.cycle_test(sums, cycle) for cycle in cycles}


@pytest.mark.parametrize("sequence, cycle", [
    ([1], 1), ([1, 1], 1), ([2], 1), ([1, 2], 2), ([2, 1], 2), ([1, 2, 1, 2], 2), ([1, 2, 3], 3),
    ([1, 2, 3, 4], 4), ([1, 1, 2, 2], 4), ([1, 2, 1], 3)])
def test_transmit_cycle_is_the_sequences_shortest_repeat(sequence, cycle):
    assert transmit_cycle(sequence) == cycle


def test_a_transmitter_adds_its_path_as_a_receiver_there_would_and_its_feed_phase(tmp_path):
    """Virtual array: TX 2 at y = d with RX 1 sees a static point 20 deg off boresight as TX 1 with RX 2 at y = d
    does (the path 2 pi f0 d sin(theta) / c each way), times TX 2's feed, exp(j 40 deg)."""
    d = 0.02
    radar = XBAND | {"n_chirps": 64, "n_channels": 2, "rx_positions_m": [0.0, d], "tx_sequence": [1, 2],
                     "tx_positions_m": [0.0, d], "tx_phase_deg": [0.0, 40.0]}
    point = {"type": "static", "name": "post", "range_m": 30.0, "azimuth_deg": 20.0, "rcs_m2": 1.0}
    path, truth = simulate(tmp_path, scene_mapping(radar, [point]))
    with h5py.File(path) as h5:
        assert list(h5.attrs["TxSeq"]) == [1, 2]
    first, _ = range_profiles(path, channel=0)
    second, _ = range_profiles(path, channel=1)
    peak = int(np.argmax(np.abs(first[0])))
    tx1_rx2, tx2_rx1 = second[0, peak], first[1, peak]
    feed = np.exp(-1j * np.deg2rad(40.0))  # the range FFT of the real IF holds the conjugate phase
    assert tx2_rx1 == pytest.approx(tx1_rx2 * feed, rel=2e-3)
    path_rad = 2 * np.pi * XBAND["f_start_hz"] / SPEED_OF_LIGHT_MPS * d * np.sin(np.deg2rad(20.0))
    ratio = tx2_rx1 / first[0, peak]
    assert np.angle(ratio * np.conj(feed)) == pytest.approx(-(path_rad + np.pi) % (2 * np.pi) - np.pi, abs=2e-3)
    assert truth["radar"]["transmit_cycle"] == 2 and truth["radar"]["doppler_span_hz"] == pytest.approx(20e3)


def test_mimo_capture_is_read_one_transmitter_at_a_time_from_txseq_or_its_static_echoes(tmp_path):
    """The hovering FIMI drone (four 2-blade rotors at 80 rev/s) recorded in MIMO mode, 8192 chirps: read from the
    file's TxSeq, TX 1's chirps at 7812.5 Hz give the chopping within 0.1 % of 160 Hz; without TxSeq the cycle is
    found on the tree's echo and the row is the same."""
    path, truth = simulate(tmp_path, mimo_mapping(n_chirps=8192))
    assert truth["radar"]["doppler_span_hz"] == pytest.approx(7812.5)
    row = process_capture(path, ProcessParams()).rows[0]
    assert row["transmitters"] == 2 and row["prf_hz"] == pytest.approx(7812.5)
    assert "the chirps take 2 transmitters in turn (the file's TxSeq)" in row["notes"]
    assert row["class"] == "drone" and row["chopping_freq_hz"] == pytest.approx(160.0, rel=1e-3)
    with h5py.File(path, "r+") as h5:
        del h5.attrs["TxSeq"]
    found = process_capture(path, ProcessParams()).rows[0]
    assert found["transmitters"] == 2 and "(found: 2 static echoes change from chirp to chirp by" in found["notes"]
    assert found["chopping_freq_hz"] == row["chopping_freq_hz"]
    assert cycle_tests(path)[2].share > 0.1


@pytest.mark.parametrize("sequence", [[1, 2, 3], [1, 2, 3, 4]])
def test_cycles_of_three_and_four_read_from_txseq_and_shown_by_their_harmonics(tmp_path, sequence):
    """Three and four transmitters: read from TxSeq (``transmitters`` 3 or 4), and their static echoes change steadily
    at the cycle's harmonics alone (as a rotor's lines on every k PRF / 3 or k PRF / 4 would: not searched)."""
    mapping = mimo_mapping(n_chirps=2048, tx_sequence=sequence, tx_positions_m=[0.0, 0.0312, 0.0624, 0.0936],
                           tx_phase_deg=[0.0, 75.0, 150.0, 20.0])
    path, _ = simulate(tmp_path, mapping)
    row = process_capture(path, ProcessParams()).rows[0]
    assert row["transmitters"] == len(sequence) and row["prf_hz"] == pytest.approx(15625.0 / len(sequence))
    tests = cycle_tests(path)
    assert tests[len(sequence)].found and not tests[2].found


def test_an_adc_offset_takes_no_echo_from_the_cycle_test(tmp_path):
    """The MIMO capture (TxSeq deleted) with 1000 counts of ADC offset added: the cycle still found on the tree and the
    post (the offset's main lobe reaches range bin 1, where it had set the level the echoes are read against)."""
    path, _ = simulate(tmp_path, mimo_mapping(n_chirps=1536))
    with h5py.File(path, "r+") as h5:
        del h5.attrs["TxSeq"]
        h5["Chn1"][...] = np.clip(h5["Chn1"][()] // 16 + 1000, -32768, 32767).astype(np.int16)
    test = cycle_tests(path)[2]
    assert test.found and 1 not in [echo.bin for echo in test.echoes]


def test_no_cycle_on_one_transmitter_even_with_a_rotor_on_the_cycles_harmonics(tmp_path):
    """The bundled captures (one transmitter) show no cycle. Nor does a hovering rotor whose chopping lines fall on
    every multiple of PRF / 12 (2 blades at 50 rev/s, PRF 2.4 kHz: lines at 100 Hz steps, PRF / 12 = 200 Hz) about
    its steady body line: steady change at every harmonic, a cycle's at its own only."""
    for sample in ("fimi_1rx", "phantom4_xband", "gull_flyby", "clutter_only"):
        test = cycle_tests(SAMPLES / f"{sample}.h5")[2]
        assert not test.showing, sample
    radar = XBAND | {"chirp_period_s": 1 / 2400.0, "n_chirps": 4800}
    drone = {"type": "multirotor", "name": "stand", "motion": {"position_m": [30.0, 0.0, 0.0]}, "body_rcs_m2": 1.0,
             "rotors": {"count": 1, "arm_m": 0.0, "blades": 2, "blade_length_m": 0.12, "rev_per_s": [50.0],
                        "blade_rcs_m2": 0.5}}
    path, _ = simulate(tmp_path, scene_mapping(radar, [drone], noise={"snr_db": 10.0}))
    echo = cycle_tests(path)[2].echoes[0]
    assert echo.contrast > transmitters.MIN_CONTRAST and echo.share > transmitters.MIN_SHARE  # steady ...
    assert echo.purity < 3 and not echo.shows  # ... at every harmonic


def test_a_rotor_line_on_half_the_chirp_rate_is_no_cycle_but_a_note(tmp_path):
    """One transmitter: a hovering rotor at 120 rev/s sampled at 2.4 kHz puts a chopping line on PRF / 2 = 5 x 240 Hz
    and on no other k PRF / 12: its echo shows a cycle of 2 (it halved the chirp rate and lost the drone); with a
    clutter echo beside it that shows none, the chirps are read as they are, a note saying what to give."""
    radar = XBAND | {"chirp_period_s": 1 / 2400.0, "n_chirps": 4800}
    drone = {"type": "multirotor", "name": "stand", "motion": {"position_m": [30.0, 0.0, 0.0]}, "body_rcs_m2": 1.0,
             "rotors": {"count": 1, "arm_m": 0.0, "blades": 2, "blade_length_m": 0.12, "rev_per_s": [120.0],
                        "blade_rcs_m2": 0.5}}
    post = {"type": "static", "name": "post", "range_m": 60.0, "azimuth_deg": 10.0, "rcs_m2": 1.0}
    path, _ = simulate(tmp_path, scene_mapping(radar, [drone, post], noise={"snr_db": 10.0}))
    test = cycle_tests(path)[2]
    assert len(test.echoes) == 2 and len(test.showing) == 1 and not test.found
    row = process_capture(path, ProcessParams()).rows[0]
    assert row["transmitters"] == 1 and row["prf_hz"] == pytest.approx(2400.0) and row["class"] == "drone"
    assert "the static echo at 30 m changes from chirp to chirp, at half the chirp rate" in row["notes"]
    assert "give --transmitters 2" in row["notes"]


@pytest.mark.parametrize("value, problem", [
    (np.array([0, 1]), "whole transmitter numbers from 1 up"),
    (np.array([1.5, 2.0]), "whole transmitter numbers from 1 up"),
    (np.array([1.0, np.nan]), "whole transmitter numbers from 1 up"),
    (np.ones((2, 2), dtype=np.int64), "not a list of 1 to 64 transmitter numbers"),
    (np.arange(1, 100), "not a list of 1 to 64 transmitter numbers"),
    ("1 2", "not a list of 1 to 64 transmitter numbers"),
])
def test_malformed_txseq_is_ignored_with_a_warning(tmp_path, value, problem):
    path, _ = simulate(tmp_path, mimo_mapping(n_chirps=1024))
    with h5py.File(path, "r+") as h5:
        h5.attrs["TxSeq"] = value
    with open_capture(path) as reader:
        assert reader.tx_sequence == ()
        assert any(w.startswith("ignored attribute TxSeq: ") and problem in w for w in reader.warnings), reader.warnings


def test_one_transmitters_chirps_too_few_is_one_line_and_txseq_prefixed_is_read(tmp_path):
    radar = RADARLOG_SMALL | {"n_chirps": 100}
    point = {"type": "point", "name": "p", "motion": {"position_m": [20.0, 0.0, 0.0], "velocity_mps": [3.0, 0, 0]}}
    path, _ = simulate(tmp_path, scene_mapping(radar, [point]))
    with h5py.File(path, "r+") as h5:
        h5.attrs["Cfg_TxSeq"] = np.array([1, 2])
    with open_capture(path) as reader:
        assert reader.tx_sequence == (1, 2)
    with pytest.raises(ParameterError, match=r"50 chirp\(s\) of one transmitter; the analysis needs at least 64"):
        process_capture(path, ProcessParams())


def test_every_nth_chirp_read_from_either_layout(tmp_path):
    """``select_every``: the per-channel and the one-dataset (/Data) layouts read the same strided rows, Tp times
    the stride, the last chirp included."""
    path, _ = simulate(tmp_path, scene_mapping(RADARLOG_SMALL | {"n_chirps": 101, "n_channels": 2}, []))
    data = tmp_path / "data.h5"
    with h5py.File(path) as h5, h5py.File(data, "w") as out:
        out.attrs.update(dict(h5.attrs))
        out["Data"] = np.stack([h5["Chn1"][()], h5["Chn2"][()]], axis=1)
        stored = np.stack([h5["Chn1"][()], h5["Chn2"][()]])
    for capture in (path, data):
        with open_capture(capture) as reader:
            reader.select_every(3)
            assert reader.n_chirps == 34 and reader.params.chirp_period_s == pytest.approx(3 * 64e-6)
            np.testing.assert_array_equal(reader.read_counts(0, 34), stored[:, ::3])
            np.testing.assert_array_equal(reader.read_counts(33, 34)[:, 0], stored[:, 99])


@pytest.mark.parametrize("value", ["abc", "0", "17", "-2"])
def test_bad_transmitters_option_is_one_line(tmp_path, value):
    result = CliRunner().invoke(main, ["process", str(SAMPLES / "gull_flyby.h5"), "--out", str(tmp_path),
                                       "--transmitters", value])
    assert result.exit_code == 1 and "must be auto or a count from 1 to 16" in result.output
    assert len(result.output.strip().splitlines()) == 1


@pytest.mark.parametrize("radar, message", [
    ({"tx_sequence": [1, 3], "tx_positions_m": [0.0, 0.01]}, "tx_positions_m lists 2 entries for transmitters 1 to 3"),
    ({"tx_sequence": [0, 1]}, "transmitter numbers 1 to 16"),
    ({"tx_sequence": [1, 2] * 40}, "tx_sequence lists 80 chirps"),
    ({"tx_sequence": [1, 2], "tx_phase_deg": [0.0, float("nan")]}, r"tx_phase_deg\[1\]: expected a finite number"),
])
def test_bad_transmitter_layout_in_a_scene_is_refused(radar, message):
    with pytest.raises(ParameterError, match=message):
        scene_from_mapping(scene_mapping(XBAND | radar, []))
