"""Flash trains: a sub-period is taken only when the flash phases repeat with it, not when they are spread
evenly (rotors at slightly different rates drift through each other's phases over a dwell)."""

import numpy as np

from mdpipe.process import flashes


def test_fold_share_of_a_train_that_repeats_at_a_third_of_its_period():
    period = 150.0
    times = np.sort(np.concatenate([np.arange(0, 30000, period) + offset for offset in (0.0, 50.0, 100.0)]))
    assert flashes._fold_share(times, period, 3) > 0.9


def test_fold_share_of_evenly_spread_phases_is_no_support():
    """Four trains whose phases drift through the whole period fill the phase histogram flat: shifting it
    by any fraction keeps its energy (0.95 for a third before the mean was taken out, and a quadrotor at
    80.5 rev/s read 242 rev/s); its structure, the deviation from flat, does not repeat."""
    rng = np.random.default_rng(4)
    times = np.sort(rng.uniform(0, 30000, size=800))
    assert flashes._fold_share(times, 140.0, 3) < 0.3
    assert flashes._fold_share(times, 140.0, 2) < 0.3
