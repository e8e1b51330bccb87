"""Tables of an evaluation: class confusion, per-feature coverage and errors, rotation coverage by band and blade
profile, confidently wrong values, wrong classes.

Everything here reads the scored records (one per scene x target, see :mod:`mdpipe.evaluate.run`).
"""

import numpy as np
import pandas as pd

from mdpipe.evaluate.scoring import CONFIDENTLY_WRONG, COVERED, FEATURES, LINE_SNR_DB

CLASSES = ("drone", "bird", "none")
WORST_LISTED = 15


def flag(column):
    """A record column of flags as bools: True only where it holds True or "True" (a column read back from a CSV may
    hold strings, or NaN where a record had no value); NaN and anything else are False."""
    def true(value):
        return value is True or value is np.True_ or (isinstance(value, str) and value == "True")

    return column.map(true).astype(bool)


def records_frame(records):
    """The records as a DataFrame, one row per scene x target (the columns of ``scenes.csv``)."""
    return pd.DataFrame.from_records(records)


def confusion(frame):
    """Counts of expected class (rows) x measured class (columns)."""
    measured = list(CLASSES) + sorted(set(frame["measured_class"]) - set(CLASSES))
    table = pd.crosstab(frame["expected_class"], frame["measured_class"])
    return table.reindex(index=list(CLASSES), columns=measured, fill_value=0)


def feature_table(frame):
    """Per feature: estimable cases, confident values among them (coverage), verdict counts and the
    error quantiles of the confident values on estimable cases (%)."""
    rows = []
    for feature in FEATURES:
        verdict = frame[f"{feature}_verdict"]
        estimable = flag(frame[f"{feature}_estimable"])
        confident = verdict.isin(COVERED)
        errors = frame.loc[confident, f"{feature}_error"].dropna().to_numpy() * 100
        quantiles = np.percentile(errors, [50, 90]).tolist() + [errors.max()] if len(errors) else [np.nan] * 3
        rows.append({"feature": feature, "estimable": int(estimable.sum()), "confident": int(confident.sum()),
                     "coverage_%": 100 * confident.sum() / estimable.sum() if estimable.sum() else np.nan,
                     "right": int((verdict == "right").sum()), "wrong": int((verdict == "wrong").sum()),
                     "unwarranted": int((verdict == "unwarranted").sum()),
                     "withheld": int((verdict == "withheld").sum()), "missed": int((verdict == "missed").sum()),
                     "err_median_%": quantiles[0], "err_90_%": quantiles[1], "err_max_%": quantiles[2]})
    return pd.DataFrame(rows)


def coverage_grid(frame, feature, *, rows, columns, order=None):
    """Coverage of ``feature`` over the cases where it is estimable, split by two record columns: each cell
    ``confident / estimable``, with a last row and column over all; cells without an estimable case are empty, and a
    missing key reads ``-`` (a column sorted first). Rows in the order of ``order`` (a record column: its mean per row
    key, falling; keys without a value last), else sorted; None where the feature is estimable nowhere."""
    estimable = frame[flag(frame[f"{feature}_estimable"])].fillna({rows: "-", columns: "-"})
    if not len(estimable):
        return None
    confident = estimable[f"{feature}_verdict"].isin(COVERED)

    def cell(mask):
        return f"{int(confident[mask].sum())} / {int(mask.sum())}" if mask.any() else ""

    row_keys = (sorted(estimable[rows].unique()) if order is None else
                list(estimable.groupby(rows)[order].mean().sort_values(ascending=False, kind="stable").index))
    column_keys = sorted(estimable[columns].unique())
    grid = [{rows: key, **{c: cell((estimable[rows] == key) & (estimable[columns] == c)) for c in column_keys},
             "all": cell(estimable[rows] == key)} for key in row_keys]
    grid.append({rows: "all", **{c: cell(estimable[columns] == c) for c in column_keys},
                 "all": cell(pd.Series(True, index=estimable.index))})
    return pd.DataFrame(grid, columns=[rows, *column_keys, "all"])


def confidently_wrong(frame):
    """Every confidently wrong value: scene, family, feature, truth, value, verdict, why (the truth's reason
    when not estimable), relative error in %; the largest error first, values without a truth last."""
    parts = []
    for feature in FEATURES:
        bad = frame[frame[f"{feature}_verdict"].isin(CONFIDENTLY_WRONG)]
        parts.append(pd.DataFrame({
            "scene": bad["scene"], "family": bad["family"], "band": bad["band"], "target": bad["target"],
            "feature": feature, "truth": bad[f"{feature}_truth"], "value": bad[f"{feature}_value"],
            "verdict": bad[f"{feature}_verdict"], "why": bad[f"{feature}_why"],
            "error_%": bad[f"{feature}_error"] * 100}))
    wrong = pd.concat(parts, ignore_index=True)
    return wrong.sort_values(["error_%"], ascending=False, na_position="last").reset_index(drop=True)


def class_seen(frame):
    """True where a measurement can tell the record's class: its blade or wing lines are ``detectable``, or it is
    expected none (bool Series)."""
    return flag(frame["detectable"]) | (frame["expected_class"] == "none")


CLASS_EVIDENCE = {"drone": "chopping_freq_hz_status", "bird": "wingbeat_freq_hz_status"}


