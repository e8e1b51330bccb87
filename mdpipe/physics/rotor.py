"""Rotor blades: echo models and the relations of the paper's Eqs. 1-6.

Geometry (Chen; paper Fig. 1): a blade of the rotor turns in the rotor plane at angle
``theta(t) = 2 pi f_rot t + phase0 + 2 pi k / N`` measured from the line of sight's projection on
that plane; the plane is seen at elevation ``beta``. A blade point at distance ``rho`` from the hub
lies ``rho cos(beta) cos(theta)`` further along the line of sight than the hub.

Echoes follow the paper's convention ``exp(-j 4 pi R / lambda)`` and are returned relative to the
hub (the hub's own carrier phase is applied by the caller), normalised so that a blade seen
broadside (a flash) has magnitude equal to its span ``tip - root`` in metres.
"""

import numpy as np

from mdpipe.errors import ParameterError

SPEED_OF_SOUND_MPS = 343.0  # no blade tip of a drone's rotor moves faster
MAX_ROTOR_TIP_MPS = 150.0   # multirotor blade tips move at 20-150 m/s


def blade_angles_rad(t_s, *, rotation_rate_hz, n_blades, phase0_rad=0.0):
    """Angles of the ``n_blades`` blades at times ``t_s``.

    Returns
    -------
    ndarray, shape (..., n_blades), rad
        Negative ``rotation_rate_hz`` turns the other way.
    """
    t = np.asarray(t_s, dtype=np.float64)[..., None]
    offsets = 2.0 * np.pi * np.arange(n_blades) / n_blades
    return 2.0 * np.pi * rotation_rate_hz * t + phase0_rad + offsets


def segment_echo(range_a_m, range_b_m, *, length_m, wavelength_m):
    """Closed-form echo of a uniform straight segment whose ends lie at ranges ``range_a_m``, ``range_b_m``.

    The line integral of ``exp(-j 4 pi R(s) / lambda) ds`` along a segment of length ``L`` whose
    range varies linearly between its ends is ``L exp(-j 2 pi (Ra + Rb) / lambda)
    sinc(2 (Rb - Ra) / lambda)`` (numpy's normalised sinc). Pass ranges relative to a reference
    (e.g. the hub) to keep phases small; the result is then relative to that reference.
    """
    ra = np.asarray(range_a_m, dtype=np.float64)
    rb = np.asarray(range_b_m, dtype=np.float64)
    return length_m * np.exp(-2j * np.pi * (ra + rb) / wavelength_m) * np.sinc(2.0 * (rb - ra) / wavelength_m)


def tapered_segment_echo(range_a_m, range_b_m, *, length_m, wavelength_m, end_reflectivity):
    """Closed-form echo of a straight segment whose reflectivity falls linearly from 1 at end a to
    ``end_reflectivity`` at end b (ranges linear along it, as in :func:`segment_echo`).

    With ``w`` in [-1/2, 1/2] along the segment, ``a(w) = abar + delta w`` (``abar = (1 + e) / 2``,
    ``delta = e - 1``) and ``y = 2 pi (Rb - Ra) / lambda``, the integral is
    ``L exp(-j 2 pi (Ra + Rb) / lambda) [abar j0(y) - (j / 2) delta j1(y)]`` with the spherical Bessel
    functions ``j0(y) = sin y / y`` and ``j1(y) = (sin y - y cos y) / y^2``. ``end_reflectivity = 1``
    is the uniform segment.
    """
    ra = np.asarray(range_a_m, dtype=np.float64)
    rb = np.asarray(range_b_m, dtype=np.float64)
    y = 2.0 * np.pi * (rb - ra) / wavelength_m
    mean = 0.5 * (1.0 + end_reflectivity)
    slope = end_reflectivity - 1.0
    j0 = np.sinc(y / np.pi)
    return length_m * np.exp(-2j * np.pi * (ra + rb) / wavelength_m) * (mean * j0 - 0.5j * slope * spherical_j1(y))


