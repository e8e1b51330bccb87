"""Files from the field are hostile: every class of tests/hostile.py is refused (one line, exit 2, no
traceback, nothing read from outside the file, no hang) or, for non-essential content, ignored with a note."""

import json
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest
from click.testing import CliRunner

import hostile
from mdpipe.cli import main
from mdpipe.errors import CaptureFormatError, ParameterError
from mdpipe.io import open_capture
from mdpipe.params import ProcessParams, RadarParams
from mdpipe.process import memory, ranging
from mdpipe.process.pipeline import process_capture
from mdpipe.report.tables import finite_json

MDPIPE = str(Path(sys.executable).parent / "mdpipe")
ALLOW = r"pass --allow-external for a trusted file"

REFUSED = [
    (hostile.external_link, rf"'/Chn1' is an external link to .*other\.h5:/Chn1; refused: it reads another file \({ALLOW}\)$"),
    (hostile.soft_link_dangling, r"'/Chn1' leads to '/nowhere', which does not exist \(a dangling link\)$"),
    (hostile.soft_link_out, rf"'/Chn1' is a soft link that leaves the file through '/ext', an external link to "
                            rf".*other\.h5:/; refused: it reads another file \({ALLOW}\)$"),
    (hostile.virtual_missing_source, rf"'/Chn1' is a virtual dataset reading .*missing\.h5; refused: it reads other "
                                     rf"files \({ALLOW}\)$"),
    (hostile.external_raw_passwd, rf"'/Chn1' keeps its samples outside the file, in /etc/passwd \(external raw "
                                  rf"storage\); refused \({ALLOW}\)$"),
    (hostile.external_raw_short, rf"'/Chn1' keeps its samples outside the file, in .*short\.raw \(external raw "
                                 rf"storage\); refused \({ALLOW}\)$"),
    (hostile.huge_declared_contiguous, r"'/Chn1' declares \(1000000000, 2048\) int16 \(4,096,000,000,000 bytes\) but "
                                       r"the file stores 0 bytes of it; the file is truncated or forged$"),
    (hostile.huge_declared_chunked, r"'/Chn1' declares \(1000000000, 2048\) int16 \(4,096,000,000,000 bytes\) in "
                                    r"15,625,000 chunks but stores 0 \(0 bytes\); the missing chunks would read as "
                                    r"invented fill values$"),
    (hostile.sparse_chunks, r"'/Chn1' declares \(128, 256\) int16 \(65,536 bytes\) in 8 chunks but stores 1 "
                            r"\(8,192 bytes\); the missing chunks would read as invented fill values$"),
    (hostile.compressed_huge_chunk, r"'/Chn1' is compressed in chunks of \(140000, 256\) \(71,680,000 bytes\), each "
                                    r"decoded whole; at most 67,108,864 bytes a chunk are read$"),
    (hostile.n_two_data, r"n_samples=2 must be a finite number in \[8, 65536\] \(samples per chirp: 8 to 65536\); "
                         r"attribute 'N', or override with --n$"),
    (hostile.fstop_inf, r"f_stop_hz=inf must be a finite number in \[1e\+08, 3e\+11\] Hz \(chirp stop frequency: "
                        r"100 MHz to 300 GHz\); attribute 'fStop', or override with --fstop$"),
    (hostile.fs_absurd, r"sample_rate_hz=1000000000000000.0 must be a finite number in \[1000, 1e\+09\] Hz \(ADC sample "
                        r"rate: 1 kHz to 1 GHz\); attribute 'fs', or override with --fs$"),
    (hostile.fusca_absurd, r"full_scale_v_per_lsb=1e\+300 must be a finite number in \[1e-12, 1000\] V/LSB \(volts per "
                           r"ADC count: 1 pV to 1 kV\); attribute 'FuSca'$"),
    (hostile.tp_absurd, r"chirp_period_s=1.8e\+19 must be a finite number in \[1e-07, 1\] s \(chirp repetition "
                        r"interval: 100 ns to 1 s\); attribute 'Tp', or override with --tp$"),
    (hostile.chn1_group, r"'/Chn1' is a group; every /ChnK must be a dataset \(n_chirps, N\)$"),
]


@pytest.mark.parametrize("build, message", REFUSED, ids=[b.__name__ for b, _ in REFUSED])
def test_hostile_capture_refused_with_one_line(tmp_path, build, message):
    path = build(tmp_path)
    with pytest.raises(CaptureFormatError, match=f"^{path}: {message}"):
        open_capture(path)
    result = CliRunner().invoke(main, ["process", str(path), "--no-figures", "--out", str(tmp_path / "out")])
    lines = result.stderr.strip().splitlines()
    assert result.exit_code == 2 and len(lines) == 1 and lines[0].startswith(f"Error: {path}: ")
    assert "Traceback" not in result.output


