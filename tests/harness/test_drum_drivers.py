"""The drum study drivers' own logic (tools/drum/chain.py, study.py, collect.py): the speed
chain's plan, what a resumed study redoes, the ramp's speed bands, option errors, and the
table formatting of collect.py. No LIGGGHTS runs, no drum_metrics."""

import contextlib
import io
import sys
import unittest
from pathlib import Path

TOOLS = Path(__file__).resolve().parents[2] / "tools"
sys.path.insert(0, str(TOOLS))
sys.path.insert(0, str(TOOLS / "drum"))
import chain  # noqa: E402
import collect  # noqa: E402
import study  # noqa: E402

NAN = float("nan")


def sweep(**kw):
    args = dict(study="s", speeds=[7, 14, 21], time=1.2, settle=0.8, period="0.006")
    args.update(kw)
    return chain.plan(**args)


class Options(unittest.TestCase):
    def test_speeds(self):
        self.assertEqual(chain.parse_speeds("7,14,21"), [7, 14, 21])
        with self.assertRaisesRegex(chain.PlanError, r"^--speeds 7,x: expected integer"):
            chain.parse_speeds("7,x")
        with self.assertRaisesRegex(chain.PlanError, r"^--speeds 21,14: .*ascending"):
            chain.parse_speeds("21,14")

    def test_ramp(self):
        self.assertEqual(chain.parse_ramp("21:28:3", [7, 21]), (21, 28, 3.0))
        for bad in ("21:28", "21:28:x", "21.5:28:3", "21:28:3:4"):
            with self.assertRaisesRegex(chain.PlanError, rf"^--ramp {bad}: expected FROM:TO:SECONDS"):
                chain.parse_ramp(bad, [21])
        with self.assertRaisesRegex(chain.PlanError, r"^--ramp 14:28:3: FROM 14 rpm is not in --speeds 7,21"):
            chain.parse_ramp("14:28:3", [7, 21])
        with self.assertRaisesRegex(chain.PlanError, r"^--ramp 21:21:3"):
            chain.parse_ramp("21:21:3", [21])

    def test_window_and_yade(self):
        self.assertEqual(chain.parse_window("0.3:0.6"), (0.3, 0.6))
        with self.assertRaisesRegex(chain.PlanError, r"^--window 0.6:0.3"):
            chain.parse_window("0.6:0.3")
        with self.assertRaisesRegex(chain.PlanError, r"^--yade 7: the slowest speed"):
            chain.parse_yade(7, [7, 14], 1.2, (0.3, 0.6))
        with self.assertRaisesRegex(chain.PlanError, r"^--yade 28: not in --speeds"):
            chain.parse_yade(28, [7, 14], 1.2, (0.3, 0.6))
        with self.assertRaisesRegex(chain.PlanError, r"^--yade 14: --window ends 0.6 s .*--time 0.4"):
            chain.parse_yade(14, [7, 14], 0.4, (0.3, 0.6))

    def test_vars(self):
        self.assertEqual(chain.parse_vars([["dt", "2e-5"], ["fill", "0.05"]]), {"dt": "2e-5", "fill": "0.05"})
        with self.assertRaisesRegex(chain.PlanError, r"^--var restart x: `restart` is set by the driver"):
            chain.parse_vars([["restart", "x"]])

    def test_study_command_line_names_the_bad_option(self):
        for argv, message in ((["--ramp", "21:28"], "--ramp 21:28: expected FROM:TO:SECONDS"),
                              (["--var", "time", "3"], "--var time 3: `time` is set by the driver"),
                              (["--speeds", "21", "--yade", "21"], "--yade 21: the slowest speed")):
            err = io.StringIO()
            with contextlib.redirect_stderr(err), self.assertRaises(SystemExit):
                study.arguments(argv)
            self.assertIn(message, err.getvalue())
        args = study.arguments(["--speeds", "21,28", "--ramp", "21:28:0.02", "--var", "fill", "0.05"])
        self.assertEqual((args.speeds, args.ramp, args.variables), ([21, 28], (21, 28, 0.02), {"fill": "0.05"}))


