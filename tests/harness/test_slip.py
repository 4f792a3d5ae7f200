"""The slip test's reading (tools/drum/slip.py) on studies with known answers: a series that drops
between 27 and 28 rpm and one that rises throughout, batch means on values whose standard error
is known, a start row taken from a study table, the step test's false alarms and power on
windows of white noise, and the false-alarm check on a steady study's series (right on white
noise, and it sees correlated noise overstate the steps)."""

import csv
import math
import random
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "drum"))
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import slip  # noqa: E402
import numpy as np  # noqa: E402
from scipy import stats  # noqa: E402

COLUMNS = ["time_s", "Hh_m", "Hc_m", "angle_deg", "bed_turn_1", "wall_roll_1", "wall_slip_1"]


def write_series(docs, name, rpm, rows):
    """docs/NAME/<rpm>rpm/series_metrics.csv with these rows (COLUMNS); returns the folder."""
    folder = docs / name / f"{rpm}rpm"
    folder.mkdir(parents=True)
    with open(folder / "series_metrics.csv", "w", newline="") as f:
        w = csv.DictWriter(f, COLUMNS)
        w.writeheader()
        w.writerows(rows)
    return folder


def write_speed(docs, name, rpm, hc, turn=1.0, n=30):
    """A speed's series: a transient in its first half (which the window leaves out), then Hc
    alternating +-0.1 mm about `hc`: batch means of 5 over the last 15 snapshots are exact."""
    rows = []
    for k in range(n):
        wobble = 1e-4 * (1 if k % 2 else -1)
        transient = 5e-3 if k < n // 2 else 0.0
        rows.append({"time_s": 0.05 * k, "Hh_m": 0.09 + hc, "Hc_m": hc + wobble + transient, "angle_deg": 30.0,
                     "bed_turn_1": turn, "wall_roll_1": 0.02, "wall_slip_1": 0.002})
    write_series(docs, name, rpm, rows)


def write_steady(docs, name, rpm, noise, n=3000, start=5.0):
    """A steady speed of a steady study: samples every 0.05 s from t = 0, steady from `start`
    (series_average.csv), Hc and the others drawn by noise(k) about fixed values."""
    folder = write_series(docs, name, rpm, [
        {"time_s": 0.05 * k, "Hh_m": 0.09 + 1e-4 * noise(), "Hc_m": -0.097 + 1e-4 * noise(),
         "angle_deg": 30.0 + 0.1 * noise(), "bed_turn_1": 0.99 + 1e-3 * noise(),
         "wall_roll_1": 0.02 + 1e-3 * noise(), "wall_slip_1": 0.002 + 1e-4 * noise()} for k in range(n)])
    with open(folder / "series_average.csv", "w", newline="") as f:
        f.write(f"rpm,steady_from_s\n{rpm},{start}\n")


