"""Error bars for the time average of a steady, autocorrelated series: overlapping batch means
with the batch length chosen from the series, and a Student-t interval at the estimator's
effective degrees of freedom.

Why not five whole drum revolutions: the drum's metrics decorrelate within tenths of a second, so
five revolution-long batch means use little of what the series knows about its own scatter. Their
standard error has 4 degrees of freedom (the true one lies within a factor 0.6-2.9 of it, 95 %),
and "mean +- 2 SE" at 4 degrees of freedom covers the true mean about 88 % of the time, not 95 %.

What `mean_interval` does instead:
- the variance of the mean by overlapping batch means (OBM, Meketon & Schmeiser 1984): every run of
  b consecutive samples is a batch; the estimate has about 1.5 (n/b - 1) degrees of freedom, half
  as many again as the same batch length laid end to end;
- the batch length from the series (`batch_length`): at least 10 integrated autocorrelation times
  tau_int (Sokal's automatic window); where the autocorrelation shows a quasi-periodic swing, whole
  swings instead, at least one and the nearest number to 10 tau_int (a batch of whole swings
  averages the swing out). Within that, the longest batch that leaves 10 degrees of freedom
  (longer batches are less biased; more degrees of freedom than 10 would narrow a 95 % interval
  by 12 % at most). Where the series is too short for both, the lower bound wins and the degrees
  of freedom fall below 10: reported, not hidden;
- the leading bias of batch means corrected: the batch-means variance falls short of
  sigma^2 = n Var(mean) by about Gamma / b, Gamma = 2 sum_k k gamma_k; for correlations that
  decay without changing sign Gamma / sigma^2 is close to tau_int (an AR(1): 2 phi / (1 - phi^2)
  against (1 + phi) / (2 (1 - phi)), 9.47 and 9.5 at phi = 0.9). So the variance is divided by
  1 - tau_int / b (at most 11 %, as b >= 10 tau_int), and the degrees of freedom are multiplied
  by it (`obm_dof`). A swing's correlations change sign and bias batch means the other way
  (upwards, a few per cent): no correction there;
- the half-width from Student's t at those degrees of freedom.

Measured on synthetic series with a known mean (tools/drum/synthetic.py,
tests/harness/test_estimator.py; the numbers in docs/drum/error_bars.md).

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
    the autocorrelation's highest point in its first positive lobe after its first zero, where that
    point stands out from the noise of an estimated autocorrelation: above twice its standard
    error by Bartlett's formula for correlations that end at the first zero (a series without a
    swing has lobes there too, only small ones), and within the first half of the series."""
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
    bartlett = math.sqrt((1.0 + 2.0 * float(np.sum(rho[1:first_zero[0]] ** 2))) / n)
    return p if rho[p] > 2.0 * bartlett and p <= n // 2 else 0


def obm_dof(n, b, decay=0.0):
    """Effective degrees of freedom of the OBM variance with batch length b of n samples:
    1.5 (n/b - 1) for batches much longer than the correlations, times 1 - decay/b
    for correlations that decay over `decay` samples (tau_int; 0 for a swing, see `mean_interval`):
    batches of 10 tau_int of an AR(1) series have about that many fewer (measured: 4.7 against the
    formula's 6.0 at 6.3 tau_int, 8.9 against 10.0 at 11 tau_int)."""
    return 1.5 * (n / b - 1.0) * (1.0 - decay / b)


