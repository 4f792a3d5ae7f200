"""The steady-state study driver's decisions (tools/drum/steady.py): which speeds are done,
when a speed stops, targets. No LIGGGHTS runs (the end-to-end test runs a tiny drum)."""

import gzip
import math
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "drum"))
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import chain  # noqa: E402
import steady  # noqa: E402

SETTINGS = {"period": "0.024", "variables": {"dt": "2e-5"}, "segment": 1.0, "cap": 30.0, "settle": 2.0,
            "targets": {"Hc": 3e-4, "angle": 0.3}, "min_batches": 5}


def committed(start, state, settings=SETTINGS):
    return {"settings": settings, "start_state_sha256": start, "state_sha256": state}


class Plan(unittest.TestCase):
    def test_resumes_after_the_last_committed_speed(self):
        c = {7: committed(None, "a"), 14: committed("a", "b"), 21: None, 28: None}
        self.assertEqual(steady.plan([7, 14, 21, 28], c, SETTINGS), [(7, True), (14, True), (21, False), (28, False)])

    def test_a_speed_from_an_older_state_of_its_predecessor_is_redone(self):
        # 14 rpm was redone after 21 rpm started from its old state: 21 and everything after it run again
        c = {7: committed(None, "a"), 14: committed("a", "b2"), 21: committed("b1", "c"), 28: committed("c", "d")}
        self.assertEqual(steady.plan([7, 14, 21, 28], c, SETTINGS), [(7, True), (14, True), (21, False), (28, False)])

    def test_the_first_speed_is_done_only_from_the_given_start_state(self):
        c = {21: committed("shipped", "a"), 28: committed("a", "b")}
        self.assertEqual(steady.plan([21, 28], c, SETTINGS, first_state="shipped"), [(21, True), (28, True)])
        # the same speeds from the grid (or from another shipped state) are not this study's
        self.assertEqual(steady.plan([21, 28], c, SETTINGS), [(21, False), (28, False)])
        self.assertEqual(steady.plan([21, 28], c, SETTINGS, first_state="other"), [(21, False), (28, False)])

    def test_other_settings_stop_the_study_naming_them(self):
        other = dict(SETTINGS, segment=0.5)
        with self.assertRaisesRegex(chain.PlanError, r"14 rpm is committed with other settings \(segment\)"):
            steady.plan([7, 14], {7: committed(None, "a"), 14: committed("a", "b", other)}, SETTINGS)
        self.assertEqual(steady.plan([7, 14], {7: committed(None, "a"), 14: committed("a", "b", other)}, SETTINGS,
                                     force=True), [(7, True), (14, False)])

    def test_extend_takes_a_speed_whose_stop_rule_alone_changed(self):
        # longer cap and another rule: the same trajectory, decided again and run on; without
        # --extend the study stops and says the option exists
        old = dict(SETTINGS, cap=20.0)
        c = {7: committed(None, "a", old), 14: committed("a", "b", old), 21: committed("b", "c")}
        self.assertEqual(steady.plan([7, 14, 21], c, SETTINGS, extend=True), [(7, "extend"), (14, "extend"), (21, True)])
        with self.assertRaisesRegex(chain.PlanError, r"7 rpm is committed with other settings \(cap\).*--extend"):
            steady.plan([7, 14, 21], c, SETTINGS)

    def test_an_extended_speed_is_done_for_its_earlier_settings(self):
        # extended under a later cap: the study's first command still finds it committed
        later = dict(SETTINGS, cap=60.0)
        c = {7: dict(committed(None, "a2", later), earlier_states_sha256=["a"], earlier_settings=[SETTINGS]),
             14: committed("a", "b")}
        self.assertEqual(steady.plan([7, 14], c, SETTINGS), [(7, True), (14, True)])
        with self.assertRaisesRegex(chain.PlanError, r"7 rpm is committed with other settings \(cap\)"):
            steady.plan([7, 14], c, dict(SETTINGS, cap=40.0))

    def test_extend_never_takes_another_trajectory(self):
        other = dict(SETTINGS, segment=0.5)
        with self.assertRaisesRegex(chain.PlanError, r"7 rpm is committed with other settings \(segment\)"):
            steady.plan([7], {7: committed(None, "a", other)}, SETTINGS, extend=True)
        # nor a speed from another start (it is redone, as without --extend)
        self.assertEqual(steady.plan([7, 14], {7: committed(None, "a"), 14: committed("x", "b", dict(SETTINGS, cap=20.0))},
                                     SETTINGS, force=True, extend=True), [(7, True), (14, False)])

    def test_the_successors_of_an_extended_speed_stay_committed(self):
        # 7 rpm ran on from "a" to "a2" after 14 rpm had started from "a"; "a0" was never 7 rpm's
        c = {7: dict(committed(None, "a2"), earlier_states_sha256=["a"]), 14: committed("a", "b"), 21: committed("b", "c")}
        self.assertEqual(steady.plan([7, 14, 21], c, SETTINGS), [(7, True), (14, True), (21, True)])
        c[14] = committed("a0", "b")
        self.assertEqual(steady.plan([7, 14, 21], c, SETTINGS), [(7, True), (14, False), (21, False)])

    def test_a_first_speed_from_an_extended_state_of_another_study(self):
        c = {21: committed("old", "a")}
        self.assertEqual(steady.plan([21], c, SETTINGS, first_state={"new", "old"}), [(21, True)])
        self.assertEqual(steady.plan([21], c, SETTINGS, first_state={"new"}), [(21, False)])


