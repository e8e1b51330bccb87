"""What every column of a feature row (``features.csv``, ``--json``) means: name, unit, meaning, when null.

The pipeline (:func:`mdpipe.process.pipeline.process_capture`) is the source of the keys; this
module defines them, one entry each, and renders the README's column table from them. A status
column ``<feature>_status`` (``ok`` or a reason code of ``mdpipe.process.validity.STATUS_CODES``)
is defined by a generic rule for any defined feature. ``python -m mdpipe.process.columns
--write-readme`` rewrites the table between the README's markers; ``--check`` fails on drift.

Signs, as in the paper (Eq. 2): Doppler positive approaching; velocities positive receding.
"""

import argparse
import sys
from dataclasses import dataclass
from pathlib import Path

STATUS_SUFFIX = "_status"
START, END = "<!-- columns:start -->", "<!-- columns:end -->"
ROOT = Path(__file__).resolve().parents[2]
KEY_CAPTURES = ("phantom4_xband.h5", "clutter_only.h5")  # a target's row and a `none` row
NO_TARGET = "no target (the `none` row of a capture without detections)"
STATUS = "its `_status` column says why (codes below; with `assumed_blades` the value is given, resting on an assumed N)"


@dataclass(frozen=True)
class Column:
    """One output column: its name, unit (``-`` for none), meaning and when it is null."""

    name: str
    unit: str
    meaning: str
    null_when: str


