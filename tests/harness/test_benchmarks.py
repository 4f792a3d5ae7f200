"""The benchmarks' own logic (benchmarks/*.py): how runs are classified and summarised, and the
README built from a results directory. No LIGGGHTS runs here."""

import math
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(ROOT / "benchmarks"))
import harness  # noqa: E402
import common  # noqa: E402
import accuracy  # noqa: E402
import cost  # noqa: E402
import full_scene  # noqa: E402
import multicontact  # noqa: E402
import peers  # noqa: E402
import reductions  # noqa: E402
import run as bench_run  # noqa: E402
import scaling  # noqa: E402
import stability  # noqa: E402
import walls  # noqa: E402
sys.path.insert(0, str(ROOT / "benchmarks" / "yade"))
import liggghts_round  # noqa: E402

NAN = float("nan")


def verdict_of(rounds, steps=5000):
    """full_scene's verdict on synthetic rounds: [[(variant, ranks, loop_s, beads), ...] per round]."""
    rows = [{"variant": name, "round": i + 1, "ranks": ranks, "loop_s": loop, "steps": steps, "beads": beads,
             "particle_steps_per_s": beads * steps / loop, "nlocal_max": 1, "nlocal_min": 1,
             "neighs_max": 1, "neighs_min": 1, "neighbor_builds": 1}
            for i, runs in enumerate(rounds) for name, ranks, loop, beads in runs]
    return full_scene.verdict(full_scene.summary(rows), rows)


class Stability(unittest.TestCase):
    def test_classify(self):
        self.assertEqual(stability.classify(False, 0, 2009, NAN, 1e-3), "stopped")
        self.assertEqual(stability.classify(True, 2008, 2009, 1e-7, 1e-3), "failed")   # a bead left the box
        self.assertEqual(stability.classify(True, 2009, 2009, 2e-3, 1e-3), "failed")   # energy above the limit
        self.assertEqual(stability.classify(True, 2009, 2009, 1e-7, 1e-3), "ok")
        self.assertEqual(stability.classify(True, 16336, 16336, 0.0079, math.inf), "ok")  # no reference energy

    def run_row(self, text, returncode, ke_limit, ke):
        with tempfile.TemporaryDirectory() as d:
            (Path(d) / "x.log").write_text(text)
            return stability.run_row(0.56, 0.3, "viscoelastic", harness.Log(Path(d) / "x.log", returncode), ke_limit, ke)

    def test_row_from_logs(self):
        row = self.run_row("column: 2009 beads, dt 3e-05 s\nERROR: viscoelastic: timestep 3e-05 s exceeds the stable "
                           "timestep 2.6e-05 s of type pair (1,1)\n", 1, 1e-3, NAN)
        self.assertEqual((row["status"], row["guard"], row["beads_kept"], row["beads"]), ("stopped", "error", 0, 2009))
        row = self.run_row("drum: 16336 beads (target 16336), period 0.006 m\ndrum: done, 16330 beads kept\n", 0, 1.0, 0.01)
        self.assertEqual((row["status"], row["guard"], row["beads_kept"], row["beads"]), ("failed", "none", 16330, 16336))

    def test_merge_replaces_reruns(self):
        old = [{"en": 0.3, "dt_over_tc": 0.1, "model": "hooke", "status": "ok"},
               {"en": "table", "dt_over_tc": 0.3, "model": "hooke", "status": "failed"}]
        new = [{"en": 0.3, "dt_over_tc": 0.1, "model": "hooke", "status": "failed"},
               {"en": 0.3, "dt_over_tc": 0.21, "model": "hooke", "status": "ok"}]
        merged = stability.merge(old, new)
        self.assertEqual(len(merged), 3)
        self.assertEqual([r["status"] for r in merged if r["dt_over_tc"] == 0.1], ["failed"])

    def test_summary(self):
        binary = [{"en": 0.56, "dt_over_tc": f, "restitution_mean": m} for f, m in ((0.4, 0.9), (0.5, 1.01))]
        column = [{"en": 0.56, "dt_over_tc": f, "model": model, "status": s, "guard": g, "load": 1}
                  for f, model, s, g in ((0.25, "hooke", "ok", "none"), (0.3, "hooke", "failed", "none"),
                                         (0.25, "viscoelastic", "ok", "none"), (0.3, "viscoelastic", "stopped", "error"))]
        drum = [{"en": "table", "dt_over_tc": 0.2, "model": "hooke", "status": "failed"}]
        limits = {0.56: {"binary_limit_tc": 0.5226, "guard_tc": 0.2613}, 0.46: {"binary_limit_tc": 0.4873, "guard_tc": 0.2436}}
        (row,) = stability.summary(binary, column, drum, limits, bead_en=0.56, drum_en=0.46)
        self.assertEqual((row["grow"], row["cfail"], row["dfail"], row["guard_column"]), (0.5, 0.3, 0.2, 0.3))
        self.assertEqual(row["guard"], "0.2613; drum 0.2436 (bead-drum en 0.46)")
        # the stiffening at which the Jury limit of the Pournin contact is the first failing dt/tc:
        # Z (w0^2 dt^2 + 4 beta dt) = 4, w0 tc = sqrt(pi^2 + ln^2 en), beta tc = -ln en
        L = -math.log(0.56)
        self.assertAlmostEqual(row["z"], 4 / ((math.pi ** 2 + L * L) * 0.3 ** 2 + 4 * L * 0.3), places=12)
        self.assertEqual(row["before"], "NO")  # the drum (Table 3.1 runs) failed at 0.2, below its guard 0.2436
        drum[0]["dt_over_tc"] = 0.3
        self.assertEqual(stability.summary(binary, column, drum, limits, 0.56, 0.46)[0]["before"], "yes")


