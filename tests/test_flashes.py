"""Flash trains: a sub-period is taken only when the flash phases repeat with it, not when they are spread
evenly (rotors at slightly different rates drift through each other's phases over a dwell)."""

import functools

import numpy as np
import pytest

from mdpipe.process import flashes, periodicity
from mdpipe.process.features import difference
from mdpipe.process.filters import local_maxima, running_min


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


PRF_HZ = 8000.0


def _noise(n, seed=7):
    rng = np.random.default_rng(seed)
    return (rng.standard_normal(n) + 1j * rng.standard_normal(n)) / np.sqrt(2)


def test_flashes_too_weak_for_events_show_in_the_power_autocorrelation():
    """Flashes 0.35 chirp long every 37.3 chirps, 4.8 dB over unit noise at best (less as they fall between
    chirps), random phases: 4 of 214 clear the event threshold (ln(8000 / 0.1) = 11.3 times the noise), too few
    for flash times. Their power's autocorrelation at 37.3 chirps sums all of them: ~0.09 against a standard
    error of 1 / sqrt(8000) = 0.011."""
    n, period = 8000, 37.3
    rng = np.random.default_rng(7)
    noise = _noise(n)
    signal = noise.copy()
    for time, phase in zip(np.arange(0.3, n, period), rng.uniform(size=n)):
        k = np.arange(int(time) - 2, int(time) + 3)
        k = k[(k >= 0) & (k < n)]
        signal[k] += np.sqrt(3.0) * np.exp(2j * np.pi * phase) * np.exp(-0.5 * ((k - time) / 0.35) ** 2)
    assert flashes.flash_period(signal, prf_hz=PRF_HZ, min_period_s=1 / 3000, max_period_s=1 / 20,
                                noise_power=1.0) is None
    found = flashes.power_period(signal, prf_hz=PRF_HZ, min_period_s=1 / 3000)
    assert found.period_s * PRF_HZ == pytest.approx(period, rel=0.01)
    assert flashes.power_period(noise, prf_hz=PRF_HZ, min_period_s=1 / 3000) is None
    # flashes shorter than a chirp repeat whole at a multiple of their period where the chirps sample them
    # alike, their own period then holding as little as a tenth of it: at 0.09 against a standard error of
    # ~0.012, a sub-period's repeat of 0.15 x 0.09 would stay under 3 standard errors; nothing rules it out
    assert not found.whole


def _flash_train(n, period, *, amplitudes, width_chirps, start=0.3, seed=7):
    """Unit noise plus Gaussian flashes every ``period`` chirps, the k-th of amplitude ``amplitudes[k % len]``,
    random phases."""
    rng = np.random.default_rng(seed)
    signal = _noise(n, seed)
    for index, (time, phase) in enumerate(zip(np.arange(start, n, period), rng.uniform(size=n))):
        k = np.arange(int(time) - 3, int(time) + 4)
        k = k[(k >= 0) & (k < n)]
        signal[k] += (amplitudes[index % len(amplitudes)] * np.exp(2j * np.pi * phase)
                      * np.exp(-0.5 * ((k - time) / width_chirps) ** 2))
    return signal


@pytest.mark.parametrize("amplitudes, width_chirps", [((3.0,), 0.35), ((3.0, 1.5), 1.0)])
def test_a_power_period_that_is_a_multiple_of_the_flashes_is_not_whole(amplitudes, width_chirps):
    """Flashes every 37.3 chirps, 19.5 dB over the noise at best. Flashes 0.35 chirp long are sampled where they
    fall between chirps, a pattern that all but repeats every third flash (3 x 0.3 chirp from whole): the
    power's period is read at 3 x 37.3 chirps. Two blades, one of half the other's amplitude: the power repeats
    once a turn, 2 x 37.3 chirps. Either way the lags a third or a half of it repeat too (the flashes do): the
    period is not whole, and no chopping frequency is read from it."""
    n, period = 8000, 37.3
    found = flashes.power_period(_flash_train(n, period, amplitudes=amplitudes, width_chirps=width_chirps),
                                 prf_hz=PRF_HZ, min_period_s=1 / 3000)
    assert found.period_s * PRF_HZ == pytest.approx((4 - len(amplitudes)) * period, rel=0.01)
    assert not found.whole


@pytest.mark.parametrize("period, multiple", [(27.35, 3), (29.45, 2), (32.45, 2)])
def test_a_weak_stroboscopic_multiple_is_not_whole(period, multiple):
    """Flashes 0.3 chirp long, 6.8 dB over the noise at best: sampled where they fall, their power repeats whole
    every 2nd or 3rd flash, the flash period itself weaker than a third of that and lost in the noise. The
    former test (no repeat of 0.3 at a half, third or quarter) passed these periods as whole; a sub-period of
    0.15 could not clear 3 standard errors here, so nothing rules it out: not whole."""
    found = flashes.power_period(_flash_train(8000, period, amplitudes=(2.2,), width_chirps=0.3),
                                 prf_hz=PRF_HZ, min_period_s=1 / 3000)
    assert found.period_s * PRF_HZ == pytest.approx(multiple * period, rel=0.01)
    assert not found.whole


@pytest.mark.parametrize("period", [105.3, 150.3, 190.3])
def test_strong_equal_flashes_repeat_whole_at_their_period(period):
    """Equal flashes a chirp long, 15.6 dB over the noise, every 105-190 chirps (the last near the longest
    period searched, 200 chirps at 8 kHz): the power repeats whole at the flash period. Its later peaks are
    read up to half the record (read up to the search's end, a period over half of it had none left to read,
    and its verdict was a coin toss)."""
    found = flashes.power_period(_flash_train(20000, period, amplitudes=(6.0,), width_chirps=1.0),
                                 prf_hz=PRF_HZ, min_period_s=1 / 3000)
    assert found.period_s * PRF_HZ == pytest.approx(period, rel=0.003)
    assert found.whole


