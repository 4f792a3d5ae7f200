"""Error bars for the time average of a steady, autocorrelated series: overlapping batch means
with the batch length chosen from the series, and a Student-t interval at the estimator's
effective degrees of freedom.

Why not a handful of whole drum revolutions: the drum's metrics decorrelate within tenths of a
second, so five revolution-long batches throw away most of what the series knows about its own
scatter. Their standard error has 4 degrees of freedom (known only to within a factor 0.6-2.9 at
95 %), and "mean +- 2 SE" at 4 degrees of freedom covers the true mean about 88 % of the time,
not 95 %.

What this does instead (`mean_interval`):
- the variance of the mean by overlapping batch means (OBM, Meketon & Schmeiser 1984): every
  window of b consecutive samples is a batch, which has about 1.5 (n/b - 1) degrees of freedom
  (Welch 1987) against n/b - 1 for the same batches laid end to end;
- the batch length b from the series (`batch_length`): at least 10 integrated autocorrelation
  times (Sokal's automatic window, so each batch mean is nearly independent of the next one but
  one) and at least one period of a quasi-periodic swing, where the autocorrelation shows one, in
  whole periods (a batch of whole swings averages the swing out); within that, the longest batch
  that still leaves 10 degrees of freedom (a longer batch is less biased, and more degrees of
  freedom than 10 narrow a 95 % interval by 12 % at most). Where the series is too short for
  both, the lower bounds win and the degrees of freedom fall below 10: reported, not hidden;
- the standard error corrected for the batch means' leading bias: for correlations that decay
  like an exponential, OBM's variance falls short by about tau_int / b (Song & Schmeiser 1995:
  -Gamma / b, Gamma = 2 sum k gamma_k, which equals tau_int times the variance of the mean's
  numerator for an AR(1)); b >= 10 tau_int keeps the correction within 11 %;
- the half-width from Student's t at those degrees of freedom.

Coverage on synthetic series with known means (tests/harness/test_estimator.py): AR(1) with
lag-one correlation 0.9 at the drum's 0.05 s snapshots, and a noisy 0.5-1 Hz swing plus AR(1)
noise, 15-40 s long; docs/drum/error_bars.md has the numbers.

Needs: python3-numpy, python3-scipy.
"""

import math
from collections import namedtuple

import numpy as np
from scipy import stats

MIN_DOF = 10  # the degrees of freedom a batch length is chosen to leave, where the series allows
TAU_BATCHES = 10  # a batch spans at least this many integrated autocorrelation times
SOKAL_C = 6.0  # Sokal's window: the sum of the autocorrelation runs to the first M >= c tau(M)

Interval = namedtuple("Interval", "mean half_width dof batch_seconds se")


def autocorrelation(x):
    """The sample autocorrelation rho_0..rho_{n-1} (about the sample mean, each lag's sum over n,
    so the sequence is positive definite), by FFT; zeros for a constant series."""
    x = np.asarray(x, float) - np.mean(x)
    n = len(x)
    f = np.fft.rfft(x, 2 * n)
    c = np.fft.irfft(f * np.conj(f), 2 * n)[:n]
    return c / c[0] if c[0] > 0 else np.zeros(n)


def integrated_time(rho):
    """(tau_int in samples, window M) by Sokal's automatic window: tau(M) = 1/2 + sum_{k<=M} rho_k
    at the first M >= SOKAL_C tau(M) (so the variance of the mean is 2 tau_int var / n). Divided by
    1 - (2M + 1)/n: subtracting the sample mean lowers every rho_k by about 2 tau_int / n, which in
    a series of a few dozen tau_int would otherwise shorten tau_int by a third (Madras & Sokal 1988)."""
    n = len(rho)
    if n < 3:
        return 0.5, 0
    tau = 0.5 + np.cumsum(rho[1:])
    window = np.nonzero(np.arange(1, n) >= SOKAL_C * tau)[0]
    m = int(window[0]) if len(window) else n - 2
    return float(tau[m] / max(1.0 - (2 * m + 3) / n, 0.5)), m + 1


