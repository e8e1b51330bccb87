"""Reproduce the paper's Tables IV and V: simulate each Table I / II configuration, process it, compare.

Three numbers per quantity: what the paper reports, what the physics predicts for the simulated scene
(Eq. 6 bandwidth, 1 / f_rot, N f_rot, the true r and f_rot; for birds the model's largest
instantaneous micro-Doppler spread and 1 / f_beat), and what mdpipe measures.
"""

from pathlib import Path

import numpy as np
import pandas as pd

from mdpipe.params import ProcessParams
from mdpipe.process.pipeline import process_capture
from mdpipe.simulate.run import simulate_to_file
from mdpipe.simulate.scene import load_scene_mapping, scene_from_mapping, scene_to_yaml

# Table IV (configs 1-4, 6, 7; config 5 is "not possible to measure"): BW in kHz, T_c in ms,
# chopping in Hz, r in cm, omega_p in rev/s.
TABLE_IV = {
    1: {"bw_spectrogram_hz": 8000, "bw_spectrum_hz": 8000, "rotation_period_s": 12.2e-3, "chopping_hz": 160.0,
        "blade_length_m": 0.11, "rotation_rate_hz": 81.3},
    2: {"bw_spectrogram_hz": 8200, "bw_spectrum_hz": 8100, "rotation_period_s": 14.3e-3, "chopping_hz": 140.6,
        "blade_length_m": 0.14, "rotation_rate_hz": 69.93},
    3: {"bw_spectrogram_hz": 17300, "bw_spectrum_hz": 17100, "rotation_period_s": 7.1e-3, "chopping_hz": 277.3,
        "blade_length_m": 0.14, "rotation_rate_hz": 140.0},
    4: {"bw_spectrogram_hz": 6750, "bw_spectrum_hz": 6550, "rotation_period_s": 14.2e-3, "chopping_hz": 140.6,
        "blade_length_m": 0.14, "rotation_rate_hz": 69.89},
    5: {},
    6: {"bw_spectrogram_hz": 25250, "bw_spectrum_hz": 25200, "rotation_period_s": 10e-3, "chopping_hz": 199.2,
        "blade_length_m": 0.2665, "rotation_rate_hz": 100.0},
    7: {"bw_spectrogram_hz": 8100, "bw_spectrum_hz": 8000, "rotation_period_s": 14.3e-3, "chopping_hz": 140.6,
        "blade_length_m": 0.144, "rotation_rate_hz": 69.93},
}
# Table V: BW from the spectrogram (Hz), wingbeat period (s).
TABLE_V = {"a": (163.0, 1.97), "b": (156.8, 1.98), "c": (288.0, 1.01), "d": (161.6, 1.0), "e": (217.6, 1.97),
           "f": (294.4, 0.996)}

DRONE_QUANTITIES = [  # name, paper key, physics (from truth), mdpipe key
    ("BW spectrogram (Hz)", "bw_spectrogram_hz", lambda t: t["doppler_bw_hz"], "doppler_bw_spectrogram_hz"),
    ("BW power spectrum (Hz)", "bw_spectrum_hz", lambda t: t["doppler_bw_hz"], "doppler_bw_hz"),
    ("T_c (s)", "rotation_period_s", lambda t: t["rotation_period_s"], "rotation_period_s"),
    ("chopping frequency (Hz)", "chopping_hz", lambda t: t["chopping_freq_hz"], "chopping_freq_hz"),
    ("r estimated (m)", "blade_length_m", lambda t: t["blade_length_m"], "blade_length_m"),
    ("omega_p estimated (rev/s)", "rotation_rate_hz", lambda t: t["rotation_rate_hz"], "rotation_rate_hz"),
]