def test_a_power_that_repeats_smoothly_is_not_flashes():
    """Two lines 250 Hz apart beat: their power is a sinusoid of period 4 ms, its autocorrelation peak half
    its lag wide. A speckled echo lit half of every 10 ms (a broad pulse, as a wing's) has a peak as wide.
    Both repeat strongly, neither as short flashes do."""
    n = 8000
    m = np.arange(n)
    noise = _noise(n)
    beat = np.exp(2j * np.pi * 300 * m / PRF_HZ) + 0.8 * np.exp(2j * np.pi * 50 * m / PRF_HZ) + 0.3 * noise
    speckle = np.convolve(_noise(n, seed=8), np.ones(3) / np.sqrt(3), mode="same")
    broad = 5 * speckle * np.sqrt(np.clip(np.cos(2 * np.pi * 100 * m / PRF_HZ), 0, None)) + noise
    for signal, period_chirps in ((beat, 32), (broad, 80)):
        r = periodicity.autocorrelation(np.abs(signal) ** 2, signed=True)
        assert r[period_chirps] > 0.25 and r[period_chirps // 2] < -0.2  # 1 / sqrt(8000) = 0.011
        assert flashes.power_period(signal, prf_hz=PRF_HZ, min_period_s=1 / 3000) is None


def test_a_speckled_echo_is_not_flashes():
    """A speckled echo (a Gaussian Doppler band 400 Hz wide about a random centre, 10 dB over the noise) has a
    power correlated over ~3 chirps: its autocorrelation strays further than a white power's, and its highest
    narrow peak stood 8-10 white standard errors high (six such echoes in a hundred were called flashes; one of these
    three no longer repeats there as a peak at twice and three times its lag, and no period is read).
    Against Bartlett's standard error for that correlation it stands 4-5: not flashes."""
    n, prf_hz = 8000, 8000.0
    f_hz = np.fft.fftfreq(n, 1 / prf_hz)
    for seed in (10, 13, 30):
        rng = np.random.default_rng(seed)
        noise = lambda: (rng.standard_normal(n) + 1j * rng.standard_normal(n)) / np.sqrt(2)  # noqa: E731
        centre_hz = rng.uniform(-prf_hz / 2, prf_hz / 2)
        band = np.exp(-0.5 * ((((f_hz - centre_hz) + prf_hz / 2) % prf_hz - prf_hz / 2) / 400.0) ** 2)
        speckle = np.fft.ifft(np.fft.fft(noise()) * band)
        speckle *= np.sqrt(10 / np.mean(np.abs(speckle) ** 2))
        signal = difference(speckle + noise())  # as the rotation analysis takes it
        r = periodicity.autocorrelation(np.abs(signal) ** 2, signed=True)
        lo, hi = periodicity.lag_range(n, sample_rate_hz=prf_hz, min_period_s=8 / prf_hz, max_period_s=1 / 40)
        prominence = r - running_min(r, 2 * lo + 1)  # a peak's strength as the period search measures it
        peaks = local_maxima(r[lo - 1:hi]) + lo - 1
        assert np.max(prominence[peaks] * np.sqrt(n - peaks)) >= 8.0  # in white standard errors
        assert flashes.power_period(signal, prf_hz=prf_hz, min_period_s=1 / 3000) is None


RAMP_SHARE = 0.8  # the ramp's share of the chirp period: flashes in the other fifth go unseen


def _ramp_parts(period_chirps, *, n_chirps=6000, phase_chirps=0.3, amplitude=6.0, wander=0.0, parts=8, seed=3,
                ramp_share=RAMP_SHARE):
    """A flash train resolved within the ramp: flash j at ``phase + j period (1 + wander sin(2 pi j / J))`` (chirps,
    J flashes in all) lands, whole, in the part of its chirp's ramp (the first ``ramp_share`` of the chirp) that holds
    it, or nowhere when it falls between ramps; unit complex noise in every part. Each flash is shorter than a
    part."""
    rng = np.random.default_rng(seed)
    x = (rng.standard_normal((n_chirps, parts)) + 1j * rng.standard_normal((n_chirps, parts))) / np.sqrt(2)
    j = np.arange(int(n_chirps / period_chirps) - 1)
    for t in phase_chirps + j * period_chirps * (1 + wander * np.sin(2 * np.pi * j / len(j))):
        chirp, within = int(t), t % 1.0
        if within < ramp_share:
            x[chirp, int(within / ramp_share * parts)] += amplitude * np.exp(2j * np.pi * rng.uniform())
    return x


def test_ramp_parts_tell_a_flash_period_the_whole_ramps_double():
    """Flashes every 37.5 chirps (wandering 0.3 %, as a rotor's rate does) fall at places in the ramp that a Hann
    window over the whole ramp weighs unequally, two by turns, and some between ramps: the whole ramps' power
    repeats whole at 75 chirps with 0.1-0.9 of it at 37.5. Resolved within the ramp each flash is caught whole
    where it falls: the train repeats whole at 37.5 chirps, and not at 75 (a repeat at half of it)."""
    train = flashes.ramp_train(_ramp_parts(37.5, wander=0.003), ramp_share=RAMP_SHARE, prf_hz=PRF_HZ)
    assert flashes.ramp_repeats_whole(train, 37.5, shortest_chirps=2.7) is True
    assert flashes.ramp_repeats_whole(train, 75.0, shortest_chirps=2.7) is False


def test_ramp_parts_do_not_settle_flashes_every_other_one_falling_between_ramps():
    """A steady train every 37.5 chirps from phase 0.45: every other flash falls at 0.95 of a chirp, between
    ramps, and nothing sees it. The seen flashes repeat every 75 chirps and nothing flashes half-way between them,
    but nothing could be seen there: 75 chirps is not taken as whole (it cannot tell), nor 37.5 (no repeat)."""
    train = flashes.ramp_train(_ramp_parts(37.5, phase_chirps=0.45), ramp_share=RAMP_SHARE, prf_hz=PRF_HZ)
    assert flashes.ramp_repeats_whole(train, 75.0, shortest_chirps=2.7) is None
    assert not flashes.ramp_repeats_whole(train, 37.5, shortest_chirps=2.7)


def test_ramp_parts_tell_two_rotors_a_phase_apart_from_a_shorter_period():
    """Two rotors at one rate flashing every 37.5 chirps, the second 7.5 chirps (a fifth of the period) after the
    first: the train repeats at 7.5 and 30 chirps (the offset, both ways: 2.3 and 0.66 times its repeat at 37.5,
    which the flashes' wander blurs more than the fixed offset) and at 15 and 22.5 with 0.14 and 0.13 of it, where
    flashes every 7.5 chirps would repeat as strongly. The period is whole (the sub-period alone read it not whole).
    A train that does flash every 7.5 chirps repeats at 15 with 1.3 times it: 37.5 chirps is not whole there."""
    first = _ramp_parts(37.5, phase_chirps=0.3, wander=0.003, seed=3)
    second = _ramp_parts(37.5, phase_chirps=7.8, wander=0.003, seed=4)
    train = flashes.ramp_train(first + second, ramp_share=RAMP_SHARE, prf_hz=PRF_HZ)
    r, lag = train.correlation, 37.5 / train.slot_chirps
    share = flashes.RAMP_SUB_SHARE * flashes._repeat_at(r, lag)
    assert flashes._repeat_at(r, lag / 5) > share > flashes._repeat_at(r, 2 * lag / 5)
    assert flashes.ramp_repeats_whole(train, 37.5, shortest_chirps=2.7) is True
    fifth = flashes.ramp_train(_ramp_parts(7.5, phase_chirps=0.3, wander=0.003), ramp_share=RAMP_SHARE, prf_hz=PRF_HZ)
    r = fifth.correlation
    assert flashes._repeat_at(r, 2 * lag / 5) > flashes.RAMP_SUB_SHARE * flashes._repeat_at(r, lag)
    assert flashes.ramp_repeats_whole(fifth, 37.5, shortest_chirps=2.7) is False


@pytest.mark.parametrize("ramp_share, period_chirps, multiple", [(0.55, 7.225, 5), (0.6, 7.725, 4), (0.65, 7.275, 5)])
def test_ramp_parts_with_lags_unread_do_not_take_a_multiple_for_whole(ramp_share, period_chirps, multiple):
    """A ramp over 0.55-0.65 of the chirp pairs too few parts at lags whose fraction of a chirp falls in the gap:
    those lags are unread (NaN). Flashes every 7.2-7.7 chirps then repeat at twice their period where the best of
    the readable lags nearby is noise. Their multiple (4 or 5 periods) is not whole: their repeat at the period
    itself stands (read whole when the lesser of it and the noise at twice it was taken)."""
    train = flashes.ramp_train(_ramp_parts(period_chirps, wander=0.003, ramp_share=ramp_share),
                               ramp_share=ramp_share, prf_hz=PRF_HZ)
    assert flashes.ramp_repeats_whole(train, multiple * period_chirps, shortest_chirps=2.7) is not True


@pytest.mark.parametrize("period_chirps", [7.5, 11.5])
def test_ramp_parts_read_a_flash_period_unread_at_one_of_its_multiples(period_chirps):
    """At a ramp of 0.6 of the chirp, a lag of a whole number of chirps and a half pairs a third of the parts: it is
    unread, and so is every lag within 3 % of it that would hold flashes 7.5 (11.5) chirps apart; the best readable
    lag nearby is noise, and three periods, 22.5 (34.5) chirps, were read whole. The flashes repeat at twice their
    period as well, a whole number of chirps, read, where a train every three periods would not: three periods are
    not whole."""
    train = flashes.ramp_train(_ramp_parts(period_chirps, phase_chirps=0.1, wander=0.003, ramp_share=0.6),
                               ramp_share=0.6, prf_hz=PRF_HZ)
    assert flashes.ramp_repeats_whole(train, 3 * period_chirps, shortest_chirps=2.7) is False


def test_ramp_parts_read_a_period_held_on_the_chirps_grid_on_fewer_pairs():
    """Flashes every 7.5 chirps from 0.05 of a chirp, at a ramp of 0.6: they fall at 0.05 and 0.55 of a chirp by turns,
    both within the ramp, and 15 chirps is a whole number: the flashes are held at those two places. Lag 7.5 pairs a
    third of the parts (unread at half), but it pairs those two places, and the flashes repeat there: 15 chirps is
    not whole (it was, on the noise of the readable lags nearby). A train every 15 chirps held at 0.05 (nothing at 0.55,
    where it would be seen) is."""
    def verdict(period_chirps):
        train = flashes.ramp_train(_ramp_parts(period_chirps, phase_chirps=0.05, ramp_share=0.6), ramp_share=0.6,
                                   prf_hz=PRF_HZ)
        return flashes.ramp_repeats_whole(train, 15.0, shortest_chirps=2.7)

    assert verdict(7.5) is False
    assert verdict(15.0) is True


@pytest.mark.parametrize("period_chirps", [8.6, 10.6])
def test_ramp_parts_of_flashes_held_in_place_are_not_cleared_by_twice_the_sub_period(period_chirps):
    """Flashes every 8.6 (10.6) chirps without wander fall at five places in the ramp, again and again: their period
    times 5 is a whole number of chirps. Each part's power weighed by its own median, they repeat at their period
    with 0.5 of their repeat at 5 periods and at twice it with 0.35 (0.45, 0.35). The lesser of the two would clear
    the flash period and read 5 periods whole; such a period (no drift of a chirp over the dwell) is read as before
    the lesser was taken."""
    train = flashes.ramp_train(_ramp_parts(period_chirps, phase_chirps=0.5), ramp_share=RAMP_SHARE, prf_hz=PRF_HZ)
    assert flashes.ramp_repeats_whole(train, 5 * period_chirps, shortest_chirps=2.7) is not True


def test_ramp_parts_of_noise_tell_nothing():
    train = flashes.ramp_train(_ramp_parts(37.5, amplitude=0.0), ramp_share=RAMP_SHARE, prf_hz=PRF_HZ)
    assert flashes.ramp_repeats_whole(train, 37.5, shortest_chirps=2.7) is None


def test_ramp_parts_of_noise_swelling_slowly_tell_nothing():
    """Noise whose power swells slowly (a log-normal envelope smoother than 400 chirps, at 33.9 kHz: within the 50 ms
    the parts' trend is taken over) lifts the parts' correlation to a floor of 0.2-0.25 at every lag read, a few
    thousandths about it. Read against 0 some period is whole; over that floor (``over_floor``, as a reading is
    overruled only so) none is. Flashes every 15.45 chirps on the same swell stand over it: whole."""
    prf_hz, n = 33905.0, 20000
    rng = np.random.default_rng(7)
    k = np.fft.rfftfreq(n)
    swell = np.fft.irfft((rng.standard_normal(len(k)) + 1j * rng.standard_normal(len(k))) * (k < 1 / 400), n)
    parts = _ramp_parts(37.5, amplitude=0.0, n_chirps=n) * np.exp(0.35 * swell / np.std(swell))[:, None]
    train = flashes.ramp_train(parts, ramp_share=RAMP_SHARE, prf_hz=prf_hz)
    assert np.all(train.correlation[[50, 150, 375]] > 0.2)
    periods = (12.3, 18.6, 27.9, 37.5)
    assert True in [flashes.ramp_repeats_whole(train, p, shortest_chirps=prf_hz / 3000) for p in periods]
    for period_chirps in periods:
        assert flashes.ramp_repeats_whole(train, period_chirps, shortest_chirps=prf_hz / 3000, over_floor=True) is None
    flashing = _ramp_parts(15.45, amplitude=6.0, n_chirps=n) * np.exp(0.35 * swell / np.std(swell))[:, None]
    train = flashes.ramp_train(flashing, ramp_share=RAMP_SHARE, prf_hz=prf_hz)  # flashes on that swell still stand
    assert flashes.ramp_repeats_whole(train, 15.45, shortest_chirps=prf_hz / 3000, over_floor=True) is True


def _read_with_ramp(chopping_hz, *, n_blades, source, period_chirps, status="ok", prf_hz=PRF_HZ, rates_hz=None,
                    parts=None):
    """A rotation read at ``chopping_hz`` (rotors at ``rates_hz``, else one at the chopping over ``n_blades``;
    ``source`` of the count), put by :func:`mdpipe.process.features._flashes_between` to the ramp's ``parts`` (else
    a train of flashes every ``period_chirps``, wandering 0.3 %; 6000 chirps)."""
    from mdpipe.process.features import Measured, Rotation, _flashes_between
    parts = _ramp_parts(period_chirps, wander=0.003) if parts is None else parts
    train = flashes.ramp_train(parts, ramp_share=RAMP_SHARE, prf_hz=prf_hz)
    rates_hz = (chopping_hz / n_blades,) if rates_hz is None else tuple(rates_hz)
    turn = Rotation(Measured(chopping_hz, status), Measured(float(np.median(rates_hz)), status), rates_hz, n_blades,
                    source)
    return turn, _flashes_between(turn, lambda: train, prf_hz=prf_hz)


@pytest.mark.parametrize("k, source", [(3, "given"), (5, "given"), (4, "measured")])
def test_a_chopping_read_at_a_kth_of_the_flashes_the_ramp_resolves_is_taken_at_k_times(k, source):
    """Flashes every 15.45 chirps (a 2-blade rotor chopping at 517.8 Hz at a PRF of 8 kHz), read at a k-th of that
    (flash times or a folded comb catching every k-th passage: where the sampling comes round again): the ramp's
    parts repeat whole at 15.45 chirps and at each of its multiples up to the reading's period. The chopping is k
    times the reading, the rate with it, for N = 2 given or measured."""
    turn, read = _read_with_ramp(PRF_HZ / 15.45 / k, n_blades=2, source=source, period_chirps=15.45)
    assert read.chopping.status == read.rate.status == "ok"
    assert read.chopping.value == pytest.approx(k * turn.chopping.value)
    assert read.chopping.value == pytest.approx(PRF_HZ / 15.45, rel=0.01)
    assert read.rate.value == pytest.approx(read.chopping.value / 2)
    assert read.rotor_rates_hz == pytest.approx([k * r for r in turn.rotor_rates_hz])
    assert (read.n_blades, read.n_blades_source) == (2, source)
    assert f"{k} times per period of the chopping read" in read.chopping.note


@pytest.mark.parametrize("rates_apart", [0.0, 0.015])
def test_half_the_flashes_read_keep_the_reading_ambiguous(rates_apart):
    """Flashes every 15.45 chirps read at half (30.9 chirps). Two rotors at one rate half a chopping period apart
    repeat there too, and one rate in a comb does not rule them out (two of four locked, beside others): the reading
    is kept as `ambiguous_period` (its value, twice it as likely; no rate), rotors resolved 1.5 % apart or not."""
    one = PRF_HZ / 30.9 / 2
    turn, read = _read_with_ramp(PRF_HZ / 30.9, n_blades=2, source="given", period_chirps=15.45,
                                 rates_hz=((1 - rates_apart / 2) * one, (1 + rates_apart / 2) * one))
    assert read.chopping.value == turn.chopping.value and read.chopping.status == "ambiguous_period"
    assert read.rate.value is None and read.rate.status == "ambiguous_period" and read.rotor_rates_hz == ()
    assert "258.9 Hz or twice it" in read.chopping.note and "rotors at one rate" in read.chopping.note


@pytest.mark.parametrize("offset_chirps, kept_ambiguous", [(5.9, False), (7.2, False), (9.8, False), (15.0, True)])
def test_two_rotors_at_one_rate_a_fraction_apart_do_not_overrule_a_reading(offset_chirps, kept_ambiguous):
    """Two 2-blade rotors at one rate flashing every 30.9 chirps, the second ``offset_chirps`` after the first,
    read right (258.9 Hz, one rotor resolved). The offset repeats near 30.9 / k (5.9 and 7.2: k = 5, 9.8: k = 3, 15.0:
    k = 2). At k = 5 it does not repeat at the multiples of 30.9 / 5, and at k = 3 its repeat at 30.9 less it, within
    3 % of 2 x 30.9 / 3, holds 0.59 of the repeat at 30.9 (flashes every 10.3 chirps would repeat there as at 30.9):
    the reading stands. At k = 2 nothing tells: it is kept as `ambiguous_period` (its value, no rate)."""
    parts = (_ramp_parts(30.9, wander=0.003, seed=3) +
             _ramp_parts(30.9, phase_chirps=0.3 + offset_chirps, wander=0.003, seed=4))
    turn, read = _read_with_ramp(PRF_HZ / 30.9, n_blades=2, source="given", period_chirps=30.9, parts=parts)
    assert (read is turn) is not kept_ambiguous
    assert read.chopping.value == turn.chopping.value
    assert read.chopping.status == ("ambiguous_period" if kept_ambiguous else "ok")


def test_an_odd_counts_chopping_read_at_a_third_is_taken_at_three_times_it():
    """Three blades flash twice per chopping period: flashes every 15.45 chirps are a chopping of 258.9 Hz. Read at a
    third of that (a chopping period of 92.7 chirps, 6 flash periods), the chopping is 3 times the reading. Read at
    half (4 flash periods: two rotors at one rate a quarter of the chopping period apart flash so too), the reading is
    kept as `ambiguous_period`."""
    turn, read = _read_with_ramp(PRF_HZ / 15.45 / 6, n_blades=3, source="given", period_chirps=15.45)
    assert read.chopping.status == "ok" and read.chopping.value == pytest.approx(3 * turn.chopping.value)
    assert read.chopping.value == pytest.approx(PRF_HZ / 15.45 / 2, rel=0.01)
    assert read.rate.value == pytest.approx(read.chopping.value / 3)
    assert "an odd count flashes twice per chopping period" in read.chopping.note
    turn, read = _read_with_ramp(PRF_HZ / 15.45 / 4, n_blades=3, source="given", period_chirps=15.45)
    assert read.chopping.value == turn.chopping.value and read.chopping.status == "ambiguous_period"


def test_an_odd_count_reads_no_odd_multiple_of_its_flashes():
    """Flashes every 15.45 chirps under a chopping period of 46.35 chirps (3 flash periods): with N = 2 the chopping is
    3 times the reading. Three blades flash twice per chopping period, so a reading at 1/m of their chopping holds 2m
    of their flash periods, never 3: with N = 3 the reading stands."""
    turn, read = _read_with_ramp(PRF_HZ / 15.45 / 3, n_blades=2, source="given", period_chirps=15.45)
    assert read.chopping.value == pytest.approx(3 * turn.chopping.value)
    turn, read = _read_with_ramp(PRF_HZ / 15.45 / 3, n_blades=3, source="given", period_chirps=15.45)
    assert read is turn


def test_a_chopping_the_ramp_confirms_stands():
    """Read at the flashes' own rate, nothing shorter repeats: the rotation stands as read (the same object)."""
    turn, read = _read_with_ramp(PRF_HZ / 15.45, n_blades=2, source="given", period_chirps=15.45)
    assert read is turn


def test_flashes_within_two_chirps_do_not_overrule_a_reading():
    """At a PRF of 4 kHz (the fastest chopping searched, 3 kHz, flashes every 1.33 chirps), flashes every 1.7 chirps
    read at half their rate (3.4 chirps): the ramp's parts repeat whole at 1.7, but a period under
    ``RAMP_MIN_PERIOD_CHIRPS`` is not read there (each part is differenced along the chirps, so a flash shows in two
    differences, a chirp apart): the reading stands."""
    from mdpipe.process.features import _settled_in_ramp
    prf_hz = 4000.0
    train = flashes.ramp_train(_ramp_parts(1.7, wander=0.003), ramp_share=RAMP_SHARE, prf_hz=prf_hz)
    assert _settled_in_ramp(lambda: train, 3.4, [2], prf_hz=prf_hz) == pytest.approx(1.7)  # read, were it asked
    turn, read = _read_with_ramp(prf_hz / 3.4, n_blades=2, source="given", period_chirps=1.7, prf_hz=prf_hz)
    assert read is turn


def test_a_chopping_at_a_fraction_of_the_flashes_with_the_count_assumed_is_kept_ambiguous():
    """The blade count assumed: its parity says whether the flash rate is the chopping or twice it. Flashes every
    15.45 chirps under a reading at a fourth of them keep the reading as `ambiguous_period` (4 times it, or twice it),
    the rate withheld; at half of them (an odd count's flashes) the reading stands."""
    turn, read = _read_with_ramp(PRF_HZ / 15.45 / 4, n_blades=2, source="assumed", period_chirps=15.45,
                                 status="assumed_blades")
    assert read.chopping.value == turn.chopping.value and read.chopping.status == "ambiguous_period"
    assert read.rate.value is None and read.rate.status == "ambiguous_period"
    assert "the blade count's parity" in read.chopping.note and "give --blades" in read.chopping.note
    assert "4 times it (an even blade count) or 2 times (an odd one)" in read.chopping.note
    turn, read = _read_with_ramp(PRF_HZ / 15.45 / 2, n_blades=2, source="assumed", period_chirps=15.45,
                                 status="assumed_blades")
    assert read is turn


def test_a_chopping_kept_but_not_stood_behind_is_left_as_it_was():
    """A chopping kept with its value as ``ambiguous_period`` (its double as likely) is not read again."""
    turn, read = _read_with_ramp(PRF_HZ / 15.45 / 5, n_blades=2, source="given", period_chirps=15.45,
                                 status="ambiguous_period")
    assert read is turn


def _sides(flash_period, *, alternate, both=False, n_chirps=8000, amplitude=4.0, upper=1.0, seed=5, offset=0.0):
    """Two range sides' slow time: unit complex noise each, and flashes (one chirp, random phase) every
    ``flash_period`` chirps, by turns on the lower and the upper side (``alternate``: an odd N's approaching and
    receding blades) or on both at once, the upper side's ``offset`` chirps later; ``both``: each flash seen on both
    sides (a beat that hardly moves); ``upper``: the upper side's share of the flashes' amplitude (a target off its
    range bin's centre)."""
    rng = np.random.default_rng(seed)
    x = (rng.standard_normal((n_chirps, 2)) + 1j * rng.standard_normal((n_chirps, 2))) / np.sqrt(2)
    for j, t in enumerate(np.arange(10.0, n_chirps - 1 - offset, flash_period)):
        on = (0, 1) if both or not alternate else (j % 2,)
        for side in on:
            x[int(t + side * offset), side] += amplitude * (upper if side else 1.0) * np.exp(2j * np.pi * rng.uniform())
    return x


def test_flashes_alternating_range_sides_tell_an_odd_blade_count():
    """Flashes every 40 chirps by turns on the two sides: each side repeats every 80 chirps and not at 40, the
    sides correlate 40 chirps apart and not at once: an odd N. Flashes on both sides at once (an even N), or each
    seen on both sides (an odd N whose beat moves under a bin), or noise: nothing concluded."""
    assert flashes.sides_alternate(_sides(40.0, alternate=True), 40.0)
    assert not flashes.sides_alternate(_sides(40.0, alternate=False), 40.0)
    assert not flashes.sides_alternate(_sides(40.0, alternate=True, both=True), 40.0)
    assert not flashes.sides_alternate(_sides(40.0, alternate=True, amplitude=0.0), 40.0)


def test_flash_times_each_range_side_flashes_at_on_its_own_are_told():
    """Each side flashing every 40 chirps, the upper side 20 chirps after the lower (an odd N's flashes by turns,
    every 20 chirps, read at its chopping period) or 13 after: each side repeats at every flash time, the sides
    neither at once nor 40 chirps apart: told. Flashes on both sides at once (an even N's) or each seen on both
    sides (the sides correlate at once and one flash apart), flashes by turns every 40 chirps (each side every
    second flash), or noise: not."""
    assert flashes.sides_flash_apart(_sides(40.0, alternate=False, offset=20.0), 40.0)
    assert flashes.sides_flash_apart(_sides(40.0, alternate=False, offset=13.0), 40.0)
    assert not flashes.sides_flash_apart(_sides(40.0, alternate=False), 40.0)
    assert not flashes.sides_flash_apart(_sides(40.0, alternate=True, both=True), 40.0)
    assert not flashes.sides_flash_apart(_sides(40.0, alternate=True), 40.0)
    assert not flashes.sides_flash_apart(_sides(40.0, alternate=True, amplitude=0.0), 40.0)


def test_flashes_alternating_range_sides_unevenly_are_read_on_both_sides_pooled():
    """Flashes by turns on the two sides (amplitude 2.5 in unit noise), the upper side's at 0.55 of the lower's (a
    target off its bin's centre): the upper side's repeat at every second flash stands 3.3 sigmas, under the 4 asked
    of one side (the lower's 12), the two sides' sum 11.8 of its own, the sides one flash apart 7.8: an odd N. At 0.45
    the upper side repeats 1.8 sigmas at the second flash and 0.65 at the next, over 0.3 of that but within 2 sigmas
    of the noise: an odd N still, on the lower side and the sides one flash apart (5.9).
    As uneven, flashes on both sides at once are not; nor are flashes by turns (2.5 below, 5 above) where the lower
    side holds a train at every flash besides (amplitude 3, 4 chirps off): its repeat at the next flash, 0.8 of its
    repeat at the second, is no noise."""
    assert flashes.sides_alternate(_sides(40.0, alternate=True, amplitude=2.5, upper=0.55, seed=7), 40.0)
    assert flashes.sides_alternate(_sides(40.0, alternate=True, amplitude=2.5, upper=0.45, seed=7), 40.0)
    assert not flashes.sides_alternate(_sides(40.0, alternate=False, amplitude=2.5, upper=0.55, seed=7), 40.0)
    rng = np.random.default_rng(7)
    every = _sides(40.0, alternate=True, amplitude=2.5, upper=2.0, seed=7)
    for t in np.arange(14.0, len(every) - 1, 40.0):
        every[int(t), 0] += 3.0 * np.exp(2j * np.pi * rng.uniform())
    assert not flashes.sides_alternate(every, 40.0)


def test_a_power_period_three_flashes_long_is_settled_at_the_flashes():
    """Flashes every 25 chirps that whole ramps read as repeating whole at 75: within the ramp 75 is not whole (a
    repeat at 25), 37.5 cannot be told (no repeat there, and none expected of a train every 25), 25 is whole: the
    search goes on past a period it cannot tell."""
    from mdpipe.process.features import resolved_in_ramp
    train = flashes.ramp_train(_ramp_parts(25.0, wander=0.003), ramp_share=RAMP_SHARE, prf_hz=PRF_HZ)
    settled = resolved_in_ramp(flashes.PowerPeriod(75.0 / PRF_HZ, True), lambda: train, prf_hz=PRF_HZ)
    assert settled.whole and settled.period_s * PRF_HZ == pytest.approx(25.0)


def test_a_ramp_sampled_over_too_little_of_the_chirp_settles_nothing():
    """A ramp sampled over 0.4 of the chirp leaves most flashes unseen wherever they fall: no ramp train."""
    assert flashes.ramp_train(_ramp_parts(37.5), ramp_share=0.4, prf_hz=PRF_HZ) is None


def test_a_partial_repeat_within_a_period_is_not_taken_for_the_flashes():
    """A rotor whose period of 75 chirps holds one bright flash and, a third and two thirds of a period later, two
    dim ones (point blades' grating flashes): within the ramp it repeats whole at 75, and its third, though nothing
    repeats within it and its multiples lie on it, repeats with a fraction of that (bright with dim flashes): the
    power period 75 whole from whole ramps stays 75, not 25."""
    from mdpipe.process.features import resolved_in_ramp
    rng = np.random.default_rng(11)
    n_chirps, parts, period = 6000, 8, 75.0
    x = (rng.standard_normal((n_chirps, parts)) + 1j * rng.standard_normal((n_chirps, parts))) / np.sqrt(2)
    j = np.arange(int(n_chirps / period) - 1)
    for offset, amplitude in ((0.0, 8.0), (period / 3, 3.0), (2 * period / 3, 3.0)):
        for t in 0.3 + offset + j * period * (1 + 0.003 * np.sin(2 * np.pi * j / len(j))):
            chirp, within = int(t), t % 1.0
            if within < RAMP_SHARE and chirp < n_chirps:
                x[chirp, int(within / RAMP_SHARE * parts)] += amplitude * np.exp(2j * np.pi * rng.uniform())
    train = flashes.ramp_train(x, ramp_share=RAMP_SHARE, prf_hz=PRF_HZ)
    assert flashes.ramp_repeat(train, 25.0) < flashes.RAMP_SETTLE_SHARE * flashes.ramp_repeat(train, 75.0)
    settled = resolved_in_ramp(flashes.PowerPeriod(75.0 / PRF_HZ, True), lambda: train, prf_hz=PRF_HZ)
    assert settled.period_s * PRF_HZ == pytest.approx(75.0)


def test_a_power_that_varies_slowly_does_not_fall_between_its_repeats():
    """Short flashes every 7.5 chirps (30 times the noise floor) fall to the floor between them: the power's
    autocorrelation dips under 0.1 within half a period of the period, and so it does where the whole echo is lit
    1.5 s and dark 0.75 s. A wing echo lit so (a flap-glide bird, 20 times the noise), rippling 30 % every 7.5
    chirps, correlates 0.35 or more at every lag there: its repeat is no flash train."""
    prf_hz, n, period = 3439.2, 5758, 7.5
    t = np.arange(n) / prf_hz
    floor = np.abs(_noise(n, seed=5)) ** 2
    pulses = np.zeros(n)
    pulses[np.round(np.arange(0, n - 1, period)).astype(int)] = 1.0
    assert flashes._falls_between(floor + 30 * pulses, period)
    lit = np.where(t % 2.25 < 1.5, 1.0, 0.05)
    assert flashes._falls_between(lit * (floor + 30 * pulses), period)  # the whole echo swelling: still flashes
    assert not flashes._falls_between(floor + 20 * lit * (1 + 0.3 * np.cos(2 * np.pi * np.arange(n) / period)), period)


def _flank_train(n, period_chirps, *, seed, ramp_share=0.8, flash=30.0, phase=0.3):
    """A flank's power per chirp: unit exponential noise, and a flash of ``flash`` times it in the chirp whose
    ramp (its first ``ramp_share``) holds each passage, every ``period_chirps``."""
    power = np.random.default_rng(seed).exponential(1.0, n)
    for t in np.arange(phase, n, period_chirps):
        if t - int(t) < ramp_share:
            power[int(t)] += flash
    return power


@pytest.mark.parametrize("period_chirps", [5.3, 7.24, 12.7])
def test_flashes_on_both_flanks_give_a_whole_multiple_of_their_period(period_chirps):
    """Flashes shorter than a chirp every 5.3-12.7 chirps, caught by ramps over 80 % of the chirp, on both range
    flanks (noise drawn apart): their power recurs where the sampling comes round again, a whole multiple of the
    flash period (3 or 4 of them here), within 1 %."""
    from mdpipe.process.flashes import flank_flash_period
    flanks = np.stack([_flank_train(2048, period_chirps, seed=1), _flank_train(2048, period_chirps, seed=2)], axis=1)
    found = flank_flash_period(flanks, prf_hz=1757.0, min_period_s=1 / 3000)
    assert found is not None
    multiple = found * 1757.0 / period_chirps
    assert round(multiple) >= 1 and multiple == pytest.approx(round(multiple), rel=0.01)


def test_flashes_on_one_flank_only_or_at_unlike_periods_are_no_drones():
    """Flashes on one flank, the other noise; or flashes on both whose powers repeat at periods not alike (every 7.24
    and 10.86 chirps, read at 28.96 and 11: not within 3 % of 1, 2 or 1/2 of each other); or a power swelling
    slowly on both (no flashes): None."""
    from mdpipe.process.flashes import flank_flash_period
    noise = np.random.default_rng(5).exponential(1.0, 2048)
    one = _flank_train(2048, 7.24, seed=1)
    assert flank_flash_period(np.stack([one, noise], axis=1), prf_hz=1757.0, min_period_s=1 / 3000) is None
    unlike = np.stack([one, _flank_train(2048, 7.24 * 1.5, seed=2)], axis=1)
    assert flank_flash_period(unlike, prf_hz=1757.0, min_period_s=1 / 3000) is None
    t = np.arange(2048)
    swell = 1.0 + 0.8 * np.sin(2 * np.pi * t / 40.0) + 0.1 * noise
    assert flank_flash_period(np.stack([swell, swell[::-1]], axis=1), prf_hz=1757.0, min_period_s=1 / 3000) is None


def test_flanks_reading_a_turn_and_a_chopping_agree():
    """One flank's flashes every 10 chirps, the other's every 10 chirps with every second flash 3 times brighter
    (one blade differing, seen on that side): their powers repeat at 10 and 20 chirps, a factor 2 apart, which
    agree; the shorter is returned."""
    from mdpipe.process.flashes import flank_flash_period, period_of_power
    even = _flank_train(2048, 10.0, seed=3)
    tagged = _flank_train(2048, 20.0, seed=4, flash=90.0) + _flank_train(2048, 20.0, seed=5, phase=10.3) - 1.0
    periods = [period_of_power(p, prf_hz=3000.0, min_period_s=1 / 3000).period_s * 3000.0 for p in (even, tagged)]
    assert periods == pytest.approx([10.0, 20.0], rel=1e-3)  # the chopping on one side, the turn on the other
    found = flank_flash_period(np.stack([even, tagged], axis=1), prf_hz=3000.0, min_period_s=1 / 3000)
    assert found * 3000.0 == pytest.approx(10.0, rel=1e-3)
    assert flank_flash_period(np.stack([tagged, even], axis=1), prf_hz=3000.0, min_period_s=1 / 3000) == found


def test_flank_flashes_repeating_with_the_grid_are_no_drones():
    """Flashes on both flanks every 60 chirps at 3 kHz, 20 ms: the period of a 50 Hz supply's ripple on the gain,
    which swells every static echo in the flanks alike. Under a 50 Hz (or 50-or-60 Hz) grid the rotation stays as the
    target's own bin read it; told there is no grid, the flanks' flashes make it a drone's."""
    from mdpipe.process.features import Rotation, _flashes_in_flanks
    from mdpipe.process.ranging import Flanks
    flanks = Flanks(np.stack([_flank_train(3000, 60.0, seed=1), _flank_train(3000, 60.0, seed=2)], axis=1))
    turn = Rotation.withheld("no_flashes", "rotation not estimable: no periodic blade flashes")
    assert _flashes_in_flanks(turn, lambda: flanks, prf_hz=3000.0, mains_hz=(50.0, 60.0)) is turn
    seen = _flashes_in_flanks(turn, lambda: flanks, prf_hz=3000.0, mains_hz=())
    assert seen.chopping.status == seen.rate.status == "ambiguous_period" and seen.rate.value is None
    assert "a whole multiple of 50 Hz" in seen.chopping.note


@pytest.mark.parametrize("common_period, drone", [(None, True), (20.0, False), (10.0, False), (60.0, False),
                                                  (27.0, True)])
def test_flank_flashes_that_every_range_bin_holds_alike_are_no_drones(common_period, drone):
    """Flashes on both flanks every 20 chirps (3 kHz): a drone's, unless what every range bin of the capture holds in
    common recurs a whole number of times (up to 6) as often or as seldom (here 1, 2 and 3: another radar's bursts,
    too few to count the capture crossed, light both flanks alike); a common mode of noise, or recurring at 27
    chirps, leaves them a drone's."""
    from mdpipe.process.features import Rotation, _flashes_in_flanks
    from mdpipe.process.ranging import Flanks
    power = np.stack([_flank_train(3000, 20.0, seed=1), _flank_train(3000, 20.0, seed=2)], axis=1)
    common = (np.random.default_rng(9).exponential(1.0, 3000) if common_period is None
              else _flank_train(3000, common_period, seed=9, flash=10.0))
    turn = Rotation.withheld("no_flashes", "rotation not estimable: no periodic blade flashes")
    seen = _flashes_in_flanks(turn, lambda: Flanks(power, common), prf_hz=3000.0, mains_hz=())
    assert (seen.chopping.status == "ambiguous_period") is drone and (seen is turn) is not drone


FOUR_ROTORS_CHIRPS = (7.05, 7.16, 7.27, 7.31)  # four rotors' flash periods, 0.6-3.7 % apart


def _interleaved_flank(n, *, seed, flash=6.0, ramp_share=0.8, periods=FOUR_ROTORS_CHIRPS):
    """A flank's power per chirp: unit exponential noise, and each rotor's flashes, every ``periods`` chirps from a
    random start, caught where the ramp (its first ``ramp_share``) holds them, each of an exponential energy of mean
    ``flash`` times the noise (where in the ramp a flash falls moves its energy across the flank's bins)."""
    rng = np.random.default_rng(seed)
    power = rng.exponential(1.0, n)
    for period in periods:
        for t in np.arange(rng.uniform(0, period), n, period):
            if t - int(t) < ramp_share:
                power[int(t)] += flash * rng.exponential(1.0)
    return power


def _flank_line(flanks, *, prf_hz=1600.0, **kw):
    """:func:`mdpipe.process.flashes.flank_line_hz` of ``flanks`` between 40 Hz and 3 kHz, as the features read it."""
    return flashes.flank_line_hz(flanks, prf_hz=prf_hz, min_hz=40.0, max_hz=3000.0, **kw)


def _near_a_multiple(f_hz, choppings_hz, *, prf_hz, most=3, rel=0.003):
    """Whether ``f_hz`` lies within ``rel`` of a multiple (up to ``most``) of one of ``choppings_hz``, folded."""
    return any(abs(abs((k * c + prf_hz / 2) % prf_hz - prf_hz / 2) - f_hz) <= rel * k * c
               for c in choppings_hz for k in range(1, most + 1))


def test_interleaved_rotors_on_both_flanks_share_a_line_where_their_power_shows_no_period():
    """Four rotors' flash trains 0.6-3.7 % apart on both range flanks (1.6 kHz, 4096 chirps, noise and flash energies
    drawn apart): their power's autocorrelation shows no period (:func:`flank_flash_period`), but both flanks'
    spectra share a line within 0.3 % of a multiple (up to 3) of one rotor's chopping frequency, 219-227 Hz."""
    from mdpipe.process.flashes import flank_flash_period
    prf_hz = 1600.0
    flanks = np.stack([_interleaved_flank(4096, seed=5), _interleaved_flank(4096, seed=6)], axis=1)
    assert flank_flash_period(flanks, prf_hz=prf_hz, min_period_s=1 / 3000) is None
    line_hz = _flank_line(flanks, prf_hz=prf_hz)
    assert line_hz is not None
    assert _near_a_multiple(line_hz, [prf_hz / p for p in FOUR_ROTORS_CHIRPS], prf_hz=prf_hz)


def test_a_line_on_one_flank_only_in_the_common_mode_at_half_the_prf_or_on_noise_is_no_flank_line():
    """No shared line where: both flanks hold noise only (10 draws); one flank holds the rotors' flashes and the other
    noise; what every range bin holds in common carries the same flashes (another radar's bursts, or a drone lighting
    every bin); both flanks swell on alternate chirps (two transmitters in turn: a line at PRF / 2); both swell at a
    wingbeat's pace (under ``min_hz``). The shared flashes, with a common mode of noise, are found."""
    prf_hz, n = 1600.0, 4096
    rng = np.random.default_rng(11)
    line = functools.partial(_flank_line, prf_hz=prf_hz)
    for _ in range(10):
        assert line(rng.exponential(1.0, (n, 2))) is None
    flashes = _interleaved_flank(n, seed=5)
    assert line(np.stack([flashes, rng.exponential(1.0, n)], axis=1)) is None
    both = np.stack([flashes, _interleaved_flank(n, seed=6)], axis=1)
    assert line(both, common=rng.exponential(1.0, n)) is not None
    assert line(both, common=_interleaved_flank(n, seed=7)) is None
    t = np.arange(n)
    alternate = 1.0 + 0.5 * (t % 2)
    assert line(rng.exponential(1.0, (n, 2)) * alternate[:, None] * 4) is None
    swell = 1.0 + 0.8 * np.sin(2 * np.pi * 9.0 * t / prf_hz)
    assert line(rng.exponential(0.1, (n, 2)) + swell[:, None]) is None


def test_interleaved_rotors_in_the_flanks_are_a_drone_s_and_a_ripple_s_line_on_the_grid_is_not():
    """Interleaved rotors on both flanks make the target's rotation ``ambiguous_period`` by their shared line (its
    frequency in the note), under a 50-or-60 Hz grid too. Both flanks swelling at 100 Hz (a rectified supply's ripple
    on the gain of the clutter about the target) share a line there: under that grid the rotation stays as the
    target's own bin read it; told there is no grid, the line makes it a drone's."""
    from mdpipe.process.features import Rotation, _flashes_in_flanks
    from mdpipe.process.ranging import Flanks
    prf_hz, n = 1600.0, 4096
    flanks = Flanks(np.stack([_interleaved_flank(n, seed=5), _interleaved_flank(n, seed=6)], axis=1))
    turn = Rotation.withheld("no_flashes", "rotation not estimable: no periodic blade flashes")
    seen = _flashes_in_flanks(turn, lambda: flanks, prf_hz=prf_hz, mains_hz=(50.0, 60.0))
    assert seen.chopping.status == seen.rate.status == "ambiguous_period" and seen.rate.value is None
    line_hz = _flank_line(flanks.power, prf_hz=prf_hz)
    assert f"shares a line at {line_hz:.4g} Hz" in seen.chopping.note
    swell = 1.0 + 0.5 * np.sin(2 * np.pi * 100.0 * np.arange(n) / prf_hz)
    ripple = Flanks(np.random.default_rng(3).exponential(1.0, (n, 2)) * swell[:, None])
    assert _flashes_in_flanks(turn, lambda: ripple, prf_hz=prf_hz, mains_hz=(50.0, 60.0)) is turn
    told = _flashes_in_flanks(turn, lambda: ripple, prf_hz=prf_hz, mains_hz=())
    assert told.chopping.status == "ambiguous_period" and "shares a line at 100 Hz" in told.chopping.note


def _flanks_with_a_line(amplitude, *, n=8192, prf_hz=1600.0, line_hz=300.0, seed=1):
    """Two flanks' powers: unit exponential noise, each plus a sinusoid of ``amplitude`` at ``line_hz`` (phases
    apart)."""
    rng = np.random.default_rng(seed)
    t = np.arange(n)
    return np.stack([rng.exponential(1.0, n) + amplitude * np.sin(2 * np.pi * line_hz * t / prf_hz + phase)
                     for phase in (0.3, 1.9)], axis=1)


def test_a_flank_line_is_read_from_13_db_up_and_off_half_the_prf():
    """A line on both flanks standing 11.7 dB over their medians (the weaker flank's) is not read, one of 15.1 dB is,
    at its frequency; the same line at 0.99 of PRF / 2 (within ``NYQUIST_GUARD``) is not, at 0.95 of it it is; under
    ``min_hz`` it is not."""
    from mdpipe.process.flashes import _lit
    prf_hz = 1600.0
    read = functools.partial(_flank_line, prf_hz=prf_hz)
    weak, strong = _flanks_with_a_line(0.13), _flanks_with_a_line(0.18)
    assert [round(10 * np.log10(min(_lit(f[:, i], prf_hz=prf_hz)(300.0) for i in (0, 1))), 1)
            for f in (weak, strong)] == [11.7, 15.1]
    assert read(weak) is None and read(strong) == pytest.approx(300.0, abs=prf_hz / 8192)
    assert read(_flanks_with_a_line(0.3, line_hz=0.99 * prf_hz / 2)) is None
    assert read(_flanks_with_a_line(0.3, line_hz=0.95 * prf_hz / 2)) == pytest.approx(0.95 * prf_hz / 2, abs=0.2)
    assert read(_flanks_with_a_line(0.3, line_hz=35.0)) is None


def test_a_flank_line_that_the_window_s_sidelobes_carry_from_the_target_or_its_body_s_beat_is_no_flashes():
    """A line both flanks share (15.1 dB) is no flashes' where its power there stands under ``LEAK_MARGIN_DB`` over
    what the range window's sidelobes carry of the target's own power's line (twice their share in dB): the target's
    line 10 times the flanks' in amplitude (their power's power 20 dB apart) is leakage through sidelobes of -10 dB
    (a share that reaches -5 dB), not through Hann's -30 dB (-45 dB); as strong as the flanks' it is leakage through
    neither. Nor is a line on a steady body's Doppler or twice it (its beats with clutter's residue and its mirror
    image); it is where the body's Doppler, times the order, swings over more than 50 Hz (its beats smeared)."""
    prf_hz, n = 1600.0, 8192
    flanks = _flanks_with_a_line(0.18)
    t = np.arange(n)
    rng = np.random.default_rng(4)
    read = functools.partial(_flank_line, flanks, prf_hz=prf_hz)
    loud = rng.exponential(1.0, n) + 1.8 * np.sin(2 * np.pi * 300.0 * t / prf_hz)
    alike = rng.exponential(1.0, n) + 0.18 * np.sin(2 * np.pi * 300.0 * t / prf_hz)
    assert read(own=loud, leak_db=-10.0) is None
    assert read(own=loud, leak_db=-30.0) == pytest.approx(300.0, abs=0.2)
    assert read(own=alike, leak_db=-10.0) == pytest.approx(300.0, abs=0.2)
    for body_hz in (300.0, -150.0, 1300.0, 500.0):  # 1300 Hz folds to -300; 500 Hz and twice it, -600, lie off
        expected = pytest.approx(300.0, abs=0.2) if body_hz == 500.0 else None
        assert read(body_hz=body_hz) == expected
    assert read(body_hz=-150.0, body_spread_hz=24.0) is None  # twice it swings over 48 Hz: its beat reaches 300
    assert read(body_hz=-150.0, body_spread_hz=26.0) == pytest.approx(300.0, abs=0.2)


def test_a_range_window_s_sidelobes_carry_a_tabled_share_of_a_target_into_its_flanks():
    """``ranging.flank_leak_db``: the greater share of a target's power in one of its flanks (bins 3-66 off, the
    target anywhere within half a bin of its bin), at most: Hann -30.1 dB, Hamming -31.4, Blackman (bins 4-67) -53.6,
    a boxcar (bins 2-65) -6.3, within 0.1 dB (each at its worst half a bin off: read at that offset alone, the same)."""
    from mdpipe.process.ranging import MAIN_LOBE_BINS, flank_leak_db
    for window, share_db in (("hann", -30.1), ("hamming", -31.4), ("blackman", -53.6), ("boxcar", -6.3)):
        assert flank_leak_db(window, 128, MAIN_LOBE_BINS[window] + 0.5, 128.0) == pytest.approx(share_db, abs=0.1)
        assert flank_leak_db(window, 128, MAIN_LOBE_BINS[window] + 0.5, 128.0, offsets=1) == pytest.approx(
            share_db, abs=0.1)