def test_external_raw_read_of_passwd_never_happens(tmp_path, monkeypatch):
    """The refusal comes before any sample is read: h5py's read is never called."""
    path = hostile.external_raw_passwd(tmp_path)
    monkeypatch.setattr(h5py.Dataset, "read_direct", lambda *a, **k: pytest.fail("read from outside the file"))
    monkeypatch.setattr(h5py.Dataset, "__getitem__", lambda *a, **k: pytest.fail("read from outside the file"))
    with pytest.raises(CaptureFormatError, match="external raw storage"):
        open_capture(path)


@pytest.mark.parametrize("build, message", [
    (hostile.external_raw_fifo, rf"'/Chn1' keeps its samples outside the file, in .*/pipe \(external raw storage\); "
                                rf"refused \({ALLOW}\)$"),
    (hostile.path_is_fifo, r"is a FIFO; captures are read from regular files only$"),
])
def test_fifo_refused_without_hanging(tmp_path, build, message):
    """In a separate process with a time limit: a FIFO that were opened would block forever."""
    path = build(tmp_path)
    for command in (["info", str(path), "--json"], ["process", str(path), "--out", str(tmp_path / "out")]):
        result = subprocess.run([MDPIPE, *command], capture_output=True, text=True, timeout=60)
        assert result.returncode == 2 and "Traceback" not in result.stderr
        assert __import__("re").fullmatch(f"Error: {path}: {message}", result.stderr.strip()), result.stderr


def test_fifo_as_external_storage_refused_even_when_allowed(tmp_path):
    path = hostile.external_raw_fifo(tmp_path)
    result = subprocess.run([MDPIPE, "info", str(path), "--allow-external"], capture_output=True, text=True,
                            timeout=60)
    assert result.returncode == 2
    assert result.stderr.strip() == f"Error: {tmp_path / 'pipe'}: is a FIFO; captures are read from regular files only"


def test_allow_external_reads_a_trusted_link_and_checks_external_sizes(tmp_path):
    path = hostile.external_link(tmp_path)
    with open_capture(path, allow_external=True) as cap:
        np.testing.assert_array_equal(cap.read_counts(0, 4)[0], hostile.noise_counts()[:4])
    result = CliRunner().invoke(main, ["process", str(path), "--allow-external", "--no-figures",
                                       "--out", str(tmp_path / "out")])
    assert result.exit_code == 0 and (tmp_path / "out" / "extlink" / "extlink.features.csv").exists()
    with pytest.raises(CaptureFormatError, match=r"'/Chn1' declares \(128, 256\) int16 \(65,536 bytes\) but its "
                                                 r"external files hold 4,096 bytes of it; the rest would read as "
                                                 r"invented zeros$"):
        open_capture(hostile.external_raw_short(tmp_path), allow_external=True)


def test_radar_parameter_override_is_checked_like_the_file(tmp_path):
    path = hostile.constant_value(tmp_path)
    result = CliRunner().invoke(main, ["info", str(path), "--tp", "1e300"])
    assert result.exit_code == 2 and result.output.strip() == (
        f"Error: {path}: chirp_period_s=1e+300 must be a finite number in [1e-07, 1] s (chirp repetition interval: "
        "100 ns to 1 s); attribute 'Tp', or override with --tp")


@pytest.mark.parametrize("field, value", [
    ("f_start_hz", 5e7), ("f_stop_hz", 4e11), ("ramp_up_s", 2.0), ("chirp_period_s", np.nan), ("ramp_down_s", -1e-6),
    ("sample_rate_hz", 2e9), ("n_samples", 4), ("n_channels", 257), ("full_scale_v_per_lsb", 0.0),
])
def test_radar_params_outside_their_range(field, value):
    good = dict(f_start_hz=76e9, f_stop_hz=76.04e9, ramp_up_s=51.2e-6, chirp_period_s=64e-6, sample_rate_hz=40e6,
                n_samples=2048)
    RadarParams(**good)
    with pytest.raises(ParameterError, match=rf"^{field}={value!r} must be a finite number in \["):
        RadarParams(**{**good, field: value})


NOTES = [
    (hostile.rxposn_group, "ignored /RxPosn: it is a group, not a dataset"),
    (hostile.rxposn_strings, "ignored /RxPosn: it holds |S1 values, not positions in m"),
    (hostile.rxposn_wrong_length, "ignored /RxPosn: it lists 5 positions for 1 channels"),
    (hostile.truth_invalid, "ignored /Truth: invalid JSON (Expecting property name enclosed in double quotes: "
                            "line 1 column 2 (char 1))"),
    (hostile.truth_deep, "ignored /Truth: JSON nested deeper than 32 levels"),
    (hostile.truth_wrong_type, "ignored /Truth: expected_json is a list, not an object"),
    (hostile.truth_dataset, "ignored /Truth: it is a dataset, not a group"),
    (hostile.rxposn_empty, "ignored /RxPosn: '/RxPosn' holds no data (an empty dataspace)"),
]


