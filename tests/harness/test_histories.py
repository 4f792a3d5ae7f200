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
        self.assertIn("settings DIFFER", histories.verdict(False, "settings"))
        self.assertIn("settings agree", histories.verdict(True, "settings"))
        self.assertIn("agree", histories.verdict(True, "timesteps"))
        self.assertIn("conventions DIFFER", histories.verdict(False, "conventions"))

    def test_welch_dof_of_equal_sides_is_the_pooled_count(self):
        self.assertAlmostEqual(histories.welch_dof(0.3, 5, 0.3, 5), 8.0)
        # one side's error dominating: its own n - 1
        self.assertAlmostEqual(histories.welch_dof(1.0, 5, 1e-6, 50), 4.0, places=6)

    def test_welch_dof_of_two_exact_sides_is_undefined(self):
        self.assertTrue(math.isnan(histories.welch_dof(0.0, 5, 0.0, 5)))
        rows = histories.compare({"batches": 5.0, "m0_u": 1.0, "m0_se_u": 0.0},
                                 {"batches": 5.0, "m0_u": 1.0, "m0_se_u": 0.0}, METRICS[:1])
        self.assertTrue(rows[0]["agree"])

    def test_a_row_with_the_estimators_dof_is_read_at_them(self):
        # a study stopped by --rule obm has no whole-revolution batches: <key>_dof stands in for n - 1
        m = dict(METRICS[0], key="m0")
        a = {"batches": math.nan, "m0_u": 1.0, "m0_se_u": 0.1, "m0_dof": 14.5}
        b = {"batches": 5.0, "m0_u": 1.0, "m0_se_u": 0.1}
        self.assertEqual(histories.compare(a, b, [m])[0]["dof"], 4.0)  # b's 5 batches are the smaller side
        self.assertAlmostEqual(histories.compare(a, dict(b, m0_dof=20.0), [m])[0]["dof"], 14.5)

    def test_smaller_sides_degrees_of_freedom(self):
        self.assertEqual(histories.smaller_dof(5, 3), 2)
        self.assertEqual(histories.smaller_dof(12, 12), 11)
        self.assertTrue(math.isnan(histories.smaller_dof(1, 5)))

    def test_same_state_passes_at_the_stated_rate(self):
        # family-wise at most 0.05 whatever the two errors' ratio (Bonferroni over 7 independent
        # metrics: 1 - (1 - 0.05/7)^7 = 0.0488; binomial sd 0.0034 at 4000 pairs). Welch-Satterthwaite's
        # estimated degrees of freedom fail this where one side's error is several times the other's
        # (3 batches against 5, the 3-batch side's 5 times: 0.11-0.13)
        n = 4000
        bound = 0.0488 + 4 * math.sqrt(0.0488 * 0.9512 / n)
        rates = {}
        for seed, (batches_a, batches_b, ratio) in enumerate(((5, 5, 1), (5, 3, 1), (5, 3, 3), (5, 3, 5), (3, 3, 20))):
            rng = np.random.default_rng(2026 + seed)
            sigma_b = ratio * math.sqrt(batches_b / batches_a)  # B's SE `ratio` times A's
            rates[(batches_a, batches_b, ratio)] = sum(
                not all(r["agree"] for r in histories.compare(history(rng, [0] * 7, batches_a),
                                                              history(rng, [0] * 7, batches_b, sigma_b), METRICS))
                for _ in range(n)) / n
        self.assertTrue(all(rate < bound for rate in rates.values()), rates)
        # the rate is reached where one side's error dominates (Welch's t is then Student's at its
        # n - 1, measured 0.040), so the degrees of freedom are not merely smaller than need be
        self.assertGreater(rates[(3, 3, 20)], 0.0488 - 4 * math.sqrt(0.0488 * 0.9512 / n), rates)

    def test_an_offset_of_a_few_standard_errors_is_caught(self):
        rng = np.random.default_rng(7)
        # true difference 6 x the combined SE of two 5-batch means (sd 1 each: SE sqrt(2/5))
        shift = 6 * math.sqrt(2 / 5)
        caught = sum(not histories.compare(history(rng, [shift] + [0] * 6), history(rng, [0] * 7), METRICS)[0]["agree"]
                     for _ in range(1000))
        self.assertGreater(caught / 1000, 0.65)  # the Bonferroni t test at 4 degrees of freedom: measured 0.76
        shift = 8 * math.sqrt(2 / 5)
        caught = sum(not histories.compare(history(rng, [shift] + [0] * 6), history(rng, [0] * 7), METRICS)[0]["agree"]
                     for _ in range(1000))
        self.assertGreater(caught / 1000, 0.95)  # measured 0.96

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
        # at 3 batches a side the estimated SEs and the smaller side's 2 degrees of freedom cost power:
        # the figure lies well above what a noncentral t at the pooled 4 degrees of freedom gives (6.4
        # SEs over 7 metrics)
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

    def test_the_count_beyond_two_flags_at_its_stated_chance(self):
        # 30 rows at 4 degrees of freedom, each beyond 2 with P 0.116: 7 or more by chance 0.052, 8 or more 0.018
        def rows(k):
            return [{"t": 3.0 if i < k else 0.5, "dof": 4.0} for i in range(30)]
        self.assertNotIn("may be somewhat small", histories.pooled(rows(7)))
        self.assertIn("may be somewhat small", histories.pooled(rows(8)))
        self.assertIn("8 of 30 rows", histories.pooled(rows(8)))
        self.assertIn("give 3.5 on average", histories.pooled(rows(8)))

    def test_the_count_beyond_two_holds_its_rate_and_sees_error_bars_too_small(self):
        # three speeds of 7 metrics, 5 batches a side, drawn from one state; then with every
        # reported SE 0.6 of the true one (error bars 40 % small)
        def trials(shrink, n, seed):
            rng = np.random.default_rng(seed)
            counts, expected, flagged, failed = [], [], 0, 0
            for _ in range(n):
                rows, fails = [], False
                for _ in range(3):
                    a, b = history(rng, [0] * 7), history(rng, [0] * 7)
                    for r in (a, b):
                        for m in METRICS:
                            r[m["se_column"]] *= shrink
                    speed = histories.compare(a, b, METRICS)
                    rows += speed
                    fails |= not all(r["agree"] for r in speed)
                k, chances = histories.beyond(rows)
                counts.append(k)
                expected.append(sum(chances))
                flagged += "may be somewhat small" in histories.pooled(rows)
                failed += fails
            return np.mean(counts), np.std(counts) / math.sqrt(n), np.mean(expected), flagged / n, failed / n
        n = 1000
        count, count_sd, expected, flagged, _ = trials(1.0, n, 11)
        # the chance at the smaller side's degrees of freedom is at least the check's own (measured 1.65
        # rows beyond 2 against 2.44 expected, of 21): never below it (normal tails would expect 0.96)
        self.assertLess(count, expected + 4 * count_sd, (count, expected))
        # flagged at most at its nominal 0.05 (binomial sd 0.0069; measured 0.006)
        self.assertLess(flagged, 0.05 + 4 * math.sqrt(0.05 * 0.95 / n), flagged)
        # error bars 40 % small: flagged in about half the runs (measured 0.46), where each speed's
        # Bonferroni check, failing at any of the three, sees it in 0.28 (and a count expecting the chance at one
        # degree of freedom, 6.2 rows, would hardly ever flag)
        _, _, _, flagged, failed = trials(0.6, n, 12)
        self.assertGreater(flagged, 0.35, flagged)
        self.assertGreater(flagged, failed + 0.1, (flagged, failed))

    def test_the_command_line_checks_each_speed_then_all_at_once(self):
        import tempfile
        sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
        import harness
        metrics = harness.drum_metric_table()
        rng = np.random.default_rng(5)

        def table(path, shift):
            rows = []
            for rpm in (14.0, 21.0):
                x = rng.normal(0.0, 1.0, (5, len(metrics)))
                row = {"rpm": rpm, "batches": 5.0, "revolutions": 5.0}
                for m, col in zip(metrics, x.T):
                    row[m["column"]] = col.mean() + (shift if rpm == 21.0 else 0.0)
                    row[m["se_column"]] = col.std(ddof=1) / math.sqrt(5)
                rows.append(row)
            harness.write_csv(path, rows)

        with tempfile.TemporaryDirectory() as d:
            a, b, out = Path(d, "a.csv"), Path(d, "b.csv"), Path(d, "out.md")
            table(a, 0.0)
            table(b, 100.0)  # 21 rpm far apart in every metric
            self.assertEqual(histories.main([str(a), str(b), "--rpm", "14", "--out", str(out)]), 0)
            self.assertNotIn("Over these speeds", out.read_text())
            self.assertEqual(histories.main([str(a), str(b), "--rpm", "14,21", "--out", str(out)]), 1)
            text = out.read_text()
            self.assertIn("**14 rpm: ", text)
            self.assertIn("**21 rpm: ", text)
            self.assertIn("DISAGREE", text)
            self.assertIn(f"of {2 * len(metrics)} rows", text)
            self.assertIn("may be somewhat small", text)
            with self.assertRaises(SystemExit):  # a speed listed twice would count twice
                histories.main([str(a), str(b), "--rpm", "14,14"])
            rows = harness.read_csv(b)  # B capped at 14 rpm, never found settled
            rows[0].update(done="False", settle_s=float("nan"), revolutions=float("nan"))
            harness.write_csv(b, rows)
            histories.main([str(a), str(b), "--rpm", "14", "--out", str(out)])
            text = out.read_text()
            self.assertIn("B: `" + str(b) + "` (5 batches, no steady window)", text)
            self.assertIn("B did not end by the stop rule", text)
            self.assertNotIn("A did not end", text)

    def test_the_settings_that_differ_are_named(self):
        import json
        import tempfile
        with tempfile.TemporaryDirectory() as d:
            def study(name, variables):
                Path(d, name, "21rpm").mkdir(parents=True)
                Path(d, name, "21rpm", "run.json").write_text(json.dumps(
                    {"settings": {"period": "0.024", "variables": variables}}))
                return str(Path(d, f"{name}.csv"))
            a = study("a", {"dt": "2e-5", "exact": "on"})
            b = study("b", {"dt": "1e-5", "exact": "on", "conventions": "yade"})
            c = study("c", {"exact": "on", "dt": "2e-5"})
            diff = histories.differing(histories.variables(a, 21.0), histories.variables(b, 21.0))
            self.assertEqual(diff, [("conventions", "default", "yade"), ("dt", "2e-5", "1e-5")])
            self.assertIn("dt 2e-5 against 1e-5", histories.settings_sentence(diff))
            same = histories.differing(histories.variables(a, 21.0), histories.variables(c, 21.0))
            self.assertEqual(same, [])
            self.assertIn("same", histories.settings_sentence(same))
            # a speed without a record: nothing claimed either way
            self.assertIsNone(histories.differing(histories.variables(a, 14.0), histories.variables(b, 21.0)))
            self.assertIn("not checked", histories.settings_sentence(None))
            # one number written two ways is one setting; records without settings are no record
            d2 = study("d", {"dt": "2e-05", "exact": "on"})
            self.assertEqual(histories.differing(histories.variables(a, 21.0), histories.variables(d2, 21.0)), [])
            for name, record in (("e", {}), ("f", {"settings": None})):
                Path(d, name, "21rpm").mkdir(parents=True)
                Path(d, name, "21rpm", "run.json").write_text(json.dumps(record))
                self.assertIsNone(histories.variables(str(Path(d, f"{name}.csv")), 21.0))
            Path(d, "g", "21rpm").mkdir(parents=True)
            Path(d, "g", "21rpm", "run.json").write_text(json.dumps({"settings": {"period": "0.024", "variables": None}}))
            self.assertEqual(histories.variables(str(Path(d, "g.csv")), 21.0), {"period": "0.024"})

    def test_a_side_that_did_not_stop_by_the_rule_is_named(self):
        steady = {"batches": 5.0, "revolutions": 5.0, "done": "True", "settle_s": 1.1}
        capped = {"batches": 4.0, "revolutions": float("nan"), "done": "False", "settle_s": float("nan")}
        settled_capped = dict(capped, settle_s=2.0, revolutions=3.2)
        self.assertEqual(histories.not_steady("A", steady), "")
        self.assertEqual(histories.not_steady("A", {"batches": 5.0}), "")  # no such columns: no claim
        self.assertIn("B did not end by the stop rule (not found settled", histories.not_steady("B", capped))
        self.assertIn("B did not end by the stop rule (settled, `done` False", histories.not_steady("B", settled_capped))
        self.assertEqual(histories.revolutions(steady), "5 batches, 5.0 revolutions")
        self.assertEqual(histories.revolutions(capped), "4 batches, no steady window")

    def test_undefined_metrics_are_left_out(self):
        a = history(np.random.default_rng(1), [0] * 7)
        b = dict(a)
        b["m3_u"] = float("nan")
        rows = histories.compare(a, b, METRICS)
        self.assertEqual([r["metric"] for r in rows], [m["label"] for m in METRICS if m["label"] != "m3"])
        self.assertTrue(all(r["t"] == 0.0 and r["agree"] for r in rows))


if __name__ == "__main__":
    unittest.main()
