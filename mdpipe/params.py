"""Parameter sets, one frozen dataclass each, validated on construction.

All quantities are SI; names carry their unit.
"""

from dataclasses import dataclass, field, replace
from typing import Optional

import numpy as np

from mdpipe.errors import ParameterError
from mdpipe.physics.radar import SPEED_OF_LIGHT_MPS, range_rate_from_doppler_mps


def require_positive(**values):
    """Raise :class:`ParameterError` naming the first value that is not a finite number > 0."""
    for name, value in values.items():
        if not (np.isfinite(value) and value > 0):
            raise ParameterError(f"{name}={value!r} must be a finite number > 0")


def check_limits(params, limits, *, giga=()):
    """Raise :class:`ParameterError` naming the first field of ``params`` outside its ``limits`` (field -> (lowest,
    highest, unit, meaning)) or not a finite number; for a field in ``giga`` given in GHz, the hint says so."""
    for name, (low, high, unit, meaning) in limits.items():
        value = getattr(params, name)
        if not (isinstance(value, (int, float, np.integer, np.floating)) and np.isfinite(value)
                and low <= value <= high):
            hint = ""
            if name in giga and np.isfinite(value) and low <= value * 1e9 <= high:
                hint = f"; did you mean {value:g}e9?"
            raise ParameterError(f"{name}={value!r} must be a finite number in [{low:g}, {high:g}]"
                                 f"{' ' + unit if unit else ''} ({meaning}){hint}")


# field -> (lowest, highest, unit, meaning): the values a radar engineer would accept, VHF to 300 GHz.
# N >= 8 keeps a range FFT meaningful; 256 RX covers cascaded MIMO front ends (Radarlog: 16).
RADAR_LIMITS = {
    "f_start_hz": (1e8, 3e11, "Hz", "chirp start frequency: 100 MHz to 300 GHz"),
    "f_stop_hz": (1e8, 3e11, "Hz", "chirp stop frequency: 100 MHz to 300 GHz"),
    "ramp_up_s": (1e-7, 1.0, "s", "up-ramp duration: 100 ns to 1 s"),
    "chirp_period_s": (1e-7, 1.0, "s", "chirp repetition interval: 100 ns to 1 s"),
    "ramp_down_s": (0.0, 1.0, "s", "down-ramp duration: 0 to 1 s"),
    "sample_rate_hz": (1e3, 1e9, "Hz", "ADC sample rate: 1 kHz to 1 GHz"),
    "n_samples": (8, 65536, "", "samples per chirp: 8 to 65536"),
    "n_channels": (1, 256, "", "RX channels: 1 to 256"),
    "full_scale_v_per_lsb": (1e-12, 1e3, "V/LSB", "volts per ADC count: 1 pV to 1 kV"),
}


GIB = 2**30  # bytes in a GiB, for the memory and disk budgets of processing and simulation
MAX_TRANSMITTERS = 16  # transmitters a radar's chirps may cycle through
MAX_TX_SEQUENCE = 64   # chirps of one transmit cycle (TxSeq)
MAX_BLADES = 12        # blades per rotor (a ducted fan's at most)