class Verdict(unittest.TestCase):
    def test_done_capped_continue(self):
        self.assertEqual(steady.verdict({"done": 1.0}, 3.0, 30.0), "done")
        self.assertEqual(steady.verdict({"done": 0.0}, 3.0, 30.0), "continue")
        self.assertEqual(steady.verdict({"done": 0.0}, 30.0, 30.0), "capped")
        self.assertEqual(steady.verdict({"done": 1.0}, 30.0, 30.0), "done")


class NextLength(unittest.TestCase):
    # drum_metrics counts a batch as round(revolution / snapshot) snapshots: at 35 rpm (a
    # revolution 12/7 s) and snapshots every 0.05 s, 34; segments of 2 s
    SNAP = 0.05

    def row(self, settled, start, batches=0):
        return {"settled": 1.0 if settled else 0.0, "steady_from_s": start if settled else float("nan"),
                "batches": float(batches)}

    def snapshots_after(self, start, t_end, length):
        return round((t_end + length - start) / self.SNAP) + 1

    def test_unsettled_runs_whole_segments(self):
        self.assertEqual(steady.next_length(self.row(False, 0), 4.0, 35, 2.0, 5, self.SNAP), 2.0)

    def test_stops_where_the_fifth_batch_fits(self):
        # settled at 1.3 s, at 9.0 s: 155 snapshots, 4 batches of 34; the fifth needs 15 more
        length = steady.next_length(self.row(True, 1.3), 9.0, 35, 2.0, 5, self.SNAP)
        self.assertAlmostEqual(length, 15 * self.SNAP, places=9)
        self.assertEqual(self.snapshots_after(1.3, 9.0, length), 5 * 34)

    def test_then_one_batch_at_a_time(self):
        t_end = 1.3 + 5 * 34 * self.SNAP  # 171 snapshots: 5 batches
        length = steady.next_length(self.row(True, 1.3), t_end, 35, 2.0, 5, self.SNAP)
        self.assertEqual(self.snapshots_after(1.3, t_end, length), 6 * 34)

    def test_batches_as_drum_metrics_rounds_them(self):
        # 42 rpm: a revolution is 28.6 snapshots, counted as 29; 144 snapshots need one more
        # (by whole revolutions the fifth seemed to fit already)
        t_end = 0.5 + 143 * self.SNAP
        self.assertAlmostEqual(steady.next_length(self.row(True, 0.5), t_end, 42, 2.0, 5, self.SNAP), self.SNAP)

    def test_at_least_one_snapshot(self):
        for rpm in (14, 28, 42, 58, 63):
            for k in range(400):
                length = steady.next_length(self.row(True, 0.05), 0.05 + k * self.SNAP, rpm, 2.0, 5, self.SNAP)
                self.assertGreaterEqual(length, self.SNAP - 1e-12, (rpm, k))

    def test_never_longer_than_a_segment(self):
        # 7 rpm: a revolution is 8.6 s
        self.assertEqual(steady.next_length(self.row(True, 3.0), 20.0, 7, 2.0, 5, self.SNAP), 2.0)


