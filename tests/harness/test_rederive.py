"""tools/drum/rederive.py: the 95 % half-widths and degrees of freedom in a study's table are what
the estimator gives on the committed series (regenerated into a temporary directory and compared),
so they cannot drift from the series or the estimator; every other column is left as it was."""

import csv
import math
import sys

import numpy as np
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "drum"))
import rederive  # noqa: E402

STUDIES = ("study_thesis", "study_bound", "study_yade")


def table(path):
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        return list(reader.fieldnames), list(reader)


class Rederive(unittest.TestCase):
    def test_committed_columns_are_current(self):
        checked = 0
        for name in STUDIES:
            committed = rederive.DOCS / f"{name}.csv"
            header, rows = table(committed)
            new = [c for c in header if "_hw95_" in c or c.endswith("_dof")]
            if not new:
                continue  # not re-derived (yet)
            with self.subTest(study=name), tempfile.TemporaryDirectory() as d:
                self.assertEqual(rederive.main(["--name", name, "--out", d, "--no-page"]), 0)
                header2, rows2 = table(Path(d) / f"{name}.csv")
                self.assertEqual(header2, header)
                for row, row2 in zip(rows, rows2, strict=True):
                    for c in header:
                        if c in new:  # to the digits the coarser of the two prints (steady.py writes all)
                            self.assertTrue(math.isclose(float(row[c]), float(row2[c]), rel_tol=1e-6)
                                            or rederive.same_to_printed_digits(float(row[c]), row2[c])
                                            or rederive.same_to_printed_digits(float(row2[c]), row[c]),
                                            (row["rpm"], c, row[c], row2[c]))
                        else:
                            self.assertEqual(row[c], row2[c], (row["rpm"], c))
                checked += 1
        self.assertGreaterEqual(checked, 1)  # study_thesis at least

    def test_every_metric_has_its_columns(self):
        header, rows = table(rederive.DOCS / "study_thesis.csv")
        for key, column, se, unit in rederive.metrics(header):
            self.assertIn(rederive.hw_column(key, unit), header)
            self.assertIn(rederive.dof_column(key), header)
        self.assertEqual(len(rederive.metrics(header)), 10)

    def test_the_window_of_each_kind_of_row(self):
        # 21 rpm (2.857 s a revolution), snapshots every 0.05 s over 10 s, steady from 1.05 s
        t = np.arange(0.0, 10.0 + 1e-9, 0.05)
        series = {"time_s": t, "Hc_m": np.arange(len(t), dtype=float)}
        batches = {"rpm": "21", "average_s": "8.95", "settle_s": "1.05", "batches": "3"}
        x, spacing = rederive.window(series, batches, "Hc_m")
        self.assertAlmostEqual(spacing, 0.05)
        self.assertEqual(len(x), 3 * 57)  # the last three whole revolutions of 57 snapshots (2.85 s)
        x, _ = rederive.window(series, dict(batches, batches="nan"), "Hc_m")
        self.assertEqual(len(x), 180)  # an estimator's row: every snapshot from the steady start
        self.assertEqual(x[0], 21.0)

    def test_printed_digits(self):
        self.assertTrue(rederive.same_to_printed_digits(0.05218352653464704, "0.05218352654"))
        self.assertFalse(rederive.same_to_printed_digits(0.0521835266, "0.05218352654"))
        self.assertTrue(rederive.same_to_printed_digits(-7.926454435e-06, "-7.926454435e-06"))
        self.assertFalse(rederive.same_to_printed_digits(-7.9264546e-06, "-7.926454435e-06"))


if __name__ == "__main__":
    unittest.main()