def spherical_j1(y):
    """Spherical Bessel function ``j1(y) = (sin y - y cos y) / y^2`` (series near 0, where the difference cancels)."""
    y = np.asarray(y, dtype=np.float64)
    small = np.abs(y) < 0.1
    safe = np.where(small, 1.0, y)
    direct = (np.sin(safe) - safe * np.cos(safe)) / safe**2
    y2 = y * y
    series = y / 3.0 * (1.0 - y2 / 10.0 * (1.0 - y2 / 28.0 * (1.0 - y2 / 54.0)))
    return np.where(small, series, direct)


BLADE_PROFILES = ("uniform", "tapered", "points")


def blade_echoes(theta_rad, *, blade_length_m, wavelength_m, elevation_deg=0.0, root_m=0.0, profile="uniform",
                 tip_reflectivity=1.0, points_per_blade=None):
    """Echo of each blade relative to its hub for blade angles ``theta_rad`` (..., n_blades).

    ``profile`` chooses the reflectivity along the span: ``uniform`` (closed-form line integral,
    :func:`segment_echo`), ``tapered`` (amplitude falling linearly from 1 at the root to
    ``tip_reflectivity`` at the tip, :func:`tapered_segment_echo`) or ``points`` (the paper's Eq. 1:
    ``points_per_blade`` = Q equal points at the mid-points of Q equal pieces, each of amplitude
    ``(tip - root) / Q``). A uniform blade seen broadside has magnitude ``tip - root`` (m).

    Returns
    -------
    ndarray, complex128, shape of ``theta_rad``
    """
    if not 0.0 <= root_m < blade_length_m:
        raise ParameterError(f"root_m={root_m!r} must lie in [0, blade_length_m={blade_length_m!r})")
    if profile not in BLADE_PROFILES:
        raise ParameterError(f"blade profile {profile!r} must be one of {', '.join(BLADE_PROFILES)}")
    projection = np.cos(np.deg2rad(elevation_deg)) * np.cos(theta_rad)  # (..., n_blades)
    span_m = blade_length_m - root_m
    if profile == "uniform":
        return segment_echo(root_m * projection, blade_length_m * projection, length_m=span_m,
                            wavelength_m=wavelength_m)
    if profile == "tapered":
        return tapered_segment_echo(root_m * projection, blade_length_m * projection, length_m=span_m,
                                    wavelength_m=wavelength_m, end_reflectivity=tip_reflectivity)
    if points_per_blade is None or int(points_per_blade) != points_per_blade or points_per_blade < 1:
        raise ParameterError(f"points_per_blade={points_per_blade!r} must be an integer >= 1")
    rho_m = root_m + span_m * (np.arange(points_per_blade) + 0.5) / points_per_blade
    phase = (-4j * np.pi / wavelength_m) * projection[..., None] * rho_m
    return (span_m / points_per_blade) * np.exp(phase).sum(axis=-1)


def rotor_echo(t_s, *, rotation_rate_hz, n_blades, blade_length_m, wavelength_m, elevation_deg=0.0,
               root_m=0.0, phase0_rad=0.0, points_per_blade=None):
    """Echo of one rotor turning at a constant rate, relative to its hub, summed over its blades.

    Parameters
    ----------
    t_s : array_like, s
        Times at which to evaluate.
    rotation_rate_hz : float
        Revolutions per second (the paper's omega_p); the sign gives the spin direction.
    n_blades : int
        Blades on the rotor (N).
    blade_length_m : float
        Distance from the hub to the blade tip (the paper's r).
    wavelength_m : float
        Carrier wavelength.
    elevation_deg : float
        Elevation beta of the rotor plane seen from the radar.
    root_m : float
        Distance from the hub to where the reflecting blade starts.
    phase0_rad : float
        Angle of blade 0 at t = 0.
    points_per_blade : int or None
        None for the closed-form line integral (:func:`segment_echo`); an integer Q for the paper's
        Eq. 1 with Q point scatterers per blade (see :func:`blade_echoes`), which converges to the
        closed form as Q grows.

    Returns
    -------
    ndarray, complex128, shape of ``t_s``
    """
    theta = blade_angles_rad(t_s, rotation_rate_hz=rotation_rate_hz, n_blades=n_blades, phase0_rad=phase0_rad)
    return blade_echoes(theta, blade_length_m=blade_length_m, wavelength_m=wavelength_m,
                        elevation_deg=elevation_deg, root_m=root_m,
                        profile="uniform" if points_per_blade is None else "points",
                        points_per_blade=points_per_blade).sum(axis=-1)