class TimeLeft(unittest.TestCase):
    SNAP = NextLength.SNAP
    row = NextLength.row

    def test_unsettled(self):
        still = steady.still_needed(self.row(False, 0), 4.0, 35, 5, self.SNAP)
        self.assertTrue(math.isnan(still))
        self.assertEqual(steady.progress_note(still, [], 2e-5), "not settled yet")

    def test_seconds_to_the_minimum_of_batches(self):
        # settled at 1.3 s, at 9.0 s: 155 snapshots of the 5 * 34 needed
        still = steady.still_needed(self.row(True, 1.3), 9.0, 35, 5, self.SNAP)
        self.assertAlmostEqual(still, 15 * self.SNAP, places=9)
        # as far as next_length goes when a segment is long enough
        self.assertAlmostEqual(still, steady.next_length(self.row(True, 1.3), 9.0, 35, 2.0, 5, self.SNAP), places=9)
        self.assertEqual(steady.still_needed(self.row(True, 1.3), 1.3 + 5 * 34 * self.SNAP, 35, 5, self.SNAP), 0.0)
        self.assertIn("error targets decide", steady.progress_note(0.0, [], 2e-5))

    def test_wall_time_at_the_rate_so_far(self):
        # two segments of 100,000 steps at dt 5e-6 (0.5 s each) in 780 s: 26 min per simulated second
        loops = [{"steps": 100000, "loop_s": 780.0}, {"steps": 100000, "loop_s": 780.0}]
        note = steady.progress_note(3.0, loops, 5e-6)
        self.assertIn("at least 3 s simulated more", note)
        self.assertIn("about 78 min at this speed's 26.0 min per simulated second", note)


class Options(unittest.TestCase):
    def test_targets(self):
        self.assertEqual(steady.parse_targets(None), {"Hc": 3e-4, "angle": 0.3})
        self.assertEqual(steady.parse_targets(["Hh=0.001"]), {"Hh": 0.001})
        with self.assertRaisesRegex(chain.PlanError, "--target Hc: expected KEY=VALUE"):
            steady.parse_targets(["Hc"])
        with self.assertRaisesRegex(chain.PlanError, "must be > 0"):
            steady.parse_targets(["Hc=0"])

    def test_revolution_is_the_batch(self):
        self.assertAlmostEqual(steady.revolution(21), 60 / 21)



