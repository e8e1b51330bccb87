"""A folder of captures: one `mdpipe process` per capture, two at a time (what `make -j2 batch` ran before
`mdpipe batch`), against `mdpipe batch -j 2` (one process pool: the imports paid once per worker).

Both end with the folder's features.csv and summary.png, both with and without the per-capture figures.
Wall time, median of --repeats, the two ways alternating so that both see the same load. Then the cost of
the manifest's content hash (SHA-256, streamed) per GB.

    python benchmarks/bench_batch.py [--inputs data_samples] [--baseline-src DIR]

``--baseline-src`` runs the per-capture way with another checkout's mdpipe (e.g. `git archive` of an older
commit unpacked in DIR); by default both ways use this one.
"""

import argparse
import hashlib
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MAIN = "import sys; from mdpipe.cli import main; sys.argv[0] = 'mdpipe'; main()"


def mdpipe(args, src=None):
    env = {**os.environ, "PYTHONPATH": str(src)} if src else None
    return subprocess.run([sys.executable, "-c", MAIN, *map(str, args)], env=env, stdout=subprocess.DEVNULL,
                          stderr=subprocess.DEVNULL, check=False)


def per_capture(captures, out, figures, src):
    """The old make rule: `mdpipe process CAPTURE --out OUT` for each capture, two at a time, then summarize."""
    extra = [] if figures else ["--no-figures"]
    with ThreadPoolExecutor(2) as pool:
        list(pool.map(lambda c: mdpipe(["process", c, "--out", out, *extra], src), captures))
    no_figure = "--no-figure" if src else "--no-figures"  # the option's name before `mdpipe batch`
    mdpipe(["summarize", out, *([] if figures else [no_figure])], src)


def batch(inputs, out, figures):
    mdpipe(["batch", inputs, "--out", out, "-j", "2", *([] if figures else ["--no-figures"])])


def timed(run):
    start = time.perf_counter()
    run()
    return time.perf_counter() - start


def hash_cost_s_per_gb(work_dir, size_bytes=256 << 20):
    path = Path(work_dir) / "hash.bin"
    with open(path, "wb") as fh:
        for _ in range(size_bytes >> 20):
            fh.write(os.urandom(1 << 20))
    times = []
    for _ in range(3):
        start = time.perf_counter()
        digest = hashlib.sha256()
        with open(path, "rb") as fh:
            for block in iter(lambda: fh.read(1 << 20), b""):
                digest.update(block)
        times.append(time.perf_counter() - start)
    path.unlink()
    return statistics.median(times) * (1 << 30) / size_bytes


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--inputs", type=Path, default=ROOT / "data_samples")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--baseline-src", type=Path, help="checkout whose mdpipe runs the per-capture way")
    args = parser.parse_args()
    captures = sorted(args.inputs.rglob("*.h5"))
    print(f"{len(captures)} captures in {args.inputs}, {sum(c.stat().st_size for c in captures) / 1e6:.1f} MB; "
          f"{os.cpu_count()} CPUs; median of {args.repeats}\n")
    print("| figures | per-capture `mdpipe process`, 2 at a time | `mdpipe batch -j 2` | speed-up |")
    print("|---|---|---|---|")
    with tempfile.TemporaryDirectory() as work:
        for figures in (True, False):
            old, new = [], []
            for i in range(args.repeats):
                for way, times in ((lambda o: per_capture(captures, o, figures, args.baseline_src), old),
                                   (lambda o: batch(args.inputs, o, figures), new)):
                    out = Path(work) / f"out{i}"
                    times.append(timed(lambda: way(out)))
                    shutil.rmtree(out)
            a, b = statistics.median(old), statistics.median(new)
            print(f"| {'yes' if figures else 'no'} | {a:.2f} s | {b:.2f} s | {a / b:.2f}x |")
        print(f"\nmanifest content hash (SHA-256, 1 MiB blocks, page cache warm): "
              f"{hash_cost_s_per_gb(work):.2f} s per GB")


if __name__ == "__main__":
    main()
