"""Full-size captures at the speed of the disk: mdpipe process against a bare h5py read, in one run.

Builds configs/fimi.yaml at full size (19,712 chirps x 2048 samples x 16 RX, 1.3 GB of int16) and a
capture twice as long, then for each (medians over --repeats, alternating, page cache as warm for
one as for the other): the bare read of the same sample datasets (h5py read_direct, 1024 rows a
call, into one reused buffer), `mdpipe process --no-figures` as a separate process, their ratio,
the peak RSS of that process, and the real-time factor (capture duration / process time). Then
simulate against a bare h5py write of the same array (benchmarks/bench_simulate.py).
"""

import argparse
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_simulate import child, full_size  # noqa: E402

BARE_READ = r"""
import sys, time, h5py, numpy as np
start = time.perf_counter()
with h5py.File(sys.argv[1], "r") as h5:
    sets = [h5[k] for k in h5 if k.startswith("Chn")]
    buffer = np.empty((1024, sets[0].shape[1]), sets[0].dtype)
    for ds in sets:
        for first in range(0, ds.shape[0], 1024):
            rows = min(1024, ds.shape[0] - first)
            ds.read_direct(buffer, np.s_[first:first + rows], np.s_[:rows])
print(time.perf_counter() - start)
"""


def measure(capture, out_dir, repeats):
    mdpipe = str(Path(sys.executable).parent / "mdpipe")
    reads, runs, peaks = [], [], []
    for _ in range(repeats):
        reads.append(child([sys.executable, "-c", BARE_READ, str(capture)])[0])
        wall, rss = child([mdpipe, "process", str(capture), "--out", str(out_dir), "--no-figures"])
        runs.append(wall)
        peaks.append(rss)
    return statistics.median(reads), statistics.median(runs), max(peaks)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workdir", default=tempfile.gettempdir(), help="where the 1.3 and 2.6 GB files go")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    work = Path(tempfile.mkdtemp(dir=args.workdir))
    mdpipe = str(Path(sys.executable).parent / "mdpipe")
    rows = []
    try:
        for label, chirps in (("full size", 19712), ("twice as long", 39424)):
            capture = work / f"fimi_{chirps}.h5"
            subprocess.run([mdpipe, "simulate", "--config", str(ROOT / "configs" / "fimi.yaml"), "-o", str(capture),
                            "--chirps", str(chirps)], check=True, capture_output=True)
            read, run, peak = measure(capture, work, args.repeats)
            duration = chirps * 64e-6
            rows.append((label, chirps, capture.stat().st_size / 1e9, read, run, peak, duration))
            capture.unlink()
        print(f"## mdpipe process against a bare read (medians of {args.repeats}; 2 cores)")
        print("| capture | chirps | GB | bare read (s) | mdpipe process (s) | ratio (target <= 3) | "
              "peak RSS (MB, target <= 512) | real-time factor (target >= 4) |")
        print("|---|---|---|---|---|---|---|---|")
        for label, chirps, gb, read, run, peak, duration in rows:
            print(f"| {label} | {chirps} | {gb:.2f} | {read:.2f} | {run:.2f} | {run / read:.2f} | {peak:.0f} | "
                  f"{duration / run:.2f} |")
        full_size(str(work), args.repeats)
    finally:
        shutil.rmtree(work)  # the captures and the output folders mdpipe process made


if __name__ == "__main__":
    main()