class Segment(unittest.TestCase):
    """A segment's log must hold one run of the steps asked for: its loop time, CPU and the
    simulated seconds go on record from it, beside the series its snapshots give."""

    def segment_with_log(self, text, seconds=2.0):
        with tempfile.TemporaryDirectory() as d:
            log = Path(d) / "seg.log"
            log.write_text(text)
            saved = steady.harness.drum
            steady.harness.drum = lambda path, np, **variables: steady.harness.Log(log)
            try:
                study = steady.Study(steady.arguments(["--name", "t", "--docs", d, "--var", "dt", "2e-5"]))
                study.work = Path(d)
                return study.segment(28, 3, Path(d) / "start.restart", seconds)
            finally:
                steady.harness.drum = saved

    LOOP = "Loop time of {t} on 2 procs for {n} steps with 65344 atoms\n"

    def test_one_run_of_the_asked_steps(self):
        log = self.segment_with_log(self.LOOP.format(t=1e-6, n=0) + self.LOOP.format(t=1000.0, n=100000))
        self.assertEqual(log.runs, [(100000, 1000.0)])

    def test_a_second_run_in_the_log_stops_the_driver(self):
        # what a drum.in rewritten during the run did: the run command read twice
        text = self.LOOP.format(t=1029.0, n=100000) + self.LOOP.format(t=1153.4, n=100000)
        with self.assertRaisesRegex(steady.harness.RunFailed, r"runs of \[100000, 100000\] steps, the segment asked for one of 100000"):
            self.segment_with_log(text)

    def test_steps_counted_as_liggghts_rounds_them(self):
        # 2.5 steps: drum.in's round() gives 3 (halves up), Python's round() would say 2
        log = self.segment_with_log(self.LOOP.format(t=0.1, n=3), seconds=5e-5)
        self.assertEqual(log.runs, [(3, 0.1)])

    def test_a_fresh_start_drops_the_histories_of_the_start_state_only(self):
        # --fresh-start: the first segment of the first speed (from --start-state) alone; later
        # segments and speeds continue restarts of the study's own models
        seen = []
        with tempfile.TemporaryDirectory() as d:
            log = Path(d) / "seg.log"
            log.write_text(self.LOOP.format(t=10.0, n=100000))
            saved = steady.harness.drum
            steady.harness.drum = lambda path, np, **variables: seen.append(variables) or steady.harness.Log(log)
            try:
                study = steady.Study(steady.arguments(["--name", "t", "--docs", d, "--var", "dt", "2e-5", "--speeds",
                                                       "21,28", "--fresh-start"]))
                study.work = Path(d)
                for rpm, k in ((21, 1), (21, 2), (28, 1)):
                    study.segment(rpm, k, Path(d) / "start.restart", 2.0)
            finally:
                steady.harness.drum = saved
        self.assertEqual([v.get("history") for v in seen], ["fresh", None, None])
        self.assertTrue(study.settings["fresh_start"])

    def test_a_short_run_stops_the_driver(self):
        with self.assertRaisesRegex(steady.harness.RunFailed, r"runs of \[50000\] steps"):
            self.segment_with_log(self.LOOP.format(t=500.0, n=50000))


class Restore(unittest.TestCase):
    def test_a_checkpoint_of_other_settings_is_not_used_and_says_so(self):
        # a step whose options were edited between two runs starts over: it must not do so silently
        import contextlib
        import io
        with tempfile.TemporaryDirectory() as d:
            study = steady.Study(steady.arguments(["--name", "t", "--docs", d, "--var", "dt", "2e-5"]))
            study.work = Path(d) / "post"
            part = study.partial(21)
            part.mkdir(parents=True)
            saved = {"settings": dict(study.settings, segment=99.0), "start_sha256": "abc", "segments": 4}
            steady.harness.write_json(part / "progress.json", saved)
            said = io.StringIO()
            with contextlib.redirect_stdout(said):
                self.assertIsNone(study.restore(21, Path(d) / "start", "abc", None))
            self.assertIn("21 rpm: the checkpoint in", said.getvalue())
            self.assertIn("not used", said.getvalue())


    def test_a_checkpoint_whose_stop_rule_changed_is_resumed_under_the_new_rule(self):
        # targets, cap and rule decide only where a speed stops: its simulated seconds are kept
        import contextlib
        import io
        with tempfile.TemporaryDirectory() as d:
            study = steady.Study(steady.arguments(["--name", "t", "--docs", d, "--var", "dt", "2e-5", "--rule", "obm",
                                                   "--target", "Hc=5e-5", "--cap", "12"]))
            study.work = Path(d) / "post"
            study.work.mkdir()
            part = study.partial(21)
            part.mkdir(parents=True)
            old = dict(study.settings, targets={"Hc": 3e-4}, cap=20.0, min_batches=3)
            del old["rule"]
            steady.pack(Path(__file__), part / "state_seg4.restart.gz")
            (part / "metrics_cache.csv").write_text("step,time_s\n10,0.0002\n")
            saved = {"settings": old, "start_sha256": "abc", "segments": 4, "simulated_s": 1.0, "last_step": 10,
                     "state": "state_seg4.restart.gz"}
            steady.harness.write_json(part / "progress.json", saved)
            with contextlib.redirect_stdout(io.StringIO()):
                done = study.restore(21, Path(d) / "start", "abc", None)
            self.assertEqual(done["segments"], 4)
            self.assertEqual(done["settings"], study.settings)


