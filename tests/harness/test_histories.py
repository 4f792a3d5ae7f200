"""tools/drum/histories.py: the two-history check's statistics. Two histories drawn from one
steady state must pass at the stated false-alarm rate, and an offset of a few standard errors
must be caught (so the check can fail)."""

import math
import sys
import unittest
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "drum"))
import histories  # noqa: E402

METRICS = [{"column": f"m{i}_u", "se_column": f"m{i}_se_u", "label": f"m{i}", "unit": "u"} for i in range(7)]


def history(rng, offsets, batches=5, sigma=1.0):
    """A study-table row: each metric's batch-means average and SE from `batches` normal batch means."""
    row = {"batches": float(batches)}
    for m, off in zip(METRICS, offsets):
        x = rng.normal(off, sigma, batches)
        row[m["column"]], row[m["se_column"]] = x.mean(), x.std(ddof=1) / math.sqrt(batches)
    return row


class Histories(unittest.TestCase):
    def test_verdict_names_what_differs(self):
        self.assertIn("DISAGREE", histories.verdict(False))
        self.assertIn("DIFFER", histories.verdict(False, "timesteps"))
        self.assertIn("agree", histories.verdict(True, "timesteps"))
        self.assertIn("conventions DIFFER", histories.verdict(False, "conventions"))

    def test_welch_dof_of_equal_sides_is_the_pooled_count(self):
        self.assertAlmostEqual(histories.welch_dof(0.3, 5, 0.3, 5), 8.0)
        # one side's error dominating: its own n - 1
        self.assertAlmostEqual(histories.welch_dof(1.0, 5, 1e-6, 50), 4.0, places=6)

    def test_same_state_passes_at_the_stated_rate(self):
        rng = np.random.default_rng(2026)
        n = 4000
        alarms = sum(not all(r["agree"] for r in histories.compare(history(rng, [0] * 7), history(rng, [0] * 7), METRICS))
                     for _ in range(n))
        # family-wise at most 0.05 (Bonferroni over 7 independent metrics: 1 - (1 - 0.05/7)^7 = 0.0488;
        # binomial sd 0.0034). Welch's t with estimated SEs is a little conservative (measured 0.037),
        # but not so much that it would pass anything: above 0.02
        self.assertLess(alarms / n, 0.0488 + 4 * math.sqrt(0.0488 * 0.9512 / n), alarms / n)
        self.assertGreater(alarms / n, 0.02)

    def test_an_offset_of_a_few_standard_errors_is_caught(self):
        rng = np.random.default_rng(7)
        # true difference 3 x the combined SE of two 5-batch means (sd 1 each: SE sqrt(2/5))
        shift = 3 * math.sqrt(2 / 5)
        caught = sum(not histories.compare(history(rng, [shift] + [0] * 6), history(rng, [0] * 7), METRICS)[0]["agree"]
                     for _ in range(1000))
        self.assertGreater(caught / 1000, 0.2)  # power of the Bonferroni t test at dof 8: measured 0.30
        shift = 8 * math.sqrt(2 / 5)
        caught = sum(not histories.compare(history(rng, [shift] + [0] * 6), history(rng, [0] * 7), METRICS)[0]["agree"]
                     for _ in range(1000))
        self.assertGreater(caught / 1000, 0.95)  # measured 0.998

    def test_the_difference_it_reports_as_detectable_is_caught_at_that_rate(self):
        # the check on histories with a true offset of its own "caught at 80 %" figure (true SEs
        # given): caught in 80 % of pairs, within 4 binomial sd of 2000 pairs (0.036), which also
        # covers the figure's own Monte Carlo error (20,000 replicas: 0.003)
        from scipy import stats
        critical = lambda dof: stats.t.ppf(1 - 0.05 / 14, dof)  # noqa: E731 (7 metrics, as compare's)
        n = 2000
        for batches_a, batches_b in ((3, 3), (5, 5), (3, 12)):
            rng = np.random.default_rng(batches_a * 100 + batches_b)
            se_a, se_b = 1 / math.sqrt(batches_a), 1 / math.sqrt(batches_b)
            shift = histories.detectable(se_a, batches_a, se_b, batches_b, critical)
            caught = sum(not histories.compare(history(rng, [shift] + [0] * 6, batches_a),
                                               history(rng, [0] * 7, batches_b), METRICS)[0]["agree"]
                         for _ in range(n))
            self.assertLess(abs(caught / n - 0.8), 4 * math.sqrt(0.16 / n), (batches_a, batches_b, caught / n))
        # at 3 batches a side the estimated SEs and degrees of freedom cost power: the figure lies
        # well above what a noncentral t at the pooled 4 degrees of freedom gives (6.4 SEs over 7 metrics)
        self.assertGreater(histories.detectable(1, 3, 1, 3, critical) / math.sqrt(2), 8.0)

    def test_compare_gives_the_detectable_difference_when_asked(self):
        rng = np.random.default_rng(3)
        a, b = history(rng, [0] * 7), history(rng, [0] * 7)
        self.assertNotIn("detectable", histories.compare(a, b, METRICS)[0])
        rows = histories.compare(a, b, METRICS, power=0.8)
        self.assertTrue(all(r["detectable"] > 3 * r["combined_se"] for r in rows))
        self.assertTrue(math.isnan(histories.detectable(1.0, 1, 1.0, 5, lambda d: 2.0)))  # one batch: no SE
        # with the Bonferroni count of the metrics compared (6 of the 7: one left out), at the power asked
        from scipy import stats
        b["m3_u"] = float("nan")
        rows = histories.compare(a, b, METRICS, power=0.5)
        critical = lambda dof: stats.t.ppf(1 - 0.05 / 12, dof)  # noqa: E731
        self.assertEqual(rows[0]["detectable"],
                         histories.detectable(a["m0_se_u"], 5, b["m0_se_u"], 5, critical, 0.5))
        self.assertLess(rows[0]["detectable"], histories.compare(a, b, METRICS, power=0.8)[0]["detectable"])

    def test_at_least_is_the_exact_tail(self):
        import itertools
        probabilities = [0.1, 0.3, 0.5, 0.05, 0.9]
        for k in range(len(probabilities) + 2):
            exact = sum(math.prod(q if hit else 1 - q for q, hit in zip(probabilities, hits))
                        for hits in itertools.product((0, 1), repeat=len(probabilities)) if sum(hits) >= k)
            self.assertAlmostEqual(histories.at_least(k, probabilities), exact, places=12)

    def test_the_count_beyond_two_holds_its_rate_and_sees_error_bars_too_small(self):
        # three speeds of 7 metrics, 5 batches a side, drawn from one state; then with every
        # reported SE 0.6 of the true one (error bars 40 % small)
        def trials(shrink, n, seed):
            rng = np.random.default_rng(seed)
            counts, expected, flagged = [], [], 0
            for _ in range(n):
                rows = []
                for _ in range(3):
                    a, b = history(rng, [0] * 7), history(rng, [0] * 7)
                    for r in (a, b):
                        for m in METRICS:
                            r[m["se_column"]] *= shrink
                    rows += histories.compare(a, b, METRICS)
                k, chances = histories.beyond(rows)
                counts.append(k)
                expected.append(sum(chances))
                flagged += "may be somewhat small" in histories.pooled(rows)
            return np.mean(counts), np.std(counts) / math.sqrt(n), np.mean(expected), flagged / n
        n = 1000
        count, count_sd, expected, flagged = trials(1.0, n, 11)
        # the Student-t chance at Satterthwaite's dof a little above the check's own (measured 1.70
        # against 1.84 of 21 rows): never below it, and not so far above that the count could not
        # fail (normal tails would expect 0.96, one degree of freedom 6.2)
        self.assertLess(count, expected + 4 * count_sd, (count, expected))
        self.assertGreater(count, 0.8 * expected, (count, expected))
        # flagged at most at its nominal 0.05 (binomial sd 0.0069; measured 0.024)
        self.assertLess(flagged, 0.05 + 4 * math.sqrt(0.05 * 0.95 / n), flagged)
        # error bars 40 % small: flagged in most runs (measured 0.70; each speed's Bonferroni check,
        # failing anywhere, 0.67 at 0.12 false alarms)
        self.assertGreater(trials(0.6, n, 12)[3], 0.5)


    def test_undefined_metrics_are_left_out(self):
        a = history(np.random.default_rng(1), [0] * 7)
        b = dict(a)
        b["m3_u"] = float("nan")
        rows = histories.compare(a, b, METRICS)
        self.assertEqual([r["metric"] for r in rows], [m["label"] for m in METRICS if m["label"] != "m3"])
        self.assertTrue(all(r["t"] == 0.0 and r["agree"] for r in rows))


if __name__ == "__main__":
    unittest.main()
