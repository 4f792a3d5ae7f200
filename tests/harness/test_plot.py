"""tools/plot.py, the charts of collide and drum_metrics: each KIND draws a PNG from a small CSV
shaped like the tool's; a usage error is one line and exit status 2, a CSV that is not the
chart's one line and 1; installed beside harness/ (share/liggghts_viscoelastic/python) it finds
its harness there."""

import math
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PLOT = ROOT / "tools" / "plot.py"
METRICS = ["Hh_m", "Hc_m", "angle_deg", "surface_velocity_mps", "bed_turn_1"]


def write(path, header, rows):
    path.write_text(",".join(header) + "\n" + "".join(",".join(map(str, r)) + "\n" for r in rows))
    return path


def sweep_dt(d):
    header = ["tc_over_dt", "dt", "restitution", "restitution_rel_err", "predicted_restitution",
              "duration_err_steps", "duration_rel_err", "tangential_restitution", "tangential_rel_err"]
    rows = [[r, 1e-4 / r, 0.56 * (1 - 0.05 / r), -0.05 / r, 0.56 * (1 - 0.049 / r), -0.3, -0.4 / r, 0.46, 0.02 / r]
            for r in (5, 10, 20, 50)]
    return write(d / "sweep_dt.csv", header, rows)


def sweep_angle(d):
    header = ["angle", "tangential_restitution_ref", "tangential_restitution_liggghts", "spin_ref",
              "spin_liggghts", "rebound_angle_ref", "rebound_angle_liggghts", "restitution_ref",
              "restitution_liggghts", "closed_form_regime"]
    rows = [[a, 0.46 - a / 100, 0.46 - a / 101, 10 * a, 10.1 * a, -a / 2, -a / 2.1, 0.56, 0.561, "sticking"]
            for a in (5, 25, 45, 65, 85)]
    csv = write(d / "sweep_angle.csv", header, rows)
    write(d / "sweep_angle.csv.reference.csv", ["angle", "tangential_restitution", "spin", "rebound_angle"],
          [[a, 0.46 - a / 100, 10 * a, -a / 2] for a in range(5, 86)])
    return csv


def law_map(d):
    rows = [[mu, a, min(0.46, 1 - a * (1.2 - mu) / 40), 0.46] for mu in (0.1, 0.5, 10) for a in (5, 20, 40, 60)]
    return write(d / "law_map.csv", ["mu", "angle", "tangential_restitution", "requested_et"], rows)


def drum_series(d):
    header = ["time_s", "beads", "wall_contacts"] + METRICS
    rows = [[0.01 * k, 1000, 80, 0.07, -0.1 + 1e-4 * k, 30 + math.sin(k), 1.1, "nan"] for k in range(20)]
    return write(d / "run_metrics.csv", header, rows)  # bed_turn all nan: "no values"


def drum_table(d):
    header = ["rpm", "beads", "steady_from_s", "snapshots", "batches"]
    for c in METRICS:
        key, _, unit = c.rpartition("_")
        header += [c, f"{key}_se_{unit}"]
    rows = [[rpm, 1000, 1.0, 50, 5] + [v for c in METRICS for v in (rpm / 100, 0.001)] for rpm in (7, 14, 21)]
    return write(d / "sweep.csv", header, rows)


KINDS = {"sweep-dt": sweep_dt, "sweep-angle": sweep_angle, "law-map": law_map, "drum-series": drum_series,
         "drum-table": drum_table}


def plot(*args, script=PLOT):
    return subprocess.run([sys.executable, str(script), *map(str, args)], capture_output=True, text=True)


class Plot(unittest.TestCase):
    def setUp(self):
        self.dir = Path(tempfile.mkdtemp(prefix="plot_test_"))
        self.addCleanup(shutil.rmtree, self.dir)

    def assertDrawn(self, run, png):
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertTrue(png.is_file(), run.stderr)
        self.assertGreater(png.stat().st_size, 10000)
        self.assertEqual(png.read_bytes()[:8], b"\x89PNG\r\n\x1a\n")

    def test_each_kind_draws_a_png(self):
        for kind, make in KINDS.items():
            with self.subTest(kind=kind):
                png = self.dir / f"{kind}.png"
                self.assertDrawn(plot(kind, make(self.dir), png, "--title", f"a {kind} chart"), png)

    def test_the_options_the_tools_pass(self):
        png = self.dir / "series.png"
        self.assertDrawn(plot("drum-series", drum_series(self.dir), png, "--steady-from", 0.1,
                              "--label", "Hc_m=centre of mass Hc [m]"), png)
        png = self.dir / "dt.png"
        self.assertDrawn(plot("sweep-dt", sweep_dt(self.dir), png, "--tangential", "on"), png)
        csv = sweep_angle(self.dir)
        reference = csv.with_name("fine.csv")
        csv.with_name(csv.name + ".reference.csv").rename(reference)
        png = self.dir / "angle.png"
        self.assertDrawn(plot("sweep-angle", csv, png, "--reference", reference), png)
        png = self.dir / "angle_coarse.png"  # no reference file: the CSV's own reference columns
        self.assertDrawn(plot("sweep-angle", csv, png), png)

    def test_unknown_kind_is_one_line_and_status_2(self):
        run = plot("frobnicate", self.dir / "x.csv", self.dir / "x.png")
        self.assertEqual(run.returncode, 2)
        self.assertEqual(run.stdout, "")
        self.assertRegex(run.stderr, r"\Aplot\.py: [^\n]*'frobnicate' is not a chart: one of sweep-dt, "
                                     r"sweep-angle, law-map, drum-series, drum-table; see plot\.py --help\n\Z")
        self.assertFalse((self.dir / "x.png").exists())

    def test_missing_argument_is_one_line_and_status_2(self):
        run = plot("law-map")
        self.assertEqual(run.returncode, 2)
        self.assertEqual(run.stderr.count("\n"), 1, run.stderr)

    def test_a_csv_of_another_chart_is_one_line_and_status_1(self):
        run = plot("law-map", sweep_dt(self.dir), self.dir / "x.png")
        self.assertEqual(run.returncode, 1)
        self.assertEqual(run.stderr.count("\n"), 1, run.stderr)
        self.assertIn("no column mu", run.stderr)
        self.assertFalse((self.dir / "x.png").exists())

    def test_installed_beside_the_harness(self):
        # the layout `cmake --install` makes: python/plot.py and python/harness/
        python = self.dir / "share" / "python"
        shutil.copytree(ROOT / "tools" / "harness", python / "harness",
                        ignore=shutil.ignore_patterns("__pycache__"))
        shutil.copy(PLOT, python / "plot.py")
        png = self.dir / "installed.png"
        self.assertDrawn(plot("law-map", law_map(self.dir), png, script=python / "plot.py"), png)


if __name__ == "__main__":
    unittest.main()