def chopping_frequency_hz(rotation_rate_hz, *, n_blades):
    """Spacing of the spectral lines, ``f_c = N omega_p / (2 pi) = N f_rot`` (Eq. 5)."""
    return n_blades * np.abs(rotation_rate_hz)


def rotation_rate_from_chopping_hz(chopping_hz, *, n_blades):
    """Inverse of :func:`chopping_frequency_hz`: revolutions per second."""
    return np.asarray(chopping_hz, dtype=np.float64) / n_blades


def flashes_per_revolution(n_blades):
    """Blade flashes (a blade broadside to the radar) per revolution: N for even N, 2N for odd N."""
    return n_blades if n_blades % 2 == 0 else 2 * n_blades


def flash_period_s(rotation_rate_hz, *, n_blades):
    """Time between blade flashes."""
    return 1.0 / (flashes_per_revolution(n_blades) * np.abs(rotation_rate_hz))


def tip_doppler_hz(rotation_rate_hz, *, blade_length_m, wavelength_m, elevation_deg=0.0):
    """Largest micro-Doppler of a blade tip, ``2 Omega r cos(beta) / lambda`` (Eq. 6, Omega in rad/s)."""
    omega_rad_s = 2.0 * np.pi * np.abs(rotation_rate_hz)
    return 2.0 * omega_rad_s * blade_length_m * np.cos(np.deg2rad(elevation_deg)) / wavelength_m


def doppler_bandwidth_hz(rotation_rate_hz, *, blade_length_m, wavelength_m, elevation_deg=0.0):
    """Width of the rotor's Doppler band, ``f_dmax - f_dmin = 4 Omega r cos(beta) / lambda`` (Eq. 6)."""
    return 2.0 * tip_doppler_hz(rotation_rate_hz, blade_length_m=blade_length_m, wavelength_m=wavelength_m,
                                elevation_deg=elevation_deg)


def blade_length_from_bandwidth_m(bandwidth_hz, *, rotation_rate_hz, wavelength_m, elevation_deg=0.0):
    """Inverse of :func:`doppler_bandwidth_hz` for the blade length r.

    Divides by ``cos(beta)``: near beta = 90 degrees the result is meaningless and the caller must
    decide whether it is estimable.
    """
    omega_rad_s = 2.0 * np.pi * np.abs(rotation_rate_hz)
    return np.asarray(bandwidth_hz, dtype=np.float64) * wavelength_m / (
        4.0 * omega_rad_s * np.cos(np.deg2rad(elevation_deg)))


def tilt_error(elevation_deg, tilt_deg):
    """Largest relative error of r from Eq. 6 inverted at elevation beta when the rotor disc is tilted by
    ``tilt_deg`` (each value, or a bound given as +-tau) from it: ``|cos(beta + tau) / cos(beta) - 1|``, about
    ``tan(beta) tau`` (5 deg of attitude: 0.4 % at 0 deg, 3 % at 19 deg, 8 % at 43 deg)."""
    beta = np.deg2rad(elevation_deg)
    tau = np.deg2rad(np.atleast_1d(np.asarray(tilt_deg, dtype=np.float64)))
    return float(np.max(np.abs(np.cos(beta + tau) / np.cos(beta) - 1.0)))