def batch_length(x, min_dof=MIN_DOF):
    """(b, tau_int, swing period) in samples for the series x (module note): b at least
    TAU_BATCHES tau_int, or where the series swings, the nearest whole number of swings to that
    (one at least); the longest such b that leaves `min_dof` degrees of freedom, or the shortest
    where none does; at most n / 2."""
    n = len(x)
    rho = autocorrelation(x)
    tau, _ = integrated_time(rho)
    period = swing_period(rho)
    unit = period or 1
    shortest = unit * max(1, round(TAU_BATCHES * max(tau, 0.0) / unit))
    lengths = unit * np.arange(1, n // 2 // unit + 1)
    enough = lengths[obm_dof(n, lengths, 0.0 if period else max(tau, 0.0)) >= min_dof]
    longest = int(enough[-1]) if len(enough) else 0
    return max(1, min(max(shortest, longest), n // 2)), tau, period


def obm(x, b):
    """(mean, standard error of the mean) by overlapping batch means of length b:
    var = n b / ((n - b + 1)(n - b)) sum_j (mean of window j - mean)^2 estimates n Var(mean)."""
    n = len(x)
    sums = np.concatenate(([0.0], np.cumsum(x)))
    mean = sums[-1] / n
    windows = (sums[b:] - sums[:-b]) / b
    var = n * b / ((n - b + 1) * (n - b)) * float(np.sum((windows - mean) ** 2))
    return mean, math.sqrt(var / n)


def mean_interval(values, dt, confidence=0.95, min_dof=MIN_DOF):
    """Interval(mean, half_width, dof, batch_seconds, se) for the mean of `values`, a steady series
    sampled every `dt` seconds (non-finite values dropped): the confidence interval is
    mean +- half_width, half_width = t(confidence, dof) se. Under 4 finite values: nan error bars."""
    x = np.asarray(values, float)
    x = x[np.isfinite(x)]
    n = len(x)
    if n < 4:
        return Interval(float(np.mean(x)) if n else math.nan, math.nan, math.nan, math.nan, math.nan)
    b, tau, period = batch_length(x, min_dof)
    # a swing's correlations change sign and bias batch means the other way: no decay term there;
    # at most b / 2 where the series is too short for 10 tau_int in half of it
    decay = 0.0 if period else min(max(tau, 0.0), b / 2.0)
    mean, se = obm(x, b)
    se /= math.sqrt(1.0 - decay / b)  # batch means' leading bias, -tau_int / b (module note)
    dof = obm_dof(n, b, decay)
    return Interval(mean, float(stats.t.ppf(0.5 + confidence / 2.0, dof)) * se, dof, b * dt, se)


def window_intervals(snapshots, start, spacing, columns, confidence=0.95):
    """{key: Interval} of each column {key: column} of `snapshots` (rows with a time_s, `spacing`
    seconds apart) from time `start` on: a steady window's error bars, metric by metric."""
    window = [r for r in snapshots if r["time_s"] >= start - 0.5 * spacing]
    return {key: mean_interval([r[c] for r in window], spacing, confidence) for key, c in columns.items()}


def compare(a, b, confidence=0.95):
    """(difference a - b, half-width of its interval, Welch-Satterthwaite dof) for two independent
    Intervals: they agree at this confidence where |difference| <= half-width, which two series
    of one steady state fail in a fraction 1 - confidence of comparisons."""
    var = a.se ** 2 + b.se ** 2
    if not var > 0:
        return a.mean - b.mean, 0.0, math.nan
    dof = var ** 2 / (a.se ** 4 / a.dof + b.se ** 4 / b.dof)
    return a.mean - b.mean, float(stats.t.ppf(0.5 + confidence / 2.0, dof)) * math.sqrt(var), dof


def power(delta, se, dof, confidence=0.95):
    """The probability that a difference of true size `delta` is found (its interval at this
    confidence excludes 0), for a difference estimated with standard error `se` at `dof` degrees
    of freedom: the noncentral t's tail beyond the critical value (both sides)."""
    if not (se > 0 and dof > 0):
        return math.nan
    crit = float(stats.t.ppf(0.5 + confidence / 2.0, dof))
    nc = abs(delta) / se
    return float(stats.nct.sf(crit, dof, nc) + stats.nct.cdf(-crit, dof, nc))


def half_width_for_power(delta, power_wanted=0.8, dof=MIN_DOF, confidence=0.95):
    """The 95 % half-width each of two independent runs must reach (at `dof` degrees of freedom
    each) for their difference to be found with probability `power_wanted` where it is `delta`:
    Hc 0.1 mm at 80 % asks 0.054 mm of each side."""
    lo, hi = 1e-12 * abs(delta), 100.0 * abs(delta)  # (at low power wanted, wider than delta)
    t = float(stats.t.ppf(0.5 + confidence / 2.0, dof))
    for _ in range(100):  # bisection: power falls as the half-width grows
        h = 0.5 * (lo + hi)
        se = math.sqrt(2.0) * h / t
        lo, hi = (h, hi) if power(delta, se, 2.0 * dof, confidence) >= power_wanted else (lo, h)
    return lo