@pytest.mark.parametrize("build, note", NOTES, ids=[b.__name__ for b, _ in NOTES])
def test_malformed_optional_content_is_a_note(tmp_path, build, note):
    path = build(tmp_path)
    with open_capture(path) as cap:
        assert cap.warnings == [note] and cap.params.rx_positions_m == () and cap.truth is None
    result = process_capture(path, ProcessParams())
    assert result.rows[0]["notes"].endswith(note)
    info = CliRunner().invoke(main, ["info", str(path), "--json"])
    assert info.exit_code == 0 and json.loads(info.output)["warnings"] == [note]
    text = CliRunner().invoke(main, ["info", str(path)])
    assert text.exit_code == 0 and f"  note: {note}" in text.output


def test_optional_content_outside_the_file_is_not_read(tmp_path):
    other = hostile.write(tmp_path / "positions.h5", extra=lambda h5: h5.create_dataset("RxPosn", data=[0.5]))
    path = hostile.write(tmp_path / "cap.h5", extra=lambda h5: h5.__setitem__(
        "RxPosn", h5py.ExternalLink(str(other), "/RxPosn")))
    with open_capture(path) as cap:
        assert cap.params.rx_positions_m == ()
        assert cap.warnings == [f"ignored /RxPosn: '/RxPosn' is an external link to {other}:/RxPosn; refused: it "
                                "reads another file (pass --allow-external for a trusted file)"]


def test_truth_json_bounds():
    from mdpipe.io.radarlog import parse_json_bounded

    assert parse_json_bounded('{"a": [[1]], "s": "[[[[[[["}', max_depth=3) == {"a": [[1]], "s": "[[[[[[["}
    with pytest.raises(ValueError, match=r"^JSON nested deeper than 2 levels$"):
        parse_json_bounded('{"a": [[1]]}', max_depth=2)
    with pytest.raises(ValueError, match=r"^JSON holds Infinity$"):
        parse_json_bounded('{"a": Infinity}')


@pytest.mark.parametrize("build, value", [(hostile.constant_zero, 0), (hostile.constant_full_scale, 32767),
                                          (hostile.constant_value, 7), (hostile.fill_value_only, 7)])
def test_constant_data_is_no_signal(tmp_path, build, value):
    path = build(tmp_path)
    with pytest.raises(ParameterError, match=rf"^{path}: every sample read is {value} \(constant data, such as a fill "
                                             r"value\); the recording holds no signal$"):
        process_capture(path, ProcessParams())


