"""Detection thresholds for averaged powers of complex Gaussian noise (numpy and the standard library only).

A cell's power in a spectrum of complex white Gaussian noise is exponential; the mean of ``n``
independent such powers is ``mu * G / n`` with ``G ~ Gamma(n, 1)``. The threshold that noise alone
exceeds with probability ``p`` is ``mu * gamma_isf(n, p) / n``; its excess over ``mu`` shrinks as
``1 / sqrt(n)``, which is the gain of integration. scipy.special.gammainccinv gives the same
numbers (a test holds them equal); importing scipy costs more than processing a small capture.
"""

import math

import numpy as np

EXACT_SHAPE_MAX = 2000  # integer shapes up to this: exact Poisson-sum survival; above: Wilson-Hilferty
BISECTION_STEPS = 200


def _bisect(function, low, high):
    """Root of an increasing ``function`` in [low, high] by bisection."""
    for _ in range(BISECTION_STEPS):
        middle = 0.5 * (low + high)
        if function(middle) > 0:
            high = middle
        else:
            low = middle
    return 0.5 * (low + high)


def normal_isf(p):
    """z with P(N(0, 1) > z) = p."""
    return _bisect(lambda z: math.log(p) - math.log(max(0.5 * math.erfc(z / math.sqrt(2)), 1e-320)), -40.0, 37.0)


def gamma_isf(shape, p):
    """x with P(Gamma(shape, 1) > x) = p (shape >= 1).

    Integer ``shape`` up to ``EXACT_SHAPE_MAX``: exact, from the survival function
    ``exp(-x) sum_{i < n} x^i / i!`` (the Poisson distribution function), solved in logs by
    bisection. Larger or fractional shapes: Wilson-Hilferty, ``n (1 - 1/(9n) + z / (3 sqrt n))^3``
    (relative error < 1e-3 for n > 1000 down to p = 1e-12).
    """
    if shape != int(shape) or shape > EXACT_SHAPE_MAX:
        z = normal_isf(p)
        return shape * (1 - 1 / (9 * shape) + z / (3 * math.sqrt(shape))) ** 3
    i = np.arange(int(shape))
    log_factorial = np.concatenate([[0.0], np.cumsum(np.log(i[1:]))])

    def log_survival_excess(log_x):  # increasing in x: log p - log S(x)
        terms = i * log_x - math.exp(log_x) - log_factorial
        peak = terms.max()
        return math.log(p) - (peak + math.log(np.exp(terms - peak).sum()))

    upper = math.log(shape + 20 * math.sqrt(shape) - 2 * math.log(p) + 10)
    return math.exp(_bisect(log_survival_excess, math.log(1e-300) if shape == 1 else -50.0, upper))