EXPLANATIONS = {
    "BW spectrogram (Hz)": (
        "mdpipe reads the flash edges (half amplitude of the broadside blade's rectangular spectrum), which sit on "
        "Eq. 6; the paper's spectrogram extent is read by eye above a display threshold, which the sinc flash and "
        "the window widen: its values run 10-16 % above Eq. 6 (config 4: 81 %, see below). In config 4 (Gamma = 26.7) "
        "the tips span 3.3 Doppler bins a side of a quarter chopping period and 6.7 of a quarter turn, the longest "
        "frame over which their Doppler holds, under the 8 the edges need: mdpipe's edges read wide and carry "
        "`few_harmonics`."),
    "BW power spectrum (Hz)": (
        "The paper's rule (20 dB above the spectrum's mean) measures where the line envelope drops below a level "
        "set by the whole span's mean, not the tip Doppler: here it reads below Eq. 6, by an amount that depends on "
        "dwell, PRF and SNR; the paper's values sit above Eq. 6 like its spectrogram BWs."),
    "T_c (s)": (
        "mdpipe and the physics give 1/f_rot exactly; the paper's T_c is read from spectrogram flashes by eye "
        "(12.2 ms for 12.5 ms at 80 rev/s)."),
    "chopping frequency (Hz)": (
        "The paper reads the spacing of the first two lines of its power spectrum; mdpipe fits many repeats of the "
        "flash period. The paper's 140.6 Hz (for N f_rot = 140 Hz) and 277.3 Hz (280 Hz) are 0.4-1 % off, as a "
        "reading of two line positions on a spectrum of finite resolution would be."),
    "r estimated (m)": (
        "The paper inverts Eq. 6 with its own (wider) bandwidths, so its r runs 5-10 % long; mdpipe inverts Eq. 6 "
        "with the flash-edge bandwidth, and not where the flash edges blur (config 4: see the spectrogram "
        "bandwidth)."),
    "omega_p estimated (rev/s)": "The paper takes 1/T_c from a by-eye T_c; mdpipe measures the flash period.",
    "BW spectrogram, bird (Hz)": (
        "The paper does not define its bird BW. The physics column is the model's largest instantaneous spread "
        "of wing-point Dopplers (C2 and phi20 are not given by the paper: 20 and 0 deg assumed); mdpipe's is the "
        "paper's 20 dB rule on the dwell spectrum, which also holds the body's Doppler sweep of a fly-by. The wings "
        "are point scatterers along rigid segments here, not the ellipsoids of Chen's model, so their echo "
        "strengths, and the spectrum's reach above the threshold, differ."),
    "wingbeat period (s)": (
        "A 0.5 Hz wingbeat gives five periods in 10 s: mdpipe does not find it in (a), (b) and (e) and says so "
        "(null). In (a), the bird all but still (0.1 m/s), the pattern repeats every 2.00 s but with a strength "
        "of 0.199, under the 0.2 a wingbeat needs; in (b) and (e) a fly-by's sweep blurs it."),
}
CONFIG4_NOTE = ("Config 4 (beta = 60 deg): Eq. 6 halves the bandwidth (cos 60 = 0.5); the paper's 6.75 kHz is "
                "90 % of its beta = 0 value, so its table does not follow its own cos(beta).")


def _relative(a, b):
    if a is None or b is None or not np.isfinite(a) or not np.isfinite(b) or b == 0:
        return None
    return a / b - 1


def _run(config_path, work_dir, figures_dir, elevation_deg):
    mapping = load_scene_mapping(config_path)
    capture = Path(work_dir) / f"{Path(config_path).stem}.h5"
    truth = simulate_to_file(scene_from_mapping(mapping), capture, scene_yaml=scene_to_yaml(mapping))
    result = process_capture(capture, ProcessParams(elevation_deg=elevation_deg))
    if figures_dir is not None:
        from mdpipe.report import plots

        if result.analyses:
            plots.spectrogram_figure(result, Path(figures_dir) / f"{capture.stem}_spectrogram.png")
            plots.spectrum_figure(result, Path(figures_dir) / f"{capture.stem}_spectrum.png")
    capture.unlink()
    return truth["targets"][0], result.rows[0]