class Summaries(unittest.TestCase):
    def test_time_to_rest(self):
        series = [{"time": t, "ke": k, "rke": 0.0, "zc": 0.05} for t, k in
                  ((0.1, 1e-2), (0.2, 1e-7), (0.3, 1e-3), (0.4, 1e-7), (0.5, 1e-8))]
        self.assertEqual(multicontact.summary(series), (1e-2, 0.4, 0.05))
        series[-1]["ke"] = 1.0  # never at rest: the last time
        self.assertEqual(multicontact.summary(series)[1], 0.5)

    def test_reduction_sigmas(self):
        full = {"period_m": 0.024, "Hc_m": -0.107, "Hc_se_m": 3e-4, "Hd_m": 0.0, "Hd_se_m": 4e-4, "angle_deg": 21.0,
                "angle_se_deg": 0.3, "cpu_s_per_simulated_s": 2700}
        near = dict(full, period_m=0.012, Hc_m=-0.1075, angle_deg=21.5, cpu_s_per_simulated_s=1350)
        self.assertAlmostEqual(reductions.sigmas(near, full)[0], -0.0005 / math.hypot(3e-4, 3e-4))
        self.assertIn("the 12 mm period** (0.50× its cost)", reductions.verdict([near, full], full))
        far = dict(near, Hc_m=-0.117)
        self.assertIn("No reduced period stays within 2 σ", reductions.verdict([far, full], full))

    def test_scaling_efficiency(self):
        rows = [{"ranks": n, "round": r, "loop_seconds": t, "steps": 300, "atoms": 1000, "nlocal_ave": 1000 / n,
                 "nlocal_max": 1000 / n, "nlocal_min": 1000 / n} for n, r, t in ((1, 1, 8.0), (2, 1, 5.0), (4, 1, 4.0))]
        table = scaling.per_ranks(rows, cores=2)
        self.assertEqual([r["efficiency"] for r in table], ["1.00", "0.80", "0.50 (oversubscribed)"])

    def test_two_runs_at_once(self):
        class Log:  # what full_scene reads of a LIGGGHTS log
            def __init__(self, loop):
                self.procs, self.loop_time, self.steps, self.atoms = 1, loop, 5000, 65344
                self.per_rank, self.neighbor_builds = {"Nlocal": (1, 1, 1)}, 3
        pair = full_scene.Together([Log(70.0), Log(80.0)])
        # the pair's work is both runs' particle-steps, done when the later one ends
        self.assertEqual((pair.procs, pair.loop_time, pair.atoms), (2, 80.0, 2 * 65344))
        self.assertAlmostEqual(pair.particle_steps_per_s, 2 * 65344 * 5000 / 80.0)

        def reading(fast, at_once):
            return verdict_of([[("fast", 2, a, 65344), ("2 at once", 2, b, 2 * 65344)] for a, b in zip(fast, at_once)])

        # throughput ratio per round: 2 t(fast) / t(2 at once)
        self.assertIn("ratio 1.250 (median over rounds; per round 1.14–1.33): two at once pay in every round",
                      reading([40, 40, 40], [64, 70, 60]))
        self.assertIn("per round 0.80–0.89): one after the other on 2 ranks pays", reading([40, 40, 40], [90, 100, 95]))
        self.assertIn("per round 0.80–1.14): the rounds disagree", reading([40, 40, 40], [70, 100, 80]))
        # the pair never counts as the fastest two-rank variant
        self.assertIn("Fastest of ours by median rate: fast,", reading([40, 40, 40], [64, 70, 60]))

    def test_sign_test(self):
        def rows(pairs):
            return [{"variant": v, "loop_s": t} for pair in pairs for v, t in zip(("fast", "fast 0.1"), pair)]
        # 8 rounds of 9 faster: P(8 or more either way of 9 fair coins) = 2 * 10 / 512
        text = full_scene.sign_test(rows([(30, 27), (36, 32), (29, 26), (35, 28), (31, 29), (33, 27), (33, 22),
                                          (29, 33), (42, 29)]), "fast", "fast 0.1")
        self.assertIn(f"faster than `fast` in 8 of 9 rounds; a count this lopsided comes by chance with probability "
                      f"{2 * 10 / 512:.2g} (two-sided) if neither is faster: a gap.", text)
        # 5 of 6: 2 * 7 / 64 = 0.22, no gap established
        text = full_scene.sign_test(rows([(30, 27), (36, 32), (29, 26), (35, 28), (31, 29), (29, 33)]),
                                    "fast", "fast 0.1")
        self.assertIn(f"in 5 of 6 rounds; a count this lopsided comes by chance with probability {2 * 7 / 64:.2g}", text)
        self.assertIn("no gap established at this noise", text)
        # slower in most rounds: lopsided the other way counts alike
        self.assertIn("in 1 of 6 rounds", full_scene.sign_test(rows([(27, 30)] * 5 + [(30, 27)]), "fast", "fast 0.1"))

    def test_parallel_efficiency_per_round(self):
        def reading(two, one):
            return verdict_of([[("fast", 2, a, 65344), ("1 rank fast", 1, b, 65344)] for a, b in zip(two, one)])

        # t(1) / (2 t(2)) per round: 90/100 = 0.90, 80/100 = 0.80, 100/100 = 1.00
        self.assertIn("median 0.90 over 3 rounds, per round 0.80–1.00.", reading([50, 50, 50], [90, 80, 100]))
        self.assertIn("per round 0.80–0.90; every round below 0.95", reading([50, 50, 50], [90, 80, 85]))
        self.assertIn("per round 0.96–1.10; every round at 0.95 or above", reading([50, 50, 50], [96, 110, 100]))

    def test_resorting_read_per_round(self):
        def reading(fast, sort):
            return verdict_of([[("fast", 2, a, 65344), ("sort 25", 2, b, 65344)] for a, b in zip(fast, sort)], 2500)

        # speed-up per round t(fast) / t(sort 25): 1.25, 1.10, 1.20
        self.assertIn("t(fast) / t(sort 25) 1.200 (median over rounds; per round 1.10–1.25): faster in every round",
                      reading([25, 22, 24], [20, 20, 20]))
        self.assertIn("per round 0.80–0.91): slower in every round", reading([20, 20, 20], [25, 22, 24]))
        self.assertIn("per round 0.90–1.10): the rounds disagree", reading([18, 22, 20], [20, 20, 20]))

    def test_yade_rounds(self):
        out = "x\nyade: round 1, 32672 beads, 300 steps, 29.0 s, 3.38e+05 particle-steps/s, 0 outside the drum\n"
        self.assertEqual(peers.yade_rounds(out), [(1, 32672, 3.38e5, 0)])


