"""Echoes that are nothing but one or two samples over the noise: an impulse (a glitch, a click), not a target.

A glitch in the receiver (one ADC sample far off; a sound card's click in a CW recording) is broadband: read as a
target's echo it fills the whole Doppler span, which reads as a drone's aliased blades (a CW recording of noise with
one sample 1000 times the noise's amplitude read as a drone, SNR 17 dB; a float capture of 128 chirps with one sample
at 1e10 read four movers). A target's moving echo lasts: a body line over the dwell, blades flashing every chopping
period, wings beating. Its strongest samples may hold most of its power (a 94 GHz drone's flashes caught at their
peaks by a CW receiver sampling at 11.8 kHz: two samples held 62 %), but its other samples stand over the noise too.
An echo whose ``IMPULSE_SAMPLES`` strongest samples (with ``IMPULSE_SPREAD`` samples either side of each: a click
rings) stand ``MIN_EXCESS_SIGMAS`` standard deviations of the noise's summed power over what noise puts there, while
its other samples do not stand that far over the noise, is read as an impulse: class ``none``, every feature but its
SNR withheld as ``impulse``.
"""

import math
from dataclasses import dataclass

import numpy as np

from mdpipe.process.features import read_as, withheld_row

IMPULSE_SAMPLES = 2
IMPULSE_SPREAD = 4        # samples either side of each that ring with it
MIN_EXCESS_SIGMAS = 10.0  # power over the noise, in standard deviations of n noise samples' summed power


@dataclass(frozen=True)
class Impulse:
    """The power over the noise in an echo's strongest samples and in the others, in standard deviations of the
    noise's summed power over the echo's samples."""

    strongest_sigmas: float
    others_sigmas: float

    @property
    def found(self):
        return self.strongest_sigmas >= MIN_EXCESS_SIGMAS and self.others_sigmas < MIN_EXCESS_SIGMAS


def impulse(signal, noise_power):
    """The :class:`Impulse` reading of ``signal`` (the mean of the samples outside the impulse removed; ``noise_power``
    per sample): its
    ``IMPULSE_SAMPLES`` strongest samples, each with ``IMPULSE_SPREAD`` samples either side (a click rings through
    the receiver's filter: a third sample at 6 % of the peak had let one read as a drone), against the others.

    Noise's strongest two of n exponential powers average ``2 H_n - 1`` times its mean (H_n the harmonic number);
    the samples beside them, and the others, its mean (a little over and under it: the test errs towards a target)."""
    signal = np.asarray(signal)
    n = len(signal)
    if n <= 2 * IMPULSE_SAMPLES * (2 * IMPULSE_SPREAD + 1) or noise_power <= 0:
        return Impulse(0.0, 0.0)
    sigma = math.sqrt(n) * noise_power
    power = np.abs(signal - np.mean(signal)) ** 2
    region = np.zeros(n, dtype=bool)
    for _ in range(IMPULSE_SAMPLES):
        peak = int(np.argmax(np.where(region, -np.inf, power)))
        region[max(peak - IMPULSE_SPREAD, 0):peak + IMPULSE_SPREAD + 1] = True
    # the mean of the others, not of all: a click of power P in the mean would lift each other sample by P / n^2
    power = np.abs(signal - np.mean(signal[~region])) ** 2
    harmonic = math.log(n) + np.euler_gamma + 1.0 / (2 * n)
    peaks_noise = IMPULSE_SAMPLES * harmonic - IMPULSE_SAMPLES * (IMPULSE_SAMPLES - 1) / 2
    inside = float(power[region].sum()) - (peaks_noise + np.count_nonzero(region) - IMPULSE_SAMPLES) * noise_power
    others = float(power[~region].sum()) - np.count_nonzero(~region) * noise_power
    return Impulse(inside / sigma, others / sigma)


def impulsive_rows(rows, signals, noise_power, capture_notes=()):
    """The target rows of one capture or recording (``signals``: each target's slow time), those whose echo is an
    impulse withheld as ``impulse``; the others as they are."""
    out = []
    for row, signal in zip(rows, signals):
        reading = impulse(signal, noise_power)
        if row["target"] is not None and reading.found:
            note = (f"class: an impulse, not a target: this echo's {IMPULSE_SAMPLES} strongest samples and the "
                    f"{IMPULSE_SPREAD} beside each stand {reading.strongest_sigmas:.3g} standard deviations over the "
                    f"noise, its others within {MIN_EXCESS_SIGMAS:g} of it (a glitch or a click; a target's echo "
                    f"lasts); {read_as(row)}")
            row = withheld_row(row, status="impulse", note=note, capture_notes=capture_notes)
        out.append(row)
    return out