def bessel_line_weights(harmonics, *, radius_m, wavelength_m, n_blades, elevation_deg=0.0, phase0_rad=0.0):
    """Complex weights of the spectral lines of one point per blade at ``radius_m`` (Eqs. 2-4).

    Line ``m`` (at ``m f_rot``) of a point on each of the N blades has weight
    ``N J_m(Gamma) exp(j m (phase0 - pi/2))`` when N divides m and 0 otherwise, with
    ``Gamma = 4 pi r cos(beta) / lambda``: only multiples of the chopping frequency survive.
    A test oracle; Gamma reaches ~850 at 76 GHz, where simulation by Bessel series is impractical.
    """
    from scipy import special  # the oracle only: keeps scipy.special (0.25 s to import) off the processing path

    m = np.asarray(harmonics)
    gamma = 4.0 * np.pi * radius_m * np.cos(np.deg2rad(elevation_deg)) / wavelength_m
    weight = n_blades * special.jv(m, gamma) * np.exp(1j * m * (phase0_rad - np.pi / 2))
    return np.where(m % n_blades == 0, weight, 0.0)


def blade_gain_factor(harmonics, blade_gains):
    """How blade gains g_k (blade k at ``theta + 2 pi k / N``) weigh line m: ``G_m = sum_k g_k exp(j 2 pi m k / N)``.

    Equal gains g give ``N g`` at multiples of N and 0 elsewhere (Eq. 5's chopping comb); unequal gains
    (an imbalance, a tag) leave lines at every multiple of the rotation rate.
    """
    gains = np.asarray(blade_gains, dtype=np.float64)
    k = np.arange(len(gains))
    m = np.asarray(harmonics)
    return np.sum(gains * np.exp(2j * np.pi * np.multiply.outer(m, k) / len(gains)), axis=-1)


def rotor_line_weights(harmonics, *, blade_gains, blade_length_m, wavelength_m, elevation_deg=0.0, root_m=0.0,
                       profile="uniform", tip_reflectivity=1.0, points_per_blade=None, phase0_rad=0.0,
                       samples=4000):
    """Complex weights of the spectral lines of one rotor's echo (normalised as :func:`blade_echoes`; line m sits at
    m times the signed rotation rate).

    A blade is a set of points at radius rho with reflectivity a(rho); each contributes
    ``J_m(Gamma(rho)) exp(j m (phase0 - pi/2))`` to line m (Eqs. 2-4, ``Gamma = 4 pi rho cos(beta) / lambda``), so
    one blade gives ``c_m = exp(j m (phase0 - pi/2)) int a(rho) J_m(Gamma(rho)) d rho`` over its span (midpoint rule
    on ``samples`` pieces for ``uniform`` and ``tapered``; the Q points themselves for ``points``), and the rotor
    ``c_m G_m`` (:func:`blade_gain_factor`; one gain per blade, ``len(blade_gains)`` = N).

    Returns
    -------
    ndarray, complex128, shape of ``harmonics``
    """
    from scipy import special  # an oracle: keeps scipy.special off the processing path's imports

    m = np.asarray(harmonics)
    span_m = blade_length_m - root_m
    if profile == "points":
        n = points_per_blade
        reflectivity = np.ones(n)
    else:
        n = samples
        reflectivity = 1.0 - (1.0 - (tip_reflectivity if profile == "tapered" else 1.0)) * (np.arange(n) + 0.5) / n
    rho_m = root_m + span_m * (np.arange(n) + 0.5) / n
    gamma = 4.0 * np.pi * rho_m * np.cos(np.deg2rad(elevation_deg)) / wavelength_m
    integral = (special.jv(m[..., None], gamma) * reflectivity).sum(axis=-1) * span_m / n
    return integral * np.exp(1j * m * (phase0_rad - np.pi / 2)) * blade_gain_factor(m, blade_gains)