class VerdictUnderAChangedRule(unittest.TestCase):
    """A speed capped (or done) under one stop rule is decided again when the rule changed: a higher
    cap lets it go on; the same rule leaves the verdict standing."""

    class Ran(Exception):
        pass

    def run_with(self, cap):
        with tempfile.TemporaryDirectory() as d:
            old = steady.Study(steady.arguments(["--name", "t", "--docs", d, "--var", "dt", "2e-5", "--cap", "20"]))
            study = steady.Study(steady.arguments(["--name", "t", "--docs", d, "--var", "dt", "2e-5", "--cap", str(cap)]))
            study.work = Path(d) / "post"
            study.work.mkdir()
            start = Path(d) / "start.restart"
            steady.harness.write_json(study.work / "21rpm_progress.json", {
                "settings": old.settings, "start": str(start), "start_sha256": "abc", "segments": 10,
                "simulated_s": 20.0, "cpu_s": 1.0, "beads": 1, "last_step": -1, "state": str(start),
                "outcome": "capped"})
            study.check = lambda rpm: {"done": 0.0, "settled": 1.0, "steady_from_s": 1.0}

            def segment(*args):
                raise self.Ran()
            study.segment = segment
            try:
                outcome, _, _ = study.run_speed(21, start, "abc")
                return outcome
            except self.Ran:
                return "ran another segment"

    def test_a_higher_cap_goes_on(self):
        self.assertEqual(self.run_with(60), "ran another segment")

    def test_the_same_rule_leaves_it_standing(self):
        self.assertEqual(self.run_with(20), "capped")