def test_repeated_chirp_is_no_signal_but_one_varying_channel_is_signal(tmp_path):
    chirp = hostile.noise_counts(1)
    path = hostile.write(tmp_path / "repeat.h5", data=np.repeat(chirp, hostile.N_CHIRPS, axis=0))
    with pytest.raises(ParameterError, match=r"every chirp read repeats the same samples \(zero variance across "
                                             r"chirps in every channel\); the recording holds no signal$"):
        process_capture(path, ProcessParams())
    # chunks that are each constant but differ from one another vary across chirps
    steps = np.repeat(np.arange(hostile.N_CHIRPS // 32, dtype=np.int16), 32)[:, None] * np.ones(256, np.int16)
    process_capture(hostile.write(tmp_path / "steps.h5", data=steps), ProcessParams(chunk_chirps=32))
    two = hostile.write(tmp_path / "two.h5", attrs={"NrChn": 2}, extra=lambda h5: h5.create_dataset(
        "Chn2", data=np.zeros((hostile.N_CHIRPS, 256), np.int16)))
    assert process_capture(two, ProcessParams()).rows[0]["class"] == "none"


def test_info_json_is_strict_json(tmp_path):
    assert finite_json({"a": [float("inf"), np.float32("nan")], "b": (1.5, {"c": -np.inf})}) == \
        {"a": [None, None], "b": [1.5, {"c": None}]}
    path = hostile.write(tmp_path / "cap.h5", extra=lambda h5: h5.create_group("Truth").attrs.__setitem__(
        "expected_json", json.dumps({"targets": [], "snr_db": float("-inf")})))
    result = CliRunner().invoke(main, ["info", str(path), "--json"])
    assert result.exit_code == 0
    record = json.loads(result.output, parse_constant=lambda c: pytest.fail(f"{c} in info --json"))
    assert record["truth"] is None and record["warnings"] == ["ignored /Truth: JSON holds -Infinity"]


def test_gate_bin_counts_match_pass_one(tmp_path):
    path = hostile.write(tmp_path / "cap.h5")
    with open_capture(path) as cap:
        for zero_pad, min_m, max_m in [(1, 1.0, 200.0), (4, 0.0, 50.0), (16, 10.0, 30.0), (2, 3.0, 1e6)]:
            process = ProcessParams(zero_pad=zero_pad, min_range_m=min_m, max_range_m=max_m)
            stats = ranging.gate_statistics(cap, zero_pad=zero_pad, min_range_m=min_m,
                                            max_range_m=min(max_m, cap.params.max_range_m))
            assert memory.gate_bin_counts(cap.params, process) == (len(stats.range_m), len(stats.gate_bins))


def test_memory_plan_refuses_before_pass_one(tmp_path, monkeypatch):
    """N = 4096 over 1 GHz: c / (2 B) = 0.1499 m bins, 9.369 mm with --zero-pad 16, so the 1-200 m gate holds
    bins 107 ... 21348 = 21242 bins, and the range DFT matrix alone takes 40 B x 4096 x 21349 = 3.5 GB to build."""
    path = hostile.big_layout("n4096", n_samples=4096, n_channels=1, n_chirps=64, fs_hz=80e6)(tmp_path)
    monkeypatch.setattr(ranging, "gate_statistics", lambda *a, **k: pytest.fail("pass 1 ran"))
    step_m = 299792458 / (2 * 1e9) / 16
    assert (int(np.ceil(1.0 / step_m)), int(200.0 / step_m)) == (107, 21348)
    with pytest.raises(ParameterError, match=rf"^{path}: processing would need about 3\.\d\d GB \(pass 1 3\.\d\d GB "
                                             r"for 1 RX x 4096 samples x 21242 gate bins, 64 chirps\), over the 2 GB "
                                             r"budget; use --zero-pad 1 \(0\.\d\d GB\) or a shorter --max-range-m "
                                             r"\(21349 range bins up to 200 m\), or raise --max-memory-gb$"):
        process_capture(path, ProcessParams(zero_pad=16))
    result = CliRunner().invoke(main, ["process", str(path), "--zero-pad", "16", "--max-memory-gb", "0.5",
                                       "--no-figures", "--out", str(tmp_path / "out")])
    assert result.exit_code == 2 and "over the 0.5 GB budget" in result.stderr and "Traceback" not in result.output


def test_info_text_survives_truth_of_another_form(tmp_path):
    path = hostile.write(tmp_path / "cap.h5", extra=lambda h5: h5.create_group("Truth").attrs.__setitem__(
        "expected_json", json.dumps({"targets": [{"name": "x"}]})))
    result = CliRunner().invoke(main, ["info", str(path)])
    assert result.exit_code == 0 and result.output.rstrip().endswith(
        "  truth (simulated):\n  (not in the simulator's form: KeyError 'kind'; see info --json)")


def test_empty_range_gate_is_refused_before_pass_one(tmp_path):
    """3.747 m bins (c / 2B, B = 40 MHz): a 1-2 m gate holds none of them."""
    path = hostile.write(tmp_path / "cap.h5")
    result = CliRunner().invoke(main, ["process", str(path), "--max-range-m", "2", "--out", str(tmp_path / "out")])
    assert result.exit_code == 2 and result.stderr.strip() == (
        f"Error: {path}: the range gate [1, 2] m holds 0 bin(s) of 3.75 m; widen it")


@pytest.mark.parametrize("build", [hostile.tp_long_double, hostile.big_endian])
def test_unusual_but_valid_number_types_read_as_their_native_twins(tmp_path, build):
    """A long double attribute and big-endian samples read as a float and native int16 would: the same rows."""
    path = build(tmp_path)
    twin = hostile.write(tmp_path / "twin.h5")
    rows, twin_rows = (process_capture(p, ProcessParams()).rows for p in (path, twin))
    assert [r["notes"] for r in rows] == [r["notes"] for r in twin_rows]
    info = CliRunner().invoke(main, ["info", str(path), "--json"])
    assert info.exit_code == 0 and json.loads(info.output)["params"]["chirp_period_s"] == 64e-6


def test_samples_that_would_overflow_are_refused_before_any_arithmetic(tmp_path):
    """A float32 sample of 3e38 (its square overflows): one line when the chirps are read, no RuntimeWarning."""
    path = hostile.float_overflowing(tmp_path)
    result = subprocess.run([MDPIPE, "process", str(path), "--no-figures", "--out", str(tmp_path / "out")],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 2
    assert result.stderr.strip() == (f"Error: {path}: chirps 0..127 hold a sample of magnitude 3e+38, beyond any ADC's "
                                     "counts or volts (1e+12); the capture is corrupt")