class Helpers(unittest.TestCase):
    def test_last_thermo(self):
        with tempfile.TemporaryDirectory() as d:
            (Path(d) / "x.log").write_text("Step Time Atoms KinEng rke CPU\n 0 0 10 1.5 0 0\n 100 0.001 10 2.5 0 1\n"
                                           "Loop time of 1 on 1 procs for 100 steps with 10 atoms\n"
                                           "Step Time Atoms KinEng rke CPU\n 100 0.001 10 3.5 0 0\nERROR: lost atoms\n")
            self.assertEqual(harness.Log(Path(d) / "x.log").thermo()["KinEng"], 3.5)

    def test_formats(self):
        self.assertEqual((common.sci(1e-4), common.sci(1e-3), common.sci(2.5e-6)), ("1e-4", "1e-3", "2.5e-6"))
        self.assertEqual(common.fmt_list([0.3, 0.9], " and "), "0.3 and 0.9")
        self.assertEqual(common.command("x.py", restart="r", append=True, np=None), "benchmarks/x.py --restart r --append")


class Readme(unittest.TestCase):
    def test_from_a_partial_results_dir(self):
        with tempfile.TemporaryDirectory() as d:
            d = Path(d)
            harness.write_csv(d / "model_cost.csv", [{"run": 1, "viscoelastic_s": 9.0, "hooke_s": 10.0, "ratio": 0.9},
                                                     {"run": 2, "viscoelastic_s": 8.0, "hooke_s": 9.0, "ratio": 0.889}])
            harness.write_json(d / "model_cost.json", {"beads": 100, "steps": 50, "runs": 2, "ranks": 2, "date": "2026-01-01",
                                                       "check": "beads 100, max position difference 0 m", "restart": "x.restart"})
            page = bench_run.readme(common.Results(d, d), harness.generated_note("benchmarks/run.py --readme-only"))
        self.assertTrue(page.startswith("<!-- Generated by `benchmarks/run.py --readme-only`"))
        self.assertIn("**Median ratio ours / stock: 0.8944**", page)
        self.assertIn("Machine: not recorded.", page)
        for section in ("core", "peers", "yade_collide", "accuracy", "multicontact", "stability", "scaling", "reductions"):
            self.assertIn(f"Not run yet: `benchmarks/run.py {section}`.", page)
        self.assertIn("Drum wall: Not run yet: `benchmarks/run.py walls`.", page)


