"""Every hostile file class of tests/hostile.py through `mdpipe info` and `mdpipe process`: outcome and peak RSS.

Each run is a separate process with a time limit (--timeout) and an address-space limit (--limit-gb),
so a hang or a runaway allocation is reported instead of taking the machine. Prints one row per
(class, command): exit code, seconds, peak RSS (MB) and the last line of stderr (or of stdout).
With --plan: for the large layouts and the bundled samples, the memory plan of
mdpipe.process.memory against the peak RSS of `mdpipe process` run with the budget lifted.
"""

import argparse
import os
import resource
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

import hostile  # noqa: E402

# cases that are also memory plans (PLAN_CASES): class, builder, extra process options
N4096_ZERO_PAD_16 = ("N=4096, --zero-pad 16", hostile.n4096, ["--zero-pad", "16"])
N32768 = ("N=32768", hostile.n32768, [])
CH64 = ("64 channels x 2048", hostile.ch64, [])

CASES = [  # class, builder, extra process options
    ("external link", hostile.external_link, []),
    ("soft link dangling", hostile.soft_link_dangling, []),
    ("soft link out of the file", hostile.soft_link_out, []),
    ("VDS, missing source", hostile.virtual_missing_source, []),
    ("external raw /etc/passwd", hostile.external_raw_passwd, []),
    ("external raw FIFO", hostile.external_raw_fifo, []),
    ("external raw shorter than declared", hostile.external_raw_short, []),
    ("(1e9, 2048) declared, contiguous", hostile.huge_declared_contiguous, []),
    ("(1e9, 2048) declared, chunked", hostile.huge_declared_chunked, []),
    ("sparse chunks", hostile.sparse_chunks, []),
    ("gzip chunk of 72 MB", hostile.compressed_huge_chunk, []),
    ("N=2", hostile.n_two_data, []),
    ("fStop=inf", hostile.fstop_inf, []),
    ("fs=1e15", hostile.fs_absurd, []),
    ("FuSca=1e300", hostile.fusca_absurd, []),
    ("Tp=1.8e19", hostile.tp_absurd, []),
    ("--tp 1e300", hostile.constant_value, ["--tp", "1e300"]),
    ("/Chn1 a group", hostile.chn1_group, []),
    ("/RxPosn a group", hostile.rxposn_group, []),
    ("/RxPosn strings", hostile.rxposn_strings, []),
    ("/RxPosn wrong length", hostile.rxposn_wrong_length, []),
    ("/Truth invalid JSON", hostile.truth_invalid, []),
    ("/Truth 200k deep", hostile.truth_deep, []),
    ("/Truth a list", hostile.truth_wrong_type, []),
    ("/Truth a dataset", hostile.truth_dataset, []),
    ("all zeros", hostile.constant_zero, []),
    ("all 32767", hostile.constant_full_scale, []),
    ("all 7", hostile.constant_value, []),
    ("fill value only", hostile.fill_value_only, []),
    ("path is a FIFO", hostile.path_is_fifo, []),
    N4096_ZERO_PAD_16,
    N32768,
    ("2048 channels", hostile.ch2048, []),
    CH64,
]


def run(args, *, timeout_s, limit_bytes):
    """Run ``args``; returns (exit code or 'timeout', seconds, peak RSS MB, last output line)."""
    def limits():
        resource.setrlimit(resource.RLIMIT_AS, (limit_bytes, limit_bytes))

    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        start = time.perf_counter()
        proc = subprocess.Popen(args, stdout=out, stderr=err, preexec_fn=limits, start_new_session=True)
        code = None
        while time.perf_counter() - start < timeout_s:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                code = os.waitstatus_to_exitcode(status)
                break
            time.sleep(0.02)
        if code is None:
            os.killpg(proc.pid, signal.SIGKILL)
            _, _, usage = os.wait4(proc.pid, 0)
            code = "timeout"
        proc.returncode = 0
        seconds = time.perf_counter() - start
        err.seek(0)
        out.seek(0)
        lines = err.read().decode(errors="replace").strip().splitlines() or \
            out.read().decode(errors="replace").strip().splitlines() or [""]
    traceback = any(line.startswith("Traceback") for line in lines)
    return code, seconds, usage.ru_maxrss / 1024, ("[traceback] " if traceback else "") + lines[-1][:150]


PLAN_CASES = [N4096_ZERO_PAD_16, ("N=4096", hostile.n4096, []), N32768, CH64]


def plan_table(args, mdpipe, tmp):
    from mdpipe.io import open_capture
    from mdpipe.params import ProcessParams
    from mdpipe.process import memory

    print("\n| capture | plan MB (pass 1 / pass 2 / peak) | measured peak RSS MB | exit | s |\n|---|---|---|---|---|")
    samples = [(p.name, lambda folder, p=p: p, []) for p in sorted((ROOT / "data_samples").glob("*.h5"))]
    for index, (name, build, options) in enumerate(PLAN_CASES + samples):
        folder = Path(tmp) / f"plan{index}"
        folder.mkdir()
        path = str(build(folder))
        with open_capture(path) as reader:
            # the plan mdpipe itself makes (within the 64 GB budget of the run below, it is returned)
            plan = memory.check_memory(reader, ProcessParams(zero_pad=int(options[1]) if options else 1,
                                                             max_memory_gb=64))
        code, seconds, rss, _ = run([mdpipe, "process", path, "--no-figures", "--out", str(folder / "out"),
                                     "--max-memory-gb", "64", *options], timeout_s=args.timeout,
                                    limit_bytes=int(args.limit_gb * 2**30))
        mb = {key: value / 2**20 for key, value in plan.items()}
        print(f"| {name} | {mb['pass 1']:.0f} / {mb['pass 2']:.0f} / {mb['peak']:.0f} | {rss:.0f} | {code} | "
              f"{seconds:.1f} |", flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--timeout", type=float, default=60.0)
    parser.add_argument("--limit-gb", type=float, default=4.0)
    parser.add_argument("--only", help="run the classes whose name contains this")
    parser.add_argument("--plan", action="store_true", help="the memory plan against measured peaks instead")
    args = parser.parse_args()
    mdpipe = str(Path(sys.executable).parent / "mdpipe")
    if args.plan:
        with tempfile.TemporaryDirectory() as tmp:
            plan_table(args, mdpipe, tmp)
        return
    print(f"| class | command | exit | s | peak RSS MB | last line |\n|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for index, (name, build, options) in enumerate(CASES):
            if args.only and args.only not in name:
                continue
            folder = Path(tmp) / str(index)
            folder.mkdir()
            path = str(build(folder))
            for command in (["info", path, "--json"], ["process", path, "--no-figures", "--out", str(folder / "out")]):
                extra = options if command[0] == "process" or options[:1] == ["--tp"] else []
                code, seconds, rss, line = run([mdpipe, *command, *extra], timeout_s=args.timeout,
                                               limit_bytes=int(args.limit_gb * 2**30))
                print(f"| {name} | {command[0]} | {code} | {seconds:.1f} | {rss:.0f} | {line} |", flush=True)


if __name__ == "__main__":
    main()
