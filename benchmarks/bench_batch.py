"""A folder of captures: one `mdpipe process` per capture, two at a time (what `make -j2 batch` ran before
`mdpipe batch`), against `mdpipe batch -j 2` (one process pool: the imports paid once per worker).

Both end with the folder's features.csv and summary.png, both with and without the per-capture figures.
Wall time, median of --repeats, the two ways alternating so that both see the same load. Then the cost of
the manifest's content hash (SHA-256, streamed) per GB.

    python benchmarks/bench_batch.py [--inputs data_samples] [--baseline-commit REV]

The per-capture way runs with this checkout's mdpipe and, with ``--baseline-commit``, once more with the
mdpipe of commit REV (its ``mdpipe/`` unpacked by ``git archive`` into a temporary folder; the
interpreter runs with -P, so the checkout's own folder does not shadow it).
"""

import argparse
import io
import os
import shutil
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from mdpipe.batch import manifest

ROOT = Path(__file__).resolve().parents[1]
# What the console script runs: ``run`` (``main`` for commits before it).
MAIN = "import sys; import mdpipe.cli as cli; sys.argv[0] = 'mdpipe'; getattr(cli, 'run', cli.main)()"


def mdpipe(args, src=None):
    env = {**os.environ, "PYTHONPATH": str(src)} if src else None
    return subprocess.run([sys.executable, "-P", "-c", MAIN, *map(str, args)], env=env, stdout=subprocess.DEVNULL,
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


def unpack_mdpipe(commit, into):
    """``mdpipe/`` of ``commit`` of this repository, unpacked in ``into``; returns ``into``."""
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", commit, "mdpipe"], capture_output=True, check=True)
    with tarfile.open(fileobj=io.BytesIO(archive.stdout)) as tar:
        tar.extractall(into, filter="data")
    return Path(into)


def compare(captures, inputs, work, repeats, src, label):
    """Print one table row per figures setting: the per-capture way (mdpipe of ``src``) against the batch."""
    for figures in (True, False):
        old, new = [], []
        for i in range(repeats):
            for way, times in ((lambda o: per_capture(captures, o, figures, src), old),
                               (lambda o: batch(inputs, o, figures), new)):
                out = Path(work) / f"out{i}"
                times.append(timed(lambda: way(out)))
                shutil.rmtree(out)
        a, b = statistics.median(old), statistics.median(new)
        print(f"| {label} | {'yes' if figures else 'no'} | {a:.2f} s | {b:.2f} s | {a / b:.2f}x |")


def timed(run):
    start = time.perf_counter()
    run()
    return time.perf_counter() - start


def hash_cost_s_per_gb(work_dir, size_bytes=256 << 20):
    path = Path(work_dir) / "hash.bin"
    with open(path, "wb") as fh:
        for _ in range(size_bytes >> 20):
            fh.write(os.urandom(1 << 20))
    times = [timed(lambda: manifest.fingerprint(path)) for _ in range(3)]  # the manifest's own hash
    path.unlink()
    return statistics.median(times) * (1 << 30) / size_bytes


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--inputs", type=Path, default=ROOT / "data_samples")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--baseline-commit", metavar="REV",
                        help="also time the per-capture way with the mdpipe of this commit")
    args = parser.parse_args()
    captures = sorted(args.inputs.rglob("*.h5"))
    print(f"{len(captures)} captures in {args.inputs}, {sum(c.stat().st_size for c in captures) / 1e6:.1f} MB; "
          f"{os.cpu_count()} CPUs; median of {args.repeats}\n")
    print("| per-capture way run with | figures | per-capture `mdpipe process`, 2 at a time | `mdpipe batch -j 2` "
          "| speed-up |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as work:
        compare(captures, args.inputs, work, args.repeats, None, "this mdpipe")
        if args.baseline_commit:
            src = unpack_mdpipe(args.baseline_commit, Path(work) / "baseline")
            compare(captures, args.inputs, work, args.repeats, src, f"mdpipe of {args.baseline_commit}")
        print(f"\nmanifest content hash (manifest.fingerprint: SHA-256, {manifest.HASH_BLOCK_BYTES >> 20} MiB blocks, "
              "page cache warm): "
              f"{hash_cost_s_per_gb(work):.2f} s per GB")


if __name__ == "__main__":
    main()
