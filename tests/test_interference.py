"""Another radar's chirps crossing ours: the bursts they leave are told from echoes (blade flashes shorter than a chirp
among them), and a detection whose echo is the bursts is read as such, not as one more drone or bird."""

from pathlib import Path

import numpy as np
import pytest

from hostile import interfered
from mdpipe.io import open_capture
from mdpipe.params import ProcessParams
from mdpipe.process import interference
from mdpipe.process.features import FEATURE_KEYS, STATUS_KEYS
from mdpipe.process.pipeline import process_capture

SAMPLES = Path(__file__).resolve().parent.parent / "data_samples"
N, M, BURST = 64, 2048, 6
PERIOD = 9.71          # chirps between crossings
FLASH_EVERY = 37       # chirps between a blade's flashes


def _chirps(seed=0):
    """One channel: noise (20 counts rms), a mover (a tone at bin 10.3, 200 counts, its phase turning 0.3 rad a chirp)
    and a blade flash every ``FLASH_EVERY`` chirps (a tone at bin 12 under a sinc envelope whose main lobe spans 9
    samples, 3000 counts: a broadside flash, its spectrum a rectangle over 14 of the 32 range bins, as a 77 GHz flash
    of 19 us in a 64-sample chirp of the default sweep spread), crossed at ``k * PERIOD`` chirps by a burst (6 samples,
    2000 counts, its frequency sweeping from the Nyquist frequency through 0 Hz and back) centred at that fraction of
    the chirp. Returns the samples (M, N), the bursts' chirps and centres, and the flashes' chirps."""
    rng = np.random.default_rng(seed)
    n = np.arange(N)
    x = rng.normal(0.0, 20.0, (M, N)) + 200 * np.cos(2 * np.pi * 10.3 * n / N + 0.3 * np.arange(M)[:, None])
    flashes = np.arange(5, M, FLASH_EVERY)
    x[flashes] += 3000 * np.sinc((n - 30) / 4.5) * np.cos(2 * np.pi * 12 * n / N + rng.uniform(0, 2 * np.pi, (len(flashes), 1)))
    crossings = np.arange(PERIOD, M, PERIOD)
    chirps, centres = crossings.astype(int), (crossings % 1) * N
    for chirp, centre in zip(chirps, centres):
        inside = np.abs(n - centre) <= BURST / 2
        x[chirp, inside] += 2000 * np.cos(np.pi * (n[inside] - centre) ** 2 / BURST + rng.uniform(0, 2 * np.pi))
    return x.astype(np.float32), chirps, centres, flashes


def test_bursts_light_most_range_bins_and_flashes_do_not():
    """Under the range window (Hann) the bursts of the middle half of the chirp stand out of the common mode; a burst
    near a ramp's end is attenuated with the echoes it would disturb. No flash chirp is a spike."""
    x, chirps, centres, flashes = _chirps()
    spiked, rows = np.zeros(M, dtype=bool), interference.read_chirps(N)
    for first in range(0, M, rows):
        spiked[first:first + rows] = interference.read_common_mode(x[first:first + rows], np.hanning(N))[1]
    middle = chirps[(centres > N / 4) & (centres < 3 * N / 4) & ~np.isin(chirps, flashes)]
    assert len(middle) > 80 and np.all(spiked[middle])
    assert set(np.flatnonzero(spiked)) <= set(chirps.tolist())


@pytest.mark.parametrize("name", ["fimi_1rx.h5", "phantom4_xband.h5", "gull_flyby.h5", "clutter_only.h5"])
def test_an_unimpaired_capture_holds_no_spikes(name):
    with open_capture(SAMPLES / name) as reader:
        common = interference.common_mode(reader)
    assert common.spikes == 0 and not common.crossed and len(common.series) == reader.n_chirps


def _row(range_m, label="drone"):
    return {**dict.fromkeys(FEATURE_KEYS, 1.0), **dict.fromkeys(STATUS_KEYS, "ok"), "range_m": range_m, "snr_db": 20.0,
            "class": label, "n_blades": None, "n_blades_source": None, "notes": f"class: what made it {label}"}


def test_an_echo_that_follows_the_bursts_is_read_as_theirs():
    rng = np.random.default_rng(2)
    series = 1.0 + rng.exponential(0.3, 4000)
    spikes = np.arange(7, 4000, 10)
    series[spikes] += 20.0
    profile = np.full(33, 20.0)
    profile[5] = 400.0  # the spikes light bin 5 the most: a flash's source
    common = interference.CommonMode(series, len(spikes), profile, range_bin_m=1.5)
    phantom = series * 3e-9 + rng.exponential(1e-9, 4000)      # the bursts, and noise
    target = rng.exponential(5e-8, 4000) + series * 1e-10      # its own echo outweighs the bursts
    source = series * 3e-9 + rng.exponential(1e-9, 4000)       # follows them, but they light its bin most
    rows = [_row(30.0), _row(45.0, "bird"), _row(7.5)]
    signals = [np.sqrt(power) for power in (phantom, target, source)]  # slow time of those powers
    out = interference.crossed_rows(rows, signals, common, ["a warning"])
    assert out[1] == rows[1] and out[2] == rows[2]
    assert out[0]["class"] == "none" and out[0]["snr_db"] == 20.0
    assert {out[0][key] for key in STATUS_KEYS if key != "snr_db_status"} == {"interference"}
    assert out[0]["notes"].endswith("; a warning") and "its echo read as drone" in out[0]["notes"]
    # a drone whose only sign is flashes of an ambiguous period: in a crossed capture the bursts repeat as flashes do
    flashes = {**_row(60.0), "chopping_freq_hz": None, "chopping_freq_hz_status": "ambiguous_period"}
    comb = _row(63.0)  # a comb: the bursts' random phases make no lines
    out = interference.crossed_rows([flashes, comb], [signals[1], signals[1]], common)
    assert out[0]["class"] == "none" and out[0]["chopping_freq_hz_status"] == "interference"
    assert "flashes of an ambiguous period" in out[0]["notes"] and out[1] == comb
    few = interference.CommonMode(series, interference.MIN_SPIKES - 1, profile, range_bin_m=1.5)
    assert interference.crossed_rows(rows, signals, few) is rows  # not crossed: as they are


def test_another_radars_bursts_leave_no_phantom_targets(tmp_path):
    """The bundled X-band Phantom crossed by another radar's chirp every 9.71 chirps: without the rule a drone appeared
    at 82 m (`blade flashes, their period ambiguous`; a burst lights every range bin, so every bin's slow time carries
    the same train of impulses); with it that echo is read as the bursts', and the drone keeps its chopping."""
    params = ProcessParams(n_blades=2)
    clean = process_capture(SAMPLES / "phantom4_xband.h5", params).rows
    rows = process_capture(interfered(SAMPLES / "phantom4_xband.h5", tmp_path / "crossed.h5", PERIOD), params).rows
    assert clean[0]["interference_share"] == 0
    assert rows[0]["class"] == "drone" and rows[0]["range_m"] == pytest.approx(clean[0]["range_m"])
    assert rows[0]["chopping_freq_hz"] == pytest.approx(clean[0]["chopping_freq_hz"], rel=1e-3)
    assert len(rows) > 1 and all(row["class"] == "none" and row["chopping_freq_hz_status"] == "interference"
                                 for row in rows[1:])
    assert 0.05 <= rows[0]["interference_share"] <= 643 / 6250
