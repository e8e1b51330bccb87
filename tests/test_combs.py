"""Line-comb statistics: the running form over orders equals the direct one, and a comb that holds to a few
orders only is scored on those."""

import numpy as np
import pytest

from mdpipe.process import combs


def spectrum(n=4096, prf_hz=4096.0, seed=1):
    rng = np.random.default_rng(seed)
    return combs.LineSpectrum(score=np.log1p(rng.exponential(size=n)), prf_hz=prf_hz)


def test_comb_statistics_over_all_orders_is_the_plain_mean_and_t():
    lines = spectrum()
    spacing = np.array([37.3, 101.9, 250.0])
    mean, t, orders = combs.comb_statistics(lines, spacing, half_width_hz=1500.0, limit=20)
    for f, m, tt, k in zip(spacing, mean, t, orders):
        order = np.arange(1, k + 1)
        signed = np.concatenate([order, -order])
        d = lines.at(f * signed) - lines.at(f * (signed + np.sign(signed) * 0.5))
        assert m == pytest.approx(d.mean(), abs=1e-12)
        assert tt == pytest.approx(d.mean() / (d.std(ddof=1) / np.sqrt(len(d))), rel=1e-9)
    assert list(orders) == [20, 14, 6]


def test_a_comb_holding_to_eight_orders_is_scored_on_them():
    """Lines of score 5 at +-k 100 Hz for k <= 8, none beyond (their smear): over the band's 15 orders the
    t drops; the extent chosen is 8."""
    lines = spectrum()
    score = lines.score.copy()
    for k in range(1, 9):
        for sign in (1, -1):
            score[int(round(sign * k * 100.0 / lines.resolution_hz)) % len(score)] = 5.0
    lines = combs.LineSpectrum(score=score, prf_hz=lines.prf_hz)
    _, t_all, k_all = combs.comb_statistics(lines, 100.0, half_width_hz=1550.0, limit=64)
    _, t_held, k_held = combs.comb_statistics(lines, 100.0, half_width_hz=1550.0, limit=64, min_orders=3)
    assert k_all[0] == 15 and k_held[0] == 8
    assert t_held[0] > 3 * t_all[0]