def transmit_cycle(sequence):
    """Chirps per transmit cycle of ``sequence`` (``TxSeq``: the transmitter of each chirp, in turn): its shortest
    repeat, 1 where it holds one transmitter (every chirp alike). A cycle ``[1, 2]`` puts each transmitter's chirps
    2 Tp apart."""
    sequence = list(sequence)
    if len(set(sequence)) <= 1:
        return 1
    return next(period for period in range(2, len(sequence) + 1)
                if len(sequence) % period == 0 and sequence == sequence[:period] * (len(sequence) // period))


@dataclass(frozen=True)
class RadarParams:
    """FMCW chirp parameters of a capture (the Radarlog attributes, in SI units).

    Parameters
    ----------
    f_start_hz, f_stop_hz : float
        Chirp start and stop frequencies (``fStrt``, ``fStop``).
    ramp_up_s : float
        Duration of the sampled up-ramp (``TRampUp``).
    chirp_period_s : float
        Chirp repetition interval, the slow-time sample period (``Tp``).
    sample_rate_hz : float
        ADC sample rate (``fs``).
    n_samples : int
        Samples per chirp (``N``).
    n_channels : int
        RX channels (``NrChn``).
    ramp_down_s : float
        Down-ramp duration (``TRampDo``); informational.
    full_scale_v_per_lsb : float
        Volts per ADC count (``FuSca``).
    rx_positions_m : tuple of float
        RX positions along the array axis, one per channel; empty when unknown.

    Every number must be finite and inside its range in ``RADAR_LIMITS``; the samples must fit in the
    up-ramp (``N / fs <= TRampUp``) and the up-ramp in the chirp period.
    """

    f_start_hz: float
    f_stop_hz: float
    ramp_up_s: float
    chirp_period_s: float
    sample_rate_hz: float
    n_samples: int
    n_channels: int = 1
    ramp_down_s: float = 0.0
    full_scale_v_per_lsb: float = 1.0
    rx_positions_m: tuple = field(default=())

    def __post_init__(self):
        check_limits(self, RADAR_LIMITS, giga=("f_start_hz", "f_stop_hz"))
        for name in ("n_samples", "n_channels"):
            if int(getattr(self, name)) != getattr(self, name):
                raise ParameterError(f"{name}={getattr(self, name)!r} must be an integer")
        if not self.f_stop_hz > self.f_start_hz:
            raise ParameterError(
                f"f_stop_hz={self.f_stop_hz!r} must exceed f_start_hz={self.f_start_hz!r} (an up-chirp)"
            )
        if self.n_samples / self.sample_rate_hz > self.ramp_up_s * (1 + 1e-9):
            raise ParameterError(
                f"n_samples / sample_rate_hz = {self.n_samples / self.sample_rate_hz:.6g} s exceeds "
                f"ramp_up_s={self.ramp_up_s!r}: the samples must fit in the up-ramp"
            )
        if self.ramp_up_s > self.chirp_period_s * (1 + 1e-9):
            raise ParameterError(
                f"ramp_up_s={self.ramp_up_s!r} exceeds chirp_period_s={self.chirp_period_s!r}"
            )
        positions = tuple(float(p) for p in self.rx_positions_m)
        if not all(np.isfinite(positions)):
            raise ParameterError(f"rx_positions_m={positions!r} must be finite")
        if positions and len(positions) != self.n_channels:
            raise ParameterError(
                f"rx_positions_m has {len(positions)} entries for n_channels={self.n_channels}"
            )
        object.__setattr__(self, "rx_positions_m", positions)
        object.__setattr__(self, "n_samples", int(self.n_samples))
        object.__setattr__(self, "n_channels", int(self.n_channels))

    @property
    def bandwidth_hz(self):
        """Swept bandwidth ``fStop - fStrt``."""
        return self.f_stop_hz - self.f_start_hz

    @property
    def slope_hz_per_s(self):
        """Sweep slope ``S = (fStop - fStrt) / TRampUp``."""
        return self.bandwidth_hz / self.ramp_up_s

    @property
    def centre_hz(self):
        """Carrier used for Doppler, the centre of the sweep."""
        return 0.5 * (self.f_start_hz + self.f_stop_hz)

    @property
    def wavelength_m(self):
        """Wavelength at the centre frequency."""
        return SPEED_OF_LIGHT_MPS / self.centre_hz

    @property
    def range_bin_m(self):
        """Spacing of the N-point range-FFT bins, ``fs c / (2 S N)``."""
        return self.sample_rate_hz * SPEED_OF_LIGHT_MPS / (2.0 * self.slope_hz_per_s * self.n_samples)

    @property
    def max_range_m(self):
        """Range of the last positive-frequency bin of a real IF (``N/2`` bins)."""
        return self.range_bin_m * (self.n_samples // 2)

    @property
    def prf_hz(self):
        """Chirp repetition frequency ``1 / Tp``, the slow-time sample rate."""
        return 1.0 / self.chirp_period_s

    @property
    def doppler_span_hz(self):
        """Unambiguous Doppler span ``1 / Tp`` (from ``-1/(2 Tp)`` to ``+1/(2 Tp)``)."""
        return self.prf_hz

    def aliases(self, low_hz, high_hz):
        """Whether a Doppler extent ``[low_hz, high_hz]`` leaves the unambiguous span (it then folds)."""
        return bool(high_hz > self.doppler_span_hz / 2 or low_hz < -self.doppler_span_hz / 2)

    @property
    def velocity_span_mps(self):
        """Unambiguous range-rate span, ``lambda / (2 Tp)``."""
        return float(-range_rate_from_doppler_mps(self.doppler_span_hz, wavelength_m=self.wavelength_m))

    @property
    def sample_times_s(self):
        """Fast-time instants of the samples within a ramp, shape (n_samples,)."""
        return np.arange(self.n_samples) / self.sample_rate_hz

    @property
    def sampled_duration_s(self):
        """Time spanned by one chirp's samples, ``N / fs``."""
        return self.n_samples / self.sample_rate_hz

    def duration_s(self, n_chirps):
        """Capture duration for ``n_chirps`` chirps."""
        return n_chirps * self.chirp_period_s

    def every(self, stride):
        """These parameters for every ``stride``-th chirp (one transmitter's of a cycle of ``stride``): Tp times
        ``stride``."""
        return self if stride == 1 else replace(self, chirp_period_s=stride * self.chirp_period_s)


# field -> (lowest, highest, unit, meaning) of an I/Q (CW) recording: a slow radar module's rates to an SDR's.
IQ_LIMITS = {
    "carrier_hz": (1e8, 3e11, "Hz", "carrier frequency: 100 MHz to 300 GHz"),
    "sample_rate_hz": (100.0, 1e9, "Hz", "I/Q sample rate: 100 Hz to 1 GHz"),
    "n_channels": (1, 256, "", "RX channels (I/Q pairs): 1 to 256"),
    "full_scale_v_per_lsb": (1e-12, 1e3, "V/LSB", "volts per count: 1 pV to 1 kV"),
}


@dataclass(frozen=True)
class IqParams:
    """A continuous-wave (CW) radar's recording of complex baseband (I/Q) samples: its slow time, sampled at
    ``sample_rate_hz``, with no range (``mdpipe.io.iq``).

    Parameters
    ----------
    carrier_hz : float
        Transmitted frequency, for Doppler.
    sample_rate_hz : float
        I/Q samples per second per channel: the slow-time rate (the pulse repetition frequency's part).
    n_channels : int
        RX channels, one I/Q pair each.
    full_scale_v_per_lsb : float
        Volts per count of integer samples.
    """

    carrier_hz: float
    sample_rate_hz: float
    n_channels: int = 1
    full_scale_v_per_lsb: float = 1.0

    def __post_init__(self):
        check_limits(self, IQ_LIMITS, giga=("carrier_hz",))
        if int(self.n_channels) != self.n_channels:
            raise ParameterError(f"n_channels={self.n_channels!r} must be an integer")
        object.__setattr__(self, "n_channels", int(self.n_channels))

    @property
    def centre_hz(self):
        """Carrier used for Doppler."""
        return self.carrier_hz

    @property
    def wavelength_m(self):
        """Wavelength of the carrier."""
        return SPEED_OF_LIGHT_MPS / self.carrier_hz

    @property
    def prf_hz(self):
        """The slow-time sample rate: the I/Q sample rate."""
        return self.sample_rate_hz

    @property
    def doppler_span_hz(self):
        """Unambiguous Doppler span of complex samples, the sample rate."""
        return self.sample_rate_hz

    @property
    def velocity_span_mps(self):
        """Unambiguous range-rate span, ``lambda fs / 2``."""
        return float(-range_rate_from_doppler_mps(self.doppler_span_hz, wavelength_m=self.wavelength_m))

    def duration_s(self, n_samples):
        """Recording duration for ``n_samples`` I/Q samples."""
        return n_samples / self.sample_rate_hz


@dataclass(frozen=True)
class ProcessParams:
    """Choices of ``mdpipe process``; the defaults are what a Radarlog user would start with.

    Parameters
    ----------
    min_range_m, max_range_m : float
        Gate in which targets are searched.
    range_m : float or None
        Analyse this range (manual bin choice) instead of detecting.
    max_targets : int
        Most targets reported per capture.
    false_alarm_probability : float
        Probability that noise alone gives a detection in a capture (range-Doppler CFAR thresholds).
    elevation_deg : float or None
        Elevation beta of the rotor plane (Eq. 6), for the blade-length inversion; None: not known,
        0 assumed and said so (the echo gives r cos(beta) only).
    n_blades : int or None
        Blades per rotor (N), for rotation rate = chopping frequency / N; None: measured from the echo
        where it tells (blade imbalance, odd-N flash doubling), else assumed and said so.
    threshold_db : float
        The paper's bandwidth rule: spectrum above its mean by this many dB.
    range_window, zero_pad : str, int
        Range-FFT window (``hann``, ``hamming``, ``blackman``, ``boxcar``) and zero-padding factor.
    stft_window_s, stft_hop_s : float or None
        Spectrogram window and hop of the figure; None chooses them from the physics of the target.
    edge_window_periods, edge_hop_fraction : float
        Spectrogram that measures the flash edges: its first window in chopping periods (a quarter holds
        one flash whole; lengthened, up to a flash period and a quarter turn, until the tips span 10
        Doppler bins a side), hop as a fraction of the window.
    dtype : str
        ``float32`` or ``float64`` for the range transform of pass 2.
    range_bins : str
        ``in-use`` evaluates the range DFT only at the bins a target occupies (a matrix product);
        ``all`` takes the full FFT and picks them (for comparison).
    chunk_chirps : int
        Chirps read per chunk.
    max_memory_gb : float
        A capture whose planned memory (:mod:`mdpipe.process.memory`) exceeds this many GiB is refused.
    mains_hz : str
        Mains hum searched in each echo and taken out (:mod:`mdpipe.process.mains`): ``auto`` (50 and 60 Hz),
        ``50``, ``60``, or ``none`` (a receiver on batteries, or a rotor held at a multiple of the grid's rate); range
        flanks recurring with these are not read as blade flashes (:mod:`mdpipe.process.features`), with ``none``
        they may be.
    transmitters : str
        Transmitters the chirps take in turn (:mod:`mdpipe.process.transmitters`): ``auto`` (the file's ``TxSeq``,
        else found on the static echoes) or a count (``1``: every chirp read as one sequence); the first one's chirps
        are read.
    """

    min_range_m: float = 1.0
    max_range_m: float = 200.0
    range_m: Optional[float] = None
    max_targets: int = 4
    false_alarm_probability: float = 1e-3
    elevation_deg: Optional[float] = None
    n_blades: Optional[int] = None
    threshold_db: float = 20.0
    range_window: str = "hann"
    zero_pad: int = 1
    stft_window_s: Optional[float] = None
    stft_hop_s: Optional[float] = None
    edge_window_periods: float = 0.25
    edge_hop_fraction: float = 0.125
    dtype: str = "float32"
    range_bins: str = "in-use"
    chunk_chirps: int = 256
    max_memory_gb: float = 2.0
    mains_hz: str = "auto"
    transmitters: str = "auto"

    def __post_init__(self):
        require_positive(max_range_m=self.max_range_m, chunk_chirps=self.chunk_chirps,
                         max_memory_gb=self.max_memory_gb)
        if not 0 <= self.min_range_m < self.max_range_m:
            raise ParameterError(f"min_range_m={self.min_range_m!r} must lie in [0, max_range_m={self.max_range_m!r})")
        if self.range_m is not None:
            require_positive(range_m=self.range_m)
        if not MIN_FALSE_ALARM_PROBABILITY <= self.false_alarm_probability < 1:
            raise ParameterError(f"false_alarm_probability={self.false_alarm_probability!r} must lie in "
                                 f"[{MIN_FALSE_ALARM_PROBABILITY:g}, 1)")
        if not 0 < self.threshold_db <= MAX_THRESHOLD_DB:
            raise ParameterError(f"threshold_db={self.threshold_db!r} must lie in (0, {MAX_THRESHOLD_DB:g}] dB")
        if self.elevation_deg is not None and not -90 <= self.elevation_deg <= 90:
            raise ParameterError(f"elevation_deg={self.elevation_deg!r} must lie in [-90, 90]")
        if self.n_blades is not None and (int(self.n_blades) != self.n_blades or not 1 <= self.n_blades <= MAX_BLADES):
            raise ParameterError(f"n_blades={self.n_blades!r} must be an integer from 1 to {MAX_BLADES}")
        if int(self.max_targets) != self.max_targets or self.max_targets < 1:
            raise ParameterError(f"max_targets={self.max_targets!r} must be an integer >= 1")
        if self.range_window not in RANGE_WINDOWS:
            raise ParameterError(f"range_window={self.range_window!r} must be one of {', '.join(RANGE_WINDOWS)}")
        if int(self.zero_pad) != self.zero_pad or not 1 <= self.zero_pad <= 16:
            raise ParameterError(f"zero_pad={self.zero_pad!r} must be an integer from 1 to 16")
        require_positive(edge_window_periods=self.edge_window_periods, edge_hop_fraction=self.edge_hop_fraction)
        if self.dtype not in ("float32", "float64"):
            raise ParameterError(f"dtype={self.dtype!r} must be float32 or float64")
        if self.range_bins not in ("in-use", "all"):
            raise ParameterError(f"range_bins={self.range_bins!r} must be in-use or all")
        for name in ("stft_window_s", "stft_hop_s"):
            value = getattr(self, name)
            if value is not None:
                require_positive(**{name: value})
                if value > MAX_STFT_S:
                    raise ParameterError(f"{name}={value!r} must be at most {MAX_STFT_S:g} s (it is cut to half the "
                                         "dwell anyway)")
        if self.mains_hz not in MAINS_CHOICES:
            raise ParameterError(f"mains_hz={self.mains_hz!r} must be one of {', '.join(MAINS_CHOICES)}")
        object.__setattr__(self, "transmitters", str(self.transmitters).strip().lower())
        if self.transmitters != "auto" and not (self.transmitters.isdigit()
                                                and 1 <= int(self.transmitters) <= MAX_TRANSMITTERS):
            raise ParameterError(f"transmitters={self.transmitters!r} must be auto or a count from 1 to "
                                 f"{MAX_TRANSMITTERS}")

    @property
    def transmitters_given(self):
        """The transmit cycle given (chirps), or None for ``auto``."""
        return None if self.transmitters == "auto" else int(self.transmitters)

    @property
    def mains_frequencies_hz(self):
        """The grid frequencies whose hum is searched (Hz): none for ``mains_hz`` ``none``."""
        return {"auto": (50.0, 60.0), "50": (50.0,), "60": (60.0,), "none": ()}[self.mains_hz]


RANGE_WINDOWS = ("hann", "hamming", "blackman", "boxcar")
MAINS_CHOICES = ("auto", "50", "60", "none")
MIN_FALSE_ALARM_PROBABILITY = 1e-12  # a CFAR threshold's inverse gamma stays finite down to here
MAX_THRESHOLD_DB = 100.0
MAX_STFT_S = 1e4
MAX_DOPPLER_LIMIT_HZ = 1e7  # 16 km/s at 94 GHz: beyond any target


DOPPLER_LIMIT_MODES = ("auto", "full")


@dataclass(frozen=True)
class FigureParams:
    """Choices of the figures only (nothing measured depends on them).

    Parameters
    ----------
    doppler_limits : str or (float, float)
        Doppler axis of the spectrogram and spectrum figures: ``auto`` (the occupied band with a
        margin, the unambiguous span marked), ``full`` (the whole span ``-PRF/2 .. PRF/2``), or
        ``(low_hz, high_hz)``.
    """

    doppler_limits: object = "auto"

    def __post_init__(self):
        limits = self.doppler_limits
        if isinstance(limits, str):
            if limits not in DOPPLER_LIMIT_MODES:
                raise ParameterError(f"doppler_limits={limits!r} must be auto, full or LOW,HIGH in Hz")
            return
        low, high = (float(v) for v in limits)
        if not (-MAX_DOPPLER_LIMIT_HZ <= low < high <= MAX_DOPPLER_LIMIT_HZ):
            raise ParameterError(f"doppler_limits=({low:g}, {high:g}) must have LOW < HIGH within "
                                 f"+-{MAX_DOPPLER_LIMIT_HZ:g} Hz")
        object.__setattr__(self, "doppler_limits", (low, high))

    @classmethod
    def from_text(cls, text):
        """Parse ``auto``, ``full`` or ``LOW,HIGH`` (Hz), as ``--doppler-limits`` takes it."""
        text = text.strip()
        if text in DOPPLER_LIMIT_MODES:
            return cls(text)
        parts = text.split(",")
        try:
            if len(parts) != 2:
                raise ValueError
            limits = tuple(float(p) for p in parts)
        except ValueError:
            raise ParameterError(f"--doppler-limits {text!r}: give auto, full or LOW,HIGH in Hz "
                                 "(e.g. -500,800)") from None
        return cls(limits)