def wrong_classes(frame):
    """The targets whose class a measurement can tell (:func:`class_seen`) read as another, a capture the processing
    failed on aside (listed with the failed captures): scene, family, band, target, expected and measured class, the
    blade or wing lines' SNR in the body's bin (dB; -inf for a target without such lines, NaN for an extra
    detection) and the status of what tells the expected class (a drone's chopping, a bird's wingbeat:
    ``evidence_status``; ``not_detected`` where no row was matched to the target, empty for the rest); drones first,
    then birds, then the rest."""
    bad = frame[class_seen(frame) & ~flag(frame["class_ok"]) & (frame["measured_class"] != "error")]

    def evidence_of(row):
        column = CLASS_EVIDENCE.get(row["expected_class"])
        if column is None:
            return ""
        status = row.get(column)
        return status if isinstance(status, str) else "not_detected"

    evidence = [evidence_of(row) for _, row in bad.iterrows()]
    order = bad["expected_class"].map({c: i for i, c in enumerate(CLASSES)})
    columns = ["scene", "family", "band", "target", "expected_class", "measured_class", "micro_line_snr_db",
               "evidence_status"]
    return (bad.assign(_order=order, evidence_status=evidence).sort_values(["_order", "scene"])[columns]
            .reset_index(drop=True))


def causes(wrong):
    """Confidently wrong values grouped by feature, verdict, family and the truth's reason."""
    if not len(wrong):
        return pd.DataFrame(columns=["feature", "verdict", "family", "why", "count"])
    grouped = wrong.fillna({"why": ""}).groupby(["feature", "verdict", "family", "why"]).size()
    return grouped.rename("count").reset_index().sort_values("count", ascending=False).reset_index(drop=True)


def _markdown(frame, floatfmt="{:.3g}"):
    cells = [[floatfmt.format(v) if isinstance(v, float) else str(v) for v in row] for row in frame.itertuples(index=False)]
    header = [str(c) for c in frame.columns]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return "\n".join(lines + ["| " + " | ".join(row) + " |" for row in cells])


def report(frame, *, title, wall_s, jobs):
    """The summary as markdown text (printed and written to ``summary.md``)."""
    subjects = frame[frame["target"] == "subject"]
    matrix = confusion(frame)
    class_right = int(flag(frame["class_ok"]).sum())
    seen_right = flag(frame.loc[class_seen(frame), "class_ok"])
    wrong = confidently_wrong(frame)
    table = feature_table(frame)
    grid = coverage_grid(subjects, "rotation_rate_hz", rows="band", columns="blade_profile", order="wavelength_m")
    per_scene = subjects.drop_duplicates("scene")
    failed = subjects[subjects["error"].fillna("") != ""]
    lines = [f"# {title}", "",
             f"{len(per_scene)} scenes ({', '.join(f'{k} {v}' for k, v in per_scene['family'].value_counts().items())}), "
             f"{len(frame) - len(subjects)} extra detections; {len(failed)} captures failed.",
             "", "## Class (rows: expected, columns: measured; extra detections are expected none)", "",
             _markdown(matrix.reset_index().rename(columns={"expected_class": "expected"})), "",
             f"Classes right: {class_right} / {len(frame)} ({100 * class_right / len(frame):.1f} %); "
             f"{seen_right.sum()} / {len(seen_right)} ({100 * seen_right.mean():.1f} %) of the targets whose "
             f"class-telling echo a measurement can see (blade or wing lines >= {LINE_SNR_DB:g} dB above the noise) "
             "and of those expected none.", "",
             "## Features (coverage = confident / estimable; errors of confident values on estimable cases)", "",
             _markdown(table), "",
             "## Rotation rate by band and blade profile (confident / estimable)", "",
             ("estimable in no scene" if grid is None else _markdown(grid)), "",
             f"## Confidently wrong: {len(wrong)} values "
             f"({int((wrong['verdict'] == 'wrong').sum())} more than 10 % off, "
             f"{int((wrong['verdict'] == 'unwarranted').sum())} where the truth says not estimable), "
             f"plus {len(frame) - class_right} wrong classes", ""]
    if len(wrong):
        lines += ["By cause:", "", _markdown(causes(wrong)), "", f"Worst {min(WORST_LISTED, len(wrong))}:", "",
                  _markdown(wrong.head(WORST_LISTED)), ""]
    misread = wrong_classes(frame)
    if len(misread):
        lines += [f"## Wrong classes where the class-telling echo is seen: {len(misread)}", "",
                  _markdown(misread), ""]
    if len(failed):
        lines += [f"## Failed captures: {len(failed)}", "", _markdown(failed[["scene", "family", "error"]]), ""]
    lines += ["## Timings", "",
              f"wall {wall_s:.1f} s with -j {jobs}; per scene simulate median {subjects['simulate_s'].median():.2f} s "
              f"(total {subjects['simulate_s'].sum():.1f} s), process median {subjects['process_s'].median():.2f} s "
              f"(total {subjects['process_s'].sum():.1f} s); largest capture {int(subjects['n_chirps'].max())} chirps"
              + (f"; {int(subjects['reused'].sum())} of {len(subjects)} captures reused (--reuse-captures)."
                 if "reused" in subjects and subjects["reused"].any() else "."),
              ""]
    return "\n".join(lines)
