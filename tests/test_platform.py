"""Without os.pwrite (Windows) mdpipe still imports, and simulate fails in one line naming the platform."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = """
import os, sys
del os.pwrite
from click.testing import CliRunner
from mdpipe.cli import main
result = CliRunner().invoke(main, ["simulate", "--config", sys.argv[1], "-o", sys.argv[2], "--chirps", "64"])
sys.stdout.write(f"{result.exit_code}\\n{result.output}")
"""


def test_simulate_without_pwrite_is_one_line(tmp_path):
    out = subprocess.run([sys.executable, "-c", SCRIPT, str(ROOT / "configs" / "samples" / "clutter_only.yaml"),
                          str(tmp_path / "x.h5")], capture_output=True, text=True, check=True, cwd=tmp_path)
    code, *lines = out.stdout.splitlines()
    assert code != "0"
    assert lines == ["Error: writing a capture needs os.pwrite, which this platform lacks (Windows): run mdpipe "
                     "simulate on Linux, macOS or WSL (reading and processing do not need it)"]
    assert not list(tmp_path.glob("x.h5*"))
