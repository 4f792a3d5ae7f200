"""Synthetic steady series with a known mean (0), shaped like the drum's metrics, to measure how
often an error bar covers the true mean (tests/harness/test_estimator.py, docs/drum/error_bars.md).

Two families, at the drum's 0.05 s snapshots, each replica 15-40 s long (the steady windows of
study_thesis span 4.7-42.7 s):
- `ar1`: AR(1) with lag-one correlation 0.9 (tau_int 9.5 snapshots, 0.475 s: the slowest of the
  drum's metrics decorrelate about this slowly);
- `swing`: a noisy oscillation at 0.5-1 Hz (an AR(2) resonance whose autocorrelation after one
  period is 0.6) carrying half the variance, plus AR(1) noise with lag-one correlation 0.7: the
  whole series' autocorrelation is 0.3 one period on, where the committed Hc series of 35-63 rpm,
  which swing with a period near 1 s, show 0.23-0.48.

The error bars compared: `estimator.mean_interval` at 95 % and the whole-revolution rule the
studies used, five batch means (a revolution each: the steady window is about five revolutions
long) and mean +- 2 standard errors at 4 degrees of freedom.

Needs: python3-numpy, python3-scipy.
"""

import math

import numpy as np
from scipy import signal

import estimator

DT = 0.05  # [s] the drum's snapshot spacing
SECONDS = (15.0, 40.0)  # replica lengths, uniform
HZ = (0.5, 1.0)  # swing frequencies, uniform
AR1_PHI = 0.9
SWING_AT_PERIOD = 0.6  # the swing's autocorrelation one period on
NOISE_PHI = 0.7


def ar1_series(rng, n, phi):
    """n samples of a stationary unit-variance AR(1) with lag-one correlation phi."""
    x = np.empty(n)
    x[0] = rng.normal()
    x[1:] = math.sqrt(1.0 - phi * phi) * rng.normal(size=n - 1)
    return signal.lfilter([1.0], [1.0, -phi], x)


def swing_series(rng, n, hz):
    """n samples: a unit-variance AR(2) resonance at `hz` (correlation SWING_AT_PERIOD one period
    on, started 20 periods early so it is stationary) plus unit-variance AR(1) noise."""
    period = 1.0 / (hz * DT)
    r, w = SWING_AT_PERIOD ** (1.0 / period), 2.0 * math.pi * hz * DT
    a = [1.0, -2.0 * r * math.cos(w), r * r]
    lead = int(20 * period)
    x = signal.lfilter([1.0], a, rng.normal(size=n + lead))[lead:]
    # the AR(2)'s variance per unit innovation variance
    var = (1.0 + r * r) / ((1.0 - r * r) * ((1.0 + r * r) ** 2 - (2.0 * r * math.cos(w)) ** 2))
    return x / math.sqrt(var) + ar1_series(rng, n, NOISE_PHI)


def draw(rng, family):
    """A pair of independent replicas of one steady state of a family ('ar1' or 'swing'): their
    length (and the swing's frequency) drawn uniformly, shared by the two."""
    n = int(round(rng.uniform(*SECONDS) / DT))
    if family == "ar1":
        return ar1_series(rng, n, AR1_PHI), ar1_series(rng, n, AR1_PHI)
    hz = rng.uniform(*HZ)
    return swing_series(rng, n, hz), swing_series(rng, n, hz)


def five_revolutions(x):
    """The studies' rule: the last five equal batches' means (one revolution each), mean +- 2
    standard errors. Returns (mean, half-width)."""
    b = len(x) // 5
    means = np.asarray(x[len(x) - 5 * b:]).reshape(5, b).mean(axis=1)
    return float(means.mean()), 2.0 * float(means.std(ddof=1)) / math.sqrt(5)


def measure(family, replicas, seed):
    """Over `replicas` pairs of a family (`draw`): {'new': how often mean_interval's 95 % interval
    of the first covers the true mean, 'old': five_revolutions' interval, 'alarms': how often the
    pair disagrees at 95 % by estimator.compare (false alarms: one state), 'old_alarms': by the
    old rule (|difference| > 2 combined standard errors), 'dof': the median effective dof}."""
    rng = np.random.default_rng(seed)
    covered = old = alarms = old_alarms = 0
    dofs = []
    for _ in range(replicas):
        x, y = draw(rng, family)
        a, b = estimator.mean_interval(x, DT), estimator.mean_interval(y, DT)
        covered += abs(a.mean) <= a.half_width
        difference, half_width, _ = estimator.compare(a, b)
        alarms += abs(difference) > half_width
        (ma, ha), (mb, hb) = five_revolutions(x), five_revolutions(y)
        old += abs(ma) <= ha
        old_alarms += abs(ma - mb) > math.hypot(ha, hb)
        dofs.append(a.dof)
    return {"new": covered / replicas, "old": old / replicas, "alarms": alarms / replicas,
            "old_alarms": old_alarms / replicas, "dof": float(np.median(dofs))}