COLUMNS = (
    Column("file", "-", "the capture, as given on the command line", "never"),
    Column("target", "-", "index of the target in the capture, strongest detection first (0, 1, ...)", NO_TARGET),
    Column("class", "-", "`drone`, `bird` or `none` (rules in `mdpipe/process/classify.py`; the reason opens `notes`)",
           "never"),
    Column("range_m", "m", "range of the detection's peak bin (with `--range-m`: the gate bin nearest the range asked)",
           NO_TARGET),
    Column("range_bin", "-", "that bin's index on the (zero-padded) range-FFT grid", NO_TARGET),
    Column("range_min_m", "m", "nearest range bin the tracker followed the target through", NO_TARGET),
    Column("range_max_m", "m", "farthest range bin the tracker followed the target through", NO_TARGET),
    Column("rx_gain_db", "dB", "SNR gain of the coherent RX combining over one RX, in the bin where the target spent "
           "most chunks (10 log10 C for a point target on C RX)", NO_TARGET),
    Column("snr_db", "dB", "SNR per chirp in the target's bin after RX combining: (moving power - noise) / noise, the "
           "noise being the median moving power over the gate", f"{NO_TARGET}; see `snr_db_status`"),
    Column("micro_doppler_halfwidth_mps", "m/s", "half-width of the band 10 dB above the noise (smoothed) or to its "
           "outermost line 15 dB above it, about its centre (the body line when one stands out), as a speed "
           "(lambda f / 2); when aliased half the unambiguous span, a lower bound (status `aliased`)", STATUS),
    Column("doppler_bw_hz", "Hz", "the paper's Doppler bandwidth: extent of the power spectrum above its mean by "
           "`threshold_db`, on 0.25 s segments of the body-demodulated echo (median of the segments' edges)", STATUS),
    Column("doppler_bw_mps", "m/s", "`doppler_bw_hz` as a velocity spread, times lambda / 2", STATUS),
    Column("doppler_low_hz", "Hz, + approaching", "lower edge of that extent", STATUS),
    Column("doppler_high_hz", "Hz, + approaching", "upper edge of that extent", STATUS),
    Column("chopping_freq_hz", "Hz", "spacing of the rotor line comb, N f_rot (Eq. 5; the median over the rotors "
           "resolved)", STATUS),
    Column("rotation_rate_hz", "rev/s", "rotation rate: the median of `rotor_rates_hz`, or, where no comb resolves "
           "the rotors, the rate of the echo's power period (a mean over the rotors; `rotor_rates_hz` empty) "
           "(status `assumed_blades` when N was neither given nor told by the echo)", STATUS),
    Column("rotation_period_s", "s", "1 / `rotation_rate_hz`", STATUS),
    Column("flash_period_s", "s", "time between blade flashes, 1 / (flashes per revolution x `rotation_rate_hz`): N "
           "flashes a turn for even N, 2N for odd", STATUS),
    Column("rotor_rates_hz", "rev/s", "rate of each rotor resolved in the line combs (`;`-separated in CSV, a list in "
           "JSON), ascending", STATUS),
    Column("doppler_bw_spectrogram_hz", "Hz", "distance between the blade-flash Doppler edges (half amplitude of the "
           "flash frames of a spectrogram a quarter chopping period long, or longer, up to a flash period and a quarter "
           "turn, until the tips span 10 Doppler bins a side): twice the tip Doppler", STATUS),
    Column("tip_doppler_hz", "Hz", "blade-tip Doppler 2 Omega r cos(beta) / lambda: half of "
           "`doppler_bw_spectrogram_hz`", STATUS),
    Column("blade_length_m", "m", "blade length r from Eq. 6 with the tip Doppler, the rotation rate and "
           "`elevation_deg`", STATUS),
    Column("body_velocity_mps", "m/s, + receding", "mean body range rate over the dwell, -lambda f_body / 2 (the body line's track, each 32 ms frame's strongest line, unwrapped across the span's ends, running median over 9 frames; unfolded with the range track where the Doppler aliases)", STATUS),
    Column("body_doppler_hz", "Hz, + approaching", "mean Doppler of the body line's track over the dwell (folded into the span)", STATUS),
    Column("wingbeat_freq_hz", "Hz", "wingbeat frequency: period of the autocorrelation of the detrended "
           "log-spectrogram", STATUS),
    Column("wingbeat_period_s", "s", "1 / `wingbeat_freq_hz`", STATUS),
    Column("flapping_share", "-", "share of the dwell a bird's wings are lit where they go dark between bursts (glides, "
           "or a slow stroke's turns): its wing rows (off the body line, 10 dB over the noise in a quarter of the 64 "
           "ms frames) fall 10 dB or more between the bursts while the body line holds within 3 dB", STATUS),
    Column("wing_stroke_swing", "-", "how far a flying body's wings' reach moves over the dwell, a share of its "
           "greatest: the spread (95th less 5th percentile) of each frame's outermost lit wing row's Doppler distance "
           "from the body line (frames of 64 ms, an eighth of the dwell at most, 50 ms at least); given from 0.15 "
           "(a stroke: a rotor's tips hold their speed)", STATUS),
    Column("aliased", "true/false", "the micro-Doppler fills the unambiguous span 1/Tp (band over 90 % of it or at both "
           "ends, or the brightest frames of a 64-chirp spectrogram fill it): bandwidths and blade length withheld",
           NO_TARGET),
    Column("n_rotors", "-", "rotors resolved in the line combs (rotors at equal rates count as one)", STATUS),
    Column("n_blades", "-", "blades per rotor N behind `rotation_rate_hz`: given (`--blades`), measured from the echo, "
           "or assumed (see `n_blades_source`)", "no rotation measured and `--blades auto`"),
    Column("n_blades_source", "-", "`given` (`--blades N`), `measured` (blade imbalance lines) or `assumed` (2, or 3 "
           "when the flashes tell N is odd)", "no rotation measured and `--blades auto`"),
    Column("stft_window_s", "s", "window of the figure's spectrogram, whole chirps: `--stft-window-s`, else a quarter "
           "chopping period, else min(64 ms, 0.2 / wingbeat), else 32 ms", NO_TARGET),
    Column("stft_hop_s", "s", "hop of that spectrogram: `--stft-hop-s`, else a quarter window", NO_TARGET),
    Column("elevation_deg", "deg", "elevation beta of the rotor plane given for Eq. 6 (`--elevation-deg`)",
           "not given (0 is assumed; `blade_length_m_status` is then `assumed_elevation`)"),
    Column("threshold_db", "dB", "the paper's bandwidth threshold above the spectrum's mean (`--threshold-db`)", "never"),
    Column("wavelength_m", "m", "wavelength at the sweep centre, used for every Doppler-velocity conversion", "never"),
    Column("prf_hz", "Hz", "chirp rate 1/Tp: the slow-time sample rate and the unambiguous Doppler span (of the "
           "chirps read: one transmitter's, where they take turns)", "never"),
    Column("transmitters", "-", "transmitters the chirps take in turn (a MIMO radar's time-division cycle; the file's "
           "`TxSeq`, found on the static echoes, or `--transmitters`): the first one's chirps are read, every "
           "`transmitters`-th; 1 for one transmitter (an I/Q recording's: 1)", "never"),
    Column("dwell_s", "s", "capture duration, chirps x Tp", "never"),
    Column("clipped_share", "-", "share of the samples read in pass 1 (the chirps probed) at the int16 full scale: "
           "over 0 a weaker detection may be clipping's image (statuses `clipping_image`)",
           "float samples (no full scale known)"),
    Column("interference_share", "-", "share of the chirps holding a burst that lights most range bins at once "
           "(another radar's chirps crossing ours): from 8 such chirps on, a detection whose power follows them, or "
           "a drone seen only by flashes of an ambiguous period, is read as their echo (statuses `interference`)",
           "never (0 without bursts)"),
    Column("mains_hum_hz", "Hz", "grid frequency (within 1 % of 50 or 60 Hz, `--mains-hz`) of the mains hum found in "
           "the echo, 6 or more sharp lines at its harmonics about 0 Hz (each sign of an order counts), and taken out "
           "before the analysis "
           "(`mdpipe/process/mains.py`)", "no hum found, `--mains-hz none`, or a capture's `none` row (an I/Q "
           "recording's holds it)"),
    Column("mdpipe_version", "-", "version of mdpipe that made the row", "never"),
    Column("notes", "-", "`; `-separated: the class's reason, why each withheld feature is withheld, warnings about "
           "the capture (clipping, another radar's chirps)", "never"),
)
BY_NAME = {column.name: column for column in COLUMNS}


