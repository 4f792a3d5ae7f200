"""tools/drum/windows.py: runs side by side over windows of simulated time. Window means of
synthetic caches whose answers are known (a constant, a linear ramp: the mean over a window is
the ramp at the window's middle snapshot time)."""

import csv
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tools" / "drum"))
sys.path.insert(0, str(REPO / "tools"))
import harness  # noqa: E402
import windows  # noqa: E402


def cache(path, times, value_of, drop=()):
    """A drum_metrics cache: every metric column, each metric's value value_of(key, t)."""
    table = harness.drum_metric_table()
    columns = ["step", "time_s", "beads", "wall_contacts"] + [m["column"] for m in table if m["key"] not in drop]
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for k, t in enumerate(times):
            w.writerow([k * 2500, repr(t), 100, 10] + [repr(value_of(m["key"], t)) for m in table if m["key"] not in drop])


class Windows(unittest.TestCase):
    def test_windows_cover_the_series_and_drop_a_short_tail(self):
        rows = [{"time_s": 3.0 + 0.05 * k} for k in range(101)]  # 3.00 .. 8.00 s
        w = windows.windows(rows, 2.0)
        # 3.00 + 0.05 k drifts by rounding: 5.00 and 7.00 may come out a hair short of the boundary
        # (the last, [7, 8]: 21 snapshots spanning half a window, kept)
        self.assertEqual([(a, b, len(r)) for a, b, r in w], [(3.0, 5.0, 40), (5.0, 7.0, 40), (7.0, 9.0, 21)])
        # a tail under half a window is dropped: [7, 7.9] spans 0.9 s; a snapshot alone at 7.00
        self.assertEqual(len(windows.windows(rows[:99], 2.0)), 2)
        self.assertEqual([len(r) for _, _, r in windows.windows(rows[:81], 2.0)], [40, 40])
        self.assertEqual([len(r) for _, _, r in windows.windows(rows[:60] + [{"time_s": 6.0}], 2.0)], [40, 21])

    def test_cli_means_of_a_constant_and_a_ramp(self):
        with tempfile.TemporaryDirectory() as d:
            d = Path(d)
            times = [3.0 + 0.05 * k for k in range(121)]  # 3 .. 9 s
            cache(d / "a.csv", times, lambda key, t: 1.0)
            cache(d / "b.csv", times, lambda key, t: 0.3 - 0.02 * (t - 3.0))
            r = subprocess.run([sys.executable, str(REPO / "tools/drum/windows.py"), "--rpm", "21", "--out",
                                str(d / "o"), f"carried={d / 'a.csv'}", f"slipping={d / 'b.csv'}"],
                               capture_output=True, text=True, cwd=REPO)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            self.assertGreater((d / "o.png").stat().st_size, 10000)
            md = (d / "o.md").read_text()
            section = md.split("## bed turn")[1].split("\n## ")[0]
            rows = [line.split("|")[1:-1] for line in section.splitlines() if line.startswith("| carried")
                    or line.startswith("| slipping")]
            self.assertEqual(len(rows), 6)
            for run, a, b, n, mean in ([c.strip() for c in row] for row in rows):
                self.assertEqual(n, "40")
                # window [a, a + 2): 40 snapshots at a + 0.05 k, mean time a + 0.975
                expected = 1.0 if run == "carried" else 0.3 - 0.02 * (float(a) + 0.975 - 3.0)
                self.assertAlmostEqual(float(mean), expected, places=3, msg=(run, a))

    def test_cache_without_the_slip_metrics_is_refused(self):
        with tempfile.TemporaryDirectory() as d:
            d = Path(d)
            cache(d / "old.csv", [3.0, 3.05, 3.1], lambda key, t: 0.0, drop=("bed_turn", "wall_slip", "wall_roll"))
            r = subprocess.run([sys.executable, str(REPO / "tools/drum/windows.py"), "--rpm", "21", "--out",
                                str(d / "o"), f"old={d / 'old.csv'}"], capture_output=True, text=True, cwd=REPO)
            self.assertNotEqual(r.returncode, 0)
            self.assertIn("no column for bed_turn, wall_roll, wall_slip", r.stdout + r.stderr)


if __name__ == "__main__":
    unittest.main()
