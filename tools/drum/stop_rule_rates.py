#!/usr/bin/python3
"""Reference rates behind two tests of test_drum_metrics (an implementation independent of
tools/drum/metrics.cpp, numpy only):

1. the stop rule checked after every batch from the minimum m on, on N(0, sigma) batch means:
   how often it stops with the true standard error above the target, at ratios just past each
   sqrt(k/m) (k batches first reach the target), k up to 16 m; the worst ratios refined;
2. MSER on steady AR(1) series (lag-one 0.9): how often the optimum falls in the second half
   (searched over all but the last tenth), i.e. a steady series judged unsettled.

  tools/drum/stop_rule_rates.py            # about 10 minutes on one core

Needs: python3-numpy, python3-scipy.
"""

import argparse

import numpy as np
from scipy import stats
from scipy.signal import lfilter


def early_stops(ratio, m, replicas, seed, confidence=0.95):
    """Fraction of runs the rule stops with sigma / sqrt(n) above the target (1)."""
    rng = np.random.default_rng(seed)
    cap = int(m * ratio * ratio * 6) + 30  # far past where the true SE meets the target
    sigma = ratio * np.sqrt(m)
    x = rng.normal(0.0, sigma, (replicas, cap))
    s1, s2 = np.cumsum(x, 1), np.cumsum(x * x, 1)
    stop = np.full(replicas, -1)
    for n in range(m, cap + 1):
        mean = s1[:, n - 1] / n
        se = np.sqrt(np.maximum((s2[:, n - 1] - n * mean * mean) / (n - 1), 0.0) / n)
        bound = np.sqrt((n - 1) / stats.chi2.ppf(1.0 - confidence, n - 1))
        stop[(se * bound <= 1.0) & (stop < 0)] = n
    stopped = stop[stop > 0]
    return float(np.mean(sigma / np.sqrt(stopped) > 1.0))


def mser_truncation(v, last):
    n = len(v)
    rev = v[::-1]
    k = np.arange(1, n + 1)
    s1, s2 = np.cumsum(rev), np.cumsum(rev * rev)
    value = ((s2 - s1 * s1 / k) / (k * k))[::-1]  # index d: the tail from d on
    return int(np.argmin(value[:min(last, n - 2) + 1]))


def unsettled(n, phi, replicas, seed):
    rng = np.random.default_rng(seed)
    e = rng.normal(size=(replicas, n))
    e[:, 0] /= np.sqrt(1.0 - phi * phi)
    x = lfilter([1.0], [1.0, -phi], e, axis=1)
    return float(np.mean([mser_truncation(v, n - 1 - max(1, n // 10)) > n / 2 for v in x]))


def main():
    for m in (3, 5):
        scan = sorted(((early_stops(np.sqrt(k / m) * 1.001, m, 50000, k), k) for k in range(m + 1, 16 * m + 1)),
                      reverse=True)
        print(f"minimum {m} batches, highest peaks (rate, k): {[(round(r, 4), k) for r, k in scan[:3]]}")
        for _, k in scan[:3]:
            print(f"  k = {k}, ratio {np.sqrt(k / m) * 1.001:.4f}: "
                  f"{early_stops(np.sqrt(k / m) * 1.001, m, 400000, 100 + k):.4f} over 400,000")
    for phi, n in ((0.9, 140), (0.9, 200), (0.9, 300), (0.7, 140)):
        print(f"AR(1) phi {phi}, {n} samples: judged unsettled in {unsettled(n, phi, 40000, 7):.4f} of 40,000")


if __name__ == "__main__":
    # no options: the arguments are only read so that --help describes the run instead of starting it
    argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    main()
