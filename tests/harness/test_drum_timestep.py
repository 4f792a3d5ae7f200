"""benchmarks/drum_timestep.py on a synthetic ladder: two runs in progress of known means (the
reference and one whose Hc sits 0.2 mm higher), read from checkpoints as campaign.sh commits
them. The difference must be found where it is and not where it is not, and the power stated
must be the noncentral t's at the measured noise. Runs drum_metrics (DRUM_METRICS from the
environment, as CTest sets it)."""

import math
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "benchmarks"))
sys.path.insert(0, str(REPO / "tools"))
sys.path.insert(0, str(REPO / "tools" / "drum"))
import drum_timestep  # noqa: E402
import estimator  # noqa: E402
import harness  # noqa: E402

COLUMNS = ["Hh_m", "Hd_m", "Hc_m", "drum_force_N", "angle_deg", "layer_thickness_m", "surface_velocity_mps",
           "bed_turn_1", "wall_slip_1", "wall_roll_1"]
MEANS = {"Hh_m": 0.087, "Hd_m": 0.066, "Hc_m": -0.0969, "drum_force_N": 0.0051, "angle_deg": 34.5,
         "layer_thickness_m": 0.0677, "surface_velocity_mps": 1.156, "bed_turn_1": 0.9976, "wall_slip_1": 0.0023,
         "wall_roll_1": 0.0305}


def checkpoint(folder, dt, seconds, seed, shift):
    """A steady series of AR(1) noise (phi 0.8 per 0.05 s snapshot, innovations 0.1 % of the mean: Hc
    about 0.03 mm over 30 s at 95 %) about MEANS + shift, as a
    checkpoint in progress: partial/metrics_cache.csv and partial/progress.json."""
    rng = np.random.default_rng(seed)
    n = round(seconds / drum_timestep.SNAPSHOT)
    part = folder / "partial"
    part.mkdir(parents=True)
    noise = {c: 0.0 for c in COLUMNS}
    rows = []
    for k in range(n):
        step = round(k * drum_timestep.SNAPSHOT / dt)
        row = {"step": step, "time_s": step * dt, "beads": 65344, "wall_contacts": 1080}
        for c in COLUMNS:
            noise[c] = 0.8 * noise[c] + rng.normal(0.0, 1e-3 * abs(MEANS[c]))
            row[c] = MEANS[c] + shift.get(c, 0.0) + noise[c]
        rows.append(row)
    header = ["step", "time_s", "beads", "wall_contacts"] + COLUMNS
    (part / "metrics_cache.csv").write_text(  # as drum_metrics writes it (plain newlines)
        ",".join(header) + "\n" + "".join(",".join(f"{r[c]!r}" for c in header) + "\n" for r in rows))
    steps = round(seconds / dt)
    harness.write_json(part / "progress.json", {"settings": {"variables": {"dt": repr(dt)}}, "segments": 2,
                                                "loops": [{"steps": steps // 2, "loop_s": 900.0},
                                                          {"steps": steps // 2, "loop_s": 600.0}]})


class Ladder(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        docs = Path(cls.tmp.name) / "docs"
        checkpoint(docs / "dt_tc81" / "21rpm", 1.23e-6, 30.0, 1, {})
        checkpoint(docs / "dt_tc20" / "21rpm", 5e-6, 30.0, 2, {"Hc_m": 2e-4})
        out = Path(cls.tmp.name) / "out"
        out.mkdir()
        # --cost's interleaved measurement of tc/20 (not of tc/81): it replaces that run's own rate
        harness.write_csv(out / "drum_timestep_cost.csv", [{"law": "plain", "tc_over_dt": 20, "wall_s_per_simulated_s": 1600.0}])
        drum_timestep.main(["--docs", str(docs), "--out", str(out)])
        cls.rows = harness.read_csv(out / "drum_timestep.csv")
        cls.out = out

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def row(self, ratio, metric):
        return next(r for r in self.rows if r["tc_over_dt"] == ratio and r["metric"] == metric)

    def test_the_offset_is_found_and_measured(self):
        r = self.row(20, "Hc_m")
        self.assertEqual(r["agree"], "False")
        self.assertLess(abs(r["difference"] - 2e-4), r["difference_hw95"])

    def test_no_offset_no_difference(self):
        agree = [r["agree"] == "True" for r in self.rows if r["tc_over_dt"] == 20 and r["metric"] != "Hc_m"]
        self.assertGreaterEqual(sum(agree), len(agree) - 1)  # 9 metrics at 95 %: one false alarm at most

    def test_power_is_the_noncentral_t_at_the_measured_noise(self):
        r = self.row(20, "angle_deg")
        se = r["difference_hw95"] / float(estimator.stats.t.ppf(0.975, r["difference_dof"]))
        self.assertAlmostEqual(r["power"], estimator.power(0.1, se, r["difference_dof"]), places=6)
        self.assertEqual(self.row(20, "bed_turn_1")["power"], "")  # no stated difference for a ratio

    def test_the_reference_has_no_difference_and_the_cost_is_the_fastest_segment(self):
        r = self.row(81.3, "Hc_m")
        self.assertEqual(r["difference"], "")
        self.assertAlmostEqual(r["wall_s_per_simulated_s"], 600.0 / (round(30.0 / 1.23e-6) // 2 * 1.23e-6), places=3)

    def test_a_measured_cost_replaces_the_runs_own(self):
        self.assertEqual((self.row(20, "Hc_m")["wall_s_per_simulated_s"], self.row(20, "Hc_m")["cost_from"]),
                         (1600.0, "interleaved"))
        self.assertEqual(self.row(81.3, "Hc_m")["cost_from"], "segments")

    def test_the_chart_is_drawn(self):
        self.assertTrue((self.out / "drum_timestep_21rpm.png").stat().st_size > 10000)


if __name__ == "__main__":
    unittest.main()
