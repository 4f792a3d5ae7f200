"""tools/drum/release.py on synthetic ramps: a bed that lets go 40 % into 27 rpm reads 27.4 on the
ramp clock, one carried to the end is a lower bound, and the interval across histories is
Student's."""

import math
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "drum"))
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import harness  # noqa: E402
import release  # noqa: E402


def ramp(docs, name, speeds, let_go=None, per=1.5, snap=0.05):
    """A ramp's series: each speed `per` seconds of snapshots, bed_turn 1 until `let_go` (rpm +
    fraction of its run), 0.5 after."""
    t = 10.0
    for rpm in speeds:
        rows = [{"time_s": t, "Hc_m": -0.097, "bed_turn_1": 1.0}]  # the state it starts from (left out)
        for k in range(1, round(per / snap) + 1):
            clock = rpm + k * snap / per
            turn = 0.5 if let_go is not None and clock > let_go else 1.0
            rows.append({"time_s": t + k * snap, "Hc_m": -0.097, "bed_turn_1": turn})
        t += per
        harness.write_csv(docs / name / f"{rpm}rpm" / "series_metrics.csv", rows)


class Release(unittest.TestCase):
    def test_ramp_clock_lower_bound_and_interval(self):
        with tempfile.TemporaryDirectory() as d:
            docs = Path(d)
            ramp(docs, "a", range(22, 31), let_go=27.4)
            ramp(docs, "b", range(22, 31), let_go=27.8)
            ramp(docs, "c", range(22, 26))
            rows = release.read(docs, [("a", 0.5, "t", "w", "h1", 1.5), ("b", 0.5, "t", "w", "h2", 1.5),
                                       ("c", 0.8, "t", "w", "h1", 1.5), ("missing", 0.8, "t", "w", "h2", 1.5)])
            self.assertEqual([r["study"] for r in rows], ["a", "b", "c"])
            # the first sample past 27.4, the 13th of 30 into 27 rpm, is the onset
            self.assertAlmostEqual(rows[0]["release_rpm"], 27 + 13 / 30, places=9)
            self.assertAlmostEqual(rows[1]["release_rpm"], 27 + 25 / 30, places=9)
            self.assertTrue(math.isnan(rows[2]["release_rpm"]))
            self.assertIn("carried to 25 rpm", rows[2]["detected"])
            mean, hw = release.interval([rows[0]["release_rpm"], rows[1]["release_rpm"]])
            self.assertAlmostEqual(mean, 27 + 19 / 30, places=9)
            # two histories 12/30 rpm apart: sd (12/30)/sqrt(2), t(0.975, 1) = 12.706
            self.assertAlmostEqual(hw, 12.706 * (12 / 30) / math.sqrt(2) / math.sqrt(2), places=3)
            release.chart(rows, docs / "release.png")
            self.assertGreater((docs / "release.png").stat().st_size, 10000)

    def test_the_scan_runs_on_12_mm_only_where_it_releases_with_24_mm(self):
        full = [{"study": "slip_thesis", "release_rpm": 31.5}, {"study": "slip_thesis_replica", "release_rpm": 31.7}]
        self.assertIsNone(release.scan_period(full))
        # the 24 mm histories' mean 31.6, 95 % half-width 12.706 x 0.1 = 1.27 rpm
        self.assertEqual(release.scan_period(full + [{"study": release.CHECK, "release_rpm": 32.5}])[0], 0.012)
        self.assertEqual(release.scan_period(full + [{"study": release.CHECK, "release_rpm": 33.0}])[0], 0.024)
        self.assertEqual(release.scan_period(full + [{"study": release.CHECK, "release_rpm": math.nan}])[0], 0.024)

    def test_the_holds_speeds_and_outcomes(self):
        rows = [{"study": "rel_mu95_a", "release_rpm": 31.53}, {"study": "rel_mu95_b", "release_rpm": 32.9},
                {"study": "rel_mu95_c", "release_rpm": 31.07}]
        # every history ran 30 rpm through carried (the earliest let go in 31); none reached 33 carried
        self.assertEqual(release.hold_speeds(rows, 0.95), (30, 33))
        self.assertIsNone(release.hold_speeds(rows[:2], 0.95))  # a history still to come
        self.assertIsNone(release.hold_speeds(rows[:2] + [{"study": "rel_mu95_c", "release_rpm": math.nan}], 0.95))
        self.assertIsNone(release.hold_speeds(rows, 0.5))
        with tempfile.TemporaryDirectory() as d:
            docs = Path(d)
            # held 30 rpm carried; 33 rpm lets go 40 % into its 4 s; a third speed that came in released
            ramp(docs, "hold", [30, 33, 34], let_go=33.4, per=4.0)
            series = release.slip.ramp_series(docs, "hold")
            self.assertEqual(release.hold_outcome(series, 30), "carried throughout")
            self.assertRegex(release.hold_outcome(series, 33), r"let go 1\.6\d s into the hold")
            self.assertIn("came in released", release.hold_outcome(series, 34))
            # the table: one row per held speed, with where it started
            ramp(docs, "rel_mu95_hold", [30, 33], let_go=33.4, per=4.0)
            harness.write_csv(docs / "rel_mu95_hold.csv", [
                {"rpm": rpm, "bed_turn_1": turn, "bed_turn_hw95_1": 0.01, "bed_turn_dof": 11.0}
                for rpm, turn in ((30, 0.99), (33, 0.6))])
            for rpm in (30, 33):
                harness.write_json(docs / "rel_mu95_hold" / f"{rpm}rpm" / "run.json", {"simulated_s": 4.0, "settings": {}})
            held = release.read_holds(docs, [("rel_mu95_hold", 0.95), ("rel_mu50_hold", 0.5)])
            self.assertEqual([(h["rpm"], h["outcome"][:7]) for h in held], [(30, "carried"), (33, "let go ")])
            self.assertIn("rel_mu95_a's 30 rpm", held[0]["start"])
            self.assertIn("hold's 30 rpm", held[1]["start"])
            # a bed that slips for a while and is carried again
            ramp(docs, "flicker", [30], per=4.0)
            rows = harness.read_csv(docs / "flicker" / "30rpm" / "series_metrics.csv")
            for r in rows[20:40]:
                r["bed_turn_1"] = 0.5
            harness.write_csv(docs / "flicker" / "30rpm" / "series_metrics.csv", rows)
            self.assertIn("on and off", release.hold_outcome(release.slip.ramp_series(docs, "flicker"), 30))

    def test_the_answer_page(self):
        def row(study, mu, conventions="thesis", wall="cylinder", release=30.0):
            return {"study": study, "mu": mu, "conventions": conventions, "wall": wall, "seconds_per_rpm": 1.76,
                    "release_rpm": release, "detected": "carried to 31 rpm (the ramp's end): releases above it"}
        # releases 25 + 10 mu with a spread of +-0.2 across the three histories
        rows = [row(f"rel_mu{round(100 * mu)}_{h}", mu, release=25 + 10 * mu + dx)
                for mu in release.SCAN_MUS for h, dx in zip("abc", (-0.2, 0.0, 0.2))]
        k, hw, n = release.slope(release.scan_points(rows))
        self.assertAlmostEqual(k, 10.0, places=9)
        self.assertEqual(n, 12)
        # one convention far outside the spread at mu 0.5 (30 +- 0.2), one inside, one never released
        rows += [row("rel_mu50_half_a", 0.5, "thesis, facet meff m/2", release=27.0),
                 row("rel_mu50_cut_a", 0.5, "thesis, no attraction", release=30.1),
                 row("rel_mu50_en51_a", 0.5, "thesis, bead-drum en 0.51", release=math.nan)]
        rows += [row(f"rel_mu50_surface_{h}", 0.5, wall="surface mesh", release=29.0 + dx)
                 for h, dx in zip("abc", (-0.2, 0.0, 0.2))]
        text = " ".join(release.page(rows).split())
        self.assertIn("the bead-drum friction moves the release: +1.00 ± ", text)
        self.assertIn("from 30.0 ± 0.5 rpm at mu 0.5 to 34.5 ± 0.5 at 0.95", text)
        # the prediction interval for one more history: t(2) 0.2 sqrt(1 + 1/3) = 0.99
        self.assertIn("no attraction: 30.10 rpm, +0.10 from the scan's mean, within its ± 0.99", text)
        self.assertIn("bead-drum en 0.51: never let go on its ramp, so above 32 rpm, outside the scan's 30.00 ± 0.99", text)
        self.assertIn("bead-drum en 0.51 and facet meff m/2 move the release beyond the spread of three histories", text)
        self.assertIn("at mu 0.5 -1.00 ± 0.", text.replace("−", "-"))
        self.assertIn("Still to run: 5 ramps", text)  # pournin, the mu 0.95 surface ramps and the 12 mm check
        # nothing run yet: says so instead of an answer
        self.assertIn("has not run far enough", release.page([]))
        # Welch: equal spreads, 3 a side: t at 4 dof times sqrt(2 var / 3)
        d, hw = release.welch([1.0, 2.0, 3.0], [2.0, 3.0, 4.0])
        self.assertAlmostEqual(d, -1.0)
        self.assertAlmostEqual(hw, float(release.stats.t.ppf(0.975, 4)) * math.sqrt(2 / 3), places=9)

    def test_the_rigid_bed_estimate(self):
        # the segment's area and centroid against a numerical integration over the drum's section
        eps, s = release.segment(0.40)
        self.assertAlmostEqual((2 * eps - math.sin(2 * eps)) / (2 * math.pi), 0.40, places=9)
        n, area, moment = 4000, 0.0, 0.0
        for i in range(n):  # strips across the segment below the chord at depth cos(eps) (R = 1)
            z = -1.0 + (1.0 - math.cos(eps)) * (i + 0.5) / n
            width = 2.0 * math.sqrt(1.0 - z * z)
            area += width * (1.0 - math.cos(eps)) / n
            moment += z * width * (1.0 - math.cos(eps)) / n
        self.assertAlmostEqual(area / math.pi, 0.40, places=5)
        self.assertAlmostEqual(-moment / area, s, places=5)
        # half full: eps = pi/2, s = 4/(3 pi), eps / sin(eps) = pi/2; at 30 deg and no rotation
        # mu = s sin 30 / ((pi/2) cos 30) = 0.156
        self.assertAlmostEqual(release.friction_needed(30.0, 0.0, fill=0.5),
                               4 / (3 * math.pi) * 0.5 / (math.pi / 2 * math.cos(math.radians(30))), places=9)
        self.assertEqual(release.friction_needed(0.0, 21.0), 0.0)
        # all wall force radial: the radial sum is exactly the load's radial part (spread 1)
        self.assertAlmostEqual(release.friction_needed(30.0, 0.0, fill=0.5, spread=1.0),
                               4 / (3 * math.pi) * math.tan(math.radians(30)), places=9)
        # the least friction any wall-force spread needs: none for an untilted bed, more with the tilt,
        # below the uniform and radial figures, and converged in the arc's discretisation
        self.assertLess(release.friction_bound(0.0, 21.0, points=60), 1e-6)
        b30, b40 = release.friction_bound(30.0, 21.0, points=90), release.friction_bound(40.0, 21.0, points=90)
        self.assertLess(b30, b40)
        self.assertLess(b40, release.friction_needed(40.0, 21.0))
        self.assertAlmostEqual(release.friction_bound(40.0, 21.0, points=180), b40, delta=0.03 * b40)
        # the drum's rotation presses the bed on the wall: less friction needed at the same angle
        self.assertLess(release.friction_needed(35.0, 60.0), release.friction_needed(35.0, 20.0))


if __name__ == "__main__":
    unittest.main()