class ObmRule(unittest.TestCase):
    IV = steady.estimator.Interval

    def test_done_only_where_every_half_width_meets_its_target_at_ten_dof(self):
        targets = {"Hc": 5e-5, "angle": 0.05}
        ok = {"Hc": self.IV(-0.097, 4e-5, 12.0, 1.0, 2e-5), "angle": self.IV(34.5, 0.04, 10.5, 1.0, 0.02)}
        self.assertEqual(steady.obm_verdict(ok, targets, 3.0, 20.0), "done")
        wide = dict(ok, angle=self.IV(34.5, 0.06, 30.0, 1.0, 0.03))
        self.assertEqual(steady.obm_verdict(wide, targets, 3.0, 20.0), "continue")
        few = dict(ok, Hc=self.IV(-0.097, 1e-5, 9.9, 1.0, 4e-6))  # narrow, but at 9.9 dof
        self.assertEqual(steady.obm_verdict(few, targets, 3.0, 20.0), "continue")
        self.assertEqual(steady.obm_verdict(few, targets, 20.0, 20.0), "capped")
        self.assertEqual(steady.obm_verdict({}, targets, 3.0, 20.0), "continue")  # not settled
        nan = dict(ok, Hc=self.IV(-0.097, math.nan, math.nan, math.nan, math.nan))
        self.assertEqual(steady.obm_verdict(nan, targets, 3.0, 20.0), "continue")

    def test_intervals_over_the_steady_window_only(self):
        # an AR(1) series about -0.097 m after a start far from it: the window begins at the steady start
        rng = steady.estimator.np.random.default_rng(7)
        x, rows = 0.0, []
        for k in range(600):
            x = 0.8 * x + rng.normal(0.0, 1e-4)
            rows.append({"time_s": 0.05 * k, "Hc_m": (-0.05 if k < 100 else -0.097) + x})
        iv = steady.estimator.window_intervals(rows, 5.0, 0.05, {"Hc": "Hc_m"})["Hc"]
        self.assertLess(abs(iv.mean + 0.097), 3 * iv.se)
        self.assertGreaterEqual(iv.dof, 10)
        whole = steady.estimator.window_intervals(rows, 0.0, 0.05, {"Hc": "Hc_m"})["Hc"]
        self.assertGreater(abs(whole.mean - iv.mean), 0.005)  # the start, a sixth of the series, would shift it

    def test_a_finished_rows_columns(self):
        metrics = [{"key": "Hc", "column": "Hc_m", "se_column": "Hc_se_m", "unit": "m"},
                   {"key": "surface_velocity", "column": "surface_velocity_mps", "se_column": "surface_velocity_se_mps",
                    "unit": "m/s"}]
        rng = steady.estimator.np.random.default_rng(3)
        snaps = [{"time_s": 0.05 * k, "Hc_m": -0.097 + 1e-4 * rng.normal(), "surface_velocity_mps": 1.15 + 0.01 * rng.normal()}
                 for k in range(400)]
        row = steady.obm_columns({"batches": 5.0, "Hc_m": -0.5, "Hc_se_m": 1.0}, snaps, 2.0, 0.05, metrics)
        self.assertTrue(math.isnan(row["batches"]))
        self.assertAlmostEqual(row["Hc_m"], sum(r["Hc_m"] for r in snaps[40:]) / 360, places=12)
        self.assertIn("surface_velocity_hw95_mps", row)  # as the value's column spells the unit
        self.assertGreaterEqual(row["Hc_dof"], 10)
        # capped before it settled: no steady window, the batch means stay
        kept = steady.obm_columns({"batches": 5.0, "Hc_m": -0.5, "Hc_se_m": 1.0}, snaps, math.nan, 0.05, metrics)
        self.assertEqual((kept["batches"], kept["Hc_m"]), (5.0, -0.5))

    def test_all_dof_holds_every_metric_to_ten_dof(self):
        # --all-dof: a metric without a target (the bed's turn) still needs its 10 dof
        targets = {"Hc": 5e-5}
        hc = self.IV(-0.097, 4e-5, 12.0, 1.0, 1.8e-5)
        self.assertEqual(steady.obm_verdict({"Hc": hc, "bed_turn": self.IV(0.9, 0.3, 1.4, 4.1, 0.2)}, targets, 8.5, 40.0),
                         "continue")
        self.assertEqual(steady.obm_verdict({"Hc": hc, "bed_turn": self.IV(0.9, 0.3, 10.2, 4.1, 0.1)}, targets, 8.5, 40.0),
                         "done")
        # time still needed: its batch length times 1 + 10 / 1.5 (obm_dof's 1.5 (n/b - 1) = 10), less the window
        left = steady.obm_still_needed({"Hc": hc, "bed_turn": self.IV(0.9, 0.3, 1.4, 4.1, 0.2)}, targets, 8.5)
        self.assertAlmostEqual(left, 4.1 * (1 + 10 / 1.5) - 8.5)
        self.assertEqual(steady.obm_still_needed({"Hc": hc}, targets, 8.5), 0.0)
        with self.assertRaises(SystemExit):  # the revolutions rule has no degrees of freedom to hold
            steady.arguments(["--all-dof"])
        self.assertEqual(steady.Study(steady.arguments(["--rule", "obm", "--all-dof"])).settings["all_dof"], True)
        self.assertNotIn("all_dof", steady.Study(steady.arguments(["--rule", "obm"])).settings)

    T10 = float(steady.estimator.stats.t.ppf(0.975, 10))

    def test_the_target_bounds_the_standard_error_at_any_dof(self):
        # a half-width of 0.0535 at 40 dof hides a larger standard error than at 10: not done
        targets = {"Hc": 0.0535}
        t40 = float(steady.estimator.stats.t.ppf(0.975, 40))
        self.assertEqual(steady.obm_verdict({"Hc": self.IV(0, 0.0535, 40, 1, 0.0535 / t40)}, targets, 3.0, 20.0),
                         "continue")
        self.assertEqual(steady.obm_verdict({"Hc": self.IV(0, 0.05, 40, 1, 0.0535 / self.T10)}, targets, 3.0, 20.0),
                         "done")

    def test_time_still_needed_from_the_square_root_law(self):
        targets = {"Hc": 5e-5}
        # twice the target after 2 s averaged: 4 times as long, 6 s more
        self.assertAlmostEqual(steady.obm_still_needed({"Hc": self.IV(0, 1e-4, 10, 1, 1e-4 / self.T10)}, targets, 2.0),
                               6.0)
        self.assertEqual(steady.obm_still_needed({"Hc": self.IV(0, 4e-5, 10, 1, 4e-5 / self.T10)}, targets, 2.0), 0.0)
        self.assertTrue(math.isnan(steady.obm_still_needed({}, targets, 2.0)))
        nan = self.IV(0, math.nan, math.nan, math.nan, math.nan)
        self.assertTrue(math.isnan(steady.obm_still_needed({"Hc": self.IV(0, 1e-4, 12, 1, 4e-5), "angle": nan},
                                                           {"Hc": 5e-5, "angle": 0.05}, 2.0)))

    def test_the_rule_is_a_setting_only_where_it_is_not_the_default(self):
        plain = steady.settings_of(steady.arguments(["--var", "dt", "2e-5"]))
        self.assertNotIn("rule", plain)  # studies committed before the option stay comparable
        obm = steady.settings_of(steady.arguments(["--var", "dt", "2e-5", "--rule", "obm"]))
        self.assertEqual(obm["rule"], "obm")
        self.assertEqual(steady.trajectory(plain), steady.trajectory(obm))