def reproduce(configs_dir, *, work_dir, figures_dir=None, progress=None):
    """Rows ``config, quantity, paper, physics, mdpipe`` for every Table I and II configuration."""
    rows = []
    for number, paper in TABLE_IV.items():
        path = Path(configs_dir) / f"table1_config{number}.yaml"
        beta = load_scene_mapping(path)["targets"][0]["elevation_deg"]
        truth, row = _run(path, work_dir, figures_dir, beta)
        for name, key, physics, measured in DRONE_QUANTITIES:
            rows.append({"config": str(number), "quantity": name, "paper": paper.get(key),
                         "physics": physics(truth), "mdpipe": row.get(measured),
                         "mdpipe_status": row.get(f"{measured}_status"), "mdpipe_class": row["class"],
                         "mdpipe_notes": row["notes"]})
        if progress:
            progress(f"config {number}: {row['class']}")
    for letter, (bw, period) in TABLE_V.items():
        truth, row = _run(Path(configs_dir) / f"table2_{letter}.yaml", work_dir, figures_dir, 0.0)
        wingbeat = row.get("wingbeat_period_s")
        for name, paper, physics, measured, status in (
                ("BW spectrogram, bird (Hz)", bw, truth["micro_doppler_spread_hz"], row.get("doppler_bw_hz"),
                 row.get("doppler_bw_hz_status")),
                ("wingbeat period (s)", period, truth["wingbeat_period_s"], wingbeat,
                 row.get("wingbeat_period_s_status"))):
            rows.append({"config": letter, "quantity": name, "paper": paper, "physics": physics, "mdpipe": measured,
                         "mdpipe_status": status, "mdpipe_class": row["class"], "mdpipe_notes": row["notes"]})
        if progress:
            progress(f"config ({letter}): {row['class']}")
    table = pd.DataFrame(rows)
    table["mdpipe_vs_physics"] = [_relative(m, p) for m, p in zip(table["mdpipe"], table["physics"])]
    table["paper_vs_physics"] = [_relative(m, p) for m, p in zip(table["paper"], table["physics"])]
    return table


def _fmt(value):
    if value is None or (isinstance(value, float) and not np.isfinite(value)):
        return "n/e"
    return "0" if abs(value) < 1e-9 else f"{value:.4g}"


def _fmt_measured(value, status):
    """mdpipe's value, with its status where it gives the value with a caveat (not ``ok``)."""
    shown = _fmt(value)
    return shown if shown == "n/e" or status in (None, "ok") else f"{shown} ({status})"


def _pct(value):
    return "" if value is None or not np.isfinite(value) else f"{100 * value:+.1f} %"


def markdown(table):
    """The comparison side by side, with an explanation under every quantity that differs by more than 5 %."""
    lines = ["# Paper Tables IV and V, reproduced", "",
             "`paper`: the paper's value; `physics`: what the physics predicts for the simulated scene; "
             "`mdpipe`: what `mdpipe process` measures on it, with its status in brackets where it is given with a "
             "caveat. n/e: not estimable (the row's notes say why). "
             "Made by `make paper`.", ""]
    explained = set()
    for quantity, group in table.groupby("quantity", sort=False):
        lines += [f"## {quantity}", "", "| config | paper | physics | mdpipe | paper vs physics | mdpipe vs physics |",
                  "|---|---|---|---|---|---|"]
        for _, r in group.iterrows():
            lines.append(f"| {r['config']} | {_fmt(r['paper'])} | {_fmt(r['physics'])} | "
                         f"{_fmt_measured(r['mdpipe'], r['mdpipe_status'])} | "
                         f"{_pct(r['paper_vs_physics'])} | {_pct(r['mdpipe_vs_physics'])} |")
        differences = [abs(v) for v in list(group["paper_vs_physics"]) + list(group["mdpipe_vs_physics"])
                       if v is not None and np.isfinite(v)]
        missing = group["mdpipe"].isna().any()
        if (differences and max(differences) > 0.05) or missing:
            lines += ["", EXPLANATIONS[quantity]]
            explained.add(quantity)
            if quantity.startswith("BW") and "4" in set(group["config"]):
                lines += ["", CONFIG4_NOTE]
        lines.append("")
    lines += ["## Configuration 5 (beta = 90 deg)", "",
              "The rotor is face-on: cos(beta) = 0, the blades never change their range, the echo does not move "
              "and MTI removes it. mdpipe reports `none` with no moving target; the paper: BW and T_c "
              "cannot be measured.", ""]
    return "\n".join(lines)
