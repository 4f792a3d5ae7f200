"""The shared harness: materials file, logs, rounds, tables (no LIGGGHTS runs here;
the materials file is also checked against LIGGGHTS' own reading in test_materials_e2e)."""

import math
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import harness  # noqa: E402

# The timing summary LAMMPS/LIGGGHTS prints after a run (format of LIGGGHTS 3.8's finish.cpp).
LOG = """Setting up run ...
Loop time of 1e-06 on 2 procs for 0 steps with 10 atoms
Loop time of 1.5 on 2 procs for 100 steps with 10 atoms

Nlocal:    5 ave 6 max 4 min
Loop time of 2.5 on 2 procs for 200 steps with 4156 atoms, finish time Mon Nov 23 20:08:17 2026


Pair  time (%) = 1.0 (40.0)
Other time (%) = 0.5 (20.0)

Nlocal:    2078 ave 2081 max 2075 min
Histogram: 1 0 0 0 0 0 0 0 0 1
Nghost:    3296.5 ave 3305 max 3288 min
Neighs:    16862 ave 16898 max 16826 min

Neighbor list builds = 7
drum: done, 4156 beads kept
"""


class Materials(unittest.TestCase):
    def test_table_3_1(self):
        m = harness.materials()
        self.assertEqual((m["bead_tc"], m["bead_en"], m["bead_et"], m["bead_mu"]), (1e-4, 0.56, 0.46, 0.5))
        self.assertEqual((m["drum_en"], m["drum_et"], m["drum_mu"]), (0.46, 0.46, 0.95))

    def test_bad_line_is_named(self):
        with tempfile.NamedTemporaryFile("w", suffix=".in") as f:
            f.write("# comment\n\nvariable a equal 1\nvariable b index 2\n")
            f.flush()
            with self.assertRaisesRegex(ValueError, r":4: expected `variable NAME equal VALUE`"):
                harness.materials(f.name)


class Logs(unittest.TestCase):
    def test_last_run_summary(self):
        with tempfile.NamedTemporaryFile("w", suffix=".log") as f:
            f.write(LOG)
            f.flush()
            log = harness.Log(f.name)
        self.assertEqual((log.loop_time, log.procs, log.steps, log.atoms), (2.5, 2, 200, 4156))
        self.assertEqual(log.per_rank["Nlocal"], (2078, 2081, 2075))
        self.assertEqual(log.sections, {"Pair": 40.0, "Other": 20.0})
        self.assertEqual(log.neighbor_builds, 7)
        self.assertEqual(log.runs, [(100, 1.5), (200, 2.5)])  # the `run 0` left out
        self.assertAlmostEqual(log.particle_steps_per_s, 4156 * 200 / 2.5)
        self.assertEqual(log.cpu_seconds, 5.0)
        self.assertEqual(log.grep(r"^drum: done, (\d+) beads kept", cast=int), 4156)
        self.assertIsNone(log.grep(r"^never (\d+)"))


class Rounds(unittest.TestCase):
    def test_interleaved_order_and_medians(self):
        order = []
        counter = iter(range(100))
        variants = {name: (lambda n=name: order.append(n) or next(counter)) for name in ("a", "b", "c")}
        r = harness.interleaved(variants, rounds=3)
        self.assertEqual(order, ["a", "b", "c"] * 3)
        self.assertEqual(r, {"a": [0, 3, 6], "b": [1, 4, 7], "c": [2, 5, 8]})
        self.assertEqual(harness.median([3, 1, 2, 10]), 2.5)
        self.assertEqual(harness.spread([3, 1, 2]), (1, 3))
        # pairwise per round, not the ratio of medians
        self.assertEqual(harness.median_ratio([1, 10, 100], [2, 5, 25]), 2)


class Tables(unittest.TestCase):
    def test_csv_by_name_roundtrip(self):
        with tempfile.TemporaryDirectory() as d:
            p = harness.write_csv(Path(d) / "x.csv", [{"b": 1.5, "a": "x"}, {"b": float("nan"), "a": "y"}])
            rows = harness.read_csv(p)
        self.assertEqual(rows[0], {"b": 1.5, "a": "x"})
        self.assertTrue(math.isnan(rows[1]["b"]))

    def test_markdown(self):
        md = harness.markdown([{"v": 0.00123, "n": "x"}, {"v": float("nan"), "n": "y"}],
                              [("name", "n", None), ("v [mm]", lambda r: 1e3 * r["v"], "{:.2f}")])
        self.assertEqual(md, "| name | v [mm] |\n|---|---|\n| x | 1.23 |\n| y | – |\n")

    def test_generated_note_names_the_command(self):
        self.assertIn("`benchmarks/run.py cost`", harness.generated_note("benchmarks/run.py cost"))


class Launch(unittest.TestCase):
    def test_mpirun_prefix(self):
        self.assertEqual(harness.mpirun(1), [])
        cmd = harness.mpirun(64)
        self.assertEqual(cmd[:3], ["mpirun", "-np", "64"])
        self.assertIn("--oversubscribe", cmd)


if __name__ == "__main__":
    unittest.main()