class Plan(unittest.TestCase):
    def test_chain(self):
        runs, series = sweep(variables={"dt": "2e-5"})
        self.assertEqual([r.name for r in runs], ["s_7rpm", "s_14rpm", "s_21rpm"])
        first, second, third = runs
        self.assertEqual((first.variables["start"], first.variables["time"], first.start_from), ("grid", "2", None))
        self.assertNotIn("restart", first.variables)
        self.assertEqual((second.variables["start"], second.variables["restart"], second.variables["time"]),
                         ("restart", "post/s/s_7rpm.restart", "1.2"))
        self.assertEqual(third.start_from, "s_14rpm")
        self.assertEqual([r.t0 for r in runs], [0.0, 2.0, 3.2])
        self.assertTrue(all(r.variables["dt"] == "2e-5" and r.variables["name"] == f"s/{r.name}" for r in runs))
        self.assertEqual([(s.out, s.reads, s.skip) for s in series],
                         [("s_7rpm", "s_7rpm", None), ("s_14rpm", "s_14rpm", None), ("s_21rpm", "s_21rpm", None)])

    def test_yade_window_is_the_docs_one(self):
        # docs/drum/README.md: from the 14 rpm state, window 3.5-3.8 s (0.3-0.6 s after the change)
        runs, series = sweep(yade=21, window=(0.3, 0.6))
        yade = runs[-1]
        self.assertEqual((yade.name, yade.kind, yade.start_from), ("s_yade_21rpm", "yade", "s_14rpm"))
        self.assertEqual((yade.variables["conventions"], yade.variables["time"], yade.variables["restart"]),
                         ("yade", "0.6", "post/s/s_14rpm.restart"))
        windows = {s.out: (s.reads, s.skip, s.until, s.average) for s in series if s.skip is not None}
        self.assertEqual(windows, {"yade_21rpm_window": ("s_yade_21rpm", 3.5, 3.8, "all"),
                                   "thesis_21rpm_window": ("s_21rpm", 3.5, 3.8, "all")})
        with self.assertRaisesRegex(chain.PlanError, r"^--yade 21: .*--var conventions yade"):
            sweep(yade=21, variables={"conventions": "yade"})

    def test_ramp(self):
        runs, series = sweep(ramp=(14, 28, 3.0), variables={"wall": "moving"})
        ramp = runs[-1]
        self.assertEqual((ramp.name, ramp.start_from, ramp.rpm, ramp.t0), ("s_ramp_14_28", "s_14rpm", 14, 3.2))
        self.assertEqual({k: ramp.variables[k] for k in ("wall", "rpm", "rpm_end", "time", "restart")},
                         {"wall": "ramp", "rpm": "14", "rpm_end": "28", "time": "3",
                          "restart": "post/s/s_14rpm.restart"})
        self.assertEqual(series[-1].reads, "s_ramp_14_28")


class Resume(unittest.TestCase):
    def setUp(self):
        self.runs, self.series = sweep(yade=21)
        self.records = {r.name: dict(r.variables) for r in self.runs}
        # when each file was written: the runs in order, then their metrics
        self.files = {r.name + x: i for i, r in enumerate(self.runs) for x in (".restart", ".json")}
        self.files.update({f: 10 for s in self.series for f in s.outputs})

    def decide(self, force=False):
        redo, todo = chain.decide(self.runs, self.series, self.records.get, self.files.get, force)
        return sorted(redo), sorted(s.out for s in todo)

    def test_all_done_is_skipped(self):
        self.assertEqual(self.decide(), ([], []))

    def test_nothing_done_runs_everything(self):
        self.records.clear()
        redo, todo = self.decide()
        self.assertEqual(len(redo), 4)
        self.assertEqual(len(todo), len(self.series))

    def test_a_missing_run_reruns_it_and_every_run_from_its_state(self):
        del self.records["s_14rpm"]
        redo, todo = self.decide()
        self.assertEqual(redo, ["s_14rpm", "s_21rpm", "s_yade_21rpm"])
        self.assertEqual(todo, ["s_14rpm", "s_21rpm", "thesis_21rpm_window", "yade_21rpm_window"])

    def test_a_record_without_restart_is_not_done(self):
        del self.files["s_21rpm.restart"]
        self.assertEqual(self.decide(), (["s_21rpm"], ["s_21rpm", "thesis_21rpm_window"]))

    def test_missing_metrics_only_redo_the_metrics(self):
        del self.files["s_7rpm_average.csv"]
        self.assertEqual(self.decide(), ([], ["s_7rpm"]))

    def test_a_run_redone_earlier_makes_the_runs_from_its_state_stale(self):
        # an earlier invocation (without --yade) redid 14 rpm: 21 rpm and the YADE run started
        # from the old state, and the metrics of 14 rpm predate its new run
        self.files["s_14rpm.json"] = self.files["s_14rpm.restart"] = 20
        redo, todo = self.decide()
        self.assertEqual(redo, ["s_21rpm", "s_yade_21rpm"])
        self.assertEqual(todo, ["s_14rpm", "s_21rpm", "thesis_21rpm_window", "yade_21rpm_window"])

    def test_force_redoes_everything(self):
        redo, todo = self.decide(force=True)
        self.assertEqual((len(redo), len(todo)), (4, len(self.series)))

    def test_other_settings_stop_the_study(self):
        self.records["s_14rpm"]["dt"] = "2e-5"
        with self.assertRaisesRegex(chain.PlanError, r"^s_14rpm exists with other settings \(dt\): --force"):
            self.decide()
        self.assertEqual(len(self.decide(force=True)[0]), 4)