class Slip(unittest.TestCase):
    def test_false_alarms_where_nothing_changes(self):
        # the reference: Welch's test on 3 against 3 independent normal batch means at 0.05, by an
        # independent simulation (numpy, 400,000 pairs): 3.45 % with this seed (3.52 % at 5 million
        # pairs) -- below 5 %, as Welch's estimated degrees of freedom make it at few batches
        rng = np.random.default_rng(1)
        a, b = rng.normal(size=(400000, 3)), rng.normal(size=(400000, 3))
        sa, sb = a.std(axis=1, ddof=1) / math.sqrt(3), b.std(axis=1, ddof=1) / math.sqrt(3)
        dof = (sa ** 2 + sb ** 2) ** 2 / (sa ** 4 / 2 + sb ** 4 / 2)
        reference = np.mean(np.abs(a.mean(axis=1) - b.mean(axis=1)) > stats.t.ppf(0.975, dof) * np.hypot(sa, sb))
        with tempfile.TemporaryDirectory() as d:
            docs = Path(d)
            noise = random.Random(5)
            write_steady(docs, "white", 21, lambda: noise.gauss(0.0, 1.0), n=30000)
            # the steady part (from 5 s) cut into pieces of 1.5 s: 31 samples, as a 1.5 s slip speed's
            # series (its start state included): 29900 // 31 = 964 pieces, 963 pairs, 6 metrics each
            found = slip.null_rate(docs, "white", 1.5, 0.5, 3, 0.05)
            called, compared, pairs = found.counts()
            self.assertEqual((compared, pairs), (963 * 6, 963))
            # within 4 binomial sd of the reference, the variance doubled for the pieces two
            # consecutive pairs share (0.0136): alpha doubled (7-8 %) or a wrong dof (5-6 %) fail
            sd = math.sqrt(2 * reference * (1 - reference) / compared)
            self.assertLess(abs(called / compared - reference), 4 * sd, (called / compared, reference))
            rate, low, high = found.interval()
            self.assertLess(low, reference)
            self.assertGreater(high, reference)
            # white noise: consecutive batch means uncorrelated (about 0 +- 0.02 over 5980 batches)
            self.assertLess(abs(found.lag1[0][1]), 0.1, found.lag1)
            # noise correlated over many samples (AR(1), 0.95 per 0.05 s: about 1 s) makes the 0.25 s
            # batch means of one window alike, their SE far too small: the check must see that
            state = [0.0] * 6
            def correlated(box=[0]):  # noqa: B006 (one AR(1) chain per metric, metrics in turn)
                i = box[0] % 6
                box[0] += 1
                state[i] = 0.95 * state[i] + math.sqrt(1 - 0.95 ** 2) * noise.gauss(0.0, 1.0)
                return state[i]
            write_steady(docs, "correlated", 21, correlated)
            found = slip.null_rate(docs, "correlated", 1.5, 0.5, 3, 0.05)
            rate, low, high = found.interval()
            self.assertGreater(low, 0.1, (rate, low, high))
            # AR(1) at 0.95 per sample: batch means of 5 samples correlate at about 0.8; the figure is
            # Hc's, over the steady part (from 5 s), batches as long as a piece's (31 samples, the
            # last 16, 3 batches: 5 samples, 0.25 s)
            self.assertGreater(found.lag1[0][1], 0.6, found.lag1)
            with open(docs / "correlated" / "21rpm" / "series_metrics.csv") as f:
                hc = np.array([float(r["Hc_m"]) for r in csv.DictReader(f) if float(r["time_s"]) >= 5.0 - 1e-9])
            means = hc[:len(hc) // 5 * 5].reshape(-1, 5).mean(axis=1)
            means -= means.mean()
            self.assertAlmostEqual(found.lag1[0][1], np.sum(means[1:] * means[:-1]) / np.sum(means ** 2), places=9)

    def test_the_interval_counts_correlated_metrics_as_fewer(self):
        # six metrics that always agree are one comparison per pair: the interval as wide as the
        # pairs' own; none called: a pair counts as one comparison
        alike = slip.NullRate([(21.0, 6 if k % 10 == 0 else 0, 6) for k in range(100)])
        one = slip.NullRate([(21.0, 1 if k % 10 == 0 else 0, 1) for k in range(100)])
        self.assertAlmostEqual(alike.interval()[2], one.interval()[2], places=6)
        self.assertAlmostEqual(alike.interval()[1], one.interval()[1], places=6)
        none = slip.NullRate([(28.0, 0, 6)] * 17)
        self.assertAlmostEqual(none.interval()[2], 1 - 0.025 ** (1 / 17), places=9)
        self.assertEqual(none.interval(21, 35)[:2], (0.0, 0.0))
        self.assertTrue(math.isnan(none.interval(40, 60)[0]))

    def test_the_report_states_the_false_alarm_rate(self):
        with tempfile.TemporaryDirectory() as d:
            docs = Path(d)
            rng = random.Random(6)
            write_steady(docs, "study_thesis", 21, lambda: rng.gauss(0.0, 1.0), n=700)
            for rpm in range(22, 25):
                write_speed(docs, "one", rpm, -0.097)
            out = docs / "slip"
            self.assertEqual(slip.main(["--study", "one", "one", "--docs", d, "--out", str(out)]), 0)
            called, compared, pairs = slip.null_rate(docs, "study_thesis", 1.45, 0.5, 3, 0.05).counts()  # (runs of 30 samples)
            text = out.with_suffix(".md").read_text()
            self.assertIn(f"every speed: {called} of {compared} (", text)
            self.assertIn("calls changes at a rate not shown to exceed the stated one", text)
            # Hc alone: one comparison per pair of pieces
            hc_called, hc_compared, _ = slip.null_rate(docs, "study_thesis", 1.45, 0.5, 3, 0.05).hc.counts()
            self.assertEqual(hc_compared, pairs)
            self.assertIn(f"Hc alone, every speed: {hc_called} of {hc_compared} (", text)
            # and the rate at other piece lengths, the run's own among them
            self.assertIn("| piece [s] | changes called |", text)
            self.assertIn(f"| 1.45 | {called} of {compared} |", text)
            self.assertEqual(slip.main(["--study", "one", "one", "--null", "-", "--docs", d, "--out", str(out)]), 0)
            self.assertNotIn("Where nothing changes", out.with_suffix(".md").read_text())

    def test_batch_means(self):
        mean, se = slip.batch_means([1.0, 2.0, 3.0, 4.0, 5.0, 6.0], 3)  # batch means 1.5, 3.5, 5.5
        self.assertAlmostEqual(mean, 3.5)
        self.assertAlmostEqual(se, 2.0 / math.sqrt(3))
        mean, se = slip.batch_means([9.0, 1.0, 1.0, 1.0], 3)  # the first value left out
        self.assertEqual((mean, se), (1.0, 0.0))
        self.assertTrue(math.isnan(slip.batch_means([1.0], 3)[1]))
        self.assertTrue(all(math.isnan(x) for x in slip.batch_means([1.0, float("nan"), 2.0, 3.0], 3)))

    def test_a_drop_at_28_and_a_steady_rise(self):
        with tempfile.TemporaryDirectory() as d:
            docs = Path(d)
            for rpm in range(22, 29):
                rise = -0.0970 + 0.0005 * (rpm - 22)
                write_speed(docs, "rises", rpm, rise)
                # the same, but the bed slips at 28 rpm: 3 mm down, its turn falls
                write_speed(docs, "slips", rpm, rise - (0.003 if rpm == 28 else 0.0), 0.9 if rpm == 28 else 1.0)
            with open(docs / "chain.csv", "w", newline="") as f:
                w = csv.DictWriter(f, ["rpm", "batches", *COLUMNS[1:], *(slip.se_column(c) for c in COLUMNS[1:])])
                w.writeheader()
                w.writerow({"rpm": 21, "batches": 5, "Hh_m": 0.087, "Hc_m": -0.0975, "angle_deg": 30.0, "bed_turn_1": 1.0,
                            "wall_roll_1": 0.02, "wall_slip_1": 0.002, **{slip.se_column(c): 1e-5 for c in COLUMNS[1:]}})
            out = docs / "slip"
            self.assertEqual(slip.main(["--study", "rises", "rises", "--study", "slips", "slips", "--start", "chain:21",
                                        "--start", "chain:21", "--docs", d, "--out", str(out)]), 0)
            text = out.with_suffix(".md").read_text()
            self.assertIn("## rises\n\n**27 → 28 rpm: Hc rises** (+0.50 mm", text)
            self.assertIn("## slips\n\n**27 → 28 rpm: Hc drops** (-2.50 mm", text)
            self.assertIn("First drop of Hc along the steps: 27 → 28 rpm", text)
            # the question answered for the two together: one drops, the other not, and they differ
            self.assertIn("**Hc drops between 27 and 28 rpm with slips and not with rises, and the two steps differ** "
                          "(slips minus rises: -3.00 ±", text)
            self.assertIn("- slips: Hc drops, -2.50 ±", text)
            self.assertEqual(text.count("First drop"), 1)
            # the windows leave the transient out: Hc within round-off of the set value
            speeds = slip.study_speeds(docs, "slips", 0.5, 3)
            self.assertEqual([s[0] for s in speeds], list(range(22, 29)))
            self.assertAlmostEqual(speeds[-1][1]["Hc_m"][0], -0.0970 + 0.003 - 0.003, delta=1e-4 / 3 + 1e-12)
            self.assertLess(speeds[-1][1]["bed_turn_1"][0], 0.95)
            # the start row comes first, from the table
            self.assertIn("| 21 | steady start | -97.50 ± 0.01 |", text)
            rows = list(csv.DictReader(open(out.with_suffix(".csv"))))
            self.assertEqual(len(rows), 16)
            self.assertGreater(out.with_suffix(".png").stat().st_size, 10000)

    def test_the_step_by_window(self):
        """A step the speed change causes reads the same with every window; one that is the tail
        of a transient (27 rpm still falling through its run, 28 rpm flat at where it ended) grows
        with the window as the fall predicts: the last m of n samples at 27 rpm average
        -0.095 - 0.005 (2n - 1 - m) / (2 (n - 1)), so the step is -5 (m - 1) / (2 (n - 1)) mm
        (0.1 mm noise: within 0.15 mm), and on a short window it is "no change"."""
        with tempfile.TemporaryDirectory() as d:
            docs = Path(d)
            n, rng = 30, random.Random(7)
            for name, at27 in (("clean", lambda k: -0.097), ("tail", lambda k: -0.095 - 0.005 * k / (n - 1))):
                for rpm, level in ((27, at27), (28, lambda k: -0.100)):
                    write_series(docs, name, rpm, [
                        {"time_s": 0.05 * k, "Hh_m": 0.09, "Hc_m": level(k) + rng.gauss(0.0, 1e-4),
                         "angle_deg": 30.0, "bed_turn_1": 1.0, "wall_roll_1": 0.02, "wall_slip_1": 0.002}
                        for k in range(n)])
            cells = [slip.step_by_window(docs, name, 3, 0.05) for name in ("clean", "tail")]
            lines = slip.window_section(["clean", "tail"], cells, 3, 0.05)
            clean = next(row for row in lines if row.startswith("| clean |")).rstrip(" |").split(" | ")[1:]
            tail = next(row for row in lines if row.startswith("| tail |")).rstrip(" |").split(" | ")[1:]
            self.assertEqual(len(clean), len(slip.WINDOWS))
            self.assertTrue(all(cell.startswith(("drops (-3.0", "drops (-2.9")) for cell in clean), clean)
            self.assertEqual(len(tail), len(slip.WINDOWS))
            for window, cell in zip(slip.WINDOWS, tail):
                m = max(1, round(window * n))
                self.assertAlmostEqual(float(cell.split("(")[1].split(" ")[0]), -5.0 * (m - 1) / (2 * (n - 1)),
                                       delta=0.15, msg=cell)
            self.assertEqual(slip.WINDOWS[0], 0.3)
            self.assertTrue(tail[0].startswith("no change"), tail)
            # a study without 27 and 28 rpm has no row; none at all, no section
            self.assertEqual(slip.step_by_window(docs, "none", 3, 0.05), [])
            self.assertEqual(slip.window_section(["none"], [slip.step_by_window(docs, "none", 3, 0.05)], 3, 0.05), [])

    def test_false_alarms_and_power_of_a_step(self):
        # two windows of one state (white noise, 30 snapshots, the last 15 in 3 batches): the
        # t-test at 0.05 calls at most about 5 % of them a change (binomial sd 0.5 % over 2000 pairs; a
        # "twice the combined error" rule calls about 12 %); a true step of 5 combined standard
        # errors of the batch means is caught in most pairs
        rng = random.Random(7)

        def window(mean):
            rows = [{c: 0.0 for c in COLUMNS} for _ in range(30)]
            for r in rows:
                r["Hc_m"] = mean + rng.gauss(0.0, 1.0)
            return slip.window_average(rows, 0.5, 3)["Hc_m"]

        def called(shift, pairs=2000):
            n = 0
            for _ in range(pairs):
                (xa, sa), (xb, sb) = window(0.0), window(shift)
                n += slip.change(xa, sa, 3, xb, sb, 3, 0.05)[0] != "no change"
            return n / pairs

        self.assertLess(called(0.0), 0.065)
        self.assertGreater(called(0.0), 0.02)  # (Welch is slightly conservative: 3.6-5 % seen)
        # batch means of 5 iid values: sd 1/sqrt(5); their means' se 1/sqrt(15); combined sqrt(2/15)
        self.assertGreater(called(5.0 * math.sqrt(2.0 / 15.0), 500), 0.75)

    def test_the_stated_catchable_drop_is_caught_four_times_in_five(self):
        # the figure the report gives for a step ("a drop of X mm would be caught with 80 %
        # probability"), for windows of white noise: batch means of 5 values, se 1/sqrt(15) a side;
        # stepping them by X, the step's own test calls 0.8 of the pairs a change (binomial sd 0.005
        # over 6000 pairs, 4 sd allowed; X is 4.28 combined errors: stated with a Bonferroni critical
        # over the 6 metrics it would be caught 0.996 of the time, with the normal's 1.96 + 0.84
        # errors 0.45, at a power of 0.85 instead of 0.8 (4.62 errors) 0.83)
        rng = random.Random(11)
        se = 1.0 / math.sqrt(15.0)
        drop = slip.catchable((se, 3, se, 3), 0.05)

        def window(mean):
            rows = [{c: 0.0 for c in COLUMNS} for _ in range(30)]
            for r in rows:
                r["Hc_m"] = mean + rng.gauss(0.0, 1.0)
            return slip.window_average(rows, 0.5, 3)["Hc_m"]

        n = 0
        for _ in range(6000):
            (xa, sa), (xb, sb) = window(0.0), window(-drop)
            n += slip.change(xa, sa, 3, xb, sb, 3, 0.05)[0] == "drops"
        self.assertAlmostEqual(n / 6000, 0.8, delta=0.02)

    def test_two_conventions_steps_compared(self):
        # changes +1 and -1 with every batch error 0.1 (3 batches a side): the difference -2 has
        # the combined error 0.2 and Satterthwaite's 8 degrees of freedom (four equal parts of 2)
        x = (1.0, math.hypot(0.1, 0.1), (0.1, 3, 0.1, 3))
        y = (-1.0, math.hypot(0.1, 0.1), (0.1, 3, 0.1, 3))
        difference, critical = slip.contrast(x, y, 0.05)
        self.assertEqual(difference, -2.0)
        self.assertAlmostEqual(critical, stats.t.ppf(0.975, 8) * 0.2, places=12)
        # unequal errors and batches: se^2 = 0.01 + 0.09 + 0.04 + 0.0025 = 0.1425 and
        # se^4 / (1e-4/2 + 8.1e-3/4 + 1.6e-3/3 + 6.25e-6/9) = 7.78 degrees of freedom (the sum of
        # n - 1, 18, or a Welch over the two changes, would give other criticals)
        x = (1.0, math.hypot(0.1, 0.3), (0.1, 3, 0.3, 5))
        y = (0.5, math.hypot(0.2, 0.05), (0.2, 4, 0.05, 10))
        dof = 0.1425 ** 2 / (1e-4 / 2 + 8.1e-3 / 4 + 1.6e-3 / 3 + 6.25e-6 / 9)
        self.assertAlmostEqual(dof, 7.78, places=2)
        self.assertAlmostEqual(slip.contrast(x, y, 0.05)[1], stats.t.ppf(0.975, dof) * math.sqrt(0.1425), places=12)
        # a speed with a single batch has no error estimate: no verdict
        self.assertTrue(math.isnan(slip.contrast(x, (0.0, 0.1, (0.1, 1, 0.0, 3)), 0.05)[1]))

    def test_the_answer_in_every_case(self):
        # studies of two speeds, 27 and 28 rpm, Hc in m with batch errors of 0.1 mm (3 batches):
        # a step's own test at 0.05 counts beyond t(0.975, 4) * 0.141 = 0.39 mm, a contrast of
        # two steps beyond t(0.975, 8) * 0.2 = 0.46 mm
        def study(step, se=1e-4):
            return [(27.0, {"Hc_m": (0.0, se)}, 1.5, 3), (28.0, {"Hc_m": (step, se)}, 1.5, 3)]

        def answer(*steps):
            return "\n".join(slip.answer_section([(f"S{k}", s) for k, s in enumerate(steps)], 0.05))

        text = answer(study(-2e-3), study(0.5e-3))
        self.assertIn("- S0: Hc drops, -2.00 ± 0.39 mm (95% interval of the change)", text)
        self.assertIn("- S1: Hc rises, +0.50 ± 0.39 mm", text)
        self.assertIn("**Hc drops between 27 and 28 rpm with S0 and not with S1, and the two steps differ** "
                      "(S1 minus S0: +2.50 ± 0.46 mm", text)
        # one passes its test, the other not, but the steps are closer than their contrast can tell
        text = answer(study(-0.45e-3), study(-0.30e-3))
        self.assertIn("- S1: Hc no change", text)
        self.assertIn("with S0 alone, but the two steps do not differ", text)
        self.assertNotIn("and not with", text)
        self.assertIn("**Hc drops between 27 and 28 rpm with both** (", answer(study(-2e-3), study(-2.1e-3)))
        self.assertIn("with both, by different amounts**", answer(study(-1e-3), study(-3e-3)))
        self.assertIn("**Hc drops between 27 and 28 rpm with neither** (", answer(study(0.5e-3), study(0.6e-3)))
        self.assertIn("with neither; the two steps differ**", answer(study(0.0), study(2e-3)))
        # no error bars: no verdict, not "no drop"
        text = answer(study(-2e-3), study(0.5e-3, float("nan")))
        self.assertIn("- S1: no verdict", text)
        self.assertIn("S0 against S1: no verdict", text)
        self.assertNotIn("not with", text)
        # three studies: every pair; the same label twice does not matter
        text = answer(study(-2e-3), study(0.5e-3), study(-2e-3))
        self.assertEqual(text.count("**Hc drops"), 3)
        self.assertTrue(slip.answer_section([("A", study(-2e-3)), ("A", study(0.5e-3))], 0.05))
        # a study without 28 rpm leaves a single one: no answer section
        self.assertEqual(slip.answer_section([("A", study(-2e-3)), ("B", study(0.0)[:1])], 0.05), [])
        # the level follows alpha
        self.assertIn("(99% interval", "\n".join(slip.answer_section([("A", study(-2e-3)), ("B", study(0.0))], 0.01)))

    def test_histories_of_one_set_answered_together(self):
        # two sets of settings with two histories each (27 and 28 rpm, batch errors 0.1 mm, 3
        # batches: a contrast counts beyond 0.46 mm): set Y drops in both histories, by 1 and 6 mm,
        # set T rises in both; Y's two steps differ beyond their error bars, T's do not
        def study(step):
            return [(27.0, {"Hc_m": (0.0, 1e-4)}, 1.5, 3), (28.0, {"Hc_m": (step, 1e-4)}, 1.5, 3)]

        with tempfile.TemporaryDirectory() as tmp:
            docs = Path(tmp)
            for name, variables in (("t1", '{"dt": "2e-5", "exact": "on"}'),
                                    ("t2", '{"exact": "on", "dt": "2e-5"}'),
                                    ("y1", '{"dt": "1e-5", "exact": "off", "conventions": "yade"}')):
                (docs / name / "28rpm").mkdir(parents=True)
                (docs / name / "28rpm" / "run.json").write_text(
                    f'{{"settings": {{"period": "0.024", "variables": {variables}}}}}')
            t1, t2, y1 = (slip.study_settings(docs, n) for n in ("t1", "t2", "y1"))
            self.assertEqual(t1, t2)  # the order in run.json does not matter
            self.assertNotEqual(t1, y1)
            self.assertIsNone(slip.study_settings(docs, "absent"))
        names = slip.set_names([t1, y1])
        self.assertEqual(names[t1], "conventions default, dt 2e-5, exact on")
        self.assertEqual(names[y1], "conventions yade, dt 1e-5, exact off")
        # with labels, a set is named by its first history's label, then the other settings in words
        named = slip.set_names([t1, y1], {t1: "thesis table", y1: "YADE conventions"})
        self.assertEqual(named[t1], "thesis table at dt 2e-5 s, exactRestitution on")
        self.assertEqual(named[y1], "YADE conventions at dt 1e-5 s, exactRestitution off")
        studies = [("T1", study(0.6e-3)), ("Y1", study(-1e-3)), ("Y2", study(-6e-3)), ("T2", study(0.5e-3))]
        text = "\n".join(slip.answer_section(studies, 0.05, sets=[t1, y1, y1, t1]))
        self.assertIn("**By set of settings: Hc drops between 27 and 28 rpm with T1 at dt 2e-5 s, exactRestitution "
                      "on in 0 of 2 histories; with Y1 at dt 1e-5 s, exactRestitution off in 2 of 2 histories.** "
                      "Steps of different sets differ in 4 of 4 Welch contrasts at 95% (below), which reuse the 4 "
                      "histories", text)
        # with the history as the unit: the mean of Y's steps (-1, -6) minus T's (0.6, 0.5)
        self.assertIn("the mean step with Y1 at dt 1e-5 s, exactRestitution off minus that with T1 at dt 2e-5 s, "
                      "exactRestitution on: -4.05 mm, Welch's p = ", text)
        # without ramps, no release line in the headline
        self.assertNotIn("where the bed lets go", text)
        # with the releases on the ramp clock: each set's onsets, their spread, the gap between sets;
        # with the verdicts over windows: how many windows call each history's drop
        headline = "\n".join(slip.sets_headline(["rises", "drops", "drops", "rises"], [t1, y1, y1, t1], [], "95%",
                                                 [31.53, 26.73, 28.03, 31.63],
                                             [["rises"] * 5, ["no change", "drops", "drops", "no change", "no change"],
                                              ["drops"] * 4 + ["no change"], ["rises"] * 5]))
        self.assertIn("with conventions default, dt 2e-5, exact on at 31.5 and 31.6 rpm (0.1 apart); with conventions "
                      "yade, dt 1e-5, exact off at 26.7 and 28.0 rpm (1.3 apart). Between sets: 3.5-4.9 rpm (", headline)
        self.assertIn("exact on in 0 of 2 histories (a drop called in 0, 0 of 5 windows, by history); with conventions "
                      "yade, dt 1e-5, exact off in 2 of 2 histories (a drop called in 2, 4 of 5 windows, by history)",
                      headline)
        # histories listed in the order given, onsets and window counts alike (a later history that
        # lets go earlier stays paired with its own windows)
        headline = "\n".join(slip.sets_headline(["drops", "drops"], [y1, y1], [], "95%", [28.03, 26.73],
                                                 [["drops"] * 4 + ["no change"], ["drops"] * 2 + ["no change"] * 3]))
        self.assertIn("at 28.0 and 26.7 rpm (1.3 apart)", headline)
        self.assertIn("(a drop called in 4, 2 of 5 windows, by history)", headline)
        # the history as the unit: Welch on one value per history, [1, 3] against [2, 6]: t = 2 / sqrt(5),
        # Satterthwaite's dof 25 / 17
        diff, p = slip.between_histories([1.0, 2.0, 3.0, 6.0], ["a", "b", "a", "b"])
        self.assertAlmostEqual(diff, 2.0)
        self.assertAlmostEqual(p, 2 * stats.t.sf(2 / math.sqrt(5), 25 / 17), places=9)
        self.assertIsNone(slip.between_histories([1.0, 2.0, 3.0], ["a", "b", "a"]))
        self.assertIn("Welch's p = 0.10", "\n".join(slip.sets_headline(
            ["rises", "drops", "drops", "rises"], [t1, y1, y1, t1], [], "95%", [31.53, 26.73, 28.03, 31.63])))
        # a history that never lets go: no release line (the spread would be undefined)
        self.assertNotIn("lets go", "\n".join(slip.sets_headline(["rises", "drops"], [t1, y1], [], "95%", [None, 27.0])))
        # across sets: the pairwise answer, four times, not in bold (within-run scatter only: the
        # per-set headline leads); within a set: compared as histories
        self.assertEqual(text.count("Pairwise, within-run scatter only: Hc drops between 27 and 28 rpm with Y"), 4)
        self.assertEqual(text.count("**Hc drops"), 0)
        self.assertIn("T2 minus T1: -0.10 ± 0.46 mm (95%): within the steps' combined error bars (a difference of ", text)
        self.assertIn("Y2 minus Y1: -5.00 ± 0.46 mm (95%): BEYOND the steps' combined error bars", text)
        self.assertNotIn("with neither", text)
        self.assertNotIn("with both", text)
        # a set whose histories disagree shows as such, and a contrast that does not tell the sets
        # apart is counted as not differing
        text = "\n".join(slip.answer_section([("T1", study(-0.2e-3)), ("Y1", study(-1e-3)), ("T2", study(-1e-3))],
                                             0.05, sets=[t1, y1, t1]))
        self.assertIn("exactRestitution on in 1 of 2 histories; with Y1 at dt 1e-5 s, exactRestitution off in 1 of 1 "
                      "history.** "
                      "Steps of different sets differ in 1 of 2 Welch contrasts", text)
        # without sets every study is its own: no headline, no histories paragraph
        text = "\n".join(slip.answer_section(studies, 0.05))
        self.assertNotIn("By set of settings", text)
        self.assertNotIn("Two histories of one set", text)
        self.assertEqual(text.count("**Hc drops"), 6)

    def test_where_the_bed_lets_go(self):
        # a ramp of 3 speeds as steady.py writes them: 10 samples 0.05 s apart, each speed's first
        # a repeat of the speed before's last state (same time; bed_turn divided by the new
        # speed, here 0.85: left out). Carried (0.98) with a one-sample dip to 0.85 at 29 rpm and
        # a sample without bed_turn, no release; at 30 rpm from 0.20 s into it (t 1.10) 0.8, with
        # one sample back above the threshold (0.91), which does not move the release
        with tempfile.TemporaryDirectory() as d:
            docs = Path(d)
            for j, rpm in enumerate((28, 29, 30)):
                rows = []
                for k in range(10):
                    turn = 0.98
                    if j and k == 0:
                        turn = 0.85
                    elif rpm == 29 and k in (5, 7):
                        turn = 0.85 if k == 5 else float("nan")
                    elif rpm == 30 and k >= 4:
                        turn = 0.91 if k == 8 else 0.8
                    rows.append({"time_s": 0.45 * j + 0.05 * k, "Hh_m": 0.1, "Hc_m": -0.093, "angle_deg": 38.0,
                                 "bed_turn_1": turn, "wall_roll_1": 0.04, "wall_slip_1": 0.003})
                write_series(docs, "ramp", rpm, rows)
            ramp = slip.ramp_series(docs, "ramp")
            self.assertEqual(len(ramp), 10 + 8 + 9)
            self.assertNotIn(0.85, [r[3] for r in ramp if r[1] == 30])
            t, rpm, into = slip.lets_go(ramp)
            self.assertEqual(rpm, 30.0)
            self.assertAlmostEqual(t, 1.10)
            self.assertAlmostEqual(into, 0.20)
            # without the running median the sample at 0.91 would leave one sample below at the end:
            # no release found
            self.assertIsNone(slip.lets_go(ramp, span=1))
            # fewer samples below than `least` at the end: not (yet) a release
            self.assertIsNone(slip.lets_go(ramp[:21]))
            self.assertIsNone(slip.lets_go(ramp[:18]))
            # the report says it, and says when a bed stays carried
            speeds = slip.study_speeds(docs, "ramp", 0.5, 3)
            self.assertIn("below 0.72) at simulated time 1.10 s, from 0.20 s into 30 rpm",
                          slip.markdown([("ramp", speeds)], 0.5, 3, 0.05, "x", ramps=[ramp]))
            self.assertIn("turns with the drum throughout",
                          slip.markdown([("ramp", speeds)], 0.5, 3, 0.05, "x", ramps=[ramp[:18]]))
            # the answer's line on where each bed lets go: a release one speed before 27 -> 28
            # would not show in that step
            line = "\n".join(slip.released_line([("A", speeds), ("B", speeds), ("C", [])], [ramp, ramp[:18], []]))
            self.assertIn("with A from 0.20 s into 30 rpm, not yet half-way; with B not up to 29 rpm.", line)
            self.assertNotIn("with C", line)
            # the same ramp three rpm lower, its released samples at 0.8 then 0.5 (the running
            # median below 0.72 from 1.15 s, 0.25 s into 27 rpm), the sample at 0.91 kept: a release that
            # starts before 28 rpm is flagged as lying before the 27 -> 28 step
            lower = [(t, rpm - 3, hc, 0.5 if t >= 1.149 and turn < 0.9 else turn) for t, rpm, hc, turn in ramp]
            line = "\n".join(slip.released_line([("L", speeds)], [lower]))
            self.assertIn("with L from 0.20 s into 27 rpm, half-way 0.25 s into 27 rpm (before the 27 → 28 rpm step", line)
            self.assertNotIn("before the 27", "\n".join(slip.released_line([("A", speeds)], [ramp])))
            # a release from 28 rpm on is not before the step; the per-study line gives the
            # half-way point too
            at28 = [(t, rpm + 1, hc, turn) for t, rpm, hc, turn in lower]
            self.assertIn("from 0.20 s into 28 rpm, half-way 0.25 s into 28 rpm.",
                          "\n".join(slip.released_line([("M", speeds)], [at28])))
            self.assertIn("below 0.72) at simulated time 1.10 s, from 0.20 s into 27 rpm, half-way 0.25 s into 27 rpm.",
                          slip.markdown([("L", speeds)], 0.5, 3, 0.05, "x", ramps=[lower]))
            self.assertIn("from 0.20 s into 30 rpm, not yet half-way.",
                          slip.markdown([("A", speeds)], 0.5, 3, 0.05, "x", ramps=[ramp]))
            # and the answer carries the line where ramps are given
            two = [(27.0, {"Hc_m": (0.0, 1e-4)}, 1.5, 3), (28.0, {"Hc_m": (-2e-3, 1e-4)}, 1.5, 3)]
            text = "\n".join(slip.answer_section([("L", two), ("B", two)], 0.05, [lower, []]))
            self.assertIn("## Answer: 27 → 28 rpm", text)
            self.assertIn("Along the ramp the bed lets go of the drum", text)
            self.assertIn("with L from 0.20 s into 27 rpm", text)
            self.assertNotIn("Along the ramp", "\n".join(slip.answer_section([("L", two), ("B", two)], 0.05)))
            self.assertEqual(slip.released_line([("A", speeds)], [[]]), [])

    def test_the_ramp_clock(self):
        # speeds of 1.5 s (10 samples 0.15 s apart after the first speed's start): 0.6 s into 27
        # rpm is 27.4; a first speed counts from its first sample
        ramp = [(0.15 * k, 26.0 + (k - 1) // 10 if k else 26.0, -0.09, 1.0) for k in range(31)]
        self.assertAlmostEqual(slip.ramp_clock(ramp, (2.1, 27.0, 0.6)), 27.4)
        self.assertAlmostEqual(slip.ramp_clock(ramp, (0.45, 26.0, 0.45)), 26.3)
        # runs of unequal length: 27 rpm cut to 0.75 s (its last 5 samples dropped), 0.6 s into it is 27.8
        short = [r for r in ramp if not (r[1] == 27.0 and r[0] > 1.5 + 0.75 + 1e-9)]
        short = [(t if rpm < 28 else t - 0.75, rpm, hc, turn) for t, rpm, hc, turn in short]
        self.assertAlmostEqual(slip.ramp_clock(short, (2.1, 27.0, 0.6)), 27.8)
        self.assertAlmostEqual(slip.ramp_clock(short, (2.4, 28.0, 0.15)), 28.1)

    def test_the_difference_two_steps_are_seen_to_differ_by(self):
        # the contrast (four batch-mean errors, 3 batches each) drawn from normal batch means and
        # judged by its own Welch test written out here (Satterthwaite over the four errors): a
        # true difference of contrast_catchable's size is called with probability 0.8 (within
        # 0.012, 4.2 binomial sd at 20,000 draws); half of it far less often
        se = np.array([1e-4, 2e-4, 1.5e-4, 1e-4])
        x = (0.0, math.hypot(se[0], se[1]), (se[0], 3, se[1], 3))
        y = (0.0, math.hypot(se[2], se[3]), (se[2], 3, se[3], 3))
        size = slip.contrast_catchable(x, y, 0.05)
        rng = np.random.default_rng(3)
        draws = 20000
        for true, expected in ((size, 0.8), (size / 2, None)):
            batches = rng.normal(0.0, 1.0, (draws, 4, 3)) * (se * math.sqrt(3))[None, :, None]
            means, errs = batches.mean(axis=2), batches.std(axis=2, ddof=1) / math.sqrt(3)
            difference = (means[:, 3] - means[:, 2] + true) - (means[:, 1] - means[:, 0])
            combined = np.sqrt(np.sum(errs ** 2, axis=1))
            dof = np.sum(errs ** 2, axis=1) ** 2 / np.sum(errs ** 4 / 2, axis=1)
            rate = np.mean(np.abs(difference) > stats.t.ppf(0.975, dof) * combined)
            if expected:
                self.assertAlmostEqual(rate, expected, delta=0.012)
            else:
                self.assertLess(rate, 0.4)

    def test_a_missing_start_speed_is_named(self):
        with tempfile.TemporaryDirectory() as d:
            write_speed(Path(d), "s", 22, -0.097)
            self.assertEqual(slip.main(["--study", "s", "s", "--start", "nowhere:21", "--docs", d,
                                        "--out", str(Path(d) / "x")]), 1)



class PlainAnswer(unittest.TestCase):
    def test_each_set_against_the_thesis_drop(self):
        a, b, c = ((("conventions", "a"),), (("conventions", "b"),), (("conventions", "c"),))  # settings as slip keys them
        lines = slip.plain_answer([a, a, b, b, c], [31.5, 31.6, 26.7, 28.0, 25.0], {a: "set A", b: "set B", c: "set C"})
        text = lines[0]
        self.assertTrue(text.startswith("In plain words: the thesis saw its drop between 27 and 28 rpm"))
        self.assertIn("with set A, the bed lets go of the drum between 31.5 and 31.6 rpm (2 histories), so it is "
                      "still carried at 28 rpm", text)
        self.assertIn("with set B, the bed lets go of the drum between 26.7 and 28.0 rpm (2 histories), where the "
                      "thesis saw its drop", text)
        self.assertIn("with set C, the bed lets go of the drum at 25.0 rpm (1 histories), before", text)
        self.assertEqual(slip.plain_answer([a, b], [31.5, None]), [])

if __name__ == "__main__":
    unittest.main()
