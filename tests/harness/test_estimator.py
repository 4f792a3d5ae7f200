"""tools/drum/estimator.py: 95 % intervals for the mean of an autocorrelated series. On synthetic
series with a known mean, shaped like the drum's metrics (tools/drum/synthetic.py: AR(1) with
lag-one correlation 0.9; a 0.5-1 Hz swing plus AR(1) noise; 15-40 s at 0.05 s), the interval must
cover the mean at 95 % within the replicas' binomial scatter, and two replicas of one state must
disagree at 5 % within it; the studies' old rule (five whole-revolution batch means, mean +- 2
standard errors at 4 degrees of freedom) must fail the same band."""

import math
import sys
import unittest
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "drum"))
import estimator  # noqa: E402
import synthetic  # noqa: E402

REPLICAS = 2000
# the band: 3 binomial standard deviations of a rate measured over REPLICAS replicas (0.49 % at
# 95 % or 5 %: +-1.46 %), so a rule that holds fails it by chance about 3 times in 1000
BAND = 3 * math.sqrt(0.05 * 0.95 / REPLICAS)


class Synthetic(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.rates = {family: synthetic.measure(family, REPLICAS, seed=2027 + k)
                     for k, family in enumerate(("ar1", "swing"))}

    def test_new_interval_covers_the_mean_at_95_percent(self):
        for family, r in self.rates.items():
            with self.subTest(family=family):
                self.assertLessEqual(abs(r["new"] - 0.95), BAND, r)

    def test_old_rule_does_not(self):
        # five batch means, +-2 SE: Student's t at 4 degrees of freedom would need 2.78 (about 88 %)
        for family, r in self.rates.items():
            with self.subTest(family=family):
                self.assertLess(r["old"], 0.95 - BAND, r)

    def test_two_replicas_of_one_state_disagree_at_5_percent(self):
        for family, r in self.rates.items():
            with self.subTest(family=family):
                self.assertLessEqual(abs(r["alarms"] - 0.05), BAND, r)
                self.assertGreater(r["old_alarms"], 0.05 + BAND, r)

    def test_degrees_of_freedom_are_well_above_the_old_four(self):
        self.assertGreater(self.rates["ar1"]["dof"], 5.0, self.rates)  # 15-40 s of 0.475 s correlation
        self.assertGreater(self.rates["swing"]["dof"], 10.0, self.rates)


class Pieces(unittest.TestCase):
    def test_obm_with_batches_of_one_is_the_plain_standard_error(self):
        x = np.random.default_rng(1).normal(size=200)
        mean, se = estimator.obm(x, 1)
        self.assertAlmostEqual(mean, x.mean())
        self.assertAlmostEqual(se, x.std(ddof=1) / math.sqrt(len(x)))

    def test_integrated_time_of_an_ar1(self):
        # tau_int = (1 + phi) / (2 (1 - phi)) = 9.5 snapshots at phi 0.9; the mean's bias corrected
        x = synthetic.ar1_series(np.random.default_rng(2), 20000, 0.9)
        tau, window = estimator.integrated_time(estimator.autocorrelation(x))
        self.assertAlmostEqual(tau, 9.5, delta=1.0)
        self.assertGreaterEqual(window, estimator.SOKAL_C * tau * 0.9)

    def test_swing_period_is_found_and_not_invented(self):
        rng = np.random.default_rng(3)
        found = [estimator.swing_period(estimator.autocorrelation(synthetic.swing_series(rng, 800, 1.0)))
                 for _ in range(50)]
        self.assertGreaterEqual(np.mean([abs(p - 20) <= 2 for p in found]), 0.9, found)  # 1 Hz: 20 snapshots
        noise = [estimator.swing_period(estimator.autocorrelation(synthetic.ar1_series(rng, 800, 0.9)))
                 for _ in range(50)]
        self.assertLessEqual(np.mean([p > 0 for p in noise]), 0.1, noise)

    def test_batch_length_leaves_ten_degrees_of_freedom_where_the_series_allows(self):
        rng = np.random.default_rng(4)
        long = synthetic.ar1_series(rng, 4000, 0.5)  # tau_int 1.5 snapshots: room for both
        b, tau, period = estimator.batch_length(long)
        self.assertGreaterEqual(b, estimator.TAU_BATCHES * tau)
        self.assertGreaterEqual(estimator.mean_interval(long, 0.05).dof, estimator.MIN_DOF)
        self.assertLess(estimator.obm_dof(len(long), b + 1, tau), estimator.MIN_DOF)  # the longest such
        short = synthetic.ar1_series(rng, 200, 0.9)  # 10 tau_int is about half of it
        b, tau, _ = estimator.batch_length(short)
        self.assertGreaterEqual(b, min(round(estimator.TAU_BATCHES * tau), len(short) // 2))
        self.assertLess(estimator.mean_interval(short, 0.05).dof, estimator.MIN_DOF)  # reported, not hidden

    def test_batches_hold_whole_swings(self):
        x = synthetic.swing_series(np.random.default_rng(5), 800, 1.0)
        b, _, period = estimator.batch_length(x)
        self.assertGreater(period, 0)
        self.assertEqual(b % period, 0)

    def test_interval_in_seconds_and_without_non_finite_values(self):
        x = synthetic.ar1_series(np.random.default_rng(6), 600, 0.5)
        a = estimator.mean_interval(x, 0.05)
        b = estimator.mean_interval(np.concatenate([x[:300], [np.nan, np.inf], x[300:]]), 0.05)
        self.assertEqual(a, b)
        self.assertAlmostEqual(a.batch_seconds / 0.05, round(a.batch_seconds / 0.05))
        self.assertTrue(math.isnan(estimator.mean_interval([1.0, 2.0, np.nan], 0.05).half_width))

    def test_compare_is_welch(self):
        a = estimator.Interval(1.0, 0.0, 10.0, 1.0, 0.3)
        b = estimator.Interval(0.0, 0.0, 10.0, 1.0, 0.4)
        difference, half_width, dof = estimator.compare(a, b)
        self.assertEqual(difference, 1.0)
        self.assertAlmostEqual(dof, 0.25 ** 2 / (0.3 ** 4 / 10 + 0.4 ** 4 / 10))
        self.assertGreater(half_width, 1.96 * 0.5)


class Power(unittest.TestCase):
    def test_the_textbook_normal_values(self):
        # a difference 2.80 standard errors large is found 80 % of the time at 95 % (1.96 + 0.84)
        self.assertAlmostEqual(estimator.power(2.8016, 1.0, 1e7), 0.80, delta=1e-3)
        self.assertAlmostEqual(estimator.power(0.0, 1.0, 1e7), 0.05, delta=1e-3)  # no difference: the false alarms

    def test_the_half_width_gives_the_power_asked(self):
        for wanted in (0.2, 0.5, 0.8, 0.95):
            h = estimator.half_width_for_power(1.0, wanted)
            se = math.sqrt(2.0) * h / float(estimator.stats.t.ppf(0.975, 10))
            self.assertAlmostEqual(estimator.power(1.0, se, 20), wanted, places=6)

    def test_the_detection_rate_of_simulated_differences(self):
        # differences of two runs with 10 dof each (chi-square standard errors), true difference
        # delta: the rate at which their Welch interval excludes 0 matches power() (binomial 4 sd)
        rng = np.random.default_rng(11)
        h = estimator.half_width_for_power(1.0)
        t10 = float(estimator.stats.t.ppf(0.975, 10))
        se = h / t10  # each run's true standard error at the half-width asked of it
        n, found = 20000, 0
        for _ in range(n):
            a = estimator.Interval(1.0 + rng.normal(0, se), math.nan, 10, math.nan,
                                   se * math.sqrt(rng.chisquare(10) / 10))
            b = estimator.Interval(rng.normal(0, se), math.nan, 10, math.nan, se * math.sqrt(rng.chisquare(10) / 10))
            d, hw, _ = estimator.compare(a, b)
            found += abs(d) > hw
        self.assertAlmostEqual(found / n, 0.80, delta=4 * math.sqrt(0.8 * 0.2 / n))


if __name__ == "__main__":
    unittest.main()