class Stop(Exception):
    """Raised by the recording drum.in run below: nothing after the first run is needed."""


class WhatTheyRun(unittest.TestCase):
    """The benchmarks measured on 2026-11-22 pass drum.in's defaults of that day (common.THEN), so a
    rerun repeats them whatever drum.in's defaults are now: a benchmark's drum.in runs are recorded
    instead of run, up to the one looked at."""

    def record(self, call, nth=1):
        seen = []

        def drum(log, np=2, check=True, **variables):
            seen.append(variables)
            if len(seen) == nth:
                raise Stop
            return None

        saved = harness.drum, common.stock_file, common.window_average, accuracy.two_body
        harness.drum = drum
        common.stock_file = lambda path, **kw: path
        common.window_average = lambda *a, **kw: {}  # reads a run's snapshots
        accuracy.two_body = lambda ratios, exact: {}  # a collide run, no drum
        try:
            with self.assertRaises(Stop):
                call()
        finally:
            harness.drum, common.stock_file, common.window_average, accuracy.two_body = saved
        return seen[-1]

    def assertThen(self, variables, **given):
        # every default of that day, unless the benchmark sets it itself (None: any value)
        for key, value in {**common.THEN, **given}.items():
            if value is not None:
                self.assertEqual(str(variables.get(key)), str(value), key)

    def test_the_defaults_of_that_day(self):
        now = {}
        for line in (ROOT / "inputs" / "drum.in").read_text().splitlines():
            words = line.split()
            if len(words) >= 4 and words[0] == "variable" and words[2] == "index":
                now[words[1]] = words[3]
        # every drum.in variable is pinned or set per run: a default added or changed later
        # cannot reach a rerun
        self.assertEqual(sorted(k for k in now if k not in common.THEN and k not in common.PER_RUN), [])
        # those that have changed since (so the pins are not idle)
        for key in ("wall", "skin", "period", "dt", "exact", "start", "dumpdt", "balance"):
            number = key in ("skin", "period", "dt", "dumpdt")
            self.assertNotEqual(float(now[key]) if number else now[key],
                                float(common.THEN[key]) if number else common.THEN[key], key)

    def test_each_benchmark(self):
        ns = lambda **kw: type("Args", (), {"np": 2, "rounds": 1, "restart": "R", **kw})()
        self.assertThen(self.record(cost.settle_slab), time=cost.SETTLE_TIME, dumpdt=cost.SETTLE_TIME)
        self.assertThen(self.record(lambda: cost.run(ns(check=10, steps=10))),
                        start="restart", dt=common.dt_of(cost.TIMESTEP_RATIO), dumpdt=None)
        acc = ns(ratios="10", exact_ratios="5", span=0.01, window=0.1, snapshot_dt=0.005)
        self.assertThen(self.record(lambda: accuracy.run(acc)), start="restart", dt=common.dt_of(10), dumpdt=1)
        # its windows: the nominal law at tc/10, then exactRestitution at tc/5
        self.assertThen(self.record(lambda: accuracy.run(acc), nth=2), start="restart", dt=common.dt_of(10),
                        dumpdt=0.005)
        self.assertThen(self.record(lambda: accuracy.run(acc), nth=3), start="restart", dt=common.dt_of(5),
                        dumpdt=0.005, exact="on")
        self.assertThen(self.record(lambda: walls.run(ns(period=0.006, time=0.2, snapshot_dt=0.02))),
                        start="restart", dt=common.dt_of(10), wall="surface")
        self.assertThen(self.record(lambda: scaling.run(ns(ranks="1,2", period=0.006, time=0.05))),
                        start="restart", dt=common.dt_of(10), dumpdt=1000)
        red = dict(periods="0.024", time=1.0, skip=0.5, span=0.003)
        self.assertThen(self.record(lambda: reductions.run(ns(cost_only=False, **red))),
                        period=0.024, dt=common.dt_of(10))
        self.assertThen(self.record(lambda: reductions.run(ns(cost_only=True, **red))),
                        period=0.024, dt=common.dt_of(10), start="restart", dumpdt=1)
        self.assertThen(self.record(lambda: liggghts_round.main("S", 0.01, 0.012, 1e-5, 2, "peers/x", 1)),
                        start="restart", period=0.012, dt=1e-5, wall="moving", conventions="yade", dumpdt=1)
        # stability's drum runs: the slab's period and the nominal law unless a law is named
        args = ns(drum_fractions="0.2", reference=0.2, drum_period=None, drum_runs="table:viscoelastic",
                  drum_time=0.03)
        self.assertThen(self.record(lambda: stability.drum(args)), start="restart", dt=None, dumpdt=1)
        args.drum_runs = "table:viscoelastic:exactRestitution"
        self.assertThen(self.record(lambda: stability.drum(args)), start="restart", dt=None, dumpdt=1,
                        exact="on", tangential="pournin")
        args.drum_runs, args.restart = "table:viscoelastic", "settled"
        self.assertThen(self.record(lambda: stability.drum(args)), start="settled", period=0.024, dt=None, dumpdt=1)

if __name__ == "__main__":
    unittest.main()