def status_codes():
    """``STATUS_CODES`` of :mod:`mdpipe.process.validity` (code -> meaning), or an empty dict before it exists."""
    try:
        from mdpipe.process.validity import STATUS_CODES
    except ImportError:
        return {}
    return dict(STATUS_CODES)


def definition(key):
    """The :class:`Column` of ``key``; a ``<feature>_status`` key of a defined feature by the generic rule.

    Raises
    ------
    KeyError
        For a key with no definition (naming the module to add it to).
    """
    if key in BY_NAME:
        return BY_NAME[key]
    feature = key[:-len(STATUS_SUFFIX)] if key.endswith(STATUS_SUFFIX) else None
    if feature in BY_NAME:
        return Column(key, "-", f"`ok` when `{feature}` is reported, else the code of why it is not "
                      "(see the status codes below)", "never")
    raise KeyError(f"column {key!r} has no definition in mdpipe/process/columns.py")


def row_keys(captures=None):
    """Keys of processed rows, in the pipeline's order: a target's row and a ``none`` row (union, first seen first)."""
    from mdpipe.params import ProcessParams
    from mdpipe.process.pipeline import process_capture

    keys = {}
    for capture in captures or [ROOT / "data_samples" / name for name in KEY_CAPTURES]:
        for row in process_capture(capture, ProcessParams()).rows:
            keys.update(dict.fromkeys(row))
    return list(keys)


def _cell(text):
    return text.replace("|", "\\|")


def markdown_table(keys):
    """The README's column table (markdown) for rows with ``keys``, and the status codes when there are any."""
    lines = ["| column | unit | meaning | null when |", "|---|---|---|---|"]
    lines += [f"| `{c.name}` | {_cell(c.unit)} | {_cell(c.meaning)} | {_cell(c.null_when)} |"
              for c in map(definition, keys)]
    codes = status_codes()
    if any(key.endswith(STATUS_SUFFIX) for key in keys) and codes:
        lines += ["", "| status code | meaning |", "|---|---|"]
        lines += [f"| `{code}` | {_cell(str(meaning))} |" for code, meaning in codes.items()]
    return "\n".join(lines) + "\n"


def replace_block(text, table):
    """``text`` with everything between the column markers replaced by ``table``."""
    if START not in text or END not in text:
        raise ValueError(f"the README has no {START} ... {END} block")
    head, rest = text.split(START, 1)
    return f"{head}{START}\n{table}{END}{rest.split(END, 1)[1]}"


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m mdpipe.process.columns", description=__doc__.split("\n")[0])
    parser.add_argument("--write-readme", action="store_true", help="rewrite the README's column table")
    parser.add_argument("--check", action="store_true", help="exit 1 when the README's table differs")
    parser.add_argument("--readme", type=Path, default=ROOT / "README.md")
    args = parser.parse_args(argv)
    table = markdown_table(row_keys())
    if not (args.write_readme or args.check):
        sys.stdout.write(table)
        return 0
    text = args.readme.read_text()
    updated = replace_block(text, table)
    if args.check:
        if updated != text:
            print(f"{args.readme}: the column table differs from mdpipe/process/columns.py; run "
                  "python -m mdpipe.process.columns --write-readme", file=sys.stderr)
            return 1
        return 0
    args.readme.write_text(updated)
    return 0


if __name__ == "__main__":
    sys.exit(main())
