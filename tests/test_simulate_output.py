"""`mdpipe simulate` output: sized before allocating, written under an exclusive temporary name, removed on
errors and signals, never overwriting without --force (never the config), with the umask's mode."""

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml
from click.testing import CliRunner

from conftest import as_from_a_terminal
from mdpipe.cli import main
from mdpipe.report.tables import atomic_write

MDPIPE = str(Path(sys.executable).parent / "mdpipe")
SCENE = {"radar": {"f_start_hz": 76e9, "f_stop_hz": 76.04e9, "ramp_up_s": 51.2e-6, "chirp_period_s": 64e-6,
                   "sample_rate_hz": 5e6, "n_samples": 256, "n_chirps": 64, "n_channels": 1},
         "noise": {"sigma_v": 1e-3},
         "targets": [{"type": "static", "name": "tree", "range_m": 11.0}]}


def config(tmp_path, **radar):
    path = tmp_path / "scene.yaml"
    path.write_text(yaml.safe_dump({**SCENE, "radar": {**SCENE["radar"], **radar}}))
    return path


def simulate(*args):
    result = CliRunner().invoke(main, ["simulate", *map(str, args)])
    assert "Traceback" not in result.output
    return result


def test_size_checked_before_anything_is_allocated(tmp_path):
    free = shutil.disk_usage(tmp_path).free
    result = simulate("--config", config(tmp_path), "-o", tmp_path / "big.h5", "--chirps", 10**12)
    size = 10**12 * 256 * 2
    assert result.exit_code == 2
    assert result.output.startswith(
        f"Error: {tmp_path / 'big.h5'}: the capture would take {size:,} bytes ({size / 2**30:.3g} GB: 1000000000000 "
        f"chirps x 256 samples x 1 RX x 2 B) but {tmp_path} has ")
    assert result.output.rstrip().endswith(" GB free; use fewer chirps (--chirps) or RX channels (--channels)")
    reported_free_gb = float(result.output.split(" has ")[1].split()[0])
    assert reported_free_gb == pytest.approx(free / 2**30, rel=0.05)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.yaml"]


def test_memory_checked_before_the_tracks_are_made(tmp_path):
    """100 000 chirps x (16 + 128 B) of body track for one target = 14.4 MB, and two int16 chunks of 512 chirps x 256
    samples = 0.5 MB: 14.9 MB, over a 0.01 GB budget."""
    result = simulate("--config", config(tmp_path), "-o", tmp_path / "c.h5", "--chirps", 100000,
                      "--max-memory-gb", 0.01)
    assert result.exit_code == 2 and result.output.strip() == (
        "Error: simulating would need about 0.0139 GB of memory (0.0134 GB of body tracks for 100000 chirps x 1 "
        "targets, 0.000488 GB of int16 chunk buffers), over the 0.01 GB budget; use fewer chirps (--chirps), "
        "RX channels (--channels) or targets, or raise --max-memory-gb")
    assert not (tmp_path / "c.h5").exists()


def test_existing_output_kept_without_force_and_config_never_overwritten(tmp_path):
    scene, out = config(tmp_path), tmp_path / "c.h5"
    out.write_bytes(b"precious")
    result = simulate("--config", scene, "-o", out)
    assert result.exit_code == 2 and result.output.strip() == f"Error: {out}: exists; pass --force to replace it"
    assert out.read_bytes() == b"precious"
    assert simulate("--config", scene, "-o", out, "--force").exit_code == 0
    assert out.read_bytes()[:8] == b"\x89HDF\r\n\x1a\n"
    before = scene.read_bytes()
    for args in (["-o", scene, "--force"], ["-o", tmp_path / "." / "scene.yaml", "--force"]):
        result = simulate("--config", scene, *args)
        assert result.exit_code == 2 and result.output.strip().endswith("is the config file itself; choose another -o")
    assert scene.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.h5", "scene.yaml"]


def test_missing_output_folder_is_one_line(tmp_path):
    out = tmp_path / "absent" / "c.h5"
    result = simulate("--config", config(tmp_path), "-o", out)
    assert result.exit_code == 2 and result.output.strip() == (
        f"Error: {out}: the folder {tmp_path / 'absent'} does not exist; create it or choose another -o")


def test_planted_symlink_at_the_old_temporary_name_is_not_followed(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_text("keep me")
    out = tmp_path / "c.h5"
    Path(str(out) + ".partial").symlink_to(victim)
    assert simulate("--config", config(tmp_path), "-o", out).exit_code == 0
    assert victim.read_text() == "keep me" and out.is_file() and not out.is_symlink()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.h5", "c.h5.partial", "scene.yaml", "victim.txt"]


def test_outputs_follow_the_umask(tmp_path):
    previous = os.umask(0o027)
    try:
        assert simulate("--config", config(tmp_path), "-o", tmp_path / "c.h5").exit_code == 0
        atomic_write(tmp_path / "t.csv", lambda tmp: Path(tmp).write_text("a\n"))
    finally:
        os.umask(previous)
    assert (tmp_path / "c.h5").stat().st_mode & 0o777 == 0o640
    assert (tmp_path / "t.csv").stat().st_mode & 0o777 == 0o640


@pytest.mark.parametrize("signum, code", [(signal.SIGTERM, 143), (signal.SIGINT, 130)])
def test_signal_mid_write_leaves_nothing(tmp_path, signum, code):
    """A 4-channel, 300 000-chirp capture (614 MB, several seconds); the signal comes once the temporary file exists."""
    out = tmp_path / "c.h5"
    proc = subprocess.Popen([MDPIPE, "simulate", "--config", str(config(tmp_path, n_channels=4)), "-o", str(out),
                             "--chirps", "300000"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=as_from_a_terminal)
    deadline = time.monotonic() + 60
    while not list(tmp_path.glob(".c.h5.*.partial")) and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.01)
    assert proc.poll() is None, "the simulation ended before the signal"
    time.sleep(0.3)
    proc.send_signal(signum)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == code and "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.yaml"]


def test_full_disk_mid_write_is_one_line_and_leaves_nothing(tmp_path, monkeypatch):
    def full(fd, data, offset):
        raise OSError(28, "No space left on device")
    monkeypatch.setattr(os, "pwrite", full)
    out = tmp_path / "c.h5"
    result = simulate("--config", config(tmp_path), "-o", out)
    assert result.exit_code == 2 and result.output.strip() == f"Error: {out}: cannot be written (No space left on device)"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.yaml"]