def swing_period(rho):
    """The period in samples of a quasi-periodic swing, 0 where the series shows none: the lag of
    the autocorrelation's highest point in its first positive lobe after its first zero, if that
    point stands out (above twice its standard error by Bartlett's formula) from the noise of an
    estimated autocorrelation; a series without a swing has lobes there too, only small ones."""
    n = len(rho)
    first_zero = np.nonzero(rho < 0)[0]
    if not len(first_zero):
        return 0
    back_up = np.nonzero(rho[first_zero[0]:] >= 0)[0]
    if not len(back_up):
        return 0
    start = first_zero[0] + back_up[0]
    down = np.nonzero(rho[start:] < 0)[0]
    end = start + down[0] if len(down) else n
    p = start + int(np.argmax(rho[start:end]))
    bartlett = math.sqrt((1.0 + 2.0 * float(np.sum(rho[1:p] ** 2))) / n)
    return p if rho[p] > 2.0 * bartlett and p <= n // 2 else 0


def obm_dof(n, b):
    """Effective degrees of freedom of the OBM variance with batch length b of n samples."""
    return 1.5 * (n / b - 1.0)


def batch_length(x, min_dof=MIN_DOF):
    """(b, tau_int, swing period) in samples for the series x (module note): b at least
    TAU_BATCHES tau_int and at least one swing, in whole swings; the longest such b that leaves
    `min_dof` degrees of freedom, or the shortest where none does; at most n / 2."""
    n = len(x)
    rho = autocorrelation(x)
    tau, _ = integrated_time(rho)
    period = swing_period(rho)
    unit = period or 1
    shortest = unit * max(1, math.ceil(TAU_BATCHES * max(tau, 0.0) / unit))
    longest = unit * math.floor(n / (1.0 + min_dof / 1.5) / unit)  # obm_dof(n, longest) >= min_dof
    return max(1, min(max(shortest, longest), n // 2)), tau, period


def obm(x, b):
    """(mean, standard error of the mean, effective dof) by overlapping batch means of length b:
    var = n b / ((n - b + 1)(n - b)) sum_j (mean of window j - mean)^2 estimates n Var(mean)."""
    n = len(x)
    sums = np.concatenate(([0.0], np.cumsum(x)))
    mean = sums[-1] / n
    windows = (sums[b:] - sums[:-b]) / b
    var = n * b / ((n - b + 1) * (n - b)) * float(np.sum((windows - mean) ** 2))
    return mean, math.sqrt(var / n), obm_dof(n, b)


def mean_interval(values, dt, confidence=0.95, min_dof=MIN_DOF):
    """Interval(mean, half_width, dof, batch_seconds, se) for the mean of `values`, a steady series
    sampled every `dt` seconds (non-finite values dropped): the confidence interval is
    mean +- half_width, half_width = t(confidence, dof) se. Under 4 finite values: nan error bars."""
    x = np.asarray(values, float)
    x = x[np.isfinite(x)]
    n = len(x)
    if n < 4:
        return Interval(float(np.mean(x)) if n else math.nan, math.nan, math.nan, math.nan, math.nan)
    b, tau, _ = batch_length(x, min_dof)
    mean, se, dof = obm(x, b)
    se /= math.sqrt(1.0 - max(tau, 0.0) / b)  # OBM's leading bias, -tau_int / b (module note)
    return Interval(mean, float(stats.t.ppf(0.5 + confidence / 2.0, dof)) * se, dof, b * dt, se)


def compare(a, b, confidence=0.95):
    """(difference a - b, half-width of its interval, Welch-Satterthwaite dof) for two independent
    Intervals: they agree at this confidence where |difference| <= half-width, which two series
    of one steady state fail in a fraction 1 - confidence of comparisons."""
    var = a.se ** 2 + b.se ** 2
    if not var > 0:
        return a.mean - b.mean, 0.0, math.nan
    dof = var ** 2 / (a.se ** 4 / a.dof + b.se ** 4 / b.dof)
    return a.mean - b.mean, float(stats.t.ppf(0.5 + confidence / 2.0, dof)) * math.sqrt(var), dof