class Bands(unittest.TestCase):
    def test_one_rpm_bands_with_bounds_between_snapshots(self):
        times = [0.0, 0.5, 1.0, 1.5, 2.0]
        rpms = [21.0, 21.5, 22.0, 22.5, 23.0]
        self.assertEqual(chain.bands(times, rpms, 21, 23),
                         [(21.0, 22.0, 0.0, 0.75, 2), (22.0, 23.0, 0.75, 3.0, 3)])

    def test_ramp_down_and_wider_bands(self):
        self.assertEqual([b[:2] + b[4:] for b in chain.bands([0, 1, 2, 3], [28, 26, 24.5, 21], 28, 21, width=2)],
                         [(27, 28, 1), (25, 27, 1), (23, 25, 1), (21, 23, 1)])


class Collect(unittest.TestCase):
    def test_value_with_error(self):
        self.assertEqual(collect.pm(-0.114812, 0.000153), "-0.11481 ± 0.00015")
        self.assertEqual(collect.pm(20.04, 0.21), "20.04 ± 0.21")
        self.assertEqual(collect.pm(123.4, 12.0), "123 ± 12")
        self.assertEqual(collect.pm(NAN, NAN), "–")
        self.assertEqual(collect.pm(0.0006261, NAN), "0.0006261")

    def test_steady(self):
        self.assertEqual(collect.steady(NAN), "not steady: last half")
        self.assertEqual(collect.steady(0.8), "0.8")

    def test_speed_tables(self):
        a = [{"rpm": 7.0, "x": "sweep"}, {"rpm": 42.0, "x": "sweep"}]
        b = [{"rpm": 42.0, "x": "high"}, {"rpm": 49.0, "x": "high"}]
        self.assertEqual([(r["rpm"], r["x"]) for r in collect.merge_speeds(a, b)],
                         [(7.0, "sweep"), (42.0, "sweep"), (49.0, "high")])
        self.assertEqual(collect.span(a), "7 to 42 rpm")
        self.assertEqual(collect.span(b[1:], "–"), "49 rpm")
        row = {"rpm": 21.0, "beads": 16336.0, "steady_from_s": NAN, "snapshots": 31.0, "Hc_m": -0.11481,
               "Hc_se_m": 0.00015}
        table = collect.speed_table([row]).splitlines()
        self.assertEqual(table[0], "| rpm | beads | steady from [s] | snapshots averaged | centre of mass Hc [m] |")
        self.assertEqual(table[2], "| 21 | 16336 | not steady: last half | 31 | -0.11481 ± 0.00015 |")

    def test_templates_have_a_note_first(self):
        for t in collect.TEMPLATES.glob("*.md.in"):
            self.assertTrue(t.read_text().startswith("${note}#"), t)


if __name__ == "__main__":
    unittest.main()