class Extend(unittest.TestCase):
    def test_a_state_that_is_not_its_records_is_not_extended(self):
        # an interrupted write left a state other than the one run.json records: refused, not spliced
        with tempfile.TemporaryDirectory() as d:
            study = steady.Study(steady.arguments(["--name", "t", "--docs", d, "--var", "dt", "2e-5", "--extend"]))
            study.work = Path(d) / "post"
            out = Path(d) / "t" / "21rpm"
            out.mkdir(parents=True)
            (out / "state.restart.gz").write_bytes(b"another state")
            with self.assertRaisesRegex(chain.PlanError, "not the end state its run.json records"):
                study.from_committed(21, {"state_sha256": "abc", "segments": 2}, out / "state.restart.gz", "s")


class Pack(unittest.TestCase):
    def test_the_same_state_packs_to_the_same_bytes(self):
        # through differently named temporary files, seconds apart: git must see one object
        with tempfile.TemporaryDirectory() as d:
            d = Path(d)
            (d / "state").write_bytes(bytes(range(256)) * 1000)
            steady.pack(d / "state", d / "a.gz")
            steady.pack(d / "state", d / "sub_b.gz")
            self.assertEqual((d / "a.gz").read_bytes(), (d / "sub_b.gz").read_bytes())
            self.assertEqual(gzip.decompress((d / "a.gz").read_bytes()), (d / "state").read_bytes())

    def test_a_committed_state_unpacks_where_post_does_not_exist_yet(self):
        # a fresh clone resuming after a finished speed: post/<name> is made on the way
        with tempfile.TemporaryDirectory() as d:
            d = Path(d)
            (d / "docs" / "7rpm").mkdir(parents=True)
            (d / "state").write_bytes(b"restart bytes" * 100)
            steady.pack(d / "state", d / "docs" / "7rpm" / "state.restart.gz")
            study = object.__new__(steady.Study)
            study.work, study.docs = d / "post" / "study", d / "docs"
            self.assertEqual(study.state(7).read_bytes(), (d / "state").read_bytes())


if __name__ == "__main__":
    unittest.main()
