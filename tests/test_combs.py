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


def _lines_at(spacing_hz, scores, lines):
    """``lines`` with the line at +-k spacing_hz set to ``scores[k - 1]``."""
    score = lines.score.copy()
    for k, value in enumerate(scores, start=1):
        for sign in (1, -1):
            score[int(round(sign * k * spacing_hz / lines.resolution_hz)) % len(score)] = value
    return combs.LineSpectrum(score=score, prf_hz=lines.prf_hz)


def _candidate(lines, spacing_hz, half_width_hz):
    contrast, t, orders = combs.comb_statistics(lines, spacing_hz, half_width_hz=half_width_hz, limit=64)
    return combs._Candidate(spacing_hz, float(contrast[0]), float(t[0]), int(orders[0]))


def test_a_multiple_whose_lines_are_strongest_gives_way_to_the_comb():
    """Lines at every +-k 127 Hz (k <= 25), every fifth twice as strong (a blade's line weights rise and fall
    along the band): the comb at 635 Hz stands out on its own (t >= COMB_T), but sums a fifth of the lines
    the 127 Hz comb sums; the comb is 127 Hz."""
    lines = _lines_at(127.0, [6.0 if k % 5 == 0 else 3.0 for k in range(1, 26)], spectrum(n=8192, prf_hz=8192.0))
    multiple = _candidate(lines, 635.0, 3200.0)
    assert multiple.t >= combs.COMB_T
    found = combs._fundamental_comb(lines, multiple, half_width_hz=3200.0, min_hz=20.0)
    assert found.spacing_hz == pytest.approx(127.0, abs=lines.resolution_hz / 4)


@pytest.mark.parametrize("between", [None, 1.2])
def test_a_comb_stays_itself_against_its_sub_multiples(between):
    """Equal lines every 200 Hz: its sub-multiples 100, 66.7 .. Hz sum the same lines (and empty positions), the
    largest spacing is kept. So with weaker lines half-way (a blade differing: a fifth as far above the noise
    floor of 0.6 as the comb's); lines half-way as strong as the comb's would make it the turn rate's."""
    scores = [4.0] * 15 if between is None else [4.0 if k % 2 == 0 else between for k in range(1, 31)]
    lines = _lines_at(200.0 if between is None else 100.0, scores, spectrum(n=8192, prf_hz=8192.0))
    comb = _candidate(lines, 200.0, 3100.0)
    assert combs._fundamental_comb(lines, comb, half_width_hz=3100.0, min_hz=20.0) is comb


def _falling_pattern(d, *, step, orders=8, seed=2):
    """Scores of a comb at 77 Hz that fall along the band (10 at order 1 to 3 at order ``orders``, the
    envelope of a rotor seen nearly face-on) plus noise of 0.2, every ``d``-th line ``step`` higher."""
    rng = np.random.default_rng(seed)
    k = np.arange(1, orders + 1)
    trend = 10.0 - 7.0 * (k - 1) / (orders - 1)
    scores = trend + rng.normal(0, 0.2, orders) + (step * (k % d == 0) if d else 0.0)
    return _lines_at(77.0, scores, spectrum(n=8192, prf_hz=8192.0))


@pytest.mark.parametrize("d", [2, 3])
def test_every_nth_line_stronger_is_read_over_the_bands_fall(d):
    """Every d-th line 2.4 stronger than its neighbours, on scores falling 7 over the band (eight orders a side
    for d = 2, twelve for d = 3): over the plain means of the others the fall outweighs the step (the former
    test's t was 1.1 on a sweep drone's 2-blade rotor, one blade 1.7x brighter); over the trend it is N = d."""
    lines = _falling_pattern(d, step=2.4, orders=4 * d)
    assert combs.blade_count_from_line_pattern(lines, 77.0, half_width_hz=77.0 * 4 * d + 30) == d


def test_a_falling_comb_without_a_pattern_tells_no_blade_count():
    for seed in range(20):
        lines = _falling_pattern(0, step=0.0, orders=12, seed=seed)
        assert combs.blade_count_from_line_pattern(lines, 77.0, half_width_hz=77.0 * 12 + 30) is None


