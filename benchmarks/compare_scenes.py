"""Two `mdpipe evaluate` runs of one sweep compared row by row: every column of their scenes.csv but the timings.

    python benchmarks/compare_scenes.py BEFORE/scenes.csv AFTER/scenes.csv

Prints each row (scene, target) that differs with the columns that moved, old -> new, and a count; exits 1 where any
row differs or the two runs hold other scenes, 2 where a file cannot be read. Used by `make evaluate-reuse` (a capture
processed again must score as it did) and to see what a processing change moved.
"""

import argparse
import sys

import numpy as np
import pandas as pd

IGNORED = ("simulate_s", "process_s", "reused")  # how long, and whether simulated: not what was read


def _number(value):
    """``value`` as a float where it reads as one (a column read as text in one file only), else None."""
    try:
        return float(value)
    except (TypeError, ValueError):
        return None


def _same(a, b):
    """Whether two cells hold the same value (NaN equal to NaN; numbers equal within 1e-12 relative)."""
    if pd.isna(a) and pd.isna(b):
        return True
    x, y = _number(a), _number(b)
    if x is not None and y is not None:
        return bool(np.isclose(x, y, rtol=1e-12, atol=0.0))
    return a == b


def differences(before, after):
    """Lines naming each row of ``after`` that differs from ``before`` (same scenes and targets, in order)."""
    columns = [c for c in before.columns if c in after.columns and c not in IGNORED]
    lines = []
    for (_, old), (_, new) in zip(before.iterrows(), after.iterrows()):
        moved = [f"{c}: {old[c]} -> {new[c]}" for c in columns if not _same(old[c], new[c])]
        if moved:
            lines.append(f"{old['scene']} {old['target']}: " + "; ".join(moved))
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before")
    parser.add_argument("after")
    args = parser.parse_args()
    try:
        before, after = pd.read_csv(args.before), pd.read_csv(args.after)
    except (OSError, ValueError) as exc:
        print(f"cannot read the two scenes.csv ({exc}); give two `mdpipe evaluate` runs' scenes.csv")
        return 2
    keys = ["scene", "target"]
    if not before[keys].equals(after[keys]) or (set(before.columns) ^ set(after.columns)) - set(IGNORED):
        print(f"{args.before} and {args.after} hold other scenes, targets or columns: not one sweep's runs")
        return 1
    lines = differences(before, after)
    print("\n".join(lines + [f"{len(lines)} of {len(after)} rows differ (timings aside)"]))
    return 1 if lines else 0


if __name__ == "__main__":
    sys.exit(main())
