"""Timed rounds: the machines are shared and noisy, so every comparison runs its
variants interleaved (A B C A B C ...) and reports medians and ratios per round."""

import statistics


def interleaved(variants, rounds, progress=None):
    """`variants`: {name: callable() -> measurement}. Runs `rounds` rounds, every variant once
    per round in the given order; returns {name: [measurement per round]}."""
    results = {name: [] for name in variants}
    for r in range(1, rounds + 1):
        for name, run in variants.items():
            if progress:
                progress(f"round {r}/{rounds}, {name} ...")
            results[name].append(run())
    return results


def median(values):
    return statistics.median(values)


def spread(values):
    """(min, max): the range of the rounds, reported beside the median."""
    return min(values), max(values)


def median_ratio(a, b):
    """Median over rounds of a[i] / b[i] (pairs from the same round saw the same load)."""
    return statistics.median(x / y for x, y in zip(a, b))
