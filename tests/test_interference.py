"""Another radar's chirps crossing ours: their bursts are found, taken out, and leave no phantom targets; blade flashes
shorter than a chirp are not taken for them."""

from pathlib import Path

import numpy as np
import pytest

from hostile import interfered
from mdpipe.io import open_capture
from mdpipe.params import ProcessParams
from mdpipe.process import interference
from mdpipe.process.pipeline import process_capture

SAMPLES = Path(__file__).resolve().parent.parent / "data_samples"
N, M, BURST = 64, 2048, 6
PERIOD = 9.71          # chirps between crossings
FLASH_EVERY = 37       # chirps between a blade's flashes
FLAT = (8, 56)         # samples inside the detection window's flat part (tapers over 12.5 % of the chirp a side)


class _Counts:
    """A reader of (channels, chirps, samples) int16 counts held in memory."""

    def __init__(self, counts):
        self.counts = counts
        self.n_chirps = counts.shape[1]
        self.params = type("Params", (), {"n_samples": counts.shape[2]})

    def read_counts(self, start, stop, *, channels=None, out=None):
        return self.counts[:, start:stop] if channels is None else self.counts[channels, start:stop]


def _scene(seed=0):
    """Two channels of noise (20 counts rms), a mover (a tone at bin 10.3, 200 counts, its phase turning 0.3 rad a
    chirp) and a blade flash every ``FLASH_EVERY`` chirps (a tone at bin 12 under a sinc envelope whose main lobe
    spans 9 samples, 3000 counts: a blade's broadside flash, its spectrum a rectangle over 14 of the 32 range bins, as
    a 77 GHz flash of 19 us in a 64-sample chirp of the default sweep spread), crossed by bursts (6 samples sweeping through the IF band, Hann-tapered, 2000 counts) at ``k * PERIOD``
    chirps, at that fraction of the chirp. Returns the counts and the bursts' chirps and first samples."""
    rng = np.random.default_rng(seed)
    n = np.arange(N)
    counts = rng.normal(0.0, 20.0, (2, M, N))
    counts += 200 * np.cos(2 * np.pi * 10.3 * n / N + 0.3 * np.arange(M)[:, None])
    flashes = np.arange(5, M, FLASH_EVERY)
    envelope = np.sinc((n - 30) / 4.5)
    counts[:, flashes] += 3000 * envelope * np.cos(2 * np.pi * 12 * n / N + rng.uniform(0, 2 * np.pi, (len(flashes), 1)))
    crossings = np.arange(PERIOD, M, PERIOD)
    chirps, firsts = crossings.astype(int), ((crossings % 1) * (N - BURST)).astype(int)
    k = np.arange(BURST)
    for chirp, first in zip(chirps, firsts):
        counts[:, chirp, first:first + BURST] += 2000 * np.hanning(BURST + 2)[1:-1] * np.cos(
            np.pi * k ** 2 / BURST + rng.uniform(0, 2 * np.pi))
    return np.round(counts).astype(np.int16), chirps, firsts, flashes


def test_bursts_are_found_where_they_are_and_blade_flashes_are_not():
    counts, chirps, firsts, flashes = _scene()
    bursts = interference.find_bursts(_Counts(counts))
    found = dict(zip(bursts.chirps.tolist(), bursts.spans.tolist()))
    flat = (firsts >= FLAT[0]) & (firsts + BURST <= FLAT[1])
    alone = flat & ~np.isin(chirps, flashes)  # a chirp holding a flash too: the stronger event is taken
    assert alone.sum() > 150
    for chirp, first in zip(chirps[alone], firsts[alone]):  # every burst in the flat part found, its samples covered,
        start, stop = found[chirp]
        assert start <= first and first + BURST <= stop <= start + 4 * BURST  # at most 4x its length replaced
    assert set(found) <= set(chirps.tolist())  # nothing else: no flash chirp


def test_the_bursts_are_replaced_by_the_neighbouring_chirps_samples():
    rng = np.random.default_rng(1)
    block = rng.integers(-1000, 1000, (2, 8, 32)).astype(np.int16)
    before = block.copy()
    bursts = interference.Bursts(np.array([0, 3, 4]), np.array([[0, 32], [10, 16], [12, 20]]), n_chirps=8,
                                 n_samples=32)
    out = bursts.excise(block, 0)
    assert out is block
    assert np.array_equal(block[:, 0], before[:, 1])  # the first chirp has one clean neighbour
    assert np.array_equal(block[:, 3, 10:16], np.rint((before[:, 2, 10:16] + before[:, 5, 10:16]) / 2))
    assert np.array_equal(block[:, 4, 12:20], np.rint((before[:, 2, 12:20] + before[:, 5, 12:20]) / 2))
    untouched = np.ones(block.shape, dtype=bool)
    untouched[:, 0] = untouched[:, 3, 10:16] = untouched[:, 4, 12:20] = False
    assert np.array_equal(block[untouched], before[untouched])
    # a read that starts later sees the same chirps at their place in it
    later = before[:, 2:].copy()
    bursts.excise(later, 2)
    assert np.array_equal(later[:, 1, 10:16], np.rint((before[:, 2, 10:16] + before[:, 5, 10:16]) / 2))


@pytest.mark.parametrize("name", ["fimi_1rx.h5", "phantom4_xband.h5", "gull_flyby.h5", "clutter_only.h5"])
def test_the_bundled_samples_hold_no_bursts(name):
    with open_capture(SAMPLES / name) as reader:
        assert len(interference.find_bursts(reader).chirps) == 0


def test_another_radars_bursts_leave_no_phantom_targets(tmp_path):
    """The bundled X-band Phantom crossed by a burst every 9.71 chirps (643 bursts in 6250 chirps): without the
    bursts taken out a second drone appeared at 195 m (`blade flashes, their period ambiguous`; a burst is
    broadband in range, so every bin's slow time carries the same train of impulses); with them, the drone alone,
    its chopping as read on the clean capture."""
    params = ProcessParams(n_blades=2)
    clean = process_capture(SAMPLES / "phantom4_xband.h5", params).rows
    rows = process_capture(interfered(SAMPLES / "phantom4_xband.h5", tmp_path / "crossed.h5", PERIOD), params).rows
    assert clean[0]["interfered_share"] == 0
    assert [row["class"] for row in rows] == ["drone"]
    assert rows[0]["range_m"] == pytest.approx(clean[0]["range_m"])
    assert rows[0]["chopping_freq_hz"] == pytest.approx(clean[0]["chopping_freq_hz"], rel=1e-3)
    assert 0.95 * 643 / 6250 <= rows[0]["interfered_share"] <= 643 / 6250
    assert "another radar's chirps crossed" in rows[0]["notes"]