def _flash_train(*, receding_delay, receding_share, prf_hz=20000.0, chopping_hz=150.0, n=20000, seed=4):
    """Blade flashes every chopping period: an approaching one on the positive side of the span (a 0.2 ms
    pulse about +3 kHz) and a receding one (about -3 kHz, ``receding_share`` of its amplitude)
    ``receding_delay`` chopping periods later, in noise 30 dB down."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / prf_hz
    period = 1.0 / chopping_hz
    phase = lambda delay: (t - delay * period + period / 2) % period - period / 2  # noqa: E731
    pulse = lambda delay: np.exp(-0.5 * (phase(delay) / 1e-4) ** 2)  # noqa: E731
    signal = pulse(0) * np.exp(2j * np.pi * 3000 * t) + receding_share * pulse(receding_delay) * np.exp(
        -2j * np.pi * 3000 * t)
    return signal + 0.03 * (rng.normal(size=n) + 1j * rng.normal(size=n)), prf_hz, chopping_hz


@pytest.mark.parametrize("delay, odd", [(0.5, True), (0.0, False)])
def test_blade_parity_from_the_sides_the_flashes_fall_on(delay, odd):
    """An odd N's flashes alternate sides (receding half a chopping period after approaching), an even N's
    span both at once. The receding flash is half as strong here: the power then repeats once per chopping
    period either way, and its lines (the former test) read even for both."""
    signal, prf_hz, chopping_hz = _flash_train(receding_delay=delay, receding_share=0.5)
    assert combs.odd_blades(signal, chopping_hz, prf_hz=prf_hz, half_width_hz=6000.0) is odd
    assert combs.flashes_doubled(signal, chopping_hz, prf_hz=prf_hz, half_width_hz=6000.0) is False


def _skirt(lines_db=None, *, spacing_hz=30.0, n=8192, prf_hz=8192.0):
    """Scores of a skirt falling away from 0 Hz (60 dB over the noise there, 3.3 dB less every 10 Hz out, a small
    ripple on it), with lines ``lines_db`` over it at +-k ``spacing_hz`` if given."""
    f_hz = np.fft.fftfreq(n, 1.0 / prf_hz)
    power = 1e6 * np.exp(-np.abs(f_hz) / 13.0) * (1.0 + 0.2 * np.cos(2 * np.pi * f_hz / 7.3))
    if lines_db is not None:
        on_line = np.abs(f_hz / spacing_hz - np.round(f_hz / spacing_hz)) * spacing_hz < prf_hz / n / 2
        power = np.where(on_line & (f_hz != 0), power * 10 ** (lines_db / 10), power)
    return combs.LineSpectrum(score=np.log1p(power), prf_hz=prf_hz)


def test_a_band_falling_away_from_the_body_line_is_no_comb():
    """On a skirt each position stands over the one half a spacing beyond it: the contrast against the outer
    half-way points reads a comb (t over COMB_T), that against the inner ones falls as much (t under -COMB_T): no
    lines. The same skirt with lines 20 dB over it at the spacing: they stand over both neighbours."""
    skirt = _skirt()
    comb = _candidate(skirt, 30.0, 100.0)
    assert comb.t >= combs.COMB_T
    inner = combs.comb_statistics(skirt, 30.0, half_width_hz=100.0, limit=comb.orders, offset=-0.5)[1][0]
    assert inner <= -combs.COMB_T
    assert not combs._stands_on_both_sides(skirt, comb, half_width_hz=100.0)
    lines = _skirt(20.0)
    assert combs._stands_on_both_sides(lines, _candidate(lines, 30.0, 100.0), half_width_hz=100.0)


def test_the_first_lines_centre_on_the_rotors_mean_rate():
    """Three rotors turning at 78, 80 and 82 Hz seen 0.1 s (10 Hz bins: their first lines unresolved), those lines
    alike; the one at 78 Hz alone holds lines on to the 30th order, so a comb read over the orders follows it. The
    first two lines centre on the rotors' mean rate, 80 Hz, within 0.5 % (the noise of the power given taken out),
    and not on the 78 Hz the comb follows."""
    prf_hz, n = 20000.0, 2000
    t = np.arange(n) / prf_hz
    rng = np.random.default_rng(4)
    noise = 0.1 * (rng.standard_normal(n) + 1j * rng.standard_normal(n)) / np.sqrt(2)
    signal = noise.copy()
    for rate_hz, orders in ((78.0, 30), (80.0, 2), (82.0, 2)):
        for k in range(1, orders + 1):
            for sign in (1, -1):
                signal += np.exp(2j * np.pi * sign * k * rate_hz * t + 1j * rng.uniform(0, 2 * np.pi))
    rate = combs.first_lines_rate_hz(combs.line_spectrum(signal, prf_hz=prf_hz, noise_power=0.01), 78.0)
    assert rate == pytest.approx(80.0, rel=0.005)
